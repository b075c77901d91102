//! Illuminance at arbitrary points from a solution: every shooting patch's mean radiosity
//! times its form factor to the point, where the patch sees the point (a ray cast).
//! This is how `goniolight radiosity --points` adds the interreflected light at points
//! that are not on a surface (a work plane).

use glam::DVec3;
use rayon::prelude::*;

use super::form_factor::{self, FormFactorKind};
use super::scene::RadiosityScene;
use crate::lighting::SurfacePoint;
use crate::shadow::{raycast, IgnoredTriangles, Light};

/// Illuminance (lux, RGB) at `point` from every patch of `scene` with the element
/// `radiosity` (lm/m², RGB), emission included.
pub fn from_patches(
    scene: &RadiosityScene,
    radiosity: &[DVec3],
    point: &SurfacePoint,
    kind: FormFactorKind,
) -> DVec3 {
    let (p, n) = (point.position, point.normal.normalize_or_zero());
    let el = &scene.elements;
    let eps = raycast::self_hit_epsilon(&scene.casters);
    let (bvh, none) = (scene.caster_bvh(), IgnoredTriangles::default());
    let mut e = DVec3::ZERO;
    for te in &el.triangles {
        for patch in &el.patches[te.first_patch as usize..][..te.patch_count as usize] {
            let f = match kind {
                FormFactorKind::Disc => {
                    form_factor::disc(p, n, patch.centroid, te.normal, patch.area)
                }
                FormFactorKind::Polygon => form_factor::polygon(p, n, &patch.polygon, te.normal),
            };
            if f <= 0.0 {
                continue;
            }
            let light = Light((patch.centroid + te.normal * eps).extend(1.0));
            if bvh.in_shadow(&light, p + n * eps, eps, &none) {
                continue;
            }
            let range = patch.first as usize..(patch.first + patch.count) as usize;
            let power: DVec3 = range.map(|k| radiosity[k] * el.area[k]).sum();
            e += power / patch.area * f;
        }
    }
    e
}

/// [`from_patches`] at many points, in parallel.
pub fn at_points(
    scene: &RadiosityScene,
    radiosity: &[DVec3],
    points: &[SurfacePoint],
    kind: FormFactorKind,
) -> Vec<DVec3> {
    points
        .par_iter()
        .map(|p| from_patches(scene, radiosity, p, kind))
        .collect()
}
