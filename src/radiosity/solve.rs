//! Running a solution to a stop condition (convergence target, shot count, time budget or
//! a cancel request), with a convergence log, and turning the result into what is shown:
//! the ambient term and the light-map atlas.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use glam::{DVec3, Vec2};

use super::gpu::{GpuSolver, Selection};
use super::scene::{luminance, RadiosityScene};
use super::Ambient;
use crate::gpu::GpuError;
use crate::render::lightmap::LightMap;

/// When to stop shooting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StopAt {
    /// Fraction of the initial unshot power that has been shot (0..1).
    pub converge: f64,
    /// At most this many shots.
    pub max_shots: Option<usize>,
    /// At most this long.
    pub time_budget: Option<Duration>,
}

impl Default for StopAt {
    fn default() -> StopAt {
        StopAt {
            converge: 0.99,
            max_shots: None,
            time_budget: None,
        }
    }
}

/// Why a solution stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The convergence target was reached.
    Converged,
    /// Nothing was left to shoot (all unshot power is zero).
    NothingLeft,
    /// The shot count was reached.
    ShotLimit,
    /// The time budget was spent.
    TimeBudget,
    /// Cancelled by the caller.
    Cancelled,
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            StopReason::Converged => "converged",
            StopReason::NothingLeft => "nothing left to shoot",
            StopReason::ShotLimit => "shot limit reached",
            StopReason::TimeBudget => "time budget spent",
            StopReason::Cancelled => "interrupted",
        })
    }
}

/// One line of the convergence log: the state before shot `shot`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvergencePoint {
    /// Shots done so far.
    pub shot: usize,
    /// Seconds since shooting started.
    pub seconds: f64,
    /// The triangle shot next (`None`: nothing left).
    pub shooter: Option<usize>,
    /// Σ |unshot luminance| × area, lm.
    pub unshot_power: f64,
    /// 1 − unshot / initial unshot power (each shooter's power times its weight where
    /// the view drives the solution: [`GpuSolver::set_shooter_weights`]).
    pub convergence: f64,
}

/// The convergence log as CSV (`shot,seconds,shooter,unshot_lm,convergence`).
pub fn convergence_csv(log: &[ConvergencePoint]) -> String {
    let mut out = String::from("shot,seconds,shooter,unshot_lm,convergence\n");
    for p in log {
        let shooter = p.shooter.map(|t| t.to_string()).unwrap_or_default();
        out.push_str(&format!(
            "{},{:.6},{shooter},{:.6},{:.8}\n",
            p.shot, p.seconds, p.unshot_power, p.convergence
        ));
    }
    out
}

impl GpuSolver<'_> {
    /// The next selection, the area of interest widened first where its stage's work is
    /// done (perspective-driven radiosity; select again after widening: what joined has
    /// light to shoot).
    pub fn select_next(&mut self) -> Result<Selection, GpuError> {
        let mut s = self.select()?;
        while self.widen_if_due(&s)? {
            s = self.select()?;
        }
        Ok(s)
    }

    /// The unshot power convergence is measured on: weighed by importance where the view
    /// drives the solution ([`Selection::weighted_power`]), else all of it.
    pub fn measured(&self, s: &Selection) -> f64 {
        if self.is_weighted() {
            s.weighted_power
        } else {
            s.unshot_power
        }
    }

    /// Shoots until `stop` says so or `cancel` is set. `progress` sees every log point
    /// as it is made. Returns why it stopped and the log (its first point is the start).
    pub fn solve(
        &mut self,
        stop: &StopAt,
        cancel: &AtomicBool,
        progress: impl FnMut(&ConvergencePoint),
    ) -> Result<(StopReason, Vec<ConvergencePoint>), GpuError> {
        self.solve_to_scale(stop, None, cancel, progress)
    }

    /// [`GpuSolver::solve`] with convergence measured against `scale` (the unshot power,
    /// weighted where the view drives the solution, it is the fraction of), instead of
    /// the first selection's: a relit solution ([`GpuSolver::relight`]) stops where a
    /// fresh solve of its new luminaires would, with `scale` from
    /// [`GpuSolver::start_power`] of their start.
    pub fn solve_to_scale(
        &mut self,
        stop: &StopAt,
        scale: Option<f64>,
        cancel: &AtomicBool,
        mut progress: impl FnMut(&ConvergencePoint),
    ) -> Result<(StopReason, Vec<ConvergencePoint>), GpuError> {
        let mut run = ShotRun::new(scale);
        let mut log = Vec::new();
        loop {
            let (point, reason) = self.advance(stop, &mut run, None, cancel)?;
            progress(&point);
            log.push(point);
            if let Some(r) = reason {
                return Ok((r, log));
            }
        }
    }

    /// One step of a solution: selects the next shooter, measures the convergence, and
    /// unless `stop` says the solution is done shoots it — stopped between batches of
    /// patches when `cancel` is set, the run's time budget is spent or `slice` (this
    /// step's own share of time) is used up; a shooter stopped early keeps the rest of
    /// its unshot power for a later step. Returns the log point (the state before the
    /// shot) and why the solution stops there, if it does. The one shooting loop: every
    /// solve, the viewer's and [`super::session::Session`]'s, is these steps.
    pub fn advance(
        &mut self,
        stop: &StopAt,
        run: &mut ShotRun,
        slice: Option<Duration>,
        cancel: &AtomicBool,
    ) -> Result<(ConvergencePoint, Option<StopReason>), GpuError> {
        let started = Instant::now();
        let s = self.select_next()?;
        let unshot = self.measured(&s);
        let initial = *run.scale.get_or_insert(unshot);
        let point = ConvergencePoint {
            shot: self.stats.shots,
            seconds: run.seconds + started.elapsed().as_secs_f64(),
            shooter: s.shooter,
            unshot_power: s.unshot_power,
            convergence: if initial > 0.0 {
                1.0 - unshot / initial
            } else {
                1.0
            },
        };
        // Converged only when no receiver waits for shots it missed; nothing asked to
        // converge shoots nothing.
        let reason = if stop.converge <= 0.0
            || (point.convergence >= stop.converge && self.area_is_whole())
        {
            Some(StopReason::Converged)
        } else if s.shooter.is_none() {
            Some(StopReason::NothingLeft)
        } else if stop.max_shots.is_some_and(|m| self.stats.shots >= m) {
            Some(StopReason::ShotLimit)
        } else if stop
            .time_budget
            .is_some_and(|b| point.seconds >= b.as_secs_f64())
        {
            Some(StopReason::TimeBudget)
        } else if cancel.load(Ordering::Relaxed) {
            Some(StopReason::Cancelled)
        } else {
            None
        };
        if let (None, Some(t)) = (reason, s.shooter) {
            let before = run.seconds;
            let over = || {
                let elapsed = started.elapsed();
                cancel.load(Ordering::Relaxed)
                    || slice.is_some_and(|d| elapsed >= d)
                    || stop
                        .time_budget
                        .is_some_and(|b| before + elapsed.as_secs_f64() >= b.as_secs_f64())
            };
            self.shoot_until(t, &over)?;
        }
        run.seconds += started.elapsed().as_secs_f64();
        Ok((point, reason))
    }
}

/// Where a run of [`GpuSolver::advance`]s stands: the unshot power its convergence is a
/// fraction of, and the seconds it has shot.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ShotRun {
    /// The unshot power at the start (`None`: the first step's).
    pub scale: Option<f64>,
    /// Seconds of steps so far (pauses between them left out).
    pub seconds: f64,
}

impl ShotRun {
    /// A run measured against `scale` (`None`: against its first step's unshot power).
    pub fn new(scale: Option<f64>) -> ShotRun {
        ShotRun {
            scale,
            seconds: 0.0,
        }
    }
}

/// The ambient term (Cohen et al. 1988; Wallner Eq. 2.4–2.6): the unshot radiosity
/// averaged over the area, times the interreflection factor 1 / (1 − ρ̄).
pub fn ambient_term(scene: &RadiosityScene, unshot: &[DVec3]) -> DVec3 {
    let el = &scene.elements;
    let total: DVec3 = (0..el.len()).map(|e| unshot[e] * el.area[e]).sum();
    total / scene.total_area.max(1e-300) / (1.0 - scene.mean_reflectance)
}

/// A solution as displayed: radiosity and received illuminance per element, with the
/// ambient term added when `ambient` asks for it (reflectance × ambient to the
/// radiosity, the ambient's luminance to the illuminance).
pub fn displayed(
    scene: &RadiosityScene,
    radiosity: &[DVec3],
    illuminance: &[f64],
    unshot: &[DVec3],
    ambient: Ambient,
) -> (Vec<DVec3>, Vec<f64>) {
    if ambient == Ambient::None {
        return (radiosity.to_vec(), illuminance.to_vec());
    }
    with_ambient(scene, radiosity, illuminance, ambient_term(scene, unshot))
}

/// A solution with the ambient term `a` added ((reflectance + transmittance) × `a` to the
/// radiosity: it arrives on both sides of a translucent surface; its
/// luminance to the illuminance): [`displayed`] with a term of the caller's (the view's,
/// [`super::view::view_ambient`]).
pub fn with_ambient(
    scene: &RadiosityScene,
    radiosity: &[DVec3],
    illuminance: &[f64],
    a: DVec3,
) -> (Vec<DVec3>, Vec<f64>) {
    let lux = luminance(a);
    (0..radiosity.len())
        .map(|e| {
            (
                radiosity[e] + scene.element_reemittance(e) * a,
                illuminance[e] + lux,
            )
        })
        .unzip()
}

/// The light-map atlas of a solution: each texel shows its element (gutters their
/// neighbour's; an unsplit block of adaptive subdivision blends with its neighbours:
/// [`super::elements::Elements::display_texels`]), rgb radiosity and a illuminance.
pub fn light_map(scene: &RadiosityScene, radiosity: &[DVec3], illuminance: &[f64]) -> LightMap {
    let el = &scene.elements;
    let texels = el.display_texels(|e| {
        let b = radiosity[e].as_vec3();
        [b.x, b.y, b.z, illuminance[e] as f32]
    });
    let size = glam::DVec2::new(el.atlas_width as f64, el.atlas_height as f64);
    LightMap {
        width: el.atlas_width,
        height: el.atlas_height,
        texels,
        triangle_uv: el
            .triangles
            .iter()
            .map(|t| t.atlas_uv.map(|uv| (uv / size).as_vec2()))
            .collect::<Vec<[Vec2; 3]>>(),
    }
}
