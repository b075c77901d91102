//! View-driven radiosity (Bozalina 2011): importance-driven and perspective-driven
//! solutions against the global one, receivers that wait and are caught up, and the
//! command's refusals.

mod common;
#[path = "common/furnace.rs"]
mod furnace_common;
#[path = "common/gpu.rs"]
mod gpu_common;

use std::sync::atomic::AtomicBool;

use glam::{DVec3, Vec3};
use goniolight::bench::radiosity_view::view_error;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::shooters::Hierarchy;
use goniolight::radiosity::solve::{self, StopAt};
use goniolight::radiosity::view::{self, Drive, ViewDriven, ViewPoint};
use goniolight::radiosity::SolverSettings;
use goniolight::scene::{Camera, Material, Scene, SceneMesh};

fn stop(converge: f64, max_shots: usize) -> StopAt {
    StopAt {
        converge,
        max_shots: Some(max_shots),
        time_budget: None,
    }
}

fn no_cancel() -> AtomicBool {
    AtomicBool::new(false)
}

/// The bundled box room with four boxes (52 triangles), lit by its luminaire.
fn boxes_room(gpu: &goniolight::gpu::Gpu) -> (Scene, RadiosityScene, InitialState) {
    let scene = Scene::load(&common::root().join("assets/scenes/boxes_room.toml")).unwrap();
    let r = RadiosityScene::with_hierarchy(&scene, 6.0, 1, Hierarchy::None).unwrap();
    let settings = SolverSettings::default();
    let light = LuminaireLight::new(gpu, &scene, settings.interp);
    let shadows = goniolight::render::ShadowSettings::default();
    let initial = InitialState::from_luminaires_gpu(gpu, &light, &r, &shadows).unwrap();
    (scene, r, initial)
}

#[test]
fn importance_and_perspective_driven_solutions_converge_to_the_global_one_in_view() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let (scene, r, initial) = boxes_room(&gpu);
    let settings = SolverSettings::default();
    let gpu_settings = GpuSettings::default();
    let point = ViewPoint::new(&scene.camera, 16.0 / 9.0).unwrap();
    let weights = view::view_weights(&r, &point);
    let seen = weights.iter().filter(|&&w| w > 0.0).count();
    assert!(
        seen > 100 && seen < r.elements.len(),
        "{seen} of {}",
        r.elements.len()
    );

    let mut reference = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
    reference
        .solve(&stop(0.9995, 50_000), &no_cancel(), |_| {})
        .unwrap();
    let reference = reference.radiosity().unwrap();

    let driven = ViewDriven::new(&gpu, &r, settings, gpu_settings, weights.clone(), None).unwrap();
    // Importance reaches surfaces the camera does not see (through interreflection).
    let unseen_with_importance = (0..r.elements.len())
        .filter(|&e| weights[e] == 0.0 && driven.importance[e] > 0.0)
        .count();
    assert!(unseen_with_importance > 100, "{unseen_with_importance}");
    for drive in [Drive::Global, Drive::Importance, Drive::Perspective] {
        let mut solver = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
        driven.drive(&mut solver, drive, &point, 10.0).unwrap();
        let (reason, log) = solver
            .solve(&stop(0.99, 20_000), &no_cancel(), |_| {})
            .unwrap();
        assert_eq!(reason, solve::StopReason::Converged, "{drive:?}");
        assert!(solver.area_is_whole(), "{drive:?}");
        assert_eq!(solver.waiting_charts(), 0);
        let (radiosity, illuminance) = solver.radiosity_and_illuminance().unwrap();
        let unshot = solver.unshot().unwrap();
        let ambient = match drive {
            Drive::Global => solve::ambient_term(&r, &unshot),
            _ => driven.ambient(&r, &unshot),
        };
        let shown = solve::with_ambient(&r, &radiosity, &illuminance, ambient).0;
        let error = view_error(&r, &weights, &shown, &reference);
        let shot_only = view_error(&r, &weights, &radiosity, &reference);
        eprintln!(
            "{drive:?}: {} shots, view error {:.4} (shot light alone {:.4})",
            log.len() - 1,
            error,
            shot_only
        );
        assert!(error < 0.01, "{drive:?}: {error}");
        // The view's ambient term brings the image closer, not further.
        assert!(error < shot_only, "{drive:?}: {error} vs {shot_only}");
    }
}

/// Two closed 2 × 1.5 × 1 m rooms 10 m apart, every wall emitting and reflecting (no
/// luminaires), room B's walls brighter so a global solve shoots them first.
fn two_rooms() -> Scene {
    let mut scene = furnace_common::closed_box(0.5, 10.0);
    let room_a = scene.meshes[0].clone();
    let inward = furnace_common::inward_box(DVec3::new(10.0, 0.0, 0.0), DVec3::new(12.0, 1.5, 1.0));
    scene.materials.push(Material {
        diffuse: Vec3::splat(0.5),
        emission: Vec3::splat(40.0),
        ..Material::default()
    });
    scene.meshes = vec![room_a, SceneMesh::from_triangles("room b", &inward, 1)];
    scene
}

#[test]
fn perspective_driven_radiosity_leaves_what_lies_outside_the_area_of_interest_alone() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let scene = two_rooms();
    let r = RadiosityScene::with_hierarchy(&scene, 8.0, 1, Hierarchy::None).unwrap();
    let initial = InitialState::emission(&r);
    let settings = SolverSettings::default();
    let gpu_settings = GpuSettings::default();
    // In room A, looking at its far (+x) wall.
    let camera = Camera::perspective(DVec3::new(0.2, 0.75, 0.5), DVec3::new(2.0, 0.75, 0.5), 40.0);
    let point = ViewPoint::new(&camera, 4.0 / 3.0).unwrap();
    let weights = view::view_weights(&r, &point);
    let in_room_b = |e: usize| r.elements.position[e].x > 5.0;
    assert!((0..r.elements.len()).all(|e| weights[e] == 0.0 || !in_room_b(e)));
    let driven = ViewDriven::new(&gpu, &r, settings, gpu_settings, weights, None).unwrap();
    let area = &view::area_stages(&r, &point, 10.0)[0];
    let chart = |e: usize| r.elements.chart[e] as usize;
    let outside = (0..r.elements.len()).filter(|&e| !area[chart(e)]).count();
    let outside_in_a = (0..r.elements.len())
        .filter(|&e| !area[chart(e)] && !in_room_b(e))
        .count();
    assert!(
        outside_in_a > 100,
        "room A's walls behind the camera: {outside_in_a}"
    );

    let shots = 12;
    let run = |drive: Drive| {
        let mut solver = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
        driven.drive(&mut solver, drive, &point, 10.0).unwrap();
        let (_, log) = solver
            .solve(&stop(1.0, shots), &no_cancel(), |_| {})
            .unwrap();
        let changed: Vec<bool> = solver
            .radiosity()
            .unwrap()
            .iter()
            .zip(&initial.radiosity)
            .map(|(b, b0)| (*b - *b0).length() > 1e-6 * b0.length())
            .collect();
        let shooters_in_b = log
            .iter()
            .filter_map(|p| p.shooter)
            .take(shots)
            .filter(|&k| {
                let elements = solver.shooters().elements_of(k);
                elements.iter().all(|&e| in_room_b(e as usize))
            })
            .count();
        (solver.area_stage(), changed, shooters_in_b)
    };
    let (stage, changed, shooters_in_b) = run(Drive::Perspective);
    assert_eq!(
        stage.map(|s| s.0),
        Some(0),
        "still the first area of interest"
    );
    let updated_outside = (0..r.elements.len())
        .filter(|&e| !area[chart(e)] && changed[e])
        .count();
    let updated_inside = (0..r.elements.len())
        .filter(|&e| area[chart(e)] && changed[e])
        .count();
    eprintln!(
        "perspective: {updated_inside} updated inside, {updated_outside} of {outside} outside, {shooters_in_b} shots from room B"
    );
    assert_eq!(updated_outside, 0);
    assert_eq!(shooters_in_b, 0);
    assert!(updated_inside > 100, "{updated_inside}");
    // The same count fails for the global solver: it shoots room B (brighter) first and
    // updates everything in front of its shooters.
    let (_, changed, shooters_in_b) = run(Drive::Global);
    let updated_outside = (0..r.elements.len())
        .filter(|&e| !area[chart(e)] && changed[e])
        .count();
    assert!(
        updated_outside > 100 && shooters_in_b > 0,
        "{updated_outside}, {shooters_in_b}"
    );
}

#[test]
fn receivers_that_wait_are_given_the_shots_they_missed() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let (_, r, initial) = boxes_room(&gpu);
    let settings = SolverSettings::default();
    // Maps of 64² texels: a store of 256 MiB keeps every missed cell's (about 50 MiB:
    // grown twice from its first 16 MiB, the kept maps copied over each time).
    let gpu_settings = GpuSettings {
        map_size: 64,
        ..GpuSettings::default()
    };
    let mut all = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
    // Batches by count, not by each solver's clock.
    all.fix_batch(16);
    // Every other chart waits; the shots are from triangles of charts that receive (so
    // both solvers shoot the same light).
    let el = &r.elements;
    let receiving: Vec<bool> = (0..el.charts.len()).map(|c| c % 2 == 0).collect();
    let shooters: Vec<usize> = (0..all.shooters().len())
        .filter(|&k| {
            all.shooters()
                .elements_of(k)
                .iter()
                .all(|&e| receiving[el.chart[e as usize] as usize])
        })
        .take(12)
        .collect();
    assert_eq!(shooters.len(), 12);
    for &k in &shooters {
        all.shoot(k).unwrap();
    }
    let expected = all.radiosity().unwrap();
    // Elements more than `tolerance` apart.
    let differ = |a: &[DVec3], b: &[DVec3], tolerance: f64| {
        (0..el.len())
            .filter(|&e| (a[e] - b[e]).length() > tolerance * (1e-3 + b[e].length()))
            .count()
    };
    // The missed cells' maps kept, then drawn again to catch up (the default).
    assert_eq!(goniolight::radiosity::gpu::DEFAULT_MAP_STORE_BYTES, 0);
    for store in [256 << 20, 0] {
        let mut waiting = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
        waiting.fix_batch(16);
        waiting.set_map_store_bytes(store);
        waiting.set_receiving(&receiving).unwrap();
        assert!(waiting.waiting_charts() > 3);
        for &k in &shooters {
            waiting.shoot(k).unwrap();
        }
        let missed = differ(&waiting.radiosity().unwrap(), &expected, 1e-2);
        assert!(
            missed > el.len() / 5,
            "the waiting charts missed light: {missed}"
        );
        assert_eq!(waiting.missed_shots(), 12);
        let drawn = waiting.drawn;
        eprintln!("{drawn} maps drawn, store {store} bytes");
        let given = waiting.set_receiving(&vec![true; el.charts.len()]).unwrap();
        assert_eq!(given, 12);
        assert_eq!(waiting.missed_shots(), 0);
        let caught_up = waiting.radiosity().unwrap();
        if store > 0 {
            // The very maps the shots were received through: nothing drawn, and every
            // element gets what it would have had (to rounding).
            assert_eq!(waiting.drawn, drawn, "a kept map was drawn again");
            assert!(waiting.maps_reused() > 0);
            let off = differ(&caught_up, &expected, 1e-5);
            assert_eq!(off, 0, "{off} elements differ with kept maps");
        } else {
            // Drawn again in batches of their own, a map's place in the atlas differs
            // from the one the other solver drew, and a texel at a depth edge may flip:
            // one element in a thousand may differ by more than 1 %.
            assert!(waiting.drawn > drawn);
            assert_eq!(waiting.maps_reused(), 0);
            let flipped = differ(&caught_up, &expected, 1e-2);
            eprintln!(
                "caught up by drawing: {flipped} of {} elements more than 1 % off",
                el.len()
            );
            assert!(
                flipped <= el.len() / 1000,
                "{flipped} of {} elements differ",
                el.len()
            );
        }
        // And the light they have yet to shoot is the same.
        let total = |v: &[DVec3]| v.iter().map(|b| b.x).sum::<f64>();
        let (got, want) = (
            total(&waiting.unshot().unwrap()),
            total(&all.unshot().unwrap()),
        );
        assert!((got - want).abs() < 1e-4 * want, "{got} vs {want}");
    }
}

#[test]
fn the_command_refuses_what_a_view_cannot_drive() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let scene = common::root().join("assets/scenes/box_room_calc.toml");
    let scene = scene.to_str().unwrap();
    let (code, _, err) = common::run_cli(
        &["radiosity", scene, "--fov-margin", "200", "--out-dir", out],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--fov-margin 200"), "{err}");
    let (code, _, err) = common::run_cli(
        &[
            "calc",
            scene,
            "--indirect",
            "radiosity",
            "--drive",
            "importance",
            "--out",
            out,
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--drive importance"), "{err}");
    assert!(!std::path::Path::new(out).exists());
}

#[test]
fn the_benchmark_measures_every_drive_through_the_command() {
    let Some(_gpu) = gpu_common::gpu() else {
        return;
    };
    let scene = common::root().join("assets/scenes/boxes_room.toml");
    let (code, out, err) = common::run_cli(
        &[
            "bench",
            "radiosity-view",
            "--json",
            "--scene",
            scene.to_str().unwrap(),
            "--texel-density",
            "4",
            "--level",
            "1",
            "--reference",
            "0.99",
            "--tolerance",
            "0.1",
            "--rooms",
            "2",
            "--map-store-mib",
            "64",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let bench = &v["bench"];
    let rows = bench["rows"].as_array().unwrap();
    let drives: Vec<&str> = rows.iter().map(|r| r["drive"].as_str().unwrap()).collect();
    assert_eq!(drives, ["global", "importance", "perspective"]);
    // Two rooms: the camera sees less than half of the elements.
    let (seen, all) = (
        bench["elements_seen"].as_u64().unwrap(),
        bench["elements"].as_u64().unwrap(),
    );
    assert!(seen > 0 && 2 * seen < all, "{seen} of {all}");
    for r in rows {
        let shot = r["seconds_shot"].as_f64().expect("each drive reaches 10 %");
        assert!(r["importance_seconds"].as_f64().unwrap() <= shot, "{r}");
        assert!(r["seconds_shown"].as_f64().is_some(), "{r}");
        // Only perspective-driven receivers wait, and their catch-up reuses kept maps.
        let reused = r["maps_reused"].as_u64().unwrap();
        assert_eq!(reused > 0, r["drive"] == "perspective", "{r}");
    }
    let (code, _, err) = common::run_cli(&["bench", "radiosity-view", "--rooms", "0"], "");
    assert_eq!(code, 2, "{err}");
}
