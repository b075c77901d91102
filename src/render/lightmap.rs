//! A solved radiosity light map for display: the renderer shows a scene with its
//! interreflected light by sampling the atlas (rgb radiosity, a illuminance) and adding
//! the luminaires' direct specular term per pixel.

use glam::Vec2;
use wgpu::util::DeviceExt;

use crate::gpu::Gpu;

/// A light-map atlas and where each of the scene's triangles lies in it.
#[derive(Debug, Clone, PartialEq)]
pub struct LightMap {
    /// Atlas width, texels.
    pub width: u32,
    /// Atlas height, texels.
    pub height: u32,
    /// Row-major texels: rgb radiosity (lm/m²), a illuminance received (lux).
    pub texels: Vec<[f32; 4]>,
    /// Per scene triangle (meshes in order, triangles in index order): the atlas
    /// coordinates (0..1, from the top-left corner) of its three corners.
    pub triangle_uv: Vec<[Vec2; 3]>,
}

impl LightMap {
    /// The radiosity (rgb, lm/m²) and the received illuminance (lux, in each of r, g
    /// and b) as float images, as `radiosity` writes `lightmap.exr` and
    /// `lightmap_lux.exr`.
    pub fn images(&self) -> Option<(image::Rgb32FImage, image::Rgb32FImage)> {
        let rgb: Vec<f32> = self
            .texels
            .iter()
            .flat_map(|t| [t[0], t[1], t[2]])
            .collect();
        let lux: Vec<f32> = self.texels.iter().flat_map(|t| [t[3]; 3]).collect();
        Some((
            image::Rgb32FImage::from_raw(self.width, self.height, rgb)?,
            image::Rgb32FImage::from_raw(self.width, self.height, lux)?,
        ))
    }

    /// Whether `other` lays the same triangles out in the same atlas (a later solution
    /// of the same elements): its texels can replace these without new vertices.
    pub fn same_layout(&self, other: &LightMap) -> bool {
        self.width == other.width
            && self.height == other.height
            && self.triangle_uv == other.triangle_uv
    }
}

/// Texture format of the light map on the GPU (filterable).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// Uploads a light map (or a 1 × 1 black one for scenes without) as a filterable texture.
pub(crate) fn upload(gpu: &Gpu, map: Option<&LightMap>) -> wgpu::TextureView {
    let (width, height, texels) = match map {
        Some(m) => (m.width, m.height, m.texels.as_slice()),
        None => (1, 1, &[[0.0f32; 4]][..]),
    };
    let halves: Vec<half::f16> = texels
        .iter()
        .flatten()
        .map(|&v| half::f16::from_f32(v.clamp(-65_000.0, 65_000.0)))
        .collect();
    let bytes: Vec<u8> = halves.iter().flat_map(|h| h.to_le_bytes()).collect();
    let texture = gpu.device.create_texture_with_data(
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some("light map"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &bytes,
    );
    texture.create_view(&Default::default())
}
