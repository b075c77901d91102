//! One frame of the viewer, in a window or headless: egui's UI pass, the viewport's GPU
//! render, egui's tessellation and painting into a target; how a run is asked for and
//! what it reports (frame-time statistics included).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{anyhow, Context as _};

use super::app::ViewerApp;
use super::viewport_gpu::Viewport;
use crate::gpu::Gpu;

/// How a run of the viewer goes: in a window, or headless.
#[derive(Debug, Clone, Default)]
pub struct WindowOptions {
    /// Inner size, logical pixels (headless: pixels).
    pub size: [u32; 2],
    /// Render this many frames, then exit.
    pub frames: Option<u64>,
    /// After the last frame, save the window (UI included) here as PNG.
    pub screenshot: Option<PathBuf>,
    /// Render the frames offscreen, without a window or a display (needs `frames`).
    pub headless: bool,
}

/// What a run did (printed as JSON by `view --frames`).
#[derive(Debug, Clone, Default, serde::Serialize)]
pub struct RunSummary {
    /// Frames rendered.
    pub frames: u64,
    /// Window size, physical pixels.
    pub window_px: [u32; 2],
    /// The viewport within it (x, y, width, height), physical pixels.
    pub viewport_px: [u32; 4],
    /// Whether the frames were rendered offscreen (`view --headless`).
    pub headless: bool,
    /// Mean frame time over the frames after the first, ms (start to start: the UI, the
    /// viewport's render, painting and, in a window, presenting).
    pub mean_frame_ms: f64,
    /// The 95th percentile of the frame times, ms.
    pub p95_frame_ms: f64,
    /// The longest frame, ms.
    pub max_frame_ms: f64,
    /// Frames that began while the radiosity solver was at work (not waiting, not done).
    pub solving_frames: u64,
    /// Their mean frame time, ms (0: none).
    pub solving_mean_frame_ms: f64,
    /// Their 95th percentile, ms.
    pub solving_p95_frame_ms: f64,
    /// The GPU.
    pub gpu: String,
    /// The surface format.
    pub surface_format: String,
    /// The screenshot written.
    pub screenshot: Option<PathBuf>,
    /// Whether a radiosity light map (or the ambient estimate) was shown at the end.
    pub indirect_shown: bool,
    /// Radiosity shots by then.
    pub indirect_shots: usize,
    /// What the radiosity solver said last.
    pub indirect_status: String,
    /// The illuminance at the viewport's centre pixel in the last frame, lux (the lux
    /// read-out as if the cursor were there; `None`: no surface there).
    pub centre_lux: Option<f64>,
}

/// How long the end of a run waits for background work to stop.
pub const WORKERS_STOP_LIMIT: Duration = Duration::from_secs(60);

impl RunSummary {
    /// Hands the GPU to `app`, starts the indirect light it opens with and notes the GPU.
    pub(super) fn start(
        &mut self,
        app: &mut ViewerApp,
        gpu: &Arc<Gpu>,
        format: wgpu::TextureFormat,
    ) {
        app.status.gpu = gpu.describe();
        app.gpu = Some(gpu.clone());
        app.start_indirect();
        self.gpu = gpu.describe();
        self.surface_format = format!("{format:?}");
    }

    /// Fills in the frame times and the radiosity solver's state at the end of a run.
    pub(super) fn finish(mut self, app: &ViewerApp, clock: &FrameClock) -> RunSummary {
        clock.summarise(&mut self);
        let radiosity = &app.radiosity;
        self.indirect_shown = radiosity.light_map.is_some();
        self.indirect_shots = radiosity.shots;
        self.indirect_status = radiosity.status.clone();
        self.viewport_px = app.status.viewport_rect_px;
        self
    }
}

/// What draws the viewer's frames: the GPU, egui and the viewport.
pub struct FramePainter {
    /// The GPU.
    pub gpu: Arc<Gpu>,
    /// egui's context.
    pub egui_ctx: egui::Context,
    egui_renderer: egui_wgpu::Renderer,
    /// The 3D view's GPU resources.
    pub viewport: Viewport,
    /// The format painted into.
    pub format: wgpu::TextureFormat,
}

/// A frame laid out and tessellated, ready to paint.
pub struct PreparedFrame {
    jobs: Vec<egui::ClippedPrimitive>,
    screen: egui_wgpu::ScreenDescriptor,
    free: Vec<egui::TextureId>,
    /// What egui asks of the platform (cursor, clipboard, …).
    pub platform_output: egui::PlatformOutput,
    /// When egui wants the next frame (`Duration::MAX`: not before an event).
    pub repaint_delay: Duration,
}

impl FramePainter {
    /// Sets up egui's renderer for targets of `format` and the viewport.
    pub fn new(gpu: Arc<Gpu>, format: wgpu::TextureFormat) -> FramePainter {
        let egui_renderer =
            egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        FramePainter {
            viewport: Viewport::new(&gpu),
            egui_ctx: egui::Context::default(),
            egui_renderer,
            gpu,
            format,
        }
    }

    /// Runs the UI on `raw` input, brings the viewport's image up to date and tessellates
    /// the frame for a target of `size_px`.
    pub fn prepare(
        &mut self,
        app: &mut ViewerApp,
        raw: egui::RawInput,
        size_px: [u32; 2],
    ) -> anyhow::Result<PreparedFrame> {
        let mut full = self.egui_ctx.run_ui(raw, |ui| app.ui(ui));
        let mut textures = std::mem::take(&mut full.textures_delta);
        for (id, deltas) in textures.set.drain() {
            for delta in deltas {
                self.egui_renderer
                    .update_texture(&self.gpu.device, &self.gpu.queue, id, &delta);
            }
        }
        let free: Vec<egui::TextureId> = textures.free.drain().collect();
        let updated = self
            .viewport
            .update(&self.gpu, app, &mut self.egui_renderer);
        let repaint_delay = full
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        let prepared = PreparedFrame {
            jobs: self.egui_ctx.tessellate(full.shapes, full.pixels_per_point),
            screen: egui_wgpu::ScreenDescriptor {
                size_in_pixels: size_px,
                pixels_per_point: full.pixels_per_point,
            },
            free,
            platform_output: full.platform_output,
            repaint_delay,
        };
        if let Err(e) = updated {
            self.finish(prepared);
            return Err(e.into());
        }
        Ok(prepared)
    }

    /// Paints `frame` (the viewport image is one of its textures) into `target`.
    pub fn paint(&mut self, frame: &PreparedFrame, target: &wgpu::TextureView) {
        let gpu = &self.gpu;
        let mut enc = gpu.device.create_command_encoder(&Default::default());
        let extra = self.egui_renderer.update_buffers(
            &gpu.device,
            &gpu.queue,
            &mut enc,
            &frame.jobs,
            &frame.screen,
        );
        {
            let mut pass = enc
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("egui"),
                    color_attachments: &[Some(crate::gpu::cleared_attachment(
                        target,
                        wgpu::Color::BLACK,
                    ))],
                    ..Default::default()
                })
                .forget_lifetime();
            self.egui_renderer
                .render(&mut pass, &frame.jobs, &frame.screen);
        }
        gpu.queue.submit(extra.into_iter().chain([enc.finish()]));
    }

    /// Frees the textures egui let go of in `frame` (after painting it, or instead).
    pub fn finish(&mut self, frame: PreparedFrame) {
        for id in &frame.free {
            self.egui_renderer.free_texture(id);
        }
    }

    /// A texture of the frame's size and format to paint into and read back.
    pub fn offscreen_target(&self, size_px: [u32; 2]) -> wgpu::Texture {
        self.gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("viewer frame"),
            size: wgpu::Extent3d {
                width: size_px[0],
                height: size_px[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    }

    /// Saves `texture` (a painted frame from [`FramePainter::offscreen_target`]) as PNG.
    pub fn save(&self, texture: &wgpu::Texture, path: &Path) -> anyhow::Result<()> {
        let (w, h) = (texture.width(), texture.height());
        let mut bytes = self.gpu.read_texture(texture)?;
        match self.format {
            wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => {
                bytes.chunks_exact_mut(4).for_each(|p| p.swap(0, 2))
            }
            wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => {}
            other => return Err(anyhow!("cannot save a window of format {other:?}")),
        }
        bytes.chunks_exact_mut(4).for_each(|p| p[3] = 255);
        let image = image::RgbaImage::from_raw(w, h, bytes).context("capture size mismatch")?;
        Ok(crate::render::output::write_image(path, &image)?)
    }
}

/// The time between the starts of successive frames, and whether the radiosity solver
/// was at work in each.
#[derive(Debug, Default)]
pub struct FrameClock {
    last: Option<Instant>,
    /// (ms, solving) of each frame after the first.
    frames: Vec<(f64, bool)>,
}

impl FrameClock {
    /// Marks the start of a frame of `app`: records the time since the last one and
    /// whether the solver is at work, and smooths it into the status bar's frame time.
    pub fn tick(&mut self, app: &mut ViewerApp) {
        let now = Instant::now();
        let Some(last) = self.last.replace(now) else {
            return;
        };
        let ms = (now - last).as_secs_f64() * 1000.0;
        self.frames.push((ms, app.solving()));
        let s = &mut app.status.frame_ms;
        *s = if *s == 0.0 { ms } else { 0.9 * *s + 0.1 * ms };
    }

    /// Fills the frame-time fields of `summary`.
    pub fn summarise(&self, summary: &mut RunSummary) {
        let all: Vec<f64> = self.frames.iter().map(|f| f.0).collect();
        let solving: Vec<f64> = self.frames.iter().filter(|f| f.1).map(|f| f.0).collect();
        summary.mean_frame_ms = mean(&all);
        summary.p95_frame_ms = percentile(&all, 0.95);
        summary.max_frame_ms = all.iter().copied().fold(0.0, f64::max);
        summary.solving_frames = solving.len() as u64;
        summary.solving_mean_frame_ms = mean(&solving);
        summary.solving_p95_frame_ms = percentile(&solving, 0.95);
    }
}

/// The mean of `v`; 0 for none.
fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.iter().sum::<f64>() / v.len() as f64
}

/// The `q` quantile (nearest rank) of `v`; 0 for none.
fn percentile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let rank = ((q * s.len() as f64).ceil() as usize).clamp(1, s.len());
    s[rank - 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_by_nearest_rank() {
        let v: Vec<f64> = (1..=20).map(f64::from).collect();
        assert_eq!(percentile(&v, 0.95), 19.0);
        assert_eq!(percentile(&v, 0.5), 10.0);
        assert_eq!(percentile(&v, 1.0), 20.0);
        assert_eq!(percentile(&[], 0.95), 0.0);
        assert_eq!(percentile(&[7.0], 0.95), 7.0);
    }

    #[test]
    fn the_clock_splits_frames_while_solving() {
        let clock = FrameClock {
            frames: vec![(10.0, true), (30.0, true), (100.0, false)],
            ..FrameClock::default()
        };
        let mut s = RunSummary::default();
        clock.summarise(&mut s);
        assert!((s.mean_frame_ms - 140.0 / 3.0).abs() < 1e-9);
        assert_eq!(s.max_frame_ms, 100.0);
        assert_eq!(s.solving_frames, 2);
        assert_eq!(s.solving_mean_frame_ms, 20.0);
        assert_eq!(s.solving_p95_frame_ms, 30.0);
    }
}
