//! Adaptive subdivision at the luminaires' shadow boundaries (Wallner §2.4): at equal
//! element count, the light map along a box's shadow edge is closer to a fine uniform
//! solution than uniform elements get; the split elements still deliver the luminaire's
//! flux, on the CPU and the GPU.

use glam::{DVec2, DVec3, Vec3};
use goniolight::photometry::{Interp, Luminaire};
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::elements::Subdivision;
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::{solve, Hierarchy, SolverSettings};
use goniolight::render::lightmap::LightMap;
use goniolight::render::{ShadowSettings, ShadowTechnique};
use goniolight::scene::{PlacedLuminaire, Scene, SceneMesh};

use crate::common;
use crate::furnace_common as furnace;
use crate::gpu_common;
use crate::radiosity_scenes_common as radiosity_scenes;

use radiosity_scenes::{material, scene_of};

const ROOM: DVec3 = DVec3::new(3.0, 2.0, 2.0);
const BOX_LO: DVec3 = DVec3::new(1.0, 0.6, 0.0);
const BOX_HI: DVec3 = DVec3::new(1.8, 1.3, 0.9);

/// A closed 3 × 2 × 2 m room (ρ = 0.5) with a box on the floor, lit by one luminaire
/// under the ceiling beside the box: the box's shadow has hard edges on the floor.
fn room_with_box_and_luminaire() -> Scene {
    let walls = furnace::inward_box(DVec3::ZERO, ROOM);
    let cube = goniolight::geometry::generate::cuboid(BOX_LO, BOX_HI);
    let furniture: Vec<[Vec3; 3]> = cube
        .triangles
        .iter()
        .map(|t| t.map(|i| cube.positions[i as usize].as_vec3()))
        .collect();
    let mut scene = scene_of(
        vec![
            SceneMesh::from_triangles("walls", &walls, 0),
            SceneMesh::from_triangles("box", &furniture, 0),
        ],
        vec![material(0.5, 0.0)],
    );
    let ldt = Luminaire::load(&common::luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    scene
        .luminaires
        .push(PlacedLuminaire::new("lamp", ldt, DVec3::new(2.3, 1.5, 1.9)));
    scene
}

fn elements(scene: &Scene, density: f64, levels: u32) -> RadiosityScene {
    RadiosityScene::with_subdivision(
        scene,
        density,
        1,
        Hierarchy::Clusters,
        Subdivision::levels(levels),
    )
    .unwrap()
}

/// The light map of the luminaires' direct light (CPU ray-cast shadows: exact edges).
fn direct_light_map(r: &RadiosityScene) -> LightMap {
    let cpu = CpuSolver::new(r, SolverSettings::default());
    solve::light_map(r, &cpu.radiosity, &cpu.illuminance)
}

/// The light map's radiosity (green) at floor point `p`, sampled bilinearly as the GPU
/// does through the floor triangle under it.
fn floor_value(r: &RadiosityScene, map: &LightMap, p: DVec2) -> f64 {
    let el = &r.elements;
    for (t, te) in el.triangles.iter().enumerate() {
        if te.chart == u32::MAX || te.normal.z < 0.99 {
            continue;
        }
        let c = r.casters.triangles[t].map(|i| r.casters.positions[i as usize].truncate());
        let (a, b, d) = (c[0], c[1], c[2]);
        let det = (b - a).perp_dot(d - a);
        let v = (p - a).perp_dot(d - a) / det;
        let w = (b - a).perp_dot(p - a) / det;
        if v < -1e-9 || w < -1e-9 || v + w > 1.0 + 1e-9 {
            continue;
        }
        let uv = te.atlas_uv[0] * (1.0 - v - w) + te.atlas_uv[1] * v + te.atlas_uv[2] * w;
        let q = uv - DVec2::splat(0.5);
        let (x0, y0) = (q.x.floor(), q.y.floor());
        let (fx, fy) = (q.x - x0, q.y - y0);
        let at = |x: f64, y: f64| {
            let (x, y) = (
                (x as i64).clamp(0, map.width as i64 - 1),
                (y as i64).clamp(0, map.height as i64 - 1),
            );
            f64::from(map.texels[(y * map.width as i64 + x) as usize][1])
        };
        return (1.0 - fy) * ((1.0 - fx) * at(x0, y0) + fx * at(x0 + 1.0, y0))
            + fy * ((1.0 - fx) * at(x0, y0 + 1.0) + fx * at(x0 + 1.0, y0 + 1.0));
    }
    panic!("no floor triangle under {p}");
}

#[test]
fn adaptive_elements_halve_the_light_maps_error_along_a_shadow_edge() {
    let scene = room_with_box_and_luminaire();
    // Elements of 20 cm split twice (to 5 cm) at shadow edges; the reference: 2.5 cm.
    let adaptive = elements(&scene, 5.0, 2);
    let reference = elements(&scene, 40.0, 0);
    let split = adaptive.elements.span.iter().filter(|&&s| s < 4).count();
    assert!(split > 100, "only {split} elements were split");
    // Uniform elements at least as many as the adaptive ones.
    let uniform = (10..=80)
        .map(|k| elements(&scene, k as f64 * 0.25, 0))
        .find(|u| u.elements.len() >= adaptive.elements.len())
        .unwrap();
    let maps = [&adaptive, &uniform, &reference].map(direct_light_map);
    // The floor beside the box, away from the walls and 10 cm from the box (the contact
    // line is every light map's limit, not the cast shadow's edge), on a 2.5 cm grid; the
    // shadow edge:
    // where the reference changes by more than 20 % within 10 cm.
    let mut points = Vec::new();
    for i in 0..=100 {
        for j in 0..=64 {
            let p = DVec2::new(0.25 + i as f64 * 0.025, 0.2 + j as f64 * 0.025);
            let near_box = p.x > BOX_LO.x - 0.1
                && p.x < BOX_HI.x + 0.1
                && p.y > BOX_LO.y - 0.1
                && p.y < BOX_HI.y + 0.1;
            if !near_box {
                points.push(p);
            }
        }
    }
    let value = |k: usize, p: DVec2| floor_value([&adaptive, &uniform, &reference][k], &maps[k], p);
    let edge: Vec<DVec2> = points
        .iter()
        .copied()
        .filter(|&p| {
            let here = value(2, p);
            [DVec2::X, DVec2::Y, -DVec2::X, -DVec2::Y]
                .iter()
                .any(|d| (value(2, p + *d * 0.1) - here).abs() > 0.2 * here.max(1e-9))
        })
        .collect();
    assert!(edge.len() > 100, "{} points on the shadow edge", edge.len());
    let mean_ref = edge.iter().map(|&p| value(2, p)).sum::<f64>() / edge.len() as f64;
    let error = |k: usize| {
        edge.iter()
            .map(|&p| (value(k, p) - value(2, p)).abs())
            .sum::<f64>()
            / edge.len() as f64
            / mean_ref
    };
    let (e_adaptive, e_uniform) = (error(0), error(1));
    eprintln!(
        "shadow edge ({} points): adaptive {} elements, error {:.2} %; uniform {} elements, \
         error {:.2} %; reference {} elements",
        edge.len(),
        adaptive.elements.len(),
        100.0 * e_adaptive,
        uniform.elements.len(),
        100.0 * e_uniform,
        reference.elements.len()
    );
    assert!(
        e_adaptive <= 0.5 * e_uniform,
        "adaptive {e_adaptive} vs uniform {e_uniform}"
    );
    // Away from the edge the adaptive map is no worse than the uniform one by much: its
    // unsplit blocks are interpolated, not shown as flat squares.
    let calm: Vec<DVec2> = points
        .iter()
        .copied()
        .filter(|p| !edge.contains(p))
        .collect();
    let calm_error = |k: usize| {
        let off: f64 = calm
            .iter()
            .map(|&p| (value(k, p) - value(2, p)).abs())
            .sum();
        off / calm.iter().map(|&p| value(2, p)).sum::<f64>()
    };
    let (c_adaptive, c_uniform) = (calm_error(0), calm_error(1));
    eprintln!(
        "away from it ({} points): adaptive {:.2} %, uniform {:.2} %",
        calm.len(),
        100.0 * c_adaptive,
        100.0 * c_uniform
    );
    assert!(c_adaptive < 0.02, "{c_adaptive}");
}

#[test]
fn split_elements_deliver_the_luminaires_flux_on_the_cpu_and_the_gpu() {
    // Every lumen lands on a surface of the closed room: Σ E × A is the flux.
    let scene = room_with_box_and_luminaire();
    let r = elements(&scene, 5.0, 2);
    let flux = scene.luminaires[0].luminaire.summary().flux_lm;
    let cpu = CpuSolver::new(&r, SolverSettings::default());
    let delivered =
        |lux: &[f64]| -> f64 { lux.iter().zip(&r.elements.area).map(|(e, a)| e * a).sum() };
    let on_cpu = delivered(&cpu.illuminance);
    eprintln!("flux {flux:.1} lm: CPU delivers {on_cpu:.1} lm");
    assert!((on_cpu / flux - 1.0).abs() < 0.01, "{on_cpu} vs {flux}");
    let Some(gpu) = gpu_common::gpu() else { return };
    let light = LuminaireLight::new(&gpu, &scene, Interp::CatmullRom);
    let shadows = ShadowSettings::with(ShadowTechnique::Paraboloid);
    let start = InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap();
    let on_gpu = delivered(&start.illuminance);
    eprintln!("GPU delivers {on_gpu:.1} lm");
    assert!((on_gpu / flux - 1.0).abs() < 0.01, "{on_gpu} vs {flux}");
    // Element by element, the GPU's shot is the CPU's ray cast away from shadow edges.
    let peak = cpu.illuminance.iter().cloned().fold(0.0, f64::max);
    let agree = (0..r.elements.len())
        .filter(|&e| {
            let (want, have) = (cpu.illuminance[e], start.illuminance[e]);
            (have - want).abs() <= 0.01 * want.max(0.01 * peak)
        })
        .count();
    let share = agree as f64 / r.elements.len() as f64;
    eprintln!(
        "GPU within 1 % of the CPU on {:.2} % of the elements",
        100.0 * share
    );
    assert!(share > 0.9, "{share}");
}

#[test]
fn the_command_subdivides_on_request_and_refuses_bad_levels() {
    let scene = common::root().join("assets/scenes/boxes_room.toml");
    let scene = scene.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (flags, why) in [
        (&["--adaptive", "5"][..], "--adaptive 5 is not in 0..=4"),
        (
            &["--adaptive", "2", "--adaptive-share", "0.8,0.2"][..],
            "LOWER ≤ UPPER",
        ),
    ] {
        let mut args = vec!["radiosity", scene, "--max-shots", "1"];
        args.extend(flags);
        let (code, _, stderr) = common::run_cli(&args, "");
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains(why), "{stderr}");
    }
    if gpu_common::gpu().is_none() {
        return;
    }
    let out = dir.path().join("out");
    let (code, _, stderr) = common::run_cli(
        &[
            "radiosity",
            scene,
            "--adaptive",
            "2",
            "--texel-density",
            "4",
            "--max-shots",
            "2",
            "--out-dir",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    // "adaptive subdivision: N elements (T texels), split …: a of 4×4, b of 2×2, c of 1×1"
    let line = stderr
        .lines()
        .find(|l| l.starts_with("adaptive subdivision:"))
        .unwrap_or_else(|| panic!("{stderr}"));
    let counts: Vec<usize> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|w| w.parse().ok())
        .collect();
    // elements, texels, then (count, side, side) for sides 4, 2, 1.
    let (elements, by_side) = (counts[0], [counts[2], counts[5], counts[8]]);
    assert_eq!(by_side.iter().sum::<usize>(), elements, "{line}");
    assert!(by_side.iter().all(|&n| n > 0), "{line}");
    assert!(out.join("lightmap.exr").exists());
}
