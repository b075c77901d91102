//! Dual-paraboloid shadow maps for luminaires (Brabec et al. 2002): two depth layers per
//! luminaire, the lower paraboloid around its γ = 0 axis and the upper one around γ = 180°.
//! A luminaire that emits only below (or above) its horizontal gets only that map drawn
//! (the other stays cleared: it never darkens anything, and no light goes there anyway).
//!
//! The paraboloid projection is not linear, so straight edges become curves the rasterizer
//! cannot follow: the casters are tessellated once (longest-edge bisection to a maximum
//! edge length), and each fragment stores the exact distance along its texel's direction
//! to its triangle's plane, so only coverage (not depth) depends on the tessellation.

use glam::{DMat3, DVec3};
use wgpu::util::DeviceExt;

use super::cutout_gpu::{piece_vertices, CasterVertex, MaskBuffers};
use crate::geometry::simplify::{merge_strips_within, Merged};
use crate::geometry::Mesh;
use crate::gpu::{shaders, Gpu};
use crate::photometry::texture::Hemisphere;
use crate::shadow::{Cutouts, IgnoredTriangles};

/// Where a luminaire is, how it is turned, where it emits and which triangles are its own
/// housing: what its shadows need.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowLight {
    /// Photometric centre, metres.
    pub position: DVec3,
    /// Luminaire frame → world.
    pub rotation: DMat3,
    /// The part of the sphere it lights.
    pub hemisphere: Hemisphere,
    /// Its housing: caster triangles that never shadow it.
    pub ignored: IgnoredTriangles,
}

/// Splits every triangle of `mesh` at the midpoint of its longest edge until no edge is
/// longer than `max_edge` metres.
pub fn tessellate(mesh: &Mesh, max_edge: f64) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    tessellate_each(mesh, max_edge, |_, t| {
        out.push(t);
        true
    });
    out
}

/// Calls `f(source triangle, piece)` for the pieces of every triangle of `mesh` after
/// [`tessellate`], triangle after triangle in order; stops when `f` returns false.
pub(crate) fn tessellate_each(
    mesh: &Mesh,
    max_edge: f64,
    mut f: impl FnMut(usize, [DVec3; 3]) -> bool,
) {
    let limit = max_edge * max_edge;
    let mut stack: Vec<[DVec3; 3]> = Vec::new();
    for (k, t) in mesh.triangles.iter().enumerate() {
        stack.push(t.map(|i| mesh.positions[i as usize]));
        while let Some(t) = stack.pop() {
            match bisect(t, limit) {
                Some(halves) => stack.extend(halves),
                None => {
                    if !f(k, t) {
                        return;
                    }
                }
            }
        }
    }
}

/// The two halves of `t` split at the middle of its longest edge, or `None` when every
/// edge is within √`limit` (or not finite: such a triangle is kept whole).
fn bisect(t: [DVec3; 3], limit: f64) -> Option<[[DVec3; 3]; 2]> {
    let lengths = [0, 1, 2].map(|k| t[k].distance_squared(t[(k + 1) % 3]));
    let k = (0..3)
        .max_by(|&a, &b| lengths[a].total_cmp(&lengths[b]))
        .unwrap_or(0);
    if lengths[k] <= limit || !lengths[k].is_finite() {
        return None;
    }
    let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
    let m = (a + b) * 0.5;
    Some([[a, m, c], [m, b, c]])
}

/// The number of triangles [`tessellate`] makes of `mesh`, counted without storing them
/// and given up at `stop_at` (a budget: huge faces must not cost time or memory to refuse).
pub fn tessellated_count(mesh: &Mesh, max_edge: f64, stop_at: usize) -> usize {
    let mut count = 0usize;
    tessellate_each(mesh, max_edge, |_, _| {
        count += 1;
        count < stop_at
    });
    count
}

/// What paraboloid maps draw: the casters with CAD fans merged back into the triangles
/// they fill (within each object, `objects` per triangle: a housing stays its own), so a
/// face drawn as hundreds of slivers is tessellated once, not sliver by sliver. The same
/// surfaces (within a millionth of the scene's size). Triangles with holes (`cutouts`)
/// are never merged: each keeps its own texture coordinates.
pub fn merged_casters(mesh: &Mesh, objects: &[u32], cutouts: Option<&Cutouts>) -> Merged {
    let size = mesh.bounds().map_or(1.0, |(lo, hi)| (hi - lo).length());
    let groups: Vec<u32>;
    let objects = match cutouts {
        Some(cut) if !objects.is_empty() => {
            let first_free = objects.iter().max().map_or(0, |&m| m + 1);
            groups = (0..objects.len())
                .map(|k| match cut.mask_of(k) {
                    Some(_) => first_free + k as u32,
                    None => objects[k],
                })
                .collect();
            &groups
        }
        _ => objects,
    };
    merge_strips_within(mesh, objects, 1e-6 * size)
}

/// The tessellated shadow casters on the GPU (non-indexed triangles, in the order of
/// the source triangles, so a light can leave out its own housing).
pub struct ParaboloidCasters {
    vertices: wgpu::Buffer,
    masks: MaskBuffers,
    vertex_count: u32,
    /// Source triangle k's pieces are vertices `first_vertex[k]..first_vertex[k + 1]`.
    first_vertex: Vec<u32>,
}

impl ParaboloidCasters {
    /// Tessellates `casters` (merged from the triangles of `source`,
    /// [`merged_casters`]) to `max_edge` metres and uploads them, with the holes of
    /// `cutouts` (of `source`). A merged triangle's pieces count as its first source
    /// triangle's.
    pub fn new(
        gpu: &Gpu,
        casters: &Merged,
        source: &Mesh,
        cutouts: Option<&Cutouts>,
        max_edge: f64,
    ) -> ParaboloidCasters {
        let mut data: Vec<CasterVertex> = Vec::new();
        let mut first_vertex = vec![0u32; source.triangles.len() + 1];
        tessellate_each(&casters.mesh, max_edge, |k, t| {
            let from = casters.origin[k] as usize;
            data.extend(piece_vertices(source, cutouts, from, t));
            first_vertex[from + 1] = data.len() as u32;
            true
        });
        // Triangles without pieces (none today) end where the previous one did.
        for k in 1..first_vertex.len() {
            first_vertex[k] = first_vertex[k].max(first_vertex[k - 1]);
        }
        let vertex_count = data.len() as u32;
        if data.is_empty() {
            data.push(CasterVertex::solid(glam::Vec3::ZERO));
        }
        let vertices = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("paraboloid casters"),
                contents: bytemuck::cast_slice(&data),
                usage: wgpu::BufferUsages::VERTEX,
            });
        ParaboloidCasters {
            vertices,
            masks: MaskBuffers::new(gpu, cutouts),
            vertex_count,
            first_vertex,
        }
    }

    /// The vertex ranges a light that ignores `ignored` (source triangles) draws.
    fn drawn_by(&self, ignored: &IgnoredTriangles) -> Vec<std::ops::Range<u32>> {
        let triangles = self.first_vertex.len() - 1;
        ignored
            .kept(triangles)
            .into_iter()
            .map(|r| self.first_vertex[r.start]..self.first_vertex[r.end])
            .filter(|r| !r.is_empty())
            .collect()
    }

    /// Number of triangles after tessellation.
    pub fn triangle_count(&self) -> u32 {
        self.vertex_count / 3
    }
}

/// `ParaboloidView` in `shaders/paraboloid.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ParaboloidViewGpu {
    position: [f32; 4],
    axis_x: [f32; 4],
    axis_y: [f32; 4],
    axis_z: [f32; 4],
    params: [f32; 4],
}

/// The maps of every luminaire: layers 2i (lower) and 2i + 1 (upper).
pub struct ParaboloidMaps {
    /// The depth texture array.
    pub texture: wgpu::Texture,
    /// Its array view.
    pub view: wgpu::TextureView,
    /// Side, texels.
    pub size: u32,
    /// Distance stored as depth 1, metres.
    pub far: f32,
}

/// Format of the maps.
pub const MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The pipeline that draws a map.
pub struct ParaboloidPasses {
    layout: wgpu::BindGroupLayout,
    mask_layout: wgpu::BindGroupLayout,
    pipeline: wgpu::RenderPipeline,
}

impl ParaboloidPasses {
    /// Builds the pipeline.
    pub fn new(gpu: &Gpu) -> ParaboloidPasses {
        let dev = &gpu.device;
        let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("paraboloid"),
            source: wgpu::ShaderSource::Wgsl(shaders::paraboloid().into()),
        });
        let layout = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("paraboloid"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let mask_layout = MaskBuffers::layout(gpu);
        let pipeline_layout = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("paraboloid"),
            bind_group_layouts: &[Some(&layout), Some(&mask_layout)],
            immediate_size: 0,
        });
        let pipeline = gpu.caster_depth_pipeline(
            "paraboloid map",
            &pipeline_layout,
            &module,
            ("vs_paraboloid", "fs_paraboloid"),
            CasterVertex::LAYOUT,
            MAP_FORMAT,
            &[],
        );
        ParaboloidPasses {
            layout,
            mask_layout,
            pipeline,
        }
    }

    /// Creates and records the maps of `lights` (`size` texels square; distances up to
    /// `far` metres).
    pub fn render(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        casters: &ParaboloidCasters,
        lights: &[ShadowLight],
        size: u32,
        far: f32,
    ) -> ParaboloidMaps {
        let layers = 2 * lights.len().max(1) as u32;
        let masks = casters.masks.bind_group(gpu, &self.mask_layout);
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("paraboloid maps"),
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: MAP_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        for layer in 0..layers {
            let view = crate::gpu::layer_view(&texture, layer);
            let light = lights.get(layer as usize / 2);
            let upper = layer % 2 == 1;
            let wanted = light.is_some_and(|l| match l.hemisphere {
                Hemisphere::Lower => !upper,
                Hemisphere::Upper => upper,
                Hemisphere::Full => true,
            });
            let bind = light.filter(|_| wanted).map(|l| {
                let axis = |v: DVec3| {
                    let v = v.as_vec3();
                    [v.x, v.y, v.z, 0.0]
                };
                let p = l.position.as_vec3();
                let record = ParaboloidViewGpu {
                    position: [p.x, p.y, p.z, upper as u32 as f32],
                    axis_x: axis(l.rotation.x_axis),
                    axis_y: axis(l.rotation.y_axis),
                    axis_z: axis(l.rotation.z_axis),
                    params: [far, size as f32, 0.0, 0.0],
                };
                let buffer = gpu.uniform_buffer("paraboloid view", &record);
                gpu.bind_group(
                    "paraboloid view",
                    &self.layout,
                    &[(0, buffer.as_entire_binding())],
                )
            });
            let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("paraboloid map"),
                color_attachments: &[],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            if let (Some(bind), Some(light)) = (bind, light) {
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.set_bind_group(1, &masks, &[]);
                pass.set_vertex_buffer(0, casters.vertices.slice(..));
                for range in casters.drawn_by(&light.ignored) {
                    pass.draw(range, 0..1);
                }
            }
        }
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        ParaboloidMaps {
            texture,
            view,
            size,
            far,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tessellation_keeps_area_and_bounds_edges() {
        let mesh = Mesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::new(6.0, 0.0, 0.0),
                DVec3::new(0.0, 4.0, 0.0),
            ],
            triangles: vec![[0, 1, 2]],
        };
        let tris = tessellate(&mesh, 0.3);
        let area: f64 = tris
            .iter()
            .map(|t| (t[1] - t[0]).cross(t[2] - t[0]).length() / 2.0)
            .sum();
        assert!((area - 12.0).abs() < 1e-9, "{area}");
        for t in &tris {
            for k in 0..3 {
                assert!(t[k].distance(t[(k + 1) % 3]) <= 0.3 + 1e-12);
            }
            // Winding is kept.
            assert!((t[1] - t[0]).cross(t[2] - t[0]).z > 0.0);
        }
        // The counter agrees with the tessellation, and stops at its budget.
        assert_eq!(tessellated_count(&mesh, 0.3, usize::MAX), tris.len());
        assert_eq!(tessellated_count(&mesh, 0.3, 100), 100);
    }
}
