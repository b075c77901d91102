//! The command-line interface: clap definitions and dispatch. Commands call the library
//! and hold no logic of their own beyond reading input and printing results.

mod batch;
mod bench;
mod bench_adaptive;
mod calc;
mod demo;
mod error;
mod indirect;
mod ldt;
mod profile;
mod radiosity;
mod render;
mod render_command;
mod silhouette;
mod sun;
#[cfg(feature = "viewer")]
mod view;

use clap::{Parser, Subcommand};

pub use batch::count_jobs;
pub use error::CliError;

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
    Render(render_command::RenderArgs),
    /// Read "x y z nx ny nz" lines from stdin and print the direct illuminance (lux) at each.
    Illuminance(render::IlluminanceArgs),
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
    /// Sun-path shadow profile of an OBJ model over a period: profile.png, hours.png,
    /// profile.csv.
    Profile(profile::ProfileArgs),
    /// Silhouette edges of an OBJ model for a point or directional light.
    Silhouette(silhouette::SilhouetteArgs),
    /// Run a list of command lines (a TOML jobs file) in one process, optionally one shard
    /// of it (`--shard K/N`), with a JSON summary.
    Batch(batch::BatchArgs),
    /// Benchmarks that print tables of ratios measured side by side.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// The interactive viewer: a scene (TOML) or an OBJ model, luminaires, sun, shadows,
    /// radiosity. `--frames N [--screenshot out.png]` renders N frames and exits.
    #[cfg(feature = "viewer")]
    View(view::ViewArgs),
}

pub use crate::io::data_root;

/// clap's parser of a number of seconds (time limits): positive, finite and at most
/// [`crate::io::limits::MAX_SECONDS`], so that no later conversion to a duration fails.
pub(crate) fn seconds_arg(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().parse().map_err(|e| format!("{s:?}: {e}"))?;
    crate::io::limits::duration(v)?;
    Ok(v)
}

/// Whether the running command polls [`interrupt_flag`] (it asked for it): then a first
/// signal lets it finish its step; otherwise a signal ends the process at once.
static POLLED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// The process-wide flag set by SIGINT (Ctrl-C), SIGTERM or SIGHUP. A command that calls
/// this polls it: the first signal sets it, and the command finishes its current step and
/// writes a complete set or nothing (as each documents), a batch starts no further job. A
/// second signal, or the first in a command that never asked for the flag, removes the
/// temporary files and staging folders of the writes in progress and ends the process at
/// once (exit 130).
pub fn interrupt_flag() -> std::sync::Arc<std::sync::atomic::AtomicBool> {
    POLLED.store(true, std::sync::atomic::Ordering::SeqCst);
    signal_flag()
}

/// The flag, with the handler installed on first use.
fn signal_flag() -> std::sync::Arc<std::sync::atomic::AtomicBool> {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, OnceLock};
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let set = flag.clone();
        let _ = ctrlc::set_handler(move || {
            if !POLLED.load(Ordering::SeqCst) || set.swap(true, Ordering::SeqCst) {
                // Nothing half-written stays: the temporary files and staging folders go.
                crate::io::outputs::remove_unfinished();
                std::process::exit(130);
            }
            eprintln!("\ninterrupted: finishing the current step (Ctrl-C again to quit)");
        });
        flag
    })
    .clone()
}

/// An error naming `flag` when the folder `path` goes into does not exist (checked before
/// the work, so that the run does not fail at its end).
pub(crate) fn check_folder_of(path: &std::path::Path, flag: &str) -> Result<(), CliError> {
    let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
    if folder.is_some_and(|f| !f.is_dir()) {
        return Err(CliError::input(anyhow::anyhow!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            folder.expect("checked").display()
        )));
    }
    Ok(())
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), CliError> {
    // Every command ends cleanly on a signal; those that poll the flag ask for it.
    signal_flag();
    match cli.command {
        Command::Ldt(cmd) => ldt::run(cmd),
        Command::Demo(args) => demo::run(args),
        Command::Render(args) => render_command::run(args),
        Command::Illuminance(args) => render::run_illuminance(args),
        Command::Calc(args) => calc::run(args),
        Command::Sun(args) => sun::run(args),
        Command::Silhouette(args) => silhouette::run(args),
        Command::Profile(args) => profile::run(args),
        Command::Radiosity(args) => radiosity::run(args),
        Command::Batch(args) => batch::run(args),
        Command::Bench(cmd) => bench::run(cmd),
        #[cfg(feature = "viewer")]
        Command::View(args) => view::run(args),
    }
}
