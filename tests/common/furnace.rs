//! The furnace: a closed box whose walls all emit E and reflect ρ, so B = E / (1 − ρ)
//! everywhere once solved.
#![allow(dead_code)]

use glam::{DVec3, Vec3};
use goniolight::scene::{Material, Scene, SceneMesh};

/// A closed 2 × 1.5 × 1 m box of one material (ρ = `rho`, exitance `e` lm/m²) facing
/// inwards, every face two triangles, with the bundled box room's settings otherwise.
pub fn closed_box(rho: f32, e: f32) -> Scene {
    let inward = inward_box(DVec3::ZERO, DVec3::new(2.0, 1.5, 1.0));
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/box_room.toml");
    Scene {
        meshes: vec![SceneMesh::from_triangles("box", &inward, 0)],
        materials: vec![Material {
            diffuse: Vec3::splat(rho),
            emission: Vec3::splat(e),
            ..Material::default()
        }],
        luminaires: Vec::new(),
        models: Vec::new(),
        grids: Vec::new(),
        calc: Default::default(),
        ..Scene::load(&path).unwrap()
    }
}

/// The faces of the box from `lo` to `hi` facing inwards, two triangles each.
pub fn inward_box(lo: DVec3, hi: DVec3) -> Vec<[Vec3; 3]> {
    let walls = goniolight::geometry::generate::cuboid(lo, hi);
    walls
        .triangles
        .iter()
        .map(|t| [t[0], t[2], t[1]].map(|i| walls.positions[i as usize].as_vec3()))
        .collect()
}
