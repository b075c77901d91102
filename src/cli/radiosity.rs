//! `goniolight radiosity`: solve a scene's interreflected light on the GPU, write the
//! rendering of the solution, the light-map atlas and the convergence log, and with
//! `--points` print the total illuminance at points read from stdin.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::anyhow;
use clap::Args;

use super::error::CliError;
use super::render::{render_to_files, ImageOptions};
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::lighting::read_points;
use crate::lighting::SurfacePoint;
use crate::radiosity::bake::{BakeChoice, BakePlan};
use crate::radiosity::elements::Elements;
use crate::radiosity::gpu::{Raster, Visibility};
use crate::radiosity::links::DEFAULT_LINK_ERROR;
use crate::radiosity::session::{self, Event, Options, SessionError, Solution, Stage};
use crate::radiosity::shooters::{Hierarchy, DEFAULT_CELL_POWER};
use crate::radiosity::solve::StopReason;
use crate::radiosity::view::Drive;
use crate::radiosity::{Ambient, FormFactorKind};
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
    #[arg(long, value_parser = super::args::seconds_arg)]
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
    /// The library's options these flags give (`adaptive_share` must hold two values:
    /// [`SolverArgs::check`]).
    pub fn options(&self) -> Options {
        let share = match self.adaptive_share[..] {
            [lower, upper] => [lower, upper],
            _ => [f64::NAN; 2],
        };
        Options {
            converge: self.converge,
            max_shots: self.max_shots,
            time_limit: self.time_limit,
            texel_density: self.texel_density,
            level: self.level,
            adaptive: self.adaptive,
            adaptive_share: share,
            visibility: self.visibility,
            map_size: self.map_size,
            raster: self.raster,
            hierarchy: self.hierarchy,
            cell_power: self.cell_power,
            link_error: self.link_error,
            form_factor: self.form_factor,
            ambient: self.ambient,
            drive: self.drive,
            fov_margin: self.fov_margin,
            importance_time_limit: None,
        }
    }

    /// The options, or an error naming the flag whose value is out of range.
    pub fn check(&self) -> Result<Options, CliError> {
        if self.adaptive_share.len() != 2 {
            let given: Vec<String> = self.adaptive_share.iter().map(f64::to_string).collect();
            return Err(CliError::input(anyhow!(
                "--adaptive-share {}: give LOWER,UPPER with 0 ≤ LOWER ≤ UPPER ≤ 1",
                given.join(",")
            )));
        }
        let options = self.options();
        options.validate()?;
        Ok(options)
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

fn style(template: &str) -> Result<indicatif::ProgressStyle, CliError> {
    indicatif::ProgressStyle::with_template(template).map_err(|e| CliError::failure(anyhow!(e)))
}

/// A spinner naming a stage (drawn on a terminal only).
fn spinner(first: &str) -> Result<indicatif::ProgressBar, CliError> {
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
                prepared_summary(self.label, p, self.load_s, self.prepared_s);
            }
            Event::Shooting(session) => {
                if let Some(d) = session.driven() {
                    eprintln!(
                        "{}: the camera sees {} of {} elements; importance solved in {:.2} s",
                        self.label.display(),
                        d.view.iter().filter(|&&w| w > 0.0).count(),
                        session.prepared().scene().elements.len(),
                        d.importance_seconds
                    );
                }
                shooting_summary(self.label, session);
                let bar = indicatif::ProgressBar::new(10_000);
                bar.set_style(style(
                    "radiosity [{bar:40}] {msg} ({elapsed_precise}, Ctrl-C stops and writes)",
                )?);
                self.bar = Some(bar);
            }
            Event::Shot(p) => {
                if let Some(bar) = &self.bar {
                    bar.set_position((p.convergence.clamp(0.0, 1.0) * 10_000.0) as u64);
                    bar.set_message(format!(
                        "{:.2} % converged, {} shots",
                        100.0 * p.convergence,
                        p.shot
                    ));
                }
            }
            Event::Solved(session) => {
                if let Some(bar) = self.bar.take() {
                    bar.finish_and_clear();
                }
                solved_summary(self.label, session, self.prepared_s);
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

/// The preparation's line: its stages' times, the triangles, the peak memory.
fn prepared_summary(label: &Path, p: &session::Prepared, load_s: f64, prepared_s: f64) {
    let rscene = p.scene();
    if p.options().adaptive > 0 {
        eprintln!(
            "{} (the splits decided in {:.2} s of CPU)",
            adaptive_summary(&rscene.elements),
            rscene.subdivision_seconds
        );
    }
    eprintln!(
        "{}: prepared in {prepared_s:.2} s — load {load_s:.2} s, {}elements and atlas {:.2} s, {}luminaires' direct light {:.2} s; {} triangles{}",
        label.display(),
        match p.options().hierarchy {
            Hierarchy::None => String::new(),
            Hierarchy::Clusters => format!("face clusters {:.2} s, ", rscene.clustering_seconds),
        },
        p.times.elements - rscene.clustering_seconds - rscene.receiving_seconds,
        if rscene.receiving_normals.is_empty() {
            String::new()
        } else {
            format!("receiving normals {:.2} s, ", rscene.receiving_seconds)
        },
        p.times.direct_light,
        p.triangle_count(),
        crate::io::peak_memory_mb().map_or(String::new(), |mb| format!(", peak memory {mb} MB")),
    );
}

/// The line before shooting: elements, charts, patches, atlas, shooters, the maps.
fn shooting_summary(label: &Path, session: &session::Session) {
    let rscene = session.prepared().scene();
    let solver = session.solver();
    eprintln!(
        "{}: {} elements in {} charts, {} patches, atlas {}×{}; {} shooters{}; visibility maps draw {} triangles ({} raster); shooting (Ctrl-C stops and writes the solution so far)",
        label.display(),
        rscene.elements.len(),
        rscene.elements.charts.len(),
        rscene.elements.patches.len(),
        rscene.elements.atlas_width,
        rscene.elements.atlas_height,
        solver.shooters().len(),
        match session.prepared().options().hierarchy {
            Hierarchy::None => " (one per triangle: --hierarchy none)".to_string(),
            Hierarchy::Clusters => {
                let tree = &rscene.planar_clusters().tree;
                format!(" of {} face clusters", tree.nodes.len() - tree.order.len())
            }
        },
        solver.visibility_triangles(),
        solver.raster().name(),
    );
}

/// The line after shooting: shots, convergence, why it stopped, the maps drawn.
fn solved_summary(label: &Path, session: &session::Session, prepared_s: f64) {
    let solver = session.solver();
    if let Some((stage, stages)) = solver.area_stage() {
        eprintln!(
            "{}: area of interest at stage {} of {stages}; {} charts hold their light back, {} wait, {} shots kept for them",
            label.display(),
            stage + 1,
            solver.holding_charts(),
            solver.waiting_charts(),
            solver.missed_shots(),
        );
    }
    let last = session.log().last().copied();
    let drawn = solver.drawn + solver.virtual_drawn;
    eprintln!(
        "{}: {} shots, {:.2} % converged ({}) in {:.2} s (+{prepared_s:.2} s to prepare); {drawn} visibility maps drawn{}, {} cells skipped (no receiver takes light from them); receivers culled to {:.0} % of the elements per map{}",
        label.display(),
        solver.shots,
        100.0 * last.map_or(1.0, |p| p.convergence),
        session.stopped().unwrap_or(StopReason::Cancelled),
        last.map_or(0.0, |p| p.seconds),
        match solver.virtual_drawn {
            0 => String::new(),
            n => format!(" ({n} of them cells' images through mirrors and glass)"),
        },
        solver.skipped,
        100.0 * solver.receiver_share(),
        crate::io::peak_memory_mb().map_or(String::new(), |mb| format!("; peak memory {mb} MB")),
    );
}

/// A solve's error as the command reports it: a cancelled preparation wrote nothing.
fn session_error(e: SessionError, label: &Path) -> CliError {
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
    let aspect = settings.width as f64 / settings.height.max(1) as f64;
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
    super::render::warn_shadow_fit(scene, &settings.shadows);
    match progress.error.take() {
        Some(e) => Err(e),
        None => Ok(solution),
    }
}

/// The interreflected illuminance of `solution` at `points` (lux), with a progress bar;
/// Ctrl-C stops it with an error.
pub fn interreflected_lux(
    label: &Path,
    solution: &Solution,
    points: &[SurfacePoint],
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
    let lux = solution.interreflected_lux(points, &cancel, &|done| bar.set_position(done as u64));
    bar.finish_and_clear();
    lux.map_err(|e| session_error(e, label))
}

/// Runs `radiosity`.
pub fn run(args: RadiosityArgs) -> Result<(), CliError> {
    args.check()?;
    let options = args.solver.check()?;
    let started = Instant::now();
    let loading = spinner("loading the scene")?;
    let cancel = super::interrupt::interrupt_flag();
    cancel.store(false, Ordering::SeqCst);
    eprintln!(
        "{}: preparing (Ctrl-C stops; nothing is written)",
        args.scene.display()
    );
    let scene = super::render::scene_at(super::render::load_scene(&args.scene)?, args.image.time)?;
    loading.finish_and_clear();
    interrupted_while(&cancel, "loading the scene")?;
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
    let solution = solve(&args.scene, &scene, &options, &mut settings, started)?;
    if !points.is_empty() {
        let gathered = Instant::now();
        let direct = solution
            .direct_lux(&points)
            .map_err(|e| session_error(e, &args.scene))?;
        let indirect = interreflected_lux(&args.scene, &solution, &points)?;
        let mut out = String::with_capacity(points.len() * 12);
        for (d, i) in direct.iter().zip(&indirect) {
            out.push_str(&format!("{:.6}\n", d + i));
        }
        print!("{out}");
        eprintln!(
            "{}: {} points gathered from {} patches in {:.2} s",
            args.scene.display(),
            points.len(),
            solution.gather_patches(),
            gathered.elapsed().as_secs_f64()
        );
    }
    if let Some(path) = &args.export {
        let planning = Instant::now();
        let (bytes, plan, map) = solution
            .export_glb(&scene, args.bake, args.bake_budget)
            .map_err(CliError::failure)?;
        eprintln!(
            "{}; chosen and refined in {:.2} s",
            bake_summary(&plan, &map),
            planning.elapsed().as_secs_f64()
        );
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
            light_map: solution.light_map(),
            csv: solution.convergence_csv(),
        };
        settings.read_hdr = true;
        settings.shown_light = crate::scene::DisplayIndirect::Radiosity;
        let staging = crate::io::outputs::Staging::beside(&dir, &inputs)
            .map_err(|e| CliError::input(anyhow!("--out-dir {}: {e}", dir.display())))?;
        write_outputs(
            solution.prepared().gpu(),
            &scene,
            &settings,
            &outputs,
            &staging,
        )?;
        staging
            .commit()
            .map_err(|e| CliError::failure(anyhow!("--out-dir {}: {e:#}", dir.display())))?;
    }
    if solution.stop() == StopReason::Cancelled {
        eprintln!("stopped early: the solution so far was written");
    }
    Ok(())
}

/// An error if Ctrl-C came while `stage` ran (before anything is written).
fn interrupted_while(cancel: &AtomicBool, stage: &str) -> Result<(), CliError> {
    if cancel.load(Ordering::SeqCst) {
        return Err(CliError::failure(anyhow!(
            "interrupted while preparing ({stage}): nothing written"
        )));
    }
    Ok(())
}

/// What the export's representation costs (Edström §5.3, §7.6).
/// What adaptive subdivision made: elements by size against one per texel.
fn adaptive_summary(el: &Elements) -> String {
    let (by_side, texels) = el.sizes();
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

/// Everything the command writes, computed before anything is written.
struct Outputs {
    light_map: LightMap,
    csv: String,
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
    let (rgb, lux) = map
        .images()
        .ok_or_else(|| CliError::failure(anyhow!("light-map size mismatch")))?;
    for (name, image) in [("lightmap.exr", rgb), ("lightmap_lux.exr", lux)] {
        write_image(&dir.join(name), &image).map_err(CliError::failure)?;
    }
    write_atomic(&dir.join("convergence.csv"), outputs.csv.as_bytes())
        .map_err(CliError::failure)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use clap::{Args, FromArgMatches};

    use super::SolverArgs;
    use crate::radiosity::session::Options;

    fn parsed(args: &[&str]) -> SolverArgs {
        let command = SolverArgs::augment_args(clap::Command::new("radiosity"));
        let matches = command
            .try_get_matches_from(std::iter::once("radiosity").chain(args.iter().copied()))
            .unwrap();
        SolverArgs::from_arg_matches(&matches).unwrap()
    }

    #[test]
    fn the_flags_defaults_are_the_librarys() {
        assert_eq!(parsed(&[]).options(), Options::default());
    }

    #[test]
    fn a_value_out_of_range_names_its_flag() {
        let e = parsed(&["--map-size", "8"]).check().unwrap_err();
        assert_eq!(e.message(), "--map-size 8 is not in 16..=4096");
        let e = parsed(&["--adaptive-share", "0.5"]).check().unwrap_err();
        assert!(e
            .message()
            .starts_with("--adaptive-share 0.5: give LOWER,UPPER"));
    }
}
