//! glTF models in scenes (`[[model]] path = "….glb"`): meshes and materials converted as
//! an OBJ's are, and the file's lights placed as luminaires.
//!
//! Materials: reflectance `baseColorFactor` × the base colour texture's mean (as `Kd` ×
//! `map_Kd`); `alphaMode` MASK cuts holes at `alphaCutoff`, BLEND keeps the texture's
//! holes and lets `1 − alpha` through diffusely, OPAQUE ignores alpha;
//! `KHR_materials_transmission` is clear glass (`specular_transmittance`, tinted by the
//! base colour) below [`FROSTED_ROUGHNESS`], diffuse transmission above; emissive ×
//! `KHR_materials_emissive_strength` is read as luminance (cd/m², the emissive texture's
//! mean), so the surface's exitance is π times it (`Ke`, lm/m²). Metals reflect
//! diffusely like other materials (radiosity has no glossy reflection).
//!
//! Lights: `KHR_lights_punctual` point and spot lights become rotationally symmetric
//! luminaires with the extension's intensity (cd) and smooth cone falloff, the colour
//! normalised to luminance 1 (the intensity is the luminous intensity);
//! `EXT_lights_ies` lights are their IES profiles, scaled by `multiplier` × the colour's
//! luminance (the extension's colour changes the output). Each is placed and aimed by
//! its node (γ = 0 along the node's −Z, C0 along its +X). Directional lights are
//! sunlight and are left to `[sky]`. `light_files` replaces a node's light by a
//! luminaire file; `import_lights = false` leaves them all out.

use std::path::Path;
use std::sync::Arc;

use glam::{DMat3, DVec3, Vec2, Vec3};

use super::file::ModelEntry;
use super::model::{model_matrix, Material, SceneMesh, MAX_EXITANCE_LM_M2};
use super::{PlacedLuminaire, SceneError};
use crate::geometry::gltf_file::{self, AlphaMode, GltfLight, GltfMaterial, GltfModel, LightKind};
use crate::photometry::Luminaire;

/// Transmissive materials at least this rough transmit diffusely (frosted, paper).
pub const FROSTED_ROUGHNESS: f32 = 0.3;

/// What one glTF model adds to a scene.
pub(super) struct GltfContent {
    /// Its meshes in the world frame.
    pub meshes: Vec<SceneMesh>,
    /// Its lights as luminaires.
    pub lights: Vec<PlacedLuminaire>,
}

/// Loads the glTF `file` of `entry` (`key` e.g. `model[0]`): its materials are appended
/// to `materials`, what was simplified to `warnings`.
pub(super) fn load(
    scene: &Path,
    key: &str,
    file: &Path,
    entry: &ModelEntry,
    (materials, warnings): (&mut Vec<Material>, &mut Vec<String>),
) -> Result<GltfContent, SceneError> {
    let path_key = format!("{key}.path");
    let model =
        gltf_file::read(file).map_err(|e| SceneError::new(scene, &path_key, e.to_string()))?;
    warnings.extend(
        model
            .warnings
            .iter()
            .map(|w| format!("{}: {w}", file.display())),
    );
    let first = materials.len();
    let mut notes = Vec::new();
    for m in &model.materials {
        let converted = material(m, &mut notes).map_err(|message| {
            SceneError::new(
                scene,
                &path_key,
                format!("{}: material {:?}: {message}", file.display(), m.name),
            )
        })?;
        materials.push(converted);
    }
    warnings.extend(notes.iter().map(|w| format!("{}: {w}", file.display())));
    let fallback = super::model::bake_overrides(scene, key, entry, first, materials)?;
    let meshes = meshes(&model, entry, first, fallback, materials, warnings);
    if meshes.is_empty() && model.lights.is_empty() {
        return Err(SceneError::new(
            scene,
            path_key,
            format!("{}: no triangles with a non-zero area", file.display()),
        ));
    }
    let dir = scene.parent().unwrap_or(Path::new(""));
    let lights = lights(scene, key, dir, file, entry, &model, warnings)?;
    Ok(GltfContent { meshes, lights })
}

/// The primitives as world-space meshes, zero-area triangles and fully cut-out
/// materials dropped (told in `warnings`).
fn meshes(
    model: &GltfModel,
    entry: &ModelEntry,
    first: usize,
    fallback: usize,
    materials: &[Material],
    warnings: &mut Vec<String>,
) -> Vec<SceneMesh> {
    let matrix = model_matrix(entry);
    let normal_matrix = DMat3::from_mat4(matrix).inverse().transpose();
    let (mut dropped, mut total) = (0usize, 0usize);
    let mut out = Vec::new();
    for p in &model.primitives {
        let material = p.material.map_or(fallback, |m| first + m);
        if p.material.is_some_and(|m| cut_away(&model.materials[m])) {
            warnings.push(format!(
                "{}: its material {:?} is cut away entirely (alpha below the cutoff)",
                p.node, materials[material].name
            ));
            continue;
        }
        let mut mesh = SceneMesh {
            name: p.node.clone(),
            material,
            ..Default::default()
        };
        for t in &p.triangles {
            total += 1;
            let corners = t.map(|i| matrix.transform_point3(p.positions[i as usize]));
            if !crate::geometry::has_area(corners) {
                dropped += 1;
                continue;
            }
            let face = (corners[1] - corners[0])
                .cross(corners[2] - corners[0])
                .normalize()
                .as_vec3();
            for (k, &i) in t.iter().enumerate() {
                let normal = p
                    .normals
                    .as_ref()
                    .map(|n| {
                        (normal_matrix * n[i as usize])
                            .normalize_or_zero()
                            .as_vec3()
                    })
                    .filter(|n| *n != Vec3::ZERO)
                    .unwrap_or(face);
                // glTF's texture origin is the image's top left, as the renderer and
                // the alpha masks sample (row 0 the image's top row).
                let uv = p
                    .uvs
                    .as_ref()
                    .map_or(Vec2::ZERO, |uv| Vec2::from(uv[i as usize]));
                mesh.indices.push(mesh.positions.len() as u32);
                mesh.positions.push(corners[k].as_vec3());
                mesh.normals.push(normal);
                mesh.uvs.push(uv);
            }
        }
        if !mesh.indices.is_empty() {
            out.push(mesh);
        }
    }
    if dropped > 0 {
        warnings.push(format!(
            "{}: {dropped} of its {total} triangles have no area and were dropped",
            entry.path
        ));
    }
    out
}

/// Whether MASK mode with a uniform alpha below the cutoff and no texture removes the
/// whole material.
fn cut_away(m: &GltfMaterial) -> bool {
    matches!(m.alpha, AlphaMode::Mask(c) if m.base_color[3] < c && m.base_color_texture.is_none())
}

/// A glTF material as the scene's [`Material`].
fn material(m: &GltfMaterial, warnings: &mut Vec<String>) -> Result<Material, String> {
    let base = Vec3::from_slice(&m.base_color[..3]);
    if base.max_element() > 1.0 {
        return Err(format!(
            "baseColorFactor {base} is a reflectance and cannot exceed 1"
        ));
    }
    let mut out = Material {
        name: m.name.clone(),
        diffuse: base,
        ..Material::default()
    };
    out.set_diffuse_map(
        m.base_color_texture
            .as_ref()
            .map(|t| Arc::new(with_alpha(t, m))),
    );
    let mean = out.texture_mean();
    let transmission = m.transmission * m.transmission_texture.as_deref().map_or(1.0, red_mean);
    let tint = base * mean;
    if transmission > 0.0 {
        out.diffuse = base * (1.0 - transmission);
        if m.roughness < FROSTED_ROUGHNESS {
            out.specular_transmittance = tint * transmission;
        } else {
            out.diffuse_transmittance = tint * transmission;
        }
        if (m.ior - 1.52).abs() > 0.05 && m.roughness < FROSTED_ROUGHNESS {
            warnings.push(format!(
                "material {:?}: index of refraction {} is modelled as glass of 1.52",
                m.name, m.ior
            ));
        }
    }
    if m.alpha == AlphaMode::Blend {
        let clear = (1.0 - m.base_color[3]).clamp(0.0, 1.0);
        out.diffuse_transmittance += Vec3::splat(clear)
            * (Vec3::ONE
                - out.diffuse_reflectance()
                - out.specular_transmittance
                - out.diffuse_transmittance)
                .max(Vec3::ZERO);
    }
    let emissive_mean = m.emissive_texture.as_deref().map_or(Vec3::ONE, srgb_mean);
    if m.emissive_texture.is_some() && m.emissive.iter().any(|&e| e > 0.0) {
        warnings.push(format!(
            "material {:?}: its emissive texture is averaged over the material",
            m.name
        ));
    }
    out.emission = Vec3::from_array(m.emissive) * emissive_mean * std::f32::consts::PI;
    if f64::from(out.emission.max_element()) > MAX_EXITANCE_LM_M2 {
        return Err(format!(
            "emissive {:?} gives {} lm/m², brighter than the sun's surface",
            m.emissive, out.emission
        ));
    }
    Ok(out)
}

/// The base colour texture with its alpha as the material's mode uses it: ignored
/// (opaque), cut at the cutoff (mask, the factor's alpha applied), or as is (blend).
fn with_alpha(t: &image::RgbaImage, m: &GltfMaterial) -> image::RgbaImage {
    let mut out = t.clone();
    for p in out.pixels_mut() {
        p.0[3] = match m.alpha {
            AlphaMode::Opaque => 255,
            AlphaMode::Mask(cutoff) => {
                let a = f32::from(p.0[3]) / 255.0 * m.base_color[3];
                if a >= cutoff {
                    255
                } else {
                    0
                }
            }
            AlphaMode::Blend => p.0[3],
        };
    }
    out
}

/// The mean of an image's red channel, 0…1 (linear data such as transmission).
fn red_mean(t: &image::RgbaImage) -> f32 {
    let n = (t.width() as f64 * t.height() as f64).max(1.0);
    (t.pixels().map(|p| f64::from(p.0[0])).sum::<f64>() / n / 255.0) as f32
}

/// The mean linear colour of an sRGB image.
fn srgb_mean(t: &image::RgbaImage) -> Vec3 {
    let linear: Vec<f64> = (0..=255u8)
        .map(|c| f64::from(super::palette::srgb_to_linear(c)))
        .collect();
    let n = (t.width() as f64 * t.height() as f64).max(1.0);
    let mut sum = [0.0f64; 3];
    for p in t.pixels() {
        for (s, &c) in sum.iter_mut().zip(&p.0[..3]) {
            *s += linear[c as usize];
        }
    }
    Vec3::from_array(sum.map(|s| (s / n) as f32))
}

/// The model's lights as luminaires placed in the world (see the module's notes).
fn lights(
    scene: &Path,
    key: &str,
    dir: &Path,
    file: &Path,
    entry: &ModelEntry,
    model: &GltfModel,
    warnings: &mut Vec<String>,
) -> Result<Vec<PlacedLuminaire>, SceneError> {
    for node in entry.light_files.keys() {
        if !model.lights.iter().any(|l| &l.node == node) {
            let names: Vec<&str> = model.lights.iter().map(|l| l.node.as_str()).collect();
            return Err(SceneError::new(
                scene,
                format!("{key}.light_files.{node}"),
                format!(
                    "{} has no light node {node:?} (its lights: {names:?})",
                    file.display()
                ),
            ));
        }
    }
    if !entry.import_lights {
        return Ok(Vec::new());
    }
    let matrix = model_matrix(entry);
    let mut out = Vec::new();
    for light in &model.lights {
        let replaced = entry.light_files.get(&light.node);
        let luminaire = match replaced {
            Some(f) => {
                let path = dir.join(f);
                let l = Luminaire::load(&path).map_err(|e| {
                    SceneError::new(
                        scene,
                        format!("{key}.light_files.{}", light.node),
                        e.to_string(),
                    )
                })?;
                Some((l, 1.0, DVec3::ONE, path))
            }
            None => luminaire_of(light, warnings)
                .map_err(|message| {
                    SceneError::new(
                        scene,
                        format!("{key}.path"),
                        format!("{}: light {:?}: {message}", file.display(), light.node),
                    )
                })?
                .map(|(l, m, c)| (l, m, c, file.to_path_buf())),
        };
        let Some((luminaire, multiplier, color, source)) = luminaire else {
            continue;
        };
        let rotation =
            gltf_file::orthonormal(DMat3::from_mat4(matrix) * light.frame).ok_or_else(|| {
                SceneError::new(
                    scene,
                    format!("{key}.scale"),
                    format!("light {:?} has no orientation", light.node),
                )
            })?;
        let mut placed = PlacedLuminaire::new(
            &light.node,
            luminaire,
            matrix.transform_point3(light.position),
        );
        placed.rotation = rotation;
        placed.multiplier = multiplier;
        placed.color = color;
        placed.file = source;
        placed.model_light = Some(light.node.clone());
        out.push(placed);
    }
    Ok(out)
}

/// The luminaire, multiplier and colour (luminance 1) of a glTF light; `None` (told in
/// `warnings`) for what is not placed: directional lights and dark or black lights; an
/// error for an IES profile that does not read.
fn luminaire_of(
    light: &GltfLight,
    warnings: &mut Vec<String>,
) -> Result<Option<(Luminaire, f64, DVec3)>, String> {
    let c = DVec3::from_array(light.color);
    let luminance = c.dot(DVec3::new(0.2126, 0.7152, 0.0722));
    let mut skip = |why: String| {
        warnings.push(format!("light {:?}: {why}; not placed", light.node));
        None
    };
    if !(luminance > 0.0 && c.min_element() >= 0.0) {
        return Ok(skip(format!("colour {c} has no luminance")));
    }
    let color = c / luminance;
    let name = &light.node;
    Ok(match &light.kind {
        LightKind::Point { candela } => {
            let l =
                crate::photometry::synthetic::rotational(name, &[0.0, 90.0, 180.0], &[*candela; 3]);
            l.map(|l| (l, 1.0, color))
                .or_else(|| skip("intensity 0".into()))
        }
        LightKind::Spot {
            candela,
            inner_cone,
            outer_cone,
        } => {
            let gammas: Vec<f64> = (0..=360).map(|k| f64::from(k) * 0.5).collect();
            let cd: Vec<f64> = gammas
                .iter()
                .map(|g| {
                    candela * gltf_file::spot_falloff(g.to_radians(), *inner_cone, *outer_cone)
                })
                .collect();
            let l = crate::photometry::synthetic::rotational(name, &gammas, &cd);
            l.map(|l| (l, 1.0, color))
                .or_else(|| skip("intensity 0".into()))
        }
        LightKind::Directional { .. } => skip(
            "a directional light is sunlight: give the scene a [sky] and [site] instead".into(),
        ),
        LightKind::Ies {
            profile,
            bytes,
            multiplier,
        } => {
            let file = if profile.to_ascii_lowercase().ends_with(".ies") {
                profile.clone()
            } else {
                format!("{profile}.ies")
            };
            let l = Luminaire::from_bytes(&file, bytes)
                .map_err(|e| format!("its IES profile {profile:?}: {e}"))?;
            Some((l, multiplier * luminance, color))
        }
    })
}
