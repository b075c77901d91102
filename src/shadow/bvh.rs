//! Ray casts against a triangle mesh through a bounding volume hierarchy: the fast path of
//! every CPU ray cast (exact shadows at points, the radiosity gather, the CPU radiosity
//! solver). The hierarchy is obvhs's binary BVH (PLOC build, reinsertion, leaves of up to 8
//! triangles) over f32 boxes; it only culls. Its traversal stack is sized to the tree's
//! measured depth: obvhs's wide BVH has a fixed 32-entry stack that silently drops nodes
//! when a tree is deeper (the 400 k-triangle high-rise block builds one 252 levels deep),
//! and its own depth bookkeeping goes stale after reinsertion. Every candidate triangle is intersected in f64 by
//! the same Möller–Trumbore test as the brute-force loop in [`super::raycast`], which stays
//! as the oracle: answers are the brute force's, hit for hit and distance for distance.
//!
//! f32 boxes could cull a triangle an f64 ray touches, so the hierarchy is built around the
//! scene's centre, each triangle's box is widened by [`TriangleBvh::pad`], and every ray is
//! first clipped to the scene's f64 bounds: its f32 origin and length are never far outside
//! the scene and their rounding stays well inside the pad.

use glam::DVec3;
use glam_bvh::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::bvh2::leaf_collapser::collapse;
use obvhs::bvh2::reinsertion::ReinsertionOptimizer;
use obvhs::bvh2::Bvh2;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};
use obvhs::ray::Ray;
use obvhs::Boundable;

use super::raycast::ray_triangle;
use super::{Cutouts, IgnoredTriangles, Light};
use crate::geometry::Mesh;

/// Relative widening of each triangle's box (of the scene's size, plus 1 m · this): f32
/// rounding of a point inside the scene is below 1e-7 of its size.
const RELATIVE_PAD: f64 = 1e-5;

/// A triangle mesh's triangles in hierarchy order, with the hierarchy.
#[derive(Clone)]
pub struct TriangleBvh {
    /// The hierarchy (absent for a mesh without triangles).
    bvh: Option<Bvh2>,
    /// Corners of each leaf primitive, in the hierarchy's primitive order.
    corners: Vec<[DVec3; 3]>,
    /// The mesh's triangle index of each leaf primitive.
    ids: Vec<u32>,
    /// Scene bounds, widened by the pad.
    bounds: (DVec3, DVec3),
    /// The f32 hierarchy's origin (the scene's centre), so f32 coordinates stay as small
    /// as the scene however far it lies from the world origin.
    centre: DVec3,
    /// How far each box is widened, metres.
    pad: f64,
    /// Holes in the mesh's alpha-masked triangles (rays pass through them).
    cutouts: Option<std::sync::Arc<Cutouts>>,
}

/// The number of levels of `bvh` (1 for a lone leaf), without recursion.
fn tree_depth(bvh: &Bvh2) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(0usize, 1usize)];
    while let Some((k, depth)) = stack.pop() {
        let Some(node) = bvh.nodes.get(k) else {
            continue;
        };
        deepest = deepest.max(depth);
        if !node.is_leaf() {
            let first = node.first_index as usize;
            stack.push((first, depth + 1));
            stack.push((first + 1, depth + 1));
        }
    }
    deepest
}

impl std::fmt::Debug for TriangleBvh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TriangleBvh")
            .field("triangles", &self.corners.len())
            .field("depth", &self.bvh.as_ref().map(|b| b.max_depth))
            .field("pad", &self.pad)
            .finish()
    }
}

/// One triangle's widened box, as obvhs wants it.
struct PaddedBox(Aabb);

impl Boundable for PaddedBox {
    fn aabb(&self) -> Aabb {
        self.0
    }
}

fn to_f32(v: DVec3) -> Vec3A {
    Vec3A::new(v.x as f32, v.y as f32, v.z as f32)
}

impl TriangleBvh {
    /// Builds the hierarchy over `mesh`'s triangles (degenerate ones included: they are
    /// never hit, as in the brute-force loop).
    pub fn new(mesh: &Mesh) -> TriangleBvh {
        let corners_of = |t: &[u32; 3]| t.map(|i| mesh.positions[i as usize]);
        let Some((lo, hi)) = mesh.bounds() else {
            return TriangleBvh {
                bvh: None,
                corners: Vec::new(),
                ids: Vec::new(),
                bounds: (DVec3::ZERO, DVec3::ZERO),
                centre: DVec3::ZERO,
                pad: 0.0,
                cutouts: None,
            };
        };
        let pad = RELATIVE_PAD * (1.0 + (hi - lo).length());
        let centre = (lo + hi) * 0.5;
        let boxes: Vec<PaddedBox> = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = corners_of(t);
                let (min, max) = (a.min(b).min(c) - pad, a.max(b).max(c) + pad);
                PaddedBox(Aabb::new(to_f32(min - centre), to_f32(max - centre)))
            })
            .collect();
        let mut bvh = PlocBuilder::with_capacity(boxes.len()).build(
            PlocSearchDistance::Medium,
            &boxes,
            (0..boxes.len() as u32).collect(),
            SortPrecision::U64,
            3,
        );
        ReinsertionOptimizer::default().run(&mut bvh, 0.05, None);
        collapse(&mut bvh, 8, 3.0);
        // The traversal stack holds at most one node per level (plus the root).
        bvh.max_depth = tree_depth(&bvh) + 1;
        let ids = bvh.primitive_indices.clone();
        let corners = ids
            .iter()
            .map(|&k| corners_of(&mesh.triangles[k as usize]))
            .collect();
        TriangleBvh {
            bvh: Some(bvh),
            corners,
            ids,
            bounds: (lo - pad, hi + pad),
            centre,
            pad,
            cutouts: None,
        }
    }

    /// This hierarchy with holes where `cutouts` (of the same mesh) has them; nothing
    /// changes when it is `None` or has no masked triangle.
    pub fn with_cutouts(mut self, cutouts: Option<std::sync::Arc<Cutouts>>) -> TriangleBvh {
        self.cutouts = cutouts.filter(|c| !c.is_empty());
        self
    }

    /// The distance along the ray to the primitive in `slot`, where it hits it outside
    /// a hole.
    fn hit(&self, o: DVec3, dir: DVec3, slot: usize, tmin: f64, tmax: f64) -> Option<f64> {
        let corners = self.corners[slot];
        let d = ray_triangle(o, dir, corners, tmin, tmax)?;
        let k = self.ids[slot] as usize;
        let through = self
            .cutouts
            .as_ref()
            .is_some_and(|c| c.passes(k, corners, o + dir * d));
        (!through).then_some(d)
    }

    /// How many triangles it holds.
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    /// Whether it holds no triangle.
    pub fn is_empty(&self) -> bool {
        self.corners.is_empty()
    }

    /// How far each triangle's f32 box is widened beyond the triangle, metres.
    pub fn pad(&self) -> f64 {
        self.pad
    }

    /// The part of the ray `o + t · dir`, t in (tmin, tmax), inside the scene's bounds,
    /// as the f32 ray obvhs traverses (origin moved to the entry point) and the entry
    /// distance to add back; `None` where the ray misses the bounds.
    fn clipped_ray(&self, o: DVec3, dir: DVec3, tmin: f64, tmax: f64) -> Option<(Ray, f64)> {
        if dir == DVec3::ZERO {
            return None;
        }
        let (lo, hi) = self.bounds;
        let (mut enter, mut leave) = (tmin, tmax);
        for axis in 0..3 {
            let (oa, da) = (o[axis], dir[axis]);
            if da == 0.0 {
                if oa < lo[axis] || oa > hi[axis] {
                    return None;
                }
                continue;
            }
            let (t0, t1) = ((lo[axis] - oa) / da, (hi[axis] - oa) / da);
            enter = enter.max(t0.min(t1));
            leave = leave.min(t0.max(t1));
        }
        if enter.partial_cmp(&leave).is_none_or(|o| o.is_gt()) {
            return None;
        }
        // Start a pad's worth of travel before the entry so rounding never starts the f32
        // ray past a triangle the f64 ray reaches.
        let slack = self.pad / dir.length();
        let start = enter - slack;
        let length = (leave - start + slack) as f32;
        // obvhs reads a direction's signs with `< 0.0` but inverts -0.0 to a negative
        // number: a -0.0 component (e.g. of -Z) would make it miss every box.
        let dir32 = to_f32(dir) + Vec3A::ZERO;
        let ray = Ray::new(to_f32(o + dir * start - self.centre), dir32, 0.0, length);
        Some((ray, start))
    }

    /// The nearest triangle hit by the ray from `o` along `dir` beyond `tmin`: (distance in
    /// units of `dir`, triangle index in the mesh); of several at the same distance, the
    /// lowest index, as [`super::raycast::first_hit`].
    pub fn first_hit(&self, o: DVec3, dir: DVec3, tmin: f64) -> Option<(f64, usize)> {
        let bvh = self.bvh.as_ref()?;
        let (ray, start) = self.clipped_ray(o, dir, tmin, f64::INFINITY)?;
        let mut best: Option<(f64, u32)> = None;
        let mut hit = obvhs::ray::RayHit::none();
        bvh.ray_traverse(ray, &mut hit, |_, slot| {
            let Some(d) = self.hit(o, dir, slot, tmin, f64::INFINITY) else {
                return f32::INFINITY;
            };
            let k = self.ids[slot];
            if best.is_none_or(|(bd, bk)| d < bd || (d == bd && k < bk)) {
                best = Some((d, k));
            }
            // Keep traversing up to (just past) the best distance, so equal distances
            // further down the tree are still seen.
            let bd = best.map_or(d, |b| b.0);
            ((bd - start) as f32 + self.pad as f32).max(0.0)
        });
        best.map(|(d, k)| (d, k as usize))
    }

    /// Whether any triangle not in `ignored` crosses the ray from `o` along `dir` within
    /// (tmin, tmax).
    pub fn blocked(
        &self,
        o: DVec3,
        dir: DVec3,
        tmin: f64,
        tmax: f64,
        ignored: &IgnoredTriangles,
    ) -> bool {
        let Some(bvh) = self.bvh.as_ref() else {
            return false;
        };
        let Some((ray, _)) = self.clipped_ray(o, dir, tmin, tmax) else {
            return false;
        };
        !bvh.ray_traverse_miss(ray, |_, slot| {
            let hit = self.hit(o, dir, slot, tmin, tmax).is_some()
                && !ignored.contains(self.ids[slot] as usize);
            if hit {
                0.0
            } else {
                f32::INFINITY
            }
        })
    }

    /// Whether `p` is in shadow of `light`, leaving out `ignored`: the same answer as
    /// [`super::raycast::in_shadow_ignoring`] on the mesh this was built from.
    pub fn in_shadow(&self, light: &Light, p: DVec3, eps: f64, ignored: &IgnoredTriangles) -> bool {
        let (dir, tmax) = super::raycast::shadow_ray(light, p, eps);
        self.blocked(p, dir, eps, tmax, ignored)
    }
}
