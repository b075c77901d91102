//! The command-line interface: clap definitions and dispatch. Commands call the library
//! and hold no logic of their own beyond reading input and printing results.

mod args;
mod batch;
mod bench;
mod bench_adaptive;
mod bench_profile;
mod bench_silhouette;
mod calc;
mod demo;
mod error;
mod illuminance;
mod image;
mod indirect;
mod interrupt;
mod ldt;
mod profile;
mod radiosity;
mod render;
mod scene_input;
mod silhouette;
mod solver_args;
mod solving;
mod sun;
mod sunlight;
#[cfg(feature = "viewer")]
mod view;

use clap::{Parser, Subcommand};

pub use batch::count_jobs;
pub use error::CliError;
pub use interrupt::interrupt_flag;

/// goniolight — real luminaires in real-time rendering, radiosity and shadow studies.
#[derive(Debug, Parser)]
#[command(name = "goniolight", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The top-level commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Luminaire files: information, sampling, interpolation check, plots, conversion.
    #[command(subcommand)]
    Ldt(ldt::LdtCommand),
    /// Run the main job on the bundled data and write its outputs.
    Demo(demo::DemoArgs),
    /// Render a scene (shaded or false-colour illuminance) to PNG and optionally EXR.
    Render(render::RenderArgs),
    /// Read "x y z nx ny nz" lines from stdin and print the direct illuminance (lux) at each
    /// (the luminaires' and the daylight of the scene's `[sky]`).
    Illuminance(illuminance::IlluminanceArgs),
    /// Lighting calculations on the scene's `[[grid]]` surfaces and `[[observer]]`s:
    /// maintained illuminance at every point (direct, or total with `--indirect
    /// radiosity`), Em/Emin/Emax/U0/g2 per grid, UGR per observer, `calc.json`, one CSV
    /// and plan per grid.
    Calc(calc::CalcArgs),
    /// The sun's position (NREL SPA) for a site and an instant.
    Sun(sun::SunArgs),
    /// Solve the scene's interreflected light (GPU progressive radiosity): rendering,
    /// light-map atlas, convergence log; with --points the total lux at points from stdin.
    Radiosity(radiosity::RadiosityArgs),
    /// Sun-path shadow profile of an OBJ or glTF model over a period: profile.png, hours.png,
    /// profile.csv.
    Profile(profile::ProfileArgs),
    /// The planning tests of a scene's windows and open spaces: VSC, annual and winter
    /// probable sunlight hours (BRE 209), EN 17037 sunlight exposure, 2 hours of sun on
    /// 21 March; `sunlight.json`, CSVs, a plan and a report.
    Sunlight(sunlight::SunlightArgs),
    /// Silhouette edges of an OBJ or glTF model for a point or directional light.
    Silhouette(silhouette::SilhouetteArgs),
    /// Run a list of command lines (a TOML jobs file) in one process, optionally one shard
    /// of it (`--shard K/N`), with a JSON summary.
    Batch(batch::BatchArgs),
    /// Benchmarks that print tables of ratios measured side by side.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// The interactive viewer: a scene (TOML) or an OBJ or glTF model, luminaires, sun, shadows,
    /// radiosity. `--frames N [--screenshot out.png]` renders N frames and exits.
    #[cfg(feature = "viewer")]
    View(view::ViewArgs),
}

pub use crate::io::data_root;

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    // Every command ends cleanly on a signal; those that poll the flag ask for it.
    interrupt::signal_flag();
    match cli.command {
        Command::Ldt(cmd) => ldt::run(cmd),
        Command::Demo(args) => demo::run(args),
        Command::Render(args) => render::run(args),
        Command::Illuminance(args) => illuminance::run(args),
        Command::Calc(args) => calc::run(args),
        Command::Sun(args) => sun::run(args),
        Command::Sunlight(args) => sunlight::run(args),
        Command::Silhouette(args) => silhouette::run(args),
        Command::Profile(args) => profile::run(args),
        Command::Radiosity(args) => radiosity::run(args),
        Command::Batch(args) => batch::run(args, &run_job_line),
        Command::Bench(cmd) => bench::run(cmd),
        #[cfg(feature = "viewer")]
        Command::View(args) => view::run(args),
    }
}

/// Parses and runs one command line of a batch job (`argv` without the program's name);
/// a batch inside a batch is refused.
fn run_job_line(argv: &[String]) -> Result<(), CliError> {
    use clap::Parser as _;
    let argv = std::iter::once("goniolight").chain(argv.iter().map(String::as_str));
    let cli = Cli::try_parse_from(argv)
        .map_err(|e| CliError::input(anyhow::anyhow!("{}", e.render())))?;
    if matches!(cli.command, Command::Batch(_)) {
        return Err(CliError::input(anyhow::anyhow!(
            "a batch cannot run a batch"
        )));
    }
    run(cli)
}
