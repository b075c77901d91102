//! The model's facades and window points of a study, set up once and solved per date.

use glam::DVec2;

use super::mask::{MaskRays, ObstructionMask};
use super::shadow_profile::Profile;
use super::surface_output::SurfaceResults;
use super::surfaces::{
    facade_hours, find_facades, surface_offset, Facade, Sun, SunRays, WindowPoint,
};
use crate::geometry::Mesh;
use crate::shadow::bvh::TriangleBvh;
use crate::shadow::IgnoredTriangles;
use crate::sun::direction_from_angles;

/// The facades of a study: every vertical face of the model, on square cells.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacadeOptions {
    /// Side of a facade cell, metres (at least 0.01).
    pub cell_m: f64,
    /// Facades smaller than this are left out, m².
    pub min_area_m2: f64,
}

impl Default for FacadeOptions {
    /// Cells of 0.5 m, facades of at least 1 m² (as `profile --facades`).
    fn default() -> Self {
        FacadeOptions {
            cell_m: 0.5,
            min_area_m2: 1.0,
        }
    }
}

/// The model's facades and the window points, set up once for every date.
pub struct SurfaceSet {
    bvh: Option<TriangleBvh>,
    facades: Vec<Facade>,
    points: Vec<WindowPoint>,
    origin: DVec2,
    min_elevation_deg: f64,
    eps: f64,
    non_casters: IgnoredTriangles,
    north_offset_deg: f64,
    /// Per window point, the sky the model hides from it (the same on every date).
    masks: Vec<ObstructionMask>,
}

/// Where a study's surfaces are and how it counts the sun on them.
#[derive(Debug, Clone)]
pub struct SurfaceSetup<'a> {
    /// The facades, when asked for.
    pub facades: Option<FacadeOptions>,
    /// The window points (the model file's plan coordinates and heights).
    pub points: &'a [WindowPoint],
    /// The model's plan centre that [`super::model::recentre`] took away.
    pub origin: DVec2,
    /// The triangles that cast no shadow.
    pub non_casters: &'a IgnoredTriangles,
    /// The model's +Y from true north, clockwise, degrees.
    pub north_offset_deg: f64,
    /// The lowest sun counted, degrees.
    pub min_elevation_deg: f64,
}

impl SurfaceSet {
    /// The facades of `model` (recentred) and the window points with their obstruction
    /// masks.
    pub fn new(model: &Mesh, setup: SurfaceSetup<'_>) -> Self {
        let wanted = setup.facades.is_some() || !setup.points.is_empty();
        let facades = match setup.facades {
            Some(f) => find_facades(model, f.cell_m, f.min_area_m2),
            None => Vec::new(),
        };
        let bvh = wanted.then(|| TriangleBvh::new(model));
        let eps = surface_offset(model);
        let masks = match &bvh {
            Some(bvh) => {
                let rays = MaskRays {
                    bvh,
                    eps,
                    non_casters: setup.non_casters,
                    north_offset_deg: setup.north_offset_deg,
                };
                setup
                    .points
                    .iter()
                    .map(|p| {
                        let (world, normal) = point_frame(p, setup.origin);
                        ObstructionMask::cast(&rays, &p.name, world, normal)
                    })
                    .collect()
            }
            None => Vec::new(),
        };
        SurfaceSet {
            bvh,
            facades,
            points: setup.points.to_vec(),
            origin: setup.origin,
            min_elevation_deg: setup.min_elevation_deg,
            eps,
            non_casters: setup.non_casters.clone(),
            north_offset_deg: setup.north_offset_deg,
            masks,
        }
    }

    /// The facades found (their hours not yet counted).
    pub fn facades(&self) -> &[Facade] {
        &self.facades
    }

    /// Per window point, the sky the model hides from it.
    pub fn masks(&self) -> &[ObstructionMask] {
        &self.masks
    }

    /// The hours on the facades and at the points under `profile`'s suns (`None` when the
    /// study has neither).
    pub fn for_profile(&self, profile: &Profile) -> Option<SurfaceResults> {
        let bvh = self.bvh.as_ref()?;
        let suns: Vec<Sun> = profile
            .steps
            .iter()
            .map(|s| Sun {
                direction: direction_from_angles(
                    s.azimuth_deg,
                    s.elevation_deg,
                    self.north_offset_deg,
                ),
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
