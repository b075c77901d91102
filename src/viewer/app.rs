//! The viewer's state, free of windowing, GPU code and egui drawing so that it runs
//! headless in tests: the window ([`super::window`]) feeds it input, renders the scene
//! it describes into the viewport texture and reports back frame time and the lux
//! under the cursor. Its panels draw it (`panels`, `luminaires`, `work`, `viewport_ui`);
//! its background work is started and polled in `background`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;

use super::camera::ViewCamera;
use super::files::{Dialog, RecentFiles};
use super::jobs::{ProfileUpdate, Worker};
use super::live_radiosity::{LiveLink, RadiositySettings, RadiosityUpdate};
use super::sun::SunControls;
use crate::gpu::Gpu;
use crate::render::lightmap::LightMap;
use crate::render::RenderSettings;
use crate::scene::{PlacedLuminaire, Scene};
use crate::study::shadow_profile::Profile;
use crate::study::view_hours::ViewHours;

/// How serious a message is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Something happened.
    Info,
    /// Something was refused; nothing changed.
    Error,
}

/// A line in the message bar.
#[derive(Debug, Clone, PartialEq)]
pub struct Message {
    /// Its level.
    pub level: Level,
    /// Its text.
    pub text: String,
}

/// Aim of a luminaire as the panel edits it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AimControls {
    /// Angle of γ = 0 from straight down, degrees.
    pub tilt_deg: f64,
    /// Heading of the tilt, degrees counter-clockwise from +X.
    pub azimuth_deg: f64,
    /// Rotation about the aim, degrees.
    pub roll_deg: f64,
}

impl AimControls {
    /// The controls that reproduce `rotation`.
    pub fn of(rotation: glam::DMat3) -> AimControls {
        let (aim, roll) = crate::scene::save::aim_and_roll(rotation);
        AimControls {
            tilt_deg: (-aim.z).clamp(-1.0, 1.0).acos().to_degrees(),
            azimuth_deg: aim.y.atan2(aim.x).to_degrees(),
            roll_deg: roll,
        }
    }

    /// The luminaire frame they describe.
    pub fn rotation(&self) -> glam::DMat3 {
        let (t, a) = (self.tilt_deg.to_radians(), self.azimuth_deg.to_radians());
        let aim = DVec3::new(t.sin() * a.cos(), t.sin() * a.sin(), -t.cos());
        crate::scene::placement::aim_frame(Some(aim), self.roll_deg)
    }
}

/// The radiosity panel.
#[derive(Default)]
pub struct RadiosityState {
    /// Settings of the next run.
    pub settings: RadiositySettings,
    /// The running (or paused, or converged and waiting) solver.
    pub worker: Option<Worker<RadiosityUpdate>>,
    /// Commands and frame credit of the running solver.
    pub link: Option<LiveLink>,
    /// Whether the solver has converged and waits for a change.
    pub waiting: bool,
    /// The view the solver was last given (camera, width / height), and since when the
    /// camera has been elsewhere.
    pub followed: Option<(crate::scene::Camera, f64)>,
    /// When the camera was last seen away from [`RadiosityState::followed`].
    pub moved_at: Option<std::time::Instant>,
    /// Whether the worker is paused.
    pub paused: bool,
    /// (seconds, converged fraction) of every shot.
    pub log: Vec<[f64; 2]>,
    /// Shots so far.
    pub shots: usize,
    /// Elements of the current run.
    pub elements: usize,
    /// The displayed solution.
    pub light_map: Option<Arc<LightMap>>,
    /// What the solver said last.
    pub status: String,
    /// Indirect light to start as soon as the GPU is there (`view --indirect`).
    pub start_with: crate::scene::DisplayIndirect,
}

/// What the shadow-profile window shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ProfileShown {
    /// Every step's shadow on the plan.
    #[default]
    Profile,
    /// Hours in shadow per plan cell.
    HoursInShadow,
    /// Hours of sun on the model, seen from the camera the profile was started with.
    SunOnModel,
}

/// The shadow-profile panel.
#[derive(Default)]
pub struct ProfileState {
    /// The running computation.
    pub worker: Option<Worker<ProfileUpdate>>,
    /// Steps done of the total.
    pub progress: (usize, usize),
    /// The last profile.
    pub result: Option<Arc<Profile>>,
    /// The hours of sun on the model seen from the camera when the profile was started.
    pub view: Option<Arc<ViewHours>>,
    /// What the window shows.
    pub shown: ProfileShown,
    /// The image shown (rebuilt when the result or the choice changes).
    pub texture: Option<egui::TextureHandle>,
    /// Whether its window is open.
    pub open: bool,
}

/// Frame statistics and read-outs the window fills in.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameStatus {
    /// Smoothed frame time, ms.
    pub frame_ms: f64,
    /// The GPU.
    pub gpu: String,
    /// The viewport's size in physical pixels.
    pub viewport_px: [u32; 2],
    /// Where the viewport lies in the window, physical pixels (x, y, w, h).
    pub viewport_rect_px: [u32; 4],
    /// The pixel of the viewport under the cursor.
    pub cursor_px: Option<[u32; 2]>,
    /// Illuminance there, lux (None off the surfaces).
    pub cursor_lux: Option<f64>,
    /// Luminance there, cd/m².
    pub cursor_luminance: Option<f64>,
    /// Top of the false-colour scale of the last frame.
    pub lux_max: f64,
}

/// Work the window does for the UI at the end of the frame.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Requests {
    /// Save the view as PNG + EXR at this path (PNG; the EXR beside it).
    pub screenshot: Option<PathBuf>,
}

/// The viewer.
pub struct ViewerApp {
    /// The scene being edited.
    pub scene: Scene,
    /// Where it was loaded from or saved to.
    pub scene_path: Option<PathBuf>,
    /// The camera.
    pub camera: ViewCamera,
    /// Display choices.
    pub display: RenderSettings,
    /// Aim controls, one per luminaire of the scene.
    pub aims: Vec<AimControls>,
    /// The luminaire being edited.
    pub selected: Option<usize>,
    /// The luminaire whose photometry window is open.
    pub photometry: Option<usize>,
    /// What the photometry window shows (C plane, datasheet diagram).
    pub photometry_view: super::photometry_sheet::PhotometryView,
    /// The sun.
    pub sun: SunControls,
    /// Radiosity.
    pub radiosity: RadiosityState,
    /// Shadow profile.
    pub profile: ProfileState,
    /// Messages, newest last.
    pub messages: Vec<Message>,
    /// Recently opened or saved scenes.
    pub recent: RecentFiles,
    /// Bumped whenever what the GPU shows changes (luminaires, sun, light map).
    pub revision: u64,
    /// Read-outs from the window.
    pub status: FrameStatus,
    /// The viewport texture (registered by the window).
    pub viewport_texture: Option<egui::TextureId>,
    /// Work for the window.
    pub requests: Requests,
    /// The GPU background jobs run on (None in UI tests).
    pub gpu: Option<Arc<Gpu>>,
    /// A file dialog open on its own thread.
    pub dialog: Option<Dialog>,
    /// Text of the "add luminaire from path" field.
    pub add_path: String,
    /// Text of the screenshot path field.
    pub screenshot_path: String,
    /// The up axis of OBJ models opened.
    pub obj_up: crate::scene::UpAxis,
    /// Whether effect lights turn (View menu).
    pub animate_effects: bool,
    /// Seconds of effect-light animation shown.
    pub effects_time_s: f64,
}

impl ViewerApp {
    /// A viewer showing `scene` (loaded from `path`, if any).
    pub fn new(scene: Scene, path: Option<PathBuf>, recent: RecentFiles) -> ViewerApp {
        let mut app = ViewerApp {
            camera: ViewCamera::from_camera(&scene.camera),
            display: RenderSettings::from_display(&scene.display),
            aims: Vec::new(),
            scene,
            scene_path: path,
            selected: None,
            photometry: None,
            photometry_view: Default::default(),
            sun: SunControls::default(),
            radiosity: RadiosityState::default(),
            profile: ProfileState::default(),
            messages: Vec::new(),
            recent,
            revision: 0,
            status: FrameStatus::default(),
            viewport_texture: None,
            requests: Requests::default(),
            gpu: None,
            dialog: None,
            add_path: String::new(),
            screenshot_path: "screenshot.png".into(),
            obj_up: crate::scene::UpAxis::Y,
            animate_effects: true,
            effects_time_s: 0.0,
        };
        app.aims = app
            .scene
            .luminaires
            .iter()
            .map(|l| AimControls::of(l.rotation))
            .collect();
        if let Some(p) = &app.scene_path {
            app.recent.add(p);
        }
        app.say_what_the_scene_needs();
        app
    }

    /// Says once per scene what its loading worked around ([`Scene::warnings`]) and what
    /// the view does with mirrors and clear glass.
    fn say_what_the_scene_needs(&mut self) {
        for w in self.scene.warnings.clone() {
            self.info(format!("warning: {w}"));
        }
        self.say_what_mirrors_show();
    }

    /// Says what the view does with mirrors and clear glass: it draws them by their
    /// diffuse part, and its direct light (and the lux under the cursor) leaves out what
    /// they pass on until radiosity has solved.
    fn say_what_mirrors_show(&mut self) {
        if let Some(m) = self.scene.specular_material() {
            let text = format!(
                "material {:?} is a mirror or clear glass: the view draws it by its diffuse \
                 part, and its direct light leaves out what it passes on (radiosity and \
                 calc include it)",
                m.name
            );
            self.info(text);
        }
    }

    /// Adds an info line.
    pub fn info(&mut self, text: impl Into<String>) {
        self.push(Level::Info, text.into());
    }

    /// Adds an error line.
    pub fn error(&mut self, text: impl Into<String>) {
        self.push(Level::Error, text.into());
    }

    fn push(&mut self, level: Level, text: String) {
        self.messages.push(Message { level, text });
        if self.messages.len() > 50 {
            self.messages.remove(0);
        }
    }

    /// The latest error, if the newest message is one.
    pub fn last_error(&self) -> Option<&str> {
        self.messages
            .last()
            .filter(|m| m.level == Level::Error)
            .map(|m| m.text.as_str())
    }

    /// Marks the lights as changed: the GPU scene is rebuilt, and a running radiosity
    /// solver is told the new luminaires and re-shoots their change in place (a solution
    /// without a solver is dropped).
    pub fn lights_changed(&mut self) {
        self.revision += 1;
        let scene = Box::new(self.render_scene());
        let interp = self.display.light_model.interp();
        let r = &mut self.radiosity;
        let relit = match (&r.worker, &r.link) {
            (Some(_), Some(link)) => link
                .commands
                .send(super::live_radiosity::RadiosityCommand::Relight(
                    scene, interp,
                ))
                .is_ok(),
            _ => false,
        };
        if relit {
            r.waiting = false;
            r.status = "relighting: re-shooting the luminaires' change…".into();
        } else if r.worker.is_some() || r.light_map.is_some() {
            self.reset_radiosity();
            self.info("radiosity reset: the lights changed");
        }
    }

    /// Loads a luminaire file and hangs it pointing down under the top of the scene.
    /// A file that does not load changes nothing and leaves an error naming it.
    pub fn add_luminaire(&mut self, path: &Path) -> bool {
        let luminaire = match crate::photometry::Luminaire::load(path) {
            Ok(l) => l,
            Err(e) => {
                self.error(format!("{}: not added: {e}", path.display()));
                return false;
            }
        };
        let (lo, hi) = self.scene.bounds();
        let position = DVec3::new((lo.x + hi.x) / 2.0, (lo.y + hi.y) / 2.0, hi.z - 0.1);
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "luminaire".into());
        let mut placed = PlacedLuminaire::new(&name, luminaire, position);
        placed.file = path.to_path_buf();
        self.scene.luminaires.push(placed);
        self.aims.push(AimControls::of(glam::DMat3::IDENTITY));
        self.selected = Some(self.scene.luminaires.len() - 1);
        self.info(format!("added {}", path.display()));
        self.lights_changed();
        true
    }

    /// Removes luminaire `i`.
    pub fn remove_luminaire(&mut self, i: usize) {
        if i < self.scene.luminaires.len() {
            let l = self.scene.luminaires.remove(i);
            self.aims.remove(i);
            self.selected = None;
            if self.photometry == Some(i) {
                self.photometry = None;
            }
            self.info(format!("removed {}", l.name));
            self.lights_changed();
        }
    }

    /// The scene the GPU shows: the edited scene plus the sun when it is on and up.
    pub fn render_scene(&self) -> Scene {
        // Effect lights turned as far as the animation has run.
        let mut scene = self.scene.at_time(self.effects_time_s);
        if self.sun.enabled {
            let sun = self.sun.position().ok();
            if let Some(sun) =
                sun.and_then(|p| crate::lighting::sun::clear_sky_sun(&self.scene, &p))
            {
                scene.luminaires.push(sun);
            }
        }
        scene
    }

    /// The renderer's settings for a viewport of `width` × `height` pixels.
    pub fn render_settings(&self, width: u32, height: u32) -> RenderSettings {
        RenderSettings {
            width,
            height,
            ..self.display.clone()
        }
    }

    /// Size of the scene (metres), for the far plane and the fly speed.
    pub fn extent(&self) -> f64 {
        let (lo, hi) = self.scene.bounds();
        (hi - lo).length().max(1.0)
    }

    /// Replaces the scene (jobs stop, the camera and display follow the new file).
    pub fn replace_scene(&mut self, scene: Scene, path: Option<PathBuf>) {
        self.reset_radiosity();
        self.profile = ProfileState::default();
        self.camera = ViewCamera::from_camera(&scene.camera);
        self.display = RenderSettings::from_display(&scene.display);
        self.aims = scene
            .luminaires
            .iter()
            .map(|l| AimControls::of(l.rotation))
            .collect();
        self.scene = scene;
        self.selected = None;
        self.photometry = None;
        if let Some(p) = &path {
            self.recent.add(p);
        }
        self.scene_path = path;
        self.revision += 1;
        self.say_what_the_scene_needs();
    }

    /// Copies the camera and display choices into the scene (before saving).
    pub fn sync_scene(&mut self) {
        let extent = self.extent();
        self.scene.camera = self.camera.camera(extent);
        self.scene.display = self.display.to_display(&self.scene.display);
    }

    /// Stops radiosity and goes back to direct light.
    pub fn reset_radiosity(&mut self) {
        if let Some(w) = self.radiosity.worker.take() {
            w.cancel();
        }
        self.radiosity.link = None;
        self.radiosity.waiting = false;
        self.radiosity.followed = None;
        self.radiosity.moved_at = None;
        let had_map = self.radiosity.light_map.take().is_some();
        self.radiosity.log.clear();
        self.radiosity.shots = 0;
        self.radiosity.paused = false;
        self.radiosity.status.clear();
        if had_map {
            self.revision += 1;
        }
    }

    /// Whether effect lights are turning in the view.
    pub fn effects_turning(&self) -> bool {
        self.animate_effects && self.scene.is_animated()
    }

    /// Whether background work is running (the window keeps repainting).
    pub fn busy(&self) -> bool {
        self.solving()
            || self.profile.worker.is_some()
            || self.sun.animate
            || self.effects_turning()
            || self.dialog.is_some()
    }

    /// Cancels the background work (the radiosity solver, a shadow profile) and waits for
    /// every worker thread to end, at most `limit` (the end of a run: a process must not
    /// exit under a worker inside the GPU driver). True when they all ended.
    pub fn stop_background(&mut self, limit: std::time::Duration) -> bool {
        if let Some(w) = &self.radiosity.worker {
            w.cancel();
        }
        if let Some(w) = &self.profile.worker {
            w.cancel();
        }
        super::jobs::wait_for_workers(limit)
    }

    /// True while the radiosity solver is at work (running, not waiting for a change).
    pub fn solving(&self) -> bool {
        self.radiosity.worker.is_some() && !self.radiosity.waiting
    }

    /// Opens whatever `path` is by its extension: a luminaire is added, a scene or an
    /// OBJ or glTF model replaces the scene.
    pub fn open_any(&mut self, path: &Path) {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        match ext.as_str() {
            "ldt" | "ies" | "xml" | "json" => {
                self.add_luminaire(path);
            }
            "toml" | "obj" | "gltf" | "glb" => self.open_scene(path),
            _ => self.error(format!(
                "{}: not a luminaire (.ldt, .ies, TM-33 .xml/.json), scene (.toml) or model (.obj, .gltf, .glb)",
                path.display()
            )),
        }
    }
}
