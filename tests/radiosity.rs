//! The radiosity solver against exact cases: Howell's form factors, the furnace (a closed
//! box with uniform exitance E and reflectance ρ converges to B = E / (1 − ρ)), energy
//! conservation, and the GPU against the CPU reference.

use std::path::PathBuf;

use glam::{DVec3, Vec3};
use goniolight::radiosity::cpu::CpuSolver;
use goniolight::radiosity::form_factor::{self, howell};
use goniolight::radiosity::scene::RadiosityScene;
use goniolight::radiosity::{Ambient, FormFactorKind, SolverSettings};
use goniolight::scene::{Camera, DisplayEntry, Material, Scene, SceneMesh};

/// The six faces of the box [lo, hi], facing inward.
fn inward_box(lo: DVec3, hi: DVec3) -> Vec<[Vec3; 3]> {
    let m = goniolight::geometry::generate::cuboid(lo, hi);
    m.triangles
        .iter()
        .map(|t| [t[0], t[2], t[1]].map(|i| m.positions[i as usize].as_vec3()))
        .collect()
}

fn material(reflectance: f32, emission: f32) -> Material {
    Material {
        diffuse: Vec3::splat(reflectance),
        emission: Vec3::splat(emission),
        ..Material::default()
    }
}

fn scene_of(meshes: Vec<SceneMesh>, materials: Vec<Material>) -> Scene {
    Scene {
        path: PathBuf::from("radiosity test"),
        meshes,
        materials,
        luminaires: Vec::new(),
        camera: Camera::perspective(DVec3::new(0.5, 0.5, 0.5), DVec3::ZERO, 60.0),
        display: DisplayEntry::default(),
    }
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
        if el.triangle[i] as usize >= half {
            continue;
        }
        area += el.area[i];
        for te in &el.triangles[half..] {
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
    let te = r.elements.triangles[t].clone();
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
