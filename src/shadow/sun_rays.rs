//! Hours of direct sun at points of a model's surfaces, by CPU ray casts through the BVH:
//! a point gets a sun's weight when the sun is in front of it (above its plane), above the
//! minimum elevation, and the ray toward the sun meets nothing. The sun study's facades and
//! window points and the planning tests' windows and open spaces count their hours so.

use glam::DVec3;

use crate::geometry::Mesh;
use crate::shadow::bvh::TriangleBvh;
use crate::shadow::IgnoredTriangles;

/// One step's sun: the unit vector toward it (world frame) and the hours it stands for.
#[derive(Debug, Clone, Copy)]
pub struct Sun {
    /// Toward the sun, world frame.
    pub direction: DVec3,
    /// Its elevation, degrees.
    pub elevation_deg: f64,
    /// The hours the step stands for.
    pub weight_h: f64,
}

/// What a surface point's hours are cast against: the model's BVH, the steps' suns, the
/// lowest sun counted, the offset off the surface, and the triangles that cast no shadow.
#[derive(Clone, Copy)]
pub struct SunRays<'a> {
    /// The model.
    pub bvh: &'a TriangleBvh,
    /// The steps' suns.
    pub suns: &'a [Sun],
    /// Suns lower than this are not counted, degrees.
    pub min_elevation_deg: f64,
    /// How far a point is moved off its surface along its normal, metres.
    pub eps: f64,
    /// Triangles that cast no shadow.
    pub non_casters: &'a IgnoredTriangles,
}

impl SunRays<'_> {
    /// Hours of direct sun at `point` on a surface facing `normal` (unit).
    pub fn hours_at(&self, point: DVec3, normal: DVec3) -> f64 {
        let origin = point + normal * self.eps;
        self.suns
            .iter()
            .filter(|s| {
                s.elevation_deg >= self.min_elevation_deg
                    && s.direction.dot(normal) > 0.0
                    && !self
                        .bvh
                        .blocked(origin, s.direction, 0.0, f64::INFINITY, self.non_casters)
            })
            .map(|s| s.weight_h)
            .sum::<f64>()
            + 0.0 // an empty sum is −0.0
    }
}

/// The distance a surface point is moved off its surface before its rays leave: a
/// millionth of the model's size, at least 0.1 mm.
pub fn surface_offset(mesh: &Mesh) -> f64 {
    mesh.bounds()
        .map_or(1e-4, |(lo, hi)| ((hi - lo).length() * 1e-6).max(1e-4))
}
