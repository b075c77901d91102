//! Alpha-mask holes on the GPU for the passes that draw bare casters (the paraboloid
//! shadow maps): each caster vertex carries its texture coordinate and its triangle's mask,
//! and the masks travel as bits (`shaders/cutout.wgsl` reads them with the CPU's rule).

use glam::DVec3;
use wgpu::util::DeviceExt;

use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::shadow::Cutouts;

/// A caster vertex: position, texture coordinate and mask ([`NO_MASK`] for solid).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CasterVertex {
    /// World position, metres.
    pub position: [f32; 3],
    /// Texture coordinate (meaningful with a mask).
    pub uv: [f32; 2],
    /// The triangle's mask, an index into [`Cutouts`]' masks.
    pub mask: u32,
}

/// The mask of a solid triangle.
pub const NO_MASK: u32 = u32::MAX;

impl CasterVertex {
    /// The vertex buffer layout (locations 0, 1, 2).
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<CasterVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x2, 2 => Uint32],
    };

    /// A solid vertex at `p`.
    pub fn solid(p: glam::Vec3) -> CasterVertex {
        CasterVertex {
            position: p.to_array(),
            uv: [0.0; 2],
            mask: NO_MASK,
        }
    }
}

/// The vertices of `piece`, a part of triangle `k` of `mesh`, with their texture
/// coordinates where `cutouts` masks the triangle.
pub fn piece_vertices(
    mesh: &Mesh,
    cutouts: Option<&Cutouts>,
    k: usize,
    piece: [DVec3; 3],
) -> [CasterVertex; 3] {
    // Solid triangles (nearly all of them) need no corners and no texture coordinates.
    let Some((cut, mask)) = cutouts.and_then(|c| Some((c, c.mask_of(k)?))) else {
        return piece.map(|p| CasterVertex::solid(p.as_vec3()));
    };
    let corners = mesh.triangles[k].map(|i| mesh.positions[i as usize]);
    piece.map(|p| match cut.uv_at(k, corners, p) {
        Some(uv) => CasterVertex {
            position: p.as_vec3().to_array(),
            uv: uv.to_array(),
            mask,
        },
        None => CasterVertex::solid(p.as_vec3()),
    })
}

/// The masks as GPU buffers: bits (1 = solid) and per mask (first bit, width, height, 0).
pub struct MaskBuffers {
    bits: wgpu::Buffer,
    info: wgpu::Buffer,
}

impl MaskBuffers {
    /// Uploads the masks of `cutouts` (one unused word for none).
    pub fn new(gpu: &Gpu, cutouts: Option<&Cutouts>) -> MaskBuffers {
        let mut bits: Vec<u32> = Vec::new();
        let mut info: Vec<[u32; 4]> = Vec::new();
        let mut first = 0u64;
        for mask in cutouts.map(Cutouts::masks).unwrap_or_default() {
            let (w, h) = mask.size();
            info.push([first as u32, w, h, 0]);
            let end = first + w as u64 * h as u64;
            bits.resize(end.div_ceil(32) as usize, 0);
            for y in 0..h {
                for x in 0..w {
                    if mask.solid_texel(x, y) {
                        let bit = first + (y * w + x) as u64;
                        bits[(bit / 32) as usize] |= 1 << (bit % 32);
                    }
                }
            }
            first = end;
        }
        bits.push(0);
        info.push([0; 4]);
        let buffer = |label, contents: &[u8]| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: wgpu::BufferUsages::STORAGE,
                })
        };
        MaskBuffers {
            bits: buffer("cut-out mask bits", bytemuck::cast_slice(&bits)),
            info: buffer("cut-out mask info", bytemuck::cast_slice(&info)),
        }
    }

    /// The bind group layout of `shaders/cutout.wgsl` (group 1, fragment stage).
    pub fn layout(gpu: &Gpu) -> wgpu::BindGroupLayout {
        let entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        gpu.device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("cut-out masks"),
                entries: &[entry(0), entry(1)],
            })
    }

    /// Their bind group for `layout` ([`MaskBuffers::layout`]).
    pub fn bind_group(&self, gpu: &Gpu, layout: &wgpu::BindGroupLayout) -> wgpu::BindGroup {
        gpu.bind_group(
            "cut-out masks",
            layout,
            &[
                (0, self.bits.as_entire_binding()),
                (1, self.info.as_entire_binding()),
            ],
        )
    }
}
