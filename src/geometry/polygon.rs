//! Polygons in plan (`[x, y]` metres): inside tests, distances, convexity, the band
//! around a convex polygon (its sides moved out, corners mitred) and clipping by a
//! convex polygon. The calculation areas of EN 12464-1 are built from these.

/// A polygon in plan: its corners in order (either way round), not closed.
pub type Polygon = [[f64; 2]];

/// Whether `(x, y)` is inside `polygon` (even-odd rule; points on an edge may go either
/// way).
pub fn inside(polygon: &Polygon, x: f64, y: f64) -> bool {
    let mut inside = false;
    let mut j = polygon.len().wrapping_sub(1);
    for i in 0..polygon.len() {
        let ([xi, yi], [xj, yj]) = (polygon[i], polygon[j]);
        if (yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// The distance from `(x, y)` to the nearest point of `polygon`'s outline, metres.
pub fn distance_to_outline(polygon: &Polygon, x: f64, y: f64) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..polygon.len() {
        let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            (((x - a[0]) * dx + (y - a[1]) * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        best = best.min((x - a[0] - t * dx).hypot(y - a[1] - t * dy));
    }
    best
}

/// Twice the signed area: positive when the corners run counter-clockwise.
pub fn signed_area2(polygon: &Polygon) -> f64 {
    (0..polygon.len())
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum()
}

/// The corners counter-clockwise, repeated corners and corners on a straight side left
/// out.
pub fn counter_clockwise(polygon: &Polygon) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = polygon.to_vec();
    if signed_area2(&p) < 0.0 {
        p.reverse();
    }
    let scale = p
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(1.0);
    let mut k = 0;
    while k < p.len() && p.len() > 3 {
        let n = p.len();
        let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
        if cross(a, b, c).abs() <= 1e-12 * scale * scale {
            p.remove(k);
        } else {
            k += 1;
        }
    }
    p
}

/// (b − a) × (c − b): positive where the path a → b → c turns left.
fn cross(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
}

/// Whether the polygon is convex with an area (every turn the same way, no side
/// crossing another).
pub fn is_convex(polygon: &Polygon) -> bool {
    let p = counter_clockwise(polygon);
    if p.len() < 3 || signed_area2(&p) <= 0.0 {
        return false;
    }
    let n = p.len();
    let turns_left = (0..n).all(|k| cross(p[(k + n - 1) % n], p[k], p[(k + 1) % n]) > 0.0);
    // All left turns that wind round once: the angles of the sides add up to one turn.
    let winding: f64 = (0..n)
        .map(|k| {
            let (a, b, c) = (p[(k + n - 1) % n], p[k], p[(k + 1) % n]);
            let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
            (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1])
        })
        .sum();
    turns_left && (winding - std::f64::consts::TAU).abs() < 1e-6
}

/// The convex polygon with every side of `convex` moved out by `width` metres, corners
/// mitred (a rectangle grows into the rectangle `width` larger on every side): every
/// point of the band is within `width` of the polygon across the nearest side. `convex`
/// must be convex ([`is_convex`]).
pub fn grow_convex(convex: &Polygon, width: f64) -> Vec<[f64; 2]> {
    let p = counter_clockwise(convex);
    let n = p.len();
    // Side k runs from p[k] to p[k+1]; its outward normal is to the right.
    let side = |k: usize| {
        let (a, b) = (p[k], p[(k + 1) % n]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        let normal = [dy / len, -dx / len];
        let moved = [a[0] + width * normal[0], a[1] + width * normal[1]];
        (moved, [dx, dy])
    };
    (0..n)
        .map(|k| {
            // Corner k joins side k−1 and side k.
            let (a, u) = side((k + n - 1) % n);
            let (b, v) = side(k);
            let det = u[0] * v[1] - u[1] * v[0];
            let t = ((b[0] - a[0]) * v[1] - (b[1] - a[1]) * v[0]) / det;
            [a[0] + t * u[0], a[1] + t * u[1]]
        })
        .collect()
}

/// `subject` clipped to the convex polygon `clipper` (Sutherland–Hodgman): the part of
/// `subject` inside `clipper`, empty when none is. `subject` may be any simple polygon
/// (an L-shaped room); where the part falls in pieces they are joined along `clipper`'s
/// sides.
pub fn clip_to_convex(subject: &Polygon, clipper: &Polygon) -> Vec<[f64; 2]> {
    let c = counter_clockwise(clipper);
    let mut out: Vec<[f64; 2]> = subject.to_vec();
    for k in 0..c.len() {
        let (a, b) = (c[k], c[(k + 1) % c.len()]);
        // Inside: on the left of a → b.
        let side = |p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        let input = std::mem::take(&mut out);
        for i in 0..input.len() {
            let (p, q) = (input[i], input[(i + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out.dedup();
    if out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// The lowest and highest corner coordinates, `([x_min, y_min], [x_max, y_max])`.
pub fn bounds(polygon: &Polygon) -> ([f64; 2], [f64; 2]) {
    polygon.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}

/// The rectangle with one corner at `corner` and sides `size` along x and y,
/// counter-clockwise.
pub fn rectangle(corner: [f64; 2], size: [f64; 2]) -> Vec<[f64; 2]> {
    let [x, y] = corner;
    vec![
        [x, y],
        [x + size[0], y],
        [x + size[0], y + size[1]],
        [x, y + size[1]],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: [[f64; 2]; 6] = [
        [0.0, 0.0],
        [8.0, 0.0],
        [8.0, 4.0],
        [4.0, 4.0],
        [4.0, 8.0],
        [0.0, 8.0],
    ];

    fn area(p: &Polygon) -> f64 {
        signed_area2(p).abs() / 2.0
    }

    #[test]
    fn a_rectangle_grows_into_the_larger_rectangle() {
        let r = rectangle([1.0, 2.0], [1.6, 0.8]);
        let g = grow_convex(&r, 0.5);
        let (lo, hi) = bounds(&g);
        assert_eq!(g.len(), 4);
        for (got, want) in lo.iter().chain(&hi).zip([0.5, 1.5, 3.1, 3.3]) {
            assert!((got - want).abs() < 1e-12, "{g:?}");
        }
        assert!((area(&g) - 2.6 * 1.8).abs() < 1e-12);
        // Clockwise input grows the same way.
        let mut cw = r.clone();
        cw.reverse();
        assert!((area(&grow_convex(&cw, 0.5)) - 2.6 * 1.8).abs() < 1e-12);
    }

    #[test]
    fn a_rotated_square_grows_by_its_sides() {
        // A unit square turned 45°: grown by w it is the square of side 1 + 2w.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let diamond = [[0.0, -h], [h, 0.0], [0.0, h], [-h, 0.0]];
        let g = grow_convex(&diamond, 0.25);
        assert!((area(&g) - 1.5 * 1.5).abs() < 1e-12);
    }

    #[test]
    fn convexity() {
        assert!(is_convex(&rectangle([0.0, 0.0], [2.0, 1.0])));
        assert!(!is_convex(&L));
        // A bow tie crosses itself.
        assert!(!is_convex(&[
            [0.0, 0.0],
            [1.0, 1.0],
            [1.0, 0.0],
            [0.0, 1.0]
        ]));
        // A pentagram turns left at every corner but winds twice.
        let star: Vec<[f64; 2]> = (0..5)
            .map(|k| {
                let a = std::f64::consts::TAU * (2 * k) as f64 / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        assert!(!is_convex(&star));
        // A corner on a straight side does not matter.
        assert!(is_convex(&[
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [0.0, 1.0]
        ]));
    }

    #[test]
    fn clipping_an_l_shaped_room_keeps_what_is_inside() {
        // The L clipped to a square over its inner corner: the square less the notch.
        let square = rectangle([2.0, 2.0], [4.0, 4.0]);
        let c = clip_to_convex(&L, &square);
        assert!((area(&c) - (16.0 - 4.0)).abs() < 1e-12, "{c:?}");
        assert!(inside(&c, 3.0, 3.0) && !inside(&c, 5.0, 5.0));
        // Wholly inside: the clipper; wholly outside: nothing.
        let inner = rectangle([1.0, 1.0], [1.0, 1.0]);
        assert!((area(&clip_to_convex(&L, &inner)) - 1.0).abs() < 1e-12);
        assert!(clip_to_convex(&L, &rectangle([20.0, 20.0], [1.0, 1.0])).is_empty());
    }

    #[test]
    fn inside_and_distance() {
        assert!(inside(&L, 1.0, 7.0) && !inside(&L, 6.0, 6.0));
        assert!((distance_to_outline(&L, 6.0, 6.0) - 2.0).abs() < 1e-12);
        assert!((distance_to_outline(&L, 9.0, 9.0) - 26f64.sqrt()).abs() < 1e-12);
        assert!((distance_to_outline(&L, 1.0, 7.0) - 1.0).abs() < 1e-12);
    }
}
