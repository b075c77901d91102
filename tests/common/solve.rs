//! A GPU radiosity solve to a convergence, for the tests that compare solutions, and the
//! bundled scenes' solves that several tests compare, each solved once per test binary.
#![allow(dead_code)] // each test file reads what it compares

use std::collections::HashMap;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex, OnceLock};

use glam::DVec3;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::shooters::Hierarchy;
use goniolight::radiosity::solve::StopAt;
use goniolight::radiosity::SolverSettings;
use goniolight::render::ShadowSettings;
use goniolight::scene::Scene;

/// What a solve gave.
pub struct Solved {
    /// Radiosity per element.
    pub radiosity: Vec<DVec3>,
    /// Illuminance received per element, lux.
    pub illuminance: Vec<f64>,
    /// Shots taken.
    pub shots: usize,
    /// Visibility maps drawn.
    pub drawn: usize,
}

/// Solves `r` from `initial` to `converge` (at most 20 000 shots).
pub fn solve(
    gpu: &goniolight::gpu::Gpu,
    r: &RadiosityScene,
    initial: &InitialState,
    gpu_settings: GpuSettings,
    converge: f64,
) -> Solved {
    solve_with(gpu, r, initial, gpu_settings, converge, |_| {})
}

/// [`solve`] with the solver first set up by `prepare`.
pub fn solve_with(
    gpu: &goniolight::gpu::Gpu,
    r: &RadiosityScene,
    initial: &InitialState,
    gpu_settings: GpuSettings,
    converge: f64,
    prepare: impl FnOnce(&mut GpuSolver),
) -> Solved {
    let mut solver = GpuSolver::new(gpu, r, initial, SolverSettings::default(), gpu_settings);
    prepare(&mut solver);
    let stop = StopAt {
        converge,
        max_shots: Some(20_000),
        time_budget: None,
    };
    solver
        .solve(&stop, &AtomicBool::new(false), |_| {})
        .unwrap();
    let (radiosity, illuminance) = solver.radiosity_and_illuminance().unwrap();
    Solved {
        radiosity,
        illuminance,
        shots: solver.stats.shots,
        drawn: solver.stats.drawn,
    }
}

/// A bundled scene (`assets/scenes/`) laid out and solved as [`bundled_solve`] was asked.
pub struct BundledSolve {
    /// The scene as loaded.
    pub scene: Scene,
    /// Its elements.
    pub r: RadiosityScene,
    /// Its luminaires' first shot on the elements.
    pub initial: InitialState,
    /// The solve from that first shot.
    pub solved: Solved,
}

/// The bundled scene `name` laid out at `density` texels per metre (level 2, charts as
/// `layout` asks), lit by its luminaires' first shot and solved with `shooters` to
/// `converge`. Solved once per test binary: a test that asks for the same solve again
/// (another test comparing with it) gets the first one, waiting while it is solved.
pub fn bundled_solve(
    gpu: &goniolight::gpu::Gpu,
    name: &str,
    density: f64,
    (layout, shooters): (Hierarchy, Hierarchy),
    converge: f64,
) -> Arc<BundledSolve> {
    type Slot = Arc<OnceLock<Arc<BundledSolve>>>;
    static SOLVES: OnceLock<Mutex<HashMap<String, Slot>>> = OnceLock::new();
    let key = format!("{name} {density} {layout:?} {shooters:?} {converge}");
    let slot = {
        let mut solves = SOLVES.get_or_init(Default::default).lock().unwrap();
        solves.entry(key).or_default().clone()
    };
    slot.get_or_init(|| {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("assets/scenes")
            .join(name);
        let scene = Scene::load(&path).unwrap();
        let r = RadiosityScene::with_hierarchy(&scene, density, 2, layout).unwrap();
        let settings = SolverSettings::default();
        let light = LuminaireLight::new(gpu, &scene, settings.interp);
        let initial =
            InitialState::from_luminaires_gpu(gpu, &light, &r, &ShadowSettings::default()).unwrap();
        let gpu_settings = GpuSettings {
            hierarchy: shooters,
            ..GpuSettings::default()
        };
        let solved = solve(gpu, &r, &initial, gpu_settings, converge);
        Arc::new(BundledSolve {
            scene,
            r,
            initial,
            solved,
        })
    })
    .clone()
}
