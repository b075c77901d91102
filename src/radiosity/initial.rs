//! Where a solution starts: every element's emission plus the reflected direct light of
//! the luminaires (their "first shot", Wallner §4.3), computed on the GPU with the
//! renderer's lighting code and the luminaires' own visibility (paraboloid) maps, or on the
//! CPU with ray-cast shadows.

use glam::DVec3;

use super::scene::{luminance, RadiosityScene};
use crate::gpu::{Gpu, GpuError};
use crate::photometry::Interp;
use crate::render::illuminance::{IlluminanceProbe, SurfacePoint};
use crate::render::layouts::Layouts;
use crate::render::{GpuScene, LightModel, ShadowSettings};
use crate::scene::Scene;

/// The state a solution starts from.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialState {
    /// Radiosity (= unshot radiosity) per element, lm/m² (RGB).
    pub radiosity: Vec<DVec3>,
    /// Illuminance each element already receives, lux (luminance).
    pub illuminance: Vec<f64>,
}

impl InitialState {
    /// Emission only (no luminaire has shot).
    pub fn emission(scene: &RadiosityScene) -> InitialState {
        InitialState::with_direct(scene, &vec![DVec3::ZERO; scene.elements.len()])
    }

    /// Emission plus reflectance × `direct` illuminance (RGB lux per element).
    pub fn with_direct(scene: &RadiosityScene, direct: &[DVec3]) -> InitialState {
        let radiosity = direct
            .iter()
            .enumerate()
            .map(|(e, d)| scene.element_emission(e) + scene.element_reflectance(e) * *d)
            .collect();
        InitialState {
            radiosity,
            illuminance: direct.iter().map(|d| luminance(*d)).collect(),
        }
    }

    /// The luminaires' shot on the GPU: direct illuminance at every element centre with
    /// `shadows` (paraboloid maps for the luminaires' own visibility, by default).
    pub fn from_luminaires_gpu(
        gpu: &Gpu,
        scene: &Scene,
        radiosity_scene: &RadiosityScene,
        interp: Interp,
        shadows: &ShadowSettings,
    ) -> Result<InitialState, GpuError> {
        let el = &radiosity_scene.elements;
        if scene.luminaires.is_empty() {
            return Ok(InitialState::emission(radiosity_scene));
        }
        let points: Vec<SurfacePoint> = (0..el.len())
            .map(|e| SurfacePoint {
                position: el.position[e],
                normal: el.normal(e),
            })
            .collect();
        let gpu_scene = GpuScene::new(gpu, &Layouts::new(gpu), scene);
        let probe = IlluminanceProbe::new(gpu, LightModel::Ldt(interp));
        let direct = probe.run_in_scene_rgb(gpu, &gpu_scene, &points, shadows)?;
        Ok(InitialState::with_direct(radiosity_scene, &direct))
    }
}
