//! One radiosity solve, whichever front end asks for it (the command line, `calc
//! --indirect`, `render --indirect`, the viewer's live solver, the benchmarks, Python):
//!
//! 1. [`Prepared::new`]: the scene's elements (and face clusters), the luminaires' direct
//!    light on them, checked against the device's limits;
//! 2. [`Prepared::session`]: the shooters and the GPU solver, driven by the camera's
//!    importance where [`Options::drive`] asks (its solve taken out of the time limit);
//! 3. [`Session::step`] (a slice of time at a time, as the viewer grants it frame by frame)
//!    or [`Session::solve`] (to [`Options`]' stop), [`Session::relight`] after the
//!    luminaires moved, dimmed, came or went, [`Session::follow`] when the camera moved;
//! 4. [`Session::finish`] and [`Prepared::into_solution`]: the [`Solution`] as shown (the
//!    ambient term where asked), its light map, the illuminance gathered at points and
//!    the glTF export.
//!
//! [`solve`] runs the four in a row. Progress comes through [`Event`]s; a cancel flag
//! stops the preparation between stages (an error: nothing to show), the shooting
//! between batches (the solution so far) and the gather (an error).

pub mod describe;
mod options;

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;

pub use self::options::{OptionError, Options};
use super::bake::{self, BakeChoice, BakePlan};
use super::elements::ElementError;
use super::gather::{self, GatherPatch};
use super::gpu::GpuSolver;
use super::initial::{InitialState, LuminaireLight};
use super::scene::{luminance, RadiosityScene};
use super::shooters::Shooters;
use super::solve::{self, ConvergencePoint, ShotRun, StopAt, StopReason};
use super::view::{self, Drive, ViewDriven, ViewPoint};
use crate::gpu::{Gpu, GpuError};
use crate::lighting::{usable_lux, SurfacePoint, UnusableLux};
use crate::photometry::Interp;
use crate::render::lightmap::LightMap;
use crate::render::ShadowSettings;
use crate::scene::{Camera, Scene};

/// A stage of a solve, as progress names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// The elements, light-map atlas and (with clusters) the face clusters and charts.
    Elements,
    /// The luminaires' direct light on the elements.
    DirectLight,
    /// The importance the camera sends through the scene (a view-driven solution).
    Importance,
    /// Gathering the solution's light at points.
    Gathering,
}

impl Stage {
    /// What the stage does, in words.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Elements => "elements and atlas",
            Stage::DirectLight => "the luminaires' direct light",
            Stage::Importance => "the view's importance",
            Stage::Gathering => "gathering at the points",
        }
    }
}

/// What a solve reports as it goes.
pub enum Event<'a> {
    /// A stage begins.
    Stage(Stage),
    /// The scene is prepared.
    Prepared(&'a Prepared),
    /// The session is set up and about to shoot.
    Shooting(&'a Session<'a>),
    /// The state before a shot (the log's newest point).
    Shot(&'a ConvergencePoint),
    /// The shooting stopped.
    Solved(&'a Session<'a>),
}

/// Why a solve failed.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// An option out of range (or one the scene cannot be solved with).
    #[error(transparent)]
    Option(#[from] OptionError),
    /// The scene's elements could not be made.
    #[error(transparent)]
    Elements(#[from] ElementError),
    /// The GPU failed, or the scene exceeds its limits ([`GpuError::Limit`]).
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A view-driven solution with an orthographic camera.
    #[error("drive {0} needs a perspective camera (the scene's is orthographic)")]
    NeedsPerspective(&'static str),
    /// A view-driven solution whose camera sees nothing.
    #[error("drive {0}: the camera sees no surface of the scene (check camera.position and camera.look_at)")]
    SeesNothing(&'static str),
    /// The cancel flag was set during a stage that has nothing to show for it.
    #[error("interrupted while {}", .0.name())]
    Cancelled(Stage),
    /// A computed illuminance is not a usable number (refused, never returned).
    #[error(transparent)]
    Unusable(#[from] UnusableLux),
}

impl SessionError {
    /// Whether the input (options, scene) is to blame rather than the machine.
    pub fn is_bad_input(&self) -> bool {
        match self {
            SessionError::Gpu(e) => matches!(e, GpuError::Limit(_)),
            SessionError::Cancelled(_) | SessionError::Unusable(_) => false,
            _ => true,
        }
    }
}

/// What a solve is of: the scene, the options, and how the luminaires light it.
pub struct Setup<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The solver's options (validated by [`Prepared::new`]).
    pub options: &'a Options,
    /// Interpolation of the luminaires' distributions.
    pub interp: Interp,
    /// The luminaires' shadows (the device's limits may lower them).
    pub shadows: &'a mut ShadowSettings,
    /// The camera and the image's width / height, which drive the solution where
    /// `options.drive` is not global (without one the solution is global until
    /// [`Session::follow`]).
    pub view: Option<(&'a Camera, f64)>,
}

/// Seconds the preparation took, by stage.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PrepareTimes {
    /// Elements and atlas (with clusters: the face clusters and receiving normals
    /// included; [`RadiosityScene::clustering_seconds`] and
    /// [`RadiosityScene::receiving_seconds`] give those).
    pub elements: f64,
    /// The luminaires' direct light on the elements.
    pub direct_light: f64,
}

/// A scene made ready to solve: its elements and the luminaires' direct light on them.
pub struct Prepared {
    gpu: Gpu,
    rscene: RadiosityScene,
    light: LuminaireLight,
    initial: InitialState,
    /// The scene's direct daylight on the elements (kept for relighting: the luminaires
    /// change, the sky does not).
    daylight: Option<super::initial::DirectLight>,
    options: Options,
    interp: Interp,
    shadows: ShadowSettings,
    view: Option<ViewPoint>,
    triangles: usize,
    /// Seconds per stage.
    pub times: PrepareTimes,
}

/// Returns `Cancelled(stage)` if `cancel` is set.
fn checkpoint(cancel: &AtomicBool, stage: Stage) -> Result<(), SessionError> {
    if cancel.load(Ordering::SeqCst) {
        return Err(SessionError::Cancelled(stage));
    }
    Ok(())
}

impl Prepared {
    /// Prepares `setup`'s scene for a solve on `gpu` (its options validated here);
    /// `cancel` stops it between stages.
    pub fn new(
        gpu: &Gpu,
        setup: Setup,
        cancel: &AtomicBool,
        events: &mut dyn FnMut(Event),
    ) -> Result<Prepared, SessionError> {
        let Setup {
            scene,
            options,
            interp,
            shadows,
            view,
        } = setup;
        options.validate()?;
        let view = match (options.drive, view) {
            (Drive::Global, _) | (_, None) => None,
            (drive, Some((camera, aspect))) => Some(
                ViewPoint::new(camera, aspect)
                    .ok_or(SessionError::NeedsPerspective(drive.name()))?,
            ),
        };
        events(Event::Stage(Stage::Elements));
        let started = Instant::now();
        let rscene = RadiosityScene::with_subdivision(
            scene,
            options.texel_density,
            options.level,
            options.hierarchy,
            options.subdivision(),
        )?;
        let elements = started.elapsed().as_secs_f64();
        checkpoint(cancel, Stage::Elements)?;
        crate::render::limits::check_scene(gpu, scene, shadows)?;
        crate::render::limits::check_radiosity(gpu, rscene.elements.len())?;
        events(Event::Stage(Stage::DirectLight));
        let started = Instant::now();
        let light = LuminaireLight::new(gpu, scene, interp);
        let mut initial = InitialState::from_luminaires_gpu(gpu, &light, &rscene, shadows)?;
        let daylight = super::initial::daylight_direct(&rscene);
        if let Some(d) = &daylight {
            initial.add_direct(&rscene, d);
        }
        checkpoint(cancel, Stage::DirectLight)?;
        let prepared = Prepared {
            gpu: gpu.clone(),
            rscene,
            light,
            initial,
            daylight,
            options: options.clone(),
            interp,
            shadows: shadows.clone(),
            view,
            triangles: scene.triangle_count(),
            times: PrepareTimes {
                elements,
                direct_light: started.elapsed().as_secs_f64(),
            },
        };
        events(Event::Prepared(&prepared));
        Ok(prepared)
    }

    /// The elements, patches and light-map atlas.
    pub fn scene(&self) -> &RadiosityScene {
        &self.rscene
    }

    /// The scene's triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// The options it was prepared with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// The luminaires' light before any interreflection.
    pub fn initial(&self) -> &InitialState {
        &self.initial
    }

    /// The device it runs on.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// A session on this preparation: the shooters, the GPU solver, and the view's
    /// importance where a view drives it (its time is taken from the time limit).
    pub fn session(&self, events: &mut dyn FnMut(Event)) -> Result<Session<'_>, SessionError> {
        let options = &self.options;
        options.check_raster(self.rscene.has_masked_casters())?;
        let shooters = Shooters::build(&self.rscene, options.hierarchy);
        let solver = GpuSolver::with_shooters(
            &self.gpu,
            &self.rscene,
            &self.initial,
            options.solver_settings(self.interp),
            options.gpu_settings(),
            shooters,
        );
        let mut session = Session {
            prepared: self,
            solver,
            driver: None,
            relit: None,
            stop: options.stop(),
            run: ShotRun::default(),
            log: Vec::new(),
            stopped: None,
        };
        if let Some(point) = &self.view {
            events(Event::Stage(Stage::Importance));
            let driver = session.drive_by(*point)?.ok_or(SessionError::SeesNothing(
                session.prepared.options.drive.name(),
            ))?;
            // The importance solve's time is the solve's.
            let spent = Duration::try_from_secs_f64(driver.driven.importance_seconds)
                .unwrap_or(Duration::MAX);
            session.stop.time_budget = session.stop.time_budget.map(|b| b.saturating_sub(spent));
            session.driver = Some(driver);
        }
        Ok(session)
    }

    /// The solution of a finished session on this preparation.
    pub fn into_solution(self, solved: Solved) -> Solution {
        Solution {
            prepared: self,
            solved,
        }
    }
}

/// The view driving a solution.
struct Driver {
    driven: ViewDriven,
    point: ViewPoint,
}

/// A view-driven solution's change of view ([`Session::follow`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Follow {
    /// The importance was solved for the new view, which drives the solution now.
    Following,
    /// The new view sees no surface (or is orthographic): the last view still drives.
    Kept,
    /// The solution is global: views do not drive it.
    Global,
}

/// A solve under way: the solver, the view driving it, its log.
pub struct Session<'p> {
    prepared: &'p Prepared,
    solver: GpuSolver<'p>,
    driver: Option<Driver>,
    /// The luminaires after [`Session::relight`]: their light and their first shot.
    relit: Option<(LuminaireLight, InitialState)>,
    stop: StopAt,
    run: ShotRun,
    log: Vec<ConvergencePoint>,
    stopped: Option<StopReason>,
}

impl<'p> Session<'p> {
    /// The solver (its counters: shots, maps drawn, cells skipped, …).
    pub fn solver(&self) -> &GpuSolver<'p> {
        &self.solver
    }

    /// The preparation it solves.
    pub fn prepared(&self) -> &'p Prepared {
        self.prepared
    }

    /// The importance solve of the view driving the solution, if one does.
    pub fn driven(&self) -> Option<&ViewDriven> {
        self.driver.as_ref().map(|d| &d.driven)
    }

    /// How often a shot may stop (between batches of this many seconds), so that a
    /// [`Session::step`] keeps to its slice.
    pub fn set_batch_seconds(&mut self, seconds: f64) {
        self.solver.set_batch_seconds(seconds);
    }

    /// The log so far (one point before each shot, and one where it stopped).
    pub fn log(&self) -> &[ConvergencePoint] {
        &self.log
    }

    /// The converged fraction at the newest log point (0 before the first step).
    pub fn convergence(&self) -> f64 {
        self.log.last().map_or(0.0, |p| p.convergence)
    }

    /// Why the last step stopped the solution (`None`: it goes on, or has not begun).
    pub fn stopped(&self) -> Option<StopReason> {
        self.stopped
    }

    /// One step: the next shooter chosen and shot for at most `slice` (`None`: the
    /// whole shot), unless the solution is done. Returns the log point and why the
    /// solution stops, if it does (a converged solution stays so until
    /// [`Session::relight`] or [`Session::follow`] changes it).
    pub fn step(
        &mut self,
        slice: Option<Duration>,
        cancel: &AtomicBool,
    ) -> Result<(ConvergencePoint, Option<StopReason>), SessionError> {
        let (point, reason) = self
            .solver
            .advance(&self.stop, &mut self.run, slice, cancel)?;
        self.log.push(point);
        self.stopped = reason;
        Ok((point, reason))
    }

    /// Steps until the options' stop (or `cancel`), each log point through `events`.
    pub fn solve(
        &mut self,
        cancel: &AtomicBool,
        events: &mut dyn FnMut(Event),
    ) -> Result<StopReason, SessionError> {
        loop {
            let (point, reason) = self.step(None, cancel)?;
            events(Event::Shot(&point));
            if let Some(r) = reason {
                return Ok(r);
            }
        }
    }

    /// The luminaires changed (moved, dimmed, came or went; the geometry did not): this
    /// is the scene now, its distributions interpolated by `interp`. The change is shot
    /// in place, and convergence is measured from the new luminaires' start, as a fresh
    /// solve of them would be.
    pub fn relight(&mut self, scene: &Scene, interp: Interp) -> Result<(), SessionError> {
        let p = self.prepared;
        let light = LuminaireLight::new(&p.gpu, scene, interp);
        let mut new = InitialState::from_luminaires_gpu(&p.gpu, &light, &p.rscene, &p.shadows)?;
        if let Some(d) = &p.daylight {
            new.add_direct(&p.rscene, d);
        }
        let old = self.relit.as_ref().map_or(&p.initial, |r| &r.1);
        self.solver.relight(old, &new)?;
        // The area of interest starts again around the view.
        if let Some(d) = &self.driver {
            d.driven.drive(
                &mut self.solver,
                p.options.drive,
                &d.point,
                p.options.fov_margin,
            )?;
        }
        self.run.scale = Some(self.solver.start_scale(&new.radiosity));
        self.relit = Some((light, new));
        self.stopped = None;
        Ok(())
    }

    /// The camera moved (`aspect`: the image's width / height): where the options drive
    /// the solution by the view, its importance is solved again and drives it.
    pub fn follow(&mut self, camera: &Camera, aspect: f64) -> Result<Follow, SessionError> {
        if self.prepared.options.drive == Drive::Global {
            return Ok(Follow::Global);
        }
        let Some(point) = ViewPoint::new(camera, aspect) else {
            return Ok(Follow::Kept);
        };
        match self.drive_by(point)? {
            Some(d) => {
                self.driver = Some(d);
                let start = self.relit.as_ref().map_or(&self.prepared.initial, |r| &r.1);
                self.run.scale = Some(self.solver.start_scale(&start.radiosity));
                self.stopped = None;
                Ok(Follow::Following)
            }
            None => Ok(Follow::Kept),
        }
    }

    /// Solves the importance of `point` and drives the solver by it; `None` (and nothing
    /// changed) when the view sees no surface.
    fn drive_by(&mut self, point: ViewPoint) -> Result<Option<Driver>, SessionError> {
        let p = self.prepared;
        let weights = view::view_weights(&p.rscene, &point);
        if weights.iter().all(|&w| w <= 0.0) {
            return Ok(None);
        }
        let driven = ViewDriven::new(
            &self.solver,
            p.options.solver_settings(p.interp),
            p.options.gpu_settings(),
            weights,
            p.options.importance_budget(),
        )?;
        driven.drive(
            &mut self.solver,
            p.options.drive,
            &point,
            p.options.fov_margin,
        )?;
        Ok(Some(Driver { driven, point }))
    }

    /// The solution as shown: radiosity and received illuminance per element, with the
    /// ambient term (the view's where a view drives) where the options show it.
    pub fn shown(&self) -> Result<(Vec<DVec3>, Vec<f64>), SessionError> {
        let (b, e) = self.solver.radiosity_and_illuminance()?;
        let unshot = self.solver.unshot_to_come()?;
        Ok(view::displayed(
            &self.prepared.rscene,
            &b,
            &e,
            &unshot,
            self.prepared.options.ambient,
            self.driven(),
        ))
    }

    /// The light-map atlas of the solution as shown.
    pub fn light_map(&self) -> Result<LightMap, SessionError> {
        let (b, e) = self.shown()?;
        Ok(solve::light_map(&self.prepared.rscene, &b, &e))
    }

    /// The solution as it stands, for [`Prepared::into_solution`].
    pub fn finish(self) -> Result<Solved, SessionError> {
        let (shown, shown_lux) = self.shown()?;
        let patches = gather::patches(&self.prepared.rscene, self.solver.shooters(), &shown);
        Ok(Solved {
            shown,
            shown_lux,
            patches,
            stop: self.stopped.unwrap_or(StopReason::Cancelled),
            log: self.log,
            relit: self.relit.map(|(light, _)| light),
        })
    }
}

/// What a finished session leaves: the solution as shown and its log.
pub struct Solved {
    shown: Vec<DVec3>,
    shown_lux: Vec<f64>,
    patches: Vec<GatherPatch>,
    stop: StopReason,
    log: Vec<ConvergencePoint>,
    relit: Option<LuminaireLight>,
}

/// A solution with what it was solved from: what every front end reads.
pub struct Solution {
    prepared: Prepared,
    solved: Solved,
}

impl Solution {
    /// The preparation (elements, options, device).
    pub fn prepared(&self) -> &Prepared {
        &self.prepared
    }

    /// Why the shooting stopped.
    pub fn stop(&self) -> StopReason {
        self.solved.stop
    }

    /// The convergence log.
    pub fn log(&self) -> &[ConvergencePoint] {
        &self.solved.log
    }

    /// The log as CSV (`shot,seconds,shooter,unshot_lm,convergence`).
    pub fn convergence_csv(&self) -> String {
        solve::convergence_csv(&self.solved.log)
    }

    /// The fraction of the initial unshot power shot when the solver stopped.
    pub fn convergence(&self) -> f64 {
        self.solved.log.last().map_or(1.0, |p| p.convergence)
    }

    /// Radiosity (W/m² as luminance-weighted rgb) and received illuminance (lux) per
    /// element, as shown.
    pub fn shown(&self) -> (&[DVec3], &[f64]) {
        (&self.solved.shown, &self.solved.shown_lux)
    }

    /// The light-map atlas of the solution as shown.
    pub fn light_map(&self) -> LightMap {
        solve::light_map(
            &self.prepared.rscene,
            &self.solved.shown,
            &self.solved.shown_lux,
        )
    }

    /// The patches the gather takes light from (the shooters' finest cells).
    pub fn gather_patches(&self) -> usize {
        self.solved.patches.len()
    }

    /// The interreflected illuminance (lux: the light the solution's surfaces send, not
    /// the luminaires' direct light) at `points`, gathered from the shooters' finest
    /// cells; `progress` sees the count done; `cancel` stops it with an error.
    pub fn interreflected_lux(
        &self,
        points: &[SurfacePoint],
        cancel: &AtomicBool,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<f64>, SessionError> {
        gather::at_points(
            &self.prepared.rscene,
            &self.solved.patches,
            points,
            self.prepared.options.form_factor,
            cancel,
            progress,
        )
        .ok_or(SessionError::Cancelled(Stage::Gathering))
        .and_then(|g| {
            let mut lux: Vec<f64> = g.into_iter().map(luminance).collect();
            usable_lux(&mut lux)?;
            Ok(lux)
        })
    }

    /// The luminaires' direct illuminance at `points` with their shadows, what mirrors
    /// and clear glass pass on, and the scene's direct daylight, lux.
    pub fn direct_lux(&self, points: &[SurfacePoint]) -> Result<Vec<f64>, SessionError> {
        let p = &self.prepared;
        let light = self.solved.relit.as_ref().unwrap_or(&p.light);
        let mut lux = light.lux(&p.gpu, points, &p.shadows)?;
        p.rscene
            .specular_light()
            .add_lux_at_points(points, &mut lux, p.interp);
        let cells = crate::daylight::points::HEMISPHERE_CELLS;
        if let Some(daylight) = p.rscene.daylight_at(points, cells) {
            for (v, d) in lux.iter_mut().zip(daylight) {
                *v += d.total();
            }
        }
        usable_lux(&mut lux)?;
        Ok(lux)
    }

    /// The total illuminance at `points` (direct and interreflected), lux.
    pub fn lux(
        &self,
        points: &[SurfacePoint],
        cancel: &AtomicBool,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Vec<f64>, SessionError> {
        let direct = self.direct_lux(points)?;
        let indirect = self.interreflected_lux(points, cancel, progress)?;
        let mut lux: Vec<f64> = direct.iter().zip(&indirect).map(|(d, i)| d + i).collect();
        usable_lux(&mut lux)?;
        Ok(lux)
    }

    /// The solved scene as glTF 2.0 binary: each surface light-mapped or vertex-lit as
    /// `choice` (and the scene file's `bake` keys, and `budget` triangles for vertex
    /// lighting) decide. Also the plan and the light map it baked.
    pub fn export_glb(
        &self,
        scene: &Scene,
        choice: BakeChoice,
        budget: Option<u64>,
    ) -> Result<(Vec<u8>, BakePlan, LightMap), super::export::ExportError> {
        let names: Vec<String> = scene.materials.iter().map(|m| m.name.clone()).collect();
        let material_bake: Vec<_> = scene.materials.iter().map(|m| m.bake).collect();
        let rscene = &self.prepared.rscene;
        let plan = bake::plan(rscene, &material_bake, choice, budget);
        let map = self.light_map();
        let bytes = super::export::glb(rscene, &map, &plan, &names, &scene.luminaires)?;
        Ok((bytes, plan, map))
    }
}

/// Prepares `setup`'s scene, solves it to the options' stop and returns the solution
/// ([`Prepared::new`], [`Prepared::session`], [`Session::solve`], [`Session::finish`]).
/// Cancelling stops the preparation with an error and the shooting with the solution so
/// far ([`Solution::stop`] is then [`StopReason::Cancelled`]).
pub fn solve(
    gpu: &Gpu,
    setup: Setup,
    cancel: &AtomicBool,
    events: &mut dyn FnMut(Event),
) -> Result<Solution, SessionError> {
    let prepared = Prepared::new(gpu, setup, cancel, events)?;
    let solved = {
        let mut session = prepared.session(events)?;
        events(Event::Shooting(&session));
        session.solve(cancel, events)?;
        events(Event::Solved(&session));
        session.finish()?
    };
    Ok(prepared.into_solution(solved))
}
