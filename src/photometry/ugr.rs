//! The UGR table of a luminaire (CIE 117:1995 formula, CIE 190:2010 tabular method): the
//! unified glare rating of a standard room lit by a regular array of the luminaire, for 19
//! room sizes, 5 reflectance combinations, viewed crosswise and endwise — the table of
//! manufacturers' datasheets.
//!
//! For one room and one view:
//!
//! UGR = 8 · log10( 0.25 / L_b · Σ L² ω / p² )
//!
//! - The room is X × Y (in units of H, the height of the luminaires above the eye; X across
//!   the line of sight, Y along it), the luminaires on a square grid of spacing SHR · H
//!   (0.25 H as standard), half a spacing from the walls; the observer's eye is at the
//!   middle of the wall of length X, at the height of the reference plane, looking
//!   horizontally along Y.
//! - For each luminaire ahead of the eye (distance R along the line of sight, T across it,
//!   H above): γ from the vertical; the C plane toward the eye by CIE 117 eq. 4.5/4.6
//!   (crosswise C = arctan(T/R), endwise C = 90° − arctan(T/R): the luminaire's long axis —
//!   EULUMDAT's C90–C270 — across or along the line of sight); L = I(C, γ) / A_p(C, γ)
//!   (`luminance`), ω = A_p / d², p Guth's position index (the IES formula of Guth's data,
//!   which CIE 117's Table 4.1 tabulates), luminaires beyond that table (H/R > 1.9 or T/R >
//!   3) left out as the table leaves them out.
//! - L_b = E_i / π, E_i the indirect illuminance on the walls: the luminaires' flux is
//!   split between the reference plane ("floor"), the walls and the ceiling by tracing the
//!   luminaire's zonal flux (its distribution averaged over C, so L_b is the same crosswise
//!   and endwise) from every luminaire position; the three surfaces then exchange light by
//!   their exact form factors (uniform exitance per surface), and E_i is the walls'
//!   illuminance from that reflected light.
//!
//! Checked against an independent numerical evaluation (`tests/cli/ugr.rs`) and against the
//! `eulumdat-ugr` package, which its authors report within 0.43 UGR of Relux
//! (`python/tests/test_ugr_oracle.py`).

use std::f64::consts::PI;

use rayon::prelude::*;
use serde::Serialize;

use super::error::PhotometryError;
use super::grid::Interp;
use super::luminance::{lamp_set_flux, LuminousArea};
use super::Luminaire;

/// The 19 standard rooms of CIE 190, X × Y in units of H.
pub const ROOMS: [[f64; 2]; 19] = [
    [2.0, 2.0],
    [2.0, 3.0],
    [2.0, 4.0],
    [2.0, 6.0],
    [2.0, 8.0],
    [2.0, 12.0],
    [4.0, 2.0],
    [4.0, 3.0],
    [4.0, 4.0],
    [4.0, 6.0],
    [4.0, 8.0],
    [4.0, 12.0],
    [8.0, 4.0],
    [8.0, 6.0],
    [8.0, 8.0],
    [8.0, 12.0],
    [12.0, 4.0],
    [12.0, 6.0],
    [12.0, 8.0],
];

/// The 5 standard reflectance combinations: ceiling, walls, reference plane.
pub const REFLECTANCES: [[f64; 3]; 5] = [
    [0.7, 0.5, 0.2],
    [0.7, 0.3, 0.2],
    [0.5, 0.5, 0.2],
    [0.5, 0.3, 0.2],
    [0.3, 0.3, 0.2],
];

/// The standard spacing-to-height ratio of the table.
pub const STANDARD_SHR: f64 = 0.25;

/// Height of the luminaires above the eye, m (UGR does not depend on it at a given SHR:
/// the flux per area and Σ L²ω/p² scale alike).
const H: f64 = 2.0;

/// A UGR table (`ldt ugr --json`).
#[derive(Debug, Clone, Serialize)]
pub struct UgrTable {
    /// Spacing-to-height ratio of the luminaire grid.
    pub shr: f64,
    /// Room sizes, X × Y in units of H.
    pub rooms: Vec<[f64; 2]>,
    /// Reflectances: ceiling, walls, reference plane.
    pub reflectances: Vec<[f64; 3]>,
    /// UGR viewed crosswise, per room, per reflectance combination; `None` (JSON null)
    /// where no luminaire sends light toward the eye (no direct glare to rate).
    pub crosswise: Vec<[Option<f64>; 5]>,
    /// UGR viewed endwise.
    pub endwise: Vec<[Option<f64>; 5]>,
    /// The lamp flux the table is for, lm.
    pub flux_lm: f64,
    /// How UGR changes with the observer's position at the spacings of
    /// [`VARIATION_SPACINGS`] (the datasheets' "variation of the observer position").
    pub observer_variation: Vec<ObserverVariation>,
}

/// The spacings of the observer-position variation, in units of H (as datasheets give it).
pub const VARIATION_SPACINGS: [f64; 3] = [1.0, 1.5, 2.0];

/// The room the variation is computed in, X × Y in units of H: the reference room of
/// UGR labelling.
pub const VARIATION_ROOM: [f64; 2] = [4.0, 8.0];

/// Eye positions per spacing and direction: the eye moves over one spacing in these steps.
const VARIATION_STEPS: usize = 4;

/// How much UGR changes as the observer moves relative to the luminaire grid, for one
/// spacing: `[up, down]`, the largest rise above and fall below the value from the
/// standard position (both ≥ 0); `None` where no luminaire glares from that position.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ObserverVariation {
    /// The spacing of the luminaires, in units of H.
    pub spacing: f64,
    /// Viewed crosswise.
    pub crosswise: Option<[f64; 2]>,
    /// Viewed endwise.
    pub endwise: Option<[f64; 2]>,
}

/// The observer-position variation of `lum` at `spacing` (units of H), in
/// [`VARIATION_ROOM`]: the eye moves from the middle of the wall across and ahead over one
/// spacing in 4 steps each way. The background luminance does not depend
/// on where the eye is (it is the walls' mean), so the change is 8 · log10 of the ratio of
/// the glare sums, the same for every reflectance combination and every flux. Positions
/// from which no luminaire glares are left out (there is no rating to compare).
pub fn observer_variation(lum: &Luminaire, spacing: f64, interp: Interp) -> ObserverVariation {
    let range = |view: View| -> Option<[f64; 2]> {
        let sum =
            |eye: [f64; 2]| glare_sum(lum, 1000.0, VARIATION_ROOM, spacing, view, interp, eye);
        let standard = sum(STANDARD_EYE);
        if standard <= 0.0 {
            return None;
        }
        let mut up: f64 = 0.0;
        let mut down: f64 = 0.0;
        for i in 0..VARIATION_STEPS {
            for j in 0..VARIATION_STEPS {
                let step = spacing / VARIATION_STEPS as f64;
                let s = sum([i as f64 * step, j as f64 * step]);
                // (A position from which no luminaire glares has no rating to compare.)
                if s > 0.0 {
                    let change = 8.0 * (s / standard).log10();
                    up = up.max(change);
                    down = down.max(-change);
                }
            }
        }
        Some([up, down])
    };
    ObserverVariation {
        spacing,
        crosswise: range(View::Crosswise),
        endwise: range(View::Endwise),
    }
}

/// How the observer looks at the luminaires.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// Line of sight across the luminaire's long axis (C90–C270).
    Crosswise,
    /// Line of sight along it.
    Endwise,
}

/// Guth's position index for a source T across, H above and R ahead of the eye (any unit).
pub fn guth_position_index(t: f64, h: f64, r: f64) -> f64 {
    let alpha = t.atan2(h).to_degrees();
    let beta = t.hypot(h).atan2(r).to_degrees();
    ((35.2 - 0.31889 * alpha - 1.22 * (-2.0 * alpha / 9.0).exp()) * 1e-3 * beta
        + (21.0 + 0.26667 * alpha - 0.002963 * alpha * alpha) * 1e-5 * beta * beta)
        .exp()
}

/// The luminaire positions of a room X × Y (metres) at spacing `s`: x across (0 at the
/// observer's wall centre), y ahead of the eye.
fn positions(x_m: f64, y_m: f64, s: f64) -> Vec<(f64, f64)> {
    let nx = (x_m / s).round().max(1.0) as usize;
    let ny = (y_m / s).round().max(1.0) as usize;
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            out.push(((i as f64 + 0.5) * s - x_m / 2.0, (j as f64 + 0.5) * s));
        }
    }
    out
}

/// The standard observer position: the middle of the wall.
pub const STANDARD_EYE: [f64; 2] = [0.0, 0.0];

/// Σ L² ω / p² over the luminaires of a room seen in `view`, the eye moved `eye` =
/// [across, ahead] (units of H) from the middle of the wall ([`STANDARD_EYE`] for the
/// table); luminaires behind the eye do not count.
pub fn glare_sum(
    lum: &Luminaire,
    flux: f64,
    room: [f64; 2],
    shr: f64,
    view: View,
    interp: Interp,
    eye: [f64; 2],
) -> f64 {
    let area = LuminousArea::of(lum);
    let mut sum = 0.0;
    for (x, y) in positions(room[0] * H, room[1] * H, shr * H) {
        let (t, r) = ((x - eye[0] * H).abs(), y - eye[1] * H);
        if !in_glare_field(t, H, r) {
            continue;
        }
        let gamma = t.hypot(r).atan2(H).to_degrees();
        let c_cross = t.atan2(r).to_degrees();
        let c = match view {
            View::Crosswise => c_cross,
            View::Endwise => 90.0 - c_cross,
        };
        let a_p = area.projected(c, gamma);
        let cd = lum.distribution.sample(c, gamma, interp) * flux / 1000.0;
        sum += glare_term(cd, a_p, t, H, r).unwrap_or(0.0);
    }
    sum
}

/// Whether a source `t` across, `h` above and `r` ahead of the eye counts in the CIE 117
/// sum: ahead of the eye, above the line of sight, and within the position index's table
/// (H/R ≤ 1.9, T/R ≤ 3), as the UGR tables count them.
pub fn in_glare_field(t: f64, h: f64, r: f64) -> bool {
    r > 0.0 && h > 0.0 && h / r <= 1.9 && t.abs() / r <= 3.0
}

/// One source's term L² ω / p² of the CIE 117 sum: `cd` candela toward the eye from a
/// projected luminous area `a_p` (m²), `t` across, `h` above and `r` ahead of the eye
/// (metres); `None` outside [`in_glare_field`] or where nothing luminous is seen.
pub fn glare_term(cd: f64, a_p: f64, t: f64, h: f64, r: f64) -> Option<f64> {
    if !in_glare_field(t, h, r) || a_p <= 0.0 || cd <= 0.0 {
        return None;
    }
    let d2 = t * t + r * r + h * h;
    let l = cd / a_p;
    let omega = a_p / d2;
    let p = guth_position_index(t.abs(), h, r);
    Some(l * l * omega / (p * p))
}

/// UGR = 8 · log10(0.25 / L_b · Σ L² ω / p²) for the glare sum `sum` and the background
/// luminance `lb` (cd/m²); `None` where nothing glares (Σ = 0) or `lb` is not positive.
pub fn ugr_of(sum: f64, lb: f64) -> Option<f64> {
    (sum > 0.0 && lb > 0.0).then(|| 8.0 * (0.25 / lb * sum).log10())
}

/// The luminaire's flux per 1° γ band (averaged over C, lm per lamp-set flux `flux`).
fn zonal_flux(lum: &Luminaire, flux: f64, interp: Interp) -> Vec<f64> {
    const C_STEPS: usize = 72;
    (0..180)
        .map(|k| {
            let (lo, hi) = ((k as f64).to_radians(), ((k + 1) as f64).to_radians());
            let g = k as f64 + 0.5;
            let mean: f64 = (0..C_STEPS)
                .map(|j| {
                    lum.distribution
                        .sample(360.0 * j as f64 / C_STEPS as f64, g, interp)
                })
                .sum::<f64>()
                / C_STEPS as f64;
            mean * flux / 1000.0 * 2.0 * PI * (lo.cos() - hi.cos())
        })
        .collect()
}

/// The direct flux of the whole array on the ceiling, the walls and the reference plane
/// of a room X × Y (metres), lm. The grid is symmetric about both centre lines of the room
/// and the zonal flux about the vertical, so one quadrant's luminaires are traced.
fn direct_split(zonal: &[f64], x_m: f64, y_m: f64, s: f64) -> [f64; 3] {
    const AZIMUTHS: usize = 72;
    let up: f64 = zonal[90..].iter().sum();
    let down: f64 = zonal[..90].iter().sum();
    let lamps = positions(x_m, y_m, s);
    // Weight 1 for a luminaire in the lower-left quadrant (as many as there are mirror
    // images of it: 4, 2 on a centre line, 1 at the centre), 0 elsewhere.
    let weight = |x: f64, y: f64| -> f64 {
        let (cx, cy) = (x, y - y_m / 2.0);
        let half = |v: f64| {
            if v.abs() < 1e-9 {
                1.0
            } else if v < 0.0 {
                2.0
            } else {
                0.0
            }
        };
        half(cx) * half(cy)
    };
    let directions: Vec<(f64, f64)> = (0..AZIMUTHS)
        .map(|a| (2.0 * PI * (a as f64 + 0.5) / AZIMUTHS as f64).sin_cos())
        .collect();
    let mut floor = 0.0;
    for &(x, y) in &lamps {
        let w = weight(x, y);
        if w == 0.0 {
            continue;
        }
        let px = x + x_m / 2.0;
        for (k, &band) in zonal[..90].iter().enumerate() {
            let reach = H * ((k as f64 + 0.5).to_radians()).tan();
            let hits = directions
                .iter()
                .filter(|(sin, cos)| {
                    let (hx, hy) = (px + reach * cos, y + reach * sin);
                    (0.0..=x_m).contains(&hx) && (0.0..=y_m).contains(&hy)
                })
                .count();
            floor += w * band * hits as f64 / AZIMUTHS as f64;
        }
    }
    let n = lamps.len() as f64;
    [up * n, down * n - floor, floor]
}

/// L_b for a room X × Y (metres) with the direct split `direct` (ceiling, walls, floor, lm)
/// and reflectances (ceiling, walls, floor): the walls' indirect illuminance over π.
fn background_luminance(direct: [f64; 3], x_m: f64, y_m: f64, rho: [f64; 3]) -> f64 {
    let a_f = x_m * y_m;
    let a_w = 2.0 * (x_m + y_m) * H;
    let f_fc = crate::geometry::howell::parallel_rectangles(x_m, y_m, H);
    let f_fw = 1.0 - f_fc;
    let f_wf = a_f * f_fw / a_w;
    let f_ww = 1.0 - 2.0 * f_wf;
    // Rows: ceiling, walls, floor; F[i][j] from i to j.
    let f = [[0.0, f_fw, f_fc], [f_wf, f_ww, f_wf], [f_fc, f_fw, 0.0]];
    let e0 = [direct[0] / a_f, direct[1] / a_w, direct[2] / a_f];
    // M = ρ (E0 + F M): solve (I − ρF) M = ρ E0.
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for i in 0..3 {
        for j in 0..3 {
            a[i][j] = f64::from(i == j) - rho[i] * f[i][j];
        }
        b[i] = rho[i] * e0[i];
    }
    let m = solve3(a, b);
    let e_wall: f64 = (0..3).map(|j| f[1][j] * m[j]).sum();
    e_wall / PI
}

/// Solves a 3 × 3 system by Cramer's rule (the matrix is diagonally dominant).
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> [f64; 3] {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    let mut x = [0.0; 3];
    for (k, xk) in x.iter_mut().enumerate() {
        let mut m = a;
        for i in 0..3 {
            m[i][k] = b[i];
        }
        *xk = det(m) / d;
    }
    x
}

/// The UGR table of `lum` for the flux of lamp set `set` (see [`lamp_set_flux`]) at
/// spacing-to-height ratio `shr`.
pub fn ugr_table(
    lum: &Luminaire,
    set: Option<usize>,
    shr: f64,
    interp: Interp,
) -> Result<UgrTable, PhotometryError> {
    if !(shr.is_finite() && (0.05..=4.0).contains(&shr)) {
        return Err(PhotometryError::Field {
            field: "shr",
            value: shr.to_string(),
            problem: "is not a spacing-to-height ratio between 0.05 and 4".into(),
        });
    }
    LuminousArea::required(lum, "UGR needs the luminance")?;
    let flux = lamp_set_flux(lum, set)?;
    let zonal = zonal_flux(lum, flux, interp);
    type Row = [Option<f64>; 5];
    let rows: Vec<(Row, Row)> = ROOMS
        .par_iter()
        .map(|&room| {
            let (x_m, y_m) = (room[0] * H, room[1] * H);
            let direct = direct_split(&zonal, x_m, y_m, shr * H);
            let sums = [View::Crosswise, View::Endwise]
                .map(|v| glare_sum(lum, flux, room, shr, v, interp, STANDARD_EYE));
            let mut cross = [None; 5];
            let mut end = [None; 5];
            for (k, rho) in REFLECTANCES.iter().enumerate() {
                let lb = background_luminance(direct, x_m, y_m, *rho);
                cross[k] = ugr_of(sums[0], lb);
                end[k] = ugr_of(sums[1], lb);
            }
            (cross, end)
        })
        .collect();
    if rows
        .iter()
        .all(|(c, e)| c.iter().chain(e).all(Option::is_none))
    {
        return Err(PhotometryError::Invalid(format!(
            "no light below the horizontal reaches the observer in any standard room (DFF {:.1} %): an indirect luminaire has no UGR table",
            lum.summary().dff_computed
        )));
    }
    Ok(UgrTable {
        shr,
        rooms: ROOMS.to_vec(),
        reflectances: REFLECTANCES.to_vec(),
        crosswise: rows.iter().map(|r| r.0).collect(),
        endwise: rows.iter().map(|r| r.1).collect(),
        flux_lm: flux,
        observer_variation: VARIATION_SPACINGS
            .par_iter()
            .map(|&s| observer_variation(lum, s, interp))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn guth_index_is_one_on_the_line_of_sight_and_grows_away_from_it() {
        assert!((guth_position_index(0.0, 0.0, 1.0) - 1.0).abs() < 1e-12);
        let straight_up = guth_position_index(0.0, 1.0, 1.0);
        // Higher above the line of sight, or further aside, weighs less (larger p).
        assert!(guth_position_index(0.0, 0.5, 1.0) < straight_up);
        assert!(guth_position_index(1.0, 0.1, 1.0) > guth_position_index(0.0, 0.1, 1.0));
        // α = 0, β = 45°: ln p = (35.2 − 1.22)·10⁻³·45 + 21·10⁻⁵·45², by hand.
        let by_hand = (33.98e-3 * 45.0 + 21e-5 * 2025.0f64).exp();
        assert!((straight_up - by_hand).abs() < 1e-12, "{straight_up}");
    }

    #[test]
    fn solve3_solves() {
        let x = solve3(
            [[2.0, 1.0, 0.0], [1.0, 3.0, 1.0], [0.0, 1.0, 4.0]],
            [3.0, 5.0, 5.0],
        );
        for (v, want) in x.iter().zip([1.0, 1.0, 1.0]) {
            assert!((v - want).abs() < 1e-12);
        }
    }
}
