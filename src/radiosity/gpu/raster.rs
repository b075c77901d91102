//! Visibility maps rasterized by compute shaders (`shaders/radiosity_raster.wgsl`).
//!
//! A render pass runs on the units of a GPU that do graphics; on an H100 or H200 that is a
//! handful of its 132 (a map of the conference room's 250 000 triangles took about 290 µs
//! on an H200, about 1 ns a triangle, whatever the map's size). A compute pass runs on
//! all of them. Each (tile, triangle) pair is one thread: it tests the triangle's texels
//! by their rays in clip space and keeps the nearest distance with an atomic; a triangle
//! whose box holds more than 64 texels goes to a list whose entries the workgroups of a
//! second pass take in turn. A last pass writes the batch's tiles into the atlas, so the
//! receive pass, the kept maps and everything after them read the same texture either
//! way. The maps are the render pass's to within a texel along edges (its fill rule
//! leaves out texels whose centre lies exactly on an edge; this one keeps them, and those
//! within the rounding of an edge function: on an H200, whose compiler fuses
//! multiply-adds, exact ties left cracks along shared edges, and 2.1 of 80 lm passed a
//! solid panel; `tests/gpu/alpha_masks.rs`). The stereographic map is the exception: here each
//! texel's ray (the direction its centre projects from) is tested against the triangle in
//! 3-D and the texels tested are the box of the arcs its edges project to, so the map is
//! exact, where the render pass draws chords between the projected vertices (and a sliver
//! between chord and rim shows what lies behind a wall's foot:
//! `tests/gpu/radiosity.rs`, `light_stays_in_its_closed_room_with_either_map`).

use super::super::atlas::VisibilityAtlas;
use super::{dispatch_groups, FACE_STRIDE};
use crate::gpu::Gpu;
use crate::render::layouts::{buffer_binding, entry};

/// How the visibility maps are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Raster {
    /// Compute on a GPU of its own, the render pipeline on a CPU adapter (lavapipe, whose
    /// rasterizer is the faster there) and wherever alpha-masked casters are drawn.
    #[default]
    Auto,
    /// The render pipeline: the GPU's rasterizer, depth test and a distance target.
    Hardware,
    /// Compute shaders on every unit of the GPU (not with alpha-masked casters); exact
    /// stereographic maps.
    Compute,
}

impl Raster {
    /// What `self` means on `gpu` for a scene with or without alpha-masked casters:
    /// never [`Raster::Auto`]. An explicit [`Raster::Compute`] with masked casters is the
    /// caller's to refuse ([`Raster::refusal`]); here it falls back to the render pass.
    pub fn resolve(self, gpu: &Gpu, masked: bool) -> Raster {
        let software = gpu.adapter.get_info().device_type == wgpu::DeviceType::Cpu;
        match self {
            Raster::Compute if !masked => Raster::Compute,
            Raster::Auto if !masked && !software => Raster::Compute,
            _ => Raster::Hardware,
        }
    }

    /// Why `self` cannot draw a scene with or without alpha-masked casters, if it cannot.
    pub fn refusal(self, masked: bool) -> Option<&'static str> {
        (self == Raster::Compute && masked).then_some(
            "does not draw alpha-masked casters (their holes need the render pass): use \
             auto or hardware",
        )
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Raster::Auto => "auto",
            Raster::Hardware => "hardware",
            Raster::Compute => "compute",
        }
    }
}

/// A listed large triangle: its tile and index.
const LARGE_ENTRY_BYTES: u64 = 8;
/// Room for this many large (tile, triangle) pairs per batch; past it a triangle is drawn
/// by its own thread (slower, never lost).
const LARGE_CAPACITY: u32 = 1 << 20;

/// Workgroups of the large pass for a batch of `tiles` tiles: 64 a tile (most tiles hold
/// fewer large triangles; a group takes the next when it is done), within one row of a
/// dispatch, and at least 256. llvmpipe ends a thread's loops after 65 535 iterations in
/// all: a group draws about 1 024 texels a thread per triangle that fills a 256² tile, so
/// about 60 such triangles a group, some 4 000 a tile, stay within it.
fn large_groups(tiles: u32) -> u32 {
    tiles.saturating_mul(64).clamp(256, 65_535)
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct RasterParams {
    item_count: u32,
    thread_count: u32,
    size: u32,
    tiles: u32,
    columns: u32,
    large_capacity: u32,
    _pad: [u32; 2],
}

/// The compute rasterizer's pipelines, built once per device ([`Gpu::cached`]).
pub struct RasterPipelines {
    layout: wgpu::BindGroupLayout,
    small: wgpu::ComputePipeline,
    large_pass: wgpu::ComputePipeline,
    resolve: wgpu::ComputePipeline,
}

/// The compute rasterizer: its pipelines and a solver's buffers.
pub struct ComputeRaster {
    pipelines: std::sync::Arc<RasterPipelines>,
    /// Per texel of the batch's tiles, the nearest distance (inverted bits).
    nearest: Option<wgpu::Buffer>,
    /// Listed large triangles.
    large: wgpu::Buffer,
    /// The list's length.
    control: wgpu::Buffer,
}

/// One batch's work: per tile, the triangle ranges it draws.
pub struct RasterWork {
    /// (tile, first triangle, triangles, first thread).
    items: Vec<[u32; 4]>,
    threads: u32,
}

impl RasterWork {
    /// No work yet.
    pub fn new() -> RasterWork {
        RasterWork {
            items: Vec::new(),
            threads: 0,
        }
    }

    /// Tile `tile` draws the index range `first..first + count` (three per triangle).
    pub fn push(&mut self, tile: u32, first_index: u32, index_count: u32) {
        let triangles = index_count / 3;
        if triangles > 0 {
            self.items
                .push([tile, first_index / 3, triangles, self.threads]);
            self.threads += triangles;
        }
    }
}

impl Default for RasterWork {
    fn default() -> RasterWork {
        RasterWork::new()
    }
}

impl RasterPipelines {
    /// Compiles the pipelines.
    pub fn new(gpu: &Gpu) -> RasterPipelines {
        use wgpu::BufferBindingType as B;
        let dev = &gpu.device;
        let compute = wgpu::ShaderStages::COMPUTE;
        let read = B::Storage { read_only: true };
        let write = B::Storage { read_only: false };
        let mut entries: Vec<_> = [B::Uniform, read, read, read, read, write, write, write]
            .iter()
            .enumerate()
            .map(|(i, &k)| entry(i as u32, compute, buffer_binding(k, false)))
            .collect();
        entries.push(entry(
            8,
            compute,
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format: super::super::atlas::MAP_FORMAT,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        ));
        let layout = dev.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("radiosity raster"),
            entries: &entries,
        });
        let pipeline_layout = dev.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("radiosity raster"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = dev.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("radiosity raster"),
            source: wgpu::ShaderSource::Wgsl(crate::gpu::shaders::radiosity_raster().into()),
        });
        let pipeline = |name: &str| {
            dev.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(name),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(name),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        RasterPipelines {
            small: pipeline("raster_small"),
            large_pass: pipeline("raster_large"),
            resolve: pipeline("raster_resolve"),
            layout,
        }
    }
}

impl ComputeRaster {
    /// A solver's rasterizer on `pipelines` (the device's).
    pub fn new(gpu: &Gpu, pipelines: std::sync::Arc<RasterPipelines>) -> ComputeRaster {
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        use wgpu::BufferUsages as U;
        ComputeRaster {
            pipelines,
            nearest: None,
            large: buffer(
                "raster large triangles",
                LARGE_ENTRY_BYTES * u64::from(LARGE_CAPACITY),
                U::STORAGE,
            ),
            control: buffer("raster control", 16, U::STORAGE | U::COPY_DST),
        }
    }

    /// Records the maps of `work` (its tiles the first `tiles` of `atlas`, their faces
    /// in `faces` at [`FACE_STRIDE`]) from the mesh `positions` / `indices`, in one
    /// compute pass timed by `timestamps`.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        gpu: &Gpu,
        enc: &mut wgpu::CommandEncoder,
        atlas: &VisibilityAtlas,
        (positions, indices): (&wgpu::Buffer, &wgpu::Buffer),
        faces: &wgpu::Buffer,
        work: &RasterWork,
        tiles: u32,
        timestamps: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let texels = u64::from(atlas.size) * u64::from(atlas.size);
        let needed = 4 * texels * u64::from(atlas.capacity());
        if self.nearest.as_ref().is_none_or(|b| b.size() < needed) {
            self.nearest = Some(gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("raster nearest distances"),
                size: needed,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }));
        }
        let nearest = self.nearest.as_ref().expect("allocated above");
        let params = RasterParams {
            item_count: work.items.len() as u32,
            thread_count: work.threads,
            size: atlas.size,
            tiles,
            columns: atlas.columns,
            large_capacity: LARGE_CAPACITY,
            _pad: [0; 2],
        };
        let params_buf = gpu.uniform_buffer("raster params", &params);
        // One unused item where there is no work (a binding is never empty).
        let items: &[[u32; 4]] = if work.items.is_empty() {
            &[[0; 4]]
        } else {
            &work.items
        };
        let items_buf = gpu.buffer_with(
            "raster items",
            bytemuck::cast_slice(items),
            wgpu::BufferUsages::STORAGE,
        );
        let bind = gpu.bind_group(
            "radiosity raster",
            &self.pipelines.layout,
            &[
                (0, params_buf.as_entire_binding()),
                (1, positions.as_entire_binding()),
                (2, indices.as_entire_binding()),
                (3, faces.as_entire_binding()),
                (4, items_buf.as_entire_binding()),
                (5, nearest.as_entire_binding()),
                (6, self.large.as_entire_binding()),
                (7, self.control.as_entire_binding()),
                (8, wgpu::BindingResource::TextureView(&atlas.view)),
            ],
        );
        enc.clear_buffer(nearest, 0, Some(4 * texels * u64::from(tiles)));
        enc.clear_buffer(&self.control, 0, None);
        let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("visibility (compute)"),
            timestamp_writes: timestamps,
        });
        let p = &self.pipelines;
        pass.set_bind_group(0, &bind, &[]);
        pass.set_pipeline(&p.small);
        dispatch_groups(&mut pass, work.threads.div_ceil(64));
        pass.set_pipeline(&p.large_pass);
        pass.dispatch_workgroups(large_groups(tiles), 1, 1);
        pass.set_pipeline(&p.resolve);
        let resolved = u64::from(tiles) * texels;
        dispatch_groups(&mut pass, resolved.div_ceil(64) as u32);
    }
}

/// The face records' stride the shader assumes (`FaceSlot`).
const _: () = assert!(FACE_STRIDE == 256);
