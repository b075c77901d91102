//! Luminaires placed in the world: position, orientation (aim + roll and/or Euler
//! rotation), dimming and colour, and the CPU reference of their direct illuminance.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};

use super::file::{LuminaireEntry, MAX_SECTORS};
use super::model::euler_xyz_deg;
use super::{finite_vec, SceneError};
use crate::photometry::{angles_to_direction, direction_to_angles, Interp, LdtTexture, Luminaire};

/// A luminaire in the scene.
#[derive(Debug, Clone)]
pub struct PlacedLuminaire {
    /// Its output in emergency mode (`calc --emergency`), if it has one.
    pub emergency: Option<EmergencyOutput>,
    /// Display name.
    pub name: String,
    /// The luminaire file.
    pub file: PathBuf,
    /// Its data.
    pub luminaire: Luminaire,
    /// Its light distribution texture (what the GPU samples).
    pub texture: LdtTexture,
    /// Photometric centre, metres.
    pub position: DVec3,
    /// Luminaire frame → world (columns: where local X = C0, local Y = C90 and local Z =
    /// up, away from γ = 0, end up).
    pub rotation: DMat3,
    /// Dimming factor.
    pub multiplier: f64,
    /// Colour normalised to luminance 1 (Rec. 709 weights).
    pub color: DVec3,
    /// Its own body in the scene's models, which never shadows its light.
    pub housing: Option<Housing>,
    /// Effect light: turning about its own up axis, degrees per second (0: still).
    pub spin_deg_per_s: f64,
    /// Effect light: one colour (luminance 1) per equal C sector of its own frame; empty:
    /// `color` everywhere.
    pub sector_colors: Vec<DVec3>,
    /// The model node whose light this is (glTF lights): it comes back with the model
    /// and is not saved as a `[[luminaire]]`.
    pub model_light: Option<String>,
}

/// A luminaire's own body: the model object(s) named `name` at the luminaire.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Housing {
    /// The object name (`housing` in the scene file).
    pub name: String,
    /// Indices into the scene's meshes.
    pub meshes: Vec<usize>,
}

/// `c` scaled to luminance 1 (lux stay photometric); an error naming `key` when a
/// component is negative or not finite, or all are 0.
fn luminance_one(scene: &Path, key: &str, c: [f64; 3]) -> Result<DVec3, SceneError> {
    let c = finite_vec(scene, key, c)?;
    let y = c.dot(LUMINANCE_WEIGHTS);
    if c.min_element() < 0.0 || y <= 0.0 {
        return Err(SceneError::new(
            scene,
            key,
            "components must be ≥ 0 and not all 0",
        ));
    }
    Ok(c / y)
}

/// Rec. 709 / sRGB luminance weights.
pub const LUMINANCE_WEIGHTS: DVec3 = DVec3::new(0.2126, 0.7152, 0.0722);

/// A luminaire's output in emergency mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EmergencyOutput {
    /// The rated emergency flux, lm.
    Flux(f64),
    /// The ballast lumen factor: the emergency flux over the declared flux.
    Factor(f64),
}

/// The smallest emergency output accepted, as a ballast lumen factor (and as a fraction
/// of the declared flux).
pub const MIN_EMERGENCY_FACTOR: f64 = 1e-6;

/// The `emergency_flux_lm` / `ballast_lumen_factor` of a `[[luminaire]]` whose file
/// declares `declared_lm`, checked: an emergency output is at most the normal one.
fn emergency_output(
    scene: &Path,
    key: &str,
    e: &LuminaireEntry,
    declared_lm: f64,
) -> Result<Option<EmergencyOutput>, SceneError> {
    match (e.emergency_flux_lm, e.ballast_lumen_factor) {
        (Some(_), Some(_)) => Err(SceneError::new(
            scene,
            format!("{key}.ballast_lumen_factor"),
            "give emergency_flux_lm or ballast_lumen_factor, not both",
        )),
        (Some(f), None)
            if !(f.is_finite()
                && f >= MIN_EMERGENCY_FACTOR * declared_lm
                && f <= declared_lm
                && declared_lm > 0.0) =>
        {
            Err(SceneError::new(
                scene,
                format!("{key}.emergency_flux_lm"),
                format!("{f}: give the emergency output in lumens, more than 0 and at most the luminaire's declared {declared_lm:.0} lm"),
            ))
        }
        (None, Some(b)) if !(b.is_finite() && (MIN_EMERGENCY_FACTOR..=1.0).contains(&b)) => {
            Err(SceneError::new(
                scene,
                format!("{key}.ballast_lumen_factor"),
                format!("{b}: a ballast lumen factor is more than 0 and at most 1"),
            ))
        }
        (Some(f), None) => Ok(Some(EmergencyOutput::Flux(f))),
        (None, Some(b)) => Ok(Some(EmergencyOutput::Factor(b))),
        (None, None) => Ok(None),
    }
}

impl PlacedLuminaire {
    /// The multiplier of its declared flux in emergency mode, if it has an emergency
    /// output: the ballast lumen factor, or the emergency flux over the declared flux.
    pub fn emergency_multiplier(&self) -> Option<f64> {
        match self.emergency? {
            EmergencyOutput::Factor(b) => Some(b),
            EmergencyOutput::Flux(f) => {
                let declared = self.luminaire.summary().flux_lm;
                (declared > 0.0).then(|| f / declared)
            }
        }
    }

    /// Builds a placed luminaire from its scene entry (`key` is e.g. `luminaire[0]`).
    pub(super) fn from_entry(
        scene: &Path,
        key: &str,
        dir: &Path,
        e: &LuminaireEntry,
        loaded: &mut HashMap<PathBuf, Luminaire>,
    ) -> Result<PlacedLuminaire, SceneError> {
        let file = dir.join(&e.file);
        // A file used by many luminaires (a hall of one fitting) is read once.
        let luminaire = match loaded.get(&file) {
            Some(l) => l.clone(),
            None => {
                let l = Luminaire::load(&file).map_err(|err| {
                    SceneError::new(scene, format!("{key}.file"), err.to_string())
                })?;
                loaded.insert(file.clone(), l.clone());
                l
            }
        };
        let position = finite_vec(scene, &format!("{key}.position"), e.position)?;
        let aim = match (e.aim, e.aim_at) {
            (Some(_), Some(_)) => {
                return Err(SceneError::new(
                    scene,
                    format!("{key}.aim_at"),
                    "give either aim or aim_at, not both",
                ))
            }
            (Some(a), None) => Some((finite_vec(scene, &format!("{key}.aim"), a)?, "aim")),
            (None, Some(t)) => Some((
                finite_vec(scene, &format!("{key}.aim_at"), t)? - position,
                "aim_at",
            )),
            (None, None) => None,
        };
        if let Some((a, k)) = aim {
            if crate::geometry::unit(a).is_none() || a.abs().max_element() < 1e-9 {
                return Err(SceneError::new(
                    scene,
                    format!("{key}.{k}"),
                    "the aim direction has zero length",
                ));
            }
        }
        if !e.roll.is_finite() {
            return Err(SceneError::new(
                scene,
                format!("{key}.roll"),
                "not a finite number",
            ));
        }
        let euler = match e.rotation_deg {
            Some(r) => finite_vec(scene, &format!("{key}.rotation_deg"), r)?.to_array(),
            None => [0.0; 3],
        };
        if !(e.multiplier.is_finite() && e.multiplier >= 0.0) {
            return Err(SceneError::new(
                scene,
                format!("{key}.multiplier"),
                format!("{} must be a finite number ≥ 0", e.multiplier),
            ));
        }
        let color = match e.color {
            None => DVec3::ONE,
            Some(c) => luminance_one(scene, &format!("{key}.color"), c)?,
        };
        let spin_deg_per_s = e.spin_deg_per_s.unwrap_or(0.0);
        if !spin_deg_per_s.is_finite() {
            return Err(SceneError::new(
                scene,
                format!("{key}.spin_deg_per_s"),
                "not a finite number",
            ));
        }
        let sectors = e.sector_colors.as_deref().unwrap_or(&[]);
        if e.sector_colors.is_some() && !(1..=MAX_SECTORS).contains(&sectors.len()) {
            return Err(SceneError::new(
                scene,
                format!("{key}.sector_colors"),
                format!("{} colours; give 1 to {MAX_SECTORS}", sectors.len()),
            ));
        }
        let sector_colors = sectors
            .iter()
            .enumerate()
            .map(|(k, &c)| luminance_one(scene, &format!("{key}.sector_colors[{k}]"), c))
            .collect::<Result<Vec<_>, _>>()?;
        let emergency = emergency_output(scene, key, e, luminaire.summary().flux_lm)?;
        let rotation = euler_xyz_deg(euler) * aim_frame(aim.map(|a| a.0), e.roll);
        let texture = LdtTexture::from_distribution(&luminaire.distribution);
        let name = e.name.clone().unwrap_or_else(|| {
            file.file_name()
                .map(|f| f.to_string_lossy().into_owned())
                .unwrap_or_default()
        });
        Ok(PlacedLuminaire {
            emergency,
            name,
            file,
            luminaire,
            texture,
            position,
            rotation,
            multiplier: e.multiplier,
            color,
            // Resolved against the models by the scene (`Scene::from_toml`).
            housing: e.housing.clone().map(|name| Housing {
                name,
                meshes: Vec::new(),
            }),
            spin_deg_per_s,
            sector_colors,
            model_light: None,
        })
    }

    /// A luminaire built in code (tests, benchmarks): hanging, pointing down, C0 along +X.
    pub fn new(name: &str, luminaire: Luminaire, position: DVec3) -> PlacedLuminaire {
        let texture = LdtTexture::from_distribution(&luminaire.distribution);
        PlacedLuminaire {
            emergency: None,
            name: name.into(),
            file: PathBuf::from(name),
            luminaire,
            texture,
            position,
            rotation: DMat3::IDENTITY,
            multiplier: 1.0,
            color: DVec3::ONE,
            housing: None,
            spin_deg_per_s: 0.0,
            sector_colors: Vec::new(),
            model_light: None,
        }
    }

    /// The luminaire `t_s` seconds on: turned by its spin about its own up axis.
    pub fn at_time(&self, t_s: f64) -> PlacedLuminaire {
        let mut l = self.clone();
        if self.spin_deg_per_s != 0.0 {
            let angle = (self.spin_deg_per_s * t_s).rem_euclid(360.0).to_radians();
            l.rotation = self.rotation * DMat3::from_rotation_z(angle);
        }
        l
    }

    /// The colour (luminance 1) of the light it sends along the world direction
    /// `world_dir`: its sector's colour, or `color`. The CPU twin of `light_color` in
    /// `shaders/lighting.wgsl`.
    pub fn color_toward(&self, world_dir: DVec3) -> DVec3 {
        let n = self.sector_colors.len();
        if n == 0 {
            return self.color;
        }
        let local = self.to_local(world_dir);
        let c = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU);
        let k = ((c / std::f64::consts::TAU * n as f64) as usize).min(n - 1);
        self.sector_colors[k]
    }

    /// Candela per texel unit: texel × this = cd (I_max · lamp flux / 1000 · multiplier).
    pub fn candela_scale(&self) -> f64 {
        self.texture.i_max * self.luminaire.distribution.lamp_flux_lm() / 1000.0 * self.multiplier
    }

    /// Direction (luminaire frame) of a world direction.
    pub fn to_local(&self, world_dir: DVec3) -> DVec3 {
        self.rotation.transpose() * world_dir
    }

    /// World direction of (C, γ) in degrees.
    pub fn world_direction(&self, c_deg: f64, gamma_deg: f64) -> DVec3 {
        self.rotation * angles_to_direction(c_deg, gamma_deg)
    }

    /// Intensity in candela toward `world_dir`, sampled from the texture (the CPU
    /// reference of the GPU sampler).
    pub fn intensity_toward(&self, world_dir: DVec3, interp: Interp) -> f64 {
        let (c, g) = direction_to_angles(self.to_local(world_dir));
        self.texture.sample(c, g, interp) * self.candela_scale()
    }

    /// Direct illuminance (lux) at `point` on a surface with unit normal `normal`:
    /// E = I(direction) · cos θ / d² (Wallner Eq. 3.4), 0 when the surface faces away.
    pub fn illuminance_at(&self, point: DVec3, normal: DVec3, interp: Interp) -> f64 {
        let to_light = self.position - point;
        let d2 = to_light.length_squared();
        if d2 <= 0.0 {
            return 0.0;
        }
        let l = to_light / d2.sqrt();
        let cos = normal.dot(l);
        if cos <= 0.0 {
            return 0.0;
        }
        self.intensity_toward(-l, interp) * cos / d2
    }
}

/// Luminaire frame → world for an aim direction (γ = 0 along it) and a roll about it.
/// Without an aim the luminaire hangs pointing down with C0 along world +X. With one, C0
/// is world +X projected onto the plane across the aim (world +Z when the aim is along X),
/// then turned by `roll_deg` about the aim.
pub fn aim_frame(aim: Option<DVec3>, roll_deg: f64) -> DMat3 {
    let down = match aim {
        None => return DMat3::from_axis_angle(DVec3::NEG_Z, roll_deg.to_radians()),
        // Scaled first: an aim of [1e200, 0, -1e200] keeps its direction.
        Some(a) => crate::geometry::unit(a).unwrap_or(DVec3::NEG_Z),
    };
    let project = |v: DVec3| v - v.dot(down) * down;
    let mut c0 = project(DVec3::X);
    if c0.length() < 1e-6 {
        c0 = project(DVec3::Z);
    }
    let c0 = c0.normalize();
    let z = -down;
    let c90 = z.cross(c0);
    let frame = DMat3::from_cols(c0, c90, z);
    DMat3::from_axis_angle(down, roll_deg.to_radians()) * frame
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn default_frame_hangs_down_with_c0_along_x() {
        let r = aim_frame(None, 0.0);
        assert!(close(r * angles_to_direction(0.0, 0.0), DVec3::NEG_Z));
        assert!(close(r * angles_to_direction(0.0, 90.0), DVec3::X));
        assert!(close(r * angles_to_direction(90.0, 90.0), DVec3::Y));
        assert!(aim_frame(Some(DVec3::NEG_Z), 0.0).abs_diff_eq(r, 1e-12));
    }

    #[test]
    fn aim_points_gamma_zero_and_frames_are_rotations() {
        for aim in [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.3, -0.8, 0.2),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(-1.0, 2.0, -3.0),
        ] {
            for roll in [0.0, 37.0, -120.0] {
                let r = aim_frame(Some(aim), roll);
                assert!(close(r * angles_to_direction(0.0, 0.0), aim.normalize()));
                assert!((r.determinant() - 1.0).abs() < 1e-12);
                assert!((r.transpose() * r - DMat3::IDENTITY)
                    .to_cols_array()
                    .iter()
                    .all(|v| v.abs() < 1e-12));
            }
        }
        // Roll turns C0 about the aim: 90° takes C0 to where C90 was (right-handed about
        // the aim direction, which is −local Z).
        let a = aim_frame(Some(DVec3::NEG_Z), 90.0);
        assert!(close(a * DVec3::X, DVec3::NEG_Y));
    }

    #[test]
    fn a_huge_aim_keeps_its_direction() {
        let small = aim_frame(Some(DVec3::new(1.0, 0.0, -1.0)), 10.0);
        let huge = aim_frame(Some(DVec3::new(1e200, 0.0, -1e200)), 10.0);
        assert!(huge.is_finite());
        assert!((huge - small)
            .abs()
            .to_cols_array()
            .iter()
            .all(|d| *d < 1e-12));
    }
}
