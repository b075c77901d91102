//! The scene's luminaires in the exported glTF: each an `EXT_lights_ies` light with its
//! profile (IES LM-63 written from its data, embedded as a buffer view) and, for viewers
//! without that extension, a `KHR_lights_punctual` point light of the same mean
//! intensity (its flux over 4π). One node per luminaire at its photometric centre, turned
//! to its frame: γ = 0 along the node's −Z and C0 along its +X, as `EXT_lights_ies`
//! defines. A reader that knows `EXT_lights_ies` (goniolight does) uses it and leaves
//! the fallback.

use gltf::json;
use json::extensions::scene::khr_lights_punctual as khr;
use json::validation::Checked::Valid;

use super::GlbBuilder;
use crate::scene::PlacedLuminaire;

/// Adds the luminaires' lights to `b` and returns their nodes (none for none).
pub(super) fn add(
    b: &mut GlbBuilder,
    luminaires: &[PlacedLuminaire],
) -> Vec<json::Index<json::Node>> {
    if luminaires.is_empty() {
        return Vec::new();
    }
    let mut profiles: Vec<(std::path::PathBuf, serde_json::Value)> = Vec::new();
    let mut fallbacks = Vec::new();
    let mut nodes = Vec::new();
    for (k, l) in luminaires.iter().enumerate() {
        let profile = match profiles.iter().position(|(file, _)| file == &l.file) {
            Some(p) => p,
            None => {
                let text =
                    crate::photometry::ies::write_ies(&l.luminaire.data, "goniolight export");
                let view = b.view(text.as_bytes(), None);
                let name = l.file.file_name().map(|f| f.to_string_lossy().into_owned());
                profiles.push((
                    l.file.clone(),
                    serde_json::json!({
                        "bufferView": view.value(),
                        "mimeType": "application/x-ies-lm-63",
                        "name": name,
                    }),
                ));
                profiles.len() - 1
            }
        };
        // glTF clamps colours to 0…1: the brightest channel becomes 1 and the multiplier
        // carries the rest, so multiplier × the colour's luminance is the dimming again.
        let brightest = l.color.max_element().max(1e-12);
        let color = (l.color / brightest).as_vec3().to_array();
        let mean_cd =
            l.luminaire.distribution.flux_lm() * l.multiplier / (4.0 * std::f64::consts::PI);
        fallbacks.push(khr::Light {
            color,
            extensions: None,
            extras: Default::default(),
            intensity: mean_cd as f32,
            name: Some(l.name.clone()),
            range: None,
            spot: None,
            type_: Valid(khr::Type::Point),
        });
        let mut others = json::extensions::scene::Node::default().others;
        others.insert(
            "EXT_lights_ies".into(),
            serde_json::json!({
                "light": profile,
                "multiplier": l.multiplier * brightest,
                "color": color,
            }),
        );
        nodes.push(b.root.push(json::Node {
            name: Some(l.name.clone()),
            translation: Some(super::to_gltf(l.position)),
            rotation: Some(json::scene::UnitQuaternion(rotation(l))),
            extensions: Some(json::extensions::scene::Node {
                khr_lights_punctual: Some(khr::KhrLightsPunctual {
                    light: json::Index::new(k as u32),
                }),
                others,
            }),
            ..Default::default()
        }));
    }
    let mut root = b.root.extensions.take().unwrap_or_default();
    root.khr_lights_punctual =
        Some(json::extensions::root::KhrLightsPunctual { lights: fallbacks });
    let list: Vec<serde_json::Value> = profiles.into_iter().map(|(_, v)| v).collect();
    root.others.insert(
        "EXT_lights_ies".into(),
        serde_json::json!({ "lights": list }),
    );
    b.root.extensions = Some(root);
    for name in ["KHR_lights_punctual", "EXT_lights_ies"] {
        b.root.extensions_used.push(name.into());
    }
    nodes
}

/// The luminaire's frame in glTF's axes as a quaternion (x, y, z, w).
fn rotation(l: &PlacedLuminaire) -> [f32; 4] {
    // World (x, y, z) → glTF (x, z, −y), a proper rotation.
    let to_gltf = glam::DMat3::from_cols(glam::DVec3::X, glam::DVec3::NEG_Z, glam::DVec3::Y);
    glam::DQuat::from_mat3(&(to_gltf * l.rotation))
        .normalize()
        .as_quat()
        .to_array()
}
