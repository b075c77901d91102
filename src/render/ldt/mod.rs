//! Light distribution textures on the GPU: an R32Float texture array (one layer per
//! luminaire, one row per C plane) plus per-layer grid information, and a compute probe
//! that samples a layer at many directions with the WGSL sampler of `shaders/ldt.wgsl`.

use bytemuck::Zeroable;
use wgpu::util::DeviceExt;

pub mod cube;
pub mod table;

use crate::gpu::{shaders, Gpu, GpuError};
use crate::photometry::{Interp, LdtTexture};

/// Per-layer grid information, laid out as `LdtInfo` in WGSL.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LdtInfoGpu {
    c_count: u32,
    gamma_count: u32,
    gamma_start: f32,
    gamma_step: f32,
    pole0: u32,
    pole180: u32,
    pad: [u32; 2],
}

/// The WGSL code of an interpolation method.
pub fn interp_code(interp: Interp) -> u32 {
    match interp {
        Interp::Nearest => 0,
        Interp::Bilinear => 1,
        Interp::CatmullRom => 2,
        Interp::Monotone => 3,
    }
}

/// Several LDTs uploaded as one texture array.
pub struct LdtAtlas {
    /// The texture array.
    pub texture: wgpu::Texture,
    /// A `D2Array` view of it.
    pub view: wgpu::TextureView,
    /// `array<LdtInfo>`, one per layer.
    pub info: wgpu::Buffer,
    /// Number of layers.
    pub layers: usize,
}

impl LdtAtlas {
    /// A one-layer atlas of zeros, for scenes without luminaires (a texture array cannot be
    /// empty).
    pub fn empty(gpu: &Gpu) -> LdtAtlas {
        let mut atlas = LdtAtlas::upload(gpu, 1, 2, &[0.0, 0.0], &[LdtInfoGpu::zeroed()]);
        atlas.layers = 0;
        atlas
    }

    /// Uploads `textures` (at least one).
    pub fn new(gpu: &Gpu, textures: &[&LdtTexture]) -> LdtAtlas {
        assert!(!textures.is_empty(), "an atlas needs at least one LDT");
        let width = textures.iter().map(|t| t.gamma_count).max().unwrap_or(1) as u32;
        let height = textures.iter().map(|t| t.c_count).max().unwrap_or(1) as u32;
        let mut texels = vec![0f32; (width * height) as usize * textures.len()];
        let mut info = Vec::with_capacity(textures.len());
        for (layer, t) in textures.iter().enumerate() {
            let base = layer * (width * height) as usize;
            for c in 0..t.c_count {
                let row = &t.data[c * t.gamma_count..(c + 1) * t.gamma_count];
                let at = base + c * width as usize;
                texels[at..at + t.gamma_count].copy_from_slice(row);
            }
            info.push(LdtInfoGpu {
                c_count: t.c_count as u32,
                gamma_count: t.gamma_count as u32,
                gamma_start: t.gamma_start_deg as f32,
                gamma_step: t.gamma_step_deg as f32,
                pole0: t.starts_at_pole() as u32,
                pole180: t.ends_at_pole() as u32,
                pad: [0; 2],
            });
        }
        LdtAtlas::upload(gpu, width, height, &texels, &info)
    }

    fn upload(gpu: &Gpu, width: u32, height: u32, texels: &[f32], info: &[LdtInfoGpu]) -> LdtAtlas {
        let layers = info.len();
        let texture = gpu.device.create_texture_with_data(
            &gpu.queue,
            &wgpu::TextureDescriptor {
                label: Some("ldt atlas"),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: layers as u32,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::R32Float,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            bytemuck::cast_slice(texels),
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        });
        let info = gpu
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("ldt info"),
                contents: bytemuck::cast_slice(info),
                usage: wgpu::BufferUsages::STORAGE,
            });
        LdtAtlas {
            texture,
            view,
            info,
            layers,
        }
    }
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ProbeParams {
    layer: u32,
    interp: u32,
    count: u32,
    pad: u32,
}

/// The compute pipeline that samples an LDT layer at many directions.
pub struct LdtProbe {
    pipeline: wgpu::ComputePipeline,
}

impl LdtProbe {
    /// Builds the pipeline.
    pub fn new(gpu: &Gpu) -> LdtProbe {
        let source = shaders::ldt_probe();
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("ldt probe"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("ldt probe"),
                layout: None,
                module: &module,
                entry_point: Some("probe"),
                compilation_options: Default::default(),
                cache: None,
            });
        LdtProbe { pipeline }
    }

    /// Normalised intensities of layer `layer` toward `directions` (luminaire frame).
    pub fn run(
        &self,
        gpu: &Gpu,
        atlas: &LdtAtlas,
        layer: usize,
        interp: Interp,
        directions: &[[f32; 3]],
    ) -> Result<Vec<f32>, GpuError> {
        let dirs: Vec<[f32; 4]> = directions.iter().map(|d| [d[0], d[1], d[2], 0.0]).collect();
        let n = dirs.len().max(1);
        let dev = &gpu.device;
        let dir_buf = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("probe directions"),
            contents: bytemuck::cast_slice(if dirs.is_empty() {
                &[[0f32; 4]]
            } else {
                &dirs[..]
            }),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let params = ProbeParams {
            layer: layer as u32,
            interp: interp_code(interp),
            count: dirs.len() as u32,
            pad: 0,
        };
        let param_buf = gpu.uniform_buffer("probe params", &params);
        let out = gpu.output_buffer("probe results", (n * 4) as u64);
        let bind = gpu.bind_group(
            "probe",
            &self.pipeline.get_bind_group_layout(0),
            &[
                (0, wgpu::BindingResource::TextureView(&atlas.view)),
                (1, atlas.info.as_entire_binding()),
                (2, param_buf.as_entire_binding()),
                (3, dir_buf.as_entire_binding()),
                (4, out.as_entire_binding()),
            ],
        );
        let workgroups = [(n as u32).div_ceil(64), 1, 1];
        let mut v = gpu.dispatch_and_read(&self.pipeline, &bind, workgroups, &out)?;
        v.truncate(dirs.len());
        Ok(v)
    }
}
