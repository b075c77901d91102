//! The visibility mesh in spatial chunks, so a visibility map draws only what its face can
//! see: triangles sorted along a Morton curve of their centroids, cut into runs of
//! [`CHUNK`] triangles, each with its box. A hemicube face is a 90° view, so most of a
//! large interior lies outside it or behind the shooting patch's plane (which nothing in
//! front of the patch can be hidden by).

use std::ops::Range;

use glam::{DMat4, DVec3, DVec4};

use crate::geometry::Mesh;

/// Triangles per chunk.
pub const CHUNK: usize = 512;

/// The mesh's vertices and its triangles' indices in chunk order, and each chunk's box.
pub struct ChunkedMesh {
    /// Vertex positions, as given.
    pub positions: Vec<[f32; 3]>,
    /// Three vertex indices per triangle, chunk after chunk.
    pub indices: Vec<u32>,
    /// Per chunk, the lowest and highest corner of its triangles.
    boxes: Vec<(DVec3, DVec3)>,
}

/// Interleaves the low 21 bits of `v` with two zero bits between each.
fn spread_bits(v: u64) -> u64 {
    let mut x = v & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    (x | x << 2) & 0x1249_2492_4924_9249
}

impl ChunkedMesh {
    /// Sorts `mesh`'s triangles into chunks.
    pub fn new(mesh: &Mesh) -> ChunkedMesh {
        let corner = |t: &[u32; 3], i: usize| mesh.positions[t[i] as usize];
        let centroid = |t: &[u32; 3]| (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
        let (lo, hi) = mesh
            .triangles
            .iter()
            .map(centroid)
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), c| {
                (lo.min(c), hi.max(c))
            });
        let scale = (hi - lo).max_element().max(1e-300);
        let key = |t: &[u32; 3]| {
            let q = ((centroid(t) - lo) / scale * f64::from((1u32 << 21) - 1)).as_u64vec3();
            spread_bits(q.x) | spread_bits(q.y) << 1 | spread_bits(q.z) << 2
        };
        let mut order: Vec<(u64, usize)> = mesh
            .triangles
            .iter()
            .enumerate()
            .map(|(i, t)| (key(t), i))
            .collect();
        order.sort_unstable();
        let sorted: Vec<[u32; 3]> = order.iter().map(|&(_, i)| mesh.triangles[i]).collect();
        let boxes = sorted
            .chunks(CHUNK)
            .map(|chunk| {
                chunk
                    .iter()
                    .flat_map(|t| (0..3).map(|i| corner(t, i)))
                    .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                        (lo.min(p), hi.max(p))
                    })
            })
            .collect();
        ChunkedMesh {
            positions: mesh
                .positions
                .iter()
                .map(|p| p.as_vec3().to_array())
                .collect(),
            indices: sorted.iter().flatten().copied().collect(),
            boxes,
        }
    }

    /// Index ranges to draw for a view through `view_proj` (clip depth 0..1; `None`: the
    /// whole front half-space, as the stereographic map sees it) from a patch whose plane
    /// passes through `at` facing `normal`: the chunks not wholly outside the view or
    /// wholly more than `behind` metres behind the plane, neighbours merged.
    pub fn visible(
        &self,
        view_proj: Option<&DMat4>,
        at: DVec3,
        normal: DVec3,
        behind: f64,
    ) -> Vec<Range<u32>> {
        let mut ranges: Vec<Range<u32>> = Vec::new();
        let triangles = self.indices.len() / 3;
        for (k, &(lo, hi)) in self.boxes.iter().enumerate() {
            if !in_front(lo, hi, at, normal, behind)
                || view_proj.is_some_and(|m| outside_view(lo, hi, m))
            {
                continue;
            }
            let first = (3 * k * CHUNK) as u32;
            let end = (3 * ((k + 1) * CHUNK).min(triangles)) as u32;
            match ranges.last_mut() {
                Some(r) if r.end == first => r.end = end,
                _ => ranges.push(first..end),
            }
        }
        ranges
    }
}

/// The eight corners of the box [lo, hi].
fn corners(lo: DVec3, hi: DVec3) -> impl Iterator<Item = DVec3> {
    (0..8).map(move |i| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Whether some corner of the box lies less than `behind` behind the plane.
fn in_front(lo: DVec3, hi: DVec3, at: DVec3, normal: DVec3, behind: f64) -> bool {
    corners(lo, hi).any(|x| normal.dot(x - at) > -behind)
}

/// Whether every corner of the box is outside one plane of the view's clip volume
/// (−w ≤ x, y ≤ w, 0 ≤ z ≤ w): then nothing in it is drawn.
fn outside_view(lo: DVec3, hi: DVec3, view_proj: &DMat4) -> bool {
    let clip: Vec<DVec4> = corners(lo, hi)
        .map(|p| *view_proj * p.extend(1.0))
        .collect();
    let all = |f: &dyn Fn(&DVec4) -> bool| clip.iter().all(f);
    all(&|c| c.x < -c.w)
        || all(&|c| c.x > c.w)
        || all(&|c| c.y < -c.w)
        || all(&|c| c.y > c.w)
        || all(&|c| c.z < 0.0)
        || all(&|c| c.z > c.w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A grid of small triangles over the cube [−5, 5]³'s six faces.
    fn room() -> Mesh {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for axis in 0..3 {
            for side in [-5.0, 5.0] {
                for i in 0..100 {
                    for j in 0..100 {
                        let mut p = [0.0; 3];
                        p[axis] = side;
                        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                        let n = positions.len() as u32;
                        for (di, dj) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)] {
                            p[u] = -5.0 + 0.1 * (i as f64 + di);
                            p[v] = -5.0 + 0.1 * (j as f64 + dj);
                            positions.push(DVec3::from_array(p));
                        }
                        triangles.push([n, n + 1, n + 2]);
                    }
                }
            }
        }
        Mesh {
            positions,
            triangles,
        }
    }

    #[test]
    fn chunks_keep_every_triangle_once() {
        let mesh = room();
        let chunked = ChunkedMesh::new(&mesh);
        let mut got: Vec<[u32; 3]> = chunked
            .indices
            .chunks(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        let mut want = mesh.triangles.clone();
        got.sort_unstable();
        want.sort_unstable();
        assert_eq!(got, want);
    }

    #[test]
    fn a_face_draws_every_triangle_it_sees_and_far_fewer_in_all() {
        let mesh = room();
        let chunked = ChunkedMesh::new(&mesh);
        // A hemicube on the floor: up, and the four sides (their lower halves behind it).
        let eye = DVec3::new(1.0, -2.0, -5.0 + 1e-6);
        let projection = DMat4::perspective_rh(std::f64::consts::FRAC_PI_2, 1.0, 1e-3, 40.0);
        let looks = [
            (DVec3::Z, DVec3::X),
            (DVec3::X, DVec3::Z),
            (-DVec3::X, DVec3::Z),
            (DVec3::Y, DVec3::Z),
            (-DVec3::Y, DVec3::Z),
        ];
        let all = chunked.indices.len() / 3;
        let mut total = 0;
        for (dir, up) in looks {
            let m = projection * DMat4::look_to_rh(eye, dir, up);
            let ranges = chunked.visible(Some(&m), eye, DVec3::Z, 1e-4);
            total += ranges.iter().map(|r| r.len() / 3).sum::<usize>();
            let in_ranges = |t: usize| ranges.iter().any(|r| r.contains(&(3 * t as u32)));
            // Every triangle with a corner inside the view and in front is drawn.
            for (t, tri) in chunked.indices.chunks(3).enumerate() {
                let seen = tri.iter().any(|&i| {
                    let p = mesh.positions[i as usize];
                    let c = m * p.extend(1.0);
                    c.w > 0.0
                        && c.x.abs() <= c.w
                        && c.y.abs() <= c.w
                        && (0.0..=c.w).contains(&c.z)
                        && (p - eye).z > -1e-4
                });
                assert!(
                    !seen || in_ranges(t),
                    "{dir}: triangle {t} seen but not drawn"
                );
            }
        }
        // Five faces draw well under five times the mesh (the whole of it for each before).
        assert!(
            total < 3 * all,
            "{total} triangles drawn for five faces of {all}"
        );
        // The stereographic map sees the front half-space: from a patch in the middle of
        // the room facing up, the floor is culled, the ceiling drawn.
        let ranges = chunked.visible(None, DVec3::ZERO, DVec3::Z, 1e-4);
        let drawn: usize = ranges.iter().map(|r| r.len() / 3).sum();
        let all = chunked.indices.len() / 3;
        assert!(drawn < all && drawn >= all / 6, "{drawn} of {all}");
        for (t, tri) in chunked.indices.chunks(3).enumerate() {
            let ceiling = tri.iter().all(|&i| mesh.positions[i as usize].z == 5.0);
            let drawn = ranges.iter().any(|r| r.contains(&(3 * t as u32)));
            assert!(!ceiling || drawn, "ceiling triangle {t} culled");
        }
    }
}
