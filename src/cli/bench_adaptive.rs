//! `goniolight bench adaptive` (Wallner Table 2.1): uniform against adaptive elements.

use clap::Args;

use super::error::CliError;
use crate::bench::adaptive::{self, Meshing};
use crate::gpu::Gpu;
use crate::radiosity::solve::StopAt;

/// Options of `bench adaptive`.
#[derive(Debug, Args)]
pub struct AdaptiveBenchArgs {
    /// Print JSON {"rows": [...]}.
    #[arg(long)]
    json: bool,
    /// The scene (default: the bundled assets/scenes/furnished_room.toml, whose brick
    /// wall has a normal map: measured with and without it).
    #[arg(long)]
    scene: Option<std::path::PathBuf>,
    /// Elements per metre where unsplit.
    #[arg(long, default_value_t = 5.0)]
    texel_density: f64,
    /// Subdivision levels of the adaptive rows; a uniform row at the finest elements'
    /// density is measured beside them.
    #[arg(long, default_value_t = 2)]
    levels: u32,
    /// Patch level (patches of 2^level unsplit elements).
    #[arg(long, default_value_t = 1)]
    level: u32,
    /// Shoot until this convergence.
    #[arg(long, default_value_t = 0.95)]
    converge: f64,
    /// Give up after this many seconds per solution.
    #[arg(long, default_value_t = 120.0, value_parser = super::args::seconds_arg)]
    time_limit: f64,
}

/// Runs `bench adaptive`.
pub fn run(args: AdaptiveBenchArgs) -> Result<(), CliError> {
    let ok = args.texel_density.is_finite()
        && args.texel_density > 0.0
        && (1..=4).contains(&args.levels)
        && args.level <= 6
        && (0.0..=1.0).contains(&args.converge)
        && args.time_limit.is_finite()
        && args.time_limit > 0.0;
    if !ok {
        return Err(CliError::input(anyhow::anyhow!(
            "--texel-density > 0, --levels in 1..=4, --level in 0..=6, --converge in 0..=1, --time-limit > 0"
        )));
    }
    let path = args
        .scene
        .unwrap_or_else(|| crate::io::data_root().join("assets/scenes/furnished_room.toml"));
    let scene = super::scene_input::load_scene(&path)?;
    let gpu = Gpu::shared()?;
    eprintln!("GPU: {}", gpu.describe());
    let d = args.texel_density;
    let meshings = [
        Meshing {
            texel_density: d,
            levels: 0,
        },
        Meshing {
            texel_density: d,
            levels: args.levels,
        },
        Meshing {
            texel_density: d * f64::from(1u32 << args.levels),
            levels: 0,
        },
    ];
    let stop = StopAt {
        converge: args.converge,
        max_shots: None,
        time_budget: crate::io::limits::duration(args.time_limit).ok(),
    };
    let rows = adaptive::run(&gpu, &scene, &meshings, args.level, &stop, |what| {
        eprintln!("solving {what} …")
    })
    .map_err(CliError::failure)?;
    let report = adaptive::report(&rows, &path, args.converge);
    println!("{}", report.text(args.json));
    Ok(())
}
