//! The GPU side of the viewport: uploads the scene the UI describes when it changes,
//! renders it into targets of the viewport's size (only when the view or the scene
//! changed), hands the image to egui as a native texture, reads the lux under the
//! cursor and writes screenshots.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context as _;

use super::app::ViewerApp;
use crate::gpu::{Gpu, GpuError};
use crate::render::lightmap::LightMap;
use crate::render::targets::Targets;
use crate::render::{GpuScene, RenderSettings, Renderer};
use crate::scene::Camera;

/// What the last image was rendered from.
#[derive(Clone, PartialEq)]
struct RenderedFrom {
    revision: u64,
    /// Light maps put into the uploaded scene so far.
    maps: u64,
    camera: Camera,
    settings: RenderSettings,
}

/// The viewport's GPU resources.
pub struct Viewport {
    renderer: Renderer,
    scene: Option<(u64, GpuScene)>,
    /// The light map the uploaded scene shows, and how many were put in so far.
    shown_map: Option<Arc<LightMap>>,
    maps: u64,
    targets: Option<Targets>,
    /// The displayable image seen as gamma-encoded bytes (what egui samples).
    gamma_view: Option<wgpu::TextureView>,
    texture: Option<egui::TextureId>,
    last: Option<RenderedFrom>,
    /// Images rendered so far, and the (image, pixel) the cursor read-out is for: the
    /// read-back waits for the GPU, so it happens only when either changes.
    rendered: u64,
    read_at: Option<(u64, [u32; 2])>,
    /// The paraboloid caster edge the uploaded scene needs to fit the GPU (0: as asked).
    fitted_tessellation_m: f64,
}

impl Viewport {
    /// Builds the renderer's pipelines.
    pub fn new(gpu: &Gpu) -> Viewport {
        Viewport {
            renderer: Renderer::new(gpu),
            scene: None,
            shown_map: None,
            maps: 0,
            targets: None,
            gamma_view: None,
            texture: None,
            last: None,
            rendered: 0,
            read_at: None,
            fitted_tessellation_m: 0.0,
        }
    }

    /// Brings the image up to date with `app` and registers it with `egui`.
    pub fn update(
        &mut self,
        gpu: &Gpu,
        app: &mut ViewerApp,
        egui: &mut egui_wgpu::Renderer,
    ) -> Result<(), GpuError> {
        let [w, h] = app.status.viewport_px;
        let (w, h) = (
            w.clamp(1, crate::render::MAX_IMAGE_SIZE),
            h.clamp(1, crate::render::MAX_IMAGE_SIZE),
        );
        let map = app.radiosity.light_map.clone();
        let map_changed = !same_arc(&map, &self.shown_map);
        let uploaded_revision = self.scene.as_ref().map(|s| s.0);
        if uploaded_revision == Some(app.revision) && map_changed {
            // A newer solution of the same atlas: only the texture changes (a whole
            // upload drops the shadow casters' caches; seconds on a big scene).
            if let (Some((_, scene)), Some(old), Some(new)) =
                (&mut self.scene, &self.shown_map, &map)
            {
                if old.same_layout(new) {
                    scene.set_light_map(gpu, new);
                    self.shown_map = map.clone();
                    self.maps += 1;
                }
            }
        }
        let map_changed = !same_arc(&map, &self.shown_map);
        if uploaded_revision != Some(app.revision) || map_changed {
            let scene = app.render_scene();
            // A scene beyond the GPU ends the viewer with the reason, never a panic.
            let mut shadows = app.render_settings(w, h).shadows;
            crate::render::limits::check_scene(gpu, &scene, &mut shadows)?;
            // The caster edge paraboloid shadows need, should the view switch to them
            // (measured once: the check above already did it for paraboloid views).
            let paraboloid = crate::shadow::ShadowTechnique::Paraboloid;
            if shadows.technique != paraboloid {
                shadows.technique = paraboloid;
                if crate::render::limits::check_scene(gpu, &scene, &mut shadows).is_err() {
                    shadows.tessellation_m = 0.0;
                }
            }
            // Said when the fitted edge changes (a scene loaded or edited), not per upload.
            if shadows.tessellation_m != self.fitted_tessellation_m {
                if let Some(w) = shadows.warning() {
                    app.info(format!("warning: {w}"));
                }
            }
            self.fitted_tessellation_m = shadows.tessellation_m;
            let uploaded = match &map {
                Some(map) => self.renderer.upload_solved(gpu, &scene, map),
                None => self.renderer.upload(gpu, &scene),
            };
            self.scene = Some((app.revision, uploaded));
            self.shown_map = map;
            self.maps += 1;
        }
        let resized = self
            .targets
            .as_ref()
            .is_none_or(|t| t.width != w || t.height != h);
        if resized {
            let targets = Targets::new(gpu, w, h);
            self.gamma_view = Some(targets.ldr.create_view(&wgpu::TextureViewDescriptor {
                format: Some(wgpu::TextureFormat::Rgba8Unorm),
                ..Default::default()
            }));
            self.targets = Some(targets);
        }
        let (Some((_, scene)), Some(targets), Some(gamma_view)) =
            (&self.scene, &self.targets, &self.gamma_view)
        else {
            return Ok(());
        };
        let mut settings = app.render_settings(w, h);
        let t = &mut settings.shadows.tessellation_m;
        *t = t.max(self.fitted_tessellation_m);
        let from = RenderedFrom {
            revision: app.revision,
            maps: self.maps,
            camera: app.camera.camera(app.extent()),
            settings,
        };
        if resized || self.last.as_ref() != Some(&from) {
            let (_, _, tone) =
                self.renderer
                    .render_to(gpu, scene, &from.camera, &from.settings, targets)?;
            app.status.lux_max = tone.lux_max;
            self.last = Some(from);
            self.rendered += 1;
            // The texture view only changes with the size.
            match self.texture {
                Some(id) if resized => egui.update_egui_texture_from_wgpu_texture(
                    &gpu.device,
                    gamma_view,
                    wgpu::FilterMode::Linear,
                    id,
                ),
                Some(_) => {}
                None => {
                    self.texture = Some(egui.register_native_texture(
                        &gpu.device,
                        gamma_view,
                        wgpu::FilterMode::Linear,
                    ))
                }
            }
        }
        app.viewport_texture = self.texture;
        self.read_cursor(gpu, app)?;
        if let Some(path) = app.requests.screenshot.take() {
            match self.screenshot(gpu, app, &path) {
                Ok(()) => app.info(format!("saved {} and its .exr", path.display())),
                Err(e) => app.error(format!("{}: screenshot not saved: {e:#}", path.display())),
            }
        }
        Ok(())
    }

    fn read_cursor(&mut self, gpu: &Gpu, app: &mut ViewerApp) -> Result<(), GpuError> {
        let (Some(t), Some([x, y])) = (&self.targets, app.status.cursor_px) else {
            app.status.cursor_lux = None;
            app.status.cursor_luminance = None;
            self.read_at = None;
            return Ok(());
        };
        if self.read_at.replace((self.rendered, [x, y])) == Some((self.rendered, [x, y])) {
            return Ok(());
        }
        if x >= t.width || y >= t.height {
            return Ok(());
        }
        let (lux, luminance) = self.read_at_pixel(gpu, [x, y])?.unzip();
        app.status.cursor_lux = lux;
        app.status.cursor_luminance = luminance;
        Ok(())
    }

    /// Illuminance (lux) and luminance (cd/m²) at viewport pixel `at` of the last image
    /// (`None` where no surface is seen or outside it).
    fn read_at_pixel(&self, gpu: &Gpu, at: [u32; 2]) -> Result<Option<(f64, f64)>, GpuError> {
        let Some(t) = &self.targets else {
            return Ok(None);
        };
        let [x, y] = at;
        if x >= t.width || y >= t.height {
            return Ok(None);
        }
        let texel: [f32; 4] = bytemuck::pod_read_unaligned(&gpu.read_texel(&t.hdr, x, y)?);
        let rgb = glam::Vec3::new(texel[0], texel[1], texel[2]).as_dvec3();
        let luminance = rgb.dot(crate::scene::placement::LUMINANCE_WEIGHTS);
        Ok((texel[3] >= 0.0).then_some((texel[3] as f64, luminance)))
    }

    /// The illuminance (lux) at the centre pixel of the last image (`None`: no surface).
    pub fn centre_lux(&self, gpu: &Gpu) -> Result<Option<f64>, GpuError> {
        let Some(t) = &self.targets else {
            return Ok(None);
        };
        Ok(self
            .read_at_pixel(gpu, [t.width / 2, t.height / 2])?
            .map(|(lux, _)| lux))
    }

    /// Renders the current view at the viewport's size and writes it as PNG (with the
    /// legend in false-colour mode) and EXR beside it.
    fn screenshot(&self, gpu: &Gpu, app: &ViewerApp, png: &Path) -> anyhow::Result<()> {
        let (_, scene) = self.scene.as_ref().context("no scene uploaded")?;
        let [w, h] = app.status.viewport_px;
        let mut settings = app.render_settings(w.max(1), h.max(1));
        settings.read_hdr = true;
        let frame =
            self.renderer
                .render(gpu, scene, &app.camera.camera(app.extent()), &settings)?;
        let exr = png.with_extension("exr");
        let linear = crate::render::output::linear_image(&frame, settings.width, settings.height)
            .context("no HDR image")?;
        crate::render::output::write_image(png, &frame.image)?;
        crate::render::output::write_image(&exr, &linear)?;
        Ok(())
    }
}

/// Whether `a` and `b` are the same map (or both none).
fn same_arc(a: &Option<Arc<LightMap>>, b: &Option<Arc<LightMap>>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        (None, None) => true,
        _ => false,
    }
}
