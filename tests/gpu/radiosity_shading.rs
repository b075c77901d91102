//! Surface detail in radiosity (Wallner §2.3.3): elements receive with the mesh's
//! interpolated vertex normals perturbed by its normal map, and reflect their diffuse
//! texture's mean colour.

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};
use goniolight::photometry::{Interp, Luminaire};
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::form_factor;
use goniolight::radiosity::gpu::{GpuSettings, GpuSolver};
use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::SolverSettings;
use goniolight::render::{ShadowSettings, ShadowTechnique};
use goniolight::scene::palette::srgb_to_linear;
use goniolight::scene::placement::aim_frame;
use goniolight::scene::{PlacedLuminaire, Scene, SceneMesh};

use crate::common;
use crate::gpu_common;
use crate::radiosity_scenes_common as radiosity_scenes;

use radiosity_scenes::{floor, material, scene_of, tilted};

const RADIUS: f32 = 1.0;
const FACETS: u32 = 12;

/// The side of a cylinder about the Z axis (radius 1 m, 0–2 m high, facing out) as
/// `FACETS` flat quads; `smooth`: its vertices carry the radial normals.
fn cylinder(smooth: bool) -> SceneMesh {
    let mut m = SceneMesh {
        name: "cylinder".into(),
        material: 0,
        ..Default::default()
    };
    for k in 0..FACETS {
        let angle = |k: u32| std::f32::consts::TAU * k as f32 / FACETS as f32;
        let (a, b) = (angle(k), angle(k + 1));
        let radial = |t: f32| Vec3::new(t.cos(), t.sin(), 0.0);
        let face = radial(0.5 * (a + b));
        let base = m.positions.len() as u32;
        for (t, z) in [(a, 0.0), (b, 0.0), (b, 2.0), (a, 2.0)] {
            m.positions.push(radial(t) * RADIUS + Vec3::Z * z);
            m.normals.push(if smooth { radial(t) } else { face });
            m.uvs.push(Vec2::ZERO);
        }
        m.indices.extend([0, 1, 2, 0, 2, 3].map(|i: u32| base + i));
    }
    m
}

/// A 0.2 m square at x = 3 m, 1 m up, facing the cylinder; exitance 1000 lm/m².
fn emitter() -> SceneMesh {
    let c = [(-0.1, 0.9), (-0.1, 1.1), (0.1, 1.1), (0.1, 0.9)].map(|(y, z)| Vec3::new(3.0, y, z));
    SceneMesh::from_triangles("emitter", &[[c[0], c[1], c[2]], [c[0], c[2], c[3]]], 1)
}

fn lit_cylinder(smooth: bool) -> Scene {
    scene_of(
        vec![cylinder(smooth), emitter()],
        vec![material(0.5, 0.0), material(0.0, 1000.0)],
    )
}

/// The charts that emit (material 1).
fn emitters(r: &RadiosityScene) -> Vec<usize> {
    (0..r.elements.charts.len())
        .filter(|&t| r.elements.charts[t].material == 1)
        .collect()
}

/// The elements that receive (material 0).
fn receivers(r: &RadiosityScene) -> Vec<usize> {
    (0..r.elements.len())
        .filter(|&e| r.elements.charts[r.elements.chart[e] as usize].material == 0)
        .collect()
}

/// The CPU solver after every emitter has shot once.
fn emitters_shot(r: &RadiosityScene) -> CpuSolver<'_> {
    let mut cpu = CpuSolver::new(r, SolverSettings::default());
    for t in emitters(r) {
        cpu.shoot(t, DVec3::ZERO);
    }
    cpu
}

/// Per element of the cylinder whose facet faces the emitter: (irradiance from the
/// emitter's shots, what the true cylinder receives there: the same form factor with the
/// radial normal). The elements of facets turned away receive nothing (light never comes
/// through a surface's back, whatever its shading normal says).
fn shot_against_the_round_surface(r: &RadiosityScene) -> Vec<(f64, f64)> {
    let cpu = emitters_shot(r);
    let poly: Vec<DVec3> = [(-0.1, 0.9), (-0.1, 1.1), (0.1, 1.1), (0.1, 0.9)]
        .map(|(y, z)| DVec3::new(3.0, y, z))
        .to_vec();
    let centre = DVec3::new(3.0, 0.0, 1.0);
    let (facing, away): (Vec<usize>, Vec<usize>) = receivers(r)
        .into_iter()
        .partition(|&e| r.elements.normal(e).dot(centre - r.elements.position[e]) > 0.0);
    assert!(away.iter().all(|&e| cpu.radiosity[e] == DVec3::ZERO));
    facing
        .into_iter()
        .map(|e| {
            let p = r.elements.position[e];
            let radial = DVec3::new(p.x, p.y, 0.0).normalize();
            let want = 1000.0 * form_factor::polygon(p, radial, &poly, -DVec3::X);
            (cpu.radiosity[e].x / 0.5, want)
        })
        .collect()
}

#[test]
fn smooth_vertex_normals_receive_as_the_round_surface_does_and_facets_do_not() {
    let smooth = RadiosityScene::new(&lit_cylinder(true), 8.0, 0).unwrap();
    let faceted = RadiosityScene::new(&lit_cylinder(false), 8.0, 0).unwrap();
    // Faceted: every element keeps its chart's normal (nothing stored).
    assert!(faceted.receiving_normals.is_empty());
    // Smooth: a full element's receiving normal is the radial direction through its
    // centre (normalised linear interpolation along a chord is exactly that).
    let el = &smooth.elements;
    let texel = 1.0 / 8.0;
    let mut checked = 0;
    for e in 0..el.len() {
        let p = el.position[e];
        if el.area[e] < 0.999 * texel * texel || p.x > 2.0 {
            continue;
        }
        let radial = DVec3::new(p.x, p.y, 0.0).normalize();
        let n = smooth.element_receiving_normal(e);
        assert!((n - radial).length() < 1e-6, "{e}: {n} vs {radial}");
        checked += 1;
    }
    assert!(checked > 300, "{checked}");

    let worst = |pairs: &[(f64, f64)]| {
        let peak = pairs.iter().map(|p| p.1).fold(0.0, f64::max);
        let worst = pairs
            .iter()
            .map(|(have, want)| (have - want).abs())
            .fold(0.0, f64::max);
        (worst / peak, peak)
    };
    let (smooth_error, peak) = worst(&shot_against_the_round_surface(&smooth));
    let (faceted_error, _) = worst(&shot_against_the_round_surface(&faceted));
    eprintln!(
        "peak {peak:.2} lux; worst error smooth {:.2} %, faceted {:.2} %",
        100.0 * smooth_error,
        100.0 * faceted_error
    );
    assert!(peak > 1.0, "{peak}");
    assert!(smooth_error < 0.03, "{smooth_error}");
    assert!(faceted_error > 0.1, "{faceted_error}");
}

#[test]
fn nothing_arrives_through_the_back_of_a_surface_whose_normals_lean_over() {
    // A floor whose vertex normals lean 50–70° toward +x, lit by an emitter below it:
    // the shading normals face the emitter, the surface does not.
    let lean = |deg: f32| Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
    let floor = SceneMesh {
        normals: vec![lean(50.0), lean(70.0), lean(70.0), lean(50.0)],
        ..floor(Vec3::Z, 1.0, 1.0)
    };
    let c = [(2.0, 0.0), (2.0, 1.0), (3.0, 1.0), (3.0, 0.0)].map(|(x, y)| Vec3::new(x, y, 0.5));
    // Facing up and toward the floor's side: in front of the shading normals only.
    let below = SceneMesh::from_triangles("below", &[[c[0], c[2], c[1]], [c[0], c[3], c[2]]], 1);
    let scene = scene_of(
        vec![floor, below],
        vec![material(0.5, 0.0), material(0.0, 1000.0)],
    );
    let mut scene = scene;
    // A luminaire there too, aimed up at the floor's side.
    let ldt = Luminaire::load(&common::luminaire("eulumdat-luminance/sample_07.ldt")).unwrap();
    let mut lamp = PlacedLuminaire::new("below", ldt, DVec3::new(2.5, 0.5, 0.6));
    lamp.rotation = aim_frame(Some(DVec3::new(-1.0, 0.0, 0.3)), 0.0);
    scene.luminaires.push(lamp);
    let r = RadiosityScene::new(&scene, 8.0, 0).unwrap();
    assert!(!r.receiving_normals.is_empty());
    let cpu = emitters_shot(&r);
    let floor = receivers(&r);
    assert!(floor.len() > 50);
    for &e in &floor {
        assert_eq!(cpu.radiosity[e], DVec3::ZERO, "element {e}");
        assert_eq!(cpu.illuminance[e], 0.0, "element {e}");
    }
    // The luminaire would light the floor through its back with its shading normals: it
    // does light the elements with them where it is in front (their own check).
    let lamp = &scene.luminaires[0];
    let e = floor[0];
    assert!(
        lamp.illuminance_at(
            r.elements.position[e],
            r.element_receiving_normal(e).normalize(),
            Interp::CatmullRom
        ) > 1.0
    );
    let Some(gpu) = gpu_common::gpu() else { return };
    let light = LuminaireLight::new(&gpu, &scene, Interp::CatmullRom);
    let shadows = ShadowSettings::with(ShadowTechnique::Paraboloid);
    let start = InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap();
    let settings = SolverSettings::default();
    let mut solver = GpuSolver::new(&gpu, &r, &start, settings, GpuSettings::default());
    for t in emitters(&r) {
        solver.shoot(t).unwrap();
    }
    let got = solver.radiosity().unwrap();
    for &e in &floor {
        assert_eq!(start.illuminance[e], 0.0, "element {e}");
        assert_eq!(got[e], DVec3::ZERO, "element {e}");
    }
}

#[test]
fn the_gpu_receives_with_the_receiving_normals_as_the_cpu_does() {
    let Some(gpu) = gpu_common::gpu() else { return };
    let r = RadiosityScene::new(&lit_cylinder(true), 8.0, 0).unwrap();
    let settings = SolverSettings::default();
    let cpu = emitters_shot(&r);
    let start = CpuSolver::new(&r, settings).state();
    let mut solver = GpuSolver::new(&gpu, &r, &start, settings, GpuSettings::default());
    for t in emitters(&r) {
        solver.shoot(t).unwrap();
    }
    let got = solver.radiosity().unwrap();
    let want = &cpu.radiosity;
    let receivers = receivers(&r);
    let peak = receivers.iter().map(|&e| want[e].x).fold(0.0, f64::max);
    let close = receivers
        .iter()
        .filter(|&&e| (got[e].x - want[e].x).abs() <= 0.01 * want[e].x.max(0.05 * peak))
        .count();
    let power =
        |b: &[DVec3]| -> f64 { receivers.iter().map(|&e| b[e].x * r.elements.area[e]).sum() };
    let ratio = power(&got) / power(want);
    eprintln!(
        "GPU/CPU power {ratio:.4}; {close} of {} within 1 %",
        receivers.len()
    );
    assert!((ratio - 1.0).abs() < 0.01, "{ratio}");
    assert!(close as f64 >= 0.95 * receivers.len() as f64, "{close}");
    // The faceted cylinder's solution differs by far more: the GPU did use the normals.
    let flat = RadiosityScene::new(&lit_cylinder(false), 8.0, 0).unwrap();
    let flat_cpu = emitters_shot(&flat);
    let differ = receivers
        .iter()
        .filter(|&&e| (got[e].x - flat_cpu.radiosity[e].x).abs() > 0.05 * peak)
        .count();
    assert!(differ > receivers.len() / 20, "{differ}");
}

fn floor_with_normal_map(img: image::RgbaImage, repeat: f32) -> RadiosityScene {
    let mut m = material(0.5, 0.0);
    m.normal_map = Some(Arc::new(img));
    RadiosityScene::new(
        &scene_of(vec![floor(Vec3::ZERO, 2.0, repeat)], vec![m]),
        4.0,
        0,
    )
    .unwrap()
}

#[test]
fn a_normal_map_tilts_the_receiving_normal_and_fine_relief_shortens_it() {
    // A uniform 30° tilt toward +u (+x here): every element receives tilted.
    let r = floor_with_normal_map(image::RgbaImage::from_pixel(4, 4, tilted(30.0)), 1.0);
    let want = DVec3::new(0.5, 0.0, 0.75f64.sqrt());
    for e in 0..r.elements.len() {
        let n = r.element_receiving_normal(e);
        assert!((n - want).length() < 0.01, "{e}: {n}");
    }
    // Stripes of ±30°, 2 cm wide under 25 cm elements: each element takes their mean,
    // straight up and cos 30° long.
    let stripes = image::RgbaImage::from_fn(2, 2, |x, _| tilted(if x == 0 { 30.0 } else { -30.0 }));
    let r = floor_with_normal_map(stripes, 50.0);
    for e in 0..r.elements.len() {
        let n = r.element_receiving_normal(e);
        assert!(
            (n - DVec3::new(0.0, 0.0, 0.75f64.sqrt())).length() < 0.01,
            "{e}: {n}"
        );
    }
}

#[test]
fn a_textured_surface_reflects_its_textures_mean_colour() {
    // Kd 0.8 with a texture of four sRGB texels: the reflectance is 0.8 × their mean in
    // linear light, per channel.
    let texels = [[255u8, 0, 128], [128, 64, 0], [0, 255, 255], [64, 128, 32]];
    let img = image::RgbaImage::from_fn(2, 2, |x, y| {
        let t = texels[(2 * y + x) as usize];
        image::Rgba([t[0], t[1], t[2], 255])
    });
    let mut m = material(0.8, 0.0);
    m.diffuse_map = Some(Arc::new(img));
    let r = RadiosityScene::new(
        &scene_of(vec![floor(Vec3::ZERO, 2.0, 1.0)], vec![m]),
        4.0,
        0,
    )
    .unwrap();
    for (ch, got) in r.reflectance[0].to_array().iter().enumerate() {
        let mean: f64 = texels
            .iter()
            .map(|t| srgb_to_linear(t[ch]) as f64)
            .sum::<f64>()
            / 4.0;
        assert!((got - 0.8 * mean).abs() < 1e-6, "channel {ch}: {got}");
    }
    // Without a texture: Kd alone.
    let r = RadiosityScene::new(
        &scene_of(vec![floor(Vec3::ZERO, 2.0, 1.0)], vec![material(0.8, 0.0)]),
        4.0,
        0,
    )
    .unwrap();
    assert!((r.reflectance[0] - DVec3::splat(0.8)).length() < 1e-6);
}

#[test]
fn a_luminaires_direct_light_on_a_smooth_cylinder_follows_the_round_surface() {
    // A luminaire 2 m from the cylinder's axis, aimed at it: on the CPU (ray cast) and on
    // the GPU (the renderer's probe), the elements facing it receive what the round
    // surface does (its own illuminance function with the radial normal).
    let mut scene = scene_of(vec![cylinder(true)], vec![material(0.5, 0.0)]);
    let ldt = Luminaire::load(&common::luminaire("eulumdat-luminance/sample_07.ldt")).unwrap();
    let mut lamp = PlacedLuminaire::new("side", ldt, DVec3::new(2.5, 0.3, 1.2));
    lamp.rotation = aim_frame(Some(DVec3::new(-1.0, -0.1, -0.1)), 0.0);
    scene.luminaires.push(lamp);
    let r = RadiosityScene::new(&scene, 8.0, 0).unwrap();
    let lamp = &scene.luminaires[0];
    let facing: Vec<usize> = (0..r.elements.len())
        .filter(|&e| {
            let p = r.elements.position[e];
            r.elements.normal(e).dot(lamp.position - p) > 0.0
        })
        .collect();
    let want: Vec<f64> = facing
        .iter()
        .map(|&e| {
            let p = r.elements.position[e];
            let radial = DVec3::new(p.x, p.y, 0.0).normalize();
            lamp.illuminance_at(p, radial, Interp::CatmullRom)
        })
        .collect();
    let peak = want.iter().cloned().fold(0.0, f64::max);
    let worst = |have: &[f64]| {
        facing
            .iter()
            .zip(&want)
            .map(|(&e, w)| (have[e] - w).abs())
            .fold(0.0, f64::max)
            / peak
    };
    let cpu = CpuSolver::new(&r, SolverSettings::default());
    let cpu_error = worst(&cpu.illuminance);
    let mut faceted = scene_of(vec![cylinder(false)], vec![material(0.5, 0.0)]);
    faceted.luminaires = scene.luminaires.clone();
    let flat = RadiosityScene::new(&faceted, 8.0, 0).unwrap();
    let flat_error = worst(&CpuSolver::new(&flat, SolverSettings::default()).illuminance);
    eprintln!(
        "peak {peak:.1} lux; worst CPU error smooth {:.2} %, faceted {:.2} %",
        100.0 * cpu_error,
        100.0 * flat_error
    );
    assert!(peak > 10.0, "{peak}");
    assert!(cpu_error < 0.03, "{cpu_error}");
    assert!(flat_error > 0.1, "{flat_error}");
    let Some(gpu) = gpu_common::gpu() else { return };
    let light = LuminaireLight::new(&gpu, &scene, Interp::CatmullRom);
    let shadows = ShadowSettings::with(ShadowTechnique::Paraboloid);
    let start = InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap();
    let gpu_error = worst(&start.illuminance);
    eprintln!("worst GPU error {:.2} %", 100.0 * gpu_error);
    assert!(gpu_error < 0.03, "{gpu_error}");
}
