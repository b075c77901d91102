//! Where adaptive subdivision splits: the luminaires' shadow boundaries (Wallner §2.4).
//!
//! Wallner renders the scene from each shooter three times and compares, per triangle,
//! the fragments rasterized (n_r) with the fragments visible (n_v); a triangle with
//! b_l ≤ n_v / n_r ≤ b_u holds a shadow boundary and is split. Here the fragments are
//! the centroids of a block's finest elements, the shooters are the luminaires (the
//! first and strongest shot, and the only one from points: the hard shadows), and
//! visibility is a ray against the casters (with their alpha-mask holes, each
//! luminaire's own housing left out). A point that faces a luminaire counts in n_r; it
//! counts in n_v when no caster is in the way and the luminaire sends it at least 1 % of
//! the brightest point's illuminance in the block, so the edge of a beam (a downlight's
//! cut-off) splits as a shadow's edge does.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;

use super::elements::{SplitTest, Subdivision};
use crate::photometry::Interp;
use crate::scene::PlacedLuminaire;
use crate::shadow::{IgnoredTriangles, Light, TriangleBvh};

/// Below this share of the block's brightest illuminance from a luminaire, a point is
/// dark.
const DARK: f64 = 0.5;

/// Splits blocks that straddle a luminaire's shadow or beam edge.
pub struct LuminaireShadowEdges<'a> {
    /// The luminaires.
    pub luminaires: &'a [PlacedLuminaire],
    /// Ray casts against the casters.
    pub bvh: &'a TriangleBvh,
    /// Per luminaire, its housing's triangles.
    pub ignored: &'a [IgnoredTriangles],
    /// How far rays start off surfaces, metres.
    pub eps: f64,
    /// The bounds on the lit share.
    pub subdivision: Subdivision,
    /// Nanoseconds spent in [`SplitTest::split`], summed over the threads.
    pub nanos: AtomicU64,
}

impl SplitTest for LuminaireShadowEdges<'_> {
    fn split(&self, points: &[DVec3], normal: DVec3) -> bool {
        let started = std::time::Instant::now();
        let split = self.any_luminaire_edge(points, normal);
        let nanos = started.elapsed().as_nanos().min(u128::from(u64::MAX)) as u64;
        self.nanos.fetch_add(nanos, Ordering::Relaxed);
        split
    }
}

impl LuminaireShadowEdges<'_> {
    /// CPU seconds spent deciding splits so far.
    pub fn seconds(&self) -> f64 {
        self.nanos.load(Ordering::Relaxed) as f64 * 1e-9
    }

    fn any_luminaire_edge(&self, points: &[DVec3], normal: DVec3) -> bool {
        let none = IgnoredTriangles::default();
        self.luminaires.iter().enumerate().any(|(k, l)| {
            let lux: Vec<f64> = points
                .iter()
                .map(|&p| l.illuminance_at(p, normal, Interp::CatmullRom))
                .collect();
            let facing = points
                .iter()
                .filter(|&&p| normal.dot(l.position - p) > 0.0)
                .count();
            let brightest = lux.iter().copied().fold(0.0, f64::max);
            if facing < 2 || brightest <= 0.0 {
                return false;
            }
            let light = Light(l.position.extend(1.0));
            let ignored = self.ignored.get(k).unwrap_or(&none);
            let lit = points
                .iter()
                .zip(&lux)
                .filter(|&(&p, &e)| {
                    e >= DARK * brightest
                        && !self
                            .bvh
                            .in_shadow(&light, p + normal * self.eps, self.eps, ignored)
                })
                .count();
            self.subdivision.partial(lit, facing)
        })
    }
}
