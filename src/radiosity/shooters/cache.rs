//! Shooting units already planned, kept for the next time they shoot alike.
//!
//! A piece's cells depend only on the piece, the cell side the oracle picked and the
//! levels above it; a merged cell only on its pieces. Progressive radiosity shoots the
//! same surfaces again and again (light comes back to them), and the oracle's side moves
//! in powers of two of the finest cell, so most shots repeat a layout already made. Laying
//! out a large cluster's grid (binning, clipping its triangles to the cells at every
//! level, the cells' outlines) cost 2.3 ms a shot on the cathedral; a hit is a copy.

use std::collections::HashMap;

use super::ShotPlan;

/// What a planned unit is, exactly: the same key always gives the same plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UnitKey {
    /// Piece `piece` from cells of side `side_bits` (`f64::to_bits`) with `levels` coarser
    /// levels.
    Piece {
        /// Index into [`super::Shooters::pieces`].
        piece: u32,
        /// The cell side, metres, as bits.
        side_bits: u64,
        /// Coarser levels asked for.
        levels: u32,
    },
    /// Pieces `first..end` shot as one merged cell under face cluster `node`.
    Merged {
        /// First piece.
        first: u32,
        /// One past the last piece.
        end: u32,
        /// Their face cluster.
        node: u32,
    },
}

/// Plans of shooting units, up to a memory budget (cleared whole when it would be
/// exceeded: the units that shoot again are planned again and come back).
#[derive(Debug, Default)]
pub struct PlanCache {
    plans: HashMap<UnitKey, ShotPlan>,
    /// Bytes held (element order, patches and their polygons), roughly.
    bytes: usize,
    /// Most bytes held before it is cleared.
    budget: usize,
    /// Plans found here.
    pub hits: u64,
    /// Plans made.
    pub misses: u64,
}

/// Default memory budget of a [`PlanCache`], bytes.
pub const DEFAULT_PLAN_CACHE_BYTES: usize = 256 << 20;

impl PlanCache {
    /// An empty cache holding at most about `budget` bytes (0: holds nothing).
    pub fn new(budget: usize) -> PlanCache {
        PlanCache {
            budget,
            ..PlanCache::default()
        }
    }

    /// The plan of `key`, made by `make` unless it is held.
    pub fn get_or_make(&mut self, key: UnitKey, make: impl FnOnce() -> ShotPlan) -> ShotPlan {
        if let Some(plan) = self.plans.get(&key) {
            self.hits += 1;
            return plan.clone();
        }
        self.misses += 1;
        let plan = make();
        let size = plan_bytes(&plan);
        if size > self.budget {
            return plan;
        }
        if self.bytes + size > self.budget {
            self.plans.clear();
            self.bytes = 0;
        }
        self.bytes += size;
        self.plans.insert(key, plan.clone());
        plan
    }

    /// Bytes held, roughly.
    pub fn bytes(&self) -> usize {
        self.bytes
    }
}

/// A plan's size in memory, roughly.
fn plan_bytes(plan: &ShotPlan) -> usize {
    let patch = std::mem::size_of::<super::PlannedPatch>();
    let point = std::mem::size_of::<glam::DVec3>();
    4 * plan.order.len()
        + plan
            .patches
            .iter()
            .map(|p| patch + point * p.polygon.len())
            .sum::<usize>()
        + 64
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(elements: u32) -> ShotPlan {
        ShotPlan {
            order: (0..elements).collect(),
            patches: Vec::new(),
            shot: elements,
        }
    }

    fn key(piece: u32) -> UnitKey {
        UnitKey::Piece {
            piece,
            side_bits: 0.5f64.to_bits(),
            levels: 4,
        }
    }

    #[test]
    fn a_held_plan_is_not_made_again_and_a_full_cache_starts_over() {
        let one = plan_bytes(&plan(100));
        let mut cache = PlanCache::new(2 * one);
        let mut made = 0;
        for k in [0, 1, 0, 1] {
            let p = cache.get_or_make(key(k), || {
                made += 1;
                plan(100)
            });
            assert_eq!(p, plan(100));
        }
        assert_eq!((made, cache.hits, cache.misses), (2, 2, 2));
        assert_eq!(cache.bytes(), 2 * one);
        // A third unit does not fit: the cache is emptied and holds the new one only.
        cache.get_or_make(key(2), || plan(100));
        assert_eq!(cache.bytes(), one);
        cache.get_or_make(key(0), || plan(100));
        assert_eq!(cache.misses, 4, "unit 0 was dropped and made again");
        // A plan larger than the whole budget is made and not kept.
        cache.get_or_make(key(3), || plan(10_000));
        assert_eq!(cache.bytes(), 2 * one);
        assert!(!cache.plans.contains_key(&key(3)));
    }
}
