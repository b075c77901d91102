//! `bench clusters`: the face-cluster hierarchy (Edström §4.2) of real models read from the
//! shared test data — the Šibenik cathedral, Greg Ward's conference room and a block of
//! high-rises — timed by stage as in Edström's Table 7.1 (his car, 242 764 polygons: 15.2 s
//! of preprocessing on a 1.4 GHz Athlon).

use std::path::Path;
use std::time::Instant;

use serde::Serialize;

use crate::radiosity::clusters::{ClusterSettings, FaceClusters};
use crate::scene::Scene;

/// One model's hierarchy.
#[derive(Debug, Clone, Serialize)]
pub struct ClusterBenchRow {
    /// What the model is.
    pub model: &'static str,
    /// Triangles with an area (the loader drops the others).
    pub triangles: usize,
    /// Seconds to read the OBJ.
    pub load_s: f64,
    /// Seconds to build the hierarchy (dual graph, merges, boxes, order).
    pub cluster_s: f64,
    /// Clusters, leaves included.
    pub clusters: usize,
    /// Roots: connected surfaces of one material.
    pub roots: usize,
    /// The deepest leaf's level.
    pub depth: usize,
}

/// The models: (name, path under the shared data, up axis, scale to metres).
pub const MODELS: [(&str, &str, &str, f64); 3] = [
    ("Šibenik cathedral", "models/sibenik/sibenik.obj", "y", 1.0),
    (
        "conference room",
        "models/conference/conference.obj",
        "y",
        0.004,
    ),
    (
        "high-rise block",
        "models/openfoam_buildings/buildings.obj",
        "z",
        1.0,
    ),
];

/// Builds the hierarchy of each model under `shared`; `progress` is told each name.
pub fn run(
    shared: &Path,
    mut progress: impl FnMut(&str),
) -> Result<Vec<ClusterBenchRow>, super::BenchError> {
    let mut rows = Vec::new();
    for (model, rel, up, scale) in MODELS {
        progress(model);
        let obj = shared.join(rel);
        let toml = format!(
            "[[model]]\npath = {:?}\nup = {up:?}\nscale = {scale}\n",
            obj.display().to_string()
        );
        let t = Instant::now();
        let scene = Scene::from_toml(&shared.join("bench.toml"), &toml)?;
        let load_s = t.elapsed().as_secs_f64();
        let (mesh, materials) = (scene.caster_mesh(), scene.caster_materials());
        let t = Instant::now();
        let h = FaceClusters::build(&mesh, &materials, ClusterSettings::default());
        let cluster_s = t.elapsed().as_secs_f64();
        rows.push(ClusterBenchRow {
            model,
            triangles: mesh.triangles.len(),
            load_s,
            cluster_s,
            clusters: h.nodes.len(),
            roots: h.roots.len(),
            depth: h.depth(),
        });
    }
    Ok(rows)
}

/// The report of `bench clusters`: seconds to load and to cluster each model.
pub fn report(rows: &[ClusterBenchRow]) -> super::report::BenchReport {
    use super::report::{BenchReport, Table};
    let mut r = BenchReport::new(serde_json::json!({ "rows": rows }));
    r.line("Face-cluster hierarchy (Edström §4.2), one thread");
    let mut t = Table::new(&[
        "model",
        "triangles",
        "load s",
        "cluster s",
        "clusters",
        "roots",
        "depth",
    ]);
    for row in rows {
        t.row(vec![
            row.model.to_string(),
            row.triangles.to_string(),
            format!("{:.2}", row.load_s),
            format!("{:.2}", row.cluster_s),
            row.clusters.to_string(),
            row.roots.to_string(),
            row.depth.to_string(),
        ]);
    }
    r.table(t);
    r
}
