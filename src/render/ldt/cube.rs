//! The Catmull-Rom cube maps of a scene's light distributions (the renderer's
//! `CatmullRomCube` light model): each distribution resampled once, on the CPU, into a cube
//! map of [`CUBE_SIZE`]² texels per face holding the exact Catmull-Rom value toward each
//! texel's centre (16-bit floats, fractions of I_max), so a lookup is one hardware-filtered
//! fetch indexed by the direction in the luminaire's frame — no (C, γ) angles, no
//! trigonometry per pixel. Between texel centres the value is bilinear, so it differs from
//! the spline where the distribution bends within a texel (0.18° at a face's centre);
//! `tests/gpu/gpu_ldt.rs` measures how far over every bundled file.

use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

use glam::DVec3;
use rayon::prelude::*;

use crate::gpu::Gpu;
use crate::photometry::{direction_to_angles, Interp, LdtTexture};

/// Texels per face side.
pub const CUBE_SIZE: u32 = 512;
/// Texel format (filterable on every backend).
pub const CUBE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;

/// The unit direction through the centre of texel (`i`, `j`) of `face` of a cube map with
/// `n` texels a side, in the order and orientation of Vulkan and WebGPU cube maps (faces
/// +X, −X, +Y, −Y, +Z, −Z; s across, t down).
pub fn cube_texel_direction(face: usize, i: u32, j: u32, n: u32) -> DVec3 {
    let s = 2.0 * (i as f64 + 0.5) / n as f64 - 1.0;
    let t = 2.0 * (j as f64 + 0.5) / n as f64 - 1.0;
    let r = match face {
        0 => DVec3::new(1.0, -t, -s),
        1 => DVec3::new(-1.0, -t, s),
        2 => DVec3::new(s, 1.0, t),
        3 => DVec3::new(s, -1.0, -t),
        4 => DVec3::new(s, -t, 1.0),
        _ => DVec3::new(-s, -t, -1.0),
    };
    r.normalize()
}

/// The texels of one distribution's cube map, face after face, row after row: the exact
/// Catmull-Rom value (fraction of I_max) toward each texel's centre.
pub fn cube_texels(t: &LdtTexture, n: u32) -> Vec<f32> {
    (0..6 * n * n)
        .into_par_iter()
        .map(|k| {
            let (face, rest) = ((k / (n * n)) as usize, k % (n * n));
            let (c, g) = direction_to_angles(cube_texel_direction(face, rest % n, rest / n, n));
            t.sample(c, g, Interp::CatmullRom).max(0.0) as f32
        })
        .collect()
}

/// Distributions whose cube maps the process keeps (16-bit texels, 3 MB each at 512²):
/// the viewer uploads its lights again every frame of an animation, and a cube map takes
/// a few hundred milliseconds of CPU to resample.
const CACHED_CUBES: usize = 64;

/// The 16-bit texels of `t`'s cube map of side `n`, resampled on the first request and
/// kept for later ones (keyed by the distribution's grid and values).
fn cached_cube_bytes(t: &LdtTexture, n: u32) -> Arc<Vec<u8>> {
    static CACHE: Mutex<Option<HashMap<u64, Arc<Vec<u8>>>>> = Mutex::new(None);
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (n, t.c_count, t.gamma_count).hash(&mut h);
    (t.gamma_start_deg.to_bits(), t.gamma_step_deg.to_bits()).hash(&mut h);
    for v in &t.data {
        v.to_bits().hash(&mut h);
    }
    let key = h.finish();
    if let Some(bytes) = CACHE
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .get_or_insert_with(HashMap::new)
        .get(&key)
    {
        return bytes.clone();
    }
    let bytes: Arc<Vec<u8>> = Arc::new(
        cube_texels(t, n)
            .into_iter()
            .flat_map(|v| half::f16::from_f32(v).to_le_bytes())
            .collect(),
    );
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    let map = cache.get_or_insert_with(HashMap::new);
    if map.len() >= CACHED_CUBES {
        map.clear();
    }
    map.insert(key, bytes.clone());
    bytes
}

/// The cube maps of every layer, as one cube-array view (one cube of zeros when there are
/// no layers).
pub fn cube_array(gpu: &Gpu, textures: &[LdtTexture], n: u32) -> wgpu::TextureView {
    let layers = textures.len().max(1) as u32;
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("catmull-rom cube maps"),
        size: wgpu::Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: 6 * layers,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: CUBE_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (layer, t) in textures.iter().enumerate() {
        let bytes = cached_cube_bytes(t, n);
        gpu.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d {
                    x: 0,
                    y: 0,
                    z: 6 * layer as u32,
                },
                aspect: wgpu::TextureAspect::All,
            },
            bytes.as_slice(),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(2 * n),
                rows_per_image: Some(n),
            },
            wgpu::Extent3d {
                width: n,
                height: n,
                depth_or_array_layers: 6,
            },
        );
    }
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::CubeArray),
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_directions_point_through_their_face() {
        let n = 8;
        let axes = [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ];
        for (face, axis) in axes.iter().enumerate() {
            for (i, j) in [(0, 0), (3, 4), (7, 7)] {
                let d = cube_texel_direction(face, i, j, n);
                assert!((d.length() - 1.0).abs() < 1e-12);
                // The face's axis is the direction's largest component.
                assert!(d.dot(*axis) >= d.abs().max_element() - 1e-12, "{face} {d}");
            }
        }
        // Vulkan's orientation: on +Z, s grows with x and t with −y.
        let a = cube_texel_direction(4, 0, 0, n);
        let b = cube_texel_direction(4, 7, 7, n);
        assert!(a.x < 0.0 && a.y > 0.0 && b.x > 0.0 && b.y < 0.0);
    }
}
