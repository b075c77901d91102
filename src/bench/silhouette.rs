//! The silhouette benchmark behind `goniolight bench silhouette`: procedural meshes of
//! about 10 k, 180 k and 1 M triangles, a moving light, brute force and hextree timed
//! side by side on one thread (and checked to agree on every query).

use std::time::Instant;

use glam::DVec3;
use serde::Serialize;

use super::median;
use crate::geometry::generate::{building, bumpy_surface, torus};
use crate::geometry::Mesh;
use crate::shadow::hextree::{ESTIMATE_DEPTH, FALLBACK_FRACTION};
use crate::shadow::{Hextree, Light, SilhouetteMesh};

/// One benchmarked mesh.
#[derive(Debug, Clone, Serialize)]
pub struct SilhouetteBenchRow {
    /// What the mesh is.
    pub mesh: String,
    /// Triangle count.
    pub triangles: usize,
    /// Median ms per brute-force query.
    pub brute_ms: f64,
    /// Median ms per hextree query.
    pub hextree_ms: f64,
    /// brute_ms / hextree_ms.
    pub speedup: f64,
    /// Mean silhouette edges per query.
    pub silhouette_edges: f64,
    /// Seconds to build the hextree (once per mesh).
    pub hextree_build_s: f64,
    /// The fraction of the queries the hextree answered by the linear scan (its
    /// hyperplane met most of the tree).
    pub scanned_fraction: f64,
}

/// The benchmark meshes, smallest first; `scale` < 1 shrinks them (for tests).
pub fn bench_meshes(scale: f64) -> Vec<(String, Mesh)> {
    let s = |n: f64| ((n * scale.sqrt()).round() as u32).max(2);
    vec![
        ("detailed building".to_string(), building(s(8.0), s(6.0), 5)),
        (
            "tessellated torus".to_string(),
            torus(s(300.0), s(300.0), 3.0, 1.0),
        ),
        (
            "bumpy scanned-like surface".to_string(),
            bumpy_surface(s(707.0), 50.0, 11),
        ),
    ]
}

/// Lights orbiting the mesh at twice its size, rising and falling.
fn lights(mesh: &Mesh, queries: usize) -> Vec<Light> {
    let (lo, hi) = mesh.bounds().expect("non-empty benchmark mesh");
    let c = (lo + hi) * 0.5;
    let r = (hi - lo).length();
    (0..queries)
        .map(|k| {
            let a = k as f64 / queries as f64 * std::f64::consts::TAU;
            let e = 0.3 + 0.5 * (k as f64 * 0.7).sin().abs();
            let p = c + DVec3::new(a.cos() * e.cos(), a.sin() * e.cos(), e.sin()) * r;
            Light::new([p.x, p.y, p.z, 1.0]).expect("finite")
        })
        .collect()
}

/// Runs the benchmark on `meshes`; `progress` is told each mesh's name as it starts.
pub fn run(
    meshes: &[(String, Mesh)],
    queries: usize,
    depth: u32,
    mut progress: impl FnMut(&str),
) -> Result<Vec<SilhouetteBenchRow>, super::BenchError> {
    let mut rows = Vec::new();
    for (name, mesh) in meshes {
        progress(name);
        let sm = SilhouetteMesh::new(mesh, name, 1e-9)?;
        let t0 = Instant::now();
        let tree = Hextree::build(&sm, depth);
        let build_s = t0.elapsed().as_secs_f64();
        let lights = lights(mesh, queries);
        // Both methods must agree on every light.
        let mut edges = 0usize;
        let mut scanned = 0usize;
        for light in &lights {
            scanned += (tree.estimate(&sm, light, ESTIMATE_DEPTH, FALLBACK_FRACTION)
                > FALLBACK_FRACTION) as usize;
            let (a, b) = (sm.brute(light), tree.query(&sm, light));
            if a.sorted() != b.sorted() || a.sorted() != tree.traverse(&sm, light).sorted() {
                return Err(super::BenchError::Disagree(format!(
                    "{name}: brute force and hextree disagree"
                )));
            }
            edges += a.edges.len();
        }
        // Then both methods over the moving light, three passes, per-query times; the two
        // alternate query by query so a change in the machine's speed hits both alike.
        let time = |f: &dyn Fn(&Light) -> usize, light: &Light| {
            let t = Instant::now();
            std::hint::black_box(f(light));
            t.elapsed().as_secs_f64() * 1e3
        };
        let (mut brute, mut hex) = (Vec::new(), Vec::new());
        for pass in 0..3 {
            for light in &lights {
                let b = |l: &Light| sm.brute(l).edges.len();
                let h = |l: &Light| tree.query(&sm, l).edges.len();
                if pass % 2 == 0 {
                    brute.push(time(&b, light));
                    hex.push(time(&h, light));
                } else {
                    hex.push(time(&h, light));
                    brute.push(time(&b, light));
                }
            }
        }
        let (b, h) = (median(brute), median(hex));
        rows.push(SilhouetteBenchRow {
            mesh: name.clone(),
            triangles: sm.mesh().triangles.len(),
            brute_ms: b,
            hextree_ms: h,
            speedup: b / h,
            silhouette_edges: edges as f64 / queries as f64,
            hextree_build_s: build_s,
            scanned_fraction: scanned as f64 / queries as f64,
        });
    }
    Ok(rows)
}

/// The report of `bench silhouette`: per mesh, brute force against the hextree.
pub fn report(rows: &[SilhouetteBenchRow]) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let mut r = BenchReport::new(serde_json::json!({ "meshes": rows }));
    let mut t = Table::new(&[
        "mesh",
        "triangles",
        "brute ms",
        "hextree ms",
        "speedup",
        "sil. edges",
        "build s",
        "scanned",
    ])
    .numbers_from(1);
    for row in rows {
        t.row(vec![
            row.mesh.to_string(),
            row.triangles.to_string(),
            format!("{:.3}", row.brute_ms),
            format!("{:.3}", row.hextree_ms),
            format!("{:.2}×", row.speedup),
            format!("{:.0}", row.silhouette_edges),
            format!("{:.2}", row.hextree_build_s),
            format!("{:.0} %", 100.0 * row.scanned_fraction),
        ]);
    }
    r.table(t);
    r
}
