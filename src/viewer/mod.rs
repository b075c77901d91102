//! The interactive viewer (`goniolight view`): winit + egui around the renderer, with
//! luminaires to add, place and inspect, display and shadow settings, the sun and its
//! shadow profiles, and progressive radiosity in the background. The UI state
//! ([`app::ViewerApp`]) is separate from the window so that tests drive it headless.

pub mod app;
mod app_files;
mod background;
pub mod camera;
pub mod files;
pub mod frame;
mod headless;
pub mod jobs;
pub mod live_radiosity;
pub mod luminaires;
mod panels;
pub mod photometry_sheet;
pub mod sun;
pub mod viewport_gpu;
pub mod viewport_ui;
pub mod window;
pub mod work;

use std::path::PathBuf;

use app::ViewerApp;
use files::{load_scene_or_model, RecentFiles};

/// The scene `view` opens without an argument, relative to [`crate::io::data_root`].
pub use crate::io::bundled::DEFAULT_SCENE;

/// A failed viewer start or run.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// The scene, model or a luminaire given at start is unusable (bad input).
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// A luminaire given at start was refused (bad input).
    #[error("{0}")]
    Luminaire(String),
    /// The window, the GPU or a screenshot failed.
    #[error("{0}")]
    Window(String),
}

impl ViewerError {
    /// True when the user's input caused it (a command exits 2 then).
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, ViewerError::Window(_))
    }
}

/// What the viewer opens with.
#[derive(Debug, Clone, Default)]
pub struct StartOptions {
    /// A scene file (TOML) or an OBJ model; `None`: the bundled furnished room.
    pub path: Option<PathBuf>,
    /// Luminaire files added at start (as if dropped on the window).
    pub add: Vec<PathBuf>,
    /// Up axis of an OBJ model given as `path`.
    pub up: crate::scene::UpAxis,
    /// Mode at start (default: the scene's).
    pub mode: Option<crate::scene::Mode>,
    /// Turn the sun on at this local time, with shadow volumes.
    pub sun_time: Option<chrono::NaiveTime>,
    /// Hold effect lights at this animation time, seconds (default: they turn).
    pub time_s: Option<f64>,
    /// Indirect light at start (default: the scene's `display.indirect`, else none).
    pub indirect: Option<crate::scene::DisplayIndirect>,
    /// What drives the radiosity solver (the Radiosity panel's "Driven by").
    pub drive: crate::radiosity::view::Drive,
    /// Milliseconds of solving each frame grants the radiosity solver (0: no limit;
    /// `None`: the panel's default).
    pub solver_ms_per_frame: Option<f64>,
    /// The window's size, how many frames to render before exiting and the screenshot.
    pub window: window::WindowOptions,
}

/// Opens the viewer and runs it until the window closes (or the frames given are drawn).
pub fn start(options: StartOptions) -> Result<window::RunSummary, ViewerError> {
    let path = match &options.path {
        Some(p) => p.clone(),
        None => crate::io::bundled::default_scene()
            .map_err(|e| ViewerError::Window(format!("{e:#}")))?,
    };
    let up = options.up;
    let scene = load_scene_or_model(&path, up)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    let is_scene = !scene.path.as_os_str().is_empty();
    let indirect = options
        .indirect
        .or(scene.display.indirect)
        .unwrap_or_default();
    let mut app = ViewerApp::new(
        scene,
        is_scene.then(|| path.clone()),
        RecentFiles::load(RecentFiles::default_store()),
    );
    for l in &options.add {
        if !app.add_luminaire(l) {
            let why = app.last_error().unwrap_or("luminaire not added");
            return Err(ViewerError::Luminaire(why.to_string()));
        }
    }
    app.obj_up = up;
    app.radiosity.start_with = indirect;
    app.radiosity.settings.options.drive = options.drive;
    if let Some(ms) = options.solver_ms_per_frame {
        app.radiosity.settings.frame_budget_ms = ms;
    }
    if let Some(m) = options.mode {
        app.display.mode = m;
    }
    if let Some(t) = options.time_s {
        app.effects_time_s = t;
        app.animate_effects = false;
    }
    if let Some(time) = options.sun_time {
        app.sun.set_time(time);
        app.sun.enabled = true;
        app.display.shadows.technique = crate::shadow::ShadowTechnique::Volumes;
    }
    let ran = if options.window.headless {
        headless::run(app, options.window)
    } else {
        window::run(app, options.window)
    };
    ran.map_err(|e| ViewerError::Window(format!("{e:#}")))
}
