//! `goniolight view`: the viewer's options, checked and handed to [`crate::viewer::start`].

use std::path::PathBuf;

use anyhow::anyhow;
use clap::Args;

use super::error::CliError;
use crate::viewer::{start, window::WindowOptions, StartOptions};

/// Options of `view`.
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A scene file (TOML) or an OBJ or glTF model (default: the bundled furnished room).
    pub path: Option<PathBuf>,
    /// Render this many frames, then exit (with --screenshot: 3 unless given).
    #[arg(long)]
    pub frames: Option<u64>,
    /// After the last frame, save the whole window (UI included) as PNG and exit.
    #[arg(long)]
    pub screenshot: Option<PathBuf>,
    /// Render the frames offscreen, without a window or a display (needs --frames or
    /// --screenshot; the size is then in pixels). The summary's frame times are the
    /// viewer's own work, GPU included, without presenting.
    #[arg(long)]
    pub headless: bool,
    /// Window width, logical pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Window height, logical pixels.
    #[arg(long, default_value_t = 800)]
    pub height: u32,
    /// Luminaire files to add to the scene at start (as if dropped on the window).
    #[arg(long = "add", value_name = "LDT|IES")]
    pub add: Vec<PathBuf>,
    /// Up axis of an OBJ or glTF model given as PATH: y (most exporters) or z.
    #[arg(long, value_enum, default_value = "y")]
    pub up: crate::scene::UpAxis,
    /// Mode at start: shaded or illuminance (default: the scene's).
    #[arg(long, value_enum)]
    pub mode: Option<crate::scene::Mode>,
    /// Turn the sun on at this local time (HH:MM) at start, with shadow volumes (the
    /// site and date are set in the Sun panel; default Vienna on the summer solstice).
    #[arg(long, value_name = "HH:MM")]
    pub sun: Option<String>,
    /// Show effect lights turned to this many seconds and hold them there (default: they
    /// turn from 0 while the window is open).
    #[arg(long, value_name = "SECONDS")]
    pub time: Option<f64>,
    /// Light shown besides the luminaires' direct light at start: none, ambient (their
    /// first bounce and the ambient term) or radiosity (solved in the background, shown
    /// as it converges); default: the scene's display.indirect, else none.
    #[arg(long, value_enum)]
    pub indirect: Option<crate::scene::DisplayIndirect>,
    /// What drives the viewer's radiosity: global (the whole scene), importance or
    /// perspective (the camera's view, followed as it moves); also in the Radiosity panel.
    #[arg(long, value_enum, default_value = "global")]
    pub drive: crate::radiosity::view::Drive,
    /// Milliseconds of radiosity solving each displayed frame grants, so the window stays
    /// interactive while it converges (0: no limit).
    #[arg(long, value_name = "MS", default_value_t = 40.0)]
    pub solver_ms_per_frame: f64,
}

/// Runs `view`.
pub fn run(args: ViewArgs) -> Result<(), CliError> {
    let bad = |m: String| Err(CliError::input(anyhow!(m)));
    if args.frames == Some(0) {
        return bad("--frames must be at least 1".into());
    }
    for (name, v) in [("--width", args.width), ("--height", args.height)] {
        if !(64..=8192).contains(&v) {
            return bad(format!("{name} {v} is not in 64..=8192"));
        }
    }
    if args.headless && args.frames.is_none() && args.screenshot.is_none() {
        return bad(
            "--headless needs --frames N (or --screenshot): it has no window to close".into(),
        );
    }
    if let Some(s) = &args.screenshot {
        if image::ImageFormat::from_path(s).ok() != Some(image::ImageFormat::Png) {
            return bad(format!("--screenshot {}: must end in .png", s.display()));
        }
    }
    let sun_time = match &args.sun {
        None => None,
        Some(t) => Some(
            chrono::NaiveTime::parse_from_str(t.trim(), "%H:%M")
                .map_err(|e| CliError::input(anyhow!("--sun {t:?}: not a time HH:MM ({e})")))?,
        ),
    };
    if let Some(t) = args.time {
        if !t.is_finite() {
            return bad(format!("--time {t} is not a finite number"));
        }
    }
    if !(args.solver_ms_per_frame.is_finite() && (0.0..=1000.0).contains(&args.solver_ms_per_frame))
    {
        return bad(format!(
            "--solver-ms-per-frame {} is not in 0..=1000",
            args.solver_ms_per_frame
        ));
    }
    let options = StartOptions {
        path: args.path.clone(),
        add: args.add.clone(),
        up: args.up,
        mode: args.mode,
        sun_time,
        time_s: args.time,
        indirect: args.indirect,
        drive: args.drive,
        solver_ms_per_frame: Some(args.solver_ms_per_frame),
        window: WindowOptions {
            size: [args.width, args.height],
            frames: args.frames.or(args.screenshot.as_ref().map(|_| 3)),
            screenshot: args.screenshot.clone(),
            headless: args.headless,
        },
    };
    let summary = start(options)?;
    if args.frames.is_some() || args.screenshot.is_some() {
        println!(
            "{}",
            serde_json::to_string(&summary).map_err(CliError::failure)?
        );
    }
    Ok(())
}
