//! `bench raycast`: CPU ray casts through the BVH against the brute-force loop, side by side
//! on one thread, on terrain-like meshes of about 10 k, 100 k and 1 M triangles. Two kinds
//! of rays: shadow rays from surface points toward a low point light (any hit ends them) and
//! nearest-hit rays from above. Every brute-force answer is checked against the BVH's.

use std::time::Instant;

use glam::DVec3;
use serde::Serialize;

use crate::geometry::generate::{bumpy_surface, XorShift};
use crate::geometry::Mesh;
use crate::shadow::{raycast, IgnoredTriangles, Light, TriangleBvh};

/// One benchmarked mesh.
#[derive(Debug, Clone, Serialize)]
pub struct RaycastBenchRow {
    /// Triangle count.
    pub triangles: usize,
    /// Seconds to build the BVH.
    pub build_s: f64,
    /// Shadow rays per second, brute force.
    pub brute_shadow_rays_per_s: f64,
    /// Shadow rays per second, BVH.
    pub bvh_shadow_rays_per_s: f64,
    /// Nearest-hit rays per second, brute force.
    pub brute_hit_rays_per_s: f64,
    /// Nearest-hit rays per second, BVH.
    pub bvh_hit_rays_per_s: f64,
    /// Fraction of the shadow rays that were blocked.
    pub blocked_fraction: f64,
}

/// The benchmark meshes: 50 m terrain patches of about 10 k, 100 k and 1 M triangles
/// (`scale` < 1 shrinks them, for tests).
pub fn bench_meshes(scale: f64) -> Vec<Mesh> {
    [71.0, 224.0, 707.0]
        .iter()
        .map(|n: &f64| bumpy_surface(((n * scale.sqrt()).round() as u32).max(2), 50.0, 7))
        .collect()
}

/// A shadow ray: the surface point and the light.
type ShadowRay = (DVec3, Light);
/// A nearest-hit ray: origin and unit direction.
type HitRay = (DVec3, DVec3);

/// The rays: `count` shadow rays (surface point, light) and as many nearest-hit rays
/// (origin, unit direction).
fn rays(mesh: &Mesh, count: usize) -> (Vec<ShadowRay>, Vec<HitRay>) {
    let mut rng = XorShift::new(11);
    let (lo, hi) = mesh.bounds().unwrap_or((DVec3::ZERO, DVec3::ONE));
    let size = hi - lo;
    let light =
        Light((lo + size * DVec3::new(1.2, 0.5, 0.0) + DVec3::Z * 0.3 * size.x).extend(1.0));
    let eps = raycast::self_hit_epsilon(mesh);
    let shadow = (0..count)
        .map(|_| {
            let t = (rng.next_f64() * mesh.triangles.len() as f64) as usize % mesh.triangles.len();
            let c = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
            let n = mesh.face_normal(t).normalize_or_zero();
            ((c[0] + c[1] + c[2]) / 3.0 + n * eps, light)
        })
        .collect();
    let hit = (0..count)
        .map(|_| {
            let o = lo + size * DVec3::new(rng.next_f64(), rng.next_f64(), 1.5);
            let d = DVec3::new(rng.next_f64() - 0.5, rng.next_f64() - 0.5, -0.6).normalize();
            (o, d)
        })
        .collect();
    (shadow, hit)
}

/// Rays per second of `f` over `items`.
fn rate<T>(items: &[T], mut f: impl FnMut(&T)) -> f64 {
    let t = Instant::now();
    for x in items {
        f(x);
    }
    items.len() as f64 / t.elapsed().as_secs_f64().max(1e-9)
}

/// Runs the benchmark: `rays` rays of each kind through the BVH, the first `brute_rays`
/// of them also by brute force; `progress` is told each mesh's size as it starts.
pub fn run(
    meshes: &[Mesh],
    rays_per_kind: usize,
    brute_rays: usize,
    mut progress: impl FnMut(usize),
) -> Result<Vec<RaycastBenchRow>, super::BenchError> {
    let none = IgnoredTriangles::default();
    let mut rows = Vec::new();
    for mesh in meshes {
        progress(mesh.triangles.len());
        let t = Instant::now();
        let bvh = TriangleBvh::new(mesh);
        let build_s = t.elapsed().as_secs_f64();
        let eps = raycast::self_hit_epsilon(mesh);
        let (shadow, hit) = rays(mesh, rays_per_kind);
        let (few_shadow, few_hit) = (
            &shadow[..brute_rays.min(shadow.len())],
            &hit[..brute_rays.min(hit.len())],
        );
        for (p, l) in few_shadow {
            if bvh.in_shadow(l, *p, eps, &none) != raycast::in_shadow(mesh, l, *p, eps) {
                return Err(super::BenchError::Disagree(format!(
                    "shadow ray from {p}: BVH and brute force disagree"
                )));
            }
        }
        for &(o, d) in few_hit {
            if bvh.first_hit(o, d, 0.0) != raycast::first_hit(mesh, o, d, 0.0) {
                return Err(super::BenchError::Disagree(format!(
                    "ray from {o} along {d}: BVH and brute force disagree"
                )));
            }
        }
        let mut blocked = 0usize;
        let bvh_shadow = rate(&shadow, |(p, l)| {
            blocked += bvh.in_shadow(l, *p, eps, &none) as usize
        });
        let brute_shadow = rate(few_shadow, |(p, l)| {
            std::hint::black_box(raycast::in_shadow(mesh, l, *p, eps));
        });
        let bvh_hit = rate(&hit, |&(o, d)| {
            std::hint::black_box(bvh.first_hit(o, d, 0.0));
        });
        let brute_hit = rate(few_hit, |&(o, d)| {
            std::hint::black_box(raycast::first_hit(mesh, o, d, 0.0));
        });
        rows.push(RaycastBenchRow {
            triangles: mesh.triangles.len(),
            build_s,
            brute_shadow_rays_per_s: brute_shadow,
            bvh_shadow_rays_per_s: bvh_shadow,
            brute_hit_rays_per_s: brute_hit,
            bvh_hit_rays_per_s: bvh_hit,
            blocked_fraction: blocked as f64 / shadow.len().max(1) as f64,
        });
    }
    Ok(rows)
}

/// The report of `bench raycast`: rays per second by brute force and through the BVH.
pub fn report(rows: &[RaycastBenchRow]) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let mut r = BenchReport::new(serde_json::json!({ "rows": rows }));
    r.line("CPU ray casts, one thread: rays/s by brute force and through the BVH");
    let mut t = Table::new(&[
        "triangles",
        "BVH build s",
        "shadow brute",
        "shadow BVH",
        "×",
        "nearest hit brute",
        "nearest hit BVH",
        "×",
        "blocked",
    ]);
    for row in rows {
        t.row(vec![
            row.triangles.to_string(),
            format!("{:.3}", row.build_s),
            format!("{:.0}", row.brute_shadow_rays_per_s),
            format!("{:.0}", row.bvh_shadow_rays_per_s),
            format!(
                "{:.0}×",
                row.bvh_shadow_rays_per_s / row.brute_shadow_rays_per_s
            ),
            format!("{:.0}", row.brute_hit_rays_per_s),
            format!("{:.0}", row.bvh_hit_rays_per_s),
            format!("{:.0}×", row.bvh_hit_rays_per_s / row.brute_hit_rays_per_s),
            format!("{:.0} %", 100.0 * row.blocked_fraction),
        ]);
    }
    r.table(t);
    r
}
