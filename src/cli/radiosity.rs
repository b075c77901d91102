//! `goniolight radiosity`: solve a scene's interreflected light on the GPU, write the
//! rendering of the solution, the light-map atlas and the convergence log, and with
//! `--points` print the total illuminance at points read from stdin.

use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::time::Instant;

use anyhow::anyhow;
use clap::Args;

use super::error::CliError;
use super::image::{render_to_files, ImageOptions};
use super::solver_args::SolverArgs;
use super::solving::{gathered_lux, interrupted_while, solve, spinner};
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::lighting::read_points;
use crate::radiosity::bake::BakeChoice;
use crate::radiosity::session::describe;
use crate::radiosity::solve::StopReason;
use crate::render::lightmap::LightMap;
use crate::render::output::write_image;
use crate::render::Renderer;
use crate::scene::Scene;

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
    let scene = super::scene_input::scene_at(
        super::scene_input::load_scene(&args.scene)?,
        args.image.time,
    )?;
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
        let lux = gathered_lux(&args.scene, &solution, &points, true)?;
        let mut out = String::with_capacity(points.len() * 12);
        for v in &lux {
            out.push_str(&format!("{v:.6}\n"));
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
            describe::bake_summary(&plan, &map),
            planning.elapsed().as_secs_f64()
        );
        let folder = path.parent().filter(|p| !p.as_os_str().is_empty());
        folder
            .map_or(Ok(()), crate::io::create_dir)
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
