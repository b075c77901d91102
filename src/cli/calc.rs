//! `calc`: the scene's calculation surfaces — per grid the illuminance at every point,
//! maintained (times the maintenance factor), its statistics in `calc.json`, the points
//! in one CSV per grid and its plan (PNG and SVG).

use std::path::PathBuf;

use anyhow::anyhow;
use clap::Args;
use serde_json::json;

use super::calc_report::{report_html, ReportGrid, ReportObserver};
use super::radiosity::SolverArgs;
use super::render::scene_at;
use super::CliError;
use crate::calc::directions::{combine, surface_points};
use crate::calc::glare::{background_point, observer_glare, ObserverGlare};
use crate::calc::plan::Plan;
use crate::calc::{grid_stats, CalcGrid, CalcSettings};
use crate::gpu::Gpu;
use crate::io::limits::MAX_TOTAL_POINTS;
use crate::io::outputs::{OutputCheck, Staging};
use crate::io::{printable, write_atomic};
use crate::lighting::SurfacePoint;
use crate::photometry::Interp;
use crate::render::illuminance::scene_illuminance;
use crate::render::{ShadowSettings, ShadowTechnique};
use crate::scene::grid::Indirect;
use crate::scene::Scene;

/// Options of `calc`.
#[derive(Debug, Args)]
pub struct CalcArgs {
    /// The scene file (TOML) with its `[[grid]]` calculation surfaces and `[[observer]]`s.
    pub scene: PathBuf,
    /// Folder for `calc.json` and one `<grid name>.csv` per grid (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    /// Maintenance factor (0–1]: the values reported are the computed ones times it
    /// (default: the scene's `calc.maintenance_factor`, else 1).
    #[arg(long, value_name = "MF")]
    pub maintenance_factor: Option<f64>,
    /// Compute on the CPU (the reference) instead of with the renderer's WGSL code.
    #[arg(long)]
    pub cpu: bool,
    /// Interpolation of the light distributions.
    #[arg(long, value_enum, default_value = "catmull-rom")]
    pub interp: Interp,
    /// Shadows cast by the scene's geometry (as for `illuminance`; default volumes: exact
    /// hard shadows by a ray from each point to each luminaire).
    #[arg(long, value_enum, default_value = "volumes")]
    pub shadows: ShadowTechnique,
    /// Seconds since the start of the animation (effect lights turned this far).
    #[arg(long)]
    pub time: Option<f64>,
    /// Palette of the plans (default: the scene's `display.palette`, else rainbow).
    #[arg(long, value_enum)]
    pub palette: Option<crate::scene::Palette>,
    /// Hard colour steps of the plans (0: smooth; default the scene's `display.steps`).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..=crate::scene::palette::MAX_STEPS as i64))]
    pub steps: Option<u32>,
    /// Print the value at every point on the plans.
    #[arg(long)]
    pub values: bool,
    /// Also write one self-contained HTML page: settings, luminaires, each grid's
    /// statistics and plan (its folder must exist, or be the --out folder).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
    /// Direct light only, or total light (direct + interreflected, through the radiosity
    /// solver). UGR at `[[observer]]`s needs the interreflected light (the background
    /// luminance): `radiosity`. Default: the scene's `calc.indirect`, else none.
    #[arg(long, value_enum)]
    pub indirect: Option<Indirect>,
    /// The most points over all grids together (each costs memory and about 100 bytes
    /// of files); a run above it is refused before any work.
    #[arg(long, value_name = "N", default_value_t = MAX_TOTAL_POINTS)]
    pub max_points: usize,
    /// The radiosity solver's options (with `--indirect radiosity`).
    #[command(flatten, next_help_heading = "Radiosity (with --indirect radiosity)")]
    pub solver: SolverArgs,
}

/// The file name of a grid's CSV: its name with anything but letters, digits, `-` and `_`
/// replaced by `-`.
pub fn csv_name(grid_name: &str) -> String {
    let stem: String = grid_name
        .trim()
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .collect();
    format!("{stem}.csv")
}

/// How the values were lit, for the grids' files: the maintenance factor, the light's
/// description and whether it includes the interreflected light.
struct Lit<'l> {
    mf: f64,
    light: &'l [String],
    total: bool,
}

/// One grid's computed values (maintained) and how they were lit.
struct Computed<'g> {
    grid: &'g CalcGrid,
    values: Vec<f64>,
}

/// Runs `calc`.
pub fn run(args: CalcArgs) -> Result<(), CliError> {
    let started = std::time::Instant::now();
    let scene = scene_at(Scene::load(&args.scene)?, args.time)?;
    if scene.grids.is_empty() && scene.observers.is_empty() {
        return Err(CliError::input(anyhow!(
            "{}: no [[grid]] or [[observer]] to compute; add a calculation surface (docs/src/guide/calc.md)",
            args.scene.display()
        )));
    }
    let mf = CalcSettings::check(
        args.maintenance_factor
            .unwrap_or(scene.calc.maintenance_factor),
    )
    .map_err(|e| CliError::input(anyhow!("--maintenance-factor {e}")))?;
    let indirect = args
        .indirect
        .or(scene.calc.indirect)
        .unwrap_or(Indirect::None);
    if !scene.observers.is_empty() && indirect == Indirect::None {
        return Err(CliError::input(anyhow!(
            "{}: UGR at the [[observer]]s needs the background luminance, which is the interreflected light at the eye: run with --indirect radiosity (or set calc.indirect = \"radiosity\")",
            args.scene.display()
        )));
    }
    if indirect == Indirect::Radiosity && args.cpu {
        return Err(CliError::input(anyhow!(
            "--cpu computes the direct light only: the radiosity solver runs on the GPU (leave out --cpu, or use --indirect none)"
        )));
    }
    args.solver.check()?;
    if args.solver.drive != crate::radiosity::view::Drive::Global {
        // A grid's lux must not depend on where the camera looks.
        return Err(CliError::input(anyhow!(
            "--drive {}: calc's interreflected light is solved for the whole scene (--drive global); view-driven solutions are for `radiosity` and the viewer",
            args.solver.drive.name()
        )));
    }
    let mut names = std::collections::HashSet::new();
    for g in &scene.grids {
        if !names.insert(csv_name(&g.entry.name)) {
            return Err(CliError::input(anyhow!(
                "{}: grid {:?} would write the same CSV file as another grid ({}); rename one",
                args.scene.display(),
                g.entry.name,
                csv_name(&g.entry.name)
            )));
        }
    }
    if args.out.is_file() {
        return Err(CliError::input(anyhow!(
            "--out {}: is a file, not a folder",
            args.out.display()
        )));
    }
    let inputs = scene.input_files();
    let mut outputs = OutputCheck::new();
    for f in &inputs {
        outputs.input(f);
    }
    outputs.output(args.out.join("calc.json"));
    for g in &scene.grids {
        let csv = csv_name(&g.entry.name);
        let stem = csv.trim_end_matches(".csv");
        for name in [csv.clone(), format!("{stem}.png"), format!("{stem}.svg")] {
            outputs.output(args.out.join(name));
        }
    }
    if let Some(report) = &args.report {
        outputs.named_output(&format!("--report {}", report.display()), report);
        // The report may go into the --out folder, which the run makes.
        if report.parent() != Some(args.out.as_path()) {
            super::check_folder_of(report, "--report")?;
        }
    }
    outputs.check()?;
    let total: usize = scene.grids.iter().map(|g| g.points.len()).sum();
    if total > args.max_points {
        return Err(CliError::input(anyhow!(
            "{}: the grids hold {total} points together, more than --max-points {} (each point costs memory and about 100 bytes of files): use a larger spacing, split the grids over several runs, or raise --max-points",
            args.scene.display(),
            args.max_points
        )));
    }
    for o in &scene.observers {
        for l in &scene.luminaires {
            crate::calc::glare::check_outside(o, l).map_err(|e| {
                CliError::input(anyhow!(
                    "{}: observer {:?}: {e}",
                    args.scene.display(),
                    o.entry.name
                ))
            })?;
        }
    }
    let cancel = super::interrupt_flag();
    let gpu = if args.cpu { None } else { Some(Gpu::shared()?) };
    // Every (point, normal) of every grid, then the observers' eyes: one list, so the
    // radiosity gather runs once.
    let grid_points: Vec<Vec<SurfacePoint>> = scene.grids.iter().map(surface_points).collect();
    let eyes: Vec<SurfacePoint> = scene.observers.iter().map(background_point).collect();
    let mut lux: Vec<Vec<f64>> = Vec::with_capacity(grid_points.len());
    for (g, points) in scene.grids.iter().zip(&grid_points) {
        interrupted(&cancel)?;
        let direct = scene_illuminance(gpu.as_ref(), &scene, points, args.interp, args.shadows)?;
        check_usable(&g.entry.name, &direct)?;
        lux.push(direct);
    }
    let mut background = vec![0.0; eyes.len()];
    let mut convergence = None;
    if indirect == Indirect::Radiosity {
        let all: Vec<SurfacePoint> = grid_points.iter().flatten().chain(&eyes).copied().collect();
        let (interreflected, converged) = interreflected_lux(&args, &scene, &all, started)?;
        convergence = Some(converged);
        let mut at = 0;
        for (g, direct) in scene.grids.iter().zip(lux.iter_mut()) {
            for v in direct.iter_mut() {
                *v += interreflected[at];
                at += 1;
            }
            check_usable(&g.entry.name, direct)?;
        }
        // UGR from the installation's initial light, as UGR tables are: the maintenance
        // factor scales neither the luminaires' luminance nor the background.
        for b in &mut background {
            *b = interreflected[at].max(0.0) / std::f64::consts::PI;
            at += 1;
        }
    }
    let computed: Vec<Computed> = scene
        .grids
        .iter()
        .zip(&lux)
        .map(|(g, lux)| Computed {
            grid: g,
            values: combine(g, lux)
                .into_iter()
                .map(|v| v.max(0.0) * mf)
                .collect(),
        })
        .collect();
    let glare: Vec<ObserverGlare> = scene
        .observers
        .iter()
        .zip(&background)
        .map(|(o, &lb)| {
            observer_glare(&scene, o, lb, args.interp)
                .map_err(|e| CliError::input(anyhow!("observer {:?}: {e}", o.entry.name)))
        })
        .collect::<Result<_, _>>()?;
    let light = match (indirect, convergence) {
        (Indirect::Radiosity, Some(c)) => vec![
            "direct + interreflected".to_string(),
            format!("(radiosity, {:.1} % converged)", 100.0 * c),
        ],
        _ => vec!["direct light only".to_string()],
    };
    interrupted(&cancel)?;
    let staging = Staging::beside(&args.out, &inputs)
        .map_err(|e| CliError::failure(anyhow!("{}: {e}", args.out.display())))?;
    let (grids_json, report_grids) = write_grids(
        &args,
        staging.dir(),
        &scene,
        &computed,
        &glare,
        Lit {
            mf,
            light: &light,
            total: indirect == Indirect::Radiosity,
        },
    )?;
    let observers_json: Vec<_> = scene
        .observers
        .iter()
        .zip(&glare)
        .map(|(o, g)| {
            json!({
                "name": o.entry.name,
                "position": o.entry.position,
                "direction": o.entry.direction,
                "ugr": g.ugr,
                "background_cd_m2": g.background_cd_m2,
                "glare_sum": g.glare_sum,
                "luminaires": g.luminaires,
            })
        })
        .collect();
    for (o, g) in scene.observers.iter().zip(&glare) {
        println!(
            "observer {:<15} UGR {:>5}  (L_b {:.1} cd/m², {} luminaire(s) in the field)",
            printable(&o.entry.name),
            g.ugr.map_or("—".into(), |u| format!("{u:.1}")),
            g.background_cd_m2,
            g.luminaires.len()
        );
    }
    let doc = json!({
        "scene": args.scene.display().to_string(),
        "interp": args.interp.name().to_string(),
        "shadows": format!("{:?}", args.shadows).to_lowercase(),
        "device": if args.cpu { "cpu" } else { "gpu" },
        "indirect": indirect,
        "convergence": convergence,
        "grids": grids_json,
        "observers": observers_json,
    });
    let text = serde_json::to_string_pretty(&doc).map_err(CliError::failure)?;
    write_atomic(&staging.dir().join("calc.json"), text.as_bytes()).map_err(CliError::failure)?;
    let mut report = None;
    if let Some(path) = &args.report {
        let settings = [
            ("scene", args.scene.display().to_string()),
            ("maintenance factor", mf.to_string()),
            (
                "light",
                format!(
                    "{}; {}",
                    light.join(" "),
                    match (args.shadows, args.cpu) {
                        (ShadowTechnique::None, _) => "no shadows",
                        (ShadowTechnique::Paraboloid, false) => "paraboloid shadow maps",
                        _ => "exact shadows (a ray from each point to each luminaire)",
                    }
                ),
            ),
            ("interpolation", args.interp.name().to_string()),
            (
                "computed on",
                if args.cpu { "CPU" } else { "GPU" }.to_string(),
            ),
        ];
        let observers: Vec<ReportObserver> = scene
            .observers
            .iter()
            .zip(&glare)
            .map(|(o, g)| ReportObserver {
                name: &o.entry.name,
                eye: o.eye,
                forward: o.forward,
                glare: g,
            })
            .collect();
        report = Some((
            path,
            report_html(&scene, &settings, &report_grids, &observers),
        ));
    }
    // Complete or none: the last chance for Ctrl-C to leave nothing.
    interrupted(&cancel)?;
    staging
        .commit()
        .map_err(|e| CliError::failure(anyhow!("{}: {e:#}", args.out.display())))?;
    if let Some((path, html)) = report {
        write_atomic(path, html.as_bytes())
            .map_err(|e| CliError::input(anyhow!("--report {}: {e:#}", path.display())))?;
    }
    println!(
        "maintenance factor {mf}; {}; wrote {} and, per grid, a CSV and a plan (PNG, SVG); {} grid(s), {} observer(s)",
        light.join(" "),
        args.out.join("calc.json").display(),
        computed.len(),
        glare.len()
    );
    Ok(())
}

/// The error of a run stopped by Ctrl-C (or SIGTERM) before its outputs were written.
fn interrupted(cancel: &std::sync::atomic::AtomicBool) -> Result<(), CliError> {
    if cancel.load(std::sync::atomic::Ordering::SeqCst) {
        return Err(CliError::failure(anyhow!("interrupted: nothing written")));
    }
    Ok(())
}

/// An error naming the grid and point when a computed illuminance is not a usable number.
fn check_usable(grid: &str, lux: &[f64]) -> Result<(), CliError> {
    if let Some((i, v)) = lux
        .iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite() || **v < -1e-6)
    {
        return Err(CliError::failure(anyhow!(
            "grid {grid:?}, point {}: the computed illuminance {v} lx is not a usable number",
            i + 1
        )));
    }
    Ok(())
}

/// The interreflected illuminance at `points` from a radiosity solution of `scene` with
/// the command's solver options (the luminaires' light on the elements with its shadows and
/// interpolation), and the solution's convergence.
fn interreflected_lux(
    args: &CalcArgs,
    scene: &Scene,
    points: &[SurfacePoint],
    started: std::time::Instant,
) -> Result<(Vec<f64>, f64), CliError> {
    let mut settings = crate::render::RenderSettings::from_display(&scene.display);
    settings.light_model = crate::render::LightModel::Ldt(args.interp);
    settings.shadows = ShadowSettings::with(args.shadows);
    let options = args.solver.check()?;
    let solved = super::radiosity::solve(&args.scene, scene, &options, &mut settings, started)?;
    if solved.stop() == crate::radiosity::solve::StopReason::Cancelled {
        return Err(CliError::failure(anyhow!(
            "interrupted while solving the interreflected light: nothing written"
        )));
    }
    let lux = super::radiosity::interreflected_lux(&args.scene, &solved, points)?;
    Ok((lux, solved.convergence()))
}

/// Writes each grid's CSV and plans; returns their `calc.json` entries and report parts.
fn write_grids<'a>(
    args: &CalcArgs,
    dir: &std::path::Path,
    scene: &'a Scene,
    computed: &[Computed<'a>],
    glare: &[ObserverGlare],
    lit: Lit,
) -> Result<(Vec<serde_json::Value>, Vec<ReportGrid<'a>>), CliError> {
    let Lit { mf, light, total } = lit;
    let mut grids_json = Vec::new();
    let mut report_grids = Vec::new();
    if !computed.is_empty() {
        println!(
            "{:<24} {:>15} {:>7} {:>9} {:>9} {:>9} {:>6} {:>6}",
            "grid", "kind", "points", "Em lx", "Emin lx", "Emax lx", "U0", "g2"
        );
    }
    for Computed { grid: g, values } in computed {
        let s = grid_stats(values);
        let csv = csv_name(&g.entry.name);
        write_atomic(&dir.join(&csv), grid_csv(g, values).as_bytes()).map_err(CliError::failure)?;
        let plan = Plan {
            grid: g,
            values,
            stats: s,
            maintenance_factor: mf,
            luminaires: scene
                .luminaires
                .iter()
                .enumerate()
                .map(|(i, l)| (l.position, format!("L{}", i + 1)))
                .collect(),
            observers: scene
                .observers
                .iter()
                .zip(glare)
                .map(|(o, gl)| {
                    let ugr = gl.ugr.map_or("—".into(), |u| format!("{u:.1}"));
                    (o.eye, o.forward, format!("{} UGR {ugr}", o.entry.name))
                })
                .collect(),
            light: light.to_vec(),
            palette: (
                args.palette.or(scene.display.palette).unwrap_or_default(),
                args.steps.or(scene.display.steps).unwrap_or(0),
            ),
            values_at_points: args.values,
        };
        let stem = csv.trim_end_matches(".csv");
        let png = plan.png().map_err(|e| CliError::failure(anyhow!(e)))?;
        write_atomic(&dir.join(format!("{stem}.png")), &png).map_err(CliError::failure)?;
        let svg = plan.svg().map_err(|e| CliError::failure(anyhow!(e)))?;
        write_atomic(&dir.join(format!("{stem}.svg")), svg.as_bytes())
            .map_err(CliError::failure)?;
        report_grids.push(ReportGrid {
            name: &g.entry.name,
            kind: format!("{:?}", g.entry.kind).to_lowercase(),
            stats: s,
            plan_svg: svg,
        });
        println!(
            "{:<24} {:>15} {:>7} {:>9.1} {:>9.1} {:>9.1} {:>6.2} {:>6.2}",
            printable(&g.entry.name),
            format!("{:?}", g.entry.kind).to_lowercase(),
            s.points,
            s.em,
            s.emin,
            s.emax,
            s.u0,
            s.g2
        );
        grids_json.push(json!({
            "name": g.entry.name,
            "kind": g.entry.kind,
            "points": s.points,
            "em": s.em,
            "emin": s.emin,
            "emax": s.emax,
            "u0": s.u0,
            "g2": s.g2,
            "maintenance_factor": mf,
            "indirect": total,
            "spacing_m": g.spacing,
            "plans": [csv.replace(".csv", ".png"), csv.replace(".csv", ".svg")],
            "csv": csv,
        }));
    }
    Ok((grids_json, report_grids))
}

/// `x,y,z,lux` with a header, one row per point (coordinates exact, so the points can be
/// fed back to `illuminance`).
fn grid_csv(g: &CalcGrid, values: &[f64]) -> String {
    let mut out = String::from("x,y,z,lux\n");
    for (p, v) in g.points.iter().zip(values) {
        out.push_str(&format!("{},{},{},{v:.6}\n", p.x, p.y, p.z));
    }
    out
}
