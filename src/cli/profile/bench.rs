//! `goniolight bench profile`.

use std::path::PathBuf;

use anyhow::anyhow;

use super::super::error::CliError;
use crate::gpu::Gpu;
use crate::scene::UpAxis;
use crate::study::model::{load_components, recentre};

/// Runs `bench profile`: the same profile with brute-force and hextree silhouettes, and
/// with the volumes ending at the ground or of one length, on the generated building and,
/// with `shared`, on the real models.
pub fn run_bench(
    as_json: bool,
    resolution: u32,
    step: u32,
    floors: u32,
    shared: Option<PathBuf>,
) -> Result<(), CliError> {
    if !(1..=40).contains(&floors) {
        return Err(CliError::input(anyhow!(
            "--floors {floors} is not in 1..=40"
        )));
    }
    let mut models = vec![crate::bench::profile::generated_building(floors)];
    if let Some(dir) = shared {
        for (name, rel) in [
            ("Delft city block", "models/delft_3dfier/testarea.obj"),
            ("high-rise block", "models/openfoam_buildings/buildings.obj"),
        ] {
            let mut mesh = load_components(&dir.join(rel), UpAxis::Z, &[])?.mesh;
            recentre(&mut mesh);
            models.push((name.to_string(), mesh));
        }
    }
    let gpu = Gpu::shared().map_err(CliError::failure)?;
    eprintln!("GPU: {}", gpu.describe());
    let rows = crate::bench::profile::run(&gpu, &models, resolution, step)?;
    if as_json {
        println!("{}", serde_json::json!({ "rows": rows }));
        return Ok(());
    }
    println!(
        "shadow profile: {} steps, {resolution}² plan",
        rows.first().map_or(0, |r| r.steps)
    );
    println!(
        "| model | triangles | silhouettes | volumes end | total s | ms/step | silhouette ms/step | volumes + read-back ms/step |"
    );
    println!("|---|---:|---|---|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {} | {:.2} | {:.1} | {:.2} | {:.1} |",
            r.model,
            r.triangles,
            r.method,
            r.volume_ends,
            r.total_s,
            r.per_step_ms,
            r.silhouette_ms_per_step,
            r.render_ms_per_step
        );
    }
    for model in rows.chunks(3) {
        if let [brute, hex, one_length] = model {
            println!(
                "{}: hextree / brute force: total {:.2}×, silhouettes {:.2}× faster; volumes to the ground / of one length: volumes {:.2}× faster",
                brute.model,
                brute.total_s / hex.total_s,
                brute.silhouette_ms_per_step / hex.silhouette_ms_per_step.max(1e-12),
                one_length.render_ms_per_step / hex.render_ms_per_step.max(1e-12)
            );
        }
    }
    Ok(())
}
