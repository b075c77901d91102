//! `calc`: the scene's calculation surfaces — per grid the illuminance at every point,
//! maintained (times the maintenance factor), its statistics in `calc.json`, the points
//! in one CSV per grid and its plan (PNG and SVG). The calculation is the library's
//! ([`crate::calc::compute`]); this parses, checks the outputs, shows progress and
//! writes.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::anyhow;
use clap::Args;

use super::error::flags_in;
use super::error::CliError;
use super::scene_input::{load_scene, scene_at};
use super::solver_args::SolverArgs;
use crate::calc::compute::{csv_name, df_plan_name, CalcError, CalcOptions, Calculation, Request};
use crate::calc::plan_dxf::plan_dxf;
use crate::calc::report::{report_html, ReportGrid, ReportObserver};
use crate::gpu::Gpu;
use crate::io::limits::MAX_TOTAL_POINTS;
use crate::io::outputs::{OutputCheck, Staging};
use crate::io::{printable, write_atomic};
use crate::photometry::Interp;
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
    /// Also write each plan as DXF (R12, metres) for CAD: NAME.dxf (and NAME-df.dxf with
    /// a daylight factor) with the outline, the isolux lines and their values, the value
    /// at every point and the luminaires, each on its layer.
    #[arg(long)]
    pub dxf: bool,
    /// Also write one self-contained HTML page: settings, luminaires, each grid's
    /// statistics and plan (its folder must exist, or be the --out folder).
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
    /// Direct light only, or total light (direct + interreflected, through the radiosity
    /// solver). UGR at `[[observer]]`s needs the interreflected light (the background
    /// luminance): `radiosity`. Default: the scene's `calc.indirect`, else none.
    #[arg(long, value_enum)]
    pub indirect: Option<Indirect>,
    /// Emergency lighting (EN 1838): the luminaires with an emergency output
    /// (`emergency_flux_lm`, `ballast_lumen_factor`) at it, the others dark, direct light
    /// only; the scene's `[[emergency]]` areas judged in place of its grids and areas.
    #[arg(long, conflicts_with = "indirect")]
    pub emergency: bool,
    /// The most points over all grids together (each costs memory and about 100 bytes
    /// of files); a run above it is refused before any work.
    #[arg(long, value_name = "N", default_value_t = MAX_TOTAL_POINTS)]
    pub max_points: usize,
    /// The radiosity solver's options (with `--indirect radiosity`).
    #[command(flatten, next_help_heading = "Radiosity (with --indirect radiosity)")]
    pub solver: SolverArgs,
}

impl CalcArgs {
    /// The library's options these flags give.
    pub fn options(&self) -> Result<CalcOptions, CliError> {
        Ok(CalcOptions {
            maintenance_factor: self.maintenance_factor,
            cpu: self.cpu,
            interp: self.interp,
            shadows: self.shadows,
            indirect: self.indirect,
            max_points: self.max_points,
            radiosity: self.solver.check()?,
        })
    }
}

/// A calculation's error as the command reports it: the library names its options'
/// fields, the command its flags.
fn calc_error(e: CalcError) -> CliError {
    match e {
        CalcError::Option { field, message } => {
            let flag = super::error::flag_of(field);
            let flag = match flag.starts_with("--") {
                true => flag.to_string(),
                false => format!("--{}", field.replace('_', "-")),
            };
            CliError::input(anyhow!("{flag} {}", flags_in(&message)))
        }
        CalcError::Radiosity(e) => e.into(),
        CalcError::Gpu(e) => e.into(),
        e => {
            let bad = e.is_bad_input();
            CliError::classified(anyhow!(flags_in(&e.to_string())), bad)
        }
    }
}

/// The files of the run: `calc.json` and per grid its CSV and plans (PNG, SVG), refused
/// before any work where one would replace an input or another output.
fn check_outputs(args: &CalcArgs, scene: &Scene) -> Result<(), CliError> {
    if args.out.is_file() {
        return Err(CliError::input(anyhow!(
            "--out {}: is a file, not a folder",
            args.out.display()
        )));
    }
    let mut outputs = OutputCheck::new();
    for f in &scene.input_files() {
        outputs.input(f);
    }
    outputs.output(args.out.join("calc.json"));
    let factor = crate::calc::daylight::has_daylight_factor(scene);
    for g in &scene.grids {
        let csv = csv_name(&g.entry.name);
        let stem = csv.trim_end_matches(".csv");
        for name in [csv.clone(), format!("{stem}.png"), format!("{stem}.svg")] {
            outputs.output(args.out.join(name));
        }
        if args.dxf {
            outputs.output(args.out.join(format!("{stem}.dxf")));
        }
        if factor {
            let exts = if args.dxf {
                &["png", "svg", "dxf"][..]
            } else {
                &["png", "svg"][..]
            };
            for ext in exts {
                outputs.output(args.out.join(df_plan_name(&csv, ext)));
            }
        }
    }
    if let Some(report) = &args.report {
        outputs.named_output(&format!("--report {}", report.display()), report);
        // The report may go into the --out folder, which the run makes.
        if report.parent() != Some(args.out.as_path()) {
            super::args::check_folder_of(report, "--report")?;
        }
    }
    outputs.check()?;
    Ok(())
}

/// Runs `calc`.
pub fn run(args: CalcArgs) -> Result<(), CliError> {
    let started = std::time::Instant::now();
    let scene = scene_at(load_scene(&args.scene)?, args.time)?;
    let scene = match args.emergency {
        true => scene.in_emergency()?,
        false => scene,
    };
    let options = args.options()?;
    let request = Request::new(&scene, &options).map_err(calc_error)?;
    check_outputs(&args, &scene)?;
    let cancel = super::interrupt::interrupt_flag();
    let gpu = if args.cpu { None } else { Some(Gpu::shared()?) };
    let daylight = request.daylight();
    let (direct, interreflected) = light_of(&args, &request, gpu.as_ref(), started)?;
    let mut calc = request.finish(direct, interreflected).map_err(calc_error)?;
    if let Some(day) = daylight {
        eprintln!("daylight: the scene's [sky] alone");
        let (direct, interreflected) = light_of(&args, &day, gpu.as_ref(), started)?;
        calc.add_daylight(
            day.finish_daylight(direct, interreflected)
                .map_err(calc_error)?,
        );
    }
    for w in &calc.warnings {
        super::scene_input::warn_once(&scene.path, w);
    }
    interrupted(&cancel)?;
    let inputs = scene.input_files();
    let staging = Staging::beside(&args.out, &inputs)
        .map_err(|e| CliError::failure(anyhow!("{}: {e}", args.out.display())))?;
    let report_grids = write_grids(&args, staging.dir(), &calc)?;
    for (o, g) in scene.observers.iter().zip(&calc.glare) {
        println!(
            "observer {:<15} UGR {:>5}  (L_b {:.1} cd/m², {} luminaire(s) in the field)",
            printable(&o.entry.name),
            g.ugr.map_or("—".into(), |u| format!("{u:.1}")),
            g.background_cd_m2,
            g.luminaires.len()
        );
    }
    print_verdicts(&calc.requirements);
    let label = args.scene.display().to_string();
    let text = serde_json::to_string_pretty(&calc.json(&label)).map_err(CliError::failure)?;
    write_atomic(&staging.dir().join("calc.json"), text.as_bytes()).map_err(CliError::failure)?;
    let report = args.report.as_ref().map(|path| {
        let observers: Vec<ReportObserver> = scene
            .observers
            .iter()
            .zip(&calc.glare)
            .map(|(o, g)| ReportObserver {
                name: &o.entry.name,
                eye: o.eye,
                forward: o.forward,
                glare: g,
            })
            .collect();
        let settings = calc.report_settings(&label);
        (
            path,
            report_html(
                &scene,
                &settings,
                &report_grids,
                &observers,
                &calc.requirements,
            ),
        )
    });
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
        "maintenance factor {}; {}; wrote {} and, per grid, a CSV and a plan (PNG, SVG{}); {} grid(s), {} observer(s)",
        calc.maintenance_factor,
        calc.light.join(" "),
        args.out.join("calc.json").display(),
        if args.dxf { ", DXF" } else { "" },
        calc.grids.len(),
        calc.glare.len()
    );
    Ok(())
}

/// Prints the verification of the areas: one line per requirement.
fn print_verdicts(verdicts: &[crate::calc::requirements::Verdict]) {
    if verdicts.is_empty() {
        return;
    }
    println!(
        "{:<20} {:<12} {:<8} {:>12} {:>14}  result",
        "area", "part", "quantity", "required", "achieved"
    );
    for v in verdicts {
        println!(
            "{:<20} {:<12} {:<8} {:>12} {:>14}  {}{}",
            printable(&v.area),
            v.part.label(),
            v.quantity.name(),
            v.limit_text(),
            v.achieved_text(),
            v.outcome(),
            v.note.as_ref().map_or(String::new(), |n| format!(" ({n})"))
        );
    }
}

/// The error of a run stopped by Ctrl-C (or SIGTERM) before its outputs were written.
fn interrupted(cancel: &AtomicBool) -> Result<(), CliError> {
    if cancel.load(Ordering::SeqCst) {
        return Err(calc_error(CalcError::Cancelled));
    }
    Ok(())
}

/// The direct light of `request` and, where it solves, the interreflected light at its
/// gather points with the solution's convergence.
fn light_of(
    args: &CalcArgs,
    request: &Request,
    gpu: Option<&Gpu>,
    started: std::time::Instant,
) -> Result<(crate::calc::compute::Direct, crate::calc::compute::Gathered), CliError> {
    let cancel = super::interrupt::interrupt_flag();
    let direct = request.direct(gpu, &cancel).map_err(calc_error)?;
    let interreflected = match request.solves() {
        true => Some(interreflected_lux(args, request, started)?),
        false => request.unlit_interreflection(),
    };
    Ok((direct, interreflected))
}

/// The interreflected illuminance at the request's gather points from a radiosity
/// solution of what lights it with the command's solver options (the light on the
/// elements with its shadows and interpolation), and the solution's convergence.
fn interreflected_lux(
    args: &CalcArgs,
    request: &Request,
    started: std::time::Instant,
) -> Result<(Vec<f64>, f64), CliError> {
    let scene = request.lighting_scene();
    let mut settings = crate::render::RenderSettings::from_display(&scene.display);
    settings.light_model = crate::render::LightModel::Ldt(args.interp);
    settings.shadows = ShadowSettings::with(args.shadows);
    let options = args.solver.check()?;
    let solved = super::solving::solve(&args.scene, scene, &options, &mut settings, started)?;
    if solved.stop() == crate::radiosity::solve::StopReason::Cancelled {
        return Err(CliError::failure(anyhow!(
            "interrupted while solving the interreflected light: nothing written"
        )));
    }
    let points = request.gather_points();
    let lux = super::solving::gathered_lux(&args.scene, &solved, &points, false)?;
    Ok((lux, solved.convergence()))
}

/// Writes each grid's CSV and plans and prints its line; returns the report's parts.
fn write_grids<'c>(
    args: &CalcArgs,
    dir: &Path,
    calc: &'c Calculation,
) -> Result<Vec<ReportGrid<'c>>, CliError> {
    let mut report_grids = Vec::new();
    if !calc.grids.is_empty() {
        println!(
            "{:<24} {:>15} {:>7} {:>9} {:>9} {:>9} {:>6} {:>6}",
            "grid", "kind", "points", "Em lx", "Emin lx", "Emax lx", "U0", "g2"
        );
    }
    for (k, (g, r)) in calc.grid_results().enumerate() {
        let s = r.stats;
        let csv = csv_name(&g.entry.name);
        write_atomic(&dir.join(&csv), calc.grid_csv(k).as_bytes()).map_err(CliError::failure)?;
        let plan = calc.plan(k, args.palette, args.steps, args.values);
        let stem = csv.trim_end_matches(".csv");
        let png = plan.png().map_err(CliError::failure)?;
        write_atomic(&dir.join(format!("{stem}.png")), &png).map_err(CliError::failure)?;
        let svg = plan.svg().map_err(CliError::failure)?;
        write_atomic(&dir.join(format!("{stem}.svg")), svg.as_bytes())
            .map_err(CliError::failure)?;
        if args.dxf {
            let dxf = plan_dxf(&plan).map_err(CliError::failure)?;
            write_atomic(&dir.join(format!("{stem}.dxf")), dxf.as_bytes())
                .map_err(CliError::failure)?;
        }
        let mut daylight_factor = None;
        if let Some(df) = calc.df_plan(k, args.palette, args.steps, args.values) {
            let png = df.png().map_err(CliError::failure)?;
            write_atomic(&dir.join(df_plan_name(&csv, "png")), &png).map_err(CliError::failure)?;
            let svg = df.svg().map_err(CliError::failure)?;
            write_atomic(&dir.join(df_plan_name(&csv, "svg")), svg.as_bytes())
                .map_err(CliError::failure)?;
            if args.dxf {
                let dxf = plan_dxf(&df).map_err(CliError::failure)?;
                write_atomic(&dir.join(df_plan_name(&csv, "dxf")), dxf.as_bytes())
                    .map_err(CliError::failure)?;
            }
            daylight_factor = df.daylight_factor.map(|f| (f, svg));
        }
        let kind = format!("{:?}", g.entry.kind).to_lowercase();
        println!(
            "{:<24} {:>15} {:>7} {:>9.1} {:>9.1} {:>9.1} {:>6.2} {:>6.2}",
            printable(&g.entry.name),
            kind,
            s.points,
            s.em,
            s.emin,
            s.emax,
            s.u0,
            s.g2
        );
        if let Some((f, _)) = &daylight_factor {
            println!(
                "{:<24} daylight factor: mean {:.2} %, median {:.2} %, min {:.2} %, max {:.2} %, U0 {:.2}",
                "", f.mean, f.median, f.min, f.max, f.u0
            );
        }
        report_grids.push(ReportGrid {
            name: &g.entry.name,
            kind,
            stats: s,
            plan_svg: svg,
            daylight_factor,
        });
    }
    Ok(report_grids)
}
