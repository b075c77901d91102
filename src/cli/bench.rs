//! `goniolight bench …`: benchmarks that print tables of ratios measured side by side in
//! one run.

use clap::Subcommand;
use serde_json::json;

use super::{silhouette, CliError};
use crate::gpu::Gpu;
use crate::render::bench;

/// Benchmarks.
#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Silhouette queries, brute force vs hextree, on ~10 k, 180 k and 1 M triangles.
    Silhouette {
        /// Print JSON {"meshes": [...]}.
        #[arg(long)]
        json: bool,
        /// Light positions per mesh, evenly along one orbit (120: 3° apart).
        #[arg(long, default_value_t = 120)]
        queries: usize,
        /// Maximum hextree depth.
        #[arg(long, default_value_t = crate::shadow::hextree::DEFAULT_DEPTH)]
        depth: u32,
        /// Shrink the meshes by this factor (1 = the full sizes).
        #[arg(long, default_value_t = 1.0)]
        scale: f64,
    },
    /// Renderer frame times (Wallner Table 3.1): point lights vs bilinear vs Catmull-Rom
    /// LDT sampling, ≈ 100 to 115 000 triangles, 1, 4 and 7 luminaires.
    Render {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// Frames submitted together per round.
        #[arg(long, default_value_t = 8)]
        frames: usize,
        /// Timed rounds per cell and light model (after a warm-up round); the median of the
        /// rounds' frame times is reported.
        #[arg(long, default_value_t = 5)]
        rounds: usize,
        /// Frame width.
        #[arg(long, default_value_t = 1280)]
        width: u32,
        /// Frame height.
        #[arg(long, default_value_t = 720)]
        height: u32,
        /// Only the two smallest scenes (a quick check).
        #[arg(long)]
        quick: bool,
    },
    /// A shadow profile of a ~180 000-triangle building, 08:00–16:00 every 5 minutes
    /// (97 steps): seconds in total and per step, silhouettes vs shadow volumes, brute
    /// force vs hextree.
    Profile {
        /// Print JSON {"rows": [...]}.
        #[arg(long)]
        json: bool,
        /// Plan pixels per side.
        #[arg(long, default_value_t = 1024)]
        resolution: u32,
        /// Minutes between steps.
        #[arg(long, default_value_t = 5)]
        step: u32,
        /// Storeys of the building (6: 180 000 triangles).
        #[arg(long, default_value_t = 6)]
        floors: u32,
    },
}

/// Runs `bench …`.
pub fn run(cmd: BenchCommand) -> Result<(), CliError> {
    match cmd {
        BenchCommand::Silhouette {
            json,
            queries,
            depth,
            scale,
        } => silhouette::run_bench(json, queries, depth, scale),
        BenchCommand::Render {
            json,
            frames,
            rounds,
            width,
            height,
            quick,
        } => run_render(
            json,
            bench::BenchPlan {
                width,
                height,
                frames,
                rounds,
            },
            quick,
        ),
        BenchCommand::Profile {
            json,
            resolution,
            step,
            floors,
        } => super::profile::run_bench(json, resolution, step, floors),
    }
}

fn run_render(as_json: bool, plan: bench::BenchPlan, quick: bool) -> Result<(), CliError> {
    let bench::BenchPlan {
        width,
        height,
        frames,
        rounds,
    } = plan;
    if frames == 0 || rounds == 0 || !(1..=8192).contains(&width) || !(1..=8192).contains(&height) {
        return Err(CliError::input(anyhow::anyhow!(
            "--frames and --rounds must be > 0 and --width/--height in 1..=8192"
        )));
    }
    let gpu = Gpu::headless()?;
    eprintln!("GPU: {}", gpu.describe());
    let root = super::data_root();
    let tess = if quick {
        &bench::TESSELLATIONS[..2]
    } else {
        &bench::TESSELLATIONS[..]
    };
    let rows = bench::run(&gpu, &root, plan, tess, |tris, lights| {
        eprintln!("benchmarking {tris} triangles, {lights} luminaires …")
    })
    .map_err(CliError::failure)?;
    if as_json {
        println!(
            "{}",
            json!({ "rows": rows, "gpu": gpu.describe(), "width": width, "height": height, "frames": frames, "rounds": rounds })
        );
        return Ok(());
    }
    println!(
        "{}, {width}×{height}, median of {rounds} rounds of {frames} frames",
        gpu.describe()
    );
    println!(
        "{:>9} {:>6} {:>10} {:>12} {:>15} {:>9} {:>9}",
        "triangles", "lights", "point ms", "bilinear ms", "catmull-rom ms", "bil/pt", "cr/pt"
    );
    for r in &rows {
        println!(
            "{:>9} {:>6} {:>10.2} {:>12.2} {:>15.2} {:>8.3}× {:>8.3}×",
            r.triangles,
            r.lights,
            r.point_ms,
            r.bilinear_ms,
            r.catmull_rom_ms,
            r.bilinear_ratio(),
            r.catmull_rom_ratio()
        );
    }
    Ok(())
}
