//! Opening and saving: scenes (TOML) and OBJ models, native file dialogs on their own
//! thread, and the list of recent files kept in the user's config folder.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver};

use super::app::ViewerApp;
use crate::scene::{Scene, SceneError, UpAxis};

/// Most recent files kept.
pub const RECENT_MAX: usize = 10;

/// Recently opened or saved scenes, newest first, stored one path per line.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecentFiles {
    /// The paths.
    pub paths: Vec<PathBuf>,
    /// Where the list is kept (None: not kept).
    pub store: Option<PathBuf>,
}

impl RecentFiles {
    /// The list kept at `store` (missing or unreadable: empty).
    pub fn load(store: Option<PathBuf>) -> RecentFiles {
        let paths = store
            .as_ref()
            .and_then(|s| std::fs::read_to_string(s).ok())
            .map(|t| {
                t.lines()
                    .filter(|l| !l.is_empty())
                    .map(PathBuf::from)
                    .collect()
            })
            .unwrap_or_default();
        RecentFiles { paths, store }
    }

    /// The default store: `$GONIOLIGHT_CONFIG_DIR`, else `$XDG_CONFIG_HOME/goniolight`,
    /// else `~/.config/goniolight`; the file `recent.txt` in it.
    pub fn default_store() -> Option<PathBuf> {
        let env = |k| {
            std::env::var_os(k)
                .filter(|v| !v.is_empty())
                .map(PathBuf::from)
        };
        let dir = env("GONIOLIGHT_CONFIG_DIR")
            .or_else(|| env("XDG_CONFIG_HOME").map(|d| d.join("goniolight")))
            .or_else(|| env("HOME").map(|h| h.join(".config").join("goniolight")))?;
        Some(dir.join("recent.txt"))
    }

    /// Puts `path` first and writes the list (a failed write only loses the list).
    pub fn add(&mut self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.paths.retain(|p| *p != path);
        self.paths.insert(0, path);
        self.paths.truncate(RECENT_MAX);
        if let Some(store) = &self.store {
            let text: String = self
                .paths
                .iter()
                .map(|p| format!("{}\n", p.display()))
                .collect();
            if let Some(dir) = store.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            let _ = crate::io::write_atomic(store, text.as_bytes());
        }
    }
}

/// Loads a scene file, or wraps an OBJ model in a scene with a camera that frames it.
pub fn load_scene_or_model(path: &Path, up: UpAxis) -> Result<Scene, SceneError> {
    let is_obj = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    if !is_obj {
        return Scene::load(path);
    }
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let text = format!(
        "[[model]]\npath = {}\nup = \"{}\"\n\n[camera]\nposition = [10.0, -10.0, 10.0]\nlook_at = [0.0, 0.0, 0.0]\n",
        toml::Value::String(absolute.to_string_lossy().into_owned()),
        match up {
            UpAxis::Y => "y",
            UpAxis::Z => "z",
        }
    );
    let mut scene = Scene::from_toml(path, &text)?;
    if scene.triangle_count() == 0 {
        return Err(SceneError::new(path, "model", "the model has no triangles"));
    }
    // Look at the model from the south-west, 30° down, so that it fills the view.
    let (lo, hi) = scene.bounds();
    let mut view = super::camera::ViewCamera::from_camera(&scene.camera);
    view.yaw_deg = 45.0;
    view.pitch_deg = -30.0;
    view.frame(lo, hi);
    scene.camera = view.camera((hi - lo).length());
    scene.path = PathBuf::new();
    Ok(scene)
}

/// What a file dialog was opened for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DialogPurpose {
    /// Add a luminaire.
    AddLuminaire,
    /// Open a scene or model.
    Open,
    /// Save the scene.
    SaveAs,
}

/// A native file dialog running on its own thread.
pub struct Dialog {
    /// Why it is open.
    pub purpose: DialogPurpose,
    answer: Receiver<Option<PathBuf>>,
}

impl Dialog {
    /// Opens a dialog for `purpose` starting in `folder`.
    pub fn open(purpose: DialogPurpose, folder: Option<PathBuf>) -> std::io::Result<Dialog> {
        let (tx, rx) = channel();
        std::thread::Builder::new()
            .name("file dialog".into())
            .spawn(move || {
                let mut d = rfd::FileDialog::new();
                if let Some(f) = folder {
                    d = d.set_directory(f);
                }
                let picked = match purpose {
                    DialogPurpose::AddLuminaire => d
                        .add_filter("Luminaires (EULUMDAT, IES)", &["ldt", "LDT", "ies", "IES"])
                        .pick_file(),
                    DialogPurpose::Open => d
                        .add_filter("Scenes and models", &["toml", "obj"])
                        .pick_file(),
                    DialogPurpose::SaveAs => d
                        .add_filter("Scene", &["toml"])
                        .set_file_name("scene.toml")
                        .save_file(),
                };
                let _ = tx.send(picked);
            })?;
        Ok(Dialog {
            purpose,
            answer: rx,
        })
    }
}

impl ViewerApp {
    /// Opens a native file dialog (the UI keeps running; the answer is polled).
    pub fn open_dialog(&mut self, purpose: DialogPurpose) {
        if self.dialog.is_some() {
            return;
        }
        let folder = self
            .scene_path
            .as_ref()
            .and_then(|p| p.parent())
            .map(Path::to_path_buf);
        match Dialog::open(purpose, folder) {
            Ok(d) => self.dialog = Some(d),
            Err(e) => self.error(format!("file dialog: {e}")),
        }
    }

    /// Acts on a dialog's answer once it is there.
    pub fn poll_dialog(&mut self) {
        let Some(d) = &self.dialog else { return };
        let answer = match d.answer.try_recv() {
            Ok(a) => a,
            Err(std::sync::mpsc::TryRecvError::Empty) => return,
            Err(std::sync::mpsc::TryRecvError::Disconnected) => None,
        };
        let purpose = d.purpose;
        self.dialog = None;
        let Some(path) = answer else { return };
        match purpose {
            DialogPurpose::AddLuminaire => {
                self.add_luminaire(&path);
            }
            DialogPurpose::Open => self.open_scene(&path),
            DialogPurpose::SaveAs => self.save_scene(&path),
        }
    }

    /// Replaces the scene by the one at `path` (a scene file or an OBJ model); on an
    /// error nothing changes.
    pub fn open_scene(&mut self, path: &Path) {
        match load_scene_or_model(path, self.obj_up) {
            Ok(scene) => {
                let is_scene = !scene.path.as_os_str().is_empty();
                self.replace_scene(scene, is_scene.then(|| path.to_path_buf()));
                self.info(format!("opened {}", path.display()));
            }
            Err(e) => self.error(format!("not opened: {e}")),
        }
    }

    /// Saves the scene (camera and display included) to `path`.
    pub fn save_scene(&mut self, path: &Path) {
        self.sync_scene();
        match self.scene.save(path) {
            Ok(()) => {
                self.scene_path = Some(path.to_path_buf());
                self.scene.path = path.to_path_buf();
                self.recent.add(path);
                self.info(format!("saved {}", path.display()));
            }
            Err(e) => self.error(format!("{}: not saved: {e:#}", path.display())),
        }
    }

    /// The File menu and the window toggles.
    pub fn menu_bar(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open scene or model…").clicked() {
                    self.open_dialog(DialogPurpose::Open);
                }
                let save = ui.add_enabled(self.scene_path.is_some(), egui::Button::new("Save"));
                if save.clicked() {
                    if let Some(p) = self.scene_path.clone() {
                        self.save_scene(&p);
                    }
                }
                if ui.button("Save as…").clicked() {
                    self.open_dialog(DialogPurpose::SaveAs);
                }
                ui.menu_button("Recent", |ui| {
                    if self.recent.paths.is_empty() {
                        ui.label("(none)");
                    }
                    for p in self.recent.paths.clone() {
                        if ui.button(p.display().to_string()).clicked() {
                            self.open_scene(&p);
                        }
                    }
                });
            });
            ui.menu_button("View", |ui| {
                if ui.button("Frame the scene").clicked() {
                    let (lo, hi) = self.scene.bounds();
                    self.camera.frame(lo, hi);
                }
                ui.radio_value(
                    &mut self.camera.mode,
                    super::camera::CameraMode::Orbit,
                    "Orbit camera",
                );
                ui.radio_value(
                    &mut self.camera.mode,
                    super::camera::CameraMode::Fly,
                    "Fly camera (W A S D Q E)",
                );
                ui.separator();
                ui.label("Up axis of OBJ models opened");
                ui.radio_value(&mut self.obj_up, UpAxis::Y, "+Y (most exporters)");
                ui.radio_value(&mut self.obj_up, UpAxis::Z, "+Z");
                ui.separator();
                if ui.button("Shadow profile window").clicked() {
                    self.profile.open = true;
                }
            });
            let title = self
                .scene_path
                .as_ref()
                .map_or("(unsaved scene)".to_string(), |p| p.display().to_string());
            ui.label(title);
        });
    }
}
