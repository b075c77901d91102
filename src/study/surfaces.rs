//! Hours of direct sun on the model's own surfaces, by CPU ray casts through the BVH:
//! every facade (a connected piece of a vertical plane) sampled on a grid of cells in its
//! own plane, and window points with a normal (EN 17037's sunlight exposure). A surface
//! point gets a step's weight when the sun is in front of it (above its plane), above the
//! minimum elevation, and the ray toward the sun meets nothing.

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::geometry::Mesh;

pub use crate::planning::verdicts::en17037_level;
pub use crate::shadow::sun_rays::{surface_offset, Sun, SunRays};

/// A facade: one connected piece of a vertical plane of the model, sampled on square
/// cells in its own plane (`u` along it to the right seen from outside, `v` up).
#[derive(Debug, Clone)]
pub struct Facade {
    /// Outward unit normal (horizontal), world frame.
    pub normal: DVec3,
    /// World position of the cell grid's lower-left corner seen from outside.
    pub origin: DVec3,
    /// Unit vector along the facade, to the right seen from outside.
    pub u: DVec3,
    /// Cells along and up.
    pub cells: (usize, usize),
    /// Side of a cell, metres.
    pub cell_m: f64,
    /// Hours per cell, row 0 at the bottom (`None`: the cell's centre is not on the
    /// facade).
    pub hours: Vec<Option<f32>>,
    /// The facade's area, m².
    pub area_m2: f64,
}

impl Facade {
    /// The world position of cell (i, j)'s centre.
    pub fn cell_center(&self, i: usize, j: usize) -> DVec3 {
        self.origin
            + self.u * ((i as f64 + 0.5) * self.cell_m)
            + DVec3::Z * ((j as f64 + 0.5) * self.cell_m)
    }

    /// The compass direction it faces, degrees clockwise from true north, for a model
    /// whose +Y is `north_offset_deg` counter-clockwise from true north.
    pub fn azimuth_deg(&self, north_offset_deg: f64) -> f64 {
        (self.normal.x.atan2(self.normal.y).to_degrees() - north_offset_deg).rem_euclid(360.0)
    }
}

/// The facades of `mesh` of at least `min_area_m2`, largest first: triangles whose normal
/// is within 3° of horizontal, grouped by plane (direction within 1°, offset within
/// 5 cm) and then by shared corners. The normal is the triangles' winding (outward in a
/// well-formed model).
pub fn find_facades(mesh: &Mesh, cell_m: f64, min_area_m2: f64) -> Vec<Facade> {
    struct Wall {
        tri: usize,
        normal: DVec3,
        angle: f64,
        offset: f64,
        area: f64,
    }
    let mut walls: Vec<Wall> = mesh
        .triangles
        .iter()
        .enumerate()
        .filter_map(|(tri, t)| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
            let n = (b - a).cross(c - a);
            let area = n.length() / 2.0;
            let n = n.normalize_or_zero();
            if area <= 0.0 || n.z.abs() > 3f64.to_radians().sin() {
                return None;
            }
            let h = DVec3::new(n.x, n.y, 0.0).normalize();
            Some(Wall {
                tri,
                normal: h,
                angle: h.y.atan2(h.x).to_degrees(),
                offset: h.dot(a),
                area,
            })
        })
        .collect();
    walls.sort_by(|p, q| {
        (p.angle.round(), p.offset)
            .partial_cmp(&(q.angle.round(), q.offset))
            .expect("finite")
    });
    // Planes: runs of the same whole degree whose offsets step by less than 5 cm.
    let mut planes: Vec<Vec<usize>> = Vec::new();
    for (k, w) in walls.iter().enumerate() {
        let joins = k > 0 && {
            let p = &walls[k - 1];
            p.angle.round() == w.angle.round() && (w.offset - p.offset).abs() < 0.05
        };
        if joins {
            planes.last_mut().expect("a plane").push(k);
        } else {
            planes.push(vec![k]);
        }
    }
    let area_of: HashMap<usize, f64> = walls.iter().map(|w| (w.tri, w.area)).collect();
    let mut facades: Vec<Facade> = planes
        .iter()
        .flat_map(|plane| {
            pieces(mesh, plane.iter().map(|&k| walls[k].tri))
                .into_iter()
                .filter_map(|tris| {
                    let area: f64 = tris.iter().map(|t| area_of[t]).sum();
                    if area < min_area_m2 {
                        return None;
                    }
                    let normal = plane
                        .iter()
                        .map(|&k| walls[k].normal * walls[k].area)
                        .sum::<DVec3>()
                        .normalize();
                    Some(facade_grid(mesh, &tris, normal, cell_m, area))
                })
                .collect::<Vec<_>>()
        })
        .collect();
    facades.sort_by(|a, b| b.area_m2.total_cmp(&a.area_m2));
    facades
}

/// `tris` split into pieces that share corners (positions to the millimetre).
fn pieces(mesh: &Mesh, tris: impl Iterator<Item = usize>) -> Vec<Vec<usize>> {
    let tris: Vec<usize> = tris.collect();
    let mut parent: Vec<usize> = (0..tris.len()).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    let mut seen: HashMap<[i64; 3], usize> = HashMap::new();
    for (k, &t) in tris.iter().enumerate() {
        for &v in &mesh.triangles[t] {
            let p = mesh.positions[v as usize] * 1000.0;
            let key = [p.x.round() as i64, p.y.round() as i64, p.z.round() as i64];
            match seen.get(&key) {
                Some(&other) => {
                    let (a, b) = (root(&mut parent, k), root(&mut parent, other));
                    parent[a] = b;
                }
                None => {
                    seen.insert(key, k);
                }
            }
        }
    }
    let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
    for (k, &t) in tris.iter().enumerate() {
        let r = root(&mut parent, k);
        groups.entry(r).or_default().push(t);
    }
    let mut out: Vec<Vec<usize>> = groups.into_values().collect();
    out.sort();
    out
}

/// The cell grid over a facade's triangles (hours not yet computed: 0 on the facade).
fn facade_grid(mesh: &Mesh, tris: &[usize], normal: DVec3, cell_m: f64, area: f64) -> Facade {
    let u = (-normal).cross(DVec3::Z).normalize();
    let flat: Vec<[DVec2; 3]> = tris
        .iter()
        .map(|&t| {
            mesh.triangles[t].map(|i| {
                let p = mesh.positions[i as usize];
                DVec2::new(p.dot(u), p.z)
            })
        })
        .collect();
    let lo = flat
        .iter()
        .flatten()
        .fold(DVec2::splat(f64::INFINITY), |a, &b| a.min(b));
    let hi = flat
        .iter()
        .flatten()
        .fold(DVec2::splat(f64::NEG_INFINITY), |a, &b| a.max(b));
    let nu = (((hi.x - lo.x) / cell_m).ceil() as usize).max(1);
    let nv = (((hi.y - lo.y) / cell_m).ceil() as usize).max(1);
    let first = mesh.positions[mesh.triangles[tris[0]][0] as usize];
    let plane = normal.dot(first);
    let origin = normal * plane + u * lo.x + DVec3::Z * lo.y;
    let mut hours = vec![None; nu * nv];
    for t in &flat {
        let (a, b) = (
            t.iter().fold(DVec2::splat(f64::INFINITY), |m, &p| m.min(p)),
            t.iter()
                .fold(DVec2::splat(f64::NEG_INFINITY), |m, &p| m.max(p)),
        );
        let i0 = (((a.x - lo.x) / cell_m - 0.5).floor().max(0.0)) as usize;
        let i1 = (((b.x - lo.x) / cell_m - 0.5).ceil() as usize).min(nu - 1);
        let j0 = (((a.y - lo.y) / cell_m - 0.5).floor().max(0.0)) as usize;
        let j1 = (((b.y - lo.y) / cell_m - 0.5).ceil() as usize).min(nv - 1);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let c = lo + DVec2::new((i as f64 + 0.5) * cell_m, (j as f64 + 0.5) * cell_m);
                if in_triangle(c, t) {
                    hours[j * nu + i] = Some(0.0);
                }
            }
        }
    }
    Facade {
        normal,
        origin,
        u,
        cells: (nu, nv),
        cell_m,
        hours,
        area_m2: area,
    }
}

fn in_triangle(p: DVec2, t: &[DVec2; 3]) -> bool {
    let side = |a: DVec2, b: DVec2| (b - a).perp_dot(p - a);
    let (d0, d1, d2) = (side(t[0], t[1]), side(t[1], t[2]), side(t[2], t[0]));
    (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
}

/// Fills every facade cell's hours of direct sun (in parallel).
pub fn facade_hours(rays: &SunRays, facades: &mut [Facade]) {
    for f in facades.iter_mut() {
        let nu = f.cells.0;
        let g = f.clone();
        f.hours.par_iter_mut().enumerate().for_each(|(k, h)| {
            if h.is_some() {
                let p = g.cell_center(k % nu, k / nu);
                *h = Some(rays.hours_at(p, g.normal) as f32);
            }
        });
    }
}

/// A window point of an EN 17037-style check: a `[[point]]` of a points file, with the
/// keys of the planning tests' `[[window]]`.
pub use crate::scene::planning::WindowEntry as WindowPoint;

/// Reads `[[point]]` tables (name, position, normal) from TOML; every error names the
/// point and key.
pub fn parse_points(text: &str) -> Result<Vec<WindowPoint>, String> {
    let windows = crate::scene::planning::parse_window_points(text)?;
    Ok(windows.into_iter().map(|w| w.entry).collect())
}

/// An error naming the first point (`point[k].normal`, `point[k].position`) whose normal
/// has no direction or whose position is not finite, or when there is none.
pub fn check_points(points: &[WindowPoint]) -> Result<(), String> {
    for (k, p) in points.iter().enumerate() {
        if crate::geometry::unit(DVec3::from_array(p.normal)).is_none() {
            return Err(format!(
                "point[{k}].normal: {:?} is not a direction",
                p.normal
            ));
        }
        if !DVec3::from_array(p.position).is_finite() {
            return Err(format!("point[{k}].position: not finite"));
        }
    }
    if points.is_empty() {
        return Err("no [[point]]".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::generate::cuboid;

    #[test]
    fn a_box_has_four_facades_facing_the_compass() {
        let m = cuboid(DVec3::ZERO, DVec3::new(4.0, 2.0, 3.0));
        let f = find_facades(&m, 0.5, 0.1);
        assert_eq!(f.len(), 4);
        assert!((f[0].area_m2 - 12.0).abs() < 1e-9 && (f[3].area_m2 - 6.0).abs() < 1e-9);
        let mut az: Vec<f64> = f.iter().map(|f| f.azimuth_deg(0.0).round()).collect();
        az.sort_by(f64::total_cmp);
        assert_eq!(az, [0.0, 90.0, 180.0, 270.0]);
        // The 4 × 3 m facades have 8 × 6 cells, every centre on the facade.
        assert_eq!(f[0].cells, (8, 6));
        assert!(f[0].hours.iter().all(Option::is_some));
        // Cell centres lie in the facade's plane, inside the box's outline.
        let c = f[0].cell_center(0, 0);
        assert!((c.z - 0.25).abs() < 1e-9);
        assert!(c.y.abs() < 1e-9 || (c.y - 2.0).abs() < 1e-9, "{c}");
    }

    #[test]
    fn levels() {
        assert_eq!(en17037_level(4.0), "high");
        assert_eq!(en17037_level(3.5), "medium");
        assert_eq!(en17037_level(1.5), "minimum");
        assert_eq!(en17037_level(1.49), "none");
    }
}
