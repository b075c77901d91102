//! `goniolight bench profile`.

use std::path::PathBuf;

use anyhow::anyhow;

use super::error::CliError;
use crate::gpu::Gpu;
use crate::scene::UpAxis;
use crate::study::model::{load_components, recentre};

/// Runs `bench profile`: the same profile with brute-force and hextree silhouettes, and
/// with the volumes ending at the ground or of one length, on the generated building and,
/// with `shared`, on the real models.
pub fn run(
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
    let mut models = vec![crate::bench::shadow_profile::generated_building(floors)];
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
    let rows = crate::bench::shadow_profile::run(&gpu, &models, resolution, step)?;
    let report = crate::bench::shadow_profile::report(&rows, resolution);
    println!("{}", report.text(as_json));
    Ok(())
}
