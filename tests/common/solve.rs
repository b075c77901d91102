//! A GPU radiosity solve to a convergence, for the tests that compare solutions.
#![allow(dead_code)] // each test file reads what it compares

use std::sync::atomic::AtomicBool;

use glam::DVec3;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::initial::InitialState;
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::solve::StopAt;
use goniolight::radiosity::SolverSettings;

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
        shots: solver.shots,
        drawn: solver.drawn,
    }
}
