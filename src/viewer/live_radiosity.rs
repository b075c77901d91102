//! The viewer's radiosity, live: a background solver that shoots within a time budget
//! granted frame by frame (so the window stays interactive while it converges), shows its
//! solution every few tenths of a second with the ambient term for what is not shot yet,
//! follows the camera when the view drives it (importance or perspective, Bozalina), and
//! when luminaires move, dim, come or go re-shoots the change in place
//! ([`crate::radiosity::session::Session::relight`]) instead of starting over. Once
//! converged it waits for the next change.

use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, TryRecvError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use super::jobs::{JobControl, Worker};
use crate::gpu::Gpu;
use crate::photometry::Interp;
use crate::radiosity::session::{Follow, Options, Prepared, Session, SessionError, Setup};
use crate::radiosity::solve::StopReason;
use crate::render::lightmap::LightMap;
use crate::render::ShadowSettings;
use crate::scene::{Camera, Scene};

/// The longest an importance solve for a new view may take, seconds.
const IMPORTANCE_SECONDS: f64 = 2.0;

/// What a radiosity run is asked to do.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiositySettings {
    /// The solve's options (the command line's defaults; the importance solve of a new
    /// view limited to [`IMPORTANCE_SECONDS`]). A converge of 0 shoots nothing: the
    /// luminaires' first bounce and the ambient term. Adaptive subdivision's splits
    /// follow the luminaires where the run started: one moved later keeps them, and its
    /// new edges are as fine as the elements there.
    pub options: Options,
    /// Interpolation of the luminaires' distributions.
    pub interp: Interp,
    /// Seconds between displayed updates.
    pub update_every_s: f64,
    /// Milliseconds of solving each displayed frame grants (0: no limit).
    pub frame_budget_ms: f64,
}

impl Default for RadiositySettings {
    fn default() -> Self {
        RadiositySettings {
            options: Options {
                importance_time_limit: Some(IMPORTANCE_SECONDS),
                ..Options::default()
            },
            interp: Interp::CatmullRom,
            update_every_s: 0.5,
            frame_budget_ms: 40.0,
        }
    }
}

/// A radiosity worker's report.
pub enum RadiosityUpdate {
    /// The scene was meshed and the luminaires shot.
    Prepared {
        /// Elements (texels).
        elements: usize,
        /// Shooting patches.
        patches: usize,
    },
    /// The solution so far.
    Progress {
        /// Shots done.
        shots: usize,
        /// Seconds of shooting (pauses excluded).
        seconds: f64,
        /// Converged fraction.
        convergence: f64,
        /// The displayable solution, when one was made for this update.
        light_map: Option<Arc<LightMap>>,
    },
    /// What changed on the way (relit, view followed), for the status line.
    Note(String),
    /// Converged or nothing left to shoot: the worker waits for a change.
    Done(String),
    /// An error (the worker has ended).
    Failed(String),
}

/// What the viewer tells a running solver.
pub enum RadiosityCommand {
    /// The luminaires changed (the geometry did not): this is the scene now, its
    /// distributions interpolated so.
    Relight(Box<Scene>, Interp),
    /// The camera moved: the view (with the viewport's width / height) to drive by.
    View(Camera, f64),
}

/// The solver's share of each frame: every displayed frame grants
/// [`RadiositySettings::frame_budget_ms`], the worker spends it on shots (stopping a shot
/// between batches when it is used up) and waits while none is left. At most two frames'
/// worth is kept, so an idle window does not save up a long stall.
#[derive(Debug)]
pub struct FrameCredit {
    per_frame_us: i64,
    credit_us: AtomicI64,
}

impl FrameCredit {
    /// A credit of `per_frame_ms` per frame (0: unlimited).
    pub fn new(per_frame_ms: f64) -> FrameCredit {
        let per_frame_us = (per_frame_ms.max(0.0) * 1000.0) as i64;
        FrameCredit {
            per_frame_us,
            credit_us: AtomicI64::new(per_frame_us),
        }
    }

    /// One frame was displayed.
    pub fn grant(&self) {
        let cap = 2 * self.per_frame_us;
        let _ = self
            .credit_us
            .fetch_update(Ordering::SeqCst, Ordering::SeqCst, |c| {
                Some((c.max(0) + self.per_frame_us).min(cap))
            });
    }

    /// How long the solver may work now (`None`: no limit; zero: wait for a frame).
    pub fn available(&self) -> Option<Duration> {
        (self.per_frame_us > 0)
            .then(|| Duration::from_micros(self.credit_us.load(Ordering::SeqCst).max(0) as u64))
    }

    /// The solver worked `spent`.
    pub fn spend(&self, spent: Duration) {
        if self.per_frame_us > 0 {
            self.credit_us
                .fetch_sub(spent.as_micros() as i64, Ordering::SeqCst);
        }
    }
}

/// The viewer's hold on a running live solver besides its worker: where commands go and
/// its frame credit.
pub struct LiveLink {
    /// Commands to it.
    pub commands: Sender<RadiosityCommand>,
    /// Its share of each frame.
    pub credit: Arc<FrameCredit>,
}

/// Starts a live radiosity solution of `scene` on `gpu`, driven by `view` (a camera and
/// the viewport's width / height) when `settings.options.drive` is not global.
pub fn start(
    gpu: Arc<Gpu>,
    scene: Scene,
    settings: RadiositySettings,
    shadows: ShadowSettings,
    view: Option<(Camera, f64)>,
) -> std::io::Result<(Worker<RadiosityUpdate>, LiveLink)> {
    let (commands, inbox) = std::sync::mpsc::channel();
    let credit = Arc::new(FrameCredit::new(settings.frame_budget_ms));
    let share = credit.clone();
    let worker = Worker::spawn("radiosity", move |tx, control| {
        let job = Job {
            gpu: &gpu,
            settings: &settings,
            shadows: &shadows,
            tx: &tx,
            control: &control,
            credit: &share,
        };
        if let Err(e) = job.run(&scene, view, &inbox) {
            let _ = tx.send(RadiosityUpdate::Failed(e));
        }
    })?;
    Ok((worker, LiveLink { commands, credit }))
}

struct Job<'a> {
    gpu: &'a Gpu,
    settings: &'a RadiositySettings,
    shadows: &'a ShadowSettings,
    tx: &'a Sender<RadiosityUpdate>,
    control: &'a JobControl,
    credit: &'a FrameCredit,
}

fn err(e: &dyn std::fmt::Display) -> String {
    e.to_string()
}

impl Job<'_> {
    fn send(&self, u: RadiosityUpdate) {
        let _ = self.tx.send(u);
    }

    /// The solution as shown: with the ambient term (the view's where the view drives).
    fn show(&self, session: &Session, seconds: f64, convergence: f64) -> Result<(), String> {
        let light_map = session.light_map().map_err(|e| err(&e))?;
        self.send(RadiosityUpdate::Progress {
            shots: session.solver().stats.shots,
            seconds,
            convergence,
            light_map: Some(Arc::new(light_map)),
        });
        Ok(())
    }

    /// Meshes, shoots the luminaires, then solves until cancelled, taking commands.
    fn run(
        &self,
        scene: &Scene,
        view: Option<(Camera, f64)>,
        inbox: &Receiver<RadiosityCommand>,
    ) -> Result<(), String> {
        let s = self.settings;
        let mut shadows = self.shadows.clone();
        let setup = Setup {
            scene,
            options: &s.options,
            interp: s.interp,
            shadows: &mut shadows,
            view: None,
        };
        let prepared = match Prepared::new(self.gpu, setup, &self.control.cancel, &mut |_| {}) {
            Ok(p) => p,
            Err(SessionError::Cancelled(_)) => return Ok(()),
            Err(e) => return Err(err(&e)),
        };
        let mut session = prepared.session(&mut |_| {}).map_err(|e| err(&e))?;
        if s.frame_budget_ms > 0.0 {
            // A shot stops between batches: half a frame's share each.
            session.set_batch_seconds(s.frame_budget_ms / 2000.0);
        }
        let rscene = prepared.scene();
        self.send(RadiosityUpdate::Prepared {
            elements: rscene.elements.len(),
            patches: rscene.elements.patches.len(),
        });
        if let Some((camera, aspect)) = &view {
            session.follow(camera, *aspect).map_err(|e| err(&e))?;
        }
        let mut seconds = 0.0;
        let mut done = false;
        let mut last_shown: Option<Instant> = None;
        let mut convergence = 0.0;
        loop {
            if self.control.cancel.load(Ordering::SeqCst) {
                return Ok(());
            }
            // A converged solver sleeps until told something.
            let command = if done {
                match inbox.recv_timeout(Duration::from_millis(50)) {
                    Ok(c) => Some(c),
                    Err(RecvTimeoutError::Timeout) => None,
                    Err(RecvTimeoutError::Disconnected) => return Ok(()),
                }
            } else {
                match inbox.try_recv() {
                    Ok(c) => Some(c),
                    Err(TryRecvError::Empty) => None,
                    Err(TryRecvError::Disconnected) => return Ok(()),
                }
            };
            if let Some(first) = command {
                let took = Instant::now();
                let notes = apply(&mut session, latest(first, inbox)).map_err(|e| err(&e))?;
                if notes.is_empty() {
                    continue;
                }
                done = false;
                self.send(RadiosityUpdate::Note(format!(
                    "{} ({:.2} s)",
                    notes.join("; "),
                    took.elapsed().as_secs_f64()
                )));
                self.show(&session, seconds, convergence)?;
                last_shown = Some(Instant::now());
                continue;
            }
            if done {
                continue;
            }
            if self.control.pause.load(Ordering::SeqCst) {
                self.control.holding.store(true, Ordering::SeqCst);
                std::thread::sleep(Duration::from_millis(30));
                continue;
            }
            self.control.holding.store(false, Ordering::SeqCst);
            let available = self.credit.available();
            if available.is_some_and(|d| d.is_zero()) {
                std::thread::sleep(Duration::from_millis(2));
                continue;
            }
            let started = Instant::now();
            let (point, finished) = session
                .step(available, &self.control.cancel)
                .map_err(|e| err(&e))?;
            if finished == Some(StopReason::Cancelled) {
                return Ok(());
            }
            convergence = point.convergence;
            let spent = started.elapsed();
            self.credit.spend(spent);
            seconds += spent.as_secs_f64();
            let due = last_shown.is_none_or(|t| t.elapsed().as_secs_f64() >= s.update_every_s);
            if finished.is_some() || due {
                self.show(&session, seconds, convergence)?;
                last_shown = Some(Instant::now());
            } else {
                self.send(RadiosityUpdate::Progress {
                    shots: session.solver().stats.shots,
                    seconds,
                    convergence,
                    light_map: None,
                });
            }
            if let Some(reason) = finished {
                self.send(RadiosityUpdate::Done(reason.to_string()));
                done = true;
            }
        }
    }
}

/// Relights `session` and follows the view as `latest` asks; what changed, for the
/// status line.
fn apply(session: &mut Session, latest: Latest) -> Result<Vec<&'static str>, SessionError> {
    let mut notes = Vec::new();
    if let Some((new_scene, interp)) = latest.relight {
        session.relight(&new_scene, interp)?;
        notes.push("relit: the luminaires' change re-shot in place");
    }
    if let Some((camera, aspect)) = latest.view {
        let driven = session.driven().is_some();
        match session.follow(&camera, aspect)? {
            Follow::Following => notes.push("following the view (importance solved again)"),
            Follow::Kept if driven => {
                notes.push("the view sees no surface: still driven by the last one")
            }
            Follow::Kept | Follow::Global => {}
        }
    }
    Ok(notes)
}

/// What the commands waiting at once come to: the latest luminaires (and interpolation)
/// and the latest view.
#[derive(Default)]
struct Latest {
    relight: Option<(Box<Scene>, Interp)>,
    view: Option<(Camera, f64)>,
}

/// `first` and every command waiting behind it, reduced to the latest of each kind (a
/// dragged luminaire sends one per frame; only where it ends counts).
fn latest(first: RadiosityCommand, inbox: &Receiver<RadiosityCommand>) -> Latest {
    let mut latest = Latest::default();
    for c in std::iter::once(first).chain(inbox.try_iter()) {
        match c {
            RadiosityCommand::Relight(scene, interp) => latest.relight = Some((scene, interp)),
            RadiosityCommand::View(camera, aspect) => latest.view = Some((camera, aspect)),
        }
    }
    latest
}

#[cfg(test)]
mod tests {
    use super::FrameCredit;
    use std::time::Duration;

    #[test]
    fn each_frame_grants_its_share_and_at_most_two_frames_are_kept() {
        let c = FrameCredit::new(40.0);
        assert_eq!(c.available(), Some(Duration::from_millis(40)));
        c.spend(Duration::from_millis(55));
        assert_eq!(c.available(), Some(Duration::ZERO), "overspent: wait");
        // The overspent 15 ms are forgiven by the next frame (a batch may overrun).
        c.grant();
        assert_eq!(c.available(), Some(Duration::from_millis(40)));
        for _ in 0..10 {
            c.grant();
        }
        assert_eq!(c.available(), Some(Duration::from_millis(80)));
    }

    #[test]
    fn no_budget_means_no_limit() {
        let c = FrameCredit::new(0.0);
        c.spend(Duration::from_secs(5));
        c.grant();
        assert_eq!(c.available(), None);
    }
}
