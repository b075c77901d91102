//! Mirrors and clear glass in the CPU reference solver ([`goniolight::radiosity::specular`])
//! against exact cases:
//! - the specular furnace: a closed box whose walls emit E and reflect ρ, one wall a
//!   mirror of ρ_s = ρ (emitting E) and a lossless pane of glass across it (τ_s + ρ_s = 1),
//!   keeps the uniform field: every surface receives E / (1 − ρ);
//! - a pane passes exactly τ_s of a luminaire's light where the straight line crosses it;
//! - a mirror gives a receiver ρ_s times what the shooter's mirror image, built as real
//!   geometry without the mirror, gives it;
//! - a luminaire over a mirror floor lights a surface facing down by its image (the law
//!   of reflection worked out by hand);
//! - the GPU solver's virtual cells (both rasterizers) against the same exact cases and
//!   against the CPU reference where an occluder stands between a shooter and a mirror.

use glam::{DVec3, Vec3};
use goniolight::gpu::Gpu;
use goniolight::photometry::{Interp, Luminaire};
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver, Raster};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::{Ambient, SolverSettings};
use goniolight::scene::{Material, PlacedLuminaire, Scene, SceneMesh};

use crate::common;
use crate::furnace_common as furnace;
use crate::gpu_common;
use crate::radiosity_scenes_common as radiosity_scenes;

use radiosity_scenes::{material, scene_of};

const ROOM: DVec3 = DVec3::new(2.0, 1.5, 1.0);

fn specular(diffuse: f32, emission: f32, reflect: f32, transmit: f32) -> Material {
    Material {
        specular_reflectance: Vec3::splat(reflect),
        specular_transmittance: Vec3::splat(transmit),
        ..material(diffuse, emission)
    }
}

/// A quad's two triangles, corners in order.
fn quad(q: [DVec3; 4]) -> Vec<[Vec3; 3]> {
    let v = q.map(|p| p.as_vec3());
    vec![[v[0], v[1], v[2]], [v[0], v[2], v[3]]]
}

fn settings() -> SolverSettings {
    SolverSettings {
        ambient: Ambient::None,
        ..SolverSettings::default()
    }
}

/// The furnace box: walls (material 0) with the y = 0 wall a mirror (material 1), and a
/// pane (material 2) across the middle at x = 1, facing +x. The box is built as its two
/// halves (without their faces at x = 1), so no wall's patch straddles the pane.
fn specular_furnace(pane: Material) -> Scene {
    let mut walls = Vec::new();
    let mut mirror = Vec::new();
    for (lo, hi) in [(0.0, 1.0), (1.0, 2.0)] {
        let half = furnace::inward_box(DVec3::new(lo, 0.0, 0.0), DVec3::new(hi, ROOM.y, ROOM.z));
        for t in half {
            if t.iter().all(|p| p.x == 1.0) {
                continue;
            }
            if t.iter().all(|p| p.y == 0.0) {
                mirror.push(t);
            } else {
                walls.push(t);
            }
        }
    }
    let (h, d) = (ROOM.z, ROOM.y);
    let pane_quad = quad([
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, d, 0.0),
        DVec3::new(1.0, d, h),
        DVec3::new(1.0, 0.0, h),
    ]);
    scene_of(
        vec![
            SceneMesh::from_triangles("walls", &walls, 0),
            SceneMesh::from_triangles("mirror", &mirror, 1),
            SceneMesh::from_triangles("pane", &pane_quad, 2),
        ],
        vec![material(0.5, 100.0), specular(0.0, 100.0, 0.5, 0.0), pane],
    )
}

#[test]
fn the_specular_furnace_keeps_the_uniform_field() {
    let scene = specular_furnace(specular(0.0, 0.0, 0.4, 0.6));
    let r = RadiosityScene::new(&scene, 4.0, 1).unwrap();
    assert_eq!(
        r.specular.windows.len(),
        4,
        "mirror, pane ±x reflections, pane"
    );
    let mut solver = CpuSolver::new(&r, settings());
    solver.solve(0.9995, 5000);
    let el = &r.elements;
    let pane = |e: usize| (el.position[e].x - 1.0).abs() < 1e-9;
    // Every surface but the pane receives E / (1 − ρ) = 200 lux; the walls reflect half.
    let (mut received, mut area, mut worst) = (0.0, 0.0, 0.0f64);
    for e in (0..el.len()).filter(|&e| !pane(e)) {
        received += solver.illuminance[e] * el.area[e];
        area += el.area[e];
        worst = worst.max((solver.illuminance[e] / 200.0 - 1.0).abs());
    }
    let mean = received / area / 200.0 - 1.0;
    eprintln!(
        "specular furnace: {} shots, convergence {:.5}, mean {:+.3} %, worst {:.3} %",
        solver.shots,
        solver.convergence(),
        100.0 * mean,
        100.0 * worst
    );
    // What is still unshot has not arrived anywhere yet.
    assert!(mean.abs() < 0.005, "energy off by {:.3} %", 100.0 * mean);
    assert!(worst < 0.01, "worst element off by {:.3} %", 100.0 * worst);

    // Without the specular transfer (the pane and mirror opaque black) it would be far off.
    let mut opaque = specular_furnace(material(0.0, 0.0));
    opaque.materials[1] = material(0.0, 100.0);
    let r = RadiosityScene::new(&opaque, 4.0, 1).unwrap();
    assert!(r.specular.is_empty());
    let mut solver = CpuSolver::new(&r, settings());
    solver.solve(0.9995, 5000);
    let el = &r.elements;
    let received: f64 = (0..el.len())
        .filter(|&e| (el.position[e].x - 1.0).abs() > 1e-9)
        .map(|e| solver.illuminance[e] * el.area[e])
        .sum();
    assert!(received / area / 200.0 < 0.9, "the check can fail");
}

/// The solution on the GPU (from the CPU's start: emission and the luminaires' shot)
/// shot until `converge` of the unshot power is gone: per element, radiosity and
/// illuminance.
fn gpu_solve(
    gpu: &Gpu,
    r: &RadiosityScene,
    raster: Raster,
    converge: f64,
) -> (Vec<DVec3>, Vec<f64>) {
    let initial = CpuSolver::new(r, settings()).state();
    let gpu_settings = GpuSettings {
        raster,
        ..GpuSettings::default()
    };
    let mut solver = GpuSolver::new(gpu, r, &initial, settings(), gpu_settings);
    assert_eq!(solver.raster(), raster, "never another rasterizer silently");
    let start = solver.select().unwrap().unshot_power;
    let mut remaining = start;
    while solver.stats.shots < 5000 && remaining > (1.0 - converge) * start {
        match solver.step().unwrap() {
            Some(s) => remaining = s.unshot_power,
            None => break,
        }
    }
    if !r.specular.is_empty() {
        assert!(
            solver.stats.virtual_drawn > 0,
            "virtual cells drew their maps"
        );
    }
    solver.radiosity_and_illuminance().unwrap()
}

#[test]
fn the_gpus_virtual_cells_keep_the_specular_furnace_uniform() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let scene = specular_furnace(specular(0.0, 0.0, 0.4, 0.6));
    let r = RadiosityScene::new(&scene, 4.0, 1).unwrap();
    let el = &r.elements;
    // (The compute rasterizer's clip plane is checked with the screened mirror.)
    for raster in [Raster::Hardware] {
        let (_, lux) = gpu_solve(&gpu, &r, raster, 0.9995);
        let (mut received, mut area, mut worst, mut off) = (0.0, 0.0, 0.0f64, 0);
        let walls: Vec<usize> = (0..el.len())
            .filter(|&e| (el.position[e].x - 1.0).abs() > 1e-9)
            .collect();
        for &e in &walls {
            received += lux[e] * el.area[e];
            area += el.area[e];
            let error = (lux[e] / 200.0 - 1.0).abs();
            worst = worst.max(error);
            if error > 0.03 {
                off += 1;
            }
        }
        let mean = received / area / 200.0 - 1.0;
        eprintln!(
            "GPU specular furnace ({raster:?}): mean {:+.3} %, worst {:.3} %, {off} of {} \
             elements off by more than 3 %",
            100.0 * mean,
            100.0 * worst,
            walls.len()
        );
        assert!(
            mean.abs() < 0.005,
            "{raster:?}: energy off by {:.3} %",
            100.0 * mean
        );
        // Slivers of elements a centimetre from the pane take light through it: the
        // maps' depth tolerance, as behind any thin wall on the GPU (10.6 % over; 36 %
        // with Wallner's nine-texel lookup).
        assert!(
            off * 100 <= walls.len() && worst < 0.2,
            "{raster:?}: {off} elements off by more than 3 %, worst {:.2} %",
            100.0 * worst
        );
    }
}

/// The mirror scene of [`a_mirror_gives_what_the_shooters_image_gives_times_its_reflectance`]
/// with a screen (material 0) at x = 1.2 over y < 0.5, high enough to miss the light from
/// the mirror to the floor but in the way of the light from the emitter to the mirror:
/// the first leg, which the GPU checks in the real cell's map, blocked for some paths.
fn screened_mirror() -> Scene {
    let screen = quad([
        DVec3::new(1.2, -1.0, 0.55),
        DVec3::new(1.2, -1.0, 1.2),
        DVec3::new(1.2, 0.5, 1.2),
        DVec3::new(1.2, 0.5, 0.55),
    ]);
    let mut s = mirror_scene(&[
        MirrorPart::Floor,
        MirrorPart::Emitter(0.0),
        MirrorPart::Mirror,
    ]);
    s.meshes
        .push(SceneMesh::from_triangles("screen", &screen, 0));
    s
}

/// The parts of the mirror scenes: an emitting 1 × 1 m quad at z = 1 facing down over
/// x = x0..x0 + 1 (material 1, 1 000 lm/m²), a black floor beside it (x = −1..0, material
/// 0) and a mirror wall at x = 2 facing −x (material 2, ρ_s 0.7).
enum MirrorPart {
    Floor,
    Emitter(f64),
    Mirror,
}

fn mirror_scene(parts: &[MirrorPart]) -> Scene {
    let meshes = parts
        .iter()
        .map(|part| match *part {
            MirrorPart::Floor => SceneMesh::from_triangles(
                "floor",
                &quad([
                    DVec3::new(-1.0, 0.0, 0.0),
                    DVec3::new(0.0, 0.0, 0.0),
                    DVec3::new(0.0, 1.0, 0.0),
                    DVec3::new(-1.0, 1.0, 0.0),
                ]),
                0,
            ),
            MirrorPart::Emitter(x0) => SceneMesh::from_triangles(
                "emitter",
                &quad([
                    DVec3::new(x0, 0.0, 1.0),
                    DVec3::new(x0, 1.0, 1.0),
                    DVec3::new(x0 + 1.0, 1.0, 1.0),
                    DVec3::new(x0 + 1.0, 0.0, 1.0),
                ]),
                1,
            ),
            MirrorPart::Mirror => SceneMesh::from_triangles(
                "mirror",
                &quad([
                    DVec3::new(2.0, -2.0, -1.0),
                    DVec3::new(2.0, -2.0, 3.0),
                    DVec3::new(2.0, 3.0, 3.0),
                    DVec3::new(2.0, 3.0, -1.0),
                ]),
                2,
            ),
        })
        .collect();
    scene_of(
        meshes,
        vec![
            material(0.0, 0.0),
            material(0.0, 1000.0),
            specular(0.0, 0.0, 0.7, 0.0),
        ],
    )
}

#[test]
fn the_gpus_virtual_cells_match_the_cpu_with_a_screen_before_the_mirror() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let screened = screened_mirror();
    let mut plain = screened.clone();
    plain.materials[2] = material(0.0, 0.0);
    let (r, r_plain) = (
        RadiosityScene::new(&screened, 8.0, 1).unwrap(),
        RadiosityScene::new(&plain, 8.0, 1).unwrap(),
    );
    let cpu_lux = |r: &RadiosityScene| {
        let mut cpu = CpuSolver::new(r, settings());
        cpu.solve(1.0, 100);
        cpu.illuminance
    };
    // What the mirror adds on the floor.
    let added = |a: &[f64], b: &[f64]| -> Vec<f64> {
        let el = &r.elements;
        (0..el.len())
            .filter(|&e| el.position[e].z.abs() < 1e-9)
            .map(|e| a[e] - b[e])
            .collect()
    };
    let cpu = added(&cpu_lux(&r), &cpu_lux(&r_plain));
    // The screen shades part of the reflected light: the case is not trivial.
    let (lo, hi) = cpu
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    assert!(hi > 3.0 * lo, "the mirror adds {lo} to {hi} lux");
    for raster in [Raster::Hardware, Raster::Compute] {
        let gpu_added = added(
            &gpu_solve(&gpu, &r, raster, 1.0).1,
            &gpu_solve(&gpu, &r_plain, raster, 1.0).1,
        );
        let within = gpu_added
            .iter()
            .zip(&cpu)
            .filter(|(g, c)| (*g / *c - 1.0).abs() < 0.1)
            .count();
        let worst = gpu_added
            .iter()
            .zip(&cpu)
            .map(|(g, c)| (g / c - 1.0).abs())
            .fold(0.0, f64::max);
        let share = within as f64 / cpu.len() as f64;
        let sum = gpu_added.iter().sum::<f64>() / cpu.iter().sum::<f64>() - 1.0;
        eprintln!(
            "screened mirror ({raster:?}): the mirror adds {lo:.1}..{hi:.1} lux; on {:.1} % of \
             {} floor elements the GPU's addition is within 10 % of the CPU's (worst {:.1} %), \
             in all {:+.2} %",
            100.0 * share,
            cpu.len(),
            100.0 * worst,
            100.0 * sum
        );
        // Wallner's nine-texel lookup let more past the screen's edge (+1.75 %, 89.7 %
        // within 10 %); one texel: +0.14 %, 98.7 %.
        assert!(
            sum.abs() < 0.01,
            "{raster:?}: {:.2} % off in all",
            100.0 * sum
        );
        assert!(
            share > 0.95,
            "{raster:?}: {:.1} % within 10 %",
            100.0 * share
        );
        assert!(worst < 0.2, "{raster:?}: worst {:.1} %", 100.0 * worst);
    }
}

fn placed_luminaire(at: DVec3) -> PlacedLuminaire {
    let path = common::luminaire("eulumdat-analysis/sample_18.ldt");
    let l = Luminaire::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    PlacedLuminaire::new("downlight", l, at)
}

/// A 6 × 6 m floor at z = 0 with a pane (material 1) standing across it at x = 0.
fn glass_scene(pane: Material) -> Scene {
    let floor = quad([
        DVec3::new(-3.0, -3.0, 0.0),
        DVec3::new(3.0, -3.0, 0.0),
        DVec3::new(3.0, 3.0, 0.0),
        DVec3::new(-3.0, 3.0, 0.0),
    ]);
    let pane_quad = quad([
        DVec3::new(0.0, -1.0, 0.5),
        DVec3::new(0.0, 1.0, 0.5),
        DVec3::new(0.0, 1.0, 2.5),
        DVec3::new(0.0, -1.0, 2.5),
    ]);
    let mut s = scene_of(
        vec![
            SceneMesh::from_triangles("floor", &floor, 0),
            SceneMesh::from_triangles("pane", &pane_quad, 1),
        ],
        vec![material(0.3, 0.0), pane],
    );
    s.luminaires = vec![placed_luminaire(DVec3::new(-1.0, 0.0, 2.0))];
    s
}

#[test]
fn a_pane_passes_its_transmittance_of_a_luminaires_light() {
    let glass = RadiosityScene::new(&glass_scene(specular(0.0, 0.0, 0.0, 0.85)), 2.0, 0).unwrap();
    let mut open = glass_scene(material(0.0, 0.0));
    open.meshes.truncate(1);
    let open = RadiosityScene::new(&open, 2.0, 0).unwrap();
    let (g, o) = (
        CpuSolver::new(&glass, settings()),
        CpuSolver::new(&open, settings()),
    );
    let (mut through, mut beside) = (0, 0);
    for k in 0..40 {
        let p = DVec3::new(0.05 + 0.07 * k as f64, -2.0 + 0.1 * k as f64, 0.0);
        let (eg, eo) = (g.direct(p, DVec3::Z), o.direct(p, DVec3::Z));
        assert!(eo.x > 0.0, "lit without the pane at {p}");
        // The straight line from the luminaire crosses the pane's plane at x = 0.
        let l = DVec3::new(-1.0, 0.0, 2.0);
        let cross = l + (p - l) * (1.0 / (p.x + 1.0));
        let inside = cross.y.abs() < 1.0 && cross.z > 0.5 && cross.z < 2.5;
        let expected = if inside { 0.85 } else { 1.0 };
        let ratio = eg.x / eo.x;
        assert!(
            (ratio - expected).abs() < 1e-5,
            "at {p} (crossing {cross}): {ratio} instead of {expected}"
        );
        if inside {
            through += 1;
        } else {
            beside += 1;
        }
    }
    assert!(
        through > 10 && beside > 5,
        "{through} through, {beside} beside"
    );
}

#[test]
fn a_mirror_gives_what_the_shooters_image_gives_times_its_reflectance() {
    // What the mirror adds on the floor must be ρ_s times what the emitter's image
    // (x = 3..4), built as real geometry in a scene without the mirror, gives it.
    use MirrorPart::{Emitter, Floor, Mirror};
    let with_mirror = mirror_scene(&[Floor, Emitter(0.0), Mirror]);
    let plain = mirror_scene(&[Floor, Emitter(0.0)]);
    let imaged = mirror_scene(&[Floor, Emitter(3.0)]);
    // Only the emitter has anything to shoot: one solve shoots it whole.
    let on_floor = |s: &Scene| {
        let r = RadiosityScene::new(s, 4.0, 1).unwrap();
        assert_eq!(r.specular.windows.len(), usize::from(s.meshes.len() == 3));
        let mut solver = CpuSolver::new(&r, settings());
        solver.solve(1.0, 100);
        assert_eq!(solver.convergence(), 1.0);
        let el = &r.elements;
        (0..el.len())
            .filter(|&e| el.position[e].z.abs() < 1e-9)
            .map(|e| (el.position[e], solver.illuminance[e]))
            .collect::<Vec<_>>()
    };
    let (m, p, i) = (on_floor(&with_mirror), on_floor(&plain), on_floor(&imaged));
    assert!(m.len() >= 16 && m.len() == p.len() && p.len() == i.len());
    for ((m, p), i) in m.iter().zip(&p).zip(&i) {
        assert!((m.0 - i.0).length() < 1e-9 && (m.0 - p.0).length() < 1e-9);
        assert!(i.1 > 0.1, "the image lights the floor at {}", i.0);
        let ratio = (m.1 - p.1) / i.1;
        assert!(
            (ratio - 0.7).abs() < 1e-6,
            "at {}: {ratio} instead of 0.7",
            m.0
        );
    }
}

#[test]
fn a_luminaire_over_a_mirror_floor_lights_the_ceiling_by_its_image() {
    let floor = quad([
        DVec3::new(-5.0, -5.0, 0.0),
        DVec3::new(5.0, -5.0, 0.0),
        DVec3::new(5.0, 5.0, 0.0),
        DVec3::new(-5.0, 5.0, 0.0),
    ]);
    let mut s = scene_of(
        vec![SceneMesh::from_triangles("floor", &floor, 0)],
        vec![specular(0.0, 0.0, 0.8, 0.0)],
    );
    s.luminaires = vec![placed_luminaire(DVec3::new(0.0, 0.0, 2.0))];
    let r = RadiosityScene::new(&s, 1.0, 0).unwrap();
    let solver = CpuSolver::new(&r, settings());
    let l = &r.luminaires[0];
    // A point at (1, 0, 1) facing down sees nothing straight (the luminaire is above it);
    // reflected, the light leaves toward (2/3, 0, 0) where the angle of incidence equals
    // the angle of reflection, and travels √10 m in all.
    let p = DVec3::new(1.0, 0.0, 1.0);
    let m = DVec3::new(2.0 / 3.0, 0.0, 0.0);
    let out = (m - l.position).normalize();
    let length = (m - l.position).length() + (p - m).length();
    assert!((length - 10f64.sqrt()).abs() < 1e-12);
    let cos = (m - p).normalize().dot(-DVec3::Z);
    let expected = 0.8 * l.intensity_toward(out, Interp::CatmullRom) * cos / (length * length);
    let got = solver.direct(p, -DVec3::Z);
    assert!(expected > 1.0);
    assert!(
        (got.x - expected).abs() < 1e-5 * expected,
        "{} lux instead of {expected}",
        got.x
    );
    // Beyond the mirror's edge there is no reflection.
    assert_eq!(
        solver.direct(DVec3::new(12.0, 0.0, 1.0), -DVec3::Z),
        DVec3::ZERO
    );
}

/// The commands with the bundled mirror room: the rendered image says what it leaves out,
/// a direct-light illuminance image is refused, and so is a view-driven solve.
#[test]
fn commands_say_what_they_do_with_mirrors() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::root().join("assets/scenes/mirror_room.toml");
    let scene = scene.to_str().unwrap();
    let png = dir.path().join("room.png");
    let png = png.to_str().unwrap();
    let small = ["--width", "64", "--height", "48"];
    let mut shaded = vec!["render", scene, "--out", png, "--mode", "shaded"];
    shaded.extend(small);
    let (code, _, stderr) = common::run_cli(&shaded, "");
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("\"mirror\" is a mirror or clear glass") && stderr.contains("diffuse part"),
        "{stderr}"
    );
    std::fs::remove_file(png).unwrap();
    let mut lux = vec!["render", scene, "--out", png, "--mode", "illuminance"];
    lux.extend(small);
    let (code, _, stderr) = common::run_cli(&lux, "");
    assert_ne!(code, 0);
    assert!(
        stderr.contains("would leave out the light it passes on"),
        "{stderr}"
    );
    assert!(!std::path::Path::new(png).exists(), "no image written");
    let (code, _, stderr) = common::run_cli(
        &[
            "radiosity",
            scene,
            "--drive",
            "perspective",
            "--max-shots",
            "2",
            "--out-dir",
        ]
        .into_iter()
        .chain([dir.path().join("out").to_str().unwrap()])
        .collect::<Vec<_>>(),
        "",
    );
    assert_ne!(code, 0);
    assert!(stderr.contains("does not handle mirrors"), "{stderr}");
}
