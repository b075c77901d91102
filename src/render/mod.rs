//! The real-time goniometric renderer (Wallner ch. 3): a depth pre-pass, one shading pass
//! that sums every luminaire with B = I · LDT(θ, φ) / d² (Eq. 3.4) and Blinn-Phong into an
//! HDR target, image statistics, and tone mapping (exposure, Reinhard) or false-colour
//! illuminance with a legend. Headless here; the viewer drives the same passes.

pub mod cutout_gpu;
pub mod gpu_scene;
pub mod illuminance;
pub mod layouts;
pub mod ldt;
pub mod legend;
pub mod lightmap;
pub mod limits;
pub mod mipmaps;
pub mod output;
pub mod paraboloid;
pub mod passes;
pub mod quality;
pub mod scene_frame;
pub mod shadows;
pub mod targets;
pub mod tonemap;
pub mod volumes;

use glam::Vec3;

pub use crate::scene::MAX_IMAGE_SIZE;
pub use crate::shadow::{ShadowTechnique, VolumeTest};
pub use gpu_scene::GpuScene;
pub use passes::LightModel;
pub use shadows::ShadowSettings;
pub use tonemap::{ImageStats, LuxPercentiles, ToneSettings};

use crate::gpu::{Gpu, GpuError};
use crate::photometry::Interp;
use crate::scene::{Camera, DisplayEntry, DisplayIndirect, Mode, Palette, Scene, Tonemap};
use layouts::Layouts;
use passes::ScenePasses;
use shadows::{ShadowFrame, ShadowPasses};
use targets::Targets;
use tonemap::ToneMapper;

/// What to render.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// How luminaires emit.
    pub light_model: LightModel,
    /// Shaded or false-colour illuminance.
    pub mode: Mode,
    /// Tone-mapping operator (shaded mode).
    pub tonemap: Tonemap,
    /// k of the exposure operator (automatic when `None`).
    pub exposure: Option<f64>,
    /// Top of the false-colour scale, lux (automatic when `None`).
    pub lux_max: Option<f64>,
    /// False-colour palette.
    pub palette: Palette,
    /// Hard colour bands on the false-colour scale (0: continuous).
    pub steps: u32,
    /// Display colour where no surface is seen (linear RGB 0..1).
    pub background: Vec3,
    /// Whether to read the HDR values back (for EXR output and tests).
    pub read_hdr: bool,
    /// Shadows.
    pub shadows: ShadowSettings,
    /// Samples per pixel side for the displayed image (1: none; odd, see
    /// [`targets::Targets`]); the numbers are the pixel centres either way.
    pub supersample: u32,
    /// What the image's light is — the luminaires' direct light, or with a light map
    /// ([`Renderer::upload_solved`]) an ambient estimate or a radiosity solution's total —
    /// named on the illuminance legend.
    pub shown_light: DisplayIndirect,
}

impl RenderSettings {
    /// The image's width over its height (a zero height counts as 1): the aspect the
    /// camera's view, and a view-driven solve's importance, are made for.
    pub fn aspect(&self) -> f64 {
        self.width as f64 / self.height.max(1) as f64
    }

    /// The light model the image is drawn with: in shaded mode Catmull-Rom comes from the
    /// cube maps ([`crate::render::ldt::cube`]: one filtered fetch per light, the cost of a
    /// point light), in illuminance mode — where the pixels are lux — from the exact spline;
    /// every other model as chosen. `illuminance`, `calc` and radiosity always sample the
    /// exact spline.
    pub fn drawn_light_model(&self) -> LightModel {
        match (self.mode, self.light_model) {
            (Mode::Shaded, LightModel::Ldt(Interp::CatmullRom)) => LightModel::CatmullRomCube,
            (_, model) => model,
        }
    }

    /// The settings of a scene's `[display]` table, with defaults for what it leaves out.
    pub fn from_display(d: &DisplayEntry) -> RenderSettings {
        RenderSettings {
            width: d.width.unwrap_or(1280),
            height: d.height.unwrap_or(720),
            light_model: LightModel::Ldt(d.interp.unwrap_or(Interp::CatmullRom)),
            mode: d.mode.unwrap_or_default(),
            tonemap: d.tonemap.unwrap_or_default(),
            exposure: d.exposure,
            lux_max: d.lux_max,
            palette: d.palette.unwrap_or_default(),
            steps: d.steps.unwrap_or(0),
            background: d
                .background
                .map(|b| glam::DVec3::from_array(b).as_vec3())
                .unwrap_or(Vec3::splat(0.02)),
            read_hdr: false,
            shadows: ShadowSettings::with(d.shadows.unwrap_or_default()),
            supersample: 1,
            shown_light: DisplayIndirect::None,
        }
    }

    /// `base` (a scene's `[display]`) with what these settings choose of it: the mode,
    /// tone mapping, exposure and scale top (absent when automatic), palette and bands
    /// (absent at their defaults), interpolation and shadow technique; its size,
    /// background and indirect light stay `base`'s. [`RenderSettings::from_display`] of
    /// the result gives these choices back.
    pub fn to_display(&self, base: &DisplayEntry) -> DisplayEntry {
        DisplayEntry {
            mode: Some(self.mode),
            tonemap: Some(self.tonemap),
            exposure: self.exposure,
            lux_max: self.lux_max,
            palette: (self.palette != Palette::default()).then_some(self.palette),
            steps: (self.steps > 0).then_some(self.steps),
            interp: Some(self.light_model.interp()),
            shadows: Some(self.shadows.technique),
            ..base.clone()
        }
    }
}

/// A rendered image.
pub struct RenderedFrame {
    /// The displayable image (sRGB); in illuminance mode widened by a panel on the right
    /// that carries the legend (beside the view, never over it).
    pub image: image::RgbaImage,
    /// Linear values when asked for: rgb = luminance (cd/m²), a = lux (−1: no surface).
    pub hdr: Option<Vec<[f32; 4]>>,
    /// Statistics of the HDR image.
    pub stats: ImageStats,
    /// The shadow-volume mask when asked for (`read_hdr` in shadow-volume mode): one
    /// layer of pixels per light, 1 where the pixel is in that light's shadow.
    pub shadow_mask: Vec<u8>,
    /// The tone-mapping settings used.
    pub tone: ToneSettings,
}

/// The renderer's pipelines (built once, reused for every frame and scene).
pub struct Renderer {
    /// Bind group layouts and the material sampler.
    pub layouts: Layouts,
    passes: ScenePasses,
    tonemapper: ToneMapper,
    /// Shadow pipelines.
    pub shadows: ShadowPasses,
}

impl Renderer {
    /// Builds the pipelines.
    pub fn new(gpu: &Gpu) -> Renderer {
        let layouts = Layouts::new(gpu);
        Renderer {
            passes: ScenePasses::new(gpu, &layouts),
            tonemapper: ToneMapper::new(gpu),
            shadows: ShadowPasses::new(gpu, targets::LDR_FORMAT),
            layouts,
        }
    }

    /// Uploads a scene.
    pub fn upload(&self, gpu: &Gpu, scene: &Scene) -> GpuScene {
        GpuScene::new(gpu, &self.layouts, scene)
    }

    /// Uploads a scene with its solved radiosity light map (displayed instead of the
    /// direct diffuse light; the luminaires add their specular term). A translucent
    /// surface's back faces come too, each side showing its own light
    /// ([`crate::scene::back_faces`]).
    pub fn upload_solved(
        &self,
        gpu: &Gpu,
        scene: &Scene,
        light_map: &lightmap::LightMap,
    ) -> GpuScene {
        let scene = crate::scene::back_faces::with_back_faces(scene);
        GpuScene::with_light_map(gpu, &self.layouts, &scene, Some(light_map))
    }

    /// Renders the HDR image of `scene` seen by `camera` into `targets` `frames` times in
    /// one submission and waits for the GPU to finish (one frame: the benchmark's unit).
    /// Returns the frame's shadow resources.
    #[allow(clippy::too_many_arguments)]
    pub fn draw_hdr(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        camera: &Camera,
        targets: &Targets,
        model: LightModel,
        shadows: &ShadowSettings,
        frames: usize,
    ) -> Result<ShadowFrame, GpuError> {
        let aspect = targets.width as f64 / targets.height as f64;
        let (render_w, render_h) = targets.render_size();
        let shadow = self.shadows.prepare(
            gpu,
            scene,
            camera.view_projection(aspect),
            camera.near_rectangle(aspect),
            render_w,
            render_h,
            shadows,
        )?;
        let frame = self.passes.frame_bind_group(
            gpu,
            &self.layouts,
            scene,
            camera,
            targets,
            model,
            &self.shadows.bindings(&shadow),
        );
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        for _ in 0..frames {
            self.passes.record_depth(&mut enc, &frame, scene, targets);
            self.shadows
                .record_mask(&mut enc, scene, &shadow, &targets.depth_view);
            self.passes
                .record_shade(gpu, &mut enc, &frame, scene, targets, model);
        }
        self.tonemapper.record_centres(gpu, &mut enc, targets);
        gpu.queue.submit([enc.finish()]);
        gpu.wait()?;
        Ok(shadow)
    }

    /// Renders a complete image.
    pub fn render(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        camera: &Camera,
        settings: &RenderSettings,
    ) -> Result<RenderedFrame, GpuError> {
        // The debug views draw over the image with the scene's depth: one sample.
        let debug = settings.shadows.show_volumes || settings.shadows.show_silhouettes;
        let supersample = if debug { 1 } else { settings.supersample };
        let targets = Targets::with_supersample(gpu, settings.width, settings.height, supersample);
        let (shadow, stats, tone) = self.render_to(gpu, scene, camera, settings, &targets)?;
        let pixels = gpu.read_texture(&targets.ldr)?;
        let mut image = image::RgbaImage::from_raw(settings.width, settings.height, pixels)
            .ok_or_else(|| GpuError::Operation("read-back size mismatch".into()))?;
        if settings.mode == Mode::Illuminance {
            image = legend::beside_lux_legend(&image, &tone, settings.shown_light.legend_word());
        }
        let (hdr, shadow_mask) = if settings.read_hdr {
            (
                Some(bytemuck::pod_collect_to_vec(
                    &gpu.read_texture(&targets.hdr)?,
                )),
                self.shadows.read_mask(gpu, &shadow)?,
            )
        } else {
            (None, Vec::new())
        };
        Ok(RenderedFrame {
            image,
            hdr,
            shadow_mask,
            stats,
            tone,
        })
    }

    /// Renders into `targets` (whose size wins over the settings'), leaving the HDR and
    /// displayable images on the GPU (the viewer shows the latter as it is); returns the
    /// frame's shadow resources, the image statistics and the tone mapping used. The
    /// legend of illuminance mode is not drawn.
    pub fn render_to(
        &self,
        gpu: &Gpu,
        scene: &GpuScene,
        camera: &Camera,
        settings: &RenderSettings,
        targets: &Targets,
    ) -> Result<(ShadowFrame, ImageStats, ToneSettings), GpuError> {
        let shadow = self.draw_hdr(
            gpu,
            scene,
            camera,
            targets,
            settings.drawn_light_model(),
            &settings.shadows,
            1,
        )?;
        let mut stats = self.tonemapper.statistics(gpu, targets)?;
        if settings.mode == Mode::Illuminance {
            let hdr: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&gpu.read_texture(&targets.hdr)?);
            stats.lux = LuxPercentiles::of_pixels(&hdr);
        }
        let tone = ToneSettings::resolve_scale(
            settings.mode,
            settings.tonemap,
            settings.exposure,
            settings.lux_max,
            (settings.palette, settings.steps),
            &stats,
        );
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        self.tonemapper
            .record(gpu, &mut enc, targets, &tone, settings.background);
        self.shadows.record_debug(
            &mut enc,
            scene,
            &shadow,
            &settings.shadows,
            &targets.ldr_view,
            &targets.depth_view,
        );
        gpu.queue.submit([enc.finish()]);
        Ok((shadow, stats, tone))
    }
}

#[cfg(test)]
mod tests {
    use super::{LightModel, RenderSettings};
    use crate::photometry::Interp;
    use crate::scene::{DisplayEntry, Mode, Palette, Tonemap};
    use crate::shadow::ShadowTechnique;

    #[test]
    fn the_aspect_is_width_over_height_and_survives_a_zero_height() {
        let mut s = RenderSettings::from_display(&DisplayEntry::default());
        (s.width, s.height) = (1280, 720);
        assert_eq!(s.aspect(), 1280.0 / 720.0);
        s.height = 0;
        assert_eq!(s.aspect(), 1280.0);
    }

    #[test]
    fn the_viewers_choices_go_into_the_scene_file_and_come_back() {
        let base = DisplayEntry {
            width: Some(640),
            height: Some(480),
            exposure: Some(0.3),
            background: Some([0.1, 0.2, 0.3]),
            ..Default::default()
        };
        let mut chosen = RenderSettings::from_display(&base);
        chosen.mode = Mode::Illuminance;
        chosen.tonemap = Tonemap::Exposure;
        chosen.exposure = None;
        chosen.lux_max = Some(750.0);
        chosen.palette = Palette::Viridis;
        chosen.steps = 6;
        chosen.light_model = LightModel::Ldt(Interp::Monotone);
        chosen.shadows.technique = ShadowTechnique::Volumes;
        let saved = chosen.to_display(&base);
        // Automatic exposure is saved as absent, not as the file's old value.
        assert_eq!(saved.exposure, None);
        assert_eq!(
            (saved.width, saved.background),
            (Some(640), base.background)
        );
        assert_eq!(RenderSettings::from_display(&saved), chosen);
    }
}
