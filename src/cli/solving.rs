//! A radiosity solve as the commands show it (`radiosity`, `calc --indirect radiosity`,
//! `render`/`demo --indirect radiosity`): a spinner naming the preparation's stage, a bar
//! of the convergence, the library's summary lines on standard error, Ctrl-C stopping the
//! preparation with an error and the shooting with the solution so far; the gather at
//! points with its bar.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::anyhow;

use super::error::{flags_in, CliError};
use crate::gpu::Gpu;
use crate::lighting::SurfacePoint;
use crate::radiosity::session::{self, Event, Options, Session, SessionError, Solution, Stage};
use crate::scene::Scene;

/// What a solve shows on the terminal: a spinner naming the preparation's stage, a bar
/// of the convergence, and the summary lines (standard error).
struct Progress<'a> {
    /// The scene file (for messages).
    label: &'a Path,
    /// When the command started.
    started: Instant,
    /// Seconds from `started` to the end of loading the scene.
    load_s: f64,
    spinner: Option<indicatif::ProgressBar>,
    bar: Option<indicatif::ProgressBar>,
    prepared_s: f64,
    error: Option<CliError>,
}

/// Steps of the convergence bar.
const BAR_STEPS: u64 = 10_000;

fn style(template: &str) -> Result<indicatif::ProgressStyle, CliError> {
    indicatif::ProgressStyle::with_template(template).map_err(|e| CliError::failure(anyhow!(e)))
}

/// A spinner naming a stage (drawn on a terminal only).
pub fn spinner(first: &str) -> Result<indicatif::ProgressBar, CliError> {
    let spinner = indicatif::ProgressBar::new_spinner();
    spinner.set_style(style("{spinner} radiosity: {msg} ({elapsed})")?);
    spinner.enable_steady_tick(Duration::from_millis(100));
    spinner.set_message(first.to_string());
    Ok(spinner)
}

impl Progress<'_> {
    fn event(&mut self, event: Event) {
        if let Err(e) = self.show(event) {
            self.error.get_or_insert(e);
        }
    }

    fn show(&mut self, event: Event) -> Result<(), CliError> {
        match event {
            Event::Stage(stage) if stage != Stage::Importance => {
                let name = stage.name();
                match &self.spinner {
                    Some(s) => s.set_message(name),
                    None => self.spinner = Some(spinner(name)?),
                }
            }
            Event::Stage(_) => {}
            Event::Prepared(p) => {
                if let Some(s) = self.spinner.take() {
                    s.finish_and_clear();
                }
                self.prepared_s = self.started.elapsed().as_secs_f64();
                if let Some(line) = p.adaptive_line() {
                    eprintln!("{line}");
                }
                let line = p.summary(self.load_s, self.prepared_s);
                eprintln!("{}: {line}", self.label.display());
            }
            Event::Shooting(session) => {
                for line in session.shooting_summary() {
                    eprintln!("{}: {}", self.label.display(), flags_in(&line));
                }
                let bar = indicatif::ProgressBar::new(BAR_STEPS);
                bar.set_style(style(
                    "radiosity [{bar:40}] {msg} ({elapsed_precise}, Ctrl-C stops and writes)",
                )?);
                self.bar = Some(bar);
            }
            Event::Shot(p) => {
                if let Some(bar) = &self.bar {
                    bar.set_position(Session::progress_position(p.convergence, BAR_STEPS));
                    bar.set_message(Session::progress_line(p.convergence, p.shot));
                }
            }
            Event::Solved(session) => {
                if let Some(bar) = self.bar.take() {
                    bar.finish_and_clear();
                }
                for line in session.solved_summary(self.prepared_s) {
                    eprintln!("{}: {}", self.label.display(), flags_in(&line));
                }
            }
        }
        Ok(())
    }
}

impl Drop for Progress<'_> {
    fn drop(&mut self) {
        for bar in [self.spinner.take(), self.bar.take()].into_iter().flatten() {
            bar.finish_and_clear();
        }
    }
}

/// A solve's error as the command reports it: a cancelled preparation wrote nothing.
pub fn session_error(e: SessionError, label: &Path) -> CliError {
    match e {
        SessionError::Cancelled(
            stage @ (Stage::Elements | Stage::DirectLight | Stage::Importance),
        ) => CliError::failure(anyhow!(
            "interrupted while preparing ({}): nothing written",
            stage.name()
        )),
        SessionError::Option(o) => CliError::from(o),
        SessionError::Cancelled(_) | SessionError::Gpu(_) => CliError::from(e),
        e => {
            let bad = e.is_bad_input();
            CliError::classified(anyhow!("{}: {e}", label.display()), bad)
        }
    }
}

/// Solves `scene` (loaded from `label` by now, the command having started at `started`)
/// with `options` on the shared device, with a spinner, a progress bar and summary
/// lines; Ctrl-C stops the preparation with an error and the shooting with the solution
/// so far.
pub fn solve(
    label: &Path,
    scene: &Scene,
    options: &Options,
    settings: &mut crate::render::RenderSettings,
    started: Instant,
) -> Result<Solution, CliError> {
    let load_s = started.elapsed().as_secs_f64();
    let aspect = settings.aspect();
    let gpu = Gpu::shared()?;
    let cancel = super::interrupt::interrupt_flag();
    let mut progress = Progress {
        label,
        started,
        load_s,
        spinner: None,
        bar: None,
        prepared_s: 0.0,
        error: None,
    };
    let setup = session::Setup {
        scene,
        options,
        interp: settings.light_model.interp(),
        shadows: &mut settings.shadows,
        view: Some((&scene.camera, aspect)),
    };
    let solution = session::solve(&gpu, setup, &cancel, &mut |e| progress.event(e))
        .map_err(|e| session_error(e, label))?;
    super::scene_input::warn_shadow_fit(scene, &settings.shadows);
    match progress.error.take() {
        Some(e) => Err(e),
        None => Ok(solution),
    }
}

/// The illuminance of `solution` at `points` (lux; `total`: direct and interreflected,
/// else interreflected only), with a progress bar; Ctrl-C stops it with an error.
pub fn gathered_lux(
    label: &Path,
    solution: &Solution,
    points: &[SurfacePoint],
    total: bool,
) -> Result<Vec<f64>, CliError> {
    eprintln!(
        "gathering at {} points from {} patches (Ctrl-C stops)",
        points.len(),
        solution.gather_patches()
    );
    let bar = indicatif::ProgressBar::new(points.len() as u64);
    bar.set_style(style(
        "gather [{bar:40}] {pos}/{len} points ({elapsed_precise}, Ctrl-C stops)",
    )?);
    // A Ctrl-C that stopped the shooting has been answered: the next one stops this.
    let cancel = super::interrupt::interrupt_flag();
    cancel.store(false, Ordering::SeqCst);
    let progress = |done: usize| bar.set_position(done as u64);
    let lux = if total {
        solution.lux(points, &cancel, &progress)
    } else {
        solution.interreflected_lux(points, &cancel, &progress)
    };
    bar.finish_and_clear();
    lux.map_err(|e| session_error(e, label))
}

/// An error if Ctrl-C came while `stage` ran (before anything is written).
pub fn interrupted_while(cancel: &AtomicBool, stage: &str) -> Result<(), CliError> {
    if cancel.load(Ordering::SeqCst) {
        return Err(CliError::failure(anyhow!(
            "interrupted while preparing ({stage}): nothing written"
        )));
    }
    Ok(())
}
