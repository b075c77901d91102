//! The window: winit event loop, wgpu surface, egui input and painting, and the
//! viewport's GPU rendering. With a frame count it renders that many frames, optionally
//! saves the whole window as a PNG, and exits (how tests and CI drive it under Xvfb).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{anyhow, Context as _};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

use super::app::ViewerApp;
use super::viewport::Viewport;
use crate::gpu::Gpu;

/// How the window runs.
#[derive(Debug, Clone, Default)]
pub struct WindowOptions {
    /// Inner size, logical pixels.
    pub size: [u32; 2],
    /// Render this many frames, then exit.
    pub frames: Option<u64>,
    /// After the last frame, save the window (UI included) here as PNG.
    pub screenshot: Option<PathBuf>,
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
    /// Mean frame time over the frames after the first, ms.
    pub mean_frame_ms: f64,
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

struct Running {
    window: Arc<Window>,
    gpu: Arc<Gpu>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    viewport: Viewport,
}

struct Handler {
    app: ViewerApp,
    options: WindowOptions,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    summary: RunSummary,
    last_frame: Option<Instant>,
    frame_ms: Vec<f64>,
    next_repaint: Option<Instant>,
}

/// Opens the window and runs the viewer until it is closed (or has rendered
/// `options.frames` frames).
pub fn run(app: ViewerApp, options: WindowOptions) -> anyhow::Result<RunSummary> {
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow!("cannot open a window: {e}. The viewer needs a display (X11 or Wayland); on a machine without one run it under Xvfb: `xvfb-run -a goniolight view …`")
    })?;
    let mut handler = Handler {
        app,
        options,
        running: None,
        error: None,
        summary: RunSummary::default(),
        last_frame: None,
        frame_ms: Vec::new(),
        next_repaint: None,
    };
    event_loop.run_app(&mut handler).context("event loop")?;
    if let Some(e) = handler.error {
        return Err(e);
    }
    let n = handler.frame_ms.len().max(1) as f64;
    handler.summary.mean_frame_ms = handler.frame_ms.iter().sum::<f64>() / n;
    let radiosity = &handler.app.radiosity;
    handler.summary.indirect_shown = radiosity.light_map.is_some();
    handler.summary.indirect_shots = radiosity.shots;
    handler.summary.indirect_status = radiosity.status.clone();
    Ok(handler.summary)
}

impl Handler {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<Running> {
        let [w, h] = self.options.size;
        let attrs = Window::default_attributes()
            .with_title("goniolight")
            .with_inner_size(winit::dpi::LogicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attrs)
                .context("creating the window")?,
        );
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window.clone())
            .context("creating the window's GPU surface")?;
        let gpu = Arc::new(Gpu::with_instance(instance, Some(&surface))?);
        let caps = surface.get_capabilities(&gpu.adapter);
        // egui blends in gamma space and prefers a plain 8-bit surface.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Bgra8Unorm
                )
            })
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| anyhow!("the GPU {} cannot present to this window", gpu.describe()))?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
        };
        surface.configure(&gpu.device, &config);
        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer =
            egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        self.app.status.gpu = gpu.describe();
        self.app.gpu = Some(gpu.clone());
        self.app.start_indirect();
        self.summary.gpu = gpu.describe();
        self.summary.surface_format = format!("{format:?}");
        Ok(Running {
            viewport: Viewport::new(&gpu),
            window,
            gpu,
            surface,
            config,
            egui_ctx,
            egui_state,
            egui_renderer,
        })
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(r) = &mut self.running else {
            return Ok(());
        };
        let now = Instant::now();
        if let Some(last) = self.last_frame.replace(now) {
            let ms = (now - last).as_secs_f64() * 1000.0;
            self.frame_ms.push(ms);
            let s = &mut self.app.status.frame_ms;
            *s = if *s == 0.0 { ms } else { 0.9 * *s + 0.1 * ms };
        }
        let raw = r.egui_state.take_egui_input(&r.window);
        let app = &mut self.app;
        let mut full = r.egui_ctx.run_ui(raw, |ui| app.ui(ui));
        let mut textures = std::mem::take(&mut full.textures_delta);
        for (id, deltas) in textures.set.drain() {
            for delta in deltas {
                r.egui_renderer
                    .update_texture(&r.gpu.device, &r.gpu.queue, id, &delta);
            }
        }
        // Freed after painting (or now, if this frame is not painted).
        let free = std::mem::take(&mut textures.free);
        let free_textures = |renderer: &mut egui_wgpu::Renderer| {
            for id in &free {
                renderer.free_texture(id);
            }
        };
        r.egui_state
            .handle_platform_output(&r.window, full.platform_output);
        r.viewport
            .update(&r.gpu, &mut self.app, &mut r.egui_renderer)?;
        let jobs = r.egui_ctx.tessellate(full.shapes, full.pixels_per_point);
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [r.config.width, r.config.height],
            pixels_per_point: full.pixels_per_point,
        };
        let surface_texture = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                r.surface.configure(&r.gpu.device, &r.config);
                r.window.request_redraw();
                free_textures(&mut r.egui_renderer);
                return Ok(());
            }
            _ => {
                r.window.request_redraw();
                free_textures(&mut r.egui_renderer);
                return Ok(());
            }
        };
        let view = surface_texture.texture.create_view(&Default::default());
        paint(&r.gpu, &mut r.egui_renderer, &jobs, &screen, &view);
        let frames_done = self.summary.frames + 1;
        let last = self.options.frames.is_some_and(|n| frames_done >= n);
        if last {
            self.summary.centre_lux = r.viewport.centre_lux(&r.gpu)?;
            if let Some(path) = self.options.screenshot.clone() {
                capture(r, &jobs, &screen, &path)?;
                self.summary.screenshot = Some(path);
            }
        }
        r.gpu.queue.present(surface_texture);
        free_textures(&mut r.egui_renderer);
        self.summary.frames = frames_done;
        self.summary.window_px = [r.config.width, r.config.height];
        self.summary.viewport_px = self.app.status.viewport_rect_px;
        let delay = full
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        self.next_repaint = now.checked_add(delay);
        if last {
            event_loop.exit();
        }
        Ok(())
    }
}

/// Paints egui (the viewport image is one of its textures) into `target`.
fn paint(
    gpu: &Gpu,
    renderer: &mut egui_wgpu::Renderer,
    jobs: &[egui::ClippedPrimitive],
    screen: &egui_wgpu::ScreenDescriptor,
    target: &wgpu::TextureView,
) {
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    let extra = renderer.update_buffers(&gpu.device, &gpu.queue, &mut enc, jobs, screen);
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
        renderer.render(&mut pass, jobs, screen);
    }
    gpu.queue.submit(extra.into_iter().chain([enc.finish()]));
}

/// Paints the same frame into an offscreen texture of the surface's format and saves it.
fn capture(
    r: &mut Running,
    jobs: &[egui::ClippedPrimitive],
    screen: &egui_wgpu::ScreenDescriptor,
    path: &std::path::Path,
) -> anyhow::Result<()> {
    let (w, h, format) = (r.config.width, r.config.height, r.config.format);
    let texture = r.gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("window capture"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    paint(&r.gpu, &mut r.egui_renderer, jobs, screen, &view);
    let mut bytes = r.gpu.read_texture(&texture)?;
    match format {
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => {
            bytes.chunks_exact_mut(4).for_each(|p| p.swap(0, 2))
        }
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => {}
        other => return Err(anyhow!("cannot save a window of format {other:?}")),
    }
    bytes.chunks_exact_mut(4).for_each(|p| p[3] = 255);
    let image = image::RgbaImage::from_raw(w, h, bytes).context("capture size mismatch")?;
    crate::render::output::write_image(path, &image)
}

impl ApplicationHandler for Handler {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(r) => {
                r.window.request_redraw();
                self.running = Some(r);
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(r) = &mut self.running else { return };
        let response = r.egui_state.on_window_event(&r.window, &event);
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                r.config.width = size.width.max(1);
                r.config.height = size.height.max(1);
                r.surface.configure(&r.gpu.device, &r.config);
                r.window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.frame(event_loop) {
                    self.error = Some(e);
                    event_loop.exit();
                }
                return;
            }
            _ => {}
        }
        if response.repaint {
            r.window.request_redraw();
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(r) = &self.running else { return };
        let due = self.next_repaint.is_some_and(|t| t <= Instant::now());
        if self.options.frames.is_some() || self.app.busy() || due {
            r.window.request_redraw();
            event_loop.set_control_flow(ControlFlow::Wait);
        } else if let Some(t) = self.next_repaint {
            event_loop.set_control_flow(ControlFlow::WaitUntil(t));
        } else {
            event_loop.set_control_flow(ControlFlow::Wait);
        }
    }
}
