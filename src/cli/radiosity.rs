//! `goniolight radiosity`: solve a scene's interreflected light on the GPU, write the
//! rendering of the solution, the light-map atlas and the convergence log, and with
//! `--points` print the total illuminance at points read from stdin.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::anyhow;
use clap::Args;
use glam::DVec3;

use super::render::{render_to_files, ImageOptions};
use super::CliError;
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::lighting::read_points;
use crate::lighting::SurfacePoint;
use crate::radiosity::bake::{self, BakeChoice, BakePlan};
use crate::radiosity::elements::{Elements, Subdivision};
use crate::radiosity::gather;
use crate::radiosity::gpu::{GpuSettings, GpuSolver, Raster, Visibility};
use crate::radiosity::initial::{InitialState, LuminaireLight};
use crate::radiosity::links::DEFAULT_LINK_ERROR;
use crate::radiosity::scene::{luminance, RadiosityScene};
use crate::radiosity::shooters::{Hierarchy, Shooters, DEFAULT_CELL_POWER};
use crate::radiosity::solve::{self, ConvergencePoint, StopAt, StopReason};
use crate::radiosity::view::{self, Drive, ViewDriven, ViewPoint};
use crate::radiosity::{Ambient, FormFactorKind, SolverSettings};
use crate::render::lightmap::LightMap;
use crate::render::output::write_image;
use crate::render::Renderer;
use crate::scene::Scene;

/// The solver's options, shared by `radiosity` and `calc --indirect radiosity`.
#[derive(Debug, Clone, Args)]
pub struct SolverArgs {
    /// Stop when this fraction of the initial unshot power has been shot (0..1).
    #[arg(long, default_value_t = 0.99)]
    pub converge: f64,
    /// Stop after this many shots.
    #[arg(long)]
    pub max_shots: Option<usize>,
    /// Stop after this many seconds of shooting.
    #[arg(long, value_parser = super::seconds_arg)]
    pub time_limit: Option<f64>,
    /// Elements (light-map texels) per metre.
    #[arg(long, default_value_t = 10.0)]
    pub texel_density: f64,
    /// Shooting patches are 2^LEVEL × 2^LEVEL texels (substructuring; 0: every texel).
    #[arg(long, default_value_t = 2)]
    pub level: u32,
    /// Adaptive subdivision (Wallner §2.4): split elements of 1 / --texel-density up to
    /// LEVELS times (each halving their side) where a luminaire's shadow or beam edge
    /// crosses them; the light map's texels are the finest elements. 0: uniform elements.
    #[arg(long, value_name = "LEVELS", default_value_t = 0)]
    pub adaptive: u32,
    /// With --adaptive: split a block only where the share of its points a luminaire
    /// lights lies in LOWER,UPPER (Wallner's b_l, b_u; none and all never split).
    #[arg(
        long,
        value_name = "LOWER,UPPER",
        value_delimiter = ',',
        default_values_t = [0.0, 1.0]
    )]
    pub adaptive_share: Vec<f64>,
    /// Visibility maps of the shooting patches.
    #[arg(long, value_enum, default_value = "hemicube")]
    pub visibility: Visibility,
    /// Side of a hemicube face or of the stereographic map, texels.
    #[arg(long, default_value_t = 256)]
    pub map_size: u32,
    /// How the visibility maps are drawn: by the GPU's render pipeline (`hardware`), or
    /// by compute shaders on all of its units (`compute`: a data-centre GPU has only a
    /// few units that do graphics); `auto` takes compute on a GPU and the render
    /// pipeline on a software driver (lavapipe) or with alpha-masked casters.
    #[arg(long, value_enum, default_value = "auto")]
    pub raster: Raster,
    /// Who shoots: every triangle from its own patches (`none`, the flat solver), or the
    /// flat face clusters of Edström's hierarchy as a whole (`clusters`): a surface drawn
    /// as thousands of triangles is one shooter.
    #[arg(long, value_enum, default_value = "clusters")]
    pub hierarchy: Hierarchy,
    /// With `--hierarchy clusters`: the largest share of the initial unshot power one
    /// shooting cell may carry; smaller is finer and slower (the oracle that sizes a
    /// cluster's shooting cells from its power).
    #[arg(long, default_value_t = DEFAULT_CELL_POWER)]
    pub cell_power: f64,
    /// With `--hierarchy clusters`: the irradiance error a receiver accepts from taking a
    /// coarse cell's light as one source, as a share of the mean initial exitance (the
    /// links' oracle: far receivers take a cluster's light from a few coarse cells, near
    /// ones from the fine cells); 0 links every receiver to the finest cells.
    #[arg(long, default_value_t = DEFAULT_LINK_ERROR)]
    pub link_error: f64,
    /// Form factor from a patch to an element.
    #[arg(long, value_enum, default_value = "polygon")]
    pub form_factor: FormFactorKind,
    /// Ambient term: for display only, also for overshooting, or none.
    #[arg(long, value_enum, default_value = "display")]
    pub ambient: Ambient,
    /// What chooses the work, from the scene's camera (Bozalina 2011): `global` shoots
    /// the most unshot power to every element; `importance` weighs each shooter by the
    /// importance the camera sends through the scene (what the view will see of its
    /// light); `perspective` also limits the receivers to the view's frustum plus
    /// --fov-margin, widened as the view's light settles (what waited is caught up).
    /// With importance and perspective, convergence and the displayed ambient term are
    /// the view's.
    #[arg(long, value_enum, default_value = "global")]
    pub drive: Drive,
    /// With --drive perspective: degrees added to the camera's half field of view for
    /// the first area of interest (each later stage adds 30°).
    #[arg(long, value_name = "DEG", default_value_t = 10.0)]
    pub fov_margin: f64,
}

impl SolverArgs {
    /// An error naming the flag whose value is out of range.
    pub fn check(&self) -> Result<(), CliError> {
        let bad = |what: String| Err(CliError::input(anyhow!(what)));
        if !(self.converge.is_finite() && (0.0..=1.0).contains(&self.converge)) {
            return bad(format!("--converge {} is not in 0..=1", self.converge));
        }
        if !(self.texel_density.is_finite() && self.texel_density > 0.0) {
            return bad(format!(
                "--texel-density {} must be a positive number of texels per metre",
                self.texel_density
            ));
        }
        if self.level > 6 {
            return bad(format!("--level {} is not in 0..=6", self.level));
        }
        if self.adaptive > 4 {
            return bad(format!("--adaptive {} is not in 0..=4", self.adaptive));
        }
        let share_ok = match self.adaptive_share[..] {
            [lower, upper] => (0.0..=1.0).contains(&lower) && (lower..=1.0).contains(&upper),
            _ => false,
        };
        if !share_ok {
            let given: Vec<String> = self.adaptive_share.iter().map(f64::to_string).collect();
            return bad(format!(
                "--adaptive-share {}: give LOWER,UPPER with 0 ≤ LOWER ≤ UPPER ≤ 1",
                given.join(",")
            ));
        }
        if !(self.cell_power.is_finite() && self.cell_power > 0.0 && self.cell_power <= 1.0) {
            return bad(format!("--cell-power {} is not in (0, 1]", self.cell_power));
        }
        if !(self.link_error.is_finite() && (0.0..=1.0).contains(&self.link_error)) {
            return bad(format!("--link-error {} is not in [0, 1]", self.link_error));
        }
        if !(16..=4096).contains(&self.map_size) {
            return bad(format!("--map-size {} is not in 16..=4096", self.map_size));
        }
        if !(self.fov_margin.is_finite() && (0.0..=180.0).contains(&self.fov_margin)) {
            return bad(format!(
                "--fov-margin {} is not in 0..=180 degrees",
                self.fov_margin
            ));
        }
        if let Some(t) = self.time_limit {
            if !(t.is_finite() && t > 0.0) {
                return bad(format!(
                    "--time-limit {t} must be a positive number of seconds"
                ));
            }
        }
        Ok(())
    }

    /// The adaptive subdivision asked for.
    pub fn subdivision(&self) -> Subdivision {
        let (lower, upper) = match self.adaptive_share[..] {
            [lower, upper] => (lower, upper),
            _ => (0.0, 1.0),
        };
        Subdivision {
            levels: self.adaptive,
            lower,
            upper,
        }
    }

    fn stop(&self) -> StopAt {
        StopAt {
            converge: self.converge,
            max_shots: self.max_shots,
            time_budget: self
                .time_limit
                .and_then(|t| crate::io::limits::duration(t).ok()),
        }
    }
}

/// Options of `radiosity`.
#[derive(Debug, Args)]
pub struct RadiosityArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// The solver's options.
    #[command(flatten)]
    pub solver: SolverArgs,
    /// Output folder: render.png, render.exr, lightmap.exr, lightmap_lux.exr,
    /// convergence.csv (default `radiosity-out`; with --points nothing is written unless
    /// it is given).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// Also write the solved scene as glTF 2.0 binary (.glb), unlit materials: each
    /// surface light-mapped (base colour texture "lightmap", TEXCOORD_0) or vertex-lit
    /// (COLOR_0, triangles split to the light map's texels), as --bake chooses; the exact
    /// radiosity and illuminance per corner (_RADIOSITY, _ILLUMINANCE) on both.
    #[arg(long, value_name = "SCENE.glb")]
    pub export: Option<PathBuf>,
    /// With --export: per surface, light map or vertex colours by the scene file's `bake`
    /// keys and else Edström's heuristic (auto); or every surface one way.
    #[arg(long, value_enum, default_value = "auto")]
    pub bake: BakeChoice,
    /// With --export and --bake auto: how many triangles vertex lighting may add to the
    /// model (default: 10 % of its triangles); surfaces that would add most are
    /// light-mapped until the rest fit.
    #[arg(long, value_name = "TRIANGLES")]
    pub bake_budget: Option<u64>,
    /// Read "x y z nx ny nz" lines from stdin and print the total illuminance (lux,
    /// direct + interreflected) at each, one per line.
    #[arg(long)]
    pub points: bool,
    /// Image options of the rendering (and the luminaires' interpolation and shadows).
    #[command(flatten)]
    pub image: ImageOptions,
}

impl RadiosityArgs {
    fn check(&self) -> Result<(), CliError> {
        let bad = |what: String| Err(CliError::input(anyhow!(what)));
        if self.export.is_none() && (self.bake != BakeChoice::Auto || self.bake_budget.is_some()) {
            return bad(
                "--bake and --bake-budget choose how --export bakes the scene: give --export SCENE.glb"
                    .into(),
            );
        }
        if self.bake != BakeChoice::Auto && self.bake_budget.is_some() {
            return bad("--bake-budget applies to --bake auto only".into());
        }
        self.solver.check()?;
        if let Some(path) = &self.export {
            if path.is_dir() {
                return bad(format!("--export {}: is a folder", path.display()));
            }
            // Missing folders are made; one that is a file would fail only after the solve.
            if let Some(file) = path.ancestors().skip(1).find(|a| a.is_file()) {
                return bad(format!(
                    "--export {}: {} is a file, not a folder",
                    path.display(),
                    file.display()
                ));
            }
        }
        if let Some(dir) = &self.out_dir {
            if dir.is_file() {
                return bad(format!("--out-dir {}: is a file", dir.display()));
            }
        }
        Ok(())
    }
}

fn progress_bar() -> Result<indicatif::ProgressBar, CliError> {
    let bar = indicatif::ProgressBar::new(10_000);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "radiosity [{bar:40}] {msg} ({elapsed_precise}, Ctrl-C stops and writes)",
        )
        .map_err(|e| CliError::failure(anyhow!(e)))?,
    );
    Ok(bar)
}

/// A spinner naming the preparation stage that runs (drawn on a terminal only), cleared
/// when dropped, so an error is printed on a clean line. Ctrl-C during a stage stops the
/// command when that stage ends, before anything is written.
struct StageSpinner {
    spinner: indicatif::ProgressBar,
    stage: std::cell::Cell<&'static str>,
    cancel: std::sync::Arc<std::sync::atomic::AtomicBool>,
}

impl StageSpinner {
    fn new(first: &'static str) -> Result<StageSpinner, CliError> {
        let spinner = indicatif::ProgressBar::new_spinner();
        spinner.set_style(
            indicatif::ProgressStyle::with_template("{spinner} radiosity: {msg} ({elapsed})")
                .map_err(|e| CliError::failure(anyhow!(e)))?,
        );
        spinner.enable_steady_tick(Duration::from_millis(100));
        spinner.set_message(first);
        let cancel = super::interrupt_flag();
        cancel.store(false, std::sync::atomic::Ordering::SeqCst);
        Ok(StageSpinner {
            spinner,
            stage: std::cell::Cell::new(first),
            cancel,
        })
    }

    /// Ends the current stage (an error if Ctrl-C came during it) and names the next.
    fn set(&self, stage: &'static str) -> Result<(), CliError> {
        self.check()?;
        self.stage.set(stage);
        self.spinner.set_message(stage);
        Ok(())
    }

    /// An error if Ctrl-C came during the current stage.
    fn check(&self) -> Result<(), CliError> {
        if self.cancel.load(std::sync::atomic::Ordering::SeqCst) {
            return Err(CliError::failure(anyhow!(
                "interrupted while preparing ({}): nothing written",
                self.stage.get()
            )));
        }
        Ok(())
    }
}

impl Drop for StageSpinner {
    fn drop(&mut self) {
        self.spinner.finish_and_clear();
    }
}

/// Everything the command writes, computed before anything is written.
struct Outputs {
    light_map: LightMap,
    csv: String,
}

/// A scene made ready to solve: its elements and the luminaires' direct light on them.
pub struct Prepared<'s> {
    /// The scene file (for messages).
    label: &'s Path,
    gpu: Gpu,
    rscene: RadiosityScene,
    light: LuminaireLight,
    initial: InitialState,
    solver: SolverArgs,
    interp: crate::photometry::Interp,
    /// The scene's camera, where the view drives the solution.
    view: Option<ViewPoint>,
    /// Seconds from the start of the command to here.
    pub prepared_s: f64,
}

/// A solution, with what it was solved from.
pub struct Solved<'p> {
    prepared: &'p Prepared<'p>,
    solver: GpuSolver<'p>,
    /// Why the solver stopped.
    pub stop: StopReason,
    log: Vec<ConvergencePoint>,
    /// The radiosity shown (with the ambient term where the solver's `ambient` says so),
    /// per element.
    shown: Vec<DVec3>,
    shown_lux: Vec<f64>,
}

/// Builds the elements of `scene` (loaded by now, the command having started at
/// `started`) and the luminaires' direct light on them, with a spinner naming each
/// stage; Ctrl-C stops it between stages.
pub fn prepare<'s>(
    label: &'s Path,
    scene: &Scene,
    solver: &SolverArgs,
    settings: &mut crate::render::RenderSettings,
    started: Instant,
) -> Result<Prepared<'s>, CliError> {
    let load_s = started.elapsed().as_secs_f64();
    let view = match solver.drive {
        Drive::Global => None,
        drive => {
            let aspect = settings.width as f64 / settings.height.max(1) as f64;
            Some(ViewPoint::new(&scene.camera, aspect).ok_or_else(|| {
                CliError::input(anyhow!(
                    "{}: --drive {} needs a perspective camera (the scene's is orthographic)",
                    label.display(),
                    drive.name()
                ))
            })?)
        }
    };
    let stage = StageSpinner::new(match solver.hierarchy {
        Hierarchy::None => "elements and atlas",
        Hierarchy::Clusters => "face clusters, charts, elements and atlas",
    })?;
    let rscene = RadiosityScene::with_subdivision(
        scene,
        solver.texel_density,
        solver.level,
        solver.hierarchy,
        solver.subdivision(),
    )
    .map_err(|e| CliError::input(anyhow!("{}: {e}", label.display())))?;
    if solver.adaptive > 0 {
        eprintln!(
            "{} (the splits decided in {:.2} s of CPU)",
            adaptive_summary(&rscene.elements),
            rscene.subdivision_seconds
        );
    }
    let elements_s = started.elapsed().as_secs_f64() - load_s;
    let interp = settings.light_model.interp();
    let gpu = Gpu::shared()?;
    crate::render::limits::check_scene(&gpu, scene, &mut settings.shadows)?;
    crate::render::limits::check_radiosity(&gpu, rscene.elements.len())?;
    stage.set("the luminaires' direct light")?;
    let light = LuminaireLight::new(&gpu, scene, interp);
    let initial = InitialState::from_luminaires_gpu(&gpu, &light, &rscene, &settings.shadows)?;
    stage.check()?;
    drop(stage);
    let prepared_s = started.elapsed().as_secs_f64();
    eprintln!(
        "{}: prepared in {prepared_s:.2} s — load {load_s:.2} s, {}elements and atlas {:.2} s, {}luminaires' direct light {:.2} s; {} triangles{}",
        label.display(),
        match solver.hierarchy {
            Hierarchy::None => String::new(),
            Hierarchy::Clusters => format!("face clusters {:.2} s, ", rscene.clustering_seconds),
        },
        elements_s - rscene.clustering_seconds - rscene.receiving_seconds,
        if rscene.receiving_normals.is_empty() {
            String::new()
        } else {
            format!("receiving normals {:.2} s, ", rscene.receiving_seconds)
        },
        prepared_s - load_s - elements_s,
        scene.triangle_count(),
        crate::io::peak_memory_mb().map_or(String::new(), |mb| format!(", peak memory {mb} MB")),
    );
    Ok(Prepared {
        label,
        gpu,
        rscene,
        light,
        initial,
        solver: solver.clone(),
        interp,
        view,
        prepared_s,
    })
}

impl Prepared<'_> {
    /// The view's weights and importance (an importance solve of at most a quarter of
    /// `time_budget`); an error when the camera sees no surface.
    fn drive(
        &self,
        light: &GpuSolver,
        point: &ViewPoint,
        settings: SolverSettings,
        gpu_settings: GpuSettings,
        time_budget: Option<Duration>,
    ) -> Result<ViewDriven, CliError> {
        let weights = view::view_weights(&self.rscene, point);
        let seen = weights.iter().filter(|&&w| w > 0.0).count();
        if seen == 0 {
            return Err(CliError::input(anyhow!(
                "{}: --drive {}: the camera sees no surface of the scene (check camera.position and camera.look_at)",
                self.label.display(),
                self.solver.drive.name()
            )));
        }
        let driven = ViewDriven::new(
            light,
            settings,
            gpu_settings,
            weights,
            time_budget.map(|b| b / 4),
        )?;
        eprintln!(
            "{}: the camera sees {seen} of {} elements; importance solved in {:.2} s",
            self.label.display(),
            self.rscene.elements.len(),
            driven.importance_seconds
        );
        Ok(driven)
    }

    /// Shoots until the solver's stop (Ctrl-C stops early), with a progress bar, and
    /// reads the solution back.
    pub fn solve(&self) -> Result<Solved<'_>, CliError> {
        let args = &self.solver;
        let rscene = &self.rscene;
        let gpu_settings = GpuSettings {
            visibility: args.visibility,
            map_size: args.map_size,
            hierarchy: args.hierarchy,
            cell_power: args.cell_power,
            link_error: args.link_error,
            raster: args.raster,
            ..GpuSettings::default()
        };
        if let Some(why) = args.raster.refusal(rscene.has_masked_casters()) {
            return Err(CliError::input(anyhow!("{}: {why}", self.label.display())));
        }
        let shooters = Shooters::build(rscene, args.hierarchy);
        let shooter_count = shooters.len();
        let settings = SolverSettings {
            form_factor: args.form_factor,
            ambient: args.ambient,
            interp: self.interp,
        };
        let mut solver = GpuSolver::with_shooters(
            &self.gpu,
            rscene,
            &self.initial,
            settings,
            gpu_settings,
            shooters,
        );
        let cancel = super::interrupt_flag();
        eprintln!(
            "{}: {} elements in {} charts, {} patches, atlas {}×{}; {shooter_count} shooters{}; visibility maps draw {} triangles ({} raster); shooting (Ctrl-C stops and writes the solution so far)",
            self.label.display(),
            rscene.elements.len(),
            rscene.elements.charts.len(),
            rscene.elements.patches.len(),
            rscene.elements.atlas_width,
            rscene.elements.atlas_height,
            match args.hierarchy {
                Hierarchy::None => " (one per triangle: --hierarchy none)".to_string(),
                Hierarchy::Clusters => {
                    let tree = &rscene.planar_clusters().tree;
                    format!(" of {} face clusters", tree.nodes.len() - tree.order.len())
                }
            },
            solver.visibility_triangles(),
            solver.raster().name(),
        );
        let mut stop_at = args.stop();
        let driven = match &self.view {
            Some(point) => {
                let d = self.drive(&solver, point, settings, gpu_settings, stop_at.time_budget)?;
                d.drive(&mut solver, args.drive, point, args.fov_margin)?;
                // The importance solve's time is the solve's.
                stop_at.time_budget = stop_at.time_budget.map(|b| {
                    b.saturating_sub(Duration::try_from_secs_f64(d.importance_seconds).unwrap_or(b))
                });
                Some(d)
            }
            None => None,
        };
        let bar = progress_bar()?;
        let (stop, log) = solver.solve(&stop_at, &cancel, |p: &ConvergencePoint| {
            bar.set_position((p.convergence.clamp(0.0, 1.0) * 10_000.0) as u64);
            bar.set_message(format!(
                "{:.2} % converged, {} shots",
                100.0 * p.convergence,
                p.shot
            ));
        })?;
        bar.finish_and_clear();
        let solve_s = log.last().map_or(0.0, |p| p.seconds);
        let (radiosity, illuminance) = solver.radiosity_and_illuminance()?;
        let unshot = solver.unshot_to_come()?;
        let (shown, shown_lux) = crate::radiosity::view::displayed(
            rscene,
            &radiosity,
            &illuminance,
            &unshot,
            args.ambient,
            driven.as_ref(),
        );
        if let Some((stage, stages)) = solver.area_stage() {
            eprintln!(
                "{}: area of interest at stage {} of {stages}; {} charts hold their light back, {} wait, {} shots kept for them",
                self.label.display(),
                stage + 1,
                solver.holding_charts(),
                solver.waiting_charts(),
                solver.missed_shots(),
            );
        }
        let last = log.last().copied();
        eprintln!(
            "{}: {} shots, {:.2} % converged ({stop}) in {solve_s:.2} s (+{:.2} s to prepare); {} visibility maps drawn{}, {} cells skipped (no receiver takes light from them); receivers culled to {:.0} % of the elements per map{}",
            self.label.display(),
            solver.shots,
            100.0 * last.map_or(1.0, |p| p.convergence),
            self.prepared_s,
            solver.drawn + solver.virtual_drawn,
            match solver.virtual_drawn {
                0 => String::new(),
                n => format!(" ({n} of them cells' images through mirrors and glass)"),
            },
            solver.skipped,
            100.0 * solver.receiver_threads as f64
                / ((solver.drawn + solver.virtual_drawn).max(1) as f64
                    * rscene.elements.len().max(1) as f64),
            crate::io::peak_memory_mb().map_or(String::new(), |mb| format!("; peak memory {mb} MB")),
        );
        Ok(Solved {
            prepared: self,
            solver,
            stop,
            log,
            shown,
            shown_lux,
        })
    }
}

impl Solved<'_> {
    /// The interreflected illuminance (lux, the light the solution's surfaces send; not
    /// the luminaires' direct light) at `points`, gathered from the shooters' finest
    /// cells, with a progress bar; Ctrl-C stops it with an error. Also the number of
    /// patches gathered from.
    pub fn interreflected_lux(
        &self,
        points: &[SurfacePoint],
    ) -> Result<(Vec<f64>, usize), CliError> {
        let rscene = &self.prepared.rscene;
        let patches = gather::patches(rscene, self.solver.shooters(), &self.shown);
        eprintln!(
            "gathering at {} points from {} patches (Ctrl-C stops)",
            points.len(),
            patches.len()
        );
        let bar = indicatif::ProgressBar::new(points.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "gather [{bar:40}] {pos}/{len} points ({elapsed_precise}, Ctrl-C stops)",
            )
            .map_err(|e| CliError::failure(anyhow!(e)))?,
        );
        // A Ctrl-C that stopped the shooting has been answered: the next one stops this.
        let cancel = super::interrupt_flag();
        cancel.store(false, std::sync::atomic::Ordering::SeqCst);
        let gathered = gather::at_points(
            rscene,
            &patches,
            points,
            self.prepared.solver.form_factor,
            &cancel,
            &|done| bar.set_position(done as u64),
        );
        bar.finish_and_clear();
        let Some(gathered) = gathered else {
            return Err(CliError::failure(anyhow!(
                "interrupted while gathering at the points: no illuminance given"
            )));
        };
        Ok((gathered.into_iter().map(luminance).collect(), patches.len()))
    }

    /// The light-map atlas of the solution as shown.
    pub fn light_map(&self) -> LightMap {
        solve::light_map(&self.prepared.rscene, &self.shown, &self.shown_lux)
    }

    /// The fraction of the initial unshot power shot when the solver stopped.
    pub fn convergence(&self) -> f64 {
        self.log.last().map_or(1.0, |p| p.convergence)
    }
}

/// Runs `radiosity`.
pub fn run(args: RadiosityArgs) -> Result<(), CliError> {
    args.check()?;
    let started = Instant::now();
    let stage = StageSpinner::new("loading the scene")?;
    eprintln!(
        "{}: preparing (Ctrl-C stops; nothing is written)",
        args.scene.display()
    );
    let scene = super::render::scene_at(Scene::load(&args.scene)?, args.image.time)?;
    stage.check()?;
    drop(stage);
    let mut settings = args.image.settings(&scene)?;
    let points = if args.points {
        read_points(std::io::stdin().lock(), "stdin")?
    } else {
        Vec::new()
    };
    let out_dir = match (&args.out_dir, args.points) {
        (Some(d), _) => Some(d.clone()),
        (None, false) => Some(PathBuf::from("radiosity-out")),
        (None, true) => None,
    };
    let inputs = scene.input_files();
    let mut outputs = crate::io::outputs::OutputCheck::new();
    for f in &inputs {
        outputs.input(f);
    }
    if let Some(dir) = &out_dir {
        for name in OUT_DIR_FILES {
            outputs.output(dir.join(name));
        }
    }
    if let Some(path) = &args.export {
        outputs.named_output(&format!("--export {}", path.display()), path);
    }
    outputs.check()?;
    let prepared = prepare(&args.scene, &scene, &args.solver, &mut settings, started)?;
    let solved = prepared.solve()?;
    if !points.is_empty() {
        let gathered = Instant::now();
        let mut direct = prepared
            .light
            .lux(&prepared.gpu, &points, &settings.shadows)?;
        // What mirrors and clear glass pass on (the probe draws straight light only).
        let interp = settings.light_model.interp();
        let specular = prepared.rscene.specular_light();
        specular.add_lux_at_points(&points, &mut direct, interp);
        let (indirect, patches) = solved.interreflected_lux(&points)?;
        let mut out = String::with_capacity(points.len() * 12);
        for (d, i) in direct.iter().zip(&indirect) {
            out.push_str(&format!("{:.6}\n", d + i));
        }
        print!("{out}");
        eprintln!(
            "{}: {} points gathered from {patches} patches in {:.2} s",
            args.scene.display(),
            points.len(),
            gathered.elapsed().as_secs_f64()
        );
    }
    let rscene = &prepared.rscene;
    let light_map = solved.light_map();
    if let Some(path) = &args.export {
        let names: Vec<String> = scene.materials.iter().map(|m| m.name.clone()).collect();
        let material_bake: Vec<_> = scene.materials.iter().map(|m| m.bake).collect();
        let planning = Instant::now();
        let plan = bake::plan(rscene, &material_bake, args.bake, args.bake_budget);
        eprintln!(
            "{}; chosen and refined in {:.2} s",
            bake_summary(&plan, &light_map),
            planning.elapsed().as_secs_f64()
        );
        let bytes = crate::radiosity::export::glb(rscene, &light_map, &plan, &names)
            .map_err(CliError::failure)?;
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
        folder
            .map_or(Ok(()), std::fs::create_dir_all)
            .map_err(anyhow::Error::from)
            .and_then(|()| write_atomic(path, &bytes))
            .map_err(|e| CliError::input(anyhow!("--export {}: {e:#}", path.display())))?;
        eprintln!("wrote {} ({} kB)", path.display(), bytes.len() >> 10);
    }
    if let Some(dir) = out_dir {
        let outputs = Outputs {
            light_map,
            csv: solve::convergence_csv(&solved.log),
        };
        settings.read_hdr = true;
        settings.shown_light = crate::scene::DisplayIndirect::Radiosity;
        let staging = crate::io::outputs::Staging::beside(&dir, &inputs)
            .map_err(|e| CliError::input(anyhow!("--out-dir {}: {e}", dir.display())))?;
        write_outputs(&prepared.gpu, &scene, &settings, &outputs, &staging)?;
        staging
            .commit()
            .map_err(|e| CliError::failure(anyhow!("--out-dir {}: {e:#}", dir.display())))?;
    }
    if solved.stop == StopReason::Cancelled {
        eprintln!("stopped early: the solution so far was written");
    }
    Ok(())
}

/// What the export's representation costs (Edström §5.3, §7.6).
/// What adaptive subdivision made: elements by size against one per texel.
fn adaptive_summary(el: &Elements) -> String {
    let levels = el.subdivision.levels;
    let mut by_side = vec![0usize; levels as usize + 1];
    for &s in &el.span {
        by_side[s.trailing_zeros() as usize] += 1;
    }
    let texels: u64 = el.span.iter().map(|&s| u64::from(s) * u64::from(s)).sum();
    let sizes: Vec<String> = by_side
        .iter()
        .enumerate()
        .rev()
        .map(|(k, n)| format!("{n} of {0}×{0}", 1u32 << k))
        .collect();
    format!(
        "adaptive subdivision: {} elements ({} texels), split at the luminaires' shadow and beam edges: {}",
        el.len(),
        texels,
        sizes.join(", ")
    )
}

fn bake_summary(plan: &BakePlan, map: &LightMap) -> String {
    format!(
        "bake: {} surfaces ({} triangles) light-mapped, {} ({} triangles) vertex-lit with {} triangles introduced (budget {}): the exported mesh draws {:+.1} % triangles over the model; light map {}×{} texels",
        plan.surfaces[0],
        plan.triangles[0],
        plan.surfaces[1],
        plan.triangles[1],
        plan.introduced,
        plan.budget,
        100.0 * plan.overhead(),
        map.width,
        map.height,
    )
}

/// The files `radiosity` writes into its output folder.
const OUT_DIR_FILES: [&str; 5] = [
    "render.png",
    "render.exr",
    "lightmap.exr",
    "lightmap_lux.exr",
    "convergence.csv",
];

/// Writes the rendering, the atlas and the log into the staging folder of the output
/// folder.
fn write_outputs(
    gpu: &Gpu,
    scene: &Scene,
    settings: &crate::render::RenderSettings,
    outputs: &Outputs,
    staging: &crate::io::outputs::Staging,
) -> Result<(), CliError> {
    let dir = staging.dir();
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::input(anyhow!("--out-dir {}: {e}", dir.display())))?;
    let png = dir.join("render.png");
    let exr = dir.join("render.exr");
    let renderer = Renderer::new(gpu);
    let (_, report) = render_to_files(
        gpu,
        &renderer,
        scene,
        Some(&outputs.light_map),
        settings,
        &png,
        Some(&exr),
    )?;
    // The files are named where they will be once moved in.
    eprintln!("{}", staging.as_target(&report));
    let map = &outputs.light_map;
    let rgb: Vec<f32> = map.texels.iter().flat_map(|t| [t[0], t[1], t[2]]).collect();
    let lux: Vec<f32> = map.texels.iter().flat_map(|t| [t[3]; 3]).collect();
    for (name, data) in [("lightmap.exr", rgb), ("lightmap_lux.exr", lux)] {
        let image = image::Rgb32FImage::from_raw(map.width, map.height, data)
            .ok_or_else(|| CliError::failure(anyhow!("light-map size mismatch")))?;
        write_image(&dir.join(name), &image).map_err(CliError::failure)?;
    }
    write_atomic(&dir.join("convergence.csv"), outputs.csv.as_bytes())
        .map_err(CliError::failure)?;
    Ok(())
}
