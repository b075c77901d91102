//! Each drawn cell's own receivers: the receive pass of a cell dispatches only over the
//! receivers that may take its light, not over every receiver of its batch.
//!
//! With links ([`crate::radiosity::links`]) a fine cell lights only the receivers within
//! its used ancestors' reach, and a used coarse cell only those beyond its own: in an
//! open office most of a batch's receivers take a fine cell's light from one of its
//! ancestors, yet each of their threads ran the cell's receive pass to find that out (on
//! lavapipe three quarters of the GPU's time went into those passes). The receivers are
//! grouped by shooting patch (a patch's elements are contiguous and close together),
//! each group with the box of its element points and the least and most reach scale of
//! its elements; a cell's receivers are the groups of its batch's receiver ranges whose
//! box may hold one that takes its light, by the shader's rule with slack
//! ([`takes_light_from`](crate::radiosity::links::takes_light_from), conservative): every
//! receiver that takes light from the cell is still dispatched, so the solution is the
//! same. `tests/gpu/links.rs` checks it against that rule, receiver by receiver.

use glam::DVec3;

use crate::radiosity::links::{bounds, farthest, highest, nearest, Links, LINK_LEVELS};
use crate::radiosity::scene::RadiosityScene;
use crate::radiosity::shooters::ShotPlan;

/// One receive-pass record: elements `first..first + count` are threads
/// `before..before + count`; `hold` 1 where they keep what they receive back.
pub type ReceiverRecord = [u32; 4];

/// The receivers grouped by patch, with their boxes and reach scales.
pub struct ReceiverGroups {
    /// Per group, its first element (ascending) …
    first: Vec<u32>,
    /// … its element count …
    count: Vec<u32>,
    /// … the box of its element points (lowest, highest corner) …
    boxes: Vec<(DVec3, DVec3)>,
    /// … and the least and most reach scale of its elements.
    scales: Vec<(f64, f64)>,
    /// Absolute slack of the tests, metres (f32 positions and distances on the GPU).
    slack: f64,
}

/// Relative slack of the reach tests (f32 distances on the GPU).
const RELATIVE_SLACK: f64 = 1e-4;

impl ReceiverGroups {
    /// The groups of `scene`'s elements, one per patch, every reach scale 1.
    pub fn new(scene: &RadiosityScene) -> ReceiverGroups {
        let el = &scene.elements;
        let (mut first, mut count, mut boxes) = (Vec::new(), Vec::new(), Vec::new());
        for p in el.patches.iter().filter(|p| p.count > 0) {
            first.push(p.first);
            count.push(p.count);
            boxes.push(bounds(
                (p.first..p.first + p.count).map(|e| el.position[e as usize]),
            ));
        }
        // Patches come in element order (the range searches below rely on it).
        assert!(
            first.windows(2).all(|w| w[0] < w[1]),
            "patches in element order"
        );
        let (lo, hi) = bounds(boxes.iter().flat_map(|b| [b.0, b.1]));
        let size = if boxes.is_empty() {
            0.0
        } else {
            (hi - lo).length()
        };
        ReceiverGroups {
            scales: vec![(1.0, 1.0); first.len()],
            first,
            count,
            boxes,
            slack: 1e-5 * (1.0 + size),
        }
    }

    /// Gives the groups the least and most of their elements' reach `scale`.
    pub fn set_scales(&mut self, scale: &[f64]) {
        for (k, s) in self.scales.iter_mut().enumerate() {
            let range = self.first[k] as usize..(self.first[k] + self.count[k]) as usize;
            *s = scale[range]
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
                    (lo.min(v), hi.max(v))
                });
        }
    }

    /// The group holding element `e`, if any.
    pub fn group_of(&self, e: u32) -> Option<usize> {
        let g = self.first.partition_point(|&f| f <= e).checked_sub(1)?;
        (e < self.first[g] + self.count[g]).then_some(g)
    }

    /// Whether group `g` may hold a receiver that takes the light of cell `k` of `plan`
    /// linked by `links` (`tolerance`: the receivers' plane tolerance): false only where
    /// none of its elements does ([`crate::radiosity::links::takes_light_from`]).
    pub fn may_take(
        &self,
        (plan, links): (&ShotPlan, &Links),
        k: usize,
        tolerance: f64,
        g: usize,
    ) -> bool {
        let rule = CellRule::new(plan, links, k, tolerance, self.slack);
        let (lo, hi) = self.boxes[g];
        rule.may_take(lo, hi, self.scales[g])
    }

    /// The records of cell `k`'s receivers among the batch's `ranges` (first element,
    /// count, hold): the groups that may hold a receiver taking its light, appended to
    /// `out` (threads counted from 0). Returns its threads, or `None` (nothing appended)
    /// for a top cell no reach limits: its receivers are the batch's ranges whole. A
    /// range not made of whole groups is taken whole.
    pub fn cell_records(
        &self,
        (plan, links): (&ShotPlan, &Links),
        k: usize,
        tolerance: f64,
        ranges: &[(u32, u32, u32)],
        out: &mut Vec<ReceiverRecord>,
    ) -> Option<u32> {
        let rule = CellRule::new(plan, links, k, tolerance, self.slack);
        if rule.top && rule.reach <= 0.0 && rule.ancestors.is_empty() {
            // Neither a reach nor its plane limits it: the batch's ranges whole.
            return None;
        }
        let mut threads = 0u32;
        let start = out.len();
        // Each record joins the one before where it continues it.
        let mut push = |first: u32, count: u32, hold: u32, out: &mut Vec<ReceiverRecord>| {
            let continues = out.len() > start;
            match out.last_mut() {
                Some(r) if continues && r[0] + r[2] == first && r[3] == hold => r[2] += count,
                _ => out.push([first, threads, count, hold]),
            }
            threads += count;
        };
        for &(first, count, hold) in ranges {
            let end = first + count;
            let a = self.first.partition_point(|&f| f < first);
            let b = self.first.partition_point(|&f| f < end);
            let whole = a < self.first.len()
                && self.first[a] == first
                && b > a
                && self.first[b - 1] + self.count[b - 1] == end;
            if !whole {
                push(first, count, hold, out);
                continue;
            }
            for g in a..b {
                let (lo, hi) = self.boxes[g];
                if rule.may_take(lo, hi, self.scales[g]) {
                    push(self.first[g], self.count[g], hold, out);
                }
            }
        }
        Some(threads)
    }
}

/// The shader's rule for one cell ([`crate::radiosity::links::takes_light_from`]) asked
/// of a box of receivers: may one of them take the cell's light?
struct CellRule {
    centroid: DVec3,
    normal: DVec3,
    /// The cell's own reach (0: none), metres at scale 1.
    reach: f64,
    top: bool,
    tolerance: f64,
    /// The used ancestors' centres and reaches (the shader's at most [`LINK_LEVELS`]).
    ancestors: Vec<(DVec3, f64)>,
    slack: f64,
}

impl CellRule {
    fn new(plan: &ShotPlan, links: &Links, k: usize, tolerance: f64, slack: f64) -> CellRule {
        let cell = &plan.patches[k];
        let mut ancestors = Vec::new();
        let mut up = cell.parent;
        for _ in 0..LINK_LEVELS {
            if up == u32::MAX {
                break;
            }
            let reach = links.reach[up as usize];
            if reach.is_finite() {
                ancestors.push((plan.patches[up as usize].centroid, reach));
            }
            up = plan.patches[up as usize].parent;
        }
        CellRule {
            centroid: cell.centroid,
            normal: cell.normal,
            reach: links.reach[k],
            top: cell.parent == u32::MAX,
            tolerance,
            ancestors,
            slack,
        }
    }

    /// Whether a receiver in the box [lo, hi] whose reach scale lies in `scale` may take
    /// the cell's light (false only where none can).
    fn may_take(&self, lo: DVec3, hi: DVec3, (least, most): (f64, f64)) -> bool {
        let (grow, shrink) = (1.0 + RELATIVE_SLACK, 1.0 - RELATIVE_SLACK);
        // Next to or behind the plane a receiver takes a top cell's light whatever the
        // reaches, and no other cell's.
        let lowest = -highest(lo, hi, -self.normal, self.centroid);
        let wholly_in_front = lowest > self.tolerance + self.slack;
        if self.top && !wholly_in_front {
            return true;
        }
        if highest(lo, hi, self.normal, self.centroid) <= self.tolerance - self.slack {
            return false;
        }
        let far = farthest(lo, hi, self.centroid);
        if self.reach > 0.0 && far < self.reach * least * shrink - self.slack {
            return false;
        }
        self.ancestors
            .iter()
            .all(|&(at, reach)| nearest(lo, hi, at) < reach * most * grow + self.slack)
    }
}
