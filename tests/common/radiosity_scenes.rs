//! Scenes made in code for the radiosity tests.
#![allow(dead_code)]

use glam::{DVec3, Vec2, Vec3};
use goniolight::scene::{Camera, Material, Scene, SceneMesh};

/// A grey diffuse material of `reflectance` with luminous exitance `emission` (lm/m²).
pub fn material(reflectance: f32, emission: f32) -> Material {
    Material {
        diffuse: Vec3::splat(reflectance),
        emission: Vec3::splat(emission),
        ..Material::default()
    }
}

/// A scene of `meshes` and `materials` without luminaires, seen from (0.5, 0.5, 0.5).
pub fn scene_of(meshes: Vec<SceneMesh>, materials: Vec<Material>) -> Scene {
    Scene::in_code(
        "radiosity test",
        meshes,
        materials,
        Vec::new(),
        Camera::perspective(DVec3::new(0.5, 0.5, 0.5), DVec3::ZERO, 60.0),
    )
}

/// A square floor of `side` metres from `corner` (its lowest x and y) facing up, with
/// texture coordinates 0..`repeat` across it (u along x, v along y) and material 0.
pub fn floor(corner: Vec3, side: f32, repeat: f32) -> SceneMesh {
    let unit = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    SceneMesh {
        name: "floor".into(),
        positions: unit
            .map(|(x, y)| corner + Vec3::new(x, y, 0.0) * side)
            .to_vec(),
        normals: vec![Vec3::Z; 4],
        uvs: unit.map(|(u, v)| Vec2::new(u, v) * repeat).to_vec(),
        indices: vec![0, 1, 2, 0, 2, 3],
        material: 0,
    }
}

/// A tangent-space normal-map texel tilted `deg` from the surface normal toward the
/// tangent (+u).
pub fn tilted(deg: f64) -> image::Rgba<u8> {
    let n = DVec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
    let c = (n * 0.5 + DVec3::splat(0.5)) * 255.0;
    image::Rgba([c.x.round() as u8, c.y.round() as u8, c.z.round() as u8, 255])
}
