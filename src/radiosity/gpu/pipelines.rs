//! The radiosity solver's GPU programs, built once per device ([`Gpu::cached`]): the
//! compute passes of `radiosity.wgsl` and the visibility maps' render pipelines, with
//! their bind group layouts.

use super::super::atlas;
use crate::gpu::Gpu;
use crate::render::layouts::{buffer_binding, entry};

/// The solver's pipelines and layouts.
pub(super) struct Pipelines {
    pub(super) shooter_sums: wgpu::ComputePipeline,
    pub(super) large_shooter_sums: wgpu::ComputePipeline,
    pub(super) select: wgpu::ComputePipeline,
    pub(super) gather: wgpu::ComputePipeline,
    pub(super) clear: wgpu::ComputePipeline,
    pub(super) restore: wgpu::ComputePipeline,
    /// Gives charts that held ([`super::deferred`]) what they held back.
    pub(super) release_held_back: wgpu::ComputePipeline,
    pub(super) receive: wgpu::ComputePipeline,
    /// A virtual cell's receive: through its windows ([`super::virtual_cells`]).
    pub(super) receive_through_windows: wgpu::ComputePipeline,
    pub(super) visibility: wgpu::RenderPipeline,
    /// A virtual cell's: nothing beyond its clip plane ([`super::virtual_cells`]).
    pub(super) visibility_clipped: wgpu::RenderPipeline,
    /// Clears one tile of the atlas (depth and distance), drawn in its viewport.
    pub(super) clear_tile: wgpu::RenderPipeline,
    pub(super) shot_layout: wgpu::BindGroupLayout,
    pub(super) face_layout: wgpu::BindGroupLayout,
    /// The visibility shader (the masked casters' pipeline is built from it).
    pub(super) vis_module: wgpu::ShaderModule,
}

/// The solver's bind group 0: `buffers` at bindings 0, 1, … (radiosity.wgsl).
pub(super) fn shared_bind_group(
    gpu: &Gpu,
    pipelines: &Pipelines,
    buffers: &[wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<(u32, wgpu::BindingResource<'_>)> = buffers
        .iter()
        .enumerate()
        .map(|(k, b)| (k as u32, b.as_entire_binding()))
        .collect();
    gpu.bind_group(
        "radiosity",
        &pipelines.shooter_sums.get_bind_group_layout(0),
        &entries,
    )
}

impl Pipelines {
    pub(super) fn new(gpu: &Gpu) -> Pipelines {
        let dev = &gpu.device;
        let shared_layout = shared_layout(dev);
        let shot_layout = shot_layout(dev);
        let face_layout = face_layout(dev);
        let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("radiosity"),
            source: wgpu::ShaderSource::Wgsl(crate::gpu::shaders::radiosity().into()),
        });
        let shared_only = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("radiosity"),
            bind_group_layouts: &[Some(&shared_layout)],
            immediate_size: 0,
        });
        let with_shot = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("radiosity receive"),
            bind_group_layouts: &[Some(&shared_layout), Some(&shot_layout)],
            immediate_size: 0,
        });
        let compute_pipeline = |name: &str, layout: &wgpu::PipelineLayout| {
            dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(layout),
                module: &module,
                entry_point: Some(name),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let vis_module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("radiosity visibility"),
            source: wgpu::ShaderSource::Wgsl(crate::gpu::shaders::radiosity_visibility().into()),
        });
        let vis_layout = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("radiosity visibility"),
            bind_group_layouts: &[Some(&face_layout)],
            immediate_size: 0,
        });
        let visibility_pipeline = |fragment: &str| {
            gpu.caster_depth_pipeline(
                "radiosity visibility",
                &vis_layout,
                &vis_module,
                ("vs_visibility", fragment),
                crate::gpu::POSITION_LAYOUT,
                atlas::DEPTH_FORMAT,
                &[Some(atlas::MAP_FORMAT.into())],
            )
        };
        let visibility = visibility_pipeline("fs_visibility");
        let visibility_clipped = visibility_pipeline("fs_visibility_clipped");
        let clear_tile = clear_tile_pipeline(dev, &vis_layout, &vis_module);
        Pipelines {
            clear_tile,
            shooter_sums: compute_pipeline("shooter_sums", &shared_only),
            large_shooter_sums: compute_pipeline("large_shooter_sums", &shared_only),
            select: compute_pipeline("select_shooter", &shared_only),
            gather: compute_pipeline("gather_patches", &shared_only),
            clear: compute_pipeline("clear_shooter", &shared_only),
            restore: compute_pipeline("restore_unshot", &shared_only),
            release_held_back: compute_pipeline("release_held_back", &shared_only),
            receive: compute_pipeline("receive", &with_shot),
            receive_through_windows: compute_pipeline("receive_through_windows", &with_shot),
            visibility,
            visibility_clipped,
            shot_layout,
            face_layout,
            vis_module,
        }
    }
}

/// Bind group 0 of every compute pass: the buffers of [`shared_bind_group`], binding by
/// binding (uniform parameters, then storage read-only or read-write as radiosity.wgsl
/// declares them).
fn shared_layout(dev: &wgpu::Device) -> wgpu::BindGroupLayout {
    use wgpu::BufferBindingType as B;
    let compute = wgpu::ShaderStages::COMPUTE;
    let kinds = [
        B::Uniform,
        B::Storage { read_only: true },
        B::Storage { read_only: true },
        B::Storage { read_only: false },
        B::Storage { read_only: false },
        B::Storage { read_only: true },
        B::Storage { read_only: false },
        B::Storage { read_only: true },
        B::Storage { read_only: false },
        B::Storage { read_only: true },
        B::Storage { read_only: false },
        B::Storage { read_only: true },
        B::Storage { read_only: false },
        B::Storage { read_only: true },
    ];
    let entries: Vec<_> = kinds
        .iter()
        .enumerate()
        .map(|(i, &k)| entry(i as u32, compute, buffer_binding(k, false)))
        .collect();
    dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("radiosity"),
        entries: &entries,
    })
}

/// Bind group 1 of the receive passes: the shot's record (at a dynamic offset), the
/// visibility atlas, the shot records, the windows' corners and the receiver runs.
fn shot_layout(dev: &wgpu::Device) -> wgpu::BindGroupLayout {
    use wgpu::BufferBindingType as B;
    let compute = wgpu::ShaderStages::COMPUTE;
    dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("radiosity shot"),
        entries: &[
            entry(0, compute, buffer_binding(B::Uniform, true)),
            entry(
                1,
                compute,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            ),
            entry(
                2,
                compute,
                buffer_binding(B::Storage { read_only: true }, false),
            ),
            entry(
                3,
                compute,
                buffer_binding(B::Storage { read_only: true }, false),
            ),
            entry(
                4,
                compute,
                buffer_binding(B::Storage { read_only: true }, false),
            ),
        ],
    })
}

/// The visibility passes' bind group: one face's record at a dynamic offset.
fn face_layout(dev: &wgpu::Device) -> wgpu::BindGroupLayout {
    use wgpu::BufferBindingType as B;
    dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("visibility face"),
        entries: &[entry(
            0,
            wgpu::ShaderStages::VERTEX_FRAGMENT,
            buffer_binding(B::Uniform, true),
        )],
    })
}

/// Clears one tile of the atlas (depth and distance), drawn as a triangle over its
/// viewport.
fn clear_tile_pipeline(
    dev: &wgpu::Device,
    vis_layout: &wgpu::PipelineLayout,
    vis_module: &wgpu::ShaderModule,
) -> wgpu::RenderPipeline {
    dev.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("visibility tile clear"),
        layout: Some(vis_layout),
        vertex: wgpu::VertexState {
            module: vis_module,
            entry_point: Some("vs_clear"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: atlas::DEPTH_FORMAT,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Always),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: vis_module,
            entry_point: Some("fs_clear"),
            compilation_options: Default::default(),
            targets: &[Some(atlas::MAP_FORMAT.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}
