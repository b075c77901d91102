//! The furnished room shipped inside the binary: `goniolight view` and `demo` without a
//! scene open it wherever the binary is installed, not only inside the checkout it was
//! built from. Outside a checkout its files (scene, model, textures, three luminaires and
//! their licences) are written once to a cache folder and read from there like any scene.

use std::path::{Path, PathBuf};

/// The bundled scene, relative to the data root (a checkout or the extracted cache).
pub const DEFAULT_SCENE: &str = "assets/scenes/furnished_room.toml";

/// Every file the bundled scene reads, by its path relative to the data root.
const FILES: &[(&str, &[u8])] = &[
    (
        DEFAULT_SCENE,
        include_bytes!("../../assets/scenes/furnished_room.toml"),
    ),
    (
        "assets/scenes/furnished_room.obj",
        include_bytes!("../../assets/scenes/furnished_room.obj"),
    ),
    (
        "assets/scenes/furnished_room.mtl",
        include_bytes!("../../assets/scenes/furnished_room.mtl"),
    ),
    (
        "assets/scenes/textures/wood.png",
        include_bytes!("../../assets/scenes/textures/wood.png"),
    ),
    (
        "assets/scenes/textures/bricks_normal.png",
        include_bytes!("../../assets/scenes/textures/bricks_normal.png"),
    ),
    (
        "luminaires/eulumdat-plot/sample_06_isym1.ldt",
        include_bytes!("../../luminaires/eulumdat-plot/sample_06_isym1.ldt"),
    ),
    (
        "luminaires/eulumdat-plot/sample_14_isym1.ldt",
        include_bytes!("../../luminaires/eulumdat-plot/sample_14_isym1.ldt"),
    ),
    (
        "luminaires/eulumdat-plot/LICENSE",
        include_bytes!("../../luminaires/eulumdat-plot/LICENSE"),
    ),
    (
        "luminaires/eulumdat-luminance/sample_03.ldt",
        include_bytes!("../../luminaires/eulumdat-luminance/sample_03.ldt"),
    ),
    (
        "luminaires/eulumdat-luminance/LICENSE",
        include_bytes!("../../luminaires/eulumdat-luminance/LICENSE"),
    ),
];

/// Why the bundled scene could not be found or extracted.
#[derive(Debug, thiserror::Error)]
pub enum BundledError {
    /// No folder to extract it into.
    #[error(
        "the bundled scene needs a cache folder: set GONIOLIGHT_CACHE_DIR, XDG_CACHE_HOME or HOME"
    )]
    NoCacheFolder,
    /// Writing one of its files failed.
    #[error(transparent)]
    Write(#[from] super::WriteError),
}

/// The bundled scene's file: the checkout's when [`super::data_root`] holds it, else the
/// copy extracted into [`cache_dir`] (written on first use, rewritten if changed).
pub fn default_scene() -> Result<PathBuf, BundledError> {
    let checkout = super::data_root().join(DEFAULT_SCENE);
    if checkout.is_file() {
        return Ok(checkout);
    }
    let dir = cache_dir().ok_or(BundledError::NoCacheFolder)?;
    Ok(extract(&dir)?)
}

/// The folder the bundled scene is extracted to: `$GONIOLIGHT_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/goniolight`, else `~/.cache/goniolight`; one subfolder per version.
pub fn cache_dir() -> Option<PathBuf> {
    let base = super::xdg_dir("GONIOLIGHT_CACHE_DIR", "XDG_CACHE_HOME", ".cache")?;
    Some(base.join(format!("bundled-{}", env!("CARGO_PKG_VERSION"))))
}

/// Writes the bundled scene's files under `dir` (each atomically, only where missing or
/// different) and returns the scene file's path.
pub fn extract(dir: &Path) -> Result<PathBuf, super::WriteError> {
    for (rel, bytes) in FILES {
        let path = dir.join(rel);
        if std::fs::read(&path).is_ok_and(|old| old == *bytes) {
            continue;
        }
        if let Some(parent) = path.parent() {
            super::create_dir(parent)?;
        }
        super::write_atomic(&path, bytes)?;
    }
    Ok(dir.join(DEFAULT_SCENE))
}
