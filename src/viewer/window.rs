//! The window: winit event loop, wgpu surface, egui input and painting, and the
//! viewport's GPU rendering. With a frame count it renders that many frames, optionally
//! saves the whole window as a PNG, and exits (how tests and CI drive it under Xvfb).

use std::sync::Arc;
use std::time::Instant;

use anyhow::{anyhow, Context as _};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

use super::app::ViewerApp;
use super::frame::{FrameClock, FramePainter, WORKERS_STOP_LIMIT};
pub use super::frame::{RunSummary, WindowOptions};
use crate::gpu::Gpu;

struct Running {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    egui_state: egui_winit::State,
    painter: FramePainter,
}

struct Handler {
    app: ViewerApp,
    options: WindowOptions,
    running: Option<Running>,
    error: Option<anyhow::Error>,
    summary: RunSummary,
    clock: FrameClock,
    next_repaint: Option<Instant>,
}

/// Opens the window and runs the viewer until it is closed (or has rendered
/// `options.frames` frames).
pub fn run(app: ViewerApp, options: WindowOptions) -> anyhow::Result<RunSummary> {
    let event_loop = EventLoop::new().map_err(|e| {
        anyhow!("cannot open a window: {e}. The viewer needs a display (X11 or Wayland); on a machine without one run it under Xvfb: `xvfb-run -a goniolight view …`, or render its frames offscreen with `view --headless --frames N`")
    })?;
    let mut handler = Handler {
        app,
        options,
        running: None,
        error: None,
        summary: RunSummary::default(),
        clock: FrameClock::default(),
        next_repaint: None,
    };
    let ran = event_loop.run_app(&mut handler).context("event loop");
    handler.app.stop_background(WORKERS_STOP_LIMIT);
    ran?;
    if let Some(e) = handler.error {
        return Err(e);
    }
    Ok(handler.summary.finish(&handler.app, &handler.clock))
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
        let painter = FramePainter::new(gpu.clone(), format);
        let egui_state = egui_winit::State::new(
            painter.egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        self.summary.start(&mut self.app, &gpu, format);
        Ok(Running {
            window,
            surface,
            config,
            egui_state,
            painter,
        })
    }

    fn frame(&mut self, event_loop: &ActiveEventLoop) -> anyhow::Result<()> {
        let Some(r) = &mut self.running else {
            return Ok(());
        };
        let now = Instant::now();
        self.clock.tick(&mut self.app);
        let raw = r.egui_state.take_egui_input(&r.window);
        let size_px = [r.config.width, r.config.height];
        let mut frame = r.painter.prepare(&mut self.app, raw, size_px)?;
        let platform_output = std::mem::take(&mut frame.platform_output);
        r.egui_state
            .handle_platform_output(&r.window, platform_output);
        let surface_texture = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                r.surface.configure(&r.painter.gpu.device, &r.config);
                r.window.request_redraw();
                r.painter.finish(frame);
                return Ok(());
            }
            _ => {
                r.window.request_redraw();
                r.painter.finish(frame);
                return Ok(());
            }
        };
        let view = surface_texture.texture.create_view(&Default::default());
        r.painter.paint(&frame, &view);
        let frames_done = self.summary.frames + 1;
        let last = self.options.frames.is_some_and(|n| frames_done >= n);
        if last {
            self.summary.centre_lux = r.painter.viewport.centre_lux(&r.painter.gpu)?;
            if let Some(path) = self.options.screenshot.clone() {
                // The same frame painted offscreen (a surface texture cannot be read).
                let texture = r.painter.offscreen_target(size_px);
                r.painter
                    .paint(&frame, &texture.create_view(&Default::default()));
                r.painter.save(&texture, &path)?;
                self.summary.screenshot = Some(path);
            }
        }
        r.painter.gpu.queue.present(surface_texture);
        self.next_repaint = now.checked_add(frame.repaint_delay);
        r.painter.finish(frame);
        self.summary.frames = frames_done;
        self.summary.window_px = size_px;
        if last {
            event_loop.exit();
        }
        Ok(())
    }
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
                r.surface.configure(&r.painter.gpu.device, &r.config);
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
