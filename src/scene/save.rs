//! Writing a scene back to its TOML format (the viewer's "Save"): models as loaded,
//! luminaires with their current placement as `aim` + `roll`, the camera and the display
//! settings. Paths are written relative to the new file's folder where they can be.

use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};

use super::file::{CameraEntry, LuminaireEntry, ModelEntry, SceneFile};
use super::placement::aim_frame;
use super::placement::EmergencyOutput;
use super::{Camera, Housing, PlacedLuminaire, Projection, Scene};

impl Scene {
    /// The file contents that reproduce this scene when saved at `dest`.
    pub fn to_file(&self, dest: &Path) -> SceneFile {
        let dir = dest.parent().unwrap_or(Path::new(""));
        SceneFile {
            model: self
                .models
                .iter()
                .map(|m| ModelEntry {
                    path: path_from(dir, Path::new(&m.path)),
                    ..m.clone()
                })
                .collect(),
            luminaire: self
                .luminaires
                .iter()
                .filter(|l| l.model_light.is_none())
                .map(|l| luminaire_entry(dir, l, self.housing_in_reach(l)))
                .collect(),
            camera: Some(camera_entry(&self.camera)),
            display: self.display.clone(),
            grid: self
                .grids
                .iter()
                .enumerate()
                .filter(|(k, _)| !self.areas.iter().any(|a| a.grids.iter().any(|g| g.1 == *k)))
                .map(|(_, g)| g.entry.clone())
                .collect(),
            area: self.areas.iter().map(|a| a.entry.clone()).collect(),
            emergency: self.emergency.iter().map(|e| e.entry.clone()).collect(),
            calc: (self.calc != Default::default()).then_some(self.calc),
            observer: self.observers.iter().map(|o| o.entry.clone()).collect(),
            material: self.material_overrides.clone(),
            site: self.site.clone(),
            window: self
                .planning
                .windows
                .iter()
                .map(|w| w.entry.clone())
                .collect(),
            open_space: self
                .planning
                .open_spaces
                .iter()
                .map(|o| o.entry.clone())
                .collect(),
            sky: self.daylight.as_ref().map(|d| d.entry.clone()),
        }
    }

    /// The scene as TOML text for a file at `dest`.
    pub fn to_toml(&self, dest: &Path) -> Result<String, crate::io::WriteError> {
        toml::to_string_pretty(&self.to_file(dest))
            .map_err(|e| crate::io::WriteError::encode(dest, e))
    }

    /// Writes the scene to `dest` (atomically: a failed write leaves no partial file).
    pub fn save(&self, dest: &Path) -> Result<(), crate::io::WriteError> {
        let text = self.to_toml(dest)?;
        crate::io::write_atomic(dest, text.as_bytes())
    }
}

/// `target` relative to `dir` when it lies under it (or `dir` is empty), else absolute.
fn path_from(dir: &Path, target: &Path) -> String {
    let absolute =
        |p: &Path| -> PathBuf { std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf()) };
    let (dir, target) = (absolute(dir), absolute(target));
    let shown = target
        .strip_prefix(&dir)
        .map_or(target.clone(), Path::to_path_buf);
    shown.to_string_lossy().replace('\\', "/")
}

/// The aim (direction of γ = 0) and roll (degrees) that [`aim_frame`] turns into
/// `rotation`.
pub fn aim_and_roll(rotation: DMat3) -> (DVec3, f64) {
    let aim = -rotation.z_axis;
    let base = aim_frame(Some(aim), 0.0);
    let (c0, c0_rolled) = (base.x_axis, rotation.x_axis);
    let roll = aim.dot(c0.cross(c0_rolled)).atan2(c0.dot(c0_rolled));
    (aim, roll.to_degrees())
}

/// The entry of `l`; its housing is written only while it is still `housing` (in reach:
/// a luminaire the viewer moved away from its body leaves that body behind).
fn luminaire_entry(dir: &Path, l: &PlacedLuminaire, housing: Option<&Housing>) -> LuminaireEntry {
    let (aim, roll) = aim_and_roll(l.rotation);
    let color = (l.color != DVec3::ONE).then(|| l.color.to_array());
    LuminaireEntry {
        file: path_from(dir, &l.file),
        position: l.position.to_array(),
        aim: Some(aim.to_array()),
        aim_at: None,
        roll,
        rotation_deg: None,
        multiplier: l.multiplier,
        color,
        name: Some(l.name.clone()),
        housing: housing.map(|h| h.name.clone()),
        spin_deg_per_s: (l.spin_deg_per_s != 0.0).then_some(l.spin_deg_per_s),
        sector_colors: (!l.sector_colors.is_empty())
            .then(|| l.sector_colors.iter().map(|c| c.to_array()).collect()),
        emergency_flux_lm: match l.emergency {
            Some(EmergencyOutput::Flux(f)) => Some(f),
            _ => None,
        },
        ballast_lumen_factor: match l.emergency {
            Some(EmergencyOutput::Factor(f)) => Some(f),
            _ => None,
        },
    }
}

fn camera_entry(c: &Camera) -> CameraEntry {
    let (fov_deg, orthographic_height) = match c.projection {
        Projection::Perspective { fov_deg } => (Some(fov_deg), None),
        Projection::Orthographic { height } => (None, Some(height)),
    };
    CameraEntry {
        position: c.position.to_array(),
        look_at: c.look_at.to_array(),
        up: Some(c.up.to_array()),
        fov_deg,
        orthographic_height,
        near: Some(c.near),
    }
}
