//! CPU references: "is this point in shadow" by ray casting (the brute-force loop over
//! every triangle: the oracle of [`super::bvh::TriangleBvh`], which every caller uses),
//! and the near-clip-volume test that decides between z-pass and z-fail (Wallner Fig. 1.4).

use glam::DVec3;

use super::{Cutouts, IgnoredTriangles, Light};
use crate::geometry::Mesh;

/// How far outside a triangle's edges (in barycentric units) a ray still hits it: rounding
/// must not let a ray through the edge two triangles share (a floor's diagonal leaked
/// light to one point in a hundred along it).
const EDGE_SLACK: f64 = 1e-9;

/// Möller–Trumbore: distance along `dir` to triangle (`a`, `b`, `c`), if hit in (tmin, tmax).
pub(crate) fn ray_triangle(
    o: DVec3,
    dir: DVec3,
    [a, b, c]: [DVec3; 3],
    tmin: f64,
    tmax: f64,
) -> Option<f64> {
    let e1 = b - a;
    let e2 = c - a;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-15 {
        return None;
    }
    let inv = 1.0 / det;
    let s = o - a;
    let u = s.dot(p) * inv;
    if !(-EDGE_SLACK..=1.0 + EDGE_SLACK).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < -EDGE_SLACK || u + v > 1.0 + EDGE_SLACK {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > tmin && t < tmax).then_some(t)
}

fn corners(mesh: &Mesh, t: &[u32; 3]) -> [DVec3; 3] {
    t.map(|i| mesh.positions[i as usize])
}

/// The nearest triangle hit by the ray from `o` along `dir` beyond `tmin`: (distance in
/// units of `dir`, triangle index).
pub fn first_hit(mesh: &Mesh, o: DVec3, dir: DVec3, tmin: f64) -> Option<(f64, usize)> {
    let mut best: Option<(f64, usize)> = None;
    for (k, t) in mesh.triangles.iter().enumerate() {
        let tmax = best.map_or(f64::INFINITY, |b| b.0);
        if let Some(d) = ray_triangle(o, dir, corners(mesh, t), tmin, tmax) {
            best = Some((d, k));
        }
    }
    best
}

/// The offset that keeps a point on a surface of `mesh` (vertices stored as f32) from
/// shadowing itself: 1e-6 of the mesh's size, plus 1e-6 m.
pub fn self_hit_epsilon(mesh: &Mesh) -> f64 {
    let size = mesh.bounds().map_or(0.0, |(lo, hi)| (hi - lo).length());
    1e-6 * (1.0 + size)
}

/// Whether `p` is in shadow: any triangle strictly between `p` and the light. `eps`
/// (relative to the scene) keeps a surface from shadowing itself.
pub fn in_shadow(mesh: &Mesh, light: &Light, p: DVec3, eps: f64) -> bool {
    in_shadow_ignoring(mesh, light, p, eps, &IgnoredTriangles::default())
}

/// [`in_shadow`] with the triangles `ignored` (the light's own housing) left out.
pub fn in_shadow_ignoring(
    mesh: &Mesh,
    light: &Light,
    p: DVec3,
    eps: f64,
    ignored: &IgnoredTriangles,
) -> bool {
    in_shadow_through(mesh, None, light, p, eps, ignored)
}

/// [`in_shadow_ignoring`] where the masked triangles of `cutouts` let light through their
/// holes.
pub fn in_shadow_through(
    mesh: &Mesh,
    cutouts: Option<&Cutouts>,
    light: &Light,
    p: DVec3,
    eps: f64,
    ignored: &IgnoredTriangles,
) -> bool {
    let (dir, tmax) = shadow_ray(light, p, eps);
    mesh.triangles.iter().enumerate().any(|(k, t)| {
        let c = corners(mesh, t);
        ray_triangle(p, dir, c, eps, tmax)
            .is_some_and(|d| cutouts.is_none_or(|cut| !cut.passes(k, c, p + dir * d)))
            && !ignored.contains(k)
    })
}

/// The ray from `p` toward `light`: unit direction and the distance where it stops (`eps`
/// short of a point light; unbounded toward a light at infinity).
pub(crate) fn shadow_ray(light: &Light, p: DVec3, eps: f64) -> (DVec3, f64) {
    if light.is_directional() {
        (light.0.truncate(), f64::INFINITY)
    } else {
        let d = light.0.truncate() - p;
        let len = d.length();
        (d / len, len - eps)
    }
}

/// The near-clip volume: the convex hull of the near-plane rectangle and the light (or the
/// rectangle swept toward a light at infinity), as inward-facing planes (n, d): inside
/// where n · x + d ≥ 0 for every plane.
pub fn near_clip_volume(near: [DVec3; 4], light: &Light) -> Vec<(DVec3, f64)> {
    let centre = (near[0] + near[1] + near[2] + near[3]) * 0.25;
    let toward = light.direction_from(centre);
    let inside = if light.is_directional() {
        centre + toward
    } else {
        (centre + light.0.truncate()) * 0.5
    };
    let mut planes = Vec::new();
    let mut add = |n: DVec3, on: DVec3| {
        if n.length_squared() > 0.0 {
            let n = n.normalize();
            let d = -n.dot(on);
            let s = if n.dot(inside) + d >= 0.0 { 1.0 } else { -1.0 };
            planes.push((n * s, d * s));
        }
    };
    let base_n = (near[1] - near[0]).cross(near[3] - near[0]);
    add(base_n, near[0]);
    for k in 0..4 {
        let (a, b) = (near[k], near[(k + 1) % 4]);
        let side = if light.is_directional() {
            (b - a).cross(light.0.truncate())
        } else {
            (b - a).cross(light.0.truncate() - a)
        };
        add(side, a);
    }
    planes
}

/// Clips a convex polygon by the half-space n · x + d ≥ 0.
fn clip(poly: Vec<DVec3>, n: DVec3, d: f64) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (dp, dq) = (n.dot(p) + d, n.dot(q) + d);
        if dp >= 0.0 {
            out.push(p);
        }
        if (dp >= 0.0) != (dq >= 0.0) {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// z-fail is needed when any triangle reaches into the near-clip volume (the camera's
/// near plane may then lie inside a shadow volume); z-pass is safe otherwise.
pub fn needs_zfail(mesh: &Mesh, light: &Light, near: [DVec3; 4]) -> bool {
    let planes = near_clip_volume(near, light);
    mesh.triangles.iter().any(|t| {
        let mut poly = corners(mesh, t).to_vec();
        for &(n, d) in &planes {
            poly = clip(poly, n, d);
            if poly.is_empty() {
                return false;
            }
        }
        true
    })
}

/// The brute-force check of [`needs_zfail`]: rays from an n × n grid of points on the
/// near rectangle toward the light; true if any is blocked.
pub fn near_plane_shadowed_by_sampling(
    mesh: &Mesh,
    light: &Light,
    near: [DVec3; 4],
    n: usize,
) -> bool {
    (0..n).any(|i| {
        (0..n).any(|j| {
            let (u, v) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
            let p = near[0] + (near[1] - near[0]) * u + (near[3] - near[0]) * v;
            in_shadow(mesh, light, p, 0.0)
        })
    })
}
