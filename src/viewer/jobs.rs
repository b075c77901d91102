//! Background work of the viewer: radiosity and shadow profiles run on their own threads
//! (sharing the window's GPU device), report progress through channels that the UI polls
//! every frame, and stop when asked; the UI thread never waits for them.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::geometry::Mesh;
use crate::gpu::Gpu;
use crate::photometry::Interp;
use crate::radiosity::gpu::{GpuSettings, GpuSolver};
use crate::radiosity::initial::{InitialState, LuminaireLight};
use crate::radiosity::scene::RadiosityScene;
use crate::radiosity::shooters::Hierarchy;
use crate::radiosity::solve;
use crate::radiosity::SolverSettings;
use crate::render::lightmap::LightMap;
use crate::render::ShadowSettings;
use crate::scene::Camera;
use crate::scene::Scene;
use crate::study::profile::{compute_on, prepare, Profile, ProfileError, ProfileSpec};
use crate::study::view_hours::{compute as view_hours, ViewHours};

/// Flags a worker reads between units of work.
#[derive(Debug, Default)]
pub struct JobControl {
    /// Stop as soon as possible (results so far are kept by the UI).
    pub cancel: AtomicBool,
    /// Hold between units of work until cleared.
    pub pause: AtomicBool,
    /// Set by the worker while it holds for `pause` (the unit under way has ended), so a
    /// pause can show "pausing…" until then.
    pub holding: AtomicBool,
}

/// A worker thread sending updates of type `U`.
pub struct Worker<U> {
    /// Its flags.
    pub control: Arc<JobControl>,
    updates: Receiver<U>,
    finished: bool,
}

impl<U: Send + 'static> Worker<U> {
    /// Starts `work` on a new thread; it sends updates and reads the flags.
    pub fn spawn(
        name: &str,
        work: impl FnOnce(Sender<U>, Arc<JobControl>) + Send + 'static,
    ) -> std::io::Result<Worker<U>> {
        let control = Arc::new(JobControl::default());
        let (tx, rx) = channel();
        let flags = control.clone();
        std::thread::Builder::new()
            .name(name.into())
            .spawn(move || work(tx, flags))?;
        Ok(Worker {
            control,
            updates: rx,
            finished: false,
        })
    }

    /// Every update sent since the last call (never blocks).
    pub fn poll(&mut self) -> Vec<U> {
        let mut out = Vec::new();
        loop {
            match self.updates.try_recv() {
                Ok(u) => out.push(u),
                Err(std::sync::mpsc::TryRecvError::Empty) => break,
                Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                    self.finished = true;
                    break;
                }
            }
        }
        out
    }

    /// Whether the thread has ended (and every update was polled).
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// Asks the thread to stop (it ends on its own; nothing waits for it).
    pub fn cancel(&self) {
        self.control.cancel.store(true, Ordering::SeqCst);
        self.control.pause.store(false, Ordering::SeqCst);
    }
}

impl<U> Drop for Worker<U> {
    fn drop(&mut self) {
        self.control.cancel.store(true, Ordering::SeqCst);
    }
}

/// What a radiosity run is asked to do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadiositySettings {
    /// Elements (light-map texels) per metre.
    pub texel_density: f64,
    /// Shooting patches of 2^level texels.
    pub level: u32,
    /// Stop at this converged fraction of the initial unshot power.
    pub converge: f64,
    /// Form factor and ambient options.
    pub solver: SolverSettings,
    /// Visibility maps.
    pub gpu: GpuSettings,
    /// Seconds between displayed updates.
    pub update_every_s: f64,
}

impl Default for RadiositySettings {
    fn default() -> Self {
        RadiositySettings {
            texel_density: 10.0,
            level: 2,
            converge: 0.99,
            solver: SolverSettings::default(),
            gpu: GpuSettings {
                hierarchy: Hierarchy::Clusters,
                ..GpuSettings::default()
            },
            update_every_s: 0.5,
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
    /// Converged, nothing left to shoot, or stopped.
    Done(String),
    /// An error.
    Failed(String),
}

/// Starts a radiosity solution of `scene` on `gpu`.
pub fn start_radiosity(
    gpu: Arc<Gpu>,
    scene: Scene,
    settings: RadiositySettings,
    shadows: ShadowSettings,
) -> std::io::Result<Worker<RadiosityUpdate>> {
    Worker::spawn("radiosity", move |tx, control| {
        let outcome = solve_radiosity(&gpu, &scene, &settings, &shadows, &tx, &control);
        let _ = tx.send(match outcome {
            Ok(reason) => RadiosityUpdate::Done(reason),
            Err(e) => RadiosityUpdate::Failed(e),
        });
    })
}

fn solve_radiosity(
    gpu: &Gpu,
    scene: &Scene,
    settings: &RadiositySettings,
    shadows: &ShadowSettings,
    tx: &Sender<RadiosityUpdate>,
    control: &JobControl,
) -> Result<String, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let rscene = RadiosityScene::with_hierarchy(
        scene,
        settings.texel_density,
        settings.level,
        settings.gpu.hierarchy,
    )
    .map_err(|e| err(&e))?;
    let interp: Interp = settings.solver.interp;
    let light = LuminaireLight::new(gpu, scene, interp);
    let initial =
        InitialState::from_luminaires_gpu(gpu, &light, &rscene, shadows).map_err(|e| err(&e))?;
    let mut solver = GpuSolver::new(gpu, &rscene, &initial, settings.solver, settings.gpu);
    let _ = tx.send(RadiosityUpdate::Prepared {
        elements: rscene.elements.len(),
        patches: rscene.elements.patches.len(),
    });
    let mut seconds = 0.0;
    let mut initial_unshot = None;
    let mut last_shown: Option<Instant> = None;
    let show = |solver: &GpuSolver, shots, seconds, convergence| -> Result<(), String> {
        let (b, e) = solver.radiosity_and_illuminance().map_err(|e| err(&e))?;
        let unshot = solver.unshot().map_err(|e| err(&e))?;
        let (b, e) = solve::displayed(&rscene, &b, &e, &unshot, settings.solver.ambient);
        let map = solve::light_map(&rscene, &b, &e);
        let _ = tx.send(RadiosityUpdate::Progress {
            shots,
            seconds,
            convergence,
            light_map: Some(Arc::new(map)),
        });
        Ok(())
    };
    loop {
        if control.cancel.load(Ordering::SeqCst) {
            return Ok("stopped".into());
        }
        if control.pause.load(Ordering::SeqCst) {
            control.holding.store(true, Ordering::SeqCst);
            std::thread::sleep(Duration::from_millis(30));
            continue;
        }
        control.holding.store(false, Ordering::SeqCst);
        let started = Instant::now();
        let s = solver.select().map_err(|e| err(&e))?;
        let initial = *initial_unshot.get_or_insert(s.unshot_power);
        let convergence = if initial > 0.0 {
            1.0 - s.unshot_power / initial
        } else {
            1.0
        };
        let finished = match s.shooter {
            _ if convergence >= settings.converge => Some("converged"),
            None => Some("nothing left to shoot"),
            Some(t) => {
                solver.shoot(t).map_err(|e| err(&e))?;
                None
            }
        };
        seconds += started.elapsed().as_secs_f64();
        let due = last_shown.is_none_or(|t| t.elapsed().as_secs_f64() >= settings.update_every_s);
        if let Some(reason) = finished {
            show(&solver, solver.shots, seconds, convergence)?;
            return Ok(reason.into());
        }
        if due {
            show(&solver, solver.shots, seconds, convergence)?;
            last_shown = Some(Instant::now());
        } else {
            let _ = tx.send(RadiosityUpdate::Progress {
                shots: solver.shots,
                seconds,
                convergence,
                light_map: None,
            });
        }
    }
}

/// A profile worker's report.
pub enum ProfileUpdate {
    /// Steps done of the total.
    Progress(usize, usize),
    /// The profile.
    Done(Box<Profile>),
    /// The hours of sun on the model from the camera the job was started with.
    View(Box<ViewHours>),
    /// Cancelled or failed.
    Failed(String),
}

/// Starts a shadow profile of `mesh` on `gpu`, then, with `view` (a perspective camera
/// and an image size), the hours of sun on the model seen from it.
pub fn start_profile(
    gpu: Arc<Gpu>,
    mesh: Mesh,
    spec: ProfileSpec,
    view: Option<(Camera, (u32, u32))>,
) -> std::io::Result<Worker<ProfileUpdate>> {
    Worker::spawn("shadow profile", move |tx, control| {
        let parts = 1 + view.is_some() as usize;
        let progress = |part: usize| {
            let tx = tx.clone();
            move |done, total| {
                let _ = tx.send(ProfileUpdate::Progress(part * total + done, parts * total));
            }
        };
        let failed = |e: ProfileError| match e {
            ProfileError::Cancelled => ProfileUpdate::Failed("cancelled".into()),
            e => ProfileUpdate::Failed(e.to_string()),
        };
        let profile = prepare(&gpu, &mesh).and_then(|geometry| {
            compute_on(&gpu, &geometry, &spec, progress(0), &control.cancel).map(|p| (p, geometry))
        });
        let geometry = match profile {
            Ok((p, geometry)) => {
                let _ = tx.send(ProfileUpdate::Done(Box::new(p)));
                geometry
            }
            Err(e) => return drop(tx.send(failed(e))),
        };
        if let Some((camera, size)) = view {
            let v = view_hours(
                &gpu,
                &geometry,
                &spec,
                &camera,
                size,
                progress(1),
                &control.cancel,
            );
            let _ = tx.send(match v {
                Ok(v) => ProfileUpdate::View(Box::new(v)),
                Err(e) => failed(e),
            });
        }
    })
}
