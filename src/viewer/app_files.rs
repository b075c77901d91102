//! What the viewer's app does with files: native dialogs, opening and saving scenes,
//! recent files (the app's methods that use [`super::files`]).

use std::path::Path;

use super::app::ViewerApp;
use super::files::{load_scene_or_model, Dialog, DialogPurpose};
use crate::scene::{Camera, UpAxis};

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
        let Some(answer) = d.try_answer() else { return };
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
                if ui.button("Plan view (from above, north up)").clicked() {
                    // The plan a scene without a camera gets: cut above the luminaires
                    // under the ceiling.
                    let plan = Camera::framing(self.scene.bounds(), &self.scene.luminaires);
                    let mode = self.camera.mode;
                    self.camera = super::camera::ViewCamera::from_camera(&plan);
                    self.camera.mode = mode;
                }
                let mut ortho = self.camera.ortho_height.is_some();
                if ui.checkbox(&mut ortho, "Orthographic").changed() {
                    let c = &mut self.camera;
                    c.ortho_height =
                        ortho.then(|| 2.0 * c.distance * (c.fov_deg.to_radians() / 2.0).tan());
                }
                if self.scene.is_animated() {
                    ui.checkbox(&mut self.animate_effects, "Animate effect lights");
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
