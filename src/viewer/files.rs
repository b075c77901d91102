//! Opening and saving: scenes (TOML) and OBJ models, native file dialogs on their own
//! thread, and the list of recent files kept in the user's config folder.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver};

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
        let dir = crate::io::xdg_dir("GONIOLIGHT_CONFIG_DIR", "XDG_CONFIG_HOME", ".config")?;
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

/// Loads a scene file, or wraps an OBJ or glTF model in a scene with a camera that
/// frames it.
pub fn load_scene_or_model(path: &Path, up: UpAxis) -> Result<Scene, SceneError> {
    let is_model = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"))
        || crate::geometry::gltf_file::is_gltf(path);
    if !is_model {
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
    /// The answer once the user has chosen: `Some(Some(path))`, `Some(None)` when the
    /// dialog was cancelled (or its thread ended), `None` while it is still open.
    pub fn try_answer(&self) -> Option<Option<PathBuf>> {
        match self.answer.try_recv() {
            Ok(a) => Some(a),
            Err(std::sync::mpsc::TryRecvError::Empty) => None,
            Err(std::sync::mpsc::TryRecvError::Disconnected) => Some(None),
        }
    }

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
                        .add_filter(
                            "Luminaires (EULUMDAT, IES, TM-33, ATLA)",
                            &["ldt", "LDT", "ies", "IES", "xml", "XML", "json", "JSON"],
                        )
                        .pick_file(),
                    DialogPurpose::Open => d
                        .add_filter("Scenes and models", &["toml", "obj", "gltf", "glb"])
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
