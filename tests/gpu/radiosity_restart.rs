//! A solution relit in place (Edström's restart semantics): after a luminaire moves,
//! dims or goes, the difference of its first shot is shot (negative where light went
//! away) instead of starting over, and the result equals a fresh solve of the changed
//! scene.

use crate::common;
use crate::gpu_common;

use std::sync::atomic::AtomicBool;

use glam::DVec3;
use goniolight::gpu::Gpu;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::{luminance, RadiosityScene};
use goniolight::radiosity::shooters::Hierarchy;
use goniolight::radiosity::solve::{StopAt, StopReason};
use goniolight::radiosity::SolverSettings;
use goniolight::render::ShadowSettings;
use goniolight::scene::Scene;

const CONVERGE: f64 = 0.998;

fn stop() -> StopAt {
    StopAt {
        converge: CONVERGE,
        max_shots: Some(20_000),
        time_budget: None,
    }
}

/// The solver's settings: 128² maps (the restarted and the fresh solves draw theirs alike;
/// what is compared is the restart, not the maps' resolution).
fn maps() -> GpuSettings {
    GpuSettings {
        map_size: 128,
        ..GpuSettings::default()
    }
}

/// The luminaires' first shot of `scene` on the elements of `r`.
fn first_shot(gpu: &Gpu, scene: &Scene, r: &RadiosityScene) -> InitialState {
    let light = LuminaireLight::new(gpu, scene, SolverSettings::default().interp);
    InitialState::from_luminaires_gpu(gpu, &light, r, &ShadowSettings::default()).unwrap()
}

/// Mean |a − b| over mean |b| (luminance).
fn mean_difference(a: &[DVec3], b: &[DVec3]) -> f64 {
    let diff: f64 = a.iter().zip(b).map(|(x, y)| luminance(*x - *y).abs()).sum();
    let size: f64 = b.iter().map(|y| luminance(*y).abs()).sum();
    diff / size
}

/// The boxes room, its elements (coarse, face clusters) and its luminaire's first shot.
fn boxes_room(gpu: &Gpu) -> (Scene, RadiosityScene, InitialState) {
    let scene = Scene::load(&common::root().join("assets/scenes/boxes_room.toml")).unwrap();
    let r = RadiosityScene::with_hierarchy(&scene, 4.0, 1, Hierarchy::Clusters).unwrap();
    let lit = first_shot(gpu, &scene, &r);
    (scene, r, lit)
}

#[test]
fn a_moved_and_dimmed_luminaire_relit_in_place_equals_a_fresh_solve() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let (scene, r, old) = boxes_room(&gpu);
    let mut changed = scene.clone();
    changed.luminaires[0].position += DVec3::new(1.6, 1.0, -0.4);
    changed.luminaires[0].multiplier *= 0.6;
    let new = first_shot(&gpu, &changed, &r);
    let (settings, gpu_settings) = (SolverSettings::default(), maps());
    let cancel = AtomicBool::new(false);

    let mut solver = GpuSolver::new(&gpu, &r, &old, settings, gpu_settings);
    solver.solve(&stop(), &cancel, |_| {}).unwrap();
    let before = solver.radiosity().unwrap();
    let shots_before = solver.stats.shots;
    solver.relight(&old, &new).unwrap();
    let scale = solver.start_power(&new.radiosity).0;
    let (reason, _) = solver
        .solve_to_scale(&stop(), Some(scale), &cancel, |_| {})
        .unwrap();
    assert_eq!(reason, StopReason::Converged);
    let (relit, relit_lux) = solver.radiosity_and_illuminance().unwrap();

    let mut fresh = GpuSolver::new(&gpu, &r, &new, settings, gpu_settings);
    assert_eq!(
        fresh.solve(&stop(), &cancel, |_| {}).unwrap().0,
        StopReason::Converged
    );
    let (expected, expected_lux) = fresh.radiosity_and_illuminance().unwrap();
    let off = mean_difference(&relit, &expected);
    let lux = |v: &[f64]| v.iter().map(|&x| DVec3::splat(x)).collect::<Vec<_>>();
    let off_lux = mean_difference(&lux(&relit_lux), &lux(&expected_lux));
    // What the test would see had the change not been shot: far off.
    let stale = mean_difference(&before, &expected);
    eprintln!(
        "relit after {} + {} shots, fresh {} shots: radiosity {:.3} %, illuminance {:.3} % \
         off (unchanged {:.1} %)",
        shots_before,
        solver.stats.shots - shots_before,
        fresh.stats.shots,
        100.0 * off,
        100.0 * off_lux,
        100.0 * stale
    );
    assert!(stale > 0.2, "the change is too small to test: {stale}");
    assert!(off < 0.01, "relit radiosity {:.3} % off", 100.0 * off);
    assert!(
        off_lux < 0.01,
        "relit illuminance {:.3} % off",
        100.0 * off_lux
    );
    // The elements where the light went away are darker, not negative.
    let negative = relit.iter().filter(|b| luminance(**b) < -0.01).count();
    assert_eq!(negative, 0, "{negative} elements below zero");
}

#[test]
fn a_luminaire_turned_off_takes_all_its_light_away() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let (scene, r, old) = boxes_room(&gpu);
    let mut dark = scene.clone();
    dark.luminaires.clear();
    let new = first_shot(&gpu, &dark, &r);
    assert!(new.radiosity.iter().all(|b| *b == DVec3::ZERO));
    let cancel = AtomicBool::new(false);
    let mut solver = GpuSolver::new(&gpu, &r, &old, SolverSettings::default(), maps());
    solver.solve(&stop(), &cancel, |_| {}).unwrap();
    let lit: f64 = solver
        .radiosity()
        .unwrap()
        .iter()
        .map(|b| luminance(*b))
        .sum();
    solver.relight(&old, &new).unwrap();
    // Nothing is left to converge to: shoot until the old light's own share is gone.
    let scale = solver.start_power(&old.radiosity).0;
    solver
        .solve_to_scale(&stop(), Some(scale), &cancel, |_| {})
        .unwrap();
    let left: f64 = solver
        .radiosity()
        .unwrap()
        .iter()
        .map(|b| luminance(*b).abs())
        .sum();
    eprintln!("left {:.4} % of the light", 100.0 * left / lit);
    assert!(left < 0.01 * lit, "{left} of {lit} left");
}
