//! Exact simplification of a triangle mesh for visibility: two triangles sharing an edge
//! whose union is a triangle — one of the shared corners lies on the segment between the
//! two far corners, as between neighbouring strips of a CAD exporter's fan — become that
//! triangle, repeatedly, so a face fanned into 350 strips is drawn as one triangle. The
//! covered point set does not change (up to `tolerance`); vertices are never moved.
//! The GPU radiosity solver draws its visibility maps from this mesh.

use glam::DVec3;
use rustc_hash::FxHashMap;

use super::Mesh;

type EdgeKey = (u32, u32);

fn key(a: u32, b: u32) -> EdgeKey {
    (a.min(b), a.max(b))
}

fn edges(t: [u32; 3]) -> [EdgeKey; 3] {
    [key(t[0], t[1]), key(t[1], t[2]), key(t[2], t[0])]
}

/// The triangles on an edge. Only an edge of exactly two can be merged across, so it keeps
/// two and marks itself crowded once it ever had more (never merged across after that:
/// conservative, and no list per edge to allocate).
#[derive(Debug, Clone, Copy, Default)]
struct EdgeUse {
    triangles: [u32; 2],
    count: u32,
    crowded: bool,
}

impl EdgeUse {
    fn add(&mut self, t: u32) {
        if self.count < 2 {
            self.triangles[self.count as usize] = t;
        } else {
            self.crowded = true;
        }
        self.count += 1;
    }

    fn remove(&mut self, t: u32) {
        if !self.crowded {
            match self.triangles[..self.count as usize]
                .iter()
                .position(|&x| x == t)
            {
                Some(0) => self.triangles[0] = self.triangles[1],
                Some(_) => {}
                None => return,
            }
        }
        self.count -= 1;
    }

    /// The two triangles on the edge, when there are exactly two.
    fn pair(&self) -> Option<(u32, u32)> {
        (self.count == 2 && !self.crowded).then_some((self.triangles[0], self.triangles[1]))
    }
}

/// `mesh` with every pair of adjacent triangles whose union is a triangle merged, until
/// none is left. `tolerance` (metres): how far the shared corner may lie off the segment.
/// Vertices at exactly the same position are one vertex.
pub fn merge_strips(mesh: &Mesh, tolerance: f64) -> Mesh {
    merge_strips_within(mesh, &[], tolerance).mesh
}

/// A merged mesh and where its triangles came from.
#[derive(Debug, Clone)]
pub struct Merged {
    /// The merged mesh, its triangles ordered by [`Merged::origin`].
    pub mesh: Mesh,
    /// Per merged triangle, the lowest-numbered source triangle in it.
    pub origin: Vec<u32>,
}

/// [`merge_strips`] merging only triangles of the same `group` (per source triangle; empty:
/// one group), e.g. the scene's objects, so a light that leaves out its own housing can
/// still leave out exactly its triangles.
pub fn merge_strips_within(mesh: &Mesh, group: &[u32], tolerance: f64) -> Merged {
    let same_group = |a: u32, b: u32| group.is_empty() || group[a as usize] == group[b as usize];
    let welded = weld_exact(mesh);
    let p = &welded.positions;
    let mut triangles = welded.triangles.clone();
    let mut alive = vec![true; triangles.len()];
    let mut origin: Vec<u32> = (0..triangles.len() as u32).collect();
    let mut by_edge: FxHashMap<EdgeKey, EdgeUse> = FxHashMap::default();
    by_edge.reserve(triangles.len() * 3 / 2);
    for (t, tri) in triangles.iter().enumerate() {
        for e in edges(*tri) {
            by_edge.entry(e).or_default().add(t as u32);
        }
    }
    let normal = |t: [u32; 3]| {
        let [a, b, c] = t.map(|i| p[i as usize]);
        (b - a).cross(c - a)
    };
    // Whether `v` lies strictly inside the segment b–d, within the tolerance.
    let between = |v: DVec3, b: DVec3, d: DVec3| {
        let bd = d - b;
        let len2 = bd.length_squared();
        if len2 <= 0.0 {
            return false;
        }
        let s = (v - b).dot(bd) / len2;
        s > 0.0 && s < 1.0 && (b + bd * s).distance(v) <= tolerance
    };
    let mut work: Vec<EdgeKey> = by_edge.keys().copied().collect();
    while let Some(e) = work.pop() {
        let Some((t1, t2)) = by_edge.get(&e).and_then(EdgeUse::pair) else {
            continue;
        };
        if !same_group(t1, t2) {
            continue;
        }
        let (a, b) = (triangles[t1 as usize], triangles[t2 as usize]);
        let far = |t: [u32; 3]| t.into_iter().find(|&v| v != e.0 && v != e.1);
        let (Some(f1), Some(f2)) = (far(a), far(b)) else {
            continue;
        };
        if normal(a).dot(normal(b)) <= 0.0 {
            continue;
        }
        let Some(shared) = [e.0, e.1]
            .into_iter()
            .find(|&v| between(p[v as usize], p[f1 as usize], p[f2 as usize]))
        else {
            continue;
        };
        let merged = a.map(|v| if v == shared { f2 } else { v });
        if normal(merged).dot(normal(a)) <= 0.0 {
            continue;
        }
        for (t, tri) in [(t1, a), (t2, b)] {
            for k in edges(tri) {
                if let Some(l) = by_edge.get_mut(&k) {
                    l.remove(t);
                }
            }
        }
        alive[t2 as usize] = false;
        triangles[t1 as usize] = merged;
        origin[t1 as usize] = origin[t1 as usize].min(origin[t2 as usize]);
        for k in edges(merged) {
            by_edge.entry(k).or_default().add(t1);
            work.push(k);
        }
    }
    let mut kept: Vec<(u32, [u32; 3])> = (0..triangles.len())
        .filter(|&t| alive[t])
        .map(|t| (origin[t], triangles[t]))
        .collect();
    kept.sort_unstable_by_key(|k| k.0);
    Merged {
        mesh: Mesh {
            positions: welded.positions,
            triangles: kept.iter().map(|k| k.1).collect(),
        },
        origin: kept.iter().map(|k| k.0).collect(),
    }
}

/// `mesh` with vertices at bit-identical positions merged (linear time; the tolerant
/// [`super::weld::weld`] sweeps along x and is quadratic where many vertices share an x,
/// as the corners of a CAD fan along an edge do).
fn weld_exact(mesh: &Mesh) -> Mesh {
    let mut index: FxHashMap<[u64; 3], u32> = FxHashMap::default();
    index.reserve(mesh.positions.len());
    let mut positions = Vec::new();
    let map: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            // +0.0 so that -0.0 and 0.0 are one position.
            let key = (*p + DVec3::ZERO).to_array().map(f64::to_bits);
            *index.entry(key).or_insert_with(|| {
                positions.push(*p);
                positions.len() as u32 - 1
            })
        })
        .collect();
    Mesh {
        positions,
        triangles: mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| map[i as usize]))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::generate::{cuboid, fan_split};

    fn area(m: &Mesh) -> f64 {
        (0..m.triangles.len())
            .map(|t| m.face_normal(t).length() / 2.0)
            .sum()
    }

    /// Whether `q` lies on a triangle of `m` (within `tol` of its plane, inside its edges).
    fn covers(m: &Mesh, q: DVec3, tol: f64) -> bool {
        m.triangles.iter().any(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            let len = n.length();
            if len == 0.0 || (q - a).dot(n / len).abs() > tol {
                return false;
            }
            [(a, b), (b, c), (c, a)]
                .iter()
                .all(|&(u, v)| (v - u).cross(q - u).dot(n) >= -tol * len)
        })
    }

    #[test]
    fn an_edge_of_three_triangles_is_never_merged_across() {
        // Two strips of a fan (their union is the triangle a, b, c) and a fin standing on
        // their shared edge: merging the strips would leave the fin on an edge that no
        // longer exists, so nothing merges; without the fin they do.
        let (a, b, c, m) = (
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        );
        let fin = DVec3::new(0.5, 0.5, 1.0);
        let mesh = |with_fin: bool| {
            let mut triangles = vec![[0, 1, 3], [0, 3, 2]];
            if with_fin {
                triangles.push([0, 3, 4]);
            }
            Mesh {
                positions: vec![a, b, c, m, fin],
                triangles,
            }
        };
        assert_eq!(merge_strips(&mesh(false), 1e-9).triangles.len(), 1);
        assert_eq!(merge_strips(&mesh(true), 1e-9).triangles.len(), 3);
    }

    #[test]
    fn fanned_faces_merge_back_and_cover_the_same_surface() {
        let coarse = cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 0.5));
        let fine = fan_split(&coarse, 50);
        let merged = merge_strips(&fine, 1e-9);
        assert_eq!(fine.triangles.len(), 600);
        assert_eq!(merged.triangles.len(), coarse.triangles.len());
        assert!((area(&merged) - area(&fine)).abs() < 1e-9);
        // Same point set: points spread over each mesh's triangles lie on the other.
        for (from, to) in [(&fine, &merged), (&merged, &fine)] {
            for (k, t) in from.triangles.iter().enumerate() {
                let [a, b, c] = t.map(|i| from.positions[i as usize]);
                for (u, v) in [(0.2, 0.3), (0.6, 0.1), (0.1, 0.8), (0.34, 0.33)] {
                    let q = a + (b - a) * u + (c - a) * v;
                    assert!(covers(to, q, 1e-9), "triangle {k}: {q}");
                }
            }
        }
        // Orientation is kept: the normals still point out of the box.
        let centre = DVec3::new(1.0, 0.5, 0.25);
        for t in 0..merged.triangles.len() {
            let a = merged.positions[merged.triangles[t][0] as usize];
            assert!(merged.face_normal(t).dot(a - centre) > 0.0);
        }
    }

    #[test]
    fn triangles_whose_union_is_no_triangle_stay() {
        // A square as two triangles, and a bent pair: nothing to merge.
        let square = Mesh {
            positions: vec![
                DVec3::ZERO,
                DVec3::X,
                DVec3::new(1.0, 1.0, 0.0),
                DVec3::Y,
                DVec3::new(0.5, 0.5, 1.0),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3], [0, 1, 4]],
        };
        assert_eq!(merge_strips(&square, 1e-9).triangles.len(), 3);
        // A strip pair whose middle corner lies 1 mm off the line merges only with a
        // tolerance above 1 mm.
        let bent = Mesh {
            positions: vec![
                DVec3::new(0.0, 1.0, 0.0),
                DVec3::ZERO,
                DVec3::new(0.5, -0.001, 0.0),
                DVec3::X,
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        assert_eq!(merge_strips(&bent, 1e-4).triangles.len(), 2);
        assert_eq!(merge_strips(&bent, 2e-3).triangles.len(), 1);
    }

    #[test]
    fn groups_never_merge_and_origins_name_their_first_source() {
        let coarse = cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 0.5));
        let fine = fan_split(&coarse, 10);
        // Every strip its own group: nothing merges.
        let apart: Vec<u32> = (0..fine.triangles.len() as u32).collect();
        assert_eq!(
            merge_strips_within(&fine, &apart, 1e-9)
                .mesh
                .triangles
                .len(),
            120
        );
        // Each coarse triangle's fan one group: one triangle each, from its first strip.
        let fans: Vec<u32> = (0..fine.triangles.len() as u32).map(|t| t / 10).collect();
        let m = merge_strips_within(&fine, &fans, 1e-9);
        assert_eq!(m.origin, (0..12).map(|k| 10 * k).collect::<Vec<u32>>());
    }
}
