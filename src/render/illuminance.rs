//! Direct illuminance at points, on the GPU with the renderer's own WGSL lighting code
//! (`shaders/lighting.wgsl`) and on the CPU as the reference.

use glam::DVec3;
use wgpu::util::DeviceExt;

use super::gpu_scene::GpuLights;
use super::passes::LightModel;
use crate::gpu::{shaders, Gpu, GpuError};
use crate::photometry::Interp;
use crate::scene::PlacedLuminaire;

/// A point on a surface: position (metres) and normal (need not be unit length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position.
    pub position: DVec3,
    /// Normal.
    pub normal: DVec3,
}

/// The CPU reference: Σ over luminaires of I · cos θ / d², lux.
pub fn illuminance_cpu(luminaires: &[PlacedLuminaire], p: &SurfacePoint, interp: Interp) -> f64 {
    let n = p.normal.normalize_or_zero();
    luminaires
        .iter()
        .map(|l| l.illuminance_at(p.position, n, interp))
        .sum()
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PointParams {
    count: u32,
    light_count: u32,
    pad: [u32; 2],
}

/// The compute pipeline of `illuminance_points`.
pub struct IlluminanceProbe {
    pipeline: wgpu::ComputePipeline,
}

impl IlluminanceProbe {
    /// Builds the pipeline for `model`.
    pub fn new(gpu: &Gpu, model: LightModel) -> IlluminanceProbe {
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("illuminance points"),
                source: wgpu::ShaderSource::Wgsl(shaders::illuminance_points().into()),
            });
        let constants = [("LIGHT_MODEL", model.code() as f64)];
        let pipeline = gpu
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("illuminance points"),
                layout: None,
                module: &module,
                entry_point: Some("illuminance_points"),
                compilation_options: wgpu::PipelineCompilationOptions {
                    constants: &constants,
                    ..Default::default()
                },
                cache: None,
            });
        IlluminanceProbe { pipeline }
    }

    /// Direct illuminance (lux) at `points` from `lights`.
    pub fn run(
        &self,
        gpu: &Gpu,
        lights: &GpuLights,
        points: &[SurfacePoint],
    ) -> Result<Vec<f64>, GpuError> {
        let mut data: Vec<[f32; 4]> = Vec::with_capacity(2 * points.len().max(1));
        for p in points {
            let (a, n) = (p.position.as_vec3(), p.normal.as_vec3());
            data.push([a.x, a.y, a.z, 0.0]);
            data.push([n.x, n.y, n.z, 0.0]);
        }
        if data.is_empty() {
            data.extend([[0.0; 4]; 2]);
        }
        let dev = &gpu.device;
        let points_buf = dev.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("points"),
            contents: bytemuck::cast_slice(&data),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let params = PointParams {
            count: points.len() as u32,
            light_count: lights.count,
            pad: [0; 2],
        };
        let params_buf = gpu.uniform_buffer("point params", &params);
        let out = gpu.output_buffer("lux", 4 * points.len().max(1) as u64);
        let bind = gpu.bind_group(
            "illuminance points",
            &self.pipeline.get_bind_group_layout(0),
            &[
                (0, params_buf.as_entire_binding()),
                (1, lights.buffer.as_entire_binding()),
                (2, wgpu::BindingResource::TextureView(&lights.atlas.view)),
                (3, lights.atlas.info.as_entire_binding()),
                (4, points_buf.as_entire_binding()),
                (5, out.as_entire_binding()),
            ],
        );
        let workgroups = [(points.len().max(1) as u32).div_ceil(64), 1, 1];
        let lux = gpu.dispatch_and_read(&self.pipeline, &bind, workgroups, &out)?;
        Ok(lux[..points.len()].iter().map(|&v| v as f64).collect())
    }
}
