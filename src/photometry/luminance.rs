//! Luminance of the luminous area, cd/m², as seen from a direction (C, γ): the intensity
//! toward it over the luminous area projected on a plane across it — the table datasheets
//! print and the UGR formula uses (CIE 117: L = I / A_p).
//!
//! The luminous area is EULUMDAT's fields 16–21 (IES converts its opening into them):
//! a bottom face of length × width (a disc of diameter `length` when the width is 0) and
//! upright side faces of the heights given per C plane. Seen from (C, γ):
//!
//! A_p = A_bottom · cos γ + (|cos C| · length · h(C0 or C180) + |sin C| · width · h(C90 or
//! C270)) · sin γ,
//!
//! the side toward C0 or C180 being the one the sign of cos C faces (and C90 or C270 for
//! sin C); a disc's side is a cylinder's outline, diameter × height from every C plane (the
//! height blended by cos² C and sin² C where the planes' heights differ). This
//! orientation of length and width reproduces Relux's luminance tables (`tests/
//! luminance.rs`: the ten lab files within Relux's own rounding).

use serde::Serialize;

use super::error::PhotometryError;
use super::grid::Interp;
use super::Luminaire;

/// The smallest luminous area accepted where luminance is computed, m² (1 mm²: smaller
/// than the smallest LED package; below it the dimensions are certainly wrong).
pub const MIN_LUMINOUS_AREA_M2: f64 = 1e-6;

/// The luminous area's faces, m².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LuminousArea {
    /// The bottom face (downward, γ = 0).
    pub bottom_m2: f64,
    /// The upright faces toward C0, C90, C180 and C270 (for a disc, its diameter times the
    /// height in that plane).
    pub sides_m2: [f64; 4],
    /// True for a disc (a cylinder's side shows the same width from every C plane).
    pub round: bool,
}

impl LuminousArea {
    /// The luminous area of `lum` (fields 16–21, millimetres).
    pub fn of(lum: &Luminaire) -> LuminousArea {
        let d = &lum.data.dimensions;
        let (l, w) = (d.area_length / 1000.0, d.area_width / 1000.0);
        let h = d.area_heights.map(|v| v / 1000.0);
        let round = w <= 0.0;
        let (bottom, across_c0, across_c90) = if round {
            (std::f64::consts::PI * l * l / 4.0, l, l)
        } else {
            (l * w, l, w)
        };
        LuminousArea {
            round,
            bottom_m2: bottom,
            sides_m2: [
                across_c0 * h[0],
                across_c90 * h[1],
                across_c0 * h[2],
                across_c90 * h[3],
            ],
        }
    }

    /// The luminous area of `lum`, refused when the file gives none (`why` says what
    /// needs it).
    pub fn required(lum: &Luminaire, why: &str) -> Result<LuminousArea, PhotometryError> {
        let d = &lum.data.dimensions;
        let fields = [
            (16, "luminous area length/diameter", d.area_length),
            (17, "luminous area width", d.area_width),
            (18, "luminous area height C0", d.area_heights[0]),
            (19, "luminous area height C90", d.area_heights[1]),
            (20, "luminous area height C180", d.area_heights[2]),
            (21, "luminous area height C270", d.area_heights[3]),
        ];
        if let Some((line, what, v)) = fields.iter().find(|(_, _, v)| *v < 0.0) {
            return Err(PhotometryError::Invalid(format!(
                "EULUMDAT line {line} ({what}): {v} mm is negative; a luminous dimension is a size ≥ 0: {why}"
            )));
        }
        let area = LuminousArea::of(lum);
        let total = area.bottom_m2 + area.sides_m2.iter().sum::<f64>();
        if total > 0.0 && total < MIN_LUMINOUS_AREA_M2 {
            return Err(PhotometryError::Invalid(format!(
                "EULUMDAT lines 16–21: a luminous area of {total:.3e} m², smaller than the {} mm² of the smallest LED; the dimensions are in millimetres: {why}",
                MIN_LUMINOUS_AREA_M2 * 1e6
            )));
        }
        if area.bottom_m2 <= 0.0 && area.sides_m2.iter().all(|s| *s <= 0.0) {
            return Err(PhotometryError::Invalid(format!(
                "the file gives no luminous area (EULUMDAT lines 16–21, IES width/length/height): {why}"
            )));
        }
        Ok(area)
    }

    /// The area projected across the direction (C, γ), m², for γ below 90°.
    pub fn projected(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        let (sc, cc) = c_deg.to_radians().sin_cos();
        let (sg, cg) = gamma_deg.to_radians().sin_cos();
        let along_c0 = if cc >= 0.0 {
            self.sides_m2[0]
        } else {
            self.sides_m2[2]
        };
        let along_c90 = if sc >= 0.0 {
            self.sides_m2[1]
        } else {
            self.sides_m2[3]
        };
        // A box shows two faces by |cos C| and |sin C|; a cylinder one outline, its height
        // blended between the planes' heights.
        let side = if self.round {
            cc * cc * along_c0 + sc * sc * along_c90
        } else {
            cc.abs() * along_c0 + sc.abs() * along_c90
        };
        self.bottom_m2 * cg.max(0.0) + side * sg
    }
}

/// A luminance table: cd/m² per C plane (rows) and γ angle (columns).
#[derive(Debug, Clone, Serialize)]
pub struct LuminanceTable {
    /// C angles, degrees.
    pub c_angles: Vec<f64>,
    /// γ angles, degrees.
    pub gamma_angles: Vec<f64>,
    /// `cd_m2[c][g]`, one array per C angle.
    pub cd_m2: Vec<Vec<f64>>,
    /// The lamp flux the intensities were scaled with, lm.
    pub flux_lm: f64,
}

impl LuminanceTable {
    /// The largest value in the table.
    pub fn max(&self) -> f64 {
        self.cd_m2.iter().flatten().cloned().fold(0.0, f64::max)
    }
}

/// The UGR grid of datasheets: C 0–345° every 15°, γ 65–85° every 5°.
pub fn ugr_grid() -> (Vec<f64>, Vec<f64>) {
    (
        (0..24).map(|k| 15.0 * k as f64).collect(),
        (0..5).map(|k| 65.0 + 5.0 * k as f64).collect(),
    )
}

/// The γ rows of a luminance table that starts at `from` degrees and runs every 5° below
/// 90° (datasheets start at 45° or 65°, the UGR grid's first row); `None` unless `from` is
/// a multiple of 5 below 90.
pub fn gamma_rows(from: u16) -> Option<Vec<f64>> {
    (from < 90 && from.is_multiple_of(5)).then(|| (from..90).step_by(5).map(f64::from).collect())
}

/// The lamp flux of lamp set `set` (1-based; `None`: the first set, as Relux and DIALux
/// read EULUMDAT's sets as alternative equipment), lm.
pub fn lamp_set_flux(lum: &Luminaire, set: Option<usize>) -> Result<f64, PhotometryError> {
    let sets = &lum.data.lamp_sets;
    let k = set.unwrap_or(1);
    match sets.get(k.wrapping_sub(1)) {
        Some(s) if s.flux_lm > 0.0 => Ok(s.flux_lm),
        Some(_) => Err(PhotometryError::Invalid(format!(
            "lamp set {k} has no flux: intensities cannot be turned into candela"
        ))),
        None => Err(PhotometryError::Field {
            field: "lamp_set",
            value: k.to_string(),
            problem: format!("is not in the file: it has {} lamp set(s)", sets.len()),
        }),
    }
}

/// The luminance of `lum` at every (C, γ) of the grid, for the flux of lamp set `set`.
/// Refuses γ of 90° or more (the table is for directions below the horizontal) and a file
/// without a luminous area.
pub fn luminance_table(
    lum: &Luminaire,
    c_angles: &[f64],
    gamma_angles: &[f64],
    set: Option<usize>,
    interp: Interp,
) -> Result<LuminanceTable, PhotometryError> {
    if let Some(g) = gamma_angles.iter().find(|g| !(0.0..90.0).contains(*g)) {
        return Err(PhotometryError::Invalid(format!(
            "γ = {g}°: a luminance table covers 0° ≤ γ < 90°"
        )));
    }
    let area = LuminousArea::required(lum, "no luminance without one")?;
    let flux = lamp_set_flux(lum, set)?;
    let cd_m2 = c_angles
        .iter()
        .map(|&c| {
            gamma_angles
                .iter()
                .map(|&g| {
                    let cd = lum.distribution.sample(c, g, interp) * flux / 1000.0;
                    let a = area.projected(c, g);
                    if a > 0.0 {
                        cd / a
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect();
    Ok(LuminanceTable {
        c_angles: c_angles.to_vec(),
        gamma_angles: gamma_angles.to_vec(),
        cd_m2,
        flux_lm: flux,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projected_area_of_a_box_seen_from_each_side() {
        let a = LuminousArea {
            bottom_m2: 0.5,
            sides_m2: [0.1, 0.2, 0.3, 0.4],
            round: false,
        };
        assert!((a.projected(0.0, 0.0) - 0.5).abs() < 1e-12);
        // From the side (γ → 90°) only the faces count: C0 sees its face, C270 its own.
        assert!((a.projected(0.0, 89.999_999) - 0.1).abs() < 1e-6);
        assert!((a.projected(180.0, 89.999_999) - 0.3).abs() < 1e-6);
        assert!((a.projected(270.0, 89.999_999) - 0.4).abs() < 1e-6);
        // Between C0 and C90 both faces show, by |cos C| and |sin C|.
        let want = 0.5 * 60f64.to_radians().cos()
            + (45f64.to_radians().cos() * 0.1 + 45f64.to_radians().sin() * 0.2)
                * 60f64.to_radians().sin();
        assert!((a.projected(45.0, 60.0) - want).abs() < 1e-12);
    }

    #[test]
    fn a_cylinder_shows_the_same_outline_from_every_c_plane() {
        let a = LuminousArea {
            bottom_m2: 0.2,
            sides_m2: [0.05; 4],
            round: true,
        };
        for c in [0.0, 15.0, 45.0, 100.0, 300.0] {
            assert!((a.projected(c, 90.0) - 0.05).abs() < 1e-12, "C{c}");
        }
    }
}
