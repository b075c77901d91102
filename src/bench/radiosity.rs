//! `goniolight bench radiosity`: time to 90 % and 99 % convergence on a Cornell-box-like
//! scene at a chosen element count (Wallner Table 4.1: "Cornell box high", ~127 000
//! elements, 4.97 s to 90 % on a GeForce 8800), hemicube vs stereographic visibility
//! measured side by side in one run.

use std::sync::atomic::AtomicBool;

use crate::gpu::Gpu;
use crate::radiosity::gpu::{GpuSettings, GpuSolver, Visibility};
use crate::radiosity::initial::{InitialState, LuminaireLight};
use crate::radiosity::scene::RadiosityScene;
use crate::radiosity::solve::StopAt;
use crate::radiosity::SolverSettings;
use crate::scene::Scene;

/// One measured solution.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RadiosityBenchRow {
    /// "hemicube" or "stereographic".
    pub visibility: String,
    /// Elements (texels).
    pub elements: usize,
    /// Shooting patches.
    pub patches: usize,
    /// Texels per metre used to get about the asked-for element count.
    pub texel_density: f64,
    /// Shots to 90 % (`None`: not reached within the shot cap).
    pub shots_90: Option<usize>,
    /// Seconds to 90 %.
    pub seconds_90: Option<f64>,
    /// Shots to 99 %.
    pub shots_99: Option<usize>,
    /// Seconds to 99 %.
    pub seconds_99: Option<f64>,
    /// Mean milliseconds per shot over the run.
    pub ms_per_shot: f64,
}

/// Total area of a scene's triangles, m².
pub fn surface_area(scene: &Scene) -> f64 {
    scene
        .meshes
        .iter()
        .flat_map(|m| {
            m.indices.chunks_exact(3).map(|t| {
                let [a, b, c] = [0, 1, 2].map(|k| m.positions[t[k] as usize].as_dvec3());
                0.5 * (b - a).cross(c - a).length()
            })
        })
        .sum()
}

/// Solves `scene` with about `elements` elements once per visibility in `visibilities`,
/// to 99 % or `max_shots`.
pub fn run(
    gpu: &Gpu,
    scene: &Scene,
    elements: usize,
    level: u32,
    visibilities: &[Visibility],
    max_shots: usize,
    mut progress: impl FnMut(Visibility, f64),
) -> anyhow::Result<Vec<RadiosityBenchRow>> {
    let density = (elements as f64 / surface_area(scene).max(1e-9)).sqrt();
    let rscene = RadiosityScene::new(scene, density, level)?;
    let settings = SolverSettings::default();
    let shadows = crate::render::ShadowSettings::default();
    let light = LuminaireLight::new(gpu, scene, settings.interp);
    let initial = InitialState::from_luminaires_gpu(gpu, &light, &rscene, &shadows)?;
    let mut rows = Vec::new();
    for &visibility in visibilities {
        let gpu_settings = GpuSettings {
            visibility,
            ..GpuSettings::default()
        };
        let mut solver = GpuSolver::new(gpu, &rscene, &initial, settings, gpu_settings);
        let stop = StopAt {
            converge: 0.99,
            max_shots: Some(max_shots),
            time_budget: None,
        };
        let (_, log) = solver.solve(&stop, &AtomicBool::new(false), |p| {
            progress(visibility, p.convergence)
        })?;
        let reach = |target: f64| log.iter().find(|p| p.convergence >= target);
        let seconds = log.last().map_or(0.0, |p| p.seconds);
        rows.push(RadiosityBenchRow {
            visibility: format!("{visibility:?}").to_lowercase(),
            elements: rscene.elements.len(),
            patches: rscene.elements.patches.len(),
            texel_density: density,
            shots_90: reach(0.9).map(|p| p.shot),
            seconds_90: reach(0.9).map(|p| p.seconds),
            shots_99: reach(0.99).map(|p| p.shot),
            seconds_99: reach(0.99).map(|p| p.seconds),
            ms_per_shot: 1000.0 * seconds / solver.shots.max(1) as f64,
        });
    }
    Ok(rows)
}
