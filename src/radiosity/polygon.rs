//! Planar polygon helpers shared by the element layout and the shooters' cells.

use glam::{DVec2, DVec3};

/// Clips a convex polygon to the half-plane left of the directed edge a → b.
fn clip_left(poly: &[DVec2], a: DVec2, b: DVec2) -> Vec<DVec2> {
    let side = |p: DVec2| (b - a).perp_dot(p - a);
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p + (q - p) * (sp / (sp - sq)));
        }
    }
    out
}

/// The axis-aligned square [lo, hi] clipped to the triangle `t` (counter-clockwise).
pub(crate) fn clip_square(lo: DVec2, hi: DVec2, t: &[DVec2; 3]) -> Vec<DVec2> {
    let mut poly = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    for k in 0..3 {
        if poly.is_empty() {
            break;
        }
        poly = clip_left(&poly, t[k], t[(k + 1) % 3]);
    }
    poly
}

/// Area and centroid of a simple polygon (shoelace).
pub(crate) fn area_centroid(poly: &[DVec2]) -> (f64, DVec2) {
    let mut a = 0.0;
    let mut c = DVec2::ZERO;
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let cross = p.perp_dot(q);
        a += cross;
        c += (p + q) * cross;
    }
    if a.abs() < 1e-300 {
        let mean = poly.iter().copied().sum::<DVec2>() / poly.len().max(1) as f64;
        return (0.0, mean);
    }
    (a / 2.0, c / (3.0 * a))
}

/// A shooting polygon for the GPU's record: `hull` when it has 3 to 8 corners; a hull with
/// more becomes its bounding rectangle, and one without area the square [lo, hi].
pub(crate) fn outline(hull: &[DVec2], lo: DVec2, hi: DVec2) -> Vec<DVec2> {
    if (3..=8).contains(&hull.len()) {
        return hull.to_vec();
    }
    let (a, b) = if hull.len() > 8 {
        let a = hull.iter().copied().fold(hi, DVec2::min);
        (a, hull.iter().copied().fold(lo, DVec2::max))
    } else {
        (lo, hi)
    };
    vec![a, DVec2::new(b.x, a.y), b, DVec2::new(a.x, b.y)]
}

/// An orthonormal frame (t, b, n) around unit `n`.
pub(crate) fn frame(n: DVec3) -> (DVec3, DVec3) {
    let t = if n.z.abs() < 0.9 {
        DVec3::Z.cross(n)
    } else {
        DVec3::X.cross(n)
    }
    .normalize();
    (t, n.cross(t))
}
