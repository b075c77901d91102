//! The model's facades and window points of a study, set up once and solved per date.

use glam::DVec2;

use super::ProfileArgs;
use crate::geometry::Mesh;
use crate::shadow::bvh::TriangleBvh;
use crate::shadow::IgnoredTriangles;
use crate::study::mask::{MaskRays, ObstructionMask};
use crate::study::profile::Profile;
use crate::study::surface_output::SurfaceResults;
use crate::study::surfaces::{
    facade_hours, find_facades, surface_offset, Facade, Sun, SunRays, WindowPoint,
};
use crate::sun::direction_from_angles;

/// The model's facades and the window points, set up once for every date.
pub(super) struct Surfaces {
    bvh: Option<TriangleBvh>,
    facades: Vec<Facade>,
    points: Vec<WindowPoint>,
    origin: DVec2,
    min_elevation_deg: f64,
    eps: f64,
    non_casters: IgnoredTriangles,
    /// Per window point, the sky the model hides from it (the same on every date).
    masks: Vec<ObstructionMask>,
}

impl Surfaces {
    pub(super) fn new(
        a: &ProfileArgs,
        model: &Mesh,
        origin: DVec2,
        points: Vec<WindowPoint>,
        non_casters: IgnoredTriangles,
    ) -> Self {
        let wanted = a.facades || !points.is_empty();
        let facades = if a.facades {
            find_facades(model, a.facade_cell, a.min_facade_area)
        } else {
            Vec::new()
        };
        if a.facades {
            eprintln!(
                "{}: {} facade(s) of at least {} m², {} cells",
                a.model.display(),
                facades.len(),
                a.min_facade_area,
                facades
                    .iter()
                    .map(|f| f.hours.iter().flatten().count())
                    .sum::<usize>()
            );
        }
        let bvh = wanted.then(|| TriangleBvh::new(model));
        let eps = surface_offset(model);
        let masks = match &bvh {
            Some(bvh) => {
                let rays = MaskRays {
                    bvh,
                    eps,
                    non_casters: &non_casters,
                    north_offset_deg: a.north_offset,
                };
                points
                    .iter()
                    .map(|p| {
                        let (world, normal) = point_frame(p, origin);
                        ObstructionMask::cast(&rays, &p.name, world, normal)
                    })
                    .collect()
            }
            None => Vec::new(),
        };
        Surfaces {
            bvh,
            facades,
            points,
            origin,
            min_elevation_deg: a.min_elevation,
            eps,
            non_casters,
            masks,
        }
    }

    /// Per window point, the sky the model hides from it.
    pub(super) fn masks(&self) -> &[ObstructionMask] {
        &self.masks
    }

    /// The hours on the facades and at the points under `profile`'s suns.
    pub(super) fn for_profile(
        &self,
        profile: &Profile,
        north_offset_deg: f64,
    ) -> Option<SurfaceResults> {
        let bvh = self.bvh.as_ref()?;
        let suns: Vec<Sun> = profile
            .steps
            .iter()
            .map(|s| Sun {
                direction: direction_from_angles(s.azimuth_deg, s.elevation_deg, north_offset_deg),
                elevation_deg: s.elevation_deg,
                weight_h: s.weight_h,
            })
            .collect();
        let mut facades = self.facades.clone();
        let rays = SunRays {
            bvh,
            suns: &suns,
            min_elevation_deg: self.min_elevation_deg,
            eps: self.eps,
            non_casters: &self.non_casters,
        };
        facade_hours(&rays, &mut facades);
        let points = self
            .points
            .iter()
            .map(|p| {
                let (world, normal) = point_frame(p, self.origin);
                let hours = rays.hours_at(world, normal);
                (p.clone(), hours)
            })
            .collect();
        Some(SurfaceResults {
            facades,
            points,
            min_elevation_deg: self.min_elevation_deg,
        })
    }
}

/// A window point's position in the recentred model and its unit normal.
fn point_frame(p: &WindowPoint, origin: DVec2) -> (glam::DVec3, glam::DVec3) {
    let [x, y, z] = p.position;
    (
        glam::DVec3::new(x - origin.x, y - origin.y, z),
        crate::geometry::unit(glam::DVec3::from_array(p.normal))
            .expect("parse_points refused normals without a direction"),
    )
}
