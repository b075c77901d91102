//! The geometry passes: a depth pre-pass and the shading pass (all luminaires in one
//! pass, into the HDR target). Shading pipelines are specialised per light model with the
//! WGSL override constant `LIGHT_MODEL`, so the interpolation costs nothing when unused.

use std::collections::HashMap;
use std::sync::Mutex;

use glam::Mat4;

use super::gpu_scene::{GpuScene, Vertex};
use super::layouts::Layouts;
use super::targets::{Targets, HDR_FORMAT};
use crate::gpu::{shaders, Gpu};
use crate::photometry::Interp;
use crate::render::ldt::interp_code;
use crate::scene::{Camera, Projection};

/// How luminaires emit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LightModel {
    /// A plain point light of constant intensity (I_max): the benchmark's baseline.
    Point,
    /// The luminaire's distribution, sampled with an interpolation.
    Ldt(Interp),
    /// Catmull-Rom from the dense table: one filtered fetch (see [`crate::render::ldt::table`]).
    CatmullRomTable,
    /// Catmull-Rom resampled into a cube map: one filtered fetch by direction, no angles
    /// (see [`crate::render::ldt::cube`]).
    CatmullRomCube,
}

impl LightModel {
    /// The value of the WGSL `LIGHT_MODEL` override.
    pub fn code(self) -> u32 {
        match self {
            LightModel::Point => 4,
            LightModel::Ldt(i) => interp_code(i),
            LightModel::CatmullRomTable => 5,
            LightModel::CatmullRomCube => 6,
        }
    }

    /// The interpolation it stands for (Catmull-Rom for the point baseline and the table).
    pub fn interp(self) -> Interp {
        match self {
            LightModel::Ldt(i) => i,
            LightModel::Point | LightModel::CatmullRomTable | LightModel::CatmullRomCube => {
                Interp::CatmullRom
            }
        }
    }
}

/// `Frame` in `shaders/scene.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FrameGpu {
    view_proj: [f32; 16],
    eye: [f32; 4],
    view_dir: [f32; 4],
    light_count: u32,
    light_map: u32,
    pad: [u32; 2],
}

/// The depth pre-pass and the shading pipelines.
pub struct ScenePasses {
    module: wgpu::ShaderModule,
    layout: wgpu::PipelineLayout,
    /// The depth pipelines of opaque and of alpha-masked materials.
    depth: [wgpu::RenderPipeline; 2],
    /// The shading pipelines by light model and whether they test alpha masks.
    shade: Mutex<HashMap<(LightModel, bool), wgpu::RenderPipeline>>,
}

impl ScenePasses {
    /// Compiles the scene shader and the depth pipeline.
    pub fn new(gpu: &Gpu, layouts: &Layouts) -> ScenePasses {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("scene"),
                source: wgpu::ShaderSource::Wgsl(shaders::scene().into()),
            });
        let layout = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("scene"),
                bind_group_layouts: &[Some(&layouts.frame), Some(&layouts.material)],
                immediate_size: 0,
            });
        // Opaque materials draw depth without a fragment stage (early depth tests); the
        // alpha-masked ones with one that discards their holes.
        let depth_pipeline = |masked: bool| {
            let constants = [("ALPHA_TEST", f64::from(u8::from(masked)))];
            gpu.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: Some("depth pre-pass"),
                    layout: Some(&layout),
                    vertex: wgpu::VertexState {
                        module: &module,
                        entry_point: Some("vs_depth"),
                        compilation_options: Default::default(),
                        buffers: &[Some(Vertex::LAYOUT)],
                    },
                    primitive: wgpu::PrimitiveState::default(),
                    depth_stencil: Some(depth_state(gpu, true, wgpu::CompareFunction::Less)),
                    multisample: Default::default(),
                    fragment: masked.then(|| wgpu::FragmentState {
                        module: &module,
                        entry_point: Some("fs_depth"),
                        compilation_options: wgpu::PipelineCompilationOptions {
                            constants: &constants,
                            ..Default::default()
                        },
                        targets: &[],
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        };
        let depth = [depth_pipeline(false), depth_pipeline(true)];
        ScenePasses {
            module,
            layout,
            depth,
            shade: Mutex::new(HashMap::new()),
        }
    }

    /// The shading pipeline of `model`, testing alpha masks when `masked` (built on first
    /// use: a shader that can discard loses early depth tests, so opaque materials get
    /// one that cannot).
    fn shade_pipeline(&self, gpu: &Gpu, model: LightModel, masked: bool) -> wgpu::RenderPipeline {
        let mut cache = self.shade.lock().unwrap_or_else(|e| e.into_inner());
        cache
            .entry((model, masked))
            .or_insert_with(|| {
                let constants = [
                    ("LIGHT_MODEL", model.code() as f64),
                    ("ALPHA_TEST", f64::from(u8::from(masked))),
                ];
                let options = wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                };
                gpu.device
                    .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                        label: Some("shade"),
                        layout: Some(&self.layout),
                        vertex: wgpu::VertexState {
                            module: &self.module,
                            entry_point: Some("vs_main"),
                            compilation_options: options.clone(),
                            buffers: &[Some(Vertex::LAYOUT)],
                        },
                        primitive: wgpu::PrimitiveState::default(),
                        depth_stencil: Some(depth_state(
                            gpu,
                            false,
                            wgpu::CompareFunction::LessEqual,
                        )),
                        multisample: Default::default(),
                        fragment: Some(wgpu::FragmentState {
                            module: &self.module,
                            entry_point: Some("fs_main"),
                            compilation_options: options,
                            targets: &[Some(wgpu::ColorTargetState {
                                format: HDR_FORMAT,
                                blend: None,
                                write_mask: wgpu::ColorWrites::ALL,
                            })],
                        }),
                        multiview_mask: None,
                        cache: None,
                    })
            })
            .clone()
    }

    /// The frame bind group (group 0) for `camera` looking at `scene` in `targets`, lit
    /// with `model`.
    #[allow(clippy::too_many_arguments)]
    pub fn frame_bind_group(
        &self,
        gpu: &Gpu,
        layouts: &Layouts,
        scene: &GpuScene,
        camera: &Camera,
        targets: &Targets,
        model: LightModel,
        shadow: &[(u32, wgpu::BindingResource<'_>)],
    ) -> wgpu::BindGroup {
        let tables = scene.lights.tables(gpu, model);
        let aspect = targets.width as f64 / targets.height as f64;
        let view_proj: Mat4 = camera.view_projection(aspect);
        let dir = (camera.look_at - camera.position).normalize().as_vec3();
        let ortho = matches!(camera.projection, Projection::Orthographic { .. });
        let eye = camera.position.as_vec3();
        let frame = FrameGpu {
            view_proj: view_proj.to_cols_array(),
            eye: [eye.x, eye.y, eye.z, ortho as u32 as f32],
            view_dir: [dir.x, dir.y, dir.z, 0.0],
            light_count: scene.lights.count,
            light_map: u32::from(scene.has_light_map),
            pad: [0; 2],
        };
        let buffer = gpu.uniform_buffer("frame", &frame);
        let mut entries = vec![
            (0, buffer.as_entire_binding()),
            (1, scene.lights.buffer.as_entire_binding()),
            (
                2,
                wgpu::BindingResource::TextureView(&scene.lights.atlas.view),
            ),
            (3, scene.lights.atlas.info.as_entire_binding()),
            (6, scene.lights.sectors.as_entire_binding()),
            (7, wgpu::BindingResource::TextureView(&tables.view)),
            (14, wgpu::BindingResource::Sampler(&tables.sampler)),
            (15, wgpu::BindingResource::TextureView(&tables.cube)),
            (12, wgpu::BindingResource::TextureView(&scene.light_map)),
            (
                13,
                wgpu::BindingResource::Sampler(&layouts.light_map_sampler),
            ),
        ];
        entries.extend(shadow.iter().cloned());
        gpu.bind_group("frame", &layouts.frame, &entries)
    }

    /// Records the depth pre-pass into `enc`.
    pub fn record_depth(
        &self,
        enc: &mut wgpu::CommandEncoder,
        frame: &wgpu::BindGroup,
        scene: &GpuScene,
        targets: &Targets,
    ) {
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth pre-pass"),
            color_attachments: &[],
            depth_stencil_attachment: Some(depth_attachment(&targets.depth_view, true)),
            ..Default::default()
        });
        pass.set_bind_group(0, frame, &[]);
        scene.draw(&mut pass, [&self.depth[0], &self.depth[1]]);
    }

    /// Records the shading pass into `enc` (after the depth pre-pass). The HDR target is
    /// cleared to luminance 0 with illuminance −1 (no surface).
    pub fn record_shade(
        &self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        frame: &wgpu::BindGroup,
        scene: &GpuScene,
        targets: &Targets,
        model: LightModel,
    ) {
        let shade = [false, true].map(|masked| self.shade_pipeline(gpu, model, masked));
        let mut pass = enc.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("shade"),
            // a = −1 marks pixels that show no surface.
            color_attachments: &[Some(crate::gpu::cleared_attachment(
                &targets.shade_view,
                wgpu::Color {
                    r: 0.0,
                    g: 0.0,
                    b: 0.0,
                    a: -1.0,
                },
            ))],
            depth_stencil_attachment: Some(depth_attachment(&targets.depth_view, false)),
            ..Default::default()
        });
        pass.set_bind_group(0, frame, &[]);
        scene.draw(&mut pass, [&shade[0], &shade[1]]);
    }
}

fn depth_state(gpu: &Gpu, write: bool, compare: wgpu::CompareFunction) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: gpu.depth_stencil_format(),
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

fn depth_attachment(
    view: &wgpu::TextureView,
    clear: bool,
) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: if clear {
                wgpu::LoadOp::Clear(1.0)
            } else {
                wgpu::LoadOp::Load
            },
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: clear.then_some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(0),
            store: wgpu::StoreOp::Store,
        }),
    }
}
