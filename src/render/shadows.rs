//! Shadows in the renderer: settings, the per-frame shadow resources (paraboloid maps or
//! the shadow-volume mask) and the bindings the shading code reads (`shaders/shadow.wgsl`).

use glam::{DVec3, Mat4};

use super::gpu_scene::GpuScene;
use super::paraboloid::{ParaboloidMaps, ParaboloidPasses, MAP_FORMAT};
use super::volumes::{LightVolume, VolumePasses, MASK_FORMAT};
use crate::gpu::{Gpu, GpuError};
use crate::lighting::{point_visibility, Occluders, SurfacePoint};
use crate::shadow::{Light, ShadowTechnique, SilhouetteMethod, VolumeTest};

/// Shadow options.
#[derive(Debug, Clone, PartialEq)]
pub struct ShadowSettings {
    /// The technique.
    pub technique: ShadowTechnique,
    /// z-pass / z-fail choice for volumes.
    pub volume_test: VolumeTest,
    /// Silhouette search for volumes.
    pub silhouette: SilhouetteMethod,
    /// Side of each paraboloid map, texels.
    pub map_size: u32,
    /// PCF kernel radius, texels (0: a single comparison).
    pub pcf_radius: u32,
    /// Longest caster edge after tessellation for the paraboloid maps, metres.
    pub tessellation_m: f64,
    /// Constant depth bias of the maps, metres.
    pub bias_m: f64,
    /// Slope bias: multiple of the receiver's depth change across the PCF kernel.
    pub bias_slope: f64,
    /// Debug view: volumes in translucent yellow.
    pub show_volumes: bool,
    /// Debug view: silhouette edges in pink.
    pub show_silhouettes: bool,
    /// The caster edge asked for, when [`super::limits::check_scene`] made
    /// `tessellation_m` coarser to fit the GPU (see [`ShadowSettings::warning`]).
    pub coarsened_from_m: Option<f64>,
}

impl Default for ShadowSettings {
    fn default() -> ShadowSettings {
        ShadowSettings {
            technique: ShadowTechnique::default(),
            volume_test: VolumeTest::Auto,
            silhouette: SilhouetteMethod::Hextree,
            map_size: 1024,
            pcf_radius: 1,
            tessellation_m: 0.25,
            bias_m: 0.01,
            bias_slope: 1.0,
            show_volumes: false,
            show_silhouettes: false,
            coarsened_from_m: None,
        }
    }
}

impl ShadowSettings {
    /// No shadows.
    pub fn none() -> ShadowSettings {
        ShadowSettings {
            technique: ShadowTechnique::None,
            ..Default::default()
        }
    }

    /// The default settings with `technique`.
    pub fn with(technique: ShadowTechnique) -> ShadowSettings {
        ShadowSettings {
            technique,
            ..Default::default()
        }
    }

    /// What the caller should be told when the paraboloid casters were tessellated more
    /// coarsely than asked to fit the GPU (the option named in backquotes).
    pub fn warning(&self) -> Option<String> {
        let asked = self.coarsened_from_m?;
        Some(format!(
            "paraboloid shadow casters tessellated to {} m edges instead of {asked} m to fit the GPU's buffers (shadows of large faces may be less exact; `shadows` volumes is exact)",
            self.tessellation_m
        ))
    }
}

/// `ShadowInfo` in `shaders/shadow.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub(crate) struct ShadowInfoGpu {
    mode: u32,
    mask_width: u32,
    pad: u32,
    map_size: u32,
    far: f32,
    bias: f32,
    bias_slope: f32,
    pcf_radius: i32,
}

impl ShadowInfoGpu {
    fn new(settings: &ShadowSettings, mode: u32, mask_width: u32) -> ShadowInfoGpu {
        ShadowInfoGpu {
            mode,
            mask_width,
            pad: 0,
            map_size: settings.map_size,
            far: 1.0,
            bias: settings.bias_m as f32,
            bias_slope: settings.bias_slope as f32,
            pcf_radius: settings.pcf_radius as i32,
        }
    }
}

/// Entries per row of the shadow mask of point queries (slot i at column i mod this).
pub const POINT_MASK_WIDTH: u32 = 1024;

/// The shadow pipelines, the comparison sampler, and the 1 × 1 empty map array bound when
/// no paraboloid maps are drawn (WGSL needs every binding filled).
pub struct ShadowPasses {
    /// Shadow-volume pipelines.
    pub volumes: VolumePasses,
    /// Paraboloid-map pipeline.
    pub paraboloid: ParaboloidPasses,
    compare_sampler: wgpu::Sampler,
    empty_maps: wgpu::TextureView,
}

/// What one frame's shading reads about shadows.
pub struct ShadowFrame {
    info: wgpu::Buffer,
    mask: wgpu::Texture,
    mask_view: wgpu::TextureView,
    maps: Option<ParaboloidMaps>,
    /// The lights' volumes (shadow-volume mode), in light order.
    pub volumes: Vec<LightVolume>,
    volume_bind: Option<wgpu::BindGroup>,
}

impl ShadowFrame {
    /// Resources with `info` and `mask`, no maps and no volumes.
    fn new(gpu: &Gpu, info: &ShadowInfoGpu, mask: wgpu::Texture) -> ShadowFrame {
        ShadowFrame {
            info: gpu.uniform_buffer("shadow info", info),
            mask_view: array_view(&mask),
            mask,
            maps: None,
            volumes: Vec::new(),
            volume_bind: None,
        }
    }
}

/// A shadow mask of `width` × `height` entries and `layers` layers (one per light).
pub fn mask_texture(gpu: &Gpu, width: u32, height: u32, layers: u32) -> wgpu::Texture {
    use wgpu::TextureUsages as U;
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("shadow mask"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers.max(1),
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: MASK_FORMAT,
        usage: U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC | U::COPY_DST,
        view_formats: &[],
    })
}

/// An array view of every layer of `texture`.
pub fn array_view(texture: &wgpu::Texture) -> wgpu::TextureView {
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    })
}

impl ShadowPasses {
    /// Builds the pipelines (debug views draw into `debug_format`).
    pub fn new(gpu: &Gpu, debug_format: wgpu::TextureFormat) -> ShadowPasses {
        let compare_sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow comparison"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            // Each comparison is bilinear over the four nearest texels, so the PCF kernel
            // gives a smooth edge rather than steps of 1/9.
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        let empty = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("no paraboloid maps"),
            size: wgpu::Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 2,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: MAP_FORMAT,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        ShadowPasses {
            volumes: VolumePasses::new(gpu, debug_format),
            paraboloid: ParaboloidPasses::new(gpu),
            compare_sampler,
            empty_maps: empty.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::D2Array),
                ..Default::default()
            }),
        }
    }

    /// Prepares the shadows of `scene` for one frame of `width` × `height` seen through
    /// `view_proj` with near rectangle `near`: draws the paraboloid maps now (they do not
    /// depend on the camera) or builds the lights' volumes (recorded per frame by
    /// [`ShadowPasses::record_mask`]).
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        view_proj: Mat4,
        near: [DVec3; 4],
        width: u32,
        height: u32,
        settings: &ShadowSettings,
    ) -> Result<ShadowFrame, GpuError> {
        let lights = &scene.shadow_lights;
        let mut info = ShadowInfoGpu::new(settings, 0, width);
        let mut maps = None;
        let mut volumes = Vec::new();
        let mut volume_bind = None;
        let mask = match settings.technique {
            ShadowTechnique::Volumes => mask_texture(gpu, width, height, lights.len() as u32),
            _ => mask_texture(gpu, 1, 1, 1),
        };
        match settings.technique {
            ShadowTechnique::None => {}
            _ if lights.is_empty() => {}
            ShadowTechnique::Paraboloid => {
                let casters = scene.paraboloid_casters(gpu, settings.tessellation_m);
                let far = scene.shadow_far();
                let mut enc = gpu.device.create_command_encoder(&Default::default());
                maps = Some(self.paraboloid.render(
                    gpu,
                    &mut enc,
                    &casters,
                    lights,
                    settings.map_size,
                    far,
                ));
                gpu.queue.submit([enc.finish()]);
                info.mode = 1;
                info.far = far;
            }
            ShadowTechnique::Volumes => {
                if let Some(geometry) = scene.volume_geometry(gpu) {
                    for l in lights {
                        let p = l.position;
                        let light = Light::new([p.x, p.y, p.z, 1.0])
                            .map_err(|e| GpuError::Operation(format!("luminaire: {e}")))?;
                        let zfail = geometry.zfail(&light, settings.volume_test, near);
                        volumes.push(geometry.volume(
                            gpu,
                            light,
                            settings.silhouette,
                            zfail,
                            &l.ignored,
                        ));
                    }
                    volume_bind = Some(self.volumes.bind_group(gpu, view_proj, &volumes, None));
                    info.mode = 2;
                }
            }
        }
        Ok(ShadowFrame {
            maps,
            volumes,
            volume_bind,
            ..ShadowFrame::new(gpu, &info, mask)
        })
    }

    /// Shadow resources that shadow nothing.
    pub fn prepare_none(&self, gpu: &Gpu) -> ShadowFrame {
        let info = ShadowInfoGpu::new(&ShadowSettings::none(), 0, 1);
        ShadowFrame::new(gpu, &info, mask_texture(gpu, 1, 1, 1))
    }

    /// Prepares the shadows of `scene` for illuminance at `points` (point i reads mask
    /// slot i): paraboloid maps as for a frame; for `volumes`, the exact visibility of
    /// each luminaire from each point by ray casting on the CPU — the hard shadows the
    /// volumes give on screen, without a view to rasterize them in.
    pub fn prepare_points(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        points: &[SurfacePoint],
        settings: &ShadowSettings,
    ) -> Result<ShadowFrame, GpuError> {
        let lights = &scene.shadow_lights;
        if settings.technique != ShadowTechnique::Volumes || lights.is_empty() {
            return self.prepare(gpu, scene, Mat4::IDENTITY, [DVec3::ZERO; 4], 1, 1, settings);
        }
        let positions: Vec<DVec3> = lights.iter().map(|l| l.position).collect();
        let ignored: Vec<_> = lights.iter().map(|l| l.ignored.clone()).collect();
        let casters = Occluders {
            mesh: &scene.casters,
            cutouts: scene.cutouts.as_ref(),
            ignored: &ignored,
        };
        let visible = point_visibility(&casters, &positions, points);
        let rows = (points.len() as u32).div_ceil(POINT_MASK_WIDTH).max(1);
        let layer_len = (POINT_MASK_WIDTH * rows) as usize;
        let mut data = vec![0u8; layer_len * lights.len()];
        for (k, layer) in visible.iter().enumerate() {
            for (i, &lit) in layer.iter().enumerate() {
                data[k * layer_len + i] = u8::from(!lit);
            }
        }
        let mask = mask_texture(gpu, POINT_MASK_WIDTH, rows, lights.len() as u32);
        gpu.queue.write_texture(
            mask.as_image_copy(),
            &data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(POINT_MASK_WIDTH),
                rows_per_image: Some(rows),
            },
            mask.size(),
        );
        let info = ShadowInfoGpu::new(settings, 2, POINT_MASK_WIDTH);
        Ok(ShadowFrame::new(gpu, &info, mask))
    }

    /// The frame bind group's shadow entries (bindings 8–11).
    pub fn bindings<'a>(&'a self, frame: &'a ShadowFrame) -> [(u32, wgpu::BindingResource<'a>); 4] {
        let maps = frame
            .maps
            .as_ref()
            .map(|m| &m.view)
            .unwrap_or(&self.empty_maps);
        [
            (8, frame.info.as_entire_binding()),
            (9, wgpu::BindingResource::TextureView(&frame.mask_view)),
            (10, wgpu::BindingResource::TextureView(maps)),
            (11, wgpu::BindingResource::Sampler(&self.compare_sampler)),
        ]
    }

    /// Records the volumes' stencil passes and mask (nothing in other modes).
    pub fn record_mask(
        &self,
        enc: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &ShadowFrame,
        depth_view: &wgpu::TextureView,
    ) {
        if let (Some(bind), Some(geometry)) = (&frame.volume_bind, scene.volume_geometry_if_built())
        {
            self.volumes
                .record_mask(enc, geometry, &frame.volumes, bind, &frame.mask, depth_view);
        }
    }

    /// Records the debug views asked for in `settings` over `color`.
    pub fn record_debug(
        &self,
        enc: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        frame: &ShadowFrame,
        settings: &ShadowSettings,
        color: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
    ) {
        if !(settings.show_volumes || settings.show_silhouettes) {
            return;
        }
        if let (Some(bind), Some(geometry)) = (&frame.volume_bind, scene.volume_geometry_if_built())
        {
            self.volumes.record_debug(
                enc,
                geometry,
                &frame.volumes,
                bind,
                color,
                depth_view,
                settings.show_volumes,
                settings.show_silhouettes,
            );
        }
    }

    /// The shadow mask read back: one layer per light (rows of pixels), 1 where the
    /// pixel is in that light's shadow volume. Empty unless in shadow-volume mode.
    pub fn read_mask(&self, gpu: &Gpu, frame: &ShadowFrame) -> Result<Vec<u8>, GpuError> {
        if frame.volume_bind.is_none() {
            return Ok(Vec::new());
        }
        gpu.read_texture(&frame.mask)
    }
}
