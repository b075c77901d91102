//! Stencil shadow volumes on the GPU (Wallner ch. 1). Per light: silhouette edges on the
//! CPU (brute force or hextree), an index buffer of the volume (sides, plus caps for
//! z-fail), extrusion to infinity in the vertex shader (w = 0), a stencil pass with
//! two-sided stencil (IncrementWrap / DecrementWrap) over the depth of the visible
//! surfaces, and a full-screen pass that writes 1 into the light's layer of a shadow mask
//! wherever the count is not 0. The shading pass then skips a light where its mask is
//! set: the "lit pass where the stencil is 0" of every light folded into one pass, so any
//! number of lights costs one shading pass and the sum stays exact (no blending).

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use glam::Mat4;
use wgpu::util::DeviceExt;

use crate::geometry::{GeometryError, Mesh};
use crate::gpu::{shaders, Gpu};
use crate::shadow::raycast::needs_zfail;
use crate::shadow::volume::volume_triangles;
use crate::shadow::{
    Hextree, IgnoredTriangles, Light, Silhouette, SilhouetteMesh, SilhouetteMethod, VolumeTest,
};

/// A mesh prepared for shadow volumes: welded, with adjacency, on the GPU as its
/// vertices (w = 1) followed by their copies to be extruded (w = 0).
pub struct VolumeGeometry {
    /// The welded mesh with adjacency and face planes.
    pub mesh: SilhouetteMesh,
    /// The mesh as given (what lights with a housing leave triangles of).
    source: Mesh,
    /// Per housing, the welded mesh without it (same vertices), built on first use.
    without: Mutex<HashMap<IgnoredTriangles, Arc<SilhouetteMesh>>>,
    hextree: OnceLock<Hextree>,
    vertices: wgpu::Buffer,
    surface: wgpu::Buffer,
    surface_index_count: u32,
}

/// A geometry's triangles split by a light, ready to draw: first those whose front
/// (winding) side is turned away from it or edge-on (the plane's value at the light ≤ 0,
/// what [`SilhouetteMesh`] calls unlit), then those facing it.
pub struct FacesByLight {
    indices: wgpu::Buffer,
    turned_from: u32,
    facing: u32,
}

/// One light's volume, ready to draw.
pub struct LightVolume {
    /// The light.
    pub light: Light,
    /// Counted by z-fail (else z-pass).
    pub zfail: bool,
    /// The silhouette found.
    pub silhouette: Silhouette,
    indices: wgpu::Buffer,
    index_count: u32,
    edges: wgpu::Buffer,
    edge_index_count: u32,
}

impl VolumeGeometry {
    /// Prepares `mesh` (named `name` in errors).
    pub fn new(gpu: &Gpu, mesh: &Mesh, name: &str) -> Result<VolumeGeometry, GeometryError> {
        let sm = SilhouetteMesh::new(mesh, name, 1e-9)?;
        let positions = &sm.mesh().positions;
        let vertices: Vec<[f32; 4]> = [1.0f32, 0.0]
            .iter()
            .flat_map(|&w| {
                positions.iter().map(move |p| {
                    let p = p.as_vec3();
                    [p.x, p.y, p.z, w]
                })
            })
            .collect();
        let vertices = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadow-volume vertices"),
                contents: bytemuck::cast_slice(&vertices),
                usage: wgpu::BufferUsages::VERTEX,
            });
        let triangles: Vec<u32> = sm.mesh().triangles.iter().flatten().copied().collect();
        let surface = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadow-volume surfaces"),
                contents: bytemuck::cast_slice(&triangles),
                usage: wgpu::BufferUsages::INDEX,
            });
        Ok(VolumeGeometry {
            surface_index_count: triangles.len() as u32,
            mesh: sm,
            source: mesh.clone(),
            without: Mutex::new(HashMap::new()),
            hextree: OnceLock::new(),
            vertices,
            surface,
        })
    }

    /// The silhouette of the mesh for `light`.
    pub fn silhouette(&self, light: &Light, method: SilhouetteMethod) -> Silhouette {
        match method {
            SilhouetteMethod::Brute => self.mesh.brute(light),
            SilhouetteMethod::Hextree => self
                .hextree
                .get_or_init(|| Hextree::build(&self.mesh, crate::shadow::hextree::DEFAULT_DEPTH))
                .query(&self.mesh, light),
        }
    }

    /// Whether `test` asks for z-fail for `light` seen through the near rectangle `near`.
    pub fn zfail(&self, light: &Light, test: VolumeTest, near: [glam::DVec3; 4]) -> bool {
        match test {
            VolumeTest::Zpass => false,
            VolumeTest::Zfail => true,
            VolumeTest::Auto => needs_zfail(self.mesh.mesh(), light, near),
        }
    }

    /// The surfaces split by which side `light` reaches: for [`VolumePasses::record_faces_mark`].
    pub fn faces_by_light(&self, gpu: &Gpu, light: &Light) -> FacesByLight {
        let l = self.mesh.light_in_frame(light);
        let triangles = &self.mesh.mesh().triangles;
        let turned = |t: &usize| self.mesh.planes[*t].dot(l) <= 0.0;
        let (from, toward): (Vec<usize>, Vec<usize>) = (0..triangles.len()).partition(turned);
        let indices: Vec<u32> = from
            .iter()
            .chain(&toward)
            .flat_map(|&t| triangles[t].iter().copied())
            .collect();
        let buffer = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("faces by light"),
                contents: bytemuck::cast_slice(if indices.is_empty() {
                    &[0u32; 3]
                } else {
                    &indices
                }),
                usage: wgpu::BufferUsages::INDEX,
            });
        FacesByLight {
            indices: buffer,
            turned_from: 3 * from.len() as u32,
            facing: 3 * toward.len() as u32,
        }
    }

    /// The welded mesh without the source triangles `ignored`, on the same vertices (the
    /// weld depends on the positions only), so its volumes index this geometry's
    /// vertex buffer. `None` when nothing is ignored or nothing would be left.
    fn without(&self, ignored: &IgnoredTriangles) -> Option<Arc<SilhouetteMesh>> {
        if ignored.is_empty() {
            return None;
        }
        let mut cache = self.without.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(m) = cache.get(ignored) {
            return Some(m.clone());
        }
        let kept = Mesh {
            positions: self.source.positions.clone(),
            triangles: ignored
                .kept(self.source.triangles.len())
                .into_iter()
                .flat_map(|r| self.source.triangles[r].iter().copied())
                .collect(),
        };
        let mesh = Arc::new(SilhouetteMesh::new(&kept, "casters without the housing", 1e-9).ok()?);
        debug_assert_eq!(
            mesh.mesh().positions.len(),
            self.mesh.mesh().positions.len()
        );
        cache.insert(ignored.clone(), mesh.clone());
        Some(mesh)
    }

    /// The volume of `light`: its sides, and for z-fail its caps. A light with a housing
    /// (`ignored` triangles) gets the volume of the mesh without it, its silhouette found
    /// by brute force (exactly what the hextree finds; the tree is built for the whole mesh).
    pub fn volume(
        &self,
        gpu: &Gpu,
        light: Light,
        method: SilhouetteMethod,
        zfail: bool,
        ignored: &IgnoredTriangles,
    ) -> LightVolume {
        let without = self.without(ignored);
        let (mesh, silhouette) = match &without {
            Some(m) => (m.as_ref(), m.brute(&light)),
            None => (&self.mesh, self.silhouette(&light, method)),
        };
        let n = self.mesh.mesh().positions.len() as u32;
        let mut triangles = volume_triangles(mesh, &light, &silhouette, false);
        if !zfail {
            // z-pass counts only faces in front of the visible surface: the caps (on the
            // lit faces and at infinity) never are.
            triangles.retain(|t| t.iter().any(|&v| v >= n) && t.iter().any(|&v| v < n));
        }
        let edge_indices: Vec<u32> = silhouette.edges.iter().flatten().copied().collect();
        let buffer = |label: &str, data: &[u32]| {
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents: bytemuck::cast_slice(if data.is_empty() { &[0u32; 3] } else { data }),
                    usage: wgpu::BufferUsages::INDEX,
                })
        };
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        LightVolume {
            light,
            zfail,
            indices: buffer("shadow volume", &flat),
            index_count: flat.len() as u32,
            edges: buffer("silhouette edges", &edge_indices),
            edge_index_count: edge_indices.len() as u32,
            silhouette,
        }
    }
}

/// How far the volumes of lights at infinity reach, instead of to infinity: for
/// orthographic views, whose far plane would cut them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Extrusion {
    /// Every vertex by this length, metres.
    Length(f32),
    /// Every vertex along the light down to the plane z = this (metres; the light above
    /// the horizon, every vertex above the plane).
    DownToZ(f32),
}

/// `VolumeLight` in `shaders/shadow_volume.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct VolumeLightGpu {
    view_proj: [f32; 16],
    light: [f32; 4],
    extrude: [f32; 4],
}

/// Format of the shadow mask: one layer per light, 1 = in its shadow volume.
pub const MASK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R8Uint;

/// How far the finite vertices of a volume are pushed away from the camera, in depth
/// (z/w): 16 steps of a depth value in [0.5, 1) (2^-24 each in 32-bit float and in 24-bit
/// depth alike), so a lit face's own cap counts as behind it in both methods (z-pass
/// ignores it, z-fail sees it enter and its extrusion leave).
pub const VOLUME_DEPTH_BIAS: f32 = 16.0 / 16_777_216.0;

/// Bytes between the per-light uniform records (the dynamic-offset alignment).
const UNIFORM_STRIDE: u64 = 256;

/// The stencil, mask and debug pipelines.
pub struct VolumePasses {
    layout: wgpu::BindGroupLayout,
    zpass: wgpu::RenderPipeline,
    zfail: wgpu::RenderPipeline,
    mark_fronts: wgpu::RenderPipeline,
    mark_backs: wgpu::RenderPipeline,
    mark: wgpu::RenderPipeline,
    debug_volume: wgpu::RenderPipeline,
    debug_edge: wgpu::RenderPipeline,
    surface: wgpu::RenderPipeline,
}

/// Begins a pass drawing into `color` (cleared to 0 when `clear_color`, else kept) over
/// `depth_view`, whose depth is cleared to 1 when `clear_depth` (else kept) and whose
/// stencil is cleared to 0 when `clear_stencil` (else read-only).
fn begin_pass<'e>(
    enc: &'e mut wgpu::CommandEncoder,
    label: &str,
    color: &wgpu::TextureView,
    clear_color: bool,
    depth_view: &wgpu::TextureView,
    clear_depth: bool,
    clear_stencil: bool,
) -> wgpu::RenderPass<'e> {
    let store = wgpu::StoreOp::Store;
    enc.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: color,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: if clear_color {
                    wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                } else {
                    wgpu::LoadOp::Load
                },
                store,
            },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: depth_view,
            depth_ops: Some(wgpu::Operations {
                load: if clear_depth {
                    wgpu::LoadOp::Clear(1.0)
                } else {
                    wgpu::LoadOp::Load
                },
                store,
            }),
            stencil_ops: clear_stencil.then_some(wgpu::Operations {
                load: wgpu::LoadOp::Clear(0),
                store,
            }),
        }),
        ..Default::default()
    })
}

/// The vertex attributes of the volumes and surfaces: one homogeneous position.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x4];

fn stencil_face(
    compare: wgpu::CompareFunction,
    depth_fail: wgpu::StencilOperation,
    pass: wgpu::StencilOperation,
) -> wgpu::StencilFaceState {
    wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: depth_fail,
        pass_op: pass,
    }
}

/// One pipeline of the shadow-volume passes: its entry points, primitives, depth and
/// stencil state, and colour target.
struct PassSpec<'a> {
    label: &'a str,
    vs: &'a str,
    fs: &'a str,
    topology: wgpu::PrimitiveTopology,
    unclipped: bool,
    cull_mode: Option<wgpu::Face>,
    depth_compare: wgpu::CompareFunction,
    depth_write: bool,
    stencil: wgpu::StencilState,
    color: wgpu::ColorTargetState,
}

impl<'a> PassSpec<'a> {
    /// Triangles read from vertex buffers, no culling, no clamping, depth not written.
    fn triangles(label: &'a str, vs: &'a str, fs: &'a str, color: wgpu::ColorTargetState) -> Self {
        PassSpec {
            label,
            vs,
            fs,
            topology: wgpu::PrimitiveTopology::TriangleList,
            unclipped: false,
            cull_mode: None,
            depth_compare: wgpu::CompareFunction::Always,
            depth_write: false,
            stencil: Default::default(),
            color,
        }
    }
}

/// What every shadow-volume pipeline shares: the module, the layouts, the depth format.
struct PassKit<'a> {
    dev: &'a wgpu::Device,
    module: wgpu::ShaderModule,
    pipeline_layout: wgpu::PipelineLayout,
    vertex_layout: wgpu::VertexBufferLayout<'static>,
    format: wgpu::TextureFormat,
}

impl PassKit<'_> {
    fn pipeline(&self, spec: PassSpec<'_>) -> wgpu::RenderPipeline {
        let buffers = [Some(self.vertex_layout.clone())];
        let targets = [Some(spec.color)];
        self.dev
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(spec.label),
                layout: Some(&self.pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &self.module,
                    entry_point: Some(spec.vs),
                    compilation_options: Default::default(),
                    buffers: if spec.vs == "vs_fullscreen" {
                        &[]
                    } else {
                        &buffers
                    },
                },
                primitive: wgpu::PrimitiveState {
                    topology: spec.topology,
                    cull_mode: spec.cull_mode,
                    unclipped_depth: spec.unclipped,
                    ..Default::default()
                },
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: self.format,
                    depth_write_enabled: Some(spec.depth_write),
                    depth_compare: Some(spec.depth_compare),
                    stencil: spec.stencil,
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &self.module,
                    entry_point: Some(spec.fs),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
    }
}

/// A stencil state counting with `front` and `back`.
fn counting(front: wgpu::StencilFaceState, back: wgpu::StencilFaceState) -> wgpu::StencilState {
    wgpu::StencilState {
        front,
        back,
        read_mask: 0xff,
        write_mask: 0xff,
    }
}

impl VolumePasses {
    /// Builds the pipelines for depth-stencil targets of the GPU's format and colour
    /// targets of `debug_format` (the debug views).
    pub fn new(gpu: &Gpu, debug_format: wgpu::TextureFormat) -> VolumePasses {
        let dev = &gpu.device;
        let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shadow volumes"),
            source: wgpu::ShaderSource::Wgsl(shaders::SHADOW_VOLUME.into()),
        });
        let layout = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow volumes"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: true,
                    min_binding_size: wgpu::BufferSize::new(
                        std::mem::size_of::<VolumeLightGpu>() as u64
                    ),
                },
                count: None,
            }],
        });
        let pipeline_layout = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("shadow volumes"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let kit = PassKit {
            dev,
            module,
            pipeline_layout,
            vertex_layout: wgpu::VertexBufferLayout {
                array_stride: 16,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &VERTEX_ATTRIBUTES,
            },
            format: gpu.depth_stencil_format(),
        };
        use wgpu::CompareFunction as C;
        use wgpu::StencilOperation as Op;
        let no_colour = wgpu::ColorTargetState {
            format: MASK_FORMAT,
            blend: None,
            write_mask: wgpu::ColorWrites::empty(),
        };
        // The volumes are pushed a little away from the camera in the vertex shader
        // (`VOLUME_DEPTH_BIAS`), not by the rasterizer's depth bias: on an NVIDIA H200 that
        // bias, 16 steps, left 3.6 % of the pixels wrong with the camera inside a volume
        // (the sides through the eye plane, depth-clamped, got a huge bias); the same
        // bias without the clamp, or the shader's with it, 0 %.
        let zpass = kit.pipeline(PassSpec {
            depth_compare: C::Less,
            stencil: counting(
                stencil_face(C::Always, Op::Keep, Op::IncrementWrap),
                stencil_face(C::Always, Op::Keep, Op::DecrementWrap),
            ),
            ..PassSpec::triangles(
                "shadow volumes z-pass",
                "vs_volume",
                "fs_count",
                no_colour.clone(),
            )
        });
        let zfail = kit.pipeline(PassSpec {
            unclipped: gpu.has_depth_clamp(),
            depth_compare: C::Less,
            stencil: counting(
                stencil_face(C::Always, Op::DecrementWrap, Op::Keep),
                stencil_face(C::Always, Op::IncrementWrap, Op::Keep),
            ),
            ..PassSpec::triangles("shadow volumes z-fail", "vs_volume", "fs_count", no_colour)
        });
        let not_zero = stencil_face(C::NotEqual, Op::Keep, Op::Keep);
        let mark = kit.pipeline(PassSpec {
            stencil: wgpu::StencilState {
                front: not_zero,
                back: not_zero,
                read_mask: 0xff,
                write_mask: 0,
            },
            ..PassSpec::triangles(
                "shadow mask",
                "vs_fullscreen",
                "fs_mark",
                MASK_FORMAT.into(),
            )
        });
        // The surfaces drawn again where they are the surface seen (the same vertex shader
        // gives the same depth), marking them: only their front sides, or only their backs.
        let mark_side = |label, cull| {
            kit.pipeline(PassSpec {
                cull_mode: Some(cull),
                depth_compare: C::Equal,
                ..PassSpec::triangles(label, "vs_surface", "fs_mark", MASK_FORMAT.into())
            })
        };
        let mark_fronts = mark_side("shadow mask: front sides", wgpu::Face::Back);
        let mark_backs = mark_side("shadow mask: back sides", wgpu::Face::Front);
        let blend = wgpu::ColorTargetState {
            format: debug_format,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
            write_mask: wgpu::ColorWrites::ALL,
        };
        let debug_volume = kit.pipeline(PassSpec {
            unclipped: gpu.has_depth_clamp(),
            depth_compare: C::LessEqual,
            ..PassSpec::triangles(
                "debug: shadow volumes",
                "vs_volume",
                "fs_debug_volume",
                blend.clone(),
            )
        });
        let debug_edge = kit.pipeline(PassSpec {
            topology: wgpu::PrimitiveTopology::LineList,
            ..PassSpec::triangles(
                "debug: silhouette edges",
                "vs_volume",
                "fs_debug_edge",
                blend,
            )
        });
        let surface = kit.pipeline(PassSpec {
            depth_compare: C::Less,
            depth_write: true,
            ..PassSpec::triangles(
                "plan surfaces",
                "vs_surface",
                "fs_surface",
                MASK_FORMAT.into(),
            )
        });
        VolumePasses {
            surface,
            layout,
            zpass,
            zfail,
            mark,
            mark_fronts,
            mark_backs,
            debug_volume,
            debug_edge,
        }
    }

    /// A bind group of per-light uniforms (one record per volume, in order; with no
    /// volumes, one record holding only the camera). `extrusion` replaces the extrusion to
    /// infinity of lights at infinity (orthographic plan views).
    pub fn bind_group(
        &self,
        gpu: &Gpu,
        view_proj: Mat4,
        volumes: &[LightVolume],
        extrusion: Option<Extrusion>,
    ) -> wgpu::BindGroup {
        let mut bytes = vec![0u8; (UNIFORM_STRIDE as usize) * volumes.len().max(1)];
        for i in 0..volumes.len().max(1) {
            let l = volumes
                .get(i)
                .map_or(glam::Vec4::ZERO, |v| v.light.0.as_vec4());
            let record = VolumeLightGpu {
                view_proj: view_proj.to_cols_array(),
                light: l.to_array(),
                extrude: match extrusion {
                    None => [0.0, VOLUME_DEPTH_BIAS, 0.0, 0.0],
                    Some(Extrusion::Length(m)) => [m, VOLUME_DEPTH_BIAS, 0.0, 0.0],
                    Some(Extrusion::DownToZ(z)) => [z, VOLUME_DEPTH_BIAS, 0.0, 1.0],
                },
            };
            let at = i * UNIFORM_STRIDE as usize;
            bytes[at..at + std::mem::size_of::<VolumeLightGpu>()]
                .copy_from_slice(bytemuck::bytes_of(&record));
        }
        let uniforms = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("shadow-volume lights"),
                contents: &bytes,
                usage: wgpu::BufferUsages::UNIFORM,
            });
        gpu.bind_group(
            "shadow volumes",
            &self.layout,
            &[(
                0,
                wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                    buffer: &uniforms,
                    offset: 0,
                    size: wgpu::BufferSize::new(std::mem::size_of::<VolumeLightGpu>() as u64),
                }),
            )],
        )
    }

    /// Records, for every light, the stencil count of its volume over the depth in
    /// `depth_view` and its layer of `mask` (1 where the count is not 0, else 0).
    pub fn record_mask(
        &self,
        enc: &mut wgpu::CommandEncoder,
        geometry: &VolumeGeometry,
        volumes: &[LightVolume],
        bind: &wgpu::BindGroup,
        mask: &wgpu::Texture,
        depth_view: &wgpu::TextureView,
    ) {
        for (i, v) in volumes.iter().enumerate() {
            let layer = crate::gpu::layer_view(mask, i as u32);
            let mut pass = begin_pass(enc, "shadow volume", &layer, true, depth_view, false, true);
            if v.index_count == 0 {
                continue;
            }
            let offset = (i as u64 * UNIFORM_STRIDE) as u32;
            pass.set_bind_group(0, bind, &[offset]);
            pass.set_pipeline(if v.zfail { &self.zfail } else { &self.zpass });
            pass.set_vertex_buffer(0, geometry.vertices.slice(..));
            pass.set_index_buffer(v.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..v.index_count, 0, 0..1);
            pass.set_pipeline(&self.mark);
            pass.draw(0..3, 0..1);
        }
    }

    /// Records 1 into `mask` (not cleared) wherever the side of a surface seen in
    /// `depth_view` is turned away from the light `faces` was split by (a light reaches
    /// only the side it faces: the front of a face turned toward it, the back of one
    /// turned away, as an open mesh shows), with the camera of `bind`'s first record,
    /// after [`Self::record_surfaces`]. Closed meshes need it only where a volume misses.
    pub fn record_faces_mark(
        &self,
        enc: &mut wgpu::CommandEncoder,
        geometry: &VolumeGeometry,
        faces: &FacesByLight,
        bind: &wgpu::BindGroup,
        mask: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
    ) {
        let mut pass = begin_pass(enc, "faces marked", mask, false, depth_view, false, false);
        pass.set_bind_group(0, bind, &[0]);
        pass.set_vertex_buffer(0, geometry.vertices.slice(..));
        pass.set_index_buffer(faces.indices.slice(..), wgpu::IndexFormat::Uint32);
        let turned_from = 0..faces.turned_from;
        let facing = faces.turned_from..faces.turned_from + faces.facing;
        for (pipeline, range) in [(&self.mark_fronts, turned_from), (&self.mark_backs, facing)] {
            if !range.is_empty() {
                pass.set_pipeline(pipeline);
                pass.draw_indexed(range, 0, 2..3);
            }
        }
    }

    /// Records the depth of `geometry`'s surfaces and of `ground` (a vertex buffer of
    /// vec4 positions and its index count, drawn as listed triangles) into `depth_view`,
    /// and into `ids` which one each pixel sees (1 ground, 2 geometry, 0 none). The
    /// camera is the first record of `bind`.
    pub fn record_surfaces(
        &self,
        enc: &mut wgpu::CommandEncoder,
        geometry: &VolumeGeometry,
        ground: (&wgpu::Buffer, &wgpu::Buffer, u32),
        bind: &wgpu::BindGroup,
        ids: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
    ) {
        let mut pass = begin_pass(enc, "plan surfaces", ids, true, depth_view, true, true);
        pass.set_pipeline(&self.surface);
        pass.set_bind_group(0, bind, &[0]);
        let (ground_vertices, ground_indices, ground_count) = ground;
        pass.set_vertex_buffer(0, ground_vertices.slice(..));
        pass.set_index_buffer(ground_indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..ground_count, 0, 1..2);
        pass.set_vertex_buffer(0, geometry.vertices.slice(..));
        pass.set_index_buffer(geometry.surface.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..geometry.surface_index_count, 0, 2..3);
    }

    /// Records the debug views over `color`: volumes translucent yellow (depth-tested
    /// against `depth_view`), silhouette edges pink on top.
    #[allow(clippy::too_many_arguments)]
    pub fn record_debug(
        &self,
        enc: &mut wgpu::CommandEncoder,
        geometry: &VolumeGeometry,
        volumes: &[LightVolume],
        bind: &wgpu::BindGroup,
        color: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
        show_volumes: bool,
        show_edges: bool,
    ) {
        let mut pass = begin_pass(
            enc,
            "shadow debug views",
            color,
            false,
            depth_view,
            false,
            false,
        );
        pass.set_vertex_buffer(0, geometry.vertices.slice(..));
        for (i, v) in volumes.iter().enumerate() {
            pass.set_bind_group(0, bind, &[(i as u64 * UNIFORM_STRIDE) as u32]);
            if show_volumes && v.index_count > 0 {
                pass.set_pipeline(&self.debug_volume);
                pass.set_index_buffer(v.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..v.index_count, 0, 0..1);
            }
            if show_edges && v.edge_index_count > 0 {
                pass.set_pipeline(&self.debug_edge);
                pass.set_index_buffer(v.edges.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..v.edge_index_count, 0, 0..1);
            }
        }
    }
}
