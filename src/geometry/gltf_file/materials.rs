//! glTF materials as read: the metallic-roughness model's factors and textures with the
//! transmission, index-of-refraction and emissive-strength extensions.

use std::sync::Arc;

use super::buffers::ImageCache;

/// How a material's alpha is used (glTF `alphaMode`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AlphaMode {
    /// Alpha is ignored.
    Opaque,
    /// Texels with alpha below the cutoff are holes.
    Mask(f32),
    /// Alpha is partial coverage.
    Blend,
}

/// A glTF material as the file gives it.
#[derive(Debug, Clone)]
pub struct GltfMaterial {
    /// Its name (`material N` when it has none).
    pub name: String,
    /// `baseColorFactor` (linear RGBA).
    pub base_color: [f32; 4],
    /// `baseColorTexture` (sRGB colour, linear alpha).
    pub base_color_texture: Option<Arc<image::RgbaImage>>,
    /// `alphaMode` with `alphaCutoff`.
    pub alpha: AlphaMode,
    /// `metallicFactor`.
    pub metallic: f32,
    /// `roughnessFactor`.
    pub roughness: f32,
    /// `KHR_materials_transmission` `transmissionFactor` (0 without the extension).
    pub transmission: f32,
    /// `transmissionTexture` (its red channel scales the factor).
    pub transmission_texture: Option<Arc<image::RgbaImage>>,
    /// `KHR_materials_ior` (1.5 without the extension).
    pub ior: f32,
    /// `emissiveFactor` × `KHR_materials_emissive_strength` (linear RGB).
    pub emissive: [f32; 3],
    /// `emissiveTexture` (sRGB), multiplying `emissive`.
    pub emissive_texture: Option<Arc<image::RgbaImage>>,
}

/// Reads material `m`; textures are decoded through `images`.
pub(super) fn read(
    m: &gltf::Material,
    data: &[Vec<u8>],
    read_uri: &dyn Fn(&str) -> Result<Vec<u8>, String>,
    images: &mut ImageCache,
    warnings: &mut Vec<String>,
) -> Result<GltfMaterial, String> {
    let pbr = m.pbr_metallic_roughness();
    let mut texture = |info: Option<gltf::texture::Info>| {
        info.map(|i| images.get(&i.texture(), data, read_uri))
            .transpose()
    };
    let base_color_texture = texture(pbr.base_color_texture())?;
    let emissive_texture = texture(m.emissive_texture())?;
    let transmission = m.transmission();
    let transmission_texture =
        texture(transmission.as_ref().and_then(|t| t.transmission_texture()))?;
    let name = m
        .name()
        .map(str::to_string)
        .unwrap_or_else(|| format!("material {}", m.index().unwrap_or(0)));
    if transmission_averaged(m) {
        warnings.push(format!(
            "material {name:?}: its transmission texture is averaged"
        ));
    }
    let strength = m.emissive_strength().unwrap_or(1.0);
    let material = GltfMaterial {
        base_color: pbr.base_color_factor(),
        base_color_texture,
        alpha: match m.alpha_mode() {
            gltf::material::AlphaMode::Opaque => AlphaMode::Opaque,
            gltf::material::AlphaMode::Mask => AlphaMode::Mask(m.alpha_cutoff().unwrap_or(0.5)),
            gltf::material::AlphaMode::Blend => AlphaMode::Blend,
        },
        metallic: pbr.metallic_factor(),
        roughness: pbr.roughness_factor(),
        transmission: transmission
            .as_ref()
            .map_or(0.0, |t| t.transmission_factor()),
        transmission_texture,
        ior: m.ior().unwrap_or(1.5),
        emissive: m.emissive_factor().map(|e| e * strength),
        emissive_texture,
        name,
    };
    let scalars = [
        material.metallic,
        material.roughness,
        material.transmission,
        material.ior,
    ];
    let mut numbers = material
        .base_color
        .iter()
        .chain(&material.emissive)
        .chain(&scalars);
    if numbers.any(|v| !v.is_finite() || *v < 0.0) {
        return Err(format!(
            "{:?}: a factor is negative or not a finite number",
            material.name
        ));
    }
    Ok(material)
}

fn transmission_averaged(m: &gltf::Material) -> bool {
    m.transmission()
        .is_some_and(|t| t.transmission_texture().is_some())
}
