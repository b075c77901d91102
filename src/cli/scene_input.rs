//! Reading a command's scene (what its loading worked around printed as warnings), the
//! scene at `--time`, and the library's warnings printed once with options as flags.

use std::path::Path;

use anyhow::anyhow;

use super::error::{flags_in, CliError};
use crate::scene::Scene;

/// The scene file at `path`, what its loading worked around printed as warnings on stderr.
pub fn load_scene(path: &std::path::Path) -> Result<Scene, CliError> {
    let scene = Scene::load(path)?;
    for w in &scene.warnings {
        eprintln!("warning: {w}");
    }
    Ok(scene)
}

/// `scene` at `--time` seconds (effect lights turned); an error when it is not finite.
pub fn scene_at(scene: Scene, time: Option<f64>) -> Result<Scene, CliError> {
    match time {
        None => Ok(scene),
        Some(t) if t.is_finite() => Ok(scene.at_time(t)),
        Some(t) => Err(CliError::input(anyhow!(
            "--time {t} is not a finite number"
        ))),
    }
}

/// What stencil shadow volumes cannot show, said once with the choice that shows it: they
/// start at a surface turned from the light, so a translucent surface lit from behind
/// stays dark in a direct render (a solved light map holds the transmitted light either
/// way); and they are built from whole triangles, so alpha-masked holes cast shadows.
/// Prints what the GPU's check changed in `shadows` (a coarser paraboloid tessellation).
pub fn warn_shadow_fit(scene: &Scene, shadows: &crate::render::ShadowSettings) {
    if let Some(w) = shadows.warning() {
        warn_once(&scene.path, &w);
    }
}

/// Prints the library's warning `text` about `file` (options as flags) unless this process
/// printed it already (a solve and the render or calculation after it meet the same
/// limits).
pub fn warn_once(file: &Path, text: &str) {
    use std::collections::HashSet;
    use std::sync::{Mutex, OnceLock};
    static SAID: OnceLock<Mutex<HashSet<String>>> = OnceLock::new();
    let line = format!("warning: {}: {}", file.display(), flags_in(text));
    let said = SAID.get_or_init(Default::default);
    if said.lock().map_or(true, |mut s| s.insert(line.clone())) {
        eprintln!("{line}");
    }
}
