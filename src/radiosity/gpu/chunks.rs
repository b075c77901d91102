//! The visibility mesh in spatial chunks, so a visibility map draws only what its view
//! can hold.
//!
//! On a GPU with few raster units (an H100 or H200) a map's cost follows the triangles
//! drawn. A hemicube face sees a 90° frustum, yet every face drew the whole mesh: five
//! times the mesh per cell. The triangles are sorted along a Z-order curve of their
//! centres and cut into chunks of consecutive triangles, each with its bounding box; a
//! face draws the runs of chunks whose box is not wholly outside its frustum (a
//! stereographic map: not wholly behind its plane, whose fragments the shader discards
//! anyway), walking a tree of boxes over the chunks from the top: a box wholly outside is
//! skipped, one wholly inside drawn whole. The test is conservative, so every map is the
//! one the whole mesh gives.

use glam::{DVec3, DVec4, Mat4};

/// At most about this many chunks (fewer on small meshes: see [`MIN_CHUNK`]).
const CHUNKS: usize = 512;
/// Fewest triangles in a chunk.
const MIN_CHUNK: usize = 64;
/// Chunks between two drawn runs that are drawn too rather than start another draw.
const GAP_CHUNKS: u32 = 2;
/// Boxes per box one level up (a level's boxes hold this many of the level below).
const FAN: usize = 8;

/// An axis-aligned box (low, high corner).
type Aabb = (DVec3, DVec3);

/// What a visibility map's tile can see.
#[derive(Debug, Clone, Copy)]
pub enum TileView {
    /// A hemicube face: the points whose clip coordinates under this matrix lie in the
    /// clip volume (wgpu's: depth from 0 to w).
    Frustum(Mat4),
    /// A stereographic map: the half-space in front of the plane through `eye` with
    /// normal `normal` (the shader discards every fragment behind it).
    HalfSpace {
        /// The map's eye.
        eye: DVec3,
        /// The map's axis (unit).
        normal: DVec3,
    },
}

/// The chunks of a visibility mesh.
#[derive(Debug, Clone)]
pub struct MeshChunks {
    /// Per chunk, its first index in the (reordered) index buffer and its index count.
    ranges: Vec<(u32, u32)>,
    /// The tree's boxes by level: the chunks' first, then each level's boxes over
    /// [`FAN`] consecutive boxes of the level below, up to one.
    levels: Vec<Vec<Aabb>>,
    /// How far outside a plane a box must lie to be culled, metres (rounding on the GPU).
    margin: f64,
}

impl MeshChunks {
    /// Sorts `triangles` (indices into `positions`) into chunks along the Z-order curve of
    /// their centres, in place, and returns the chunks.
    pub fn new(positions: &[DVec3], triangles: &mut [[u32; 3]]) -> MeshChunks {
        let corner = |t: &[u32; 3], k: usize| positions[t[k] as usize];
        let (lo, hi) = positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        let extent = (hi - lo).max(DVec3::splat(1e-300));
        let key = |t: &[u32; 3]| {
            let centre = (corner(t, 0) + corner(t, 1) + corner(t, 2)) / 3.0;
            let q = ((centre - lo) / extent * 1023.0).clamp(DVec3::ZERO, DVec3::splat(1023.0));
            morton3(q.x as u32, q.y as u32, q.z as u32)
        };
        // Stable: triangles of one key keep their order.
        triangles.sort_by_key(key);
        let size = triangles.len().div_ceil(CHUNKS).max(MIN_CHUNK);
        let mut ranges = Vec::new();
        let mut boxes = Vec::new();
        for (k, chunk) in triangles.chunks(size).enumerate() {
            ranges.push(((3 * k * size) as u32, (3 * chunk.len()) as u32));
            boxes.push(chunk.iter().flatten().fold(
                (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
                |(lo, hi), &i| {
                    let p = positions[i as usize];
                    (lo.min(p), hi.max(p))
                },
            ));
        }
        let mut levels = vec![boxes];
        while levels.last().is_some_and(|l| l.len() > 1) {
            let up = levels[levels.len() - 1]
                .chunks(FAN)
                .map(|g| {
                    g.iter()
                        .fold(g[0], |(lo, hi), &(a, b)| (lo.min(a), hi.max(b)))
                })
                .collect();
            levels.push(up);
        }
        MeshChunks {
            ranges,
            levels,
            margin: 1e-5 * (hi - lo).length().max(1e-300),
        }
    }

    /// The index ranges (first, count) a tile seeing `view` draws, neighbouring chunks
    /// merged into one range; with `cull` false, the whole mesh.
    pub fn visible(&self, view: &TileView, cull: bool, out: &mut Vec<(u32, u32)>) {
        out.clear();
        if self.ranges.is_empty() {
            return;
        }
        if !cull {
            self.push(0..self.ranges.len(), out);
            return;
        }
        let planes = view.planes();
        // Boxes to test: (level, index), from the top.
        let top = self.levels.len() - 1;
        let mut stack = vec![(top, 0usize)];
        while let Some((level, k)) = stack.pop() {
            match self.side(&planes, &self.levels[level][k]) {
                Side::Outside => {}
                Side::Inside => {
                    // Every chunk under it.
                    let span = FAN.pow(level as u32);
                    self.push(k * span..((k + 1) * span).min(self.ranges.len()), out);
                }
                Side::Crossing if level == 0 => self.push(k..k + 1, out),
                Side::Crossing => {
                    let below = self.levels[level - 1].len();
                    // Pushed last first, so the chunks come out in order.
                    for c in (k * FAN..((k + 1) * FAN).min(below)).rev() {
                        stack.push((level - 1, c));
                    }
                }
            }
        }
    }

    /// Where box `b` lies against `planes`.
    fn side(&self, planes: &[DVec4], &(lo, hi): &Aabb) -> Side {
        let mut inside = true;
        for p in planes {
            let n = p.truncate();
            // The corners farthest along the plane's normal and against it.
            let far = DVec3::select(n.cmpge(DVec3::ZERO), hi, lo);
            let near = DVec3::select(n.cmpge(DVec3::ZERO), lo, hi);
            if n.dot(far) + p.w < -self.margin {
                return Side::Outside;
            }
            inside &= n.dot(near) + p.w >= self.margin;
        }
        if inside {
            Side::Inside
        } else {
            Side::Crossing
        }
    }

    /// Appends the index ranges of `chunks`, each merged with the last range where the
    /// gap between them is at most [`GAP_CHUNKS`] chunks (drawing the chunks between is
    /// harmless and saves a draw call: recording the draws cost more on the CPU than the
    /// few triangles more on the GPU).
    fn push(&self, chunks: std::ops::Range<usize>, out: &mut Vec<(u32, u32)>) {
        let gap = GAP_CHUNKS * self.ranges.first().map_or(0, |r| r.1);
        for c in chunks {
            let (start, count) = self.ranges[c];
            match out.last_mut() {
                Some((s, n)) if *s + *n + gap >= start => *n = start + count - *s,
                _ => out.push((start, count)),
            }
        }
    }

    /// How many chunks there are.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    /// Whether the mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }
}

/// Where a box lies against a view's planes.
enum Side {
    /// Wholly outside one plane: nothing in it is seen.
    Outside,
    /// Wholly inside every plane.
    Inside,
    /// Neither.
    Crossing,
}

impl TileView {
    /// The planes (unit normal, offset: inside where n · p + w ≥ 0) bounding what it sees.
    fn planes(&self) -> Vec<DVec4> {
        match *self {
            TileView::HalfSpace { eye, normal } => vec![normal.extend(-normal.dot(eye))],
            TileView::Frustum(m) => {
                let m = m.as_dmat4();
                let [r0, r1, r2, r3] = [0, 1, 2, 3].map(|k| m.row(k));
                // Gribb and Hartmann: −w ≤ x, y ≤ w and 0 ≤ z ≤ w in clip space.
                [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2]
                    .into_iter()
                    .map(|p| p / p.truncate().length().max(1e-300))
                    .collect()
            }
        }
    }
}

/// The Z-order (Morton) code of a point's three 10-bit coordinates.
fn morton3(x: u32, y: u32, z: u32) -> u32 {
    fn spread(v: u32) -> u32 {
        let mut v = v & 0x3ff;
        v = (v | (v << 16)) & 0x030000ff;
        v = (v | (v << 8)) & 0x0300f00f;
        v = (v | (v << 4)) & 0x030c30c3;
        (v | (v << 2)) & 0x09249249
    }
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;

    /// A grid of small triangles over the cube [−5, 5]³.
    fn cloud() -> (Vec<DVec3>, Vec<[u32; 3]>) {
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for i in 0..40 {
            for j in 0..40 {
                for k in 0..40 {
                    let c = DVec3::new(i as f64, j as f64, k as f64) * 0.25 - DVec3::splat(5.0);
                    let n = positions.len() as u32;
                    positions.extend([c, c + DVec3::X * 0.1, c + DVec3::Y * 0.1]);
                    triangles.push([n, n + 1, n + 2]);
                }
            }
        }
        (positions, triangles)
    }

    /// The triangles a view draws, by their corners.
    fn drawn(triangles: &[[u32; 3]], ranges: &[(u32, u32)]) -> HashSet<[u32; 3]> {
        ranges
            .iter()
            .flat_map(|&(s, n)| &triangles[(s / 3) as usize..((s + n) / 3) as usize])
            .copied()
            .collect()
    }

    /// Whether triangle `t` is not wholly outside any one of the view's planes (what the
    /// GPU may draw a fragment of).
    fn touches(view: &TileView, positions: &[DVec3], t: &[u32; 3]) -> bool {
        view.planes().iter().all(|q| {
            t.iter()
                .any(|&i| q.truncate().dot(positions[i as usize]) + q.w >= 0.0)
        })
    }

    #[test]
    fn a_view_draws_every_triangle_it_can_see_and_far_fewer_than_all() {
        let (positions, mut triangles) = cloud();
        let mut sorted: Vec<[u32; 3]> = triangles.clone();
        let chunks = MeshChunks::new(&positions, &mut triangles);
        // The same triangles, reordered.
        let mut again = triangles.clone();
        sorted.sort_unstable();
        again.sort_unstable();
        assert_eq!(sorted, again);
        assert!(chunks.len() > 4);
        let eye = glam::Vec3::new(0.2, 0.1, 0.3);
        let projection = Mat4::perspective_rh(std::f32::consts::FRAC_PI_2, 1.0, 0.01, 100.0);
        let views = [
            TileView::Frustum(projection * Mat4::look_to_rh(eye, glam::Vec3::X, glam::Vec3::Z)),
            TileView::Frustum(projection * Mat4::look_to_rh(eye, -glam::Vec3::Z, glam::Vec3::X)),
            TileView::HalfSpace {
                eye: eye.as_dvec3(),
                normal: DVec3::new(1.0, 1.0, 0.0).normalize(),
            },
        ];
        let mut ranges = Vec::new();
        // A 90° frustum holds a sixth of the directions, a half-space half; chunks of
        // 2 × 2 × 1 m along its sides take about as much again.
        for (view, limit) in views.iter().zip([5, 5, 7]) {
            chunks.visible(view, true, &mut ranges);
            let seen = drawn(&triangles, &ranges);
            for t in &triangles {
                if touches(view, &positions, t) {
                    assert!(
                        seen.contains(t),
                        "{view:?}: a triangle it sees is not drawn"
                    );
                }
            }
            assert!(
                seen.len() * 10 < triangles.len() * limit,
                "{view:?}: {} of {}",
                seen.len(),
                triangles.len()
            );
            chunks.visible(view, false, &mut ranges);
            assert_eq!(
                ranges,
                vec![(0, 3 * triangles.len() as u32)],
                "no culling: all"
            );
        }
    }
}
