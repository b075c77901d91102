//! Oriented bounding boxes of face clusters (Edström §4.2.2): one axis along the cluster's
//! summed area normal, the other two those of the minimum-area rectangle around the points
//! projected on the plane across it (rotating an edge of the convex hull).

use glam::{DVec2, DVec3};

/// A box: centre, three unit axes (the third along the cluster's normal) and half sizes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obb {
    /// Centre, metres.
    pub centre: DVec3,
    /// Unit axes: two in the cluster's plane, the third along its summed area normal.
    pub axes: [DVec3; 3],
    /// Half extents along the axes, metres.
    pub half: DVec3,
}

impl Obb {
    /// The eight corners.
    pub fn corners(&self) -> [DVec3; 8] {
        std::array::from_fn(|k| {
            let s = |bit: usize| if k >> bit & 1 == 1 { 1.0 } else { -1.0 };
            self.centre
                + self.axes[0] * (s(0) * self.half.x)
                + self.axes[1] * (s(1) * self.half.y)
                + self.axes[2] * (s(2) * self.half.z)
        })
    }

    /// Whether `p` lies inside, with `tolerance` metres to spare.
    pub fn contains(&self, p: DVec3, tolerance: f64) -> bool {
        let d = p - self.centre;
        (0..3).all(|k| d.dot(self.axes[k]).abs() <= self.half[k] + tolerance)
    }

    /// The box around `points` with its third axis along `normal` (any direction when
    /// `normal` is zero: a cluster whose faces cancel out).
    pub fn around(points: &[DVec3], normal: DVec3) -> Obb {
        let n = normal.try_normalize().unwrap_or(DVec3::Z);
        let (u0, v0) = n.any_orthonormal_pair();
        let flat: Vec<DVec2> = points
            .iter()
            .map(|p| DVec2::new(p.dot(u0), p.dot(v0)))
            .collect();
        let dir = min_area_direction(&flat);
        let (u, v) = (u0 * dir.x + v0 * dir.y, v0 * dir.x - u0 * dir.y);
        let axes = [u, v, n];
        let mut lo = DVec3::splat(f64::INFINITY);
        let mut hi = DVec3::splat(f64::NEG_INFINITY);
        for p in points {
            let q = DVec3::new(p.dot(u), p.dot(v), p.dot(n));
            lo = lo.min(q);
            hi = hi.max(q);
        }
        if points.is_empty() {
            (lo, hi) = (DVec3::ZERO, DVec3::ZERO);
        }
        let mid = (lo + hi) * 0.5;
        Obb {
            centre: u * mid.x + v * mid.y + n * mid.z,
            axes,
            half: (hi - lo) * 0.5,
        }
    }
}

/// The unit direction of one side of the minimum-area rectangle around `points`.
fn min_area_direction(points: &[DVec2]) -> DVec2 {
    min_area_rectangle(points).0
}

/// The minimum-area rectangle around `points`: the unit direction `e` of one side, and the
/// rectangle's corners `lo`, `hi` in the frame (along `e`, along `e.perp()`).
pub(crate) fn min_area_rectangle(points: &[DVec2]) -> (DVec2, DVec2, DVec2) {
    let area = |r: &(DVec2, DVec2, DVec2)| (r.2.x - r.1.x) * (r.2.y - r.1.y);
    enclosing_rectangles(points)
        .into_iter()
        .fold(None, |best: Option<(DVec2, DVec2, DVec2)>, r| match best {
            Some(b) if area(&b) <= area(&r) => Some(b),
            _ => Some(r),
        })
        .unwrap_or((DVec2::X, DVec2::ZERO, DVec2::ZERO))
}

/// The rectangle around `points` with a side along each edge of their convex hull (the
/// minimum-area one is among them; rotating calipers find it in linear time, which hulls of
/// a few points do not need): per edge, its unit direction `e` and the corners `lo`, `hi`
/// in the frame (along `e`, along `e.perp()`).
pub(crate) fn enclosing_rectangles(points: &[DVec2]) -> Vec<(DVec2, DVec2, DVec2)> {
    let hull = convex_hull(points);
    (0..hull.len())
        .filter_map(|i| (hull[(i + 1) % hull.len()] - hull[i]).try_normalize())
        .map(|e| {
            let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
            for p in &hull {
                let q = DVec2::new(p.dot(e), e.perp_dot(*p));
                lo = lo.min(q);
                hi = hi.max(q);
            }
            (e, lo, hi)
        })
        .collect()
}

/// Andrew's monotone chain: the convex hull, counter-clockwise, collinear points dropped.
pub(crate) fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull = half_hull(p.iter().copied());
    hull.pop();
    let mut upper = half_hull(p.iter().rev().copied());
    upper.pop();
    hull.extend(upper);
    hull
}

/// One chain of the monotone-chain hull over points in sorted order.
fn half_hull(points: impl Iterator<Item = DVec2>) -> Vec<DVec2> {
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut chain: Vec<DVec2> = Vec::new();
    for q in points {
        while chain.len() >= 2 && cross(chain[chain.len() - 2], chain[chain.len() - 1], q) <= 0.0 {
            chain.pop();
        }
        chain.push(q);
    }
    chain
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotated_rectangle_gets_its_own_box() {
        // A 4 × 1 rectangle turned 30° in the plane z = 2: the box is 4 × 1 × 0.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let pts: Vec<DVec3> = [(0.0, 0.0), (4.0, 0.0), (4.0, 1.0), (0.0, 1.0), (2.0, 0.5)]
            .map(|(x, y)| DVec3::new(c * x - s * y, s * x + c * y, 2.0))
            .to_vec();
        let b = Obb::around(&pts, DVec3::Z);
        let mut sides = [b.half.x * 2.0, b.half.y * 2.0];
        sides.sort_by(f64::total_cmp);
        assert!(
            (sides[0] - 1.0).abs() < 1e-9 && (sides[1] - 4.0).abs() < 1e-9,
            "{sides:?}"
        );
        assert!(b.half.z.abs() < 1e-12);
        assert!(pts.iter().all(|&p| b.contains(p, 1e-9)));
        assert!((b.axes[2] - DVec3::Z).length() < 1e-12);
    }
}
