//! Form factors from a differential receiver area to a shooting patch, and the analytic
//! values of Howell's catalogue the tests check them against.

use std::f64::consts::PI;

use glam::DVec3;

/// How the solver evaluates the form factor from a receiver element to a shooting patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum FormFactorKind {
    /// The disc approximation (Wallace et al.; Wallner Eq. 2.2): A cos φi cos φj / (π d² + A).
    /// Cheap, but it saturates for receivers next to the patch (−10 % for perpendicular
    /// squares sharing an edge).
    Disc,
    /// The exact form factor to the patch's polygon (Lambert's contour integral), clipped
    /// to the receiver's horizon (the default).
    #[default]
    Polygon,
}

/// Disc approximation (Wallner Eq. 2.2 with one sample): from a differential area at `p`
/// with unit normal `n` to a disc of `area` at `q` with unit normal `nq`.
pub fn disc(p: DVec3, n: DVec3, q: DVec3, nq: DVec3, area: f64) -> f64 {
    let d = q - p;
    let d2 = d.length_squared();
    if d2 <= 0.0 {
        return 0.0;
    }
    let w = d / d2.sqrt();
    let cos_p = n.dot(w);
    let cos_q = -nq.dot(w);
    if cos_p <= 0.0 || cos_q <= 0.0 {
        return 0.0;
    }
    area * cos_p * cos_q / (PI * d2 + area)
}

/// Clips `poly` to the half-space n · (x − p) ≥ 0.
fn clip_above(poly: &[DVec3], p: DVec3, n: DVec3) -> Vec<DVec3> {
    let side = |x: DVec3| n.dot(x - p);
    let mut out = Vec::with_capacity(poly.len() + 2);
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            out.push(a + (b - a) * (sa / (sa - sb)));
        }
    }
    out
}

/// Exact form factor from a differential area at `p` with unit normal `n` to the planar
/// convex polygon `poly` with unit normal `nq` (emitting on that side), unoccluded:
/// Lambert's formula F = (1 / 2π) Σ θ_k n · g_k over the polygon's edges.
pub fn polygon(p: DVec3, n: DVec3, poly: &[DVec3], nq: DVec3) -> f64 {
    if poly.len() < 3 || nq.dot(p - poly[0]) <= 0.0 {
        return 0.0;
    }
    let clipped = clip_above(poly, p, n);
    if clipped.len() < 3 {
        return 0.0;
    }
    let mut sum = 0.0;
    for (i, &a) in clipped.iter().enumerate() {
        let b = clipped[(i + 1) % clipped.len()];
        let (ra, rb) = (a - p, b - p);
        let cross = ra.cross(rb);
        let len = cross.length();
        if len <= 1e-300 {
            continue;
        }
        let angle = len.atan2(ra.dot(rb));
        sum += angle * n.dot(cross / len);
    }
    (sum / (2.0 * PI)).abs()
}

/// Analytic form factors (Howell), kept in `geometry` for the photometry that needs them.
pub use crate::geometry::howell;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn howell_formulas_give_the_catalogue_values() {
        assert!((howell::parallel_rectangles(1.0, 1.0, 1.0) - 0.199825).abs() < 1e-6);
        assert!((howell::perpendicular_rectangles(1.0, 1.0, 1.0) - 0.200044).abs() < 1e-6);
        // Equal discs, r = h: (3 − √5) / 2.
        let want = (3.0 - 5f64.sqrt()) / 2.0;
        assert!((howell::coaxial_discs(1.0, 1.0, 1.0) - want).abs() < 1e-12);
    }

    #[test]
    fn polygon_form_factor_of_a_disc_like_polygon_matches_the_point_to_disc_value() {
        // From a point on the axis to a coaxial disc of radius r at height h: r² / (h² + r²).
        let (r, h) = (0.7, 1.3);
        let ring: Vec<DVec3> = (0..2000)
            .map(|k| {
                let a = -(k as f64) / 2000.0 * std::f64::consts::TAU;
                DVec3::new(r * a.cos(), r * a.sin(), h)
            })
            .collect();
        let f = polygon(DVec3::ZERO, DVec3::Z, &ring, -DVec3::Z);
        assert!((f - r * r / (h * h + r * r)).abs() < 1e-5, "{f}");
        // Seen from behind the polygon's front: nothing.
        assert_eq!(polygon(DVec3::ZERO, DVec3::Z, &ring, DVec3::Z), 0.0);
        // A polygon half below the horizon counts only its upper half.
        let square = [
            DVec3::new(1.0, -0.5, -0.5),
            DVec3::new(1.0, 0.5, -0.5),
            DVec3::new(1.0, 0.5, 0.5),
            DVec3::new(1.0, -0.5, 0.5),
        ];
        let up = polygon(DVec3::ZERO, DVec3::Z, &square, -DVec3::X);
        let side = polygon(DVec3::ZERO, DVec3::X, &square, -DVec3::X);
        assert!(up > 0.0 && up < side, "{up} {side}");
    }

    #[test]
    fn disc_approximation_tends_to_the_exact_value_far_away() {
        let square = [
            DVec3::new(-0.05, -0.05, 3.0),
            DVec3::new(-0.05, 0.05, 3.0),
            DVec3::new(0.05, 0.05, 3.0),
            DVec3::new(0.05, -0.05, 3.0),
        ];
        let p = DVec3::new(0.4, 0.2, 0.0);
        let exact = polygon(p, DVec3::Z, &square, -DVec3::Z);
        let approx = disc(p, DVec3::Z, DVec3::new(0.0, 0.0, 3.0), -DVec3::Z, 0.01);
        assert!((approx / exact - 1.0).abs() < 1e-3, "{approx} vs {exact}");
    }
}
