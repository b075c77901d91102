//! Links from a shooter's cells to its receivers: which level of a cluster's cell quadtree
//! each receiver takes its light from (Hanrahan et al.'s hierarchical radiosity with a
//! refinement oracle per link, Edström §3.2.2 and ch. 4, on the shooter side of
//! progressive shooting).
//!
//! A cluster's cells ([`super::shooters::Shooters::plan_levels`]) form a quadtree: the
//! finest cells the power oracle chose and up to [`LINK_LEVELS`] coarser levels. The form
//! factor from a receiver to a cell's polygon is exact (Lambert's contour integral), so a
//! coarse cell errs only where its radiosity is not uniform and where its centre sees
//! differently from its parts. A receiver at distance d from a cell of area A whose fine
//! cells' radiosity differs from its mean by up to ΔB takes at most A / (π d²) of that
//! difference, so the link's error is below ε beyond the cell's **reach**
//! sqrt(A ΔB / (π ε)), and at least [`MIN_REACH`] radii (visibility from its centre); the
//! finest cells reach everything. A receiver takes its light from the first cell down the
//! tree that it is beyond the reach of: a uniformly lit ceiling sends its light to the
//! floor from a few coarse cells, a hot spot from the fine cells around it. Every receiver
//! so takes the light of every part of the shooter exactly once.
//!
//! With a view driving, a receiver's share of the link error follows its importance
//! (Smits, Arvo and Salesin 1992, on the receiving side): one whose light the view needs
//! a share w of takes every reach times √w, the visibility sphere included
//! ([`Links::reach_for`]); the search then asks boxes of a few elements
//! ([`ReceiverBoxes::of_elements`]) with their least and most scale. Any per-receiver
//! scale keeps "exactly once": the rule only moves where along the path a receiver takes
//! the light.
//!
//! A cell is drawn (its visibility map rendered) only when some receiver in front of it
//! takes light from it, and refined only when some receiver is within its reach: those
//! questions go to a BVH over the charts' boxes of element centres ([`ReceiverBoxes`]),
//! and are answered conservatively (a box stands for every element in it). Receivers stay
//! elements — one GPU thread each, so receiving per cluster and pushing the light down
//! would save nothing there and blur shadows: nothing is pushed or pulled.

use glam::DVec3;
use glam_bvh::Vec3A;
use obvhs::aabb::Aabb;
use obvhs::bvh2::Bvh2;
use obvhs::ploc::{PlocBuilder, PlocSearchDistance, SortPrecision};

use super::scene::RadiosityScene;
use super::shooters::ShotPlan;

/// Default link error ε, as a share of the mean initial exitance (initial unshot power
/// over the scene's area): the irradiance error a receiver accepts from a coarse cell.
pub const DEFAULT_LINK_ERROR: f64 = 0.05;
/// Most levels of coarser cells above the finest (cells up to 16 times the side).
pub const LINK_LEVELS: u32 = 4;
/// A receiver takes light from a coarse cell only at least this many cell radii away
/// (beyond the sphere around it: visibility is tested from its centre) — times its reach
/// scale where a view weighs the receivers ([`Links::reach_for`]).
pub const MIN_REACH: f64 = 1.0;
/// Receivers closer to a shooter's plane than this share of the scene's size take light
/// from its top cells only (their form factor is next to nothing).
const PLANE_TOLERANCE: f64 = 1e-4;
/// Most plane tests per box in receiver culling ([`ReceiverBoxes::in_front_of_any`]).
pub const MAX_CULLING_PLANES: usize = 64;
/// Relative slack of the conservative questions (f32 distances on the GPU).
const SLACK: f64 = 1e-5;

/// The charts' boxes of element centres in a bounding volume hierarchy: does any receiver
/// lie in a region?
pub struct ReceiverBoxes {
    bvh: Option<Bvh2>,
    /// Per chart with elements, its box (lowest and highest corner), metres.
    boxes: Vec<(DVec3, DVec3)>,
    /// Per chart with elements, its elements (first, count).
    ranges: Vec<(u32, u32)>,
    /// The f32 hierarchy's origin.
    centre: DVec3,
    /// How far the f32 boxes are widened, metres.
    pad: f64,
    /// The scene's size (diagonal), metres.
    size: f64,
    /// The charts in depth-first order of the hierarchy …
    depth_first: Vec<u32>,
    /// … and per node, the run of them under it (start, end).
    spans: Vec<(u32, u32)>,
    /// Per box, the least and most reach scale of its receivers ([`ReachScale`]) …
    scales: Vec<ReachScale>,
    /// … and per node of the hierarchy, of the boxes under it.
    node_scales: Vec<ReachScale>,
}

/// The least and most factor on the receivers' reaches in a box (importance-driven link
/// error, [`ReceiverBoxes::of_elements`]): 1 and 1 without a view.
pub type ReachScale = (f64, f64);

/// Most elements per box of [`ReceiverBoxes::of_elements`].
pub const ELEMENTS_PER_BOX: usize = 64;

/// How [`ReceiverBoxes::visit`] walks.
#[derive(Clone, Copy)]
enum Visit {
    /// Stop at the first chart found.
    First,
    /// Find them all, taking a node of at most `group` charts whole where its box passes.
    All { group: u32 },
}

/// The primitives of `bvh` in depth-first order, and per node the run of that list under
/// it (start, end).
fn depth_first(bvh: &Bvh2) -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut order = Vec::with_capacity(bvh.primitive_indices.len());
    let mut spans = vec![(0u32, 0u32); bvh.nodes.len()];
    // A node is met twice: before its children (its run starts) and after (it ends).
    let mut stack = vec![(0usize, false)];
    while let Some((k, children_done)) = stack.pop() {
        let Some(node) = bvh.nodes.get(k) else {
            continue;
        };
        let c = node.first_index as usize;
        if node.is_leaf() {
            let start = order.len() as u32;
            order.extend_from_slice(&bvh.primitive_indices[c..][..node.prim_count as usize]);
            spans[k] = (start, order.len() as u32);
        } else if children_done {
            spans[k].1 = order.len() as u32;
        } else {
            spans[k].0 = order.len() as u32;
            // The second child is popped after the first: runs in child order.
            stack.extend([(k, true), (c + 1, false), (c, false)]);
        }
    }
    (order, spans)
}

fn to_f32(v: DVec3) -> Vec3A {
    Vec3A::new(v.x as f32, v.y as f32, v.z as f32)
}

impl ReceiverBoxes {
    /// The hierarchy over `scene`'s charts.
    pub fn new(scene: &RadiosityScene) -> ReceiverBoxes {
        let el = &scene.elements;
        let charts: Vec<_> = el.charts.iter().filter(|c| c.count > 0).collect();
        let ranges = charts.iter().map(|c| (c.first, c.count)).collect();
        let boxes: Vec<(DVec3, DVec3)> = charts
            .iter()
            .map(|c| {
                bounds(
                    el.position[c.first as usize..][..c.count as usize]
                        .iter()
                        .copied(),
                )
            })
            .collect();
        ReceiverBoxes::from_boxes(boxes, ranges)
    }

    /// The hierarchy over `scene`'s elements in boxes of at most [`ELEMENTS_PER_BOX`]
    /// neighbours of one chart (a chart's elements sorted along a Morton curve and cut in
    /// runs), each box with the least and most of its elements' `scale` (the factor on
    /// their reaches, [`Links::reach_for`]): the link search's receivers when their link
    /// error follows their importance, finer than charts so that the part of a floor the
    /// eye sees does not make its every part as demanding. Only [`ReceiverBoxes::any`] and
    /// [`ReceiverBoxes::any_scaled`] are meant for it (its boxes' ranges are their
    /// charts').
    pub fn of_elements(scene: &RadiosityScene, scale: &[f64]) -> ReceiverBoxes {
        let el = &scene.elements;
        assert_eq!(scale.len(), el.len());
        let (lo, hi) = bounds(el.position.iter().copied());
        let extent = (hi - lo).max(DVec3::splat(1e-30));
        let mut boxes = Vec::new();
        let mut ranges = Vec::new();
        let mut scales = Vec::new();
        for chart in el.charts.iter().filter(|c| c.count > 0) {
            let mut members: Vec<(u64, usize)> = (chart.first..chart.first + chart.count)
                .map(|e| {
                    let q = (el.position[e as usize] - lo) / extent * 1023.0;
                    let code = morton(q.x as u64, q.y as u64, q.z as u64);
                    (code, e as usize)
                })
                .collect();
            members.sort_unstable();
            for run in members.chunks(ELEMENTS_PER_BOX) {
                boxes.push(bounds(run.iter().map(|&(_, e)| el.position[e])));
                ranges.push((chart.first, chart.count));
                scales.push(widest(run.iter().map(|&(_, e)| (scale[e], scale[e]))));
            }
        }
        let mut boxes = ReceiverBoxes::build(boxes, ranges, None);
        boxes.set_scales(scales);
        boxes
    }

    /// Gives the boxes their reach scales (one per box) and each node those of its boxes.
    fn set_scales(&mut self, scales: Vec<ReachScale>) {
        let over = |run: &[u32]| widest(run.iter().map(|&b| scales[b as usize]));
        self.node_scales = self
            .spans
            .iter()
            .map(|&(start, end)| over(&self.depth_first[start as usize..end as usize]))
            .collect();
        self.scales = scales;
    }

    /// The hierarchy over `charts` alone (indices, see [`ReceiverBoxes::range`]): its
    /// chart `k` is `charts[k]` here. Queries about a few charts among many (the charts
    /// that join perspective-driven radiosity's area of interest) then cost what those
    /// few do.
    /// Its tolerances are the whole hierarchy's, so it finds exactly the charts of
    /// `charts` that the whole one finds.
    pub fn subset(&self, charts: &[usize]) -> ReceiverBoxes {
        let mut subset = ReceiverBoxes::build(
            charts.iter().map(|&k| self.boxes[k]).collect(),
            charts.iter().map(|&k| self.ranges[k]).collect(),
            Some(self.size),
        );
        subset.set_scales(charts.iter().map(|&k| self.scales[k]).collect());
        subset
    }

    /// The hierarchy over chart boxes (lowest, highest corner) holding the elements
    /// `ranges` (first, count).
    fn from_boxes(boxes: Vec<(DVec3, DVec3)>, ranges: Vec<(u32, u32)>) -> ReceiverBoxes {
        ReceiverBoxes::build(boxes, ranges, None)
    }

    /// [`ReceiverBoxes::from_boxes`] with the tolerances of a scene of `size` metres
    /// (default: the boxes' own extent).
    fn build(
        boxes: Vec<(DVec3, DVec3)>,
        ranges: Vec<(u32, u32)>,
        size: Option<f64>,
    ) -> ReceiverBoxes {
        let lo = boxes.iter().map(|b| b.0).fold(DVec3::INFINITY, DVec3::min);
        let hi = boxes
            .iter()
            .map(|b| b.1)
            .fold(DVec3::NEG_INFINITY, DVec3::max);
        let size = size.unwrap_or(if boxes.is_empty() {
            1.0
        } else {
            (hi - lo).length()
        });
        let centre = if boxes.is_empty() {
            DVec3::ZERO
        } else {
            (lo + hi) * 0.5
        };
        let pad = 1e-5 * (1.0 + size);
        let aabbs: Vec<Aabb> = boxes
            .iter()
            .map(|(a, b)| Aabb::new(to_f32(*a - centre - pad), to_f32(*b - centre + pad)))
            .collect();
        let bvh = (!aabbs.is_empty()).then(|| {
            PlocBuilder::with_capacity(aabbs.len()).build(
                PlocSearchDistance::Medium,
                &aabbs,
                (0..aabbs.len() as u32).collect(),
                SortPrecision::U64,
                1,
            )
        });
        let (depth_first, spans) = bvh.as_ref().map(depth_first).unwrap_or_default();
        ReceiverBoxes {
            scales: vec![(1.0, 1.0); boxes.len()],
            node_scales: vec![(1.0, 1.0); spans.len()],
            depth_first,
            spans,
            bvh,
            boxes,
            ranges,
            centre,
            pad,
            size,
        }
    }

    /// Whether some chart's box satisfies `wanted`, which must hold for every box around
    /// one it holds for (so whole subtrees are skipped where a node's box fails it).
    pub fn any(&self, wanted: impl Fn(DVec3, DVec3) -> bool) -> bool {
        self.any_scaled(|lo, hi, _| wanted(lo, hi))
    }

    /// [`ReceiverBoxes::any`] where `wanted` also sees the box's least and most reach
    /// scale (of its receivers; of its boxes for a node).
    pub fn any_scaled(&self, wanted: impl Fn(DVec3, DVec3, ReachScale) -> bool) -> bool {
        self.visit(wanted, &|_, _, _| false, Visit::First, &mut |_| {})
    }

    /// The element ranges (first, count) of the charts that may lie in front of the plane
    /// through `at` facing `normal` (a shooter `thickness` metres thick about it), in
    /// element order: every element behind the shooter or in its plane (where a patch's
    /// form factor is 0) is in a chart left out — receiver culling.
    pub fn in_front(&self, normal: DVec3, at: DVec3, thickness: f64) -> Vec<(u32, u32)> {
        self.in_front_of_any(&[(normal, at, thickness)])
    }

    /// [`ReceiverBoxes::in_front`] of any of `planes` (normal, point, thickness): the
    /// receivers of a shooter whose cells face several ways. Up to
    /// [`MAX_CULLING_PLANES`] planes are tested one by one; more (a curved shooter) are
    /// taken in that many runs of consecutive planes, each bounded by the cone of its
    /// normals around the sphere of its points.
    pub fn in_front_of_any(&self, planes: &[(DVec3, DVec3, f64)]) -> Vec<(u32, u32)> {
        let mut out: Vec<(u32, u32)> = self
            .charts_in_front_of_any(planes)
            .into_iter()
            .map(|k| self.ranges[k])
            .collect();
        out.sort_unstable();
        out
    }

    /// The charts (indices, see [`ReceiverBoxes::range`]) of
    /// [`ReceiverBoxes::in_front_of_any`], in no order.
    pub fn charts_in_front_of_any(&self, planes: &[(DVec3, DVec3, f64)]) -> Vec<usize> {
        self.charts_roughly_in_front_of_any(planes, 1)
    }

    /// [`ReceiverBoxes::charts_in_front_of_any`], but a subtree of at most `group`
    /// charts whose box is in front is taken whole, untested chart by chart: a superset,
    /// as safe for receiver culling (what lies behind receives nothing), and far cheaper
    /// where charts are tiny and many (the conference room's 118 000 charts took 8.6 ms a
    /// cull on an H200's host, half its solve). `group` 1 is exact.
    pub fn charts_roughly_in_front_of_any(
        &self,
        planes: &[(DVec3, DVec3, f64)],
        group: u32,
    ) -> Vec<usize> {
        let runs: Vec<PlaneRun> = planes
            .chunks(planes.len().div_ceil(MAX_CULLING_PLANES).max(1))
            .map(PlaneRun::new)
            .collect();
        let slack = self.pad + SLACK * self.size;
        let mut charts = Vec::new();
        // A node wholly in front of one run's planes takes its whole subtree untested
        // (on a shot of many facings most of a model is).
        self.visit(
            |lo, hi, _| runs.iter().any(|run| run.highest(lo, hi) > -slack),
            &|lo, hi, _| runs.iter().any(|run| run.lowest(lo, hi) > -slack),
            Visit::All { group },
            &mut |k| charts.push(k),
        );
        charts
    }

    /// The elements of `charts` (indices, any order; a repeat counts once) as sorted element
    /// ranges (first, count), neighbouring charts' ranges merged into one: the receive
    /// pass's records, far fewer than the charts where most of a model is in front (the
    /// conference room: 118 000 charts of one or two elements). Linear in the charts
    /// of the scene when many are asked for, else in those asked for.
    pub fn merged_ranges(&self, charts: &[usize]) -> Vec<(u32, u32)> {
        let mut ranges: Vec<(u32, u32)> = Vec::new();
        let mut push = |(first, count): (u32, u32)| match ranges.last_mut() {
            Some(last) if last.0 + last.1 == first => last.1 += count,
            _ => ranges.push((first, count)),
        };
        if charts.len() * 16 < self.ranges.len() {
            let mut sorted = charts.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            sorted.into_iter().for_each(|k| push(self.ranges[k]));
        } else {
            let mut asked = vec![false; self.ranges.len()];
            charts.iter().for_each(|&k| asked[k] = true);
            (0..self.ranges.len())
                .filter(|&k| asked[k])
                .for_each(|k| push(self.ranges[k]));
        }
        ranges
    }

    /// The charts with elements.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    /// Whether no chart has elements.
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }

    /// Chart `k`'s elements (first, count): the scene's charts with elements, in order.
    pub fn range(&self, k: usize) -> (u32, u32) {
        self.ranges[k]
    }

    /// Walks the hierarchy where `wanted` holds, calling `found` with each chart whose
    /// box satisfies it; with [`Visit::First`] stops at the first (and says whether there
    /// was one). Where `whole` holds for a node's box, `wanted` holds for every box in it:
    /// its charts are found without testing them; with [`Visit::All`] so are those of a
    /// node of at most `group` charts whose box satisfies `wanted`.
    fn visit(
        &self,
        wanted: impl Fn(DVec3, DVec3, ReachScale) -> bool,
        whole: &dyn Fn(DVec3, DVec3, ReachScale) -> bool,
        how: Visit,
        found: &mut dyn FnMut(usize),
    ) -> bool {
        let (first, group) = match how {
            Visit::First => (true, 1),
            Visit::All { group } => (false, group.max(1)),
        };
        let Some(bvh) = &self.bvh else {
            return false;
        };
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let Some(node) = bvh.nodes.get(k) else {
                continue;
            };
            let aabb = node.aabb();
            let lo = DVec3::new(aabb.min.x as f64, aabb.min.y as f64, aabb.min.z as f64);
            let hi = DVec3::new(aabb.max.x as f64, aabb.max.y as f64, aabb.max.z as f64);
            let (lo, hi) = (lo + self.centre - self.pad, hi + self.centre + self.pad);
            let scale = self.node_scales[k];
            if !wanted(lo, hi, scale) {
                continue;
            }
            let (start, end) = self.spans[k];
            if (group > 1 && end - start <= group) || whole(lo, hi, scale) {
                // Everything under the node, listed in one run (no walk down to it).
                for &p in &self.depth_first[start as usize..end as usize] {
                    found(p as usize);
                    if first {
                        return true;
                    }
                }
                continue;
            }
            let child = node.first_index as usize;
            if node.is_leaf() {
                for &p in &bvh.primitive_indices[child..][..node.prim_count as usize] {
                    let (a, b) = self.boxes[p as usize];
                    if wanted(a, b, self.scales[p as usize]) {
                        found(p as usize);
                        if first {
                            return true;
                        }
                    }
                }
            } else {
                stack.push(child);
                stack.push(child + 1);
            }
        }
        false
    }

    /// Receivers closer to a shooter's plane than this take light from its top cells only,
    /// metres.
    pub fn plane_tolerance(&self) -> f64 {
        PLANE_TOLERANCE * self.size
    }
}

/// The links of one shot: per patch of the plan, its reach and whether it is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Links {
    /// Per patch, how far a receiver must be to take its light from it, metres (0 for the
    /// finest cells, infinite where the link error is 0).
    pub reach: Vec<f64>,
    /// Per patch, whether some receiver in front takes light from it.
    pub drawn: Vec<bool>,
}

impl Links {
    /// How far a receiver whose reach scale is `scale` (the square root of its share of
    /// the link error, in (0, 1]: [`ReceiverBoxes::of_elements`]) must be to take patch
    /// `k`'s light from it: the patch's reach times `scale`, the [`MIN_REACH`] sphere
    /// included — a receiver the view needs little of also accepts the error of seeing a
    /// near cell from its centre.
    pub fn reach_for(&self, k: usize, scale: f64) -> f64 {
        self.reach[k] * scale
    }

    /// How many patches are drawn.
    pub fn drawn_count(&self) -> usize {
        self.drawn.iter().filter(|&&d| d).count()
    }
}

/// A cell's reach: the distance beyond which a receiver's error from taking the cell's
/// mean radiosity (its fine cells' differing from it by up to `variation`, lm/m²) over
/// its `area` (m²) as one source is below `epsilon` (lux).
pub fn reach(level: u32, radius: f64, area: f64, variation: f64, epsilon: f64) -> f64 {
    if level == 0 {
        return 0.0;
    }
    if epsilon.is_nan() || epsilon <= 0.0 {
        return f64::INFINITY;
    }
    let oracle = (area * variation.abs() / (std::f64::consts::PI * epsilon)).sqrt();
    oracle.max(MIN_REACH * radius)
}

/// Per cell of `plan`, how far its fine cells' `radiosity` (per cell, lm/m²) strays from
/// its own.
fn variation(plan: &ShotPlan, radiosity: &[f64]) -> Vec<f64> {
    let mut lo = radiosity.to_vec();
    let mut hi = radiosity.to_vec();
    // Depth first: children follow their parent, so backwards reaches children first.
    for k in (0..plan.patches.len()).rev() {
        let up = plan.patches[k].parent;
        if up != u32::MAX {
            let up = up as usize;
            lo[up] = lo[up].min(lo[k]);
            hi[up] = hi[up].max(hi[k]);
        }
    }
    (0..radiosity.len())
        .map(|k| (hi[k] - radiosity[k]).max(radiosity[k] - lo[k]))
        .collect()
}

/// Consecutive planes (normal n_i through a_i, t_i thick) bounded together: for x in a
/// box, n_i · (x − a_i) + t_i ≤ m · (x − c) + δ |x − c| + ρ (1 + δ) + t, with m their mean
/// normal, δ the largest |n_i − m|, c the centre of the a_i and ρ their largest distance
/// from it, t the largest t_i. One plane: its own test.
struct PlaneRun {
    normal: DVec3,
    centre: DVec3,
    spread: f64,
    radius: f64,
    thickness: f64,
}

impl PlaneRun {
    fn new(planes: &[(DVec3, DVec3, f64)]) -> PlaneRun {
        let sum: DVec3 = planes.iter().map(|p| p.0).sum();
        let normal = sum.try_normalize().unwrap_or(planes[0].0);
        let centre = planes.iter().map(|p| p.1).sum::<DVec3>() / planes.len() as f64;
        let most =
            |f: &dyn Fn(&(DVec3, DVec3, f64)) -> f64| planes.iter().map(f).fold(0.0, f64::max);
        PlaneRun {
            normal,
            centre,
            spread: most(&|p| (p.0 - normal).length()),
            radius: most(&|p| (p.1 - centre).length()),
            thickness: most(&|p| p.2),
        }
    }

    /// An upper bound of the highest point of the box [lo, hi] above the run's planes.
    fn highest(&self, lo: DVec3, hi: DVec3) -> f64 {
        let best = corners(lo, hi)
            .map(|x| {
                let d = x - self.centre;
                self.normal.dot(d) + self.spread_term(d)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        best + self.radius * (1.0 + self.spread) + self.thickness
    }

    /// A lower bound of the lowest point of the box [lo, hi] above every one of the run's
    /// planes: n_i · (x − a_i) + t_i ≥ m · (x − c) − δ |x − c| − ρ, least at a corner
    /// (a linear term less a convex one).
    fn lowest(&self, lo: DVec3, hi: DVec3) -> f64 {
        let worst = corners(lo, hi)
            .map(|x| {
                let d = x - self.centre;
                self.normal.dot(d) - self.spread_term(d)
            })
            .fold(f64::INFINITY, f64::min);
        worst - self.radius
    }

    /// δ |d| (nothing to compute for one plane).
    fn spread_term(&self, d: DVec3) -> f64 {
        if self.spread > 0.0 {
            self.spread * d.length()
        } else {
            0.0
        }
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

/// The highest corner of the box [lo, hi] above the plane through `at` facing `normal`.
pub(crate) fn highest(lo: DVec3, hi: DVec3, normal: DVec3, at: DVec3) -> f64 {
    corners(lo, hi)
        .map(|x| normal.dot(x - at))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The lowest and highest corner of `points`' box.
pub(crate) fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
        (lo.min(p), hi.max(p))
    })
}

/// The least and the most of `scales`.
fn widest(scales: impl Iterator<Item = ReachScale>) -> ReachScale {
    scales.fold((f64::INFINITY, 0.0), |(least, most), (l, m)| {
        (least.min(l), f64::max(most, m))
    })
}

/// The Morton code of a point's 10-bit grid coordinates.
fn morton(x: u64, y: u64, z: u64) -> u64 {
    // Spreads 10 bits to every third of 30.
    let spread = |mut v: u64| {
        v &= 0x3ff;
        v = (v | (v << 16)) & 0x0300_00ff;
        v = (v | (v << 8)) & 0x0300_f00f;
        v = (v | (v << 4)) & 0x030c_30c3;
        (v | (v << 2)) & 0x0924_9249
    };
    spread(x) | (spread(y) << 1) | (spread(z) << 2)
}

/// Nearest distance from `p` to the box [lo, hi].
pub(crate) fn nearest(lo: DVec3, hi: DVec3, p: DVec3) -> f64 {
    p.clamp(lo, hi).distance(p)
}

/// Farthest distance from `p` to the box [lo, hi].
pub(crate) fn farthest(lo: DVec3, hi: DVec3, p: DVec3) -> f64 {
    (p - lo).abs().max((hi - p).abs()).length()
}

/// Links `plan`'s cells (each with mean unshot `radiosity`, lm/m²) to the
/// receivers for the link error `epsilon` (lux): each cell's reach, and which cells are
/// drawn.
///
/// A coarse cell is used only where it saves visibility maps: drawing it costs one map,
/// and it spares its subtree the receivers beyond its reach. Each cell takes the cheaper
/// choice given its ancestors' (a small search over at most [`LINK_LEVELS`] levels; a
/// tie keeps the finer cells). In a small room every fine cell has a wall within reach,
/// so nothing coarse is used; in a hall the far side takes a floor's light from a few
/// cells.
pub fn link(plan: &ShotPlan, radiosity: &[f64], receivers: &ReceiverBoxes, epsilon: f64) -> Links {
    let patches = &plan.patches;
    let oracle: Vec<f64> = patches
        .iter()
        .zip(variation(plan, radiosity))
        .map(|(p, dv)| reach(p.level, p.radius, p.element_area, dv, epsilon))
        .collect();
    let search = Search {
        plan,
        children: plan.children(),
        oracle: &oracle,
        receivers,
        slack: receivers.pad + SLACK * receivers.size,
    };
    let mut reach: Vec<f64> = patches
        .iter()
        .map(|p| if p.level == 0 { 0.0 } else { f64::INFINITY })
        .collect();
    let mut drawn = vec![false; patches.len()];
    for k in (0..patches.len()).filter(|&k| patches[k].parent == u32::MAX) {
        let (_, choice) = search.cheapest(k, &[]);
        for (cell, used, draw) in choice {
            if used {
                reach[cell] = oracle[cell];
            }
            drawn[cell] = draw;
        }
    }
    Links { reach, drawn }
}

/// The search for the cheapest links of one plan.
struct Search<'a> {
    plan: &'a ShotPlan,
    children: Vec<Vec<u32>>,
    oracle: &'a [f64],
    receivers: &'a ReceiverBoxes,
    /// Absolute slack of the conservative questions, metres.
    slack: f64,
}

impl Search<'_> {
    /// Whether the box [lo, hi] is in front of cell `k`'s plane.
    fn in_front(&self, lo: DVec3, hi: DVec3, k: usize) -> bool {
        let cell = &self.plan.patches[k];
        let tolerance = self.receivers.plane_tolerance() - self.slack;
        highest(lo, hi, cell.normal, cell.centroid) > tolerance
    }

    /// Cell `k`'s reach for a receiver whose reach scale is `scale` ([`Links::reach_for`]).
    fn reach(&self, k: usize, scale: f64) -> f64 {
        self.oracle[k] * scale
    }

    /// Whether the box [lo, hi] (its receivers' reach scales `scale`) may hold a receiver
    /// within the reach of used cell `k`.
    fn within(&self, lo: DVec3, hi: DVec3, scale: ReachScale, k: usize) -> bool {
        let at = self.plan.patches[k].centroid;
        nearest(lo, hi, at) < self.reach(k, scale.1) * (1.0 + SLACK) + self.slack
    }

    /// Whether the box [lo, hi] (its receivers' reach scales `scale`) may hold a receiver
    /// beyond the reach of cell `k`.
    fn beyond(&self, lo: DVec3, hi: DVec3, scale: ReachScale, k: usize) -> bool {
        let at = self.plan.patches[k].centroid;
        farthest(lo, hi, at) >= self.reach(k, scale.0) * (1.0 - SLACK) - self.slack
    }

    /// Cell `k`'s subtree with nothing used or drawn (`k` last).
    fn idle(&self, k: usize) -> Vec<(usize, bool, bool)> {
        let mut out = Vec::new();
        let mut stack = vec![k];
        while let Some(c) = stack.pop() {
            out.push((c, false, false));
            stack.extend(self.children[c].iter().map(|&d| d as usize));
        }
        out.reverse();
        out
    }

    /// The fewest maps cell `k`'s subtree needs when the receivers are those in front and
    /// within the reach of every cell of `used` (its used ancestors), and the choices that
    /// give it: (cell, used, drawn).
    fn cheapest(&self, k: usize, used: &[usize]) -> (usize, Vec<(usize, bool, bool)>) {
        let level = self.plan.patches[k].level;
        let some = |extra: &dyn Fn(DVec3, DVec3, ReachScale) -> bool| {
            self.receivers.any_scaled(|lo, hi, scale| {
                self.in_front(lo, hi, k)
                    && used.iter().all(|&a| self.within(lo, hi, scale, a))
                    && extra(lo, hi, scale)
            })
        };
        if level == 0 {
            let draw = some(&|_, _, _| true);
            return (usize::from(draw), vec![(k, false, draw)]);
        }
        let subtree = |used: &[usize]| {
            let mut cost = 0;
            let mut choice = Vec::new();
            for &c in &self.children[k] {
                let (n, mut more) = self.cheapest(c as usize, used);
                cost += n;
                choice.append(&mut more);
            }
            (cost, choice)
        };
        if !some(&|_, _, _| true) {
            return (0, self.idle(k));
        }
        // Not used: every receiver looks further down.
        let (finer, mut finer_choice) = subtree(used);
        // Used: the receivers beyond its reach take its light, the rest look further down.
        let draw = some(&|lo, hi, scale| self.beyond(lo, hi, scale, k));
        let mut inner = used.to_vec();
        inner.push(k);
        let (below, mut below_choice) = if some(&|lo, hi, scale| self.within(lo, hi, scale, k)) {
            subtree(&inner)
        } else {
            let mut none = self.idle(k);
            none.pop();
            (0, none)
        };
        let coarse = usize::from(draw) + below;
        if coarse < finer {
            below_choice.push((k, true, draw));
            (coarse, below_choice)
        } else {
            finer_choice.push((k, false, false));
            (finer, finer_choice)
        }
    }
}

/// Whether a receiver at `p` whose reach scale is `scale` ([`Links::reach_for`]; 1
/// without a view) takes light from cell `k` of `plan` — the GPU receive pass's rule, in
/// f64: in front of the cell's plane (beyond `tolerance`), beyond the cell's reach and
/// within every ancestor's; nearer the plane, from top cells only.
pub fn takes_light_from(
    plan: &ShotPlan,
    links: &Links,
    k: usize,
    tolerance: f64,
    (p, scale): (DVec3, f64),
) -> bool {
    let cell = &plan.patches[k];
    if cell.normal.dot(p - cell.centroid) <= tolerance {
        return cell.parent == u32::MAX;
    }
    if p.distance(cell.centroid) < links.reach_for(k, scale) {
        return false;
    }
    let mut a = cell.parent;
    while a != u32::MAX {
        let up = &plan.patches[a as usize];
        if p.distance(up.centroid) >= links.reach_for(a as usize, scale) {
            return false;
        }
        a = up.parent;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pseudo-random numbers in [0, 1) (a fixed LCG: the test is reproducible).
    fn numbers(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn culling_takes_exactly_the_charts_whose_own_box_passes() {
        let mut r = numbers(7);
        let boxes: Vec<(DVec3, DVec3)> = (0..3000)
            .map(|_| {
                let lo = DVec3::new(r(), r(), r()) * 20.0;
                (lo, lo + DVec3::new(r(), r(), r()) * 0.5)
            })
            .collect();
        let ranges: Vec<(u32, u32)> = (0..boxes.len() as u32).map(|i| (2 * i, 2)).collect();
        let receivers = ReceiverBoxes::from_boxes(boxes.clone(), ranges.clone());
        let slack = receivers.pad + SLACK * receivers.size;
        // One plane, a few (one run each) and many (runs of several, a cone each).
        for count in [1, 3, 70, 200] {
            let planes: Vec<(DVec3, DVec3, f64)> = (0..count)
                .map(|_| {
                    let n = DVec3::new(r() - 0.5, r() - 0.5, r() - 0.5).normalize();
                    (n, DVec3::new(r(), r(), r()) * 20.0, 0.1 * r())
                })
                .collect();
            let runs: Vec<PlaneRun> = planes
                .chunks(planes.len().div_ceil(MAX_CULLING_PLANES).max(1))
                .map(PlaneRun::new)
                .collect();
            let mut want: Vec<(u32, u32)> = boxes
                .iter()
                .zip(&ranges)
                .filter(|((lo, hi), _)| runs.iter().any(|run| run.highest(*lo, *hi) > -slack))
                .map(|(_, &range)| range)
                .collect();
            want.sort_unstable();
            let got = receivers.in_front_of_any(&planes);
            assert_eq!(got, want, "{count} planes");
            // By groups: every chart of the exact answer, each once, and (with few
            // planes) still not everything.
            let exact = receivers.charts_in_front_of_any(&planes);
            let mut rough = receivers.charts_roughly_in_front_of_any(&planes, 16);
            rough.sort_unstable();
            assert!(rough.windows(2).all(|w| w[0] < w[1]), "{count}: a repeat");
            assert!(
                exact.iter().all(|k| rough.binary_search(k).is_ok()),
                "{count}"
            );
            assert!(rough.len() >= exact.len());
            if count <= 3 {
                assert!(rough.len() < boxes.len(), "{count}: {}", rough.len());
            }
            let mut one = receivers.charts_roughly_in_front_of_any(&planes, 1);
            one.sort_unstable();
            let mut exact_sorted = exact.clone();
            exact_sorted.sort_unstable();
            assert_eq!(one, exact_sorted, "{count}: group 1 is exact");
            // A subset's hierarchy finds exactly the subset's charts the whole one does.
            let some: Vec<usize> = (0..boxes.len()).filter(|k| k % 7 < 2).collect();
            let sub = receivers.subset(&some);
            let mut from_sub: Vec<usize> = sub
                .charts_in_front_of_any(&planes)
                .into_iter()
                .map(|k| some[k])
                .collect();
            from_sub.sort_unstable();
            let mut want_sub = exact_sorted.clone();
            want_sub.retain(|k| k % 7 < 2);
            assert_eq!(from_sub, want_sub, "{count}: the subset");
            assert!(!got.is_empty(), "{count} planes");
            if count <= 3 {
                assert!(got.len() < boxes.len(), "{count}: {}", got.len());
            }
            // And every box corner in front of a plane is in a taken chart.
            for ((lo, hi), range) in boxes.iter().zip(&ranges) {
                let in_front = corners(*lo, *hi)
                    .any(|x| planes.iter().any(|(n, a, t)| n.dot(x - *a) + t > 0.0));
                assert!(!in_front || got.binary_search(range).is_ok());
            }
        }
    }

    #[test]
    fn merged_ranges_cover_exactly_the_charts_asked_for() {
        let mut r = numbers(11);
        // Charts of 1–3 elements, laid out one after another, but for a gap after
        // every seventh (as charts without elements leave none: a jump in `first`).
        let mut first = 0u32;
        let ranges: Vec<(u32, u32)> = (0..2000)
            .map(|k| {
                let count = 1 + (r() * 3.0) as u32;
                let range = (first, count);
                first += count + u32::from(k % 7 == 6);
                range
            })
            .collect();
        let boxes = vec![(DVec3::ZERO, DVec3::ONE); ranges.len()];
        let receivers = ReceiverBoxes::from_boxes(boxes, ranges.clone());
        // Few charts (sorted path) and many (marked path), in shuffled order.
        for share in [0.01, 0.5, 0.97, 1.0] {
            let mut charts: Vec<usize> = (0..ranges.len()).filter(|_| r() < share).collect();
            for i in (1..charts.len()).rev() {
                charts.swap(i, (r() * (i + 1) as f64) as usize);
            }
            let merged = receivers.merged_ranges(&charts);
            let elements = |list: &[(u32, u32)]| -> Vec<u32> {
                let mut e: Vec<u32> = list.iter().flat_map(|&(f, c)| f..f + c).collect();
                e.sort_unstable();
                e
            };
            let asked: Vec<(u32, u32)> = charts.iter().map(|&k| ranges[k]).collect();
            assert_eq!(elements(&merged), elements(&asked), "share {share}");
            // Sorted, and no two records that could have been one.
            assert!(
                merged.windows(2).all(|w| w[0].0 + w[0].1 < w[1].0),
                "{share}"
            );
            if share == 1.0 {
                // Only the gaps split them: one record per run of seven charts.
                assert_eq!(merged.len(), ranges.len().div_ceil(7));
            }
        }
        assert!(receivers.merged_ranges(&[]).is_empty());
    }

    #[test]
    fn a_runs_lowest_point_bounds_every_plane_from_below() {
        let mut r = numbers(11);
        for _ in 0..200 {
            let planes: Vec<(DVec3, DVec3, f64)> = (0..5)
                .map(|_| {
                    let n = (DVec3::Z + DVec3::new(r() - 0.5, r() - 0.5, 0.0)).normalize();
                    (n, DVec3::new(r(), r(), r()), 0.05 * r())
                })
                .collect();
            let run = PlaneRun::new(&planes);
            let lo = DVec3::new(r(), r(), r()) * 4.0 - 2.0;
            let hi = lo + DVec3::new(r(), r(), r());
            let bound = run.lowest(lo, hi);
            let upper = run.highest(lo, hi);
            for x in corners(lo, hi) {
                for (n, a, t) in &planes {
                    let h = n.dot(x - *a) + t;
                    assert!(
                        h >= bound - 1e-12 && h <= upper + 1e-12,
                        "{h} not in [{bound}, {upper}]"
                    );
                }
            }
        }
    }
}
