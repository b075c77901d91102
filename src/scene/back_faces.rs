//! Back faces for translucent surfaces: each triangle of a material with a diffuse
//! transmittance gets a twin with the other winding, so its far side is a surface of its
//! own (radiosity's elements and shooters, and its light map in the solved display;
//! `radiosity/transmission.rs` has the model).

use std::borrow::Cow;

use super::{Scene, SceneMesh};

/// Whether a material with diffuse transmittance `t` (linear RGB) is translucent.
pub fn is_translucent(t: glam::Vec3) -> bool {
    t.max_element() > 0.0
}

/// Whether mesh `m` of `scene` has a translucent material.
fn is_translucent_mesh(scene: &Scene, m: &SceneMesh) -> bool {
    scene
        .materials
        .get(m.material)
        .is_some_and(|mat| is_translucent(mat.diffuse_transmittance))
}

/// Whether some surface of `scene` is translucent (its material has a diffuse
/// transmittance).
pub fn has_translucent_surfaces(scene: &Scene) -> bool {
    scene.meshes.iter().any(|m| is_translucent_mesh(scene, m))
}

/// `scene` with a back face for every triangle of a translucent material, appended after
/// its meshes (a luminaire housing's back faces are part of the housing); `scene` itself
/// when nothing is translucent.
pub fn with_back_faces(scene: &Scene) -> Cow<'_, Scene> {
    let translucent = |m: &SceneMesh| is_translucent_mesh(scene, m);
    if !has_translucent_surfaces(scene) {
        return Cow::Borrowed(scene);
    }
    let mut out = scene.clone();
    let mut back_of = vec![None; scene.meshes.len()];
    for (i, m) in scene.meshes.iter().enumerate() {
        if !translucent(m) {
            continue;
        }
        back_of[i] = Some(out.meshes.len());
        out.meshes.push(SceneMesh {
            name: format!("{} (back)", m.name),
            normals: m.normals.iter().map(|n| -*n).collect(),
            indices: m
                .indices
                .chunks_exact(3)
                .flat_map(|t| [t[0], t[2], t[1]])
                .collect(),
            ..m.clone()
        });
    }
    for l in &mut out.luminaires {
        if let Some(h) = &mut l.housing {
            let backs: Vec<usize> = h.meshes.iter().filter_map(|&m| back_of[m]).collect();
            h.meshes.extend(backs);
        }
    }
    Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Material;
    use glam::Vec3;

    fn panel_scene(transmittance: f32) -> Scene {
        let mut scene = Scene::from_toml(std::path::Path::new("panel.toml"), "").unwrap();
        scene.materials.push(Material {
            name: "opal".into(),
            diffuse: Vec3::splat(0.4),
            diffuse_transmittance: Vec3::splat(transmittance),
            ..Material::default()
        });
        let quad = [
            [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)],
            [Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        ];
        scene
            .meshes
            .push(SceneMesh::from_triangles("floor", &quad, 0));
        scene
            .meshes
            .push(SceneMesh::from_triangles("panel", &quad, 1));
        scene
    }

    #[test]
    fn translucent_meshes_get_reversed_back_faces_after_the_scene() {
        let opaque = panel_scene(0.0);
        assert!(matches!(with_back_faces(&opaque), Cow::Borrowed(_)));
        let scene = panel_scene(0.3);
        let twinned = with_back_faces(&scene);
        assert_eq!(twinned.meshes.len(), 3);
        let (front, back) = (&twinned.meshes[1], &twinned.meshes[2]);
        assert_eq!(back.material, 1);
        let normal = |m: &SceneMesh, t: usize| {
            let c = [0, 1, 2].map(|k| m.positions[m.indices[3 * t + k] as usize]);
            (c[1] - c[0]).cross(c[2] - c[0]).normalize()
        };
        for t in 0..2 {
            assert_eq!(normal(front, t), Vec3::Z);
            assert_eq!(normal(back, t), -Vec3::Z);
        }
        assert_eq!(back.normals[0], -Vec3::Z);
        assert_eq!(
            twinned.caster_mesh().triangles[..4],
            scene.caster_mesh().triangles[..]
        );
    }
}
