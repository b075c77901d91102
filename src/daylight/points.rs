//! Daylight reaching points directly: the sky and the ground seen through the model's
//! openings and glazing (the sky component and the externally reflected component from
//! the ground plane), and the sun's disc. Every direction of the point's hemisphere is
//! followed by a ray: a clear pane passes it on ([`Glazing`], as often as panes are met),
//! anything else stops it (what surfaces reflect is the radiosity solution's business).
//! This is the CPU reference of daylight at points.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::DVec3;
use rayon::prelude::*;

use super::glazing::Glazing;
use super::sky::{Sky, SUN_DIAMETER_DEG};
use crate::geometry::Mesh;
use crate::lighting::SurfacePoint;
use crate::scene::Scene;
use crate::shadow::TriangleBvh;

/// Cells of a point's hemisphere (rings of equal angle from the normal, and the
/// azimuth): one ray each.
pub const HEMISPHERE_CELLS: (usize, usize) = (128, 512);
/// Cells of a radiosity element's hemisphere: what it reflects is averaged over many
/// elements on its way to a point, so a coarser sampling serves.
pub const ELEMENT_CELLS: (usize, usize) = (32, 128);
/// Rays over the sun's disc (an equal-area spiral).
pub const SUN_RAYS: usize = 19;
/// Most panes a ray passes before it counts as stopped.
const MOST_PANES: usize = 8;

/// What stands between a point and the sky.
#[derive(Debug, Clone, Copy)]
pub struct Obstructions<'a> {
    /// The model's triangles.
    pub mesh: &'a Mesh,
    /// Its ray-casting structure.
    pub bvh: &'a TriangleBvh,
    /// The glazing of each triangle (`None`: opaque).
    pub glazing: &'a [Option<Glazing>],
    /// Distance a ray starts from its point (and from each pane it passes), metres.
    pub eps: f64,
}

/// Daylight at a point, lux, by where it comes from.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DaylightAtPoint {
    /// From the sky, through openings and glazing (the sky component).
    pub sky: f64,
    /// From the ground below the horizon (ρ_g·E_h/π where the model has no ground of its own).
    pub ground: f64,
    /// From the sun's disc.
    pub sun: f64,
}

impl DaylightAtPoint {
    /// The sum, lux.
    pub fn total(&self) -> f64 {
        self.sky + self.ground + self.sun
    }
}

/// The glazing of each of `scene`'s caster triangles ([`Scene::caster_mesh`]'s order):
/// faces with `specular_transmittance` are clear panes (their transmittance at normal
/// incidence the mean of the channels, at most a non-absorbing pane's 0.918), every other
/// face is opaque (`None`).
pub fn scene_glazing(scene: &Scene) -> Vec<Option<Glazing>> {
    let most = Glazing::clearest().normal_transmittance();
    let panes: Vec<Option<Glazing>> = scene
        .materials
        .iter()
        .map(|m| {
            let t = f64::from(m.specular_transmittance.element_sum()) / 3.0;
            (t > 0.0)
                .then(|| Glazing::with_normal_transmittance(t.min(most)))
                .flatten()
        })
        .collect();
    scene
        .caster_materials()
        .iter()
        .map(|&m| panes.get(m).copied().flatten())
        .collect()
}

/// The daylight of `scene`'s sky at each point, its model the obstructions
/// ([`scene_glazing`]); `None` when the scene has no `[sky]`.
pub fn scene_daylight(scene: &Scene, points: &[SurfacePoint]) -> Option<Vec<DaylightAtPoint>> {
    let daylight = scene.daylight.as_ref()?;
    let mesh = scene.caster_mesh();
    let bvh = TriangleBvh::new(&mesh).with_cutouts(scene.caster_cutouts());
    let glazing = scene_glazing(scene);
    let obstructions = Obstructions {
        mesh: &mesh,
        bvh: &bvh,
        glazing: &glazing,
        eps: crate::shadow::raycast::self_hit_epsilon(&mesh),
    };
    Some(daylight_at_points(
        &daylight.sky,
        Some(&obstructions),
        points,
        HEMISPHERE_CELLS,
    ))
}

/// The daylight at each point (in parallel), its hemisphere in `cells` (rings from the
/// normal, and the azimuth; [`HEMISPHERE_CELLS`] for points, [`ELEMENT_CELLS`] for the radiosity
/// solution's elements).
pub fn daylight_at_points(
    sky: &Sky,
    obstructions: Option<&Obstructions>,
    points: &[SurfacePoint],
    cells: (usize, usize),
) -> Vec<DaylightAtPoint> {
    points
        .par_iter()
        .map(|p| daylight_at(sky, obstructions, p, cells))
        .collect()
}

/// Where in its azimuth cells a point's rays lie, in [0, 1): a hash of its position, so
/// that neighbouring points do not alias the same way, while a point gives the same value
/// whatever list it is in.
fn azimuth_offset(p: DVec3) -> f64 {
    let h = (p.dot(DVec3::new(12.9898, 78.233, 37.719)).sin() * 43_758.545_3).fract();
    h.abs()
}

/// The daylight at one point, its hemisphere in `cells`: one ray per cell, then more in
/// every cell whose share of light differs from a neighbour's (the edges of openings,
/// panes and obstructions: [`EDGE_RAYS`] across the edge the neighbours show, 2 along it),
/// so that an opening seen small or at a grazing angle is measured by its outline rather
/// than by whole cells.
pub fn daylight_at(
    sky: &Sky,
    obstructions: Option<&Obstructions>,
    point: &SurfacePoint,
    cells: (usize, usize),
) -> DaylightAtPoint {
    let n = point.normal.normalize();
    let hemisphere = Hemisphere::new(n, point.position, cells);
    let (n_r, n_a) = cells;
    let trace = |dir: DVec3| transmitted(obstructions, point.position, dir);
    let shares: Vec<f64> = (0..n_r * n_a)
        .map(|c| trace(hemisphere.direction(c / n_a, c % n_a, (0.5, 0.5))))
        .collect();
    let mut out = DaylightAtPoint::default();
    for i in 0..n_r {
        let weight = hemisphere.weight(i);
        for j in 0..n_a {
            let share = shares[i * n_a + j];
            // An edge: light on one side and none on the other, or a pane more or less
            // (a pane's smooth change with the angle is not an edge).
            let differs = |r: usize, a: usize| {
                let other = shares[r * n_a + a];
                (other - share).abs() > EDGE_STEP * other.max(share)
            };
            let across_rings = (i > 0 && differs(i - 1, j)) || (i + 1 < n_r && differs(i + 1, j));
            let along_ring = differs(i, (j + n_a - 1) % n_a) || differs(i, (j + 1) % n_a);
            let mut add = |dir: DVec3, lux: f64| {
                if dir.z > 0.0 {
                    out.sky += lux;
                } else {
                    out.ground += lux;
                }
            };
            if across_rings || along_ring {
                // Finely across the edge the neighbours show, coarsely along it.
                let (nu, nv) = match (across_rings, along_ring) {
                    (true, true) => (EDGE_RAYS / 2, EDGE_RAYS / 2),
                    (true, false) => (EDGE_RAYS, 2),
                    _ => (2, EDGE_RAYS),
                };
                let sub = weight / (nu * nv) as f64;
                for u in 0..nu {
                    for v in 0..nv {
                        let at = ((u as f64 + 0.5) / nu as f64, (v as f64 + 0.5) / nv as f64);
                        let dir = hemisphere.direction(i, j, at);
                        let passed = trace(dir);
                        if passed > 0.0 {
                            add(dir, sub * passed * sky.luminance(dir));
                        }
                    }
                }
            } else if share > 0.0 {
                let dir = hemisphere.direction(i, j, (0.5, 0.5));
                add(dir, weight * share * sky.luminance(dir));
            }
        }
    }
    if let Some(sun) = sky.sun {
        out.sun = sun.normal_lux
            * sun_disc(sun.direction)
                .map(|d| n.dot(d).max(0.0) * trace(d))
                .sum::<f64>()
            / SUN_RAYS as f64;
    }
    out
}

/// Relative step in the share of light between neighbouring cells taken for an edge.
const EDGE_STEP: f64 = 0.05;

/// Rays across an edge in a cell refined there (half as many each way where edges run
/// both ways).
pub const EDGE_RAYS: usize = 16;

/// A point's hemisphere in cells: rings of equal angle from the normal (as fine at the
/// horizon as at the zenith: openings seen at grazing angles are not coarsened), each cell
/// weighted by its share of the projected solid angle.
struct Hemisphere {
    normal: DVec3,
    tangent: DVec3,
    bitangent: DVec3,
    rings: usize,
    sectors: usize,
    offset: f64,
}

impl Hemisphere {
    fn new(normal: DVec3, position: DVec3, (rings, sectors): (usize, usize)) -> Hemisphere {
        let (tangent, bitangent) = normal.any_orthonormal_pair();
        Hemisphere {
            normal,
            tangent,
            bitangent,
            rings,
            sectors,
            offset: azimuth_offset(position),
        }
    }

    /// sin² of the angle from the normal at ring boundary `k` (0 … rings).
    fn ring(&self, k: f64) -> f64 {
        (FRAC_PI_2 * k / self.rings as f64).sin().powi(2)
    }

    /// π × the share of the projected solid angle of one cell of ring `i`.
    fn weight(&self, i: usize) -> f64 {
        PI * (self.ring(i as f64 + 1.0) - self.ring(i as f64)) / self.sectors as f64
    }

    /// The direction at `(u, v)` ∈ [0, 1)² within cell (`i`, `j`): `u` across the ring
    /// in equal projected solid angle, `v` along the azimuth.
    fn direction(&self, i: usize, j: usize, (u, v): (f64, f64)) -> DVec3 {
        let (lo, hi) = (self.ring(i as f64), self.ring(i as f64 + 1.0));
        let s2 = lo + u * (hi - lo);
        let (sin_t, cos_t) = (s2.sqrt(), (1.0 - s2).max(0.0).sqrt());
        let a = 2.0 * PI * (j as f64 + self.offset - 0.5 + v) / self.sectors as f64;
        (self.tangent * a.cos() + self.bitangent * a.sin()) * sin_t + self.normal * cos_t
    }
}

/// Directions over the sun's disc round `centre`, equal areas each (Vogel's spiral).
fn sun_disc(centre: DVec3) -> impl Iterator<Item = DVec3> {
    let (u, v) = centre.any_orthonormal_pair();
    let radius = (SUN_DIAMETER_DEG / 2.0).to_radians();
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..SUN_RAYS).map(move |k| {
        let r = radius * ((k as f64 + 0.5) / SUN_RAYS as f64).sqrt();
        let a = golden * k as f64;
        (centre + (u * a.cos() + v * a.sin()) * r.tan()).normalize()
    })
}

/// The share of light along `dir` from `origin` that gets out: 1 through nothing, the
/// product of the panes' transmittances through glazing, 0 where an opaque face stops it.
fn transmitted(obstructions: Option<&Obstructions>, origin: DVec3, dir: DVec3) -> f64 {
    let Some(o) = obstructions else {
        return 1.0;
    };
    let mut share = 1.0;
    let mut from = origin;
    for _ in 0..MOST_PANES {
        match o.bvh.first_hit(from, dir, o.eps) {
            None => return share,
            Some((t, k)) => {
                let Some(pane) = o.glazing.get(k).copied().flatten() else {
                    return 0.0;
                };
                let normal = o.mesh.face_normal(k).normalize_or_zero();
                share *= pane.transmittance(normal.dot(dir));
                from += dir * t;
            }
        }
    }
    0.0
}
