//! `goniolight.Scene`: a scene loaded once from its file, or built from a dict with the
//! scene file's keys, and passed to `render`, `illuminance`, `radiosity` and `calc` in
//! place of a path.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;

use goniolight::scene::Scene;

use crate::{value_error, warn};

/// A loaded scene (what `Scene.load` and `Scene.from_dict` return).
#[pyclass]
pub struct NativeScene {
    pub(crate) scene: Scene,
}

/// Raises what loading `scene` worked around (`Scene::warnings`: a missing MTL file,
/// triangles without area) as `UserWarning`s.
fn warn_all(py: Python<'_>, scene: &Scene) -> PyResult<()> {
    for w in &scene.warnings {
        warn::<pyo3::exceptions::PyUserWarning>(py, w)?;
    }
    Ok(())
}

#[pymethods]
impl NativeScene {
    /// The scene file at `path` and everything it refers to.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<NativeScene> {
        let scene = Scene::load(&path).map_err(value_error)?;
        warn_all(py, &scene)?;
        Ok(NativeScene { scene })
    }

    /// The scene of `json` (a JSON object with the scene file's keys); relative paths
    /// resolve against the folder of `path`, which names the scene in messages.
    #[staticmethod]
    fn from_json(py: Python<'_>, json: &str, path: PathBuf) -> PyResult<NativeScene> {
        let value: serde_json::Value = serde_json::from_str(json).map_err(value_error)?;
        let scene = Scene::from_json(&path, value).map_err(value_error)?;
        warn_all(py, &scene)?;
        Ok(NativeScene { scene })
    }

    /// The scene file (or the name given to a scene from a dict).
    #[getter]
    fn path(&self) -> String {
        self.scene.path.display().to_string()
    }

    /// Triangles of the model.
    #[getter]
    fn triangles(&self) -> usize {
        self.scene.triangle_count()
    }

    /// The area of the model's triangles, m².
    #[getter]
    fn area(&self) -> f64 {
        self.scene.surface_area()
    }

    /// Placed luminaires.
    #[getter]
    fn luminaires(&self) -> usize {
        self.scene.luminaires.len()
    }

    /// The calculation grids' names.
    #[getter]
    fn grids(&self) -> Vec<String> {
        self.scene
            .grids
            .iter()
            .map(|g| g.entry.name.clone())
            .collect()
    }

    /// The glare observers' count.
    #[getter]
    fn observers(&self) -> usize {
        self.scene.observers.len()
    }

    /// What loading worked around.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.scene.warnings.clone()
    }
}

/// A scene argument of the native functions: a scene file's path or a loaded scene.
#[derive(FromPyObject)]
pub enum SceneArg<'py> {
    /// A `Scene` loaded before.
    Loaded(PyRef<'py, NativeScene>),
    /// A scene file, read now.
    Path(PathBuf),
}

impl SceneArg<'_> {
    /// The scene's file, for messages and reports.
    pub fn path(&self) -> &Path {
        match self {
            SceneArg::Loaded(s) => &s.scene.path,
            SceneArg::Path(p) => p,
        }
    }

    /// The scene: the loaded one, or the file read now (its warnings raised).
    pub fn scene(&self, py: Python<'_>) -> PyResult<Scene> {
        match self {
            SceneArg::Loaded(s) => Ok(s.scene.clone()),
            SceneArg::Path(p) => {
                let scene = Scene::load(p).map_err(value_error)?;
                warn_all(py, &scene)?;
                Ok(scene)
            }
        }
    }
}
