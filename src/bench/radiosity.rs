//! `goniolight bench radiosity`: time to 90 % and 99 % convergence on a Cornell-box-like
//! scene at a chosen element count (Wallner Table 4.1: "Cornell box high", ~127 000
//! elements, 4.97 s to 90 % on a GeForce 8800), hemicube vs stereographic visibility and
//! flat vs face-cluster shooters (Edström) measured side by side in one run.

use std::sync::atomic::AtomicBool;

use crate::gpu::Gpu;
use crate::radiosity::gpu::{GpuSettings, GpuSolver, Raster, Visibility};
use crate::radiosity::initial::{InitialState, LuminaireLight};
use crate::radiosity::scene::RadiosityScene;
use crate::radiosity::shooters::{Hierarchy, Shooters};
use crate::radiosity::solve::StopAt;
use crate::radiosity::{Ambient, SolverSettings};
use crate::scene::Scene;

/// One measured solution.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RadiosityBenchRow {
    /// "hemicube" or "stereographic".
    pub visibility: String,
    /// "none" (every triangle shoots) or "clusters" (flat face clusters shoot).
    pub hierarchy: String,
    /// The links' error (`--link-error`; 0: every receiver takes the finest cells).
    pub link_error: f64,
    /// "display" or "overshoot" (ambient overshooting).
    pub ambient: String,
    /// The cells' largest share of the initial unshot power (`--cell-power`).
    pub cell_power: f64,
    /// Side of a visibility map (a hemicube face or the stereographic map), texels.
    pub map_size: u32,
    /// Visibility maps drawn (one per drawn cell or patch).
    pub maps: usize,
    /// Whether each face drew only the mesh chunks it can see.
    pub chunk_culling: bool,
    /// How the maps were drawn: "hardware" (the render pipeline) or "compute".
    pub raster: String,
    /// Visibility-mesh triangles drawn per map (over its faces).
    pub triangles_per_map: f64,
    /// Triangles of the visibility mesh.
    pub visibility_triangles: usize,
    /// Shooters.
    pub shooters: usize,
    /// Seconds to build the shooters (the face-cluster hierarchy with clusters).
    pub shooters_seconds: f64,
    /// Triangles.
    pub triangles: usize,
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
    /// Seconds the whole run took (to 99 % or the limits).
    pub seconds: f64,
    /// Shots in the whole run.
    pub shots: usize,
    /// The convergence reached (fraction of the initial unshot power shot).
    pub convergence: f64,
    /// Where the shots' time went, by phase.
    pub phase_seconds: crate::radiosity::gpu::ShotTimes,
    /// Share of the shooting units whose cells came from the plan cache (laid out in an
    /// earlier shot of the same side).
    pub plan_cache_hits: f64,
    /// Receiver threads dispatched per map (the batch's culled receivers).
    pub receivers_per_map: f64,
    /// The GPU's own time in the batches' visibility and receive passes (`None` where the
    /// adapter has no timestamp queries).
    pub gpu_pass_seconds: Option<crate::radiosity::gpu::GpuPassSeconds>,
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

/// What one benchmark run solves with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadiosityBenchPlan {
    /// About this many elements (by area: a texel density of √(elements / area)) …
    pub elements: usize,
    /// … unless a texel density (texels per metre) is given.
    pub texel_density: Option<f64>,
    /// Patch level.
    pub level: u32,
    /// Give up after this many shots per solution.
    pub max_shots: usize,
    /// Give up after this many seconds per solution.
    pub time_limit: Option<f64>,
    /// Side of a visibility map, texels.
    pub map_size: u32,
}

/// One solution to measure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadiosityBenchConfig {
    /// Visibility maps.
    pub visibility: Visibility,
    /// Who shoots.
    pub hierarchy: Hierarchy,
    /// The links' error (with clusters).
    pub link_error: f64,
    /// Ambient term use: `Display` (shown only) or `Overshoot` (Wallner §4.3.5).
    pub ambient: Ambient,
    /// With clusters: the largest share of the initial unshot power one shooting cell
    /// carries ([`GpuSettings::cell_power`]).
    pub cell_power: f64,
    /// Each visibility face draws only the mesh chunks it can see
    /// ([`GpuSettings::chunk_culling`]).
    pub chunk_culling: bool,
    /// How the maps are drawn ([`GpuSettings::raster`]).
    pub raster: Raster,
}

/// Solves `scene` with about `plan.elements` elements once per entry of `configs`, to 99 %
/// or the plan's limits. The scene and each hierarchy's elements are checked against the
/// GPU's limits first (as `radiosity` does), so a scene too large is refused, not a panic.
pub fn run(
    gpu: &Gpu,
    scene: &Scene,
    plan: RadiosityBenchPlan,
    configs: &[RadiosityBenchConfig],
    mut progress: impl FnMut(&RadiosityBenchConfig, f64),
) -> Result<Vec<RadiosityBenchRow>, super::BenchError> {
    let RadiosityBenchPlan {
        elements,
        texel_density,
        level,
        max_shots,
        time_limit,
        map_size,
    } = plan;
    let density =
        texel_density.unwrap_or_else(|| (elements as f64 / surface_area(scene).max(1e-9)).sqrt());
    let defaults = SolverSettings::default();
    let mut shadows = crate::render::ShadowSettings::default();
    crate::render::limits::check_scene(gpu, scene, &mut shadows)?;
    let light = LuminaireLight::new(gpu, scene, defaults.interp);
    // The hierarchy lays the charts too, so each has its own elements.
    let mut prepared: Vec<(Hierarchy, RadiosityScene, InitialState)> = Vec::new();
    let mut rows = Vec::new();
    for config in configs {
        let RadiosityBenchConfig {
            visibility,
            hierarchy,
            link_error,
            ambient,
            cell_power,
            chunk_culling,
            raster,
        } = *config;
        if !prepared.iter().any(|p| p.0 == hierarchy) {
            let rscene = RadiosityScene::with_hierarchy(scene, density, level, hierarchy)?;
            crate::render::limits::check_radiosity(gpu, rscene.elements.len())?;
            let initial = InitialState::from_luminaires_gpu(gpu, &light, &rscene, &shadows)?;
            prepared.push((hierarchy, rscene, initial));
        }
        let Some((_, rscene, initial)) = prepared.iter().find(|p| p.0 == hierarchy) else {
            continue;
        };
        let gpu_settings = GpuSettings {
            visibility,
            hierarchy,
            link_error,
            map_size,
            cell_power,
            chunk_culling,
            raster,
            ..GpuSettings::default()
        };
        if let Some(why) = raster.refusal(rscene.has_masked_casters()) {
            return Err(super::BenchError::Refused(why.into()));
        }
        let settings = SolverSettings {
            ambient,
            ..defaults
        };
        let built = std::time::Instant::now();
        let shooters = Shooters::build(rscene, hierarchy);
        let shooters_seconds = built.elapsed().as_secs_f64();
        let shooter_count = shooters.len();
        let mut solver =
            GpuSolver::with_shooters(gpu, rscene, initial, settings, gpu_settings, shooters);
        solver.time_passes();
        let stop = StopAt {
            converge: 0.99,
            max_shots: Some(max_shots),
            time_budget: time_limit.and_then(|t| crate::io::limits::duration(t).ok()),
        };
        let (_, log) = solver.solve(&stop, &AtomicBool::new(false), |p| {
            progress(config, p.convergence)
        })?;
        let reach = |target: f64| log.iter().find(|p| p.convergence >= target);
        let seconds = log.last().map_or(0.0, |p| p.seconds);
        let gpu_pass_seconds = solver.gpu_pass_seconds()?;
        rows.push(RadiosityBenchRow {
            visibility: format!("{visibility:?}").to_lowercase(),
            hierarchy: format!("{hierarchy:?}").to_lowercase(),
            link_error,
            ambient: format!("{ambient:?}").to_lowercase(),
            cell_power,
            map_size,
            maps: solver.stats.drawn,
            chunk_culling,
            raster: solver.raster().name().to_string(),
            triangles_per_map: solver.stats.triangles_drawn as f64
                / solver.stats.drawn.max(1) as f64,
            visibility_triangles: solver.visibility_triangles(),
            shooters: shooter_count,
            shooters_seconds,
            triangles: rscene.elements.triangles.len(),
            elements: rscene.elements.len(),
            patches: rscene.elements.patches.len(),
            texel_density: density,
            shots_90: reach(0.9).map(|p| p.shot),
            seconds_90: reach(0.9).map(|p| p.seconds),
            shots_99: reach(0.99).map(|p| p.shot),
            seconds_99: reach(0.99).map(|p| p.seconds),
            ms_per_shot: 1000.0 * seconds / solver.stats.shots.max(1) as f64,
            seconds,
            shots: solver.stats.shots,
            convergence: log.last().map_or(0.0, |p| p.convergence),
            phase_seconds: solver.stats.times,
            plan_cache_hits: {
                let c = &solver.stats.plan_cache;
                c.hits as f64 / (c.hits + c.misses).max(1) as f64
            },
            receivers_per_map: solver.stats.receiver_threads as f64
                / solver.stats.drawn.max(1) as f64,
            gpu_pass_seconds,
        });
    }
    Ok(rows)
}
