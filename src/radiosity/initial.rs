//! Where a solution starts: every element's emission plus the reflected direct light of
//! the luminaires (their "first shot", Wallner §4.3), computed on the GPU with the
//! renderer's lighting code and the luminaires' own visibility (paraboloid) maps, or on the
//! CPU with ray-cast shadows.

use glam::DVec3;

use super::scene::{luminance, RadiosityScene};
use crate::gpu::{Gpu, GpuError};
use crate::lighting::SurfacePoint;
use crate::photometry::Interp;
use crate::render::illuminance::IlluminanceProbe;
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

/// The luminaires' direct illuminance per element (RGB lux), on its front and, for a
/// translucent element, on its back.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectLight {
    /// On the element's front (its own side).
    pub front: Vec<DVec3>,
    /// On its back (zero where it is opaque).
    pub back: Vec<DVec3>,
}

impl InitialState {
    /// Emission only (no luminaire has shot).
    pub fn emission(scene: &RadiosityScene) -> InitialState {
        let none = vec![DVec3::ZERO; scene.elements.len()];
        InitialState::with_direct(
            scene,
            &DirectLight {
                front: none.clone(),
                back: none,
            },
        )
    }

    /// Emission plus reflectance × the direct illuminance on the front plus transmittance
    /// × that on the back ([`super::transmission`]); the illuminance is the front's.
    pub fn with_direct(scene: &RadiosityScene, direct: &DirectLight) -> InitialState {
        let radiosity = (0..direct.front.len())
            .map(|e| {
                scene.element_emission(e)
                    + scene.element_reflectance(e) * direct.front[e]
                    + scene.element_transmittance(e) * direct.back[e]
            })
            .collect();
        InitialState {
            radiosity,
            illuminance: direct.front.iter().map(|d| luminance(*d)).collect(),
        }
    }

    /// Adds the direct light `extra` (reflected from the front, transmitted from the
    /// back) to the state: radiosity is linear in its sources.
    pub fn add_direct(&mut self, scene: &RadiosityScene, extra: &DirectLight) {
        let added = InitialState::with_direct(scene, extra);
        for (e, (b, lux)) in added.radiosity.iter().zip(&added.illuminance).enumerate() {
            self.radiosity[e] += *b - scene.element_emission(e);
            self.illuminance[e] += lux;
        }
    }

    /// The luminaires' shot on the GPU: direct illuminance at every element (averaged
    /// over its samples near a luminaire) with `shadows` (paraboloid maps for the
    /// luminaires' own visibility, by default).
    pub fn from_luminaires_gpu(
        gpu: &Gpu,
        light: &LuminaireLight,
        radiosity_scene: &RadiosityScene,
        shadows: &ShadowSettings,
    ) -> Result<InitialState, GpuError> {
        if light.scene.lights.count == 0 {
            return Ok(InitialState::emission(radiosity_scene));
        }
        let samples = DirectSamples::near(radiosity_scene, &light.positions);
        let mut direct = light.rgb(gpu, &samples.points, shadows)?;
        add_specular_direct(radiosity_scene, &samples.points, &mut direct, light.interp);
        Ok(InitialState::with_direct(
            radiosity_scene,
            &samples.direct(&direct),
        ))
    }
}

/// The scene's direct daylight on every element (one sample at its centre, each side
/// that receives; [`crate::daylight::points::ELEMENT_CELLS`] rays), grey; `None` without a
/// sky.
pub fn daylight_direct(scene: &RadiosityScene) -> Option<DirectLight> {
    let samples = DirectSamples::near(scene, &[]);
    let lux = scene.daylight_at(&samples.points, crate::daylight::points::ELEMENT_CELLS)?;
    let grey: Vec<DVec3> = lux.iter().map(|d| DVec3::splat(d.total())).collect();
    Some(samples.direct(&grey))
}

/// Adds to `direct` (one per point) the luminaires' light at `points` by way of mirrors
/// and clear glass ([`super::specular::SpecularLight`], on the CPU's threads): the GPU's
/// first shot draws only their straight light.
pub fn add_specular_direct(
    scene: &RadiosityScene,
    points: &[SurfacePoint],
    direct: &mut [DVec3],
    interp: Interp,
) {
    if !scene.specular.is_empty() {
        scene.specular_light().add_at_points(points, direct, interp);
    }
}

/// A scene's luminaires on the GPU with the renderer's point probe: their direct light at
/// elements (the luminaires' shot) and at query points, uploaded and compiled once.
pub struct LuminaireLight {
    scene: GpuScene,
    probe: IlluminanceProbe,
    /// Where the luminaires are (the elements' sample grids are finer near them).
    positions: Vec<DVec3>,
    /// How their distributions are interpolated.
    interp: Interp,
}

impl LuminaireLight {
    /// Uploads `scene` and builds the probe for `interp`.
    pub fn new(gpu: &Gpu, scene: &Scene, interp: Interp) -> LuminaireLight {
        LuminaireLight {
            scene: GpuScene::new(gpu, &Layouts::new(gpu), scene),
            probe: IlluminanceProbe::new(gpu, LightModel::Ldt(interp)),
            positions: scene.luminaires.iter().map(|l| l.position).collect(),
            interp,
        }
    }

    /// Direct illuminance (lux) at `points`.
    pub fn lux(
        &self,
        gpu: &Gpu,
        points: &[SurfacePoint],
        shadows: &ShadowSettings,
    ) -> Result<Vec<f64>, GpuError> {
        self.probe.run_in_scene(gpu, &self.scene, points, shadows)
    }

    /// Direct illuminance at `points` in colour (RGB lux).
    pub fn rgb(
        &self,
        gpu: &Gpu,
        points: &[SurfacePoint],
        shadows: &ShadowSettings,
    ) -> Result<Vec<DVec3>, GpuError> {
        self.probe
            .run_in_scene_rgb(gpu, &self.scene, points, shadows)
    }
}

/// Where the luminaires' direct light is sampled: per element a grid over its texel whose
/// spacing is at most a quarter of the distance to the nearest luminaire (one point, the
/// centroid, from four texels away; up to 8 × 8). A luminaire a few centimetres from a
/// ceiling puts most of its upward flux on a handful of elements, where one sample at
/// the centroid would be 10–20 % off; the average over the grid integrates it.
///
/// The points carry the direction of the element's receiving normal
/// ([`RadiosityScene::element_receiving_normal`]) and the element's average is scaled by
/// its length. Where a luminaire lies behind an element's plane but in front of its
/// shading normal (the terminator of a curved mesh), the element's samples take the
/// geometric normal instead, so no light arrives through its back.
///
/// A translucent element ([`super::transmission`]) has a second grid facing its back,
/// after every element's first.
#[derive(Debug, Clone, PartialEq)]
pub struct DirectSamples {
    /// The sample points with their element's normal.
    pub points: Vec<SurfacePoint>,
    /// Element e's samples are `points[first[e]..first[e + 1]]`.
    pub first: Vec<usize>,
    /// The back grids: the element and its samples' range in `points`.
    pub back: Vec<(usize, std::ops::Range<usize>)>,
    /// Per element, what its samples' mean is multiplied by (the receiving normal's
    /// length; 1 where the element receives with its chart's normal).
    pub scale: Vec<f64>,
}

impl DirectSamples {
    /// The samples of every element of `scene` for its luminaires.
    pub fn new(scene: &RadiosityScene) -> DirectSamples {
        let positions: Vec<DVec3> = scene.luminaires.iter().map(|l| l.position).collect();
        DirectSamples::near(scene, &positions)
    }

    /// The samples of every element of `scene` for luminaires at `positions` (the
    /// scene's luminaires moved: a solution relit, [`super::gpu::GpuSolver::relight`]).
    pub fn near(scene: &RadiosityScene, positions: &[DVec3]) -> DirectSamples {
        let el = &scene.elements;
        let mut points = Vec::with_capacity(el.len());
        let mut first = Vec::with_capacity(el.len() + 1);
        let mut scales = Vec::with_capacity(el.len());
        let grid = |e: usize| {
            let texel_m = el.side_m(e);
            let nearest = positions
                .iter()
                .map(|p| p.distance(el.position[e]))
                .fold(f64::INFINITY, f64::min);
            let n = ((4.0 * texel_m / nearest.max(1e-9)).ceil() as u32).clamp(1, 8);
            el.texel_samples(e, n)
        };
        for e in 0..el.len() {
            first.push(points.len());
            let (normal, scale) = receiving_direction(scene, e, positions);
            scales.push(scale);
            points.extend(
                grid(e)
                    .into_iter()
                    .map(|position| SurfacePoint { position, normal }),
            );
        }
        first.push(points.len());
        let mut back = Vec::new();
        for e in (0..el.len()).filter(|&e| scene.element_transmittance(e) != DVec3::ZERO) {
            let start = points.len();
            let normal = -el.normal(e);
            points.extend(
                grid(e)
                    .into_iter()
                    .map(|position| SurfacePoint { position, normal }),
            );
            back.push((e, start..points.len()));
        }
        DirectSamples {
            points,
            first,
            back,
            scale: scales,
        }
    }

    /// Per element the mean of `values` (one per sample point) on its front and back.
    pub fn direct(&self, values: &[DVec3]) -> DirectLight {
        let mean = |r: std::ops::Range<usize>| {
            let count = r.len().max(1) as f64;
            values[r].iter().sum::<DVec3>() / count
        };
        let front = self
            .first
            .windows(2)
            .zip(&self.scale)
            .map(|(w, scale)| mean(w[0]..w[1]) * *scale)
            .collect();
        let mut back = vec![DVec3::ZERO; self.scale.len()];
        for (e, range) in &self.back {
            back[*e] = mean(range.clone());
        }
        DirectLight { front, back }
    }
}

/// The unit normal element `e`'s direct-light samples take and the factor on their mean
/// ([`DirectSamples`]), for luminaires at `positions`.
fn receiving_direction(scene: &RadiosityScene, e: usize, positions: &[DVec3]) -> (DVec3, f64) {
    let geometric = scene.elements.normal(e);
    let receiving = scene.element_receiving_normal(e);
    let Some((direction, length)) = super::shading::own_direction(geometric, receiving) else {
        return (geometric, 1.0);
    };
    let at = scene.elements.position[e];
    let through_back = positions.iter().any(|p| {
        let to = *p - at;
        to.dot(geometric) <= 0.0 && to.dot(direction) > 0.0
    });
    if through_back {
        (geometric, 1.0)
    } else {
        (direction, length)
    }
}
