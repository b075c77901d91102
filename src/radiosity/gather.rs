//! Illuminance at arbitrary points from a solution: every shooting patch's mean radiosity
//! times its form factor to the point, where the patch sees the point (a ray cast).
//! This is how `goniolight radiosity --points` adds the interreflected light at points
//! that are not on a surface (a work plane). The patches are the shooters' finest ones:
//! each triangle's patches without a hierarchy, each flat cluster's finest cells with one
//! (a floor of 500 strips is a few hundred cells, not thousands of strip patches).
//! Through mirrors and clear glass each patch also lights a point from its images
//! ([`super::specular`]), the legs ray-cast as in the CPU reference solver.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::form_factor::{self, FormFactorKind};
use super::scene::RadiosityScene;
use super::shooters::Shooters;
use super::specular::SpecularPath;
use crate::lighting::SurfacePoint;
use crate::shadow::{IgnoredTriangles, Light};

/// One patch to gather from: its polygon, where it sees from, and its mean radiosity.
#[derive(Debug, Clone)]
pub struct GatherPatch {
    /// Convex polygon, counter-clockwise from the front, metres.
    pub polygon: Vec<DVec3>,
    /// Where its visibility rays start, metres.
    pub centroid: DVec3,
    /// Unit normal.
    pub normal: DVec3,
    /// Polygon area, m².
    pub area: f64,
    /// Its elements' mean radiosity, lm/m² (RGB).
    pub radiosity: DVec3,
    /// Its images through the specular windows: path, imaged polygon and normal.
    pub images: Vec<(SpecularPath, Vec<DVec3>, DVec3)>,
}

/// The finest patches of every shooter with the element `radiosity` (lm/m², RGB).
pub fn patches(
    scene: &RadiosityScene,
    shooters: &Shooters,
    radiosity: &[DVec3],
) -> Vec<GatherPatch> {
    let el = &scene.elements;
    (0..shooters.len())
        .into_par_iter()
        .flat_map_iter(|s| {
            let plan = shooters.plan(scene, s, 0.0);
            plan.patches
                .into_iter()
                .map(|p| {
                    let members = &plan.order[p.first as usize..][..p.count as usize];
                    let power: DVec3 = members
                        .iter()
                        .map(|&e| radiosity[e as usize] * el.area[e as usize])
                        .sum();
                    GatherPatch {
                        radiosity: power / p.element_area.max(1e-300) * p.power_scale(),
                        images: scene.specular.images(&p.polygon, p.centroid, p.normal),
                        polygon: p.polygon,
                        centroid: p.centroid,
                        normal: p.normal,
                        area: p.area,
                    }
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Illuminance (lux, RGB) at `point` from `patches` (emission included).
pub fn from_patches(
    scene: &RadiosityScene,
    patches: &[GatherPatch],
    point: &SurfacePoint,
    kind: FormFactorKind,
) -> DVec3 {
    let (p, n) = (point.position, point.normal.normalize_or_zero());
    let eps = scene.self_hit_epsilon;
    let (bvh, none) = (scene.visibility_bvh(), IgnoredTriangles::default());
    let form_factor = |centroid: DVec3, polygon: &[DVec3], normal: DVec3, area: f64| match kind {
        FormFactorKind::Disc => form_factor::disc(p, n, centroid, normal, area),
        FormFactorKind::Polygon => form_factor::polygon(p, n, polygon, normal),
    };
    let mut e = DVec3::ZERO;
    for patch in patches {
        let source = patch.centroid + patch.normal * eps;
        for (path, polygon, normal) in &patch.images {
            let f = form_factor(path.virtual_source(), polygon, *normal, patch.area);
            let caster = scene.caster_bvh();
            if f > 0.0
                && scene
                    .specular
                    .trace(caster, source, path, p + n * eps, eps, &none)
                    .is_some()
            {
                e += path.weight * patch.radiosity * f;
            }
        }
        let f = form_factor(patch.centroid, &patch.polygon, patch.normal, patch.area);
        if f <= 0.0 {
            continue;
        }
        let light = Light(source.extend(1.0));
        if bvh.in_shadow(&light, p + n * eps, eps, &none) {
            continue;
        }
        e += patch.radiosity * f;
    }
    e
}

/// [`from_patches`] at many points, in parallel, calling `progress` with the number of
/// points done so far; `None` when `cancel` was set before all were done.
pub fn at_points(
    scene: &RadiosityScene,
    patches: &[GatherPatch],
    points: &[SurfacePoint],
    kind: FormFactorKind,
    cancel: &AtomicBool,
    progress: &(dyn Fn(usize) + Sync),
) -> Option<Vec<DVec3>> {
    let done = AtomicUsize::new(0);
    points
        .par_iter()
        .map(|p| {
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            let e = from_patches(scene, patches, p, kind);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Some(e)
        })
        .collect()
}
