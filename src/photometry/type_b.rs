//! IES Type B (and Type A) photometry resampled onto the C-γ grid every other part of
//! goniolight uses.
//!
//! Type B (floodlights): the polar axis is the luminaire's horizontal *lateral* axis. A
//! direction is given by the vertical angle V, the rotation of a half-plane about the polar
//! axis (V = 0 through the beam, V > 0 above it) and the horizontal angle H, the angle from
//! that plane's meridian toward the polar axis (H > 0 to the luminaire's left). In the Type
//! B frame (x the photometric axis, y the polar axis, z up) the direction is
//! `(cos H cos V, sin H, cos H sin V)`.
//!
//! The conversion (CIE 121 / IES LM-75 conventions, the one Radiance's `ies2rad` makes):
//! the photometric axis becomes the C-γ frame's γ = 0 axis (nadir), the polar axis lies
//! along C90–C270 (H > 0 toward C90) and V > 0 toward C0, so that
//! `cos γ = cos H · cos V` and `tan C = sin H / (cos H · sin V)`. A floodlight therefore
//! arrives aimed straight down, as a downlight with its beam on the axis; the scene aims it.
//!
//! Type A (automotive) is Type B turned 90° about the vertical axis (counter-clockwise, as
//! prEN 13032-1 defines it): its polar axis lies along C0–C180, so C_A = C_B + 90°.
//!
//! Directions outside the measured range (behind the luminaire for the usual
//! −90°…90° tables) carry no light. Tables given for 0°…90° only are mirrored (LM-63:
//! laterally symmetric data).

use glam::DVec3;

/// A Type C table: C angles (full circle), γ angles and candela rows per C angle.
#[derive(Debug, Clone, PartialEq)]
pub struct CGammaTable {
    /// C angles in `[0°, 360°]`, the last 360° closing the circle as LM-63 writes it.
    pub c: Vec<f64>,
    /// γ angles `0°…180°`.
    pub gamma: Vec<f64>,
    /// Candela, one row per C angle.
    pub candela: Vec<Vec<f64>>,
}

/// Checks that Type B/A angle lists start where LM-63 allows: −90° (a full range) or 0°
/// (laterally symmetric data, mirrored).
pub fn check_ranges(vertical: &[f64], horizontal: &[f64]) -> Result<(), String> {
    for (what, a) in [("vertical", vertical), ("horizontal", horizontal)] {
        let first = a[0];
        if first != 0.0 && first != -90.0 && a.len() > 1 {
            return Err(format!(
                "Type B/A {what} angles must start at -90° (full range) or 0° (symmetric), found {first}°"
            ));
        }
    }
    Ok(())
}

/// (H, V) in degrees of a direction in the C-γ luminaire frame, for photometric type 2
/// (Type B) or 3 (Type A).
pub fn direction_to_hv(photometric_type: u8, dir: DVec3) -> (f64, f64) {
    let d = dir.normalize_or_zero();
    // Type A is Type B turned 90° about the vertical: undo that turn first.
    let d = if photometric_type == 3 {
        DVec3::new(d.y, -d.x, d.z)
    } else {
        d
    };
    // Type B frame: photometric axis = −z (nadir), polar axis = +y, "up" = +x.
    let (beam, polar, up) = (-d.z, d.y, d.x);
    let h = polar.clamp(-1.0, 1.0).asin().to_degrees();
    let v = up.atan2(beam).to_degrees();
    (h, v)
}

/// Bilinear lookup in a table whose angles start at −90° or at 0° (mirrored); zero outside.
fn lookup(vertical: &[f64], horizontal: &[f64], candela: &[Vec<f64>], h: f64, v: f64) -> f64 {
    let fold = |a: f64, axis: &[f64]| if axis[0] >= 0.0 { a.abs() } else { a };
    let (h, v) = (fold(h, horizontal), fold(v, vertical));
    let bracket = |axis: &[f64], a: f64| -> Option<(usize, usize, f64)> {
        if axis.len() == 1 {
            // One angle: the table does not vary along this axis.
            return Some((0, 0, 0.0));
        }
        let last = axis.len() - 1;
        if a < axis[0] - 1e-9 || a > axis[last] + 1e-9 {
            return None;
        }
        let k = axis.partition_point(|&x| x <= a).clamp(1, last);
        let t = ((a - axis[k - 1]) / (axis[k] - axis[k - 1])).clamp(0.0, 1.0);
        Some((k - 1, k, t))
    };
    let (Some((h0, h1, th)), Some((v0, v1, tv))) = (bracket(horizontal, h), bracket(vertical, v))
    else {
        return 0.0;
    };
    let at = |hi: usize, vi: usize| candela[hi][vi];
    let lo = at(h0, v0) * (1.0 - tv) + at(h0, v1) * tv;
    let hi = at(h1, v0) * (1.0 - tv) + at(h1, v1) * tv;
    lo * (1.0 - th) + hi * th
}

/// The γ step of the C-γ grid: the finest of 0.5°, 1° and 2° not coarser than the finest
/// step of the Type B table (so the beam keeps its measured resolution).
fn gamma_step(vertical: &[f64], horizontal: &[f64]) -> f64 {
    let finest = vertical
        .windows(2)
        .chain(horizontal.windows(2))
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    [2.0, 1.0, 0.5]
        .into_iter()
        .find(|&s| s <= finest + 1e-9)
        .unwrap_or(0.5)
}

/// Resamples a Type B (2) or Type A (3) table, candela rows per horizontal angle, onto a
/// full C-γ grid (γ every 0.5°, 1° or 2°: the coarsest not coarser than the table's finest
/// step; C every two γ steps, at most 5°).
pub fn to_c_gamma(
    photometric_type: u8,
    vertical: &[f64],
    horizontal: &[f64],
    candela: &[Vec<f64>],
) -> CGammaTable {
    let dg = gamma_step(vertical, horizontal);
    let dc = (2.0 * dg).min(5.0);
    let steps = |span: f64, d: f64| (span / d).round() as usize;
    let gamma: Vec<f64> = (0..=steps(180.0, dg)).map(|i| i as f64 * dg).collect();
    let c: Vec<f64> = (0..=steps(360.0, dc)).map(|i| i as f64 * dc).collect();
    let rows = c
        .iter()
        .map(|&cd| {
            gamma
                .iter()
                .map(|&g| {
                    let dir = super::angles_to_direction(cd, g);
                    let (h, v) = direction_to_hv(photometric_type, dir);
                    lookup(vertical, horizontal, candela, h, v)
                })
                .collect()
        })
        .collect();
    CGammaTable {
        c,
        gamma,
        candela: rows,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::angles_to_direction;

    #[test]
    fn axes_map_as_documented() {
        // Beam axis → nadir; H toward C90; V toward C0.
        let (h, v) = direction_to_hv(2, angles_to_direction(0.0, 0.0));
        assert!(h.abs() < 1e-12 && v.abs() < 1e-12);
        let (h, v) = direction_to_hv(2, angles_to_direction(90.0, 30.0));
        assert!((h - 30.0).abs() < 1e-9 && v.abs() < 1e-9, "{h} {v}");
        let (h, v) = direction_to_hv(2, angles_to_direction(0.0, 30.0));
        assert!(h.abs() < 1e-9 && (v - 30.0).abs() < 1e-9, "{h} {v}");
        // cos γ = cos H cos V everywhere.
        for (c, g) in [(37.0, 52.0), (200.0, 80.0), (300.0, 10.0)] {
            let (h, v) = direction_to_hv(2, angles_to_direction(c, g));
            let cg = h.to_radians().cos() * v.to_radians().cos();
            assert!((cg - g.to_radians().cos()).abs() < 1e-12);
        }
        // Type A's polar axis is C0–C180 (Type B's turned 90°): H > 0 toward C180.
        let (h, v) = direction_to_hv(3, angles_to_direction(180.0, 30.0));
        assert!((h - 30.0).abs() < 1e-9 && v.abs() < 1e-9, "{h} {v}");
    }

    #[test]
    fn symmetric_tables_mirror_and_outside_is_dark() {
        let vertical = [0.0, 45.0, 90.0];
        let horizontal = [0.0, 90.0];
        let candela = vec![vec![100.0, 50.0, 0.0], vec![10.0, 10.0, 10.0]];
        assert_eq!(lookup(&vertical, &horizontal, &candela, 0.0, -45.0), 50.0);
        assert_eq!(lookup(&vertical, &horizontal, &candela, -45.0, 0.0), 55.0);
        let full_v = [-90.0, 0.0, 90.0];
        let c2 = vec![vec![0.0, 100.0, 0.0]];
        assert_eq!(lookup(&full_v, &[0.0], &c2, 0.0, 120.0), 0.0);
    }
}
