//! `goniolight bench radiosity-view`: Bozalina's "time to significant lighting events"
//! (§6.2, judged by eye) as a number — the time until the image in view is within a
//! tolerance (mean absolute luminance, weighted by the pixels each element covers) of the
//! converged image — for global progressive refinement, importance-driven and
//! perspective-driven radiosity, measured side by side in one run.

use std::sync::atomic::AtomicBool;
use std::time::Instant;

use glam::DVec3;

use super::BenchError;
use crate::gpu::Gpu;
use crate::radiosity::gpu::{GpuSettings, GpuSolver};
use crate::radiosity::initial::{InitialState, LuminaireLight};
use crate::radiosity::scene::{luminance, RadiosityScene};
use crate::radiosity::shooters::Hierarchy;
use crate::radiosity::solve::{self, StopAt};
use crate::radiosity::view::{self, Drive, ViewDriven, ViewPoint};
use crate::radiosity::SolverSettings;
use crate::scene::Scene;

/// One drive's run.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ViewBenchRow {
    /// "global", "importance" or "perspective".
    pub drive: String,
    /// Seconds the view's weights took ([`view::view_weights`]: a ray to the eye per
    /// element; counted in the times below for the driven drives, 0 for global) …
    pub view_weights_seconds: f64,
    /// … seconds of the importance solve and of setting the drive up (counted too) …
    pub importance_seconds: f64,
    /// … of which its solver's setup.
    pub importance_setup_seconds: f64,
    /// Seconds until the displayed image (with the drive's ambient term) is within the
    /// tolerance; `None`: not within the time limit.
    pub seconds_shown: Option<f64>,
    /// Seconds until the shot light alone (no ambient term) is within the tolerance.
    pub seconds_shot: Option<f64>,
    /// Shots until the shot light alone is within the tolerance.
    pub shots_shot: Option<usize>,
    /// Where the shots' time went until then, by phase.
    pub phase_seconds: crate::radiosity::gpu::ShotTimes,
    /// Receivers a drawn map's receive pass covered on average until then (the batch's
    /// culled receivers, holding ones included).
    pub receivers_per_map: f64,
    /// The GPU's own clock in the maps' and receive passes until then (`None`: the
    /// adapter has no timestamp queries).
    pub gpu_pass_seconds: Option<crate::radiosity::gpu::GpuPassSeconds>,
    /// The displayed image's error when the run ended.
    pub final_error: f64,
    /// Visibility maps drawn in the run.
    pub maps: usize,
    /// Maps copied back from the kept maps for a catch-up (perspective-driven), not drawn.
    pub maps_reused: usize,
    /// Shots in the run.
    pub shots: usize,
}

/// What the run measured.
#[derive(Debug, Clone, serde::Serialize)]
pub struct ViewBench {
    /// Elements.
    pub elements: usize,
    /// Elements the camera sees.
    pub elements_seen: usize,
    /// Seconds of the reference (global) solve.
    pub reference_seconds: f64,
    /// Its convergence.
    pub reference_convergence: f64,
    /// The tolerance, a share of the image's mean luminance.
    pub tolerance: f64,
    /// One row per drive (the first round).
    pub rows: Vec<ViewBenchRow>,
    /// Every round's rows (`--repeat`; the first is `rows`): the drives run in turn,
    /// round after round, against the one reference.
    pub rounds: Vec<Vec<ViewBenchRow>>,
    /// Per drive, its seconds to the tolerance (shot light) and its speed-up over global
    /// across the rounds.
    pub summary: Vec<DriveSummary>,
}

/// The least, median and greatest of some values.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Spread {
    /// The least …
    pub min: f64,
    /// … the median ([`super::median`]) …
    pub median: f64,
    /// … and the greatest.
    pub max: f64,
}

impl Spread {
    /// The spread of `values`; `None` when there are none (or one is not a number).
    pub fn of(values: &[f64]) -> Option<Spread> {
        if values.is_empty() || values.iter().any(|v| v.is_nan()) {
            return None;
        }
        Some(Spread {
            min: values.iter().copied().fold(f64::INFINITY, f64::min),
            median: super::median(values.to_vec()),
            max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        })
    }
}

/// One drive across the rounds.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct DriveSummary {
    /// The drive.
    pub drive: String,
    /// Rounds in which it reached the tolerance (shot light) …
    pub rounds_reached: usize,
    /// … its seconds to it in those …
    pub seconds_shot: Option<Spread>,
    /// … and, per round in which both reached it, global's seconds over its own.
    pub speedup: Option<Spread>,
    /// The same three for the image as shown (the shot light with the drive's ambient
    /// term): rounds in which it reached the tolerance …
    pub rounds_reached_shown: usize,
    /// … its seconds to it …
    pub seconds_shown: Option<Spread>,
    /// … and global's seconds (as shown) over its own.
    pub speedup_shown: Option<Spread>,
}

/// Drive `d`'s rounds that reached the tolerance by `seconds`, their seconds and
/// per round global's seconds (`rounds[k][0]`) over its own.
fn reached(
    rounds: &[Vec<ViewBenchRow>],
    d: usize,
    seconds: fn(&ViewBenchRow) -> Option<f64>,
) -> (usize, Option<Spread>, Option<Spread>) {
    let own: Vec<f64> = rounds.iter().filter_map(|r| seconds(&r[d])).collect();
    let speedup: Vec<f64> = rounds
        .iter()
        .filter_map(|r| match (seconds(&r[0]), seconds(&r[d])) {
            (Some(g), Some(s)) if s > 0.0 => Some(g / s),
            _ => None,
        })
        .collect();
    (own.len(), Spread::of(&own), Spread::of(&speedup))
}

/// Per drive of the first round, its [`DriveSummary`] over `rounds`.
pub fn summarise(rounds: &[Vec<ViewBenchRow>]) -> Vec<DriveSummary> {
    let Some(first) = rounds.first() else {
        return Vec::new();
    };
    (0..first.len())
        .map(|d| {
            let (rounds_reached, seconds_shot, speedup) = reached(rounds, d, |r| r.seconds_shot);
            let (rounds_reached_shown, seconds_shown, speedup_shown) =
                reached(rounds, d, |r| r.seconds_shown);
            DriveSummary {
                drive: first[d].drive.clone(),
                rounds_reached,
                seconds_shot,
                speedup,
                rounds_reached_shown,
                seconds_shown,
                speedup_shown,
            }
        })
        .collect()
}

/// The benchmark's settings (`bench radiosity-view`'s options).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct ViewBenchPlan {
    /// Texels per metre.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 10.0))]
    pub texel_density: f64,
    /// Patch level.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 2))]
    pub level: u32,
    /// Shooters.
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value = "clusters"))]
    pub hierarchy: Hierarchy,
    /// Within this share of the image's mean luminance (0.05: 5 %).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 0.05))]
    pub tolerance: f64,
    /// The converged image: a global solve to this convergence.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 0.999))]
    pub reference: f64,
    /// Give up on a drive after this many seconds.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 600.0))]
    pub time_limit: f64,
    /// Perspective-driven: the first area of interest's margin, degrees.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 10.0))]
    pub fov_margin: f64,
    /// Perspective-driven: MiB of visibility maps kept for the receivers that wait, so
    /// their catch-up copies rather than draws them (0: drawn again).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = crate::radiosity::gpu::DEFAULT_MAP_STORE_BYTES >> 20))]
    pub map_store_mib: u64,
    /// How the visibility maps are drawn (`auto`, `hardware`, `compute`; see
    /// `radiosity --raster`).
    #[cfg_attr(feature = "cli", arg(long, value_enum, default_value = "auto"))]
    pub raster: crate::radiosity::gpu::Raster,
    /// Rounds: the three drives run in turn this many times (one reference), and the
    /// summary gives each drive's least, median and greatest time and speed-up.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub repeat: usize,
}

/// The view's error of `radiosity` against `reference`: Σ W |ΔL| / Σ W L over the
/// elements, W the pixels each covers (view weight × area), L luminance.
pub fn view_error(
    scene: &RadiosityScene,
    weights: &[f64],
    radiosity: &[DVec3],
    reference: &[DVec3],
) -> f64 {
    let el = &scene.elements;
    let (mut diff, mut total) = (0.0, 0.0);
    for e in 0..el.len() {
        let w = weights[e] * el.area[e];
        let r = luminance(reference[e]);
        diff += w * (luminance(radiosity[e]) - r).abs();
        total += w * r;
    }
    diff / total.max(1e-300)
}

/// `scene` repeated `n` times in a row along +x, 0.5 m apart (meshes, materials shared,
/// luminaires and their housings): a building of closed rooms where the camera, in the
/// first, sees a small part.
pub fn row_of_rooms(scene: &Scene, n: usize) -> Scene {
    let (lo, hi) = scene
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.x), hi.max(p.x))
        });
    let step = f64::from(hi - lo).max(0.0) + 0.5;
    let mut out = scene.clone();
    let meshes = scene.meshes.len();
    for k in 1..n {
        let dx = step * k as f64;
        out.meshes.extend(scene.meshes.iter().map(|m| {
            let mut m = m.clone();
            for p in &mut m.positions {
                p.x += dx as f32;
            }
            m
        }));
        out.luminaires.extend(scene.luminaires.iter().map(|l| {
            let mut l = l.clone();
            l.position.x += dx;
            if let Some(h) = &mut l.housing {
                for m in &mut h.meshes {
                    *m += meshes * k;
                }
            }
            l
        }));
    }
    out
}

/// Runs the benchmark on `scene` seen from `point`.
pub fn run(
    gpu: &Gpu,
    scene: &Scene,
    point: &ViewPoint,
    plan: ViewBenchPlan,
    mut progress: impl FnMut(&str),
) -> Result<ViewBench, BenchError> {
    let settings = SolverSettings::default();
    let mut shadows = crate::render::ShadowSettings::default();
    crate::render::limits::check_scene(gpu, scene, &mut shadows)?;
    let rscene =
        RadiosityScene::with_hierarchy(scene, plan.texel_density, plan.level, plan.hierarchy)?;
    crate::render::limits::check_radiosity(gpu, rscene.elements.len())?;
    let light = LuminaireLight::new(gpu, scene, settings.interp);
    let initial = InitialState::from_luminaires_gpu(gpu, &light, &rscene, &shadows)?;
    let gpu_settings = GpuSettings {
        hierarchy: plan.hierarchy,
        raster: plan.raster,
        ..GpuSettings::default()
    };
    if let Some(why) = plan.raster.refusal(rscene.has_masked_casters()) {
        return Err(BenchError::Refused(why.into()));
    }
    // Driving by the view starts from its weights: timed, and charged to the driven drives.
    let started = Instant::now();
    let weights = view::view_weights(&rscene, point);
    let view_weights_seconds = started.elapsed().as_secs_f64();
    let elements_seen = weights.iter().filter(|&&w| w > 0.0).count();
    if elements_seen == 0 {
        return Err(BenchError::Refused(
            "the camera sees no surface of the scene".into(),
        ));
    }

    progress("reference");
    let started = Instant::now();
    let mut reference = GpuSolver::new(gpu, &rscene, &initial, settings, gpu_settings);
    let stop = StopAt {
        converge: plan.reference,
        ..StopAt::default()
    };
    let (_, log) = reference.solve(&stop, &AtomicBool::new(false), |_| {})?;
    let reference_seconds = started.elapsed().as_secs_f64();
    let reference = reference.radiosity()?;

    let what = Drives {
        gpu,
        scene: &rscene,
        initial: &initial,
        settings,
        gpu_settings,
        plan,
        point,
        weights: &weights,
        view_weights_seconds,
        reference: &reference,
    };
    let mut rounds = Vec::new();
    for round in 0..plan.repeat.max(1) {
        let mut rows = Vec::new();
        for drive in [Drive::Global, Drive::Importance, Drive::Perspective] {
            if plan.repeat > 1 {
                progress(&format!(
                    "{} (round {} of {})",
                    drive.name(),
                    round + 1,
                    plan.repeat
                ));
            } else {
                progress(drive.name());
            }
            rows.push(what.run(drive)?);
        }
        rounds.push(rows);
    }
    Ok(ViewBench {
        elements: rscene.elements.len(),
        elements_seen,
        reference_seconds,
        reference_convergence: log.last().map_or(1.0, |p| p.convergence),
        tolerance: plan.tolerance,
        rows: rounds[0].clone(),
        summary: summarise(&rounds),
        rounds,
    })
}

/// What every drive's run shares: the scene, its direct light, the view and the
/// reference.
#[derive(Clone, Copy)]
struct Drives<'a> {
    gpu: &'a Gpu,
    scene: &'a RadiosityScene,
    initial: &'a InitialState,
    settings: SolverSettings,
    gpu_settings: GpuSettings,
    plan: ViewBenchPlan,
    point: &'a ViewPoint,
    weights: &'a [f64],
    view_weights_seconds: f64,
    reference: &'a [DVec3],
}

impl Drives<'_> {
    /// One run of `drive` from the direct light until the shot light and the displayed
    /// image are within the tolerance (or the time limit).
    fn run(&self, drive: Drive) -> Result<ViewBenchRow, BenchError> {
        let Drives {
            gpu,
            scene: rscene,
            initial,
            settings,
            gpu_settings,
            plan,
            point,
            weights,
            view_weights_seconds,
            reference,
        } = *self;
        let mut solver = GpuSolver::new(gpu, rscene, initial, settings, gpu_settings);
        solver.set_map_store_bytes(plan.map_store_mib << 20);
        solver.time_passes();
        // The clock runs only while the solver works (not while the bench reads back).
        let mut clock = 0.0;
        let (driven, weights_seconds) = match drive {
            Drive::Global => (None, 0.0),
            _ => {
                let d = ViewDriven::new(&solver, settings, gpu_settings, weights.to_vec(), None)?;
                let t = Instant::now();
                d.drive(&mut solver, drive, point, plan.fov_margin)?;
                clock += d.importance_seconds + t.elapsed().as_secs_f64();
                (Some(d), view_weights_seconds)
            }
        };
        let importance_seconds = clock;
        clock += weights_seconds;
        let mut row = ViewBenchRow {
            drive: drive.name().to_string(),
            view_weights_seconds: weights_seconds,
            importance_seconds,
            importance_setup_seconds: driven.as_ref().map_or(0.0, |d| d.importance_setup_seconds),
            seconds_shown: None,
            seconds_shot: None,
            shots_shot: None,
            phase_seconds: Default::default(),
            receivers_per_map: 0.0,
            gpu_pass_seconds: None,
            final_error: f64::NAN,
            maps: 0,
            maps_reused: 0,
            shots: 0,
        };
        loop {
            let (radiosity, illuminance) = solver.radiosity_and_illuminance()?;
            let unshot = solver.unshot_to_come()?;
            let ambient = match &driven {
                Some(d) => d.ambient(rscene, &unshot),
                None => solve::ambient_term(rscene, &unshot),
            };
            let shown = solve::with_ambient(rscene, &radiosity, &illuminance, ambient).0;
            let error_shown = view_error(rscene, weights, &shown, reference);
            let error_shot = view_error(rscene, weights, &radiosity, reference);
            if error_shown <= plan.tolerance && row.seconds_shown.is_none() {
                row.seconds_shown = Some(clock);
            }
            if error_shot <= plan.tolerance && row.seconds_shot.is_none() {
                row.seconds_shot = Some(clock);
                row.shots_shot = Some(solver.stats.shots);
                row.phase_seconds = solver.stats.times;
                row.receivers_per_map =
                    solver.stats.receiver_threads as f64 / solver.stats.drawn.max(1) as f64;
                row.gpu_pass_seconds = solver.gpu_pass_seconds()?;
            }
            row.final_error = error_shown;
            if row.seconds_shot.is_some() && row.seconds_shown.is_some() || clock > plan.time_limit
            {
                break;
            }
            let t = Instant::now();
            let one = StopAt {
                converge: 1.0,
                max_shots: Some(solver.stats.shots + 1),
                time_budget: None,
            };
            let (reason, _) = solver.solve(&one, &AtomicBool::new(false), |_| {})?;
            clock += t.elapsed().as_secs_f64();
            if reason == solve::StopReason::NothingLeft {
                break;
            }
        }
        row.maps = solver.stats.drawn;
        row.maps_reused = solver.maps_reused();
        row.shots = solver.stats.shots;
        Ok(row)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(drive: &str, seconds_shot: Option<f64>) -> ViewBenchRow {
        ViewBenchRow {
            drive: drive.into(),
            view_weights_seconds: 0.0,
            importance_seconds: 0.0,
            importance_setup_seconds: 0.0,
            // The image as shown gets there at half the shot light's time.
            seconds_shown: seconds_shot.map(|s| s / 2.0),
            seconds_shot,
            shots_shot: None,
            phase_seconds: Default::default(),
            receivers_per_map: 0.0,
            gpu_pass_seconds: None,
            final_error: 0.0,
            maps: 0,
            maps_reused: 0,
            shots: 0,
        }
    }

    #[test]
    fn spread_is_the_least_median_and_greatest() {
        let s = Spread::of(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!((s.min, s.median, s.max), (1.0, 2.0, 3.0));
        // An even count: the mean of the middle two.
        let s = Spread::of(&[4.0, 1.0, 3.0, 2.0]).unwrap();
        assert_eq!((s.min, s.median, s.max), (1.0, 2.5, 4.0));
        assert_eq!(Spread::of(&[]), None);
        assert_eq!(Spread::of(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn the_summary_takes_each_rounds_speedup_against_that_rounds_global() {
        let rounds = vec![
            vec![row("global", Some(20.0)), row("perspective", Some(4.0))],
            vec![row("global", Some(30.0)), row("perspective", Some(5.0))],
            vec![row("global", Some(18.0)), row("perspective", None)],
        ];
        let s = summarise(&rounds);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].drive, "global");
        assert_eq!(s[0].rounds_reached, 3);
        let g = s[0].speedup.unwrap();
        assert_eq!((g.min, g.median, g.max), (1.0, 1.0, 1.0));
        assert_eq!(s[0].seconds_shot.unwrap().median, 20.0);
        // 20 / 4 and 30 / 5 (the third round's perspective did not reach it): not the
        // ratio of the medians (20 / 4.5).
        assert_eq!(s[1].rounds_reached, 2);
        let p = s[1].speedup.unwrap();
        assert_eq!((p.min, p.median, p.max), (5.0, 5.5, 6.0));
        assert_eq!(s[1].seconds_shot.unwrap().median, 4.5);
        // As shown: its own seconds and speed-ups, round by round the same way.
        assert_eq!(s[1].rounds_reached_shown, 2);
        assert_eq!(s[1].seconds_shown.unwrap().median, 2.25);
        let p = s[1].speedup_shown.unwrap();
        assert_eq!((p.min, p.median, p.max), (5.0, 5.5, 6.0));
        assert_eq!(s[0].seconds_shown.unwrap().max, 15.0);
        assert!(summarise(&[]).is_empty());
    }
}
