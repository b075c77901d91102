//! Direct illuminance at points, on the GPU with the renderer's own WGSL lighting code
//! (`shaders/lighting.wgsl`, with the shadows of `shaders/shadow.wgsl`) and on the CPU as
//! the reference (shadows by ray casting).

use glam::DVec3;
use wgpu::util::DeviceExt;

use super::gpu_scene::{GpuLights, GpuScene};
use super::layouts::Layouts;
use super::passes::LightModel;
use super::shadows::{ShadowFrame, ShadowPasses, ShadowSettings};
use crate::gpu::{shaders, Gpu, GpuError};
use crate::lighting::specular::SceneWindows;
use crate::photometry::Interp;
use crate::scene::Scene;
use crate::shadow::ShadowTechnique;

pub use crate::lighting::{
    illuminance_cpu, illuminance_cpu_in_scene, point_visibility, Occluders, SurfacePoint,
    UnusableLux,
};

/// Why [`scene_illuminance`] gave no values.
#[derive(Debug, thiserror::Error)]
pub enum IlluminanceError {
    /// The GPU failed or the scene is beyond its limits.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A computed value is not a usable number (refused, never returned).
    #[error(transparent)]
    Unusable(#[from] UnusableLux),
}

/// Direct illuminance (lux) at `points` in `scene` with `shadows` (its technique; the GPU's
/// check may coarsen its paraboloid tessellation: [`ShadowSettings::warning`]): on `gpu`
/// with the renderer's own lighting code, or by the CPU twin when `gpu` is `None`
/// (ray-cast shadows unless `none`); with shadows, plus the light mirrors and clear glass
/// pass on (ray-cast, [`SceneWindows`]); plus the daylight of the scene's `[sky]` (sky,
/// ground and sun through its openings and glazing, always on the CPU:
/// [`crate::daylight::points::scene_daylight`]). Every value is checked
/// ([`crate::lighting::usable_lux`]).
pub fn scene_illuminance(
    gpu: Option<&Gpu>,
    scene: &Scene,
    points: &[SurfacePoint],
    interp: Interp,
    shadows: &mut ShadowSettings,
) -> Result<Vec<f64>, IlluminanceError> {
    let mut lux = straight_illuminance(gpu, scene, points, interp, shadows)?;
    // Mirrors and clear glass pass light on where shadows are drawn ([`SceneWindows`]).
    if shadows.technique != ShadowTechnique::None {
        if let Some(windows) = SceneWindows::new(scene) {
            let light = windows.light(&scene.luminaires);
            light.add_lux_at_points(points, &mut lux, interp);
        }
    }
    if let Some(daylight) = crate::daylight::points::scene_daylight(scene, points) {
        for (v, d) in lux.iter_mut().zip(daylight) {
            *v += d.total();
        }
    }
    crate::lighting::usable_lux(&mut lux)?;
    Ok(lux)
}

/// [`scene_illuminance`] without what mirrors and glass pass on.
fn straight_illuminance(
    gpu: Option<&Gpu>,
    scene: &Scene,
    points: &[SurfacePoint],
    interp: Interp,
    shadows: &mut ShadowSettings,
) -> Result<Vec<f64>, GpuError> {
    let technique = shadows.technique;
    let Some(gpu) = gpu else {
        let (mesh, cutouts) = (scene.caster_mesh(), scene.caster_cutouts());
        let ignored = scene.ignored_per_luminaire();
        let casters = (technique != ShadowTechnique::None).then_some(Occluders {
            mesh: &mesh,
            cutouts: cutouts.as_ref(),
            ignored: &ignored,
        });
        return Ok(illuminance_cpu_in_scene(
            &scene.luminaires,
            casters.as_ref(),
            points,
            interp,
        ));
    };
    super::limits::check_scene(gpu, scene, shadows)?;
    let uploaded = GpuScene::new(gpu, &Layouts::new(gpu), scene);
    IlluminanceProbe::new(gpu, LightModel::Ldt(interp))
        .run_in_scene(gpu, &uploaded, points, shadows)
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct PointParams {
    count: u32,
    light_count: u32,
    pad: [u32; 2],
}

/// The compute pipeline of `illuminance_points`, with the shadow passes it reads.
pub struct IlluminanceProbe {
    pipeline: wgpu::ComputePipeline,
    model: LightModel,
    shadows: ShadowPasses,
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
        IlluminanceProbe {
            pipeline,
            model,
            shadows: ShadowPasses::new(gpu, super::targets::LDR_FORMAT),
        }
    }

    /// Direct illuminance (lux) at `points` from `lights`, without shadows.
    pub fn run(
        &self,
        gpu: &Gpu,
        lights: &GpuLights,
        points: &[SurfacePoint],
    ) -> Result<Vec<f64>, GpuError> {
        let frame = self.shadows.prepare_none(gpu);
        Ok(lux_of(&self.dispatch(gpu, lights, &frame, points)?))
    }

    /// Direct illuminance (lux) at `points` from the luminaires of `scene`, shadowed by
    /// its geometry as `settings` say.
    pub fn run_in_scene(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        points: &[SurfacePoint],
        settings: &ShadowSettings,
    ) -> Result<Vec<f64>, GpuError> {
        let frame = self.shadows.prepare_points(gpu, scene, points, settings)?;
        Ok(lux_of(&self.dispatch(
            gpu,
            &scene.lights,
            &frame,
            points,
        )?))
    }

    /// As [`IlluminanceProbe::run_in_scene`], in colour: per point the illuminance of each
    /// luminaire times its colour (RGB, lux; the colours have luminance 1).
    pub fn run_in_scene_rgb(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        points: &[SurfacePoint],
        settings: &ShadowSettings,
    ) -> Result<Vec<DVec3>, GpuError> {
        let frame = self.shadows.prepare_points(gpu, scene, points, settings)?;
        let rgba = self.dispatch(gpu, &scene.lights, &frame, points)?;
        Ok(rgba
            .iter()
            .map(|v| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64))
            .collect())
    }

    fn dispatch(
        &self,
        gpu: &Gpu,
        lights: &GpuLights,
        shadow: &ShadowFrame,
        points: &[SurfacePoint],
    ) -> Result<Vec<[f32; 4]>, GpuError> {
        let mut data: Vec<[f32; 4]> = Vec::with_capacity(2 * points.len().max(1));
        for p in points {
            let (a, n) = (p.position.as_vec3(), p.normal.as_vec3());
            data.push([a.x, a.y, a.z, 0.0]);
            data.push([n.x, n.y, n.z, 0.0]);
        }
        if data.is_empty() {
            data.extend([[0.0; 4]; 2]);
        }
        let tables = lights.tables(gpu, self.model);
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
        let out = gpu.output_buffer("lux", 16 * points.len().max(1) as u64);
        let [s8, s9, s10, s11] = self.shadows.bindings(shadow);
        let bind = gpu.bind_group(
            "illuminance points",
            &self.pipeline.get_bind_group_layout(0),
            &[
                (0, params_buf.as_entire_binding()),
                (1, lights.buffer.as_entire_binding()),
                (2, wgpu::BindingResource::TextureView(&lights.atlas.view)),
                (3, lights.atlas.info.as_entire_binding()),
                (6, lights.sectors.as_entire_binding()),
                (7, wgpu::BindingResource::TextureView(&tables.view)),
                (14, wgpu::BindingResource::Sampler(&tables.sampler)),
                (15, wgpu::BindingResource::TextureView(&tables.cube)),
                (4, points_buf.as_entire_binding()),
                (5, out.as_entire_binding()),
                s8,
                s9,
                s10,
                s11,
            ],
        );
        let workgroups = [(points.len().max(1) as u32).div_ceil(64), 1, 1];
        let values = gpu.dispatch_and_read(&self.pipeline, &bind, workgroups, &out)?;
        Ok(values
            .chunks_exact(4)
            .take(points.len())
            .map(|c| [c[0], c[1], c[2], c[3]])
            .collect())
    }
}

/// The lux (alpha) of the probe's RGBA results.
fn lux_of(rgba: &[[f32; 4]]) -> Vec<f64> {
    rgba.iter().map(|v| v[3] as f64).collect()
}
