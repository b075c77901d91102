//! `view --headless --frames N`: the viewer's frames rendered offscreen, without a window
//! or a display — the same UI pass, viewport render and painting as in a window, minus
//! presenting. For measuring frame rates on GPUs that have no display (a compute server)
//! and for checks without Xvfb.

use std::sync::Arc;
use std::time::Instant;

use anyhow::anyhow;

use super::app::ViewerApp;
use super::frame::{FrameClock, FramePainter, RunSummary, WindowOptions, WORKERS_STOP_LIMIT};
use crate::gpu::Gpu;

/// The format frames are painted in (egui blends in gamma space).
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Renders `options.frames` frames of `app` offscreen at `options.size` (pixels, one pixel
/// per point), each waited for on the GPU, and reports them as a window run would.
pub fn run(mut app: ViewerApp, options: WindowOptions) -> anyhow::Result<RunSummary> {
    let frames = options
        .frames
        .ok_or_else(|| anyhow!("a headless viewer needs a number of frames (--frames N)"))?;
    let gpu = Arc::new(Gpu::headless()?);
    let mut summary = RunSummary {
        headless: true,
        ..RunSummary::default()
    };
    summary.start(&mut app, &gpu, FORMAT);
    let mut clock = FrameClock::default();
    let drawn = draw(&mut app, &gpu, &options, frames, &mut summary, &mut clock);
    app.stop_background(WORKERS_STOP_LIMIT);
    drawn?;
    Ok(summary.finish(&app, &clock))
}

/// Draws the frames into an offscreen target, then reads the centre's lux and saves the
/// screenshot.
fn draw(
    app: &mut ViewerApp,
    gpu: &Arc<Gpu>,
    options: &WindowOptions,
    frames: u64,
    summary: &mut RunSummary,
    clock: &mut FrameClock,
) -> anyhow::Result<()> {
    let mut painter = FramePainter::new(gpu.clone(), FORMAT);
    let size_px = options.size;
    let target = painter.offscreen_target(size_px);
    let view = target.create_view(&Default::default());
    let max_texture_side = gpu.device.limits().max_texture_dimension_2d as usize;
    let began = Instant::now();
    for n in 1..=frames {
        clock.tick(app);
        let raw = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(size_px[0] as f32, size_px[1] as f32),
            )),
            time: Some(began.elapsed().as_secs_f64()),
            max_texture_side: Some(max_texture_side),
            ..Default::default()
        };
        let frame = painter.prepare(app, raw, size_px)?;
        painter.paint(&frame, &view);
        painter.finish(frame);
        // As a window's present would, the frame ends when the GPU has drawn it.
        gpu.wait()?;
        summary.frames = n;
    }
    summary.window_px = size_px;
    summary.centre_lux = painter.viewport.centre_lux(gpu)?;
    if let Some(path) = &options.screenshot {
        painter.save(&target, path)?;
        summary.screenshot = Some(path.clone());
    }
    Ok(())
}
