//! Glare at observers (`[[observer]]`): the unified glare rating of CIE 117:1995,
//!
//! UGR = 8 · log10( 0.25 / L_b · Σ L² ω / p² ),
//!
//! summed over the scene's luminaires as the observer sees them: each luminaire's
//! intensity toward the eye from its own distribution (as placed, dimmed and interpolated
//! as for the lux), its luminous area projected toward the eye (the file's luminous
//! dimensions), Guth's position index from where it stands in the eye's frame (T across,
//! H above, R ahead), and only luminaires the eye sees (a ray from the eye to the
//! luminaire's photometric centre, its own housing left out) that stand in the field the
//! position index covers (ahead, above the line of sight, H/R ≤ 1.9, T/R ≤ 3). The
//! background luminance L_b = E_i / π, E_i the indirect illuminance at the eye on the plane
//! across the line of sight (CIE 117 §4.2), comes from the radiosity solution.

use glam::DVec3;
use serde::Serialize;

use crate::lighting::{point_visibility, Occluders, SurfacePoint};
use crate::photometry::luminance::LuminousArea;
use crate::photometry::ugr::{glare_term, guth_position_index, in_glare_field, ugr_of};
use crate::photometry::{direction_to_angles, Interp};
use crate::scene::{Observer, Scene};

/// One luminaire as an observer sees it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LuminaireGlare {
    /// Index into the scene's luminaires.
    pub luminaire: usize,
    /// Its luminance toward the eye, cd/m².
    pub luminance_cd_m2: f64,
    /// The solid angle of its luminous area seen from the eye, sr.
    pub solid_angle_sr: f64,
    /// Guth's position index.
    pub position_index: f64,
    /// Its term L² ω / p².
    pub term: f64,
}

/// The glare at one observer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObserverGlare {
    /// UGR; `None` (JSON null) where no luminaire in the field glares.
    pub ugr: Option<f64>,
    /// L_b, cd/m².
    pub background_cd_m2: f64,
    /// Σ L² ω / p².
    pub glare_sum: f64,
    /// The luminaires counted.
    pub luminaires: Vec<LuminaireGlare>,
}

/// The point and normal at which the indirect illuminance of `observer`'s background is
/// measured: the eye, on the plane across the line of sight, facing ahead.
pub fn background_point(observer: &Observer) -> SurfacePoint {
    SurfacePoint {
        position: observer.eye,
        normal: observer.forward,
    }
}

/// An error when `observer`'s eye lies inside the luminaire `l`'s body (the box of its
/// luminaire dimensions, or of its luminous area where larger, around the photometric
/// centre): the glare formula's solid angle and position index mean nothing there.
pub fn check_outside(observer: &Observer, l: &crate::scene::PlacedLuminaire) -> Result<(), String> {
    let d = &l.luminaire.data.dimensions;
    let along = d.length.max(d.area_length).max(0.0) / 1000.0;
    let across = if d.width > 0.0 || d.area_width > 0.0 {
        d.width.max(d.area_width) / 1000.0
    } else {
        along
    };
    let tall = d
        .height
        .max(d.area_heights.iter().copied().fold(0.0, f64::max))
        / 1000.0;
    let reach = 0.5 * (along * along + across * across + tall * tall).sqrt();
    let distance = observer.eye.distance(l.position);
    if distance <= reach.max(1e-3) {
        return Err(format!(
            "the eye is {distance:.3} m from the photometric centre of {}, inside the luminaire ({reach:.3} m from its centre to its corners); move the eye out of it",
            l.file.display()
        ));
    }
    Ok(())
}

/// The glare at `observer` with the background luminance `background_cd_m2`; an error
/// naming the luminaire file when a luminaire in the field has no luminous area.
pub fn observer_glare(
    scene: &Scene,
    observer: &Observer,
    background_cd_m2: f64,
    interp: Interp,
) -> Result<ObserverGlare, String> {
    let positions: Vec<DVec3> = scene.luminaires.iter().map(|l| l.position).collect();
    let eye = [background_point(observer)];
    let (mesh, cutouts) = (scene.caster_mesh(), scene.caster_cutouts());
    let casters = Occluders {
        mesh: &mesh,
        cutouts: cutouts.as_ref(),
        ignored: &scene.ignored_per_luminaire(),
    };
    let visible = point_visibility(&casters, &positions, &eye);
    let mut luminaires = Vec::new();
    for (i, l) in scene.luminaires.iter().enumerate() {
        check_outside(observer, l)?;
        let (t, h, r) = observer.relative(l.position);
        if !in_glare_field(t, h, r) || !visible[i][0] {
            continue;
        }
        let toward_eye = observer.eye - l.position;
        let (c, gamma) = direction_to_angles(l.to_local(toward_eye));
        if gamma >= 90.0 {
            continue;
        }
        let area = LuminousArea::required(&l.luminaire, "UGR needs the luminance")
            .map_err(|e| format!("{}: {e}", l.file.display()))?;
        let a_p = area.projected(c, gamma);
        let cd = l.intensity_toward(toward_eye, interp);
        let Some(term) = glare_term(cd, a_p, t, h, r) else {
            continue;
        };
        luminaires.push(LuminaireGlare {
            luminaire: i,
            luminance_cd_m2: cd / a_p,
            solid_angle_sr: a_p / toward_eye.length_squared(),
            position_index: guth_position_index(t.abs(), h, r),
            term,
        });
    }
    let glare_sum: f64 = luminaires.iter().map(|l| l.term).sum();
    if glare_sum > 0.0 && (background_cd_m2.is_nan() || background_cd_m2 <= 0.0) {
        return Err(format!(
            "the background luminance L_b is {background_cd_m2} cd/m² (no light reflected toward the eye) while {} luminaire(s) glare: UGR = 8 log10(0.25 / L_b · Σ) has no finite value; give the room's surfaces a reflectance",
            luminaires.len()
        ));
    }
    Ok(ObserverGlare {
        ugr: ugr_of(glare_sum, background_cd_m2),
        background_cd_m2,
        glare_sum,
        luminaires,
    })
}
