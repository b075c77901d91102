//! Patch refinement for badly shaped triangles (Edström §4.4.2–4.4.3), used where the
//! exported scene draws a surface with vertex lighting and the light map is finer than
//! its triangles.
//!
//! Regular refinement (each side cut into `n`, `n²` parts) keeps a triangle's shape: a
//! CAD strip 10 m long and 5 cm wide under 10 cm texels becomes 10 000 strips as thin as
//! itself, and its light is still sampled only along two lines. Edström's BSP refinement
//! splits a patch (a convex polygon) by the line perpendicular to the longest side of its
//! minimum-area enclosing rectangle, through the rectangle's middle; each end of that line
//! moves to the nearest vertex on its side of the boundary when one lies within a snap
//! tolerance, so the pieces meet at existing vertices and few t-vertices arise. Patches are
//! split, largest first, until the long side of each one's rectangle is at most the
//! requested size: the strip above becomes 128 patches and 256 triangles. Of two
//! minimum-area rectangles (a right triangle has one along its legs and one along its
//! hypotenuse) the split crosses the longer, so a right isosceles triangle splits through
//! its right angle into two like it. A well-shaped triangle is already as good as
//! patches get under regular refinement, which then draws fewer triangles (a 3-4-5 m
//! triangle under 25 cm: 400 against 527): each triangle takes the refinement
//! that draws fewer ([`refine_triangle`]).
//!
//! T-vertices (a split's end on a neighbour's side) are never left: every patch carries
//! every point that lies on its boundary — those of its neighbours' splits inside the
//! triangle, and those the neighbouring triangles of the same surface put on a shared edge
//! ([`refine_surface`]) — and each patch is triangulated with all of them (ear clipping
//! that keeps the best smallest angle; a convex patch with `m` boundary points gives
//! `m − 2` triangles), so the mesh is conforming and a vertex colour interpolates without
//! cracks.

use std::collections::BinaryHeap;

use glam::{DVec2, DVec3};
use rustc_hash::FxHashMap;

use super::clusters::obb::enclosing_rectangles;
use crate::geometry::Mesh;

/// How far the ends of a splitting line move to meet a vertex, as a share of the patch's
/// long side (each piece keeps at least 3/8 of it).
pub const SNAP_TOLERANCE: f64 = 0.125;

/// The most patches one triangle is refined into (a guard; the callers' sizes stay far
/// below it).
const MAX_PATCHES: usize = 1 << 16;

/// One triangle refined: points in the triangle's plane and its leaf patches.
#[derive(Debug, Clone, PartialEq)]
pub struct Patches {
    /// The points, metres in the plane; the first three are the triangle's corners.
    pub points: Vec<DVec2>,
    /// The leaf patches: convex polygons, counter-clockwise, as indices into `points`,
    /// with every point that lies on their boundary.
    pub leaves: Vec<Vec<u32>>,
}

/// How a patch is measured and split, from its minimum-area rectangles (a right isosceles
/// triangle has two of the same area: along its legs and along its hypotenuse).
#[derive(Debug, Clone, Copy)]
struct Measure {
    /// The long side of the squarest minimum-area rectangle: the patch's size.
    size: f64,
    /// The long side of the longest one: the patch is split across it...
    long: f64,
    /// ...whose unit direction this is...
    axis: DVec2,
    /// ...through its middle, at this coordinate along `axis`.
    middle: f64,
}

/// Measures patch `poly`: so a right isosceles triangle is split through its right angle
/// into two like it, and counts as small enough once its legs are.
fn measure(points: &[DVec2], poly: &[u32]) -> Measure {
    let p: Vec<DVec2> = poly.iter().map(|&i| points[i as usize]).collect();
    let rectangles: Vec<(f64, f64, DVec2, f64)> = enclosing_rectangles(&p)
        .into_iter()
        .map(|(e, lo, hi)| {
            let size = hi - lo;
            if size.x >= size.y {
                (size.x * size.y, size.x, e, (lo.x + hi.x) * 0.5)
            } else {
                (size.x * size.y, size.y, e.perp(), (lo.y + hi.y) * 0.5)
            }
        })
        .collect();
    let least = rectangles.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let smallest: Vec<_> = rectangles
        .into_iter()
        .filter(|r| r.0 <= least * (1.0 + 1e-9))
        .collect();
    let size = smallest.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
    smallest
        .into_iter()
        .fold(None, |best: Option<(f64, f64, DVec2, f64)>, r| match best {
            Some(b) if b.1 >= r.1 => Some(b),
            _ => Some(r),
        })
        .map_or(
            Measure {
                size: 0.0,
                long: 0.0,
                axis: DVec2::X,
                middle: 0.0,
            },
            |(_, long, axis, middle)| Measure {
                size,
                long,
                axis,
                middle,
            },
        )
}

/// Twice the signed area of polygon `poly` (positive counter-clockwise).
fn area2(points: &[DVec2], poly: &[u32]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (
                points[poly[i] as usize],
                points[poly[(i + 1) % poly.len()] as usize],
            );
            a.perp_dot(b)
        })
        .sum()
}

/// Whether `p` lies on segment a–b strictly between its ends (within `eps` metres).
fn inside_segment(p: DVec2, a: DVec2, b: DVec2, eps: f64) -> bool {
    let d = b - a;
    let length = d.length();
    if length <= eps {
        return false;
    }
    let along = (p - a).dot(d) / length;
    let off = d.perp_dot(p - a).abs() / length;
    off <= eps && along > eps && along < length - eps
}

/// One end of a splitting line on a patch's boundary.
#[derive(Debug, Clone, Copy)]
enum End {
    /// At the patch's vertex (a position in its list).
    Vertex(usize),
    /// Inside the side from position `usize` to the next, at this point.
    Side(usize, DVec2),
}

/// The refinement of one triangle, growing patch by patch.
struct Refinement {
    points: Vec<DVec2>,
    patches: Vec<Vec<u32>>,
    live: Vec<bool>,
    /// Each live patch's sides, directed as it runs (point to next point): which patch.
    /// A side's neighbour across it runs it backwards, since every patch carries every
    /// point on its boundary.
    sides: FxHashMap<(u32, u32), usize>,
    eps: f64,
}

impl Refinement {
    /// The refinement of `patches` (all live) over `points`.
    fn new(points: Vec<DVec2>, patches: Vec<Vec<u32>>, eps: f64) -> Refinement {
        let mut r = Refinement {
            points,
            live: Vec::with_capacity(patches.len()),
            patches: Vec::with_capacity(patches.len()),
            sides: FxHashMap::default(),
            eps,
        };
        for patch in patches {
            r.push(patch);
        }
        r
    }

    /// Adds a live patch.
    fn push(&mut self, patch: Vec<u32>) -> usize {
        let k = self.patches.len();
        for s in 0..patch.len() {
            self.sides
                .insert((patch[s], patch[(s + 1) % patch.len()]), k);
        }
        self.patches.push(patch);
        self.live.push(true);
        k
    }

    /// Retires patch `k` (split into pieces pushed after it).
    fn retire(&mut self, k: usize) {
        let patch = std::mem::take(&mut self.patches[k]);
        for s in 0..patch.len() {
            let side = (patch[s], patch[(s + 1) % patch.len()]);
            if self.sides.get(&side) == Some(&k) {
                self.sides.remove(&side);
            }
        }
        self.live[k] = false;
    }

    /// Inserts point `i` into the live patch that runs side `a → b`, between them.
    fn insert_into_side(&mut self, a: u32, b: u32, i: u32) {
        let Some(k) = self.sides.remove(&(a, b)) else {
            return;
        };
        let patch = &mut self.patches[k];
        let at = patch
            .iter()
            .position(|&x| x == a)
            .expect("a side's patch holds it");
        patch.insert(at + 1, i);
        self.sides.insert((a, i), k);
        self.sides.insert((i, b), k);
    }

    /// Inserts point `i` into every live patch with a side that has it strictly inside
    /// (a search over all patches, for points from outside the refinement).
    fn insert_on_sides(&mut self, i: u32) {
        let p = self.points[i as usize];
        let mut found = Vec::new();
        for k in (0..self.patches.len()).filter(|&k| self.live[k]) {
            let poly = &self.patches[k];
            let n = poly.len();
            found.extend(
                (0..n)
                    .map(|s| (poly[s], poly[(s + 1) % n]))
                    .find(|&(a, b)| {
                        inside_segment(
                            p,
                            self.points[a as usize],
                            self.points[b as usize],
                            self.eps,
                        )
                    }),
            );
        }
        for (a, b) in found {
            self.insert_into_side(a, b, i);
        }
    }

    /// Adds the points `extra`, each on the side of some live patch, to every patch whose
    /// side holds it; a point within `eps` of one already there is that point.
    fn add_points(&mut self, extra: &[DVec2]) {
        for &p in extra {
            if self.points.iter().all(|q| q.distance(p) > self.eps) {
                self.points.push(p);
                self.insert_on_sides((self.points.len() - 1) as u32);
            }
        }
    }

    /// Where the line `dot(q, axis) = middle` crosses patch `k`'s boundary: two ends, each
    /// snapped to a vertex within `snap` metres when `snap > 0`.
    fn ends(&self, k: usize, axis: DVec2, middle: f64, snap: f64) -> Option<[End; 2]> {
        let poly = &self.patches[k];
        let n = poly.len();
        let at = |s: usize| self.points[poly[s % n] as usize];
        let side = |s: usize| at(s).dot(axis) - middle;
        let mut ends = Vec::with_capacity(2);
        for s in 0..n {
            let (a, b) = (side(s), side(s + 1));
            if (a < 0.0) == (b < 0.0) {
                continue;
            }
            let c = at(s) + (at(s + 1) - at(s)) * (a / (a - b));
            let (da, db) = (c.distance(at(s)), c.distance(at(s + 1)));
            let nearest = if da <= db { (s, da) } else { ((s + 1) % n, db) };
            ends.push(if nearest.1 <= snap.max(self.eps) {
                End::Vertex(nearest.0)
            } else {
                End::Side(s, c)
            });
        }
        (ends.len() == 2).then(|| [ends[0], ends[1]])
    }

    /// Splits patch `k` along the chord between `ends`, inserting new points into it and
    /// its neighbours. `None` (and nothing changed) when the chord would leave a piece
    /// without area.
    fn split(&mut self, k: usize, ends: [End; 2]) -> Option<[usize; 2]> {
        let mut poly = self.patches[k].clone();
        let n = poly.len();
        // Where each end sits in the patch once the new points are in, and which are new.
        let place = |e: End| match e {
            End::Vertex(s) => (s as f64, None),
            End::Side(s, p) => (s as f64 + 0.5, Some(p)),
        };
        let (pa, pb) = (place(ends[0]), place(ends[1]));
        if pa.0 == pb.0 {
            return None;
        }
        let mut new_points = Vec::new();
        let mut index = |p: Option<DVec2>, points: &mut Vec<DVec2>| {
            p.map(|p| {
                points.push(p);
                let i = (points.len() - 1) as u32;
                new_points.push(i);
                i
            })
        };
        let mut points = std::mem::take(&mut self.points);
        let ia = index(pa.1, &mut points);
        let ib = index(pb.1, &mut points);
        // Insert the later side's point first, so the earlier position still holds.
        let mut inserts: Vec<(f64, u32)> = [(pa.0, ia), (pb.0, ib)]
            .into_iter()
            .filter_map(|(at, i)| i.map(|i| (at, i)))
            .collect();
        inserts.sort_by(|a, b| b.0.total_cmp(&a.0));
        for &(at, i) in &inserts {
            poly.insert(at.ceil() as usize, i);
        }
        let position = |(at, i): (f64, Option<u32>), poly: &[u32]| match i {
            Some(i) => poly.iter().position(|&x| x == i).unwrap(),
            None => poly
                .iter()
                .position(|&x| x == self.patches[k][at as usize])
                .unwrap(),
        };
        let (mut a, mut b) = (position((pa.0, ia), &poly), position((pb.0, ib), &poly));
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        let first: Vec<u32> = poly[a..=b].to_vec();
        let second: Vec<u32> = poly[b..].iter().chain(&poly[..=a]).copied().collect();
        let whole = area2(&points, &self.patches[k]);
        let keeps_area = |piece: &[u32]| piece.len() >= 3 && area2(&points, piece) > 1e-9 * whole;
        if b - a < 2
            || n + inserts.len() - (b - a) < 2
            || !keeps_area(&first)
            || !keeps_area(&second)
        {
            points.truncate(points.len() - new_points.len());
            self.points = points;
            return None;
        }
        self.points = points;
        // The new points' neighbours across the sides they split (before k, which runs
        // those sides forwards, retires).
        let outside: Vec<(u32, u32, u32)> = [(ends[0], ia), (ends[1], ib)]
            .into_iter()
            .filter_map(|(e, i)| match (e, i) {
                (End::Side(s, _), Some(i)) => {
                    let old = &self.patches[k];
                    Some((old[(s + 1) % n], old[s], i))
                }
                _ => None,
            })
            .collect();
        self.retire(k);
        let ids = [self.push(first), self.push(second)];
        for (b, a, i) in outside {
            self.insert_into_side(b, a, i);
        }
        Some(ids)
    }
}

/// Refines the triangle `corners` (counter-clockwise, metres) until no patch's
/// minimum-area rectangle is longer than `size` (Edström §4.4.2), largest patch first.
/// `boundary`: points already on its sides (where refined neighbours split them), which
/// splits snap to like the triangle's own vertices.
pub fn refine(corners: [DVec2; 3], size: f64, boundary: &[DVec2]) -> Patches {
    let scale = corners
        .iter()
        .map(|c| c.distance(corners[0]))
        .fold(0.0, f64::max);
    let size = size.max(1e-6 * scale);
    // No side longer than `size`: no rectangle around it is longer either (nor when the
    // triangle has no area to refine).
    let longest = (0..3)
        .map(|k| corners[k].distance(corners[(k + 1) % 3]))
        .fold(0.0, f64::max);
    let whole = area2(&corners, &[0, 1, 2]);
    if longest <= size || whole <= 1e-12 * scale * scale {
        return Patches {
            points: corners.to_vec(),
            leaves: vec![vec![0, 1, 2]],
        };
    }
    let mut r = Refinement::new(corners.to_vec(), vec![vec![0, 1, 2]], 1e-9 * scale);
    r.add_points(boundary);
    // Largest first (a positive f64's bits sort as the number), so a coarse split's points
    // are on the boundary of the finer patches by the time those snap.
    let mut heap = BinaryHeap::new();
    heap.push((measure(&r.points, &r.patches[0]).size.to_bits(), 0usize));
    while let Some((bits, k)) = heap.pop() {
        if f64::from_bits(bits) <= size || r.patches.len() >= MAX_PATCHES {
            break;
        }
        if !r.live[k] {
            continue;
        }
        let m = measure(&r.points, &r.patches[k]);
        let split = [SNAP_TOLERANCE * m.long, 0.0].into_iter().find_map(|snap| {
            r.ends(k, m.axis, m.middle, snap)
                .and_then(|e| r.split(k, e))
        });
        for piece in split.into_iter().flatten() {
            let size = measure(&r.points, &r.patches[piece]).size;
            heap.push((size.to_bits(), piece));
        }
    }
    let leaves = r
        .patches
        .into_iter()
        .zip(r.live)
        .filter_map(|(p, live)| live.then_some(p))
        .collect();
    Patches {
        points: r.points,
        leaves,
    }
}

/// Regular refinement of the triangle `corners`: each side cut into `n`, `n²` triangles
/// (the leaves), wound as it.
pub fn regular(corners: [DVec2; 3], n: u32) -> Patches {
    let n = n.max(1);
    let mut points = corners.to_vec();
    let mut index = FxHashMap::default();
    for (k, &i) in [(0, 0), (n, 0), (0, n)].iter().enumerate() {
        index.insert(i, k as u32);
    }
    // Grid point (i, j): i n-ths of the way to corner 1, j to corner 2.
    let mut at = |i: u32, j: u32| {
        *index.entry((i, j)).or_insert_with(|| {
            let (u, v) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            points.push(corners[0] + (corners[1] - corners[0]) * u + (corners[2] - corners[0]) * v);
            (points.len() - 1) as u32
        })
    };
    let mut leaves = Vec::with_capacity((n * n) as usize);
    for i in 0..n {
        for j in 0..n - i {
            leaves.push(vec![at(i, j), at(i + 1, j), at(i, j + 1)]);
            if i + j + 2 <= n {
                leaves.push(vec![at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    Patches { points, leaves }
}

/// The triangle `corners` refined to patches no longer than `size`: Edström's refinement
/// where it draws fewer triangles than regular refinement to sides of at most `size`
/// (slivers, right isosceles triangles), regular refinement where that draws fewer (a
/// well-shaped triangle's `n²` parts are already as good as patches get).
pub fn refine_triangle(corners: [DVec2; 3], size: f64, boundary: &[DVec2]) -> Patches {
    let bsp = refine(corners, size, boundary);
    let longest = (0..3)
        .map(|k| corners[k].distance(corners[(k + 1) % 3]))
        .fold(0.0, f64::max);
    let n = (longest / size.max(1e-12) * (1.0 - 1e-9))
        .ceil()
        .clamp(1.0, 1024.0) as u32;
    let drawn: usize = bsp.leaves.iter().map(|l| l.len() - 2).sum();
    if (n * n) as usize <= drawn {
        regular(corners, n)
    } else {
        bsp
    }
}

/// Inserts the points `extra` (each on the boundary of some leaf) into the leaves whose
/// side holds them, skipping any within `eps` of a point already there.
fn add_boundary_points(patches: &mut Patches, extra: &[DVec2], eps: f64) {
    let mut r = Refinement::new(
        std::mem::take(&mut patches.points),
        std::mem::take(&mut patches.leaves),
        eps,
    );
    r.add_points(extra);
    patches.points = r.points;
    patches.leaves = r.patches;
}

/// Triangulates a convex polygon whose boundary may hold collinear points: ears are cut
/// one by one, each time the one whose smallest angle is largest, never one that is flat
/// or that would leave the rest without area; `m` points give `m − 2` triangles.
pub fn triangulate(points: &[DVec2], poly: &[u32]) -> Vec<[u32; 3]> {
    let mut ring = poly.to_vec();
    let mut left = area2(points, &ring);
    let floor = 1e-12 * left.abs().max(f64::MIN_POSITIVE);
    let mut out = Vec::with_capacity(ring.len().saturating_sub(2));
    while ring.len() > 3 {
        let n = ring.len();
        let mut best: Option<(f64, usize, f64)> = None;
        for i in 0..n {
            let [a, b, c] =
                [ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]].map(|k| points[k as usize]);
            let ear = (b - a).perp_dot(c - b);
            if ear <= floor || left - ear <= floor {
                continue;
            }
            let quality = smallest_angle([a, b, c]);
            if best.is_none_or(|(q, _, _)| quality > q) {
                best = Some((quality, i, ear));
            }
        }
        let Some((_, i, ear)) = best else {
            break;
        };
        out.push([ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]]);
        ring.remove(i);
        left -= ear;
    }
    if ring.len() == 3 {
        out.push([ring[0], ring[1], ring[2]]);
    }
    out
}

/// The smallest angle of a triangle, radians.
pub fn smallest_angle(t: [DVec2; 3]) -> f64 {
    (0..3)
        .map(|k| {
            let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            (b - a).angle_to(c - a).abs()
        })
        .fold(f64::INFINITY, f64::min)
}

/// A triangle's plane frame: its corners in metres with corner 0 at the origin and
/// corner 1 on +x (counter-clockwise seen from the front).
fn plane_corners(p: [DVec3; 3]) -> [DVec2; 3] {
    let x = (p[1] - p[0]).normalize_or_zero();
    let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
    let y = n.cross(x);
    p.map(|q| DVec2::new((q - p[0]).dot(x), (q - p[0]).dot(y)))
}

/// Barycentric weights of `q` over the plane-frame triangle `c` (`c[0]` at the origin,
/// `c[1]` on +x).
fn weights(c: &[DVec2; 3], q: DVec2) -> DVec3 {
    let v = if c[2].y != 0.0 { q.y / c[2].y } else { 0.0 };
    let u = if c[1].x != 0.0 {
        (q.x - c[2].x * v) / c[1].x
    } else {
        0.0
    };
    DVec3::new(1.0 - u - v, u, v)
}

/// An edge of a mesh, by its corners' positions (lower first), and whether a triangle's
/// side `k` runs along it backwards.
type EdgeKey = ([u64; 3], [u64; 3]);

/// Side `k` of triangle `p` as an edge key, and whether it runs backwards along it.
fn edge_of(p: [DVec3; 3], k: usize) -> (EdgeKey, bool) {
    let key = |q: DVec3| q.to_array().map(f64::to_bits);
    let (a, b) = (key(p[k]), key(p[(k + 1) % 3]));
    if a <= b {
        ((a, b), false)
    } else {
        ((b, a), true)
    }
}

/// The points of a surface's refinement on each edge, as the share of the way along it.
#[derive(Default)]
struct EdgePoints(FxHashMap<EdgeKey, Vec<f64>>);

impl EdgePoints {
    /// The points on the sides of triangle `p` (plane frame `plane`), in that frame.
    fn on(&self, p: [DVec3; 3], plane: &[DVec2; 3], k: usize) -> Vec<DVec2> {
        let (edge, flipped) = edge_of(p, k);
        let (a, b) = (plane[k], plane[(k + 1) % 3]);
        self.0.get(&edge).map_or_else(Vec::new, |list| {
            list.iter()
                .map(|&s| a + (b - a) * if flipped { 1.0 - s } else { s })
                .collect()
        })
    }

    /// Records the points of `patches` that lie on the sides of triangle `p`.
    fn record(&mut self, p: [DVec3; 3], plane: &[DVec2; 3], patches: &Patches) {
        for k in 0..3 {
            let (a, b) = (plane[k], plane[(k + 1) % 3]);
            let eps = 1e-9 * a.distance(b);
            let (edge, flipped) = edge_of(p, k);
            let list = self.0.entry(edge).or_default();
            for &q in &patches.points[3..] {
                if inside_segment(q, a, b, eps) {
                    let s = (q - a).dot(b - a) / (b - a).length_squared();
                    let s = if flipped { 1.0 - s } else { s };
                    if list.iter().all(|&x| (x - s).abs() > 1e-9) {
                        list.push(s);
                    }
                }
            }
        }
    }
}

/// Refines the triangles `triangles` of `mesh` (one surface: where two share an edge,
/// matched by corner position, each takes the points the other puts on it, and splits
/// snap to the points of those refined before), each until its patches are at most
/// `size(t)` metres long. Per triangle, in the order given: its parts, each as three
/// corners in barycentric weights over the triangle's corners, wound as the triangle.
pub fn refine_surface(
    mesh: &Mesh,
    triangles: &[u32],
    size: impl Fn(u32) -> f64,
) -> Vec<Vec<[DVec3; 3]>> {
    let corners = |t: u32| mesh.triangles[t as usize].map(|i| mesh.positions[i as usize]);
    let mut edges = EdgePoints::default();
    let mut refined: Vec<([DVec2; 3], Patches)> = Vec::with_capacity(triangles.len());
    for &t in triangles {
        let p = corners(t);
        let plane = plane_corners(p);
        let known: Vec<DVec2> = (0..3).flat_map(|k| edges.on(p, &plane, k)).collect();
        let patches = refine_triangle(plane, size(t), &known);
        edges.record(p, &plane, &patches);
        refined.push((plane, patches));
    }
    triangles
        .iter()
        .zip(&mut refined)
        .map(|(&t, (plane, patches))| {
            let p = corners(t);
            for k in 0..3 {
                let (a, b) = (plane[k], plane[(k + 1) % 3]);
                add_boundary_points(patches, &edges.on(p, plane, k), 1e-9 * a.distance(b));
            }
            patches
                .leaves
                .iter()
                .flat_map(|leaf| triangulate(&patches.points, leaf))
                .map(|tri| tri.map(|i| weights(plane, patches.points[i as usize])))
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every side of the triangulation either lies on the triangle's boundary or is shared,
    /// in opposite directions, by exactly two triangles: no t-vertex, no overlap.
    fn assert_conforming(p: &Patches, tris: &[[u32; 3]]) {
        let mut sides: FxHashMap<(u32, u32), i32> = FxHashMap::default();
        for t in tris {
            for k in 0..3 {
                *sides.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        let c = [p.points[0], p.points[1], p.points[2]];
        let on_boundary = |a: DVec2, b: DVec2| {
            (0..3).any(|k| {
                let (x, y) = (c[k], c[(k + 1) % 3]);
                let eps = 1e-9 * x.distance(y);
                [a, b].iter().all(|&q| {
                    q.distance(x) <= eps || q.distance(y) <= eps || inside_segment(q, x, y, eps)
                })
            })
        };
        for (&(a, b), &count) in &sides {
            assert_eq!(count, 1, "side {a}–{b} twice in one direction");
            let twin = sides.contains_key(&(b, a));
            let boundary = on_boundary(p.points[a as usize], p.points[b as usize]);
            assert!(
                twin != boundary,
                "side {a}–{b}: twin {twin}, boundary {boundary}"
            );
        }
    }

    fn triangles_of(p: &Patches) -> Vec<[u32; 3]> {
        p.leaves
            .iter()
            .flat_map(|l| triangulate(&p.points, l))
            .collect()
    }

    fn area(p: &Patches, tris: &[[u32; 3]]) -> f64 {
        tris.iter().map(|t| area2(&p.points, t) * 0.5).sum()
    }

    /// A CAD strip 10 m × 5 cm under 10 cm patches: about a hundred patches no longer than
    /// 10 cm, well shaped, conforming, covering the strip — where regular refinement makes
    /// 100² = 10 000 slivers.
    #[test]
    fn a_long_thin_triangle_becomes_short_patches() {
        let corners = [DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::new(3.0, 0.05)];
        let p = refine(corners, 0.1, &[]);
        for leaf in &p.leaves {
            assert!(measure(&p.points, leaf).size <= 0.1 + 1e-12);
            assert!(area2(&p.points, leaf) > 0.0, "{leaf:?}");
        }
        let tris = triangles_of(&p);
        assert!(
            (area(&p, &tris) - 0.25).abs() < 1e-12,
            "{}",
            area(&p, &tris)
        );
        assert_conforming(&p, &tris);
        assert!(
            (100..=300).contains(&tris.len()),
            "{} triangles from {} patches",
            tris.len(),
            p.leaves.len()
        );
        // Regular refinement keeps the strip's angles (its smallest 0.4°) in every part;
        // these patches are blocks at most 10 cm long and as wide as the strip there, so
        // half of their triangles have no angle under 10°.
        let mut angles: Vec<f64> = tris
            .iter()
            .map(|t| smallest_angle(t.map(|i| p.points[i as usize])).to_degrees())
            .collect();
        angles.sort_by(f64::total_cmp);
        assert!(
            angles[angles.len() / 2] > 10.0,
            "median {}",
            angles[angles.len() / 2]
        );
    }

    /// The splitting line through the middle of the base ends 0.1 m from the apex, within
    /// the snap tolerance (0.5 m for a 4 m side): it moves there, and the triangle splits
    /// into two triangles with one new point instead of a triangle and a quadrilateral.
    #[test]
    fn a_split_snaps_to_a_near_vertex() {
        let corners = [DVec2::ZERO, DVec2::new(4.0, 0.0), DVec2::new(1.9, 1.0)];
        let p = refine(corners, 3.5, &[]);
        assert_eq!(p.points.len(), 4, "{:?}", p.points);
        assert!((p.points[3] - DVec2::new(2.0, 0.0)).length() < 1e-12);
        assert_eq!(p.leaves.len(), 2);
        assert!(p.leaves.iter().all(|l| l.len() == 3));
    }

    /// Regular refinement: `n²` triangles wound as the triangle, each `1/n²` of its area,
    /// on the grid of `n`ths, conforming.
    #[test]
    fn regular_refinement_tiles_the_triangle_with_n_squared_parts() {
        let corners = [DVec2::ZERO, DVec2::new(3.0, 0.5), DVec2::new(1.0, 2.0)];
        let whole = area2(corners.as_ref(), &[0, 1, 2]);
        for n in [1u32, 2, 5, 32] {
            let p = regular(corners, n);
            assert_eq!(p.leaves.len(), (n * n) as usize);
            assert_eq!(p.points.len(), ((n + 1) * (n + 2) / 2) as usize);
            for leaf in &p.leaves {
                let part = area2(&p.points, leaf) * f64::from(n * n);
                assert!((part - whole).abs() < 1e-9, "{n}: {part}");
            }
            let tris = triangles_of(&p);
            assert_conforming(&p, &tris);
        }
    }

    /// Each triangle takes the refinement that draws fewer triangles: a well-shaped one
    /// (3-4-5 m) its `n²` regular parts, a sliver Edström's patches.
    #[test]
    fn a_triangle_is_refined_the_cheaper_way() {
        let well = [DVec2::ZERO, DVec2::new(4.0, 0.0), DVec2::new(4.0, 3.0)];
        assert_eq!(refine_triangle(well, 0.25, &[]), regular(well, 20));
        let bsp = triangles_of(&refine(well, 0.25, &[])).len();
        assert!(bsp > 400, "{bsp}");
        let sliver = [DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::new(3.0, 0.05)];
        let p = refine_triangle(sliver, 0.1, &[]);
        assert_eq!(p, refine(sliver, 0.1, &[]));
        assert!(triangles_of(&p).len() < 300);
    }

    /// Flat points on a patch's sides: still `m − 2` triangles, none without area.
    #[test]
    fn collinear_boundary_points_triangulate_without_slivers() {
        let points: Vec<DVec2> = [
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (0.0, 1.0),
            (0.0, 0.5),
        ]
        .map(|(x, y)| DVec2::new(x, y))
        .to_vec();
        let poly: Vec<u32> = (0..7).collect();
        let tris = triangulate(&points, &poly);
        assert_eq!(tris.len(), 5);
        let total: f64 = tris.iter().map(|t| area2(&points, t) * 0.5).sum();
        assert!((total - 3.0).abs() < 1e-12);
        assert!(tris.iter().all(|t| area2(&points, t) > 1e-6));
    }

    /// Two slivers sharing their long side (a 10 m × 10 cm quad cut along its diagonal):
    /// every point one puts on the diagonal is a corner of the other's triangles too.
    #[test]
    fn triangles_of_one_surface_share_the_points_on_their_common_edge() {
        let v = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        let mesh = Mesh {
            positions: vec![v(0.0, 0.0), v(10.0, 0.0), v(10.0, 0.1), v(0.0, 0.1)],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let parts = refine_surface(&mesh, &[0, 1], |_| 0.3);
        let at = |t: usize, w: DVec3| {
            let tri = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
            tri[0] * w.x + tri[1] * w.y + tri[2] * w.z
        };
        let on_diagonal = |t: usize| -> Vec<DVec3> {
            let mut pts: Vec<DVec3> = parts[t]
                .iter()
                .flatten()
                .map(|&w| at(t, w))
                .filter(|q| (q.y - q.x * 0.01).abs() < 1e-9)
                .collect();
            pts.sort_by(|a, b| a.x.total_cmp(&b.x));
            pts.dedup_by(|a, b| a.distance(*b) < 1e-9);
            pts
        };
        for (t, list) in parts.iter().enumerate() {
            for w in list {
                let [p, q, r] = w.map(|w| at(t, w));
                assert!((q - p).cross(r - p).z > 0.0, "wound as the triangle");
            }
        }
        let (a, b) = (on_diagonal(0), on_diagonal(1));
        assert!(a.len() > 30, "{}", a.len());
        assert_eq!(a.len(), b.len());
        assert!(a.iter().zip(&b).all(|(p, q)| p.distance(*q) < 1e-9));
        let total: f64 = (0..2)
            .flat_map(|t| parts[t].iter().map(move |w| (t, w)))
            .map(|(t, w)| {
                let [p, q, r] = w.map(|w| at(t, w));
                (q - p).cross(r - p).length() * 0.5
            })
            .sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
    }
}
