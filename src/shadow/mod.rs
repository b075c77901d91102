//! Shadows: silhouettes (brute force and the 4D dual-space hextree), shadow-volume
//! geometry, the z-pass/z-fail decision and a CPU ray-cast reference.

pub mod bvh;
pub mod cutout;
pub mod hextree;
pub mod raycast;
pub mod silhouette;
pub mod sun_rays;
pub mod technique;
pub mod volume;

use glam::{DVec3, DVec4};

pub use bvh::TriangleBvh;
pub use cutout::Cutouts;
pub use hextree::Hextree;
pub use silhouette::{Silhouette, SilhouetteMesh};
pub use technique::{ShadowTechnique, VolumeTest};

/// Triangles of a caster mesh that one light ignores: its own housing (a measured
/// distribution already contains the shadow of the luminaire's own body), as ranges of
/// triangle indices.
#[derive(Debug, Clone, Default, PartialEq, Eq, Hash)]
pub struct IgnoredTriangles(pub Vec<std::ops::Range<usize>>);

impl IgnoredTriangles {
    /// Whether triangle `k` is ignored.
    pub fn contains(&self, k: usize) -> bool {
        self.0.iter().any(|r| r.contains(&k))
    }

    /// Whether no triangle is ignored.
    pub fn is_empty(&self) -> bool {
        self.0.iter().all(|r| r.is_empty())
    }

    /// The ranges of `0..count` that are not ignored, in order.
    pub fn kept(&self, count: usize) -> Vec<std::ops::Range<usize>> {
        let mut cut: Vec<_> = self.0.iter().filter(|r| !r.is_empty()).cloned().collect();
        cut.sort_by_key(|r| r.start);
        let mut out = Vec::new();
        let mut at = 0;
        for r in cut {
            if r.start > at {
                out.push(at..r.start.min(count));
            }
            at = at.max(r.end);
        }
        if at < count {
            out.push(at..count);
        }
        out.retain(|r| !r.is_empty());
        out
    }
}

/// How to find silhouette edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum SilhouetteMethod {
    /// Test every edge.
    Brute,
    /// The 4D dual-space hextree.
    #[default]
    Hextree,
}

/// A light as a homogeneous position: w = 1 a point light at (x, y, z), w = 0 a light
/// at infinity in direction (x, y, z) from the scene (for the sun: toward the sun).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light(pub DVec4);

impl Light {
    /// Checks and normalises `[x, y, z, w]`: finite, w ≥ 0 (w > 0 is divided out), and a
    /// non-zero direction when w = 0.
    pub fn new(v: [f64; 4]) -> Result<Light, String> {
        if v.iter().any(|x| !x.is_finite()) {
            return Err(format!("light {v:?} is not finite"));
        }
        let [x, y, z, w] = v;
        if w < 0.0 {
            return Err(format!("light W must be 0 or positive, got {w}"));
        }
        if w == 0.0 {
            let d = DVec3::new(x, y, z);
            if d.length_squared() == 0.0 {
                return Err("a directional light (W = 0) needs a non-zero direction".into());
            }
            return Ok(Light(d.normalize().extend(0.0)));
        }
        Ok(Light(DVec4::new(x / w, y / w, z / w, 1.0)))
    }

    /// True for a light at infinity.
    pub fn is_directional(&self) -> bool {
        self.0.w == 0.0
    }

    /// Unit direction from `p` toward the light.
    pub fn direction_from(&self, p: DVec3) -> DVec3 {
        if self.is_directional() {
            self.0.truncate()
        } else {
            (self.0.truncate() - p).normalize_or_zero()
        }
    }
}
