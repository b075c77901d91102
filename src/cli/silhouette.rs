//! `goniolight silhouette` and `goniolight bench silhouette`.

use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use super::error::CliError;
use crate::geometry::read_model_objects;
use crate::shadow::{Hextree, Light, SilhouetteMesh};

pub use crate::shadow::SilhouetteMethod as Method;

/// Options of `silhouette`.
#[derive(Debug, Args)]
pub struct SilhouetteArgs {
    /// The model (OBJ or glTF), read as is (no up-axis change).
    pub model: PathBuf,
    /// Homogeneous light X,Y,Z,W: W = 1 a point light, W = 0 a direction toward the light.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_light)]
    pub light: [f64; 4],
    /// Search method.
    #[arg(long, value_enum, default_value = "hextree")]
    pub method: Method,
    /// Maximum hextree depth.
    #[arg(long, default_value_t = crate::shadow::hextree::DEFAULT_DEPTH)]
    pub depth: u32,
    /// Weld vertices closer than this fraction of the bounding-box diagonal.
    #[arg(long, default_value_t = 1e-9)]
    pub weld: f64,
    /// Print JSON {"count", "edges"} with 0-based vertex indices (the OBJ's own numbering).
    #[arg(long)]
    pub json: bool,
}

fn parse_light(s: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("bad number {t:?} in --light"))
        })
        .collect::<Result<_, _>>()?;
    <[f64; 4]>::try_from(v)
        .map_err(|v| format!("--light needs X,Y,Z,W (4 numbers), got {}", v.len()))
}

/// Runs `silhouette`.
pub fn run(a: SilhouetteArgs) -> Result<(), CliError> {
    let light =
        Light::new(a.light).map_err(|e| CliError::input(anyhow::anyhow!("--light: {e}")))?;
    if !(a.weld >= 0.0 && a.weld < 0.1) {
        return Err(CliError::input(anyhow::anyhow!(
            "--weld {} must be in [0, 0.1)",
            a.weld
        )));
    }
    let (mesh, _) = read_model_objects(&a.model)?;
    let name = a.model.display().to_string();
    let sm = SilhouetteMesh::new(&mesh, &name, a.weld)?;
    if sm.degenerate > 0 {
        eprintln!(
            "warning: {name}: {} of its {} triangles have no area and were dropped",
            sm.degenerate,
            mesh.triangles.len()
        );
    }
    let s = match a.method {
        Method::Brute => sm.brute(&light),
        Method::Hextree => Hextree::build(&sm, a.depth).query(&sm, &light),
    };
    let edges = sm.to_input_indices(&s);
    if a.json {
        println!("{}", json!({"count": edges.len(), "edges": edges}));
    } else {
        let [m, b, i, n] = sm.adjacency.census();
        println!(
            "{name}: {} triangles, {} edges ({m} manifold, {b} border, {i} inconsistent winding, {n} non-manifold)",
            sm.mesh().triangles.len(),
            sm.adjacency.edges.len()
        );
        println!("{} silhouette edges ({:?})", edges.len(), a.method);
        for [i, j] in edges {
            println!("{i} {j}");
        }
    }
    Ok(())
}
