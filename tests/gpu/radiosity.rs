//! The radiosity solver against exact cases: Howell's form factors, the furnace (a closed
//! box with uniform exitance E and reflectance ρ converges to B = E / (1 − ρ)), energy
//! conservation, and the GPU against the CPU reference.

use glam::{DVec3, Vec3};
use goniolight::photometry::{Interp, Luminaire};
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::form_factor::{self, howell};
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver, Raster, Visibility, PATCHES_PER_BATCH};
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::solve;
use goniolight::radiosity::{Ambient, FormFactorKind, SolverSettings};
use goniolight::render::{GpuScene, RenderSettings, Renderer};
use goniolight::render::{ShadowSettings, ShadowTechnique};
use goniolight::scene::placement::aim_frame;
use goniolight::scene::{Camera, DisplayEntry, Material, PlacedLuminaire, Scene, SceneMesh};

use crate::common;
use crate::gpu_common;
use crate::radiosity_scenes_common as radiosity_scenes;

use radiosity_scenes::{floor, material, scene_of, tilted};

use common::luminaire;

/// The six faces of the box [lo, hi], facing inward.
fn inward_box(lo: DVec3, hi: DVec3) -> Vec<[Vec3; 3]> {
    let m = goniolight::geometry::generate::cuboid(lo, hi);
    m.triangles
        .iter()
        .map(|t| [t[0], t[2], t[1]].map(|i| m.positions[i as usize].as_vec3()))
        .collect()
}

fn furnace(rho: f32, e: f32) -> Scene {
    let walls = SceneMesh::from_triangles(
        "box",
        &inward_box(DVec3::ZERO, DVec3::new(2.0, 1.5, 1.0)),
        0,
    );
    scene_of(vec![walls], vec![material(rho, e)])
}

/// An open scene of two quads (each two triangles) with reflectance 0.5.
fn two_quads(a: [DVec3; 4], b: [DVec3; 4]) -> Scene {
    let quad = |q: [DVec3; 4]| {
        let v = q.map(|p| p.as_vec3());
        [[v[0], v[1], v[2]], [v[0], v[2], v[3]]]
    };
    let mut tris = quad(a).to_vec();
    tris.extend(quad(b));
    scene_of(
        vec![SceneMesh::from_triangles("quads", &tris, 0)],
        vec![material(0.5, 0.0)],
    )
}

/// F from the first half of the triangles to the second: (1 / A1) Σ_i A_i Σ_p F(i → p).
fn area_form_factor(r: &RadiosityScene, kind: FormFactorKind) -> f64 {
    let el = &r.elements;
    let half = el.triangles.len() / 2;
    let (mut sum, mut area) = (0.0, 0.0);
    for i in 0..el.len() {
        if el.chart[i] as usize >= half {
            continue;
        }
        area += el.area[i];
        for te in &el.charts[half..] {
            for p in &el.patches[te.first_patch as usize..][..te.patch_count as usize] {
                let (pi, ni) = (el.position[i], el.normal(i));
                let f = match kind {
                    FormFactorKind::Disc => {
                        form_factor::disc(pi, ni, p.centroid, te.normal, p.area)
                    }
                    FormFactorKind::Polygon => form_factor::polygon(pi, ni, &p.polygon, te.normal),
                };
                sum += el.area[i] * f;
            }
        }
    }
    sum / area
}

#[test]
fn element_form_factors_match_howell_within_two_percent() {
    let parallel = two_quads(
        [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        [
            DVec3::Z,
            DVec3::new(0.0, 1.0, 1.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
        ],
    );
    let perpendicular = two_quads(
        [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        [DVec3::ZERO, DVec3::Z, DVec3::new(1.0, 0.0, 1.0), DVec3::X],
    );
    // Two coaxial 96-gons of radius 1 at distance 1 (fans of triangles), facing each other.
    let n = 96;
    let ring = |z: f64, k: usize| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), z)
    };
    let mut fans = Vec::new();
    for (z, flip) in [(0.0, false), (1.0, true)] {
        for k in 0..n {
            let (p, q) = (ring(z, k), ring(z, k + 1));
            let c = DVec3::new(0.0, 0.0, z);
            let t = if flip { [c, q, p] } else { [c, p, q] };
            fans.push(t.map(|v| v.as_vec3()));
        }
    }
    let discs = scene_of(
        vec![SceneMesh::from_triangles("discs", &fans, 0)],
        vec![material(0.5, 0.0)],
    );
    // The 96-gon's area is (n / 2π) sin(2π / n) of the disc's: scale the disc value.
    let polygon_area = n as f64 / 2.0 * (std::f64::consts::TAU / n as f64).sin();
    let disc_want = howell::coaxial_discs(1.0, 1.0, 1.0) * polygon_area / std::f64::consts::PI;
    for (name, scene, want) in [
        ("parallel squares", parallel, 0.199825),
        ("perpendicular squares", perpendicular, 0.200044),
        ("coaxial discs", discs, disc_want),
    ] {
        let r = RadiosityScene::new(&scene, 20.0, 2).unwrap();
        for kind in [FormFactorKind::Polygon, FormFactorKind::Disc] {
            let f = area_form_factor(&r, kind);
            eprintln!(
                "{name}, {kind:?}: {f:.6} vs {want:.6} ({:+.2} %)",
                100.0 * (f / want - 1.0)
            );
            let error = f / want - 1.0;
            if kind == FormFactorKind::Disc && name.starts_with("perpendicular") {
                // Wallner's disc approximation saturates for elements next to the shared
                // edge: a known underestimate (about −10 %), why polygon is the default.
                assert!((-0.15..-0.05).contains(&error), "{name} {kind:?}: {error}");
            } else {
                assert!(error.abs() < 0.02, "{name} {kind:?}: {f} vs {want}");
            }
        }
    }
}

fn solved(scene: &RadiosityScene, kind: FormFactorKind, ambient: Ambient) -> CpuSolver<'_> {
    let settings = SolverSettings {
        form_factor: kind,
        ambient,
        ..SolverSettings::default()
    };
    let mut solver = CpuSolver::new(scene, settings);
    solver.solve(0.9999, 5000);
    solver
}

#[test]
fn furnace_converges_to_e_over_one_minus_rho_on_the_cpu() {
    let r = RadiosityScene::new(&furnace(0.5, 100.0), 8.0, 1).unwrap();
    let mut shots = Vec::new();
    for ambient in [Ambient::Display, Ambient::Overshoot] {
        let solver = solved(&r, FormFactorKind::Polygon, ambient);
        let worst = solver
            .radiosity
            .iter()
            .map(|b| (b.x / 200.0 - 1.0).abs())
            .fold(0.0, f64::max);
        eprintln!(
            "furnace, {ambient:?}: {} shots, worst {:.4} %",
            solver.shots,
            100.0 * worst
        );
        assert!(solver.convergence() >= 0.9999);
        assert!(worst < 0.01, "{ambient:?}: worst relative error {worst}");
        shots.push(solver.shots);
    }
    // Overshooting needs fewer shots (Wallner Table 4.1: 10–40 % less time).
    assert!(shots[1] < shots[0], "{shots:?}");
    // The disc approximation underestimates near the box's edges: it must not pass.
    let disc = solved(&r, FormFactorKind::Disc, Ambient::Display);
    let worst = disc
        .radiosity
        .iter()
        .map(|b| (b.x / 200.0 - 1.0).abs())
        .fold(0.0, f64::max);
    assert!(worst > 0.05, "{worst}");
}

#[test]
fn one_shot_in_a_closed_box_delivers_all_its_power() {
    let r = RadiosityScene::new(&furnace(0.5, 100.0), 8.0, 1).unwrap();
    let mut solver = CpuSolver::new(
        &r,
        SolverSettings {
            form_factor: FormFactorKind::Polygon,
            ..SolverSettings::default()
        },
    );
    let before = solver.radiosity.clone();
    let (t, extra) = solver.select().unwrap();
    let te = r.elements.charts[t].clone();
    let shot: f64 = (te.first..te.first + te.count)
        .map(|e| solver.unshot[e as usize].x * r.elements.area[e as usize])
        .sum();
    solver.shoot(t, extra);
    // Received power before reflection: Σ ΔB A / ρ.
    let received: f64 = (0..r.elements.len())
        .map(|e| (solver.radiosity[e].x - before[e].x) * r.elements.area[e] / 0.5)
        .sum();
    eprintln!("shot {shot:.4} lm, received {received:.4} lm");
    assert!((received / shot - 1.0).abs() < 0.01, "{received} vs {shot}");
    // Its own unshot radiosity is gone.
    assert!((te.first..te.first + te.count).all(|e| solver.unshot[e as usize] == DVec3::ZERO));
}

/// The triangles of the box [lo, hi], facing outward.
fn outward_box(lo: DVec3, hi: DVec3) -> Vec<[Vec3; 3]> {
    let cube = goniolight::geometry::generate::cuboid(lo, hi);
    cube.triangles
        .iter()
        .map(|t| t.map(|i| cube.positions[i as usize].as_vec3()))
        .collect()
}

/// The room [0, size] (reflectance 0.5) whose ceiling emits, with `furniture` (0.5).
fn lit_room(size: DVec3, furniture: Vec<[Vec3; 3]>) -> Scene {
    let all = inward_box(DVec3::ZERO, size);
    // The two ceiling triangles (all corners at the top) emit.
    let top = size.z as f32;
    let (ceiling, walls): (Vec<[Vec3; 3]>, Vec<[Vec3; 3]>) =
        all.into_iter().partition(|t| t.iter().all(|v| v.z == top));
    scene_of(
        vec![
            SceneMesh::from_triangles("walls", &walls, 0),
            SceneMesh::from_triangles("ceiling", &ceiling, 1),
            SceneMesh::from_triangles("furniture", &furniture, 0),
        ],
        vec![material(0.5, 0.0), material(0.7, 1000.0)],
    )
}

/// A room with an emissive ceiling and a box standing in it (the box shadows the floor).
fn room_with_box() -> Scene {
    lit_room(
        DVec3::new(3.0, 2.0, 2.0),
        outward_box(DVec3::new(1.0, 0.6, 0.0), DVec3::new(1.8, 1.3, 0.9)),
    )
}

#[test]
fn one_gpu_shot_equals_the_cpu_reference_shot() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&room_with_box(), 6.0, 1).unwrap();
    // The stereographic map at 512² (262 k texels, about the hemicube's 197 k at 256: a
    // 256² front and four half faces): its mesh split so no edge bends wrongly, it loses
    // nothing systematically (before the split 4.6 % of the power at 256²; then +0.32 %
    // at 512², the hemicube +0.26 %, both Wallner's neighbour tolerance; measured now
    // −0.07 % and −0.02 %, 99.5 % and 99.6 % of the elements within 5 %).
    for (visibility, kind, map_size, goal) in [
        (
            Visibility::Hemicube,
            FormFactorKind::Polygon,
            256,
            (0.01, 0.95),
        ),
        (
            Visibility::Hemicube,
            FormFactorKind::Disc,
            256,
            (0.01, 0.95),
        ),
        (
            Visibility::Stereographic,
            FormFactorKind::Polygon,
            512,
            (0.005, 0.95),
        ),
    ] {
        // The render pipeline and the compute rasterizer, each against the CPU's rays.
        for raster in [Raster::Hardware, Raster::Compute] {
            one_gpu_shot_against_the_cpu(&gpu, &r, (visibility, kind, map_size, raster), goal);
        }
    }
}

/// [`one_gpu_shot_equals_the_cpu_reference_shot`] for one map, form factor and rasterizer:
/// the share of the power the GPU delivers within `power_tolerance` of the CPU's, and
/// `share` of the elements within 5 %.
fn one_gpu_shot_against_the_cpu(
    gpu: &goniolight::gpu::Gpu,
    r: &RadiosityScene,
    (visibility, kind, map_size, raster): (Visibility, FormFactorKind, u32, Raster),
    (power_tolerance, share): (f64, f64),
) {
    let settings = SolverSettings {
        form_factor: kind,
        ..SolverSettings::default()
    };
    let mut cpu = CpuSolver::new(r, settings);
    let start = cpu.state();
    let initial = start.radiosity.clone();
    let gpu_settings = GpuSettings {
        visibility,
        map_size,
        raster,
        ..GpuSettings::default()
    };
    let mut solver = GpuSolver::new(gpu, r, &start, settings, gpu_settings);
    assert_eq!(solver.raster(), raster, "never another rasterizer silently");
    let chosen = solver.select().unwrap();
    let (best, extra) = cpu.select().unwrap();
    // The same shooter, or one with the same power (the two ceiling triangles tie).
    let t = chosen.shooter.unwrap();
    let power = |t: usize| {
        let te = &r.elements.charts[t];
        (te.first..te.first + te.count)
            .map(|e| cpu.unshot[e as usize].x * r.elements.area[e as usize])
            .sum::<f64>()
    };
    assert!((power(t) / power(best) - 1.0).abs() < 1e-5, "{t} vs {best}");
    assert!((chosen.unshot_power / cpu.unshot_power() - 1.0).abs() < 1e-4);
    cpu.shoot(t, extra);
    solver.shoot(t).unwrap();
    let got = solver.radiosity().unwrap();
    let max_gain = (0..r.elements.len())
        .map(|e| cpu.radiosity[e].x - initial[e].x)
        .fold(0.0, f64::max);
    let (mut agree, mut lit, mut shadowed) = (0, 0, 0);
    for e in 0..r.elements.len() {
        let want = cpu.radiosity[e].x - initial[e].x;
        let have = got[e].x - initial[e].x;
        agree += ((have - want).abs() <= 0.01 * want.max(0.02 * max_gain)) as usize;
        lit += (want > 0.0) as usize;
        shadowed += (want == 0.0 && r.elements.chart[e] as usize != t) as usize;
    }
    let fraction = agree as f64 / r.elements.len() as f64;
    let total = |b: &[DVec3]| -> f64 {
        (0..r.elements.len())
            .map(|e| (b[e].x - initial[e].x) * r.elements.area[e])
            .sum()
    };
    let within5 = (0..r.elements.len())
        .filter(|&e| {
            let want = cpu.radiosity[e].x - initial[e].x;
            let have = got[e].x - initial[e].x;
            (have - want).abs() <= 0.05 * want.max(0.02 * max_gain)
        })
        .count();
    let ratio = total(&got) / total(&cpu.radiosity);
    let within5 = within5 as f64 / r.elements.len() as f64;
    eprintln!(
        "{visibility:?} {kind:?} {raster:?}: power GPU/CPU {ratio:.4}, within 5 %: {:.2} %",
        100.0 * within5
    );
    // Per element the two differ in penumbrae: the CPU casts one ray per patch, the
    // GPU reads the texel of a map its centre falls in.
    assert!(
        (ratio - 1.0).abs() <= power_tolerance,
        "{visibility:?} {kind:?} {raster:?}: {ratio}"
    );
    assert!(
        within5 >= share,
        "{visibility:?} {kind:?} {raster:?}: {within5}"
    );
    eprintln!(
        "{visibility:?} {kind:?} {raster:?}: {:.2} % of {} elements agree ({lit} lit, {shadowed} unlit)",
        100.0 * fraction,
        r.elements.len()
    );
    assert!(lit > 500 && shadowed > 50, "{lit} lit, {shadowed} unlit");
    let unshot = solver.unshot().unwrap();
    let te = &r.elements.charts[t];
    assert!((te.first..te.first + te.count).all(|e| unshot[e as usize] == DVec3::ZERO));
}

/// A shot stopped between batches of patches (time limit, Ctrl-C) loses no energy and
/// counts none twice: shooting the rest of the same triangle afterwards gives exactly the
/// solution of one whole shot.
#[test]
fn a_shot_stopped_between_batches_resumes_without_loss() {
    let Some(gpu) = gpu_common::gpu() else { return };
    // Level 0: every texel a patch; the largest triangles hold > 1 batch of them.
    let r = RadiosityScene::new(&furnace(0.5, 100.0), 10.0, 0).unwrap();
    let settings = SolverSettings::default();
    let initial = CpuSolver::new(&r, settings).state();
    let new = || GpuSolver::new(&gpu, &r, &initial, settings, GpuSettings::default());
    let (mut whole, mut split) = (new(), new());
    let t = whole.select().unwrap().shooter.unwrap();
    let patches = r.elements.charts[t].patch_count as usize;
    assert!(
        patches > PATCHES_PER_BATCH,
        "{patches} patches: one batch only"
    );
    whole.shoot(t).unwrap();
    assert_eq!(split.select().unwrap().shooter, Some(t));
    let batches = std::cell::Cell::new(0);
    let after_one = || {
        batches.set(batches.get() + 1);
        true
    };
    assert!(
        !split.shoot_until(t, &after_one).unwrap(),
        "stopped after one batch"
    );
    assert_eq!(batches.get(), 1);
    let part = split.unshot().unwrap();
    let full = whole.unshot().unwrap();
    let power = |u: &[DVec3]| -> f64 { u.iter().zip(&r.elements.area).map(|(b, a)| b.x * a).sum() };
    assert!(
        power(&part) > power(&full) * 1.01,
        "part of the triangle is still unshot"
    );
    split.shoot(t).unwrap();
    let (a, b) = (whole.radiosity().unwrap(), split.radiosity().unwrap());
    let worst = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x.x - y.x).abs() / x.x.abs().max(1e-9))
        .fold(0.0, f64::max);
    assert!(worst < 1e-5, "worst relative difference {worst}");
    let (ua, ub) = (
        power(&whole.unshot().unwrap()),
        power(&split.unshot().unwrap()),
    );
    assert!((ua - ub).abs() <= 1e-5 * ua, "unshot {ua} vs {ub}");
}

#[test]
fn furnace_converges_on_the_gpu() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&furnace(0.5, 100.0), 4.0, 1).unwrap();
    for raster in [Raster::Hardware, Raster::Compute] {
        furnace_on_the_gpu(&gpu, &r, raster);
    }
}

/// The furnace solved on `gpu` with the maps drawn by `raster`: B = E / (1 − ρ) = 200
/// lm/m² and 200 lx everywhere, within 1 %.
fn furnace_on_the_gpu(gpu: &goniolight::gpu::Gpu, r: &RadiosityScene, raster: Raster) {
    let settings = SolverSettings::default();
    let initial = CpuSolver::new(r, settings).state();
    let gpu_settings = GpuSettings {
        raster,
        ..GpuSettings::default()
    };
    let mut solver = GpuSolver::new(gpu, r, &initial, settings, gpu_settings);
    assert_eq!(solver.raster(), raster);
    let start = solver.select().unwrap().unshot_power;
    let mut remaining = start;
    while solver.stats.shots < 500 && remaining > 1e-4 * start {
        match solver.step().unwrap() {
            Some(s) => remaining = s.unshot_power,
            None => break,
        }
    }
    let (b, lux) = solver.radiosity_and_illuminance().unwrap();
    let worst = b
        .iter()
        .map(|b| (b.x / 200.0 - 1.0).abs())
        .fold(0.0, f64::max);
    // Every element receives what it sees everywhere: B = 200 lm/m² → 200 lx.
    let worst_lux = lux
        .iter()
        .map(|e| (e / 200.0 - 1.0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "GPU furnace ({raster:?}): {} shots, worst {:.3} %, illuminance worst {:.3} %",
        solver.stats.shots,
        100.0 * worst,
        100.0 * worst_lux
    );
    assert!(worst < 0.01, "worst relative error {worst}");
    assert!(worst_lux < 0.01, "worst illuminance error {worst_lux}");
}

#[test]
fn ambient_overshooting_on_the_gpu_converges_in_fewer_shots() {
    let Some(gpu) = gpu_common::gpu() else { return };
    // The furnace laid in charts (one per face), both GPU shooter kinds: overshooting
    // (Feda and Purgathofer; Wallner §4.3.5) reaches 99.99 % in fewer shots, to the same B.
    // Each face has its own material (the same ρ and E), so with clusters each face is a
    // surface and a shooter: one shooter holding all the light has no ambient to overshoot.
    let faces = inward_box(DVec3::ZERO, DVec3::new(2.0, 1.5, 1.0));
    let meshes = faces
        .chunks(2)
        .enumerate()
        .map(|(k, pair)| SceneMesh::from_triangles(&format!("face {k}"), pair, k))
        .collect();
    let six = scene_of(meshes, vec![material(0.5, 100.0); 6]);
    let r =
        RadiosityScene::with_hierarchy(&six, 8.0, 1, goniolight::radiosity::Hierarchy::Clusters)
            .unwrap();
    assert_eq!(r.elements.charts.len(), 6, "one chart per face");
    assert_eq!(
        goniolight::radiosity::shooters::Shooters::clusters(&r).len(),
        6,
        "one shooter per face"
    );
    for hierarchy in [
        goniolight::radiosity::Hierarchy::None,
        goniolight::radiosity::Hierarchy::Clusters,
    ] {
        let mut shots = Vec::new();
        for ambient in [Ambient::Display, Ambient::Overshoot] {
            let settings = SolverSettings {
                ambient,
                ..SolverSettings::default()
            };
            let initial = CpuSolver::new(&r, settings).state();
            let gpu_settings = GpuSettings {
                hierarchy,
                ..GpuSettings::default()
            };
            let mut solver = GpuSolver::new(&gpu, &r, &initial, settings, gpu_settings);
            let stop = solve::StopAt {
                converge: 0.9999,
                max_shots: Some(2000),
                time_budget: None,
            };
            solver
                .solve(&stop, &std::sync::atomic::AtomicBool::new(false), |_| {})
                .unwrap();
            let worst = solver
                .radiosity()
                .unwrap()
                .iter()
                .map(|b| (b.x / 200.0 - 1.0).abs())
                .fold(0.0, f64::max);
            eprintln!(
                "GPU furnace, {hierarchy:?}, {ambient:?}: {} shots, worst {:.3} %",
                solver.stats.shots,
                100.0 * worst
            );
            assert!(worst < 0.005, "{hierarchy:?} {ambient:?}: {worst}");
            shots.push(solver.stats.shots);
        }
        assert!(
            (shots[1] as f64) < 0.9 * shots[0] as f64,
            "{hierarchy:?}: overshooting {shots:?}"
        );
    }
}

#[test]
fn luminaires_shot_on_the_gpu_matches_the_cpu_ray_cast() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let mut scene = room_with_box();
    let ldt = Luminaire::load(&luminaire("eulumdat-luminance/sample_07.ldt")).unwrap();
    let mut lamp = PlacedLuminaire::new("tilted", ldt, DVec3::new(2.3, 1.5, 1.9));
    lamp.rotation = aim_frame(Some(DVec3::new(-0.4, -0.3, -1.0)), 20.0);
    scene.luminaires.push(lamp);
    let r = RadiosityScene::new(&scene, 6.0, 1).unwrap();
    let cpu = CpuSolver::new(&r, SolverSettings::default());
    let shadows = ShadowSettings::with(ShadowTechnique::Paraboloid);
    let gpu_start = {
        let light = LuminaireLight::new(&gpu, &scene, Interp::CatmullRom);
        InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap()
    };
    let n = r.elements.len();
    let peak = cpu.illuminance.iter().cloned().fold(0.0, f64::max);
    let agree = (0..n)
        .filter(|&e| {
            let (want, have) = (cpu.illuminance[e], gpu_start.illuminance[e]);
            (have - want).abs() <= 0.01 * want.max(0.01 * peak)
        })
        .count();
    let lit = cpu.illuminance.iter().filter(|&&e| e > 0.0).count();
    let shadowed = n - lit;
    let share = agree as f64 / n as f64;
    eprintln!("luminaires' shot: GPU within 1 % of the CPU on {:.2} % of {n} elements ({shadowed} in shadow)", 100.0 * share);
    // Paraboloid maps blur shadow edges over a PCF kernel; everywhere else they agree.
    assert!(shadowed > 50 && share > 0.97, "{share}");
    for e in 0..n {
        let want = cpu.radiosity[e];
        let have = gpu_start.radiosity[e];
        let tolerance = 0.02 * want.x.max(0.02 * peak);
        if (cpu.illuminance[e] - gpu_start.illuminance[e]).abs() <= 0.01 * cpu.illuminance[e] {
            assert!(
                (have - want).abs().max_element() <= tolerance,
                "{e}: {have} vs {want}"
            );
        }
    }
}

#[test]
fn luminaires_shot_delivers_the_luminaires_flux_in_a_closed_room() {
    // The bundled box room: a luminaire 5 cm under the ceiling, 45 % of its flux upward.
    // Every lumen lands on a wall, so Σ E × A over the elements is the luminaire's flux;
    // one sample per element at the centroid would miss the ceiling's peak by ~10 %.
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = Scene::load(&common::root().join("assets/scenes/box_room.toml")).unwrap();
    let flux = scene.luminaires[0].luminaire.summary().flux_lm;
    let r = RadiosityScene::new(&scene, 10.0, 2).unwrap();
    let shadows = ShadowSettings::with(ShadowTechnique::Paraboloid);
    let start = {
        let light = LuminaireLight::new(&gpu, &scene, Interp::CatmullRom);
        InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap()
    };
    let delivered: f64 = (0..r.elements.len())
        .map(|e| start.illuminance[e] * r.elements.area[e])
        .sum();
    let centroid_only: f64 = (0..r.elements.len())
        .map(|e| {
            scene.luminaires[0].illuminance_at(
                r.elements.position[e],
                r.elements.normal(e),
                Interp::CatmullRom,
            ) * r.elements.area[e]
        })
        .sum();
    eprintln!(
        "luminaire flux {flux:.1} lm: delivered {delivered:.1} lm ({:+.2} %), centroid samples only {:+.2} %",
        100.0 * (delivered / flux - 1.0),
        100.0 * (centroid_only / flux - 1.0)
    );
    assert!(
        (delivered / flux - 1.0).abs() < 0.01,
        "{delivered} vs {flux}"
    );
}

#[test]
fn a_patch_lights_nothing_behind_its_plane() {
    // An emitting panel 1 cm under a ceiling, facing down, over a floor: the ceiling (in
    // front of the panel's back) must get nothing, the floor its share (the bug this
    // guards against lit the ceiling of the Cornell box from the back of its light).
    let Some(gpu) = gpu_common::gpu() else { return };
    let quad = |z: f32, half: f32, up: bool| -> Vec<[Vec3; 3]> {
        let c = [(-half, -half), (half, -half), (half, half), (-half, half)]
            .map(|(x, y)| Vec3::new(x, y, z));
        if up {
            vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
        } else {
            vec![[c[0], c[2], c[1]], [c[0], c[3], c[2]]]
        }
    };
    let scene = scene_of(
        vec![
            SceneMesh::from_triangles("panel", &quad(0.99, 0.3, false), 1),
            SceneMesh::from_triangles("ceiling", &quad(1.0, 1.0, false), 0),
            SceneMesh::from_triangles("floor", &quad(0.0, 1.0, true), 0),
        ],
        vec![material(0.5, 0.0), material(0.0, 1000.0)],
    );
    let r = RadiosityScene::new(&scene, 10.0, 1).unwrap();
    let settings = SolverSettings::default();
    let mut cpu = CpuSolver::new(&r, settings);
    let mut solver = GpuSolver::new(&gpu, &r, &cpu.state(), settings, GpuSettings::default());
    for _ in 0..2 {
        let (t, extra) = cpu.select().unwrap();
        cpu.shoot(t, extra);
        solver.shoot(t).unwrap();
    }
    let b = solver.radiosity().unwrap();
    let mean = |b: &[DVec3], tris: std::ops::Range<usize>| {
        let el = &r.elements;
        let elements = tris.flat_map(|t| {
            let te = &el.charts[t];
            te.first as usize..(te.first + te.count) as usize
        });
        let (sum, area) = elements.fold((0.0, 0.0), |(s, a), e| {
            (s + b[e].x * el.area[e], a + el.area[e])
        });
        sum / area
    };
    for (who, b) in [("GPU", &b), ("CPU", &cpu.radiosity)] {
        let (ceiling, floor) = (mean(b, 2..4), mean(b, 4..6));
        eprintln!("{who}: ceiling {ceiling:.3}, floor {floor:.3} lm/m²");
        assert_eq!(ceiling, 0.0, "{who}");
        assert!(floor > 10.0, "{who}: {floor}");
    }
}

#[test]
fn solved_display_is_the_light_map_plus_the_direct_specular_term() {
    // A glossy floor under one luminaire, nothing else: its radiosity is ρ × the direct
    // light, so the solved display (light map + specular) must look like the direct
    // render, highlight included.
    let Some(gpu) = gpu_common::gpu() else { return };
    solved_display_matches_the_direct_render(&gpu, Floor::default());
    // Textured: the solution reflects the texture's mean colour, and the display varies
    // it about that mean by the texels (a checker of 1.0 and 0.05 in linear light).
    let checker = image::RgbaImage::from_fn(8, 8, |x, y| {
        let v = if (x + y) % 2 == 0 { 255 } else { 64 };
        image::Rgba([v, v, v, 255])
    });
    solved_display_matches_the_direct_render(
        &gpu,
        Floor {
            texture: Some(checker),
            ..Floor::default()
        },
    );
}

#[test]
fn solved_display_keeps_the_normal_maps_relief_finer_than_its_elements() {
    // Stripes tilted ±30°, 6.25 cm wide, under 25 cm elements: each element receives
    // with the stripes' mean normal, and the display adds back, per pixel, the direct
    // light's difference between the pixel's normal and that mean. It must look like
    // the direct render, relief and all.
    let Some(gpu) = gpu_common::gpu() else { return };
    let stripes = image::RgbaImage::from_fn(2, 2, |x, _| tilted(if x == 0 { 30.0 } else { -30.0 }));
    solved_display_matches_the_direct_render(
        &gpu,
        Floor {
            normal_map: Some(stripes),
            repeat: 32.0,
            texel_density: 4.0,
            ..Floor::default()
        },
    );
}

#[test]
fn a_normal_maps_solved_display_differs_from_the_flat_one_only_where_it_tilts() {
    // The map's left half (the floor's x < 0, the image's left) is tilted 30° about the
    // floor's y axis, its right half flat; the same floor without a map is the reference.
    let Some(gpu) = gpu_common::gpu() else { return };
    let half = image::RgbaImage::from_fn(64, 64, |x, _| {
        if x < 32 {
            tilted(30.0)
        } else {
            image::Rgba([128, 128, 255, 255])
        }
    });
    let floor_with = |normal_map| Floor {
        normal_map,
        repeat: 1.0,
        texel_density: 10.0,
        ..Floor::default()
    };
    let (_, mapped) = direct_and_solved_displays(&gpu, floor_with(Some(half)));
    let (_, flat) = direct_and_solved_displays(&gpu, floor_with(None));
    // Median relative difference over the floor's pixels in columns of the image.
    let median = |columns: std::ops::Range<usize>| {
        let mut rel: Vec<f32> = (0..120)
            .flat_map(|y| columns.clone().map(move |x| y * 160 + x))
            .filter(|&i| flat[i] > 1.0)
            .map(|i| (mapped[i] / flat[i] - 1.0).abs())
            .collect();
        assert!(rel.len() > 1000, "{}", rel.len());
        rel.sort_by(f32::total_cmp);
        rel[rel.len() / 2]
    };
    let (tilted_side, flat_side) = (median(5..60), median(100..155));
    eprintln!(
        "mapped vs flat solved display: tilted half {:.1} %, flat half {:.2} %",
        100.0 * tilted_side,
        100.0 * flat_side
    );
    assert!(tilted_side > 0.05, "{tilted_side}");
    assert!(flat_side < 0.01, "{flat_side}");
}

/// The floor of the solved-display tests.
struct Floor {
    /// Diffuse texture.
    texture: Option<image::RgbaImage>,
    /// Normal map.
    normal_map: Option<image::RgbaImage>,
    /// Texture repeats across the 4 m floor.
    repeat: f32,
    /// Light-map texels per metre.
    texel_density: f64,
}

impl Default for Floor {
    fn default() -> Floor {
        Floor {
            texture: None,
            normal_map: None,
            repeat: 3.0,
            texel_density: 40.0,
        }
    }
}

fn solved_display_matches_the_direct_render(gpu: &goniolight::gpu::Gpu, floor_kind: Floor) {
    let (direct, solved) = direct_and_solved_displays(gpu, floor_kind);
    let (peak, at) = direct
        .iter()
        .enumerate()
        .fold((0.0f32, 0), |b, (i, &v)| if v > b.0 { (v, i) } else { b });
    let mut rel: Vec<f32> = direct
        .iter()
        .zip(&solved)
        .filter(|(d, _)| **d > 0.0)
        .map(|(d, s)| (s / d - 1.0).abs())
        .collect();
    rel.sort_by(f32::total_cmp);
    let median = rel[rel.len() / 2];
    eprintln!(
        "solved vs direct display: highlight {peak:.1} vs {:.1}, median difference {:.2} %",
        solved[at],
        100.0 * median
    );
    // The highlight is mostly specular: without the specular term it would drop by far.
    assert!(
        (solved[at] / peak - 1.0).abs() < 0.05,
        "{} vs {peak}",
        solved[at]
    );
    assert!(median < 0.03, "{median}");
}

/// The 160 × 120 HDR luminance (r + g + b) of the floor's direct render and of its
/// solved display (its radiosity is the luminaire's direct light, no interreflection).
fn direct_and_solved_displays(
    gpu: &goniolight::gpu::Gpu,
    floor_kind: Floor,
) -> (Vec<f32>, Vec<f32>) {
    let floor = floor(Vec3::new(-2.0, -2.0, 0.0), 4.0, floor_kind.repeat);
    let glossy = Material {
        specular: Vec3::splat(0.3),
        shininess: 60.0,
        diffuse_map: floor_kind.texture.map(std::sync::Arc::new),
        normal_map: floor_kind.normal_map.map(std::sync::Arc::new),
        ..material(0.5, 0.0)
    };
    let mut scene = scene_of(vec![floor], vec![glossy]);
    let ldt = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    scene
        .luminaires
        .push(PlacedLuminaire::new("lamp", ldt, DVec3::new(0.0, 0.0, 1.5)));
    scene.camera = Camera::perspective(DVec3::new(0.0, -2.5, 1.2), DVec3::new(0.0, 0.6, 0.0), 60.0);
    let r = RadiosityScene::new(&scene, floor_kind.texel_density, 1).unwrap();
    let light = LuminaireLight::new(gpu, &scene, Interp::CatmullRom);
    let shadows = ShadowSettings::none();
    let start = InitialState::from_luminaires_gpu(gpu, &light, &r, &shadows).unwrap();
    let map = solve::light_map(&r, &start.radiosity, &start.illuminance);
    let renderer = Renderer::new(gpu);
    let mut settings = RenderSettings::from_display(&DisplayEntry::default());
    (settings.width, settings.height, settings.read_hdr) = (160, 120, true);
    settings.shadows = shadows;
    let luminance = |uploaded: &GpuScene| -> Vec<f32> {
        let frame = renderer
            .render(gpu, uploaded, &scene.camera, &settings)
            .unwrap();
        frame
            .hdr
            .unwrap()
            .iter()
            .map(|p| p[0] + p[1] + p[2])
            .collect()
    };
    let direct = luminance(&renderer.upload(gpu, &scene));
    let solved = luminance(&renderer.upload_solved(gpu, &scene, &map));
    (direct, solved)
}

/// More elements than one 128 MiB binding held as the solver's first 48-byte records
/// (2 796 202): every per-element buffer is 16 bytes wide now (8.4 M elements per binding),
/// and 4.46 M receivers need more than 65 535 workgroups of 64 (a two-dimensional dispatch).
/// One shot in the furnace box picks the strongest triangle (its 515 000 elements summed
/// by a workgroup: one llvmpipe thread stops after 65 535 loop iterations), delivers all
/// its power, and the elements past the old limit receive what the form factors to the
/// shooter's patches give (a convex box: all visible).
#[test]
fn elements_past_one_binding_of_the_old_records_receive_their_light() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let rho = 0.5;
    let r = RadiosityScene::new(&furnace(rho as f32, 100.0), 585.0, 8).unwrap();
    let el = &r.elements;
    let old_limit = (128usize << 20) / 48;
    assert!(el.len() > old_limit, "{} elements", el.len());
    goniolight::render::limits::check_radiosity(&gpu, el.len()).unwrap();
    let settings = SolverSettings::default();
    let initial = CpuSolver::new(&r, settings).state();
    let mut solver = GpuSolver::new(&gpu, &r, &initial, settings, GpuSettings::default());
    // Millions of elements (a floor triangle alone has 339 000) still pick the strongest shooter (a floor
    // triangle, 150 lm) and the right unshot power.
    let chosen = solver.select().unwrap();
    let t = chosen.shooter.unwrap();
    let cpu = CpuSolver::new(&r, settings);
    let (best, _) = cpu.select().unwrap();
    let power = |t: usize| 100.0 * el.charts[t].area;
    assert!((power(t) / power(best) - 1.0).abs() < 1e-4, "{t} vs {best}");
    let unshot_power = chosen.unshot_power / cpu.unshot_power();
    assert!((unshot_power - 1.0).abs() < 1e-4, "{unshot_power}");
    solver.shoot(t).unwrap();
    let b = solver.radiosity().unwrap();
    let chart = &el.charts[t];
    let shot: f64 = (chart.first..chart.first + chart.count)
        .map(|e| 100.0 * el.area[e as usize])
        .sum();
    let gain = |e: usize| b[e].x - initial.radiosity[e].x;
    let received: f64 = (0..el.len()).map(|e| gain(e) * el.area[e] / rho).sum();
    eprintln!(
        "{} elements: shot {shot:.3} lm, received {received:.3} lm",
        el.len()
    );
    assert!((received / shot - 1.0).abs() < 0.01, "{received} vs {shot}");
    let patches = &el.patches[chart.first_patch as usize..][..chart.patch_count as usize];
    let (mut worst, mut lit, mut off) = (0.0f64, 0, 0);
    for e in old_limit..el.len() {
        if el.chart[e] as usize == t {
            continue;
        }
        let want: f64 = patches
            .iter()
            .map(|p| {
                rho * 100.0
                    * form_factor::polygon(el.position[e], el.normal(e), &p.polygon, chart.normal)
            })
            .sum();
        // Relative to at least 0.01 lm/m²: radiosity is stored as f32 (a step of 8e-6 at
        // the 100 lm/m² the elements start from).
        let d = (gain(e) - want).abs() / want.max(0.01);
        worst = worst.max(d);
        off += (d > 0.01) as usize;
        lit += (want > 1e-3) as usize;
    }
    eprintln!(
        "past the old limit: {lit} lit elements, {off} more than 1 % off, worst {:.4} %",
        100.0 * worst
    );
    assert!(lit > 10_000, "{lit}");
    // Every element within 1 % but those (measured: 159 of 1 664 330) less than a
    // millimetre from a corner, a hundredth of a texel's width away at 256²: there the
    // texel shows the other wall, seen at a grazing angle, and the plane that wall's
    // texels fit may miss by more than the element's distance (measured: 5.1 % low).
    assert!(
        off * 5_000 < lit,
        "{off} of {lit} elements more than 1 % off"
    );
    assert!(worst < 0.06, "worst relative difference {worst}");
}

/// One element more than a binding holds is refused with what to do, before any buffer is
/// made (a panic inside wgpu otherwise); as many as it holds are accepted.
#[test]
fn more_elements_than_one_binding_holds_are_refused() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let limits = gpu.device.limits();
    let fit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size)
        / goniolight::render::limits::RADIOSITY_ELEMENT_BYTES;
    let check = |n: u64| goniolight::render::limits::check_radiosity(&gpu, n as usize);
    check(fit).unwrap();
    let message = check(fit + 1).unwrap_err().to_string();
    assert!(
        message.contains("lower `texel_density`")
            && message.contains(&format!("about {fit} elements fit")),
        "{message}"
    );
}

/// A room with an emissive ceiling and a 12 × 12 grid of small boxes on its floor (1 728
/// triangles: several chunks of the visibility mesh).
fn room_with_many_boxes() -> Scene {
    let mut boxes = Vec::new();
    for i in 0..12 {
        for j in 0..12 {
            let lo = DVec3::new(0.3 + 0.45 * i as f64, 0.3 + 0.45 * j as f64, 0.0);
            let hi = lo + DVec3::new(0.25, 0.25, 0.2 + 0.05 * ((i * 7 + j * 3) % 11) as f64);
            boxes.extend(outward_box(lo, hi));
        }
    }
    lit_room(DVec3::new(6.0, 6.0, 3.0), boxes)
}

/// Shoots `first` (or else the first shooter selected), then every 9th shooter, twelve
/// of them, in batches of 16 cells: two solvers shot so place their maps alike and shoot
/// the same shooters in the same order (the selection breaks ties between equal shooters
/// either way: the two ceiling triangles). Returns the first.
fn shoot_the_same_shooters(solver: &mut GpuSolver, first: Option<usize>) -> usize {
    // Batches by count, not by the clock.
    solver.fix_batch(16);
    let chosen = solver.select().unwrap().shooter.unwrap();
    let first = first.unwrap_or(chosen);
    solver.shoot(first).unwrap();
    for s in (0..solver.shooters().len()).step_by(9).take(12) {
        solver.select().unwrap();
        solver.shoot(s).unwrap();
    }
    first
}

#[test]
fn faces_that_draw_only_the_chunks_they_can_see_give_the_same_solution() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&room_with_many_boxes(), 5.0, 1).unwrap();
    let settings = SolverSettings::default();
    let start = CpuSolver::new(&r, settings).state();
    for visibility in [Visibility::Hemicube, Visibility::Stereographic] {
        let solve = |chunk_culling: bool, first: Option<usize>| {
            let gpu_settings = GpuSettings {
                visibility,
                chunk_culling,
                ..GpuSettings::default()
            };
            let mut solver = GpuSolver::new(&gpu, &r, &start, settings, gpu_settings);
            let first = shoot_the_same_shooters(&mut solver, first);
            let maps = solver.stats.drawn as u64;
            let per_map = solver.stats.triangles_drawn as f64 / maps as f64;
            let mesh = solver.visibility_triangles();
            (solver.radiosity().unwrap(), per_map, mesh, first)
        };
        let (culled, culled_per_map, mesh, first) = solve(true, None);
        let (whole, whole_per_map, _, _) = solve(false, Some(first));
        let faces = if visibility == Visibility::Hemicube {
            5.0
        } else {
            1.0
        };
        eprintln!(
            "{visibility:?}: {mesh} triangles; per map {culled_per_map:.0} drawn with culling, {whole_per_map:.0} without"
        );
        assert_eq!(
            whole_per_map,
            faces * mesh as f64,
            "without: the whole mesh per face"
        );
        let largest = whole.iter().map(|b| b.x).fold(0.0, f64::max);
        for (e, (a, b)) in culled.iter().zip(&whole).enumerate() {
            assert!(
                (a.x - b.x).abs() <= 1e-6 * largest,
                "{visibility:?}: element {e}: {} with culling, {} without",
                a.x,
                b.x
            );
        }
        if visibility == Visibility::Hemicube {
            assert!(
                culled_per_map < 0.6 * whole_per_map,
                "a hemicube's five faces draw {culled_per_map:.0} of {whole_per_map:.0}"
            );
        }
    }
}

/// The compute rasterizer draws the hemicube's maps the render pipeline draws, to within a
/// texel along edges: the same shooters shot on the room with 144 boxes (shadows, grazing
/// boxes, faces crossing the eye's plane) deliver the same power within 0.1 %, and all but
/// one element in 200 the same radiosity within 0.1 % of the largest (on lavapipe and on an
/// H200; lavapipe at 5 texels a metre: 32 of 10 240 elements differ, at 8: 33 of 19 470;
/// the elements along edges are a larger share of fewer, the solve a quarter of the time). Its stereographic maps follow the arcs the edges project to, where the render
/// pipeline draws chords: the same power within 0.5 % (0.16 % on lavapipe), while 15 % of
/// the elements differ by more than 0.1 % (against the CPU's rays the two are alike:
/// [`one_gpu_shot_equals_the_cpu_reference_shot`]; through closed walls:
/// [`light_stays_in_its_closed_room_with_either_map`]). And `auto` is compute on a GPU, the
/// render pipeline on a software driver and with alpha masks.
#[test]
fn the_compute_rasterizer_gives_the_render_pipelines_solution() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&room_with_many_boxes(), 5.0, 1).unwrap();
    let settings = SolverSettings::default();
    let start = CpuSolver::new(&r, settings).state();
    let software = gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
    let auto = if software {
        Raster::Hardware
    } else {
        Raster::Compute
    };
    assert_eq!(Raster::Auto.resolve(&gpu, false), auto);
    assert_eq!(Raster::Compute.resolve(&gpu, false), Raster::Compute);
    assert_eq!(Raster::Compute.resolve(&gpu, true), Raster::Hardware);
    assert_eq!(Raster::Auto.resolve(&gpu, true), Raster::Hardware);
    for visibility in [Visibility::Hemicube, Visibility::Stereographic] {
        let solve = |raster: Raster, first: Option<usize>| {
            let gpu_settings = GpuSettings {
                visibility,
                raster,
                ..GpuSettings::default()
            };
            let mut solver = GpuSolver::new(&gpu, &r, &start, settings, gpu_settings);
            assert_eq!(solver.raster(), raster);
            let first = shoot_the_same_shooters(&mut solver, first);
            (solver.radiosity().unwrap(), first)
        };
        let (hardware, first) = solve(Raster::Hardware, None);
        let (compute, _) = solve(Raster::Compute, Some(first));
        let initial = |e: usize| start.radiosity[e].x;
        let largest = hardware
            .iter()
            .enumerate()
            .map(|(e, b)| b.x - initial(e))
            .fold(0.0, f64::max);
        let (mut worst, mut differ) = (0.0f64, 0usize);
        for (a, b) in hardware.iter().zip(&compute) {
            let d = (a.x - b.x).abs() / largest;
            worst = worst.max(d);
            differ += usize::from(d > 1e-3);
        }
        let total = |b: &[DVec3]| -> f64 {
            b.iter()
                .enumerate()
                .map(|(e, b)| (b.x - initial(e)) * r.elements.area[e])
                .sum()
        };
        let ratio = total(&compute) / total(&hardware);
        eprintln!(
            "{visibility:?}: compute / render pipeline {ratio:.5}; worst element {:.3} % of the largest gain; {differ} of {} elements differ by more than 0.1 %",
            100.0 * worst,
            hardware.len()
        );
        // A texel whose centre lies on an edge is the compute rasterizer's and not the
        // render pipeline's: where a receiver sees that edge at a grazing angle its 3 × 3
        // test may flip (as between two batchings of the same shots, GpuSolver::fix_batch).
        assert!(largest > 0.0);
        if visibility == Visibility::Stereographic {
            assert!((ratio - 1.0).abs() < 5e-3, "{visibility:?}: {ratio}");
            continue;
        }
        assert!((ratio - 1.0).abs() < 1e-3, "{visibility:?}: {ratio}");
        assert!(worst < 0.05, "{visibility:?}: worst {worst}");
        assert!(
            differ * 200 < hardware.len(),
            "{visibility:?}: {differ} elements differ"
        );
    }
}

/// Two closed 2 × 1.5 × 1 m rooms 10 m apart: room A's walls emit, room B's do not, and
/// no light may reach room B through room A's walls. The hemicube is exact, and so is the
/// stereographic map drawn by compute shaders (texels tested by their rays, arcs for edges).
/// The render pipeline draws the chords between projected vertices: where an edge lies in
/// a shooting cell's plane (a wall's foot seen from a floor cell) the sliver between chord
/// and rim shows what lies beyond the wall, and room B's feet just above the floor's plane
/// were seen through it. Its empty texels no longer count as seen (2.1e-5 of the power
/// leaked before at 128², 1.7e-6 now, whatever the map's size: room B drawn in the sliver).
#[test]
fn light_stays_in_its_closed_room_with_either_map() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let room_a = SceneMesh::from_triangles(
        "room a",
        &inward_box(DVec3::ZERO, DVec3::new(2.0, 1.5, 1.0)),
        0,
    );
    let room_b = SceneMesh::from_triangles(
        "room b",
        &inward_box(DVec3::new(10.0, 0.0, 0.0), DVec3::new(12.0, 1.5, 1.0)),
        1,
    );
    let scene = scene_of(
        vec![room_a, room_b],
        vec![material(0.5, 10.0), material(0.5, 0.0)],
    );
    let r = RadiosityScene::new(&scene, 8.0, 1).unwrap();
    let settings = SolverSettings::default();
    let start = CpuSolver::new(&r, settings).state();
    let in_b = |e: usize| r.elements.position[e].x > 5.0;
    let power = |b: &[DVec3], e: usize| b[e].x * r.elements.area[e];
    let emitted: f64 = (0..r.elements.len())
        .map(|e| power(&start.radiosity, e))
        .sum();
    let (s, h) = (Visibility::Stereographic, Visibility::Hemicube);
    let (chords, exact) = (Raster::Hardware, Raster::Compute);
    for (visibility, raster, map_size, allowed) in [
        (s, exact, 128, 0.0),
        (s, exact, 256, 0.0),
        (h, exact, 128, 0.0),
        (h, chords, 128, 0.0),
        (s, chords, 128, 2.5e-6),
        (s, chords, 256, 2.5e-6),
    ] {
        let gpu_settings = GpuSettings {
            visibility,
            raster,
            map_size,
            ..GpuSettings::default()
        };
        let mut solver = GpuSolver::new(&gpu, &r, &start, settings, gpu_settings);
        let stop = solve::StopAt {
            converge: 1.0,
            max_shots: Some(24),
            time_budget: None,
        };
        solver
            .solve(&stop, &std::sync::atomic::AtomicBool::new(false), |_| {})
            .unwrap();
        assert_eq!(solver.stats.shots, 24);
        let b = solver.radiosity().unwrap();
        let leaked = (0..r.elements.len())
            .filter(|&e| in_b(e))
            .map(|e| power(&b, e))
            .sum::<f64>()
            / emitted;
        let kept: f64 = (0..r.elements.len())
            .filter(|&e| !in_b(e))
            .map(|e| power(&b, e))
            .sum();
        eprintln!("{visibility:?} {raster:?} {map_size}²: room B holds {leaked:.3e} of the power");
        // Room A took the light in (B = E / (1 − ρ) once solved: twice the emission).
        assert!(kept > 1.5 * emitted, "{kept} of {emitted}");
        assert!(
            leaked <= allowed,
            "{visibility:?} {raster:?} {map_size}: {leaked}"
        );
    }
}

/// One shot in a room with 144 boxes on its floor (1 964 elements in shadow) against the
/// CPU's rays: the same power within 0.5 % and nine elements in ten within 5 %, with
/// either map and either rasterizer. Wallner's lookup (a receiver seen if one of the
/// nine texels around its own is at least as far) lit every receiver within a texel and
/// a half of a box's outline: +5.7 % of the power with the hemicube at 256², +6.5 % with
/// the stereographic map at 512², three elements in four within 5 %.
#[test]
fn one_gpu_shot_in_a_cluttered_room_equals_the_cpu_reference_shot() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&room_with_many_boxes(), 6.0, 1).unwrap();
    for (visibility, map_size) in [
        (Visibility::Hemicube, 256),
        (Visibility::Stereographic, 512),
    ] {
        for raster in [Raster::Hardware, Raster::Compute] {
            one_gpu_shot_against_the_cpu(
                &gpu,
                &r,
                (visibility, FormFactorKind::Polygon, map_size, raster),
                (0.005, 0.9),
            );
        }
    }
}
