//! The command-line interface: clap definitions and dispatch. Commands call the library
//! and hold no logic of their own beyond reading input and printing results.

mod bench;
mod demo;
mod ldt;
mod profile;
mod radiosity;
mod render;
mod silhouette;
mod sun;

use clap::{Parser, Subcommand};

use crate::photometry::PhotometryError;

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
    /// Read "x y z nx ny nz" lines from stdin and print the direct illuminance (lux) at each.
    Illuminance(render::IlluminanceArgs),
    /// The sun's position (NREL SPA) for a site and an instant.
    Sun(sun::SunArgs),
    /// Solve the scene's interreflected light (GPU progressive radiosity): rendering,
    /// light-map atlas, convergence log; with --points the total lux at points from stdin.
    Radiosity(radiosity::RadiosityArgs),
    /// Sun-path shadow profile of an OBJ model over a period: profile.png, hours.png,
    /// profile.csv.
    Profile(profile::ProfileArgs),
    /// Silhouette edges of an OBJ model for a point or directional light.
    Silhouette(silhouette::SilhouetteArgs),
    /// Benchmarks that print tables of ratios measured side by side.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// The interactive viewer: a scene (TOML) or an OBJ model, luminaires, sun, shadows,
    /// radiosity. `--frames N [--screenshot out.png]` renders N frames and exits.
    View(crate::viewer::ViewArgs),
}

/// A failed command: the error and whether it was the input's fault (exit 2) or not (1).
#[derive(Debug)]
pub struct CliError {
    /// What went wrong, with context.
    pub error: anyhow::Error,
    /// True for bad input or usage.
    pub bad_input: bool,
}

impl CliError {
    /// An error caused by the user's input (exit code 2).
    pub fn input(error: impl Into<anyhow::Error>) -> CliError {
        CliError {
            error: error.into(),
            bad_input: true,
        }
    }

    /// Any other failure (exit code 1).
    pub fn failure(error: impl Into<anyhow::Error>) -> CliError {
        CliError {
            error: error.into(),
            bad_input: false,
        }
    }

    /// The process exit code.
    pub fn code(&self) -> u8 {
        if self.bad_input {
            2
        } else {
            1
        }
    }
}

impl From<PhotometryError> for CliError {
    fn from(e: PhotometryError) -> CliError {
        let bad_input = e.is_bad_input();
        CliError {
            error: e.into(),
            bad_input,
        }
    }
}

/// The folder holding the bundled data (`assets/`, `luminaires/`): the source checkout the
/// binary was built from when it is still there, else the working directory.
pub fn data_root() -> std::path::PathBuf {
    let built = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    if built.join("assets").is_dir() && built.join("luminaires").is_dir() {
        built.to_path_buf()
    } else {
        std::path::PathBuf::from(".")
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Command::Ldt(cmd) => ldt::run(cmd),
        Command::Demo(args) => demo::run(args),
        Command::Render(args) => render::run(args),
        Command::Illuminance(args) => render::run_illuminance(args),
        Command::Sun(args) => sun::run(args),
        Command::Silhouette(args) => silhouette::run(args),
        Command::Profile(args) => profile::run(args),
        Command::Radiosity(args) => radiosity::run(args),
        Command::Bench(cmd) => bench::run(cmd),
        Command::View(args) => crate::viewer::run(args),
    }
}
