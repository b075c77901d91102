//! Scenes made in code for the radiosity tests.

use std::path::PathBuf;

use glam::{DVec3, Vec3};
use goniolight::scene::{Camera, DisplayEntry, Material, Scene, SceneMesh};

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
    Scene {
        path: PathBuf::from("radiosity test"),
        meshes,
        materials,
        luminaires: Vec::new(),
        camera: Camera::perspective(DVec3::new(0.5, 0.5, 0.5), DVec3::ZERO, 60.0),
        display: DisplayEntry::default(),
        models: Vec::new(),
        grids: Vec::new(),
        calc: Default::default(),
        observers: Vec::new(),
    }
}
