//! `goniolight sunlight`: the planning tests of a scene's `[[window]]`s and
//! `[[open_space]]`s (BRE 209 VSC, APSH/WPSH and gardens; EN 17037 sunlight exposure),
//! before and after with `--baseline`.

use std::path::PathBuf;

use anyhow::anyhow;
use chrono::NaiveDate;
use clap::Args;

use super::error::CliError;
use super::scene_input::load_scene;
use crate::calc::compute::csv_name;
use crate::io::outputs::{OutputCheck, Staging};
use crate::io::{printable, write_atomic};
use crate::planning::output::{open_space_csv, sunlight_json, window_rows, windows_csv};
use crate::planning::plan::site_plan_svg;
use crate::planning::report::report_html;
use crate::planning::verdicts::en17037_level;
use crate::planning::{
    add_areas_file, add_points_file, assess, PlanningError, SunlightOptions, SunlightRequest,
    DEFAULT_STEP_MIN,
};

/// Options of `sunlight`.
#[derive(Debug, Args)]
pub struct SunlightArgs {
    /// The scene file (TOML) with `[site]`, `[[window]]`s and/or `[[open_space]]`s.
    pub scene: PathBuf,
    /// Output folder: sunlight.json, windows.csv, one CSV per open space, plan.svg,
    /// report.html.
    #[arg(long)]
    pub out: PathBuf,
    /// More window reference points: a `profile --points` file (`[[point]]` tables with
    /// name, position, normal).
    #[arg(long)]
    pub points: Option<PathBuf>,
    /// More open spaces: analysis areas as `profile --areas` takes them (GeoJSON Polygon
    /// and MultiPolygon features named by `properties.name`), on the ground at z = 0.
    #[arg(long, value_name = "FILE.geojson")]
    pub areas: Option<PathBuf>,
    /// Metres between the points of the --areas.
    #[arg(long, default_value_t = crate::scene::planning::DEFAULT_OPEN_SPACE_SPACING)]
    pub area_spacing: f64,
    /// An EPW weather file for the probable sunlight hours (APSH, WPSH).
    #[arg(long)]
    pub weather: Option<PathBuf>,
    /// The scene of the existing situation: its model replaces the scene's for the
    /// before figures (same windows and open spaces).
    #[arg(long)]
    pub baseline: Option<PathBuf>,
    /// The day of the gardens' 2-hour test (default: 21 March of --year).
    #[arg(long)]
    pub date: Option<NaiveDate>,
    /// The day of EN 17037's sunlight exposure, 1 February … 21 March (default: 21 March
    /// of --year).
    #[arg(long)]
    pub en17037_date: Option<NaiveDate>,
    /// The year of the default days (default: this year).
    #[arg(long)]
    pub year: Option<i32>,
    /// Minutes between the suns of a day.
    #[arg(long, default_value_t = DEFAULT_STEP_MIN)]
    pub step: f64,
    /// EN 17037's minimum solar altitude for the site, degrees (lower suns do not count
    /// at windows).
    #[arg(long, default_value_t = 0.0)]
    pub min_elevation: f64,
}

impl SunlightArgs {
    /// The library's request.
    fn request(&self) -> SunlightRequest<'_> {
        SunlightRequest {
            weather: self.weather.as_deref(),
            date: self.date,
            en17037_date: self.en17037_date,
            year: self.year,
            step_min: Some(self.step),
            min_elevation_deg: Some(self.min_elevation),
        }
    }
}

/// A library error as the command line's: option keys become flags.
fn planning_error(e: PlanningError) -> CliError {
    match e {
        PlanningError::Cancelled => CliError::failure(anyhow!("interrupted: nothing written")),
        PlanningError::Input { key, message } => {
            let flag = match key.as_str() {
                "step" | "year" | "weather" | "points" | "areas" => format!("--{key}"),
                "min_elevation" => "--min-elevation".to_string(),
                "date" => "--date/--en17037-date".to_string(),
                _ => key,
            };
            CliError::input(anyhow!("{flag}: {message}"))
        }
    }
}

/// Runs `sunlight`.
pub fn run(args: SunlightArgs) -> Result<(), CliError> {
    let mut scene = load_scene(&args.scene)?;
    if let Some(points) = &args.points {
        add_points_file(&mut scene, points).map_err(planning_error)?;
    }
    if let Some(areas) = &args.areas {
        add_areas_file(&mut scene, areas, args.area_spacing).map_err(planning_error)?;
    }
    let baseline = args.baseline.as_deref().map(load_scene).transpose()?;
    let (options, warnings) =
        SunlightOptions::from_request(&args.request()).map_err(planning_error)?;
    for w in warnings {
        eprintln!("warning: {w}");
    }
    let mut inputs = scene.input_files();
    inputs.extend(baseline.iter().flat_map(|b| b.input_files()));
    inputs.extend(args.weather.iter().cloned());
    inputs.extend(args.points.iter().cloned());
    inputs.extend(args.areas.iter().cloned());
    check_outputs(&args, &scene, &inputs)?;
    let cancel = super::interrupt::interrupt_flag();
    let assessment = assess(&scene, baseline.as_ref(), &options, &cancel).map_err(|e| match e {
        PlanningError::Input { key, message } if !key.starts_with("--") && scene_key(&key) => {
            CliError::input(anyhow!("{}: {key}: {message}", args.scene.display()))
        }
        other => planning_error(other),
    })?;
    for w in &assessment.warnings {
        eprintln!("warning: {w}");
    }
    let label = args.scene.display().to_string();
    let baseline_label = args.baseline.as_ref().map(|b| b.display().to_string());
    let rows = window_rows(&scene, &assessment);
    let json = sunlight_json(
        &scene,
        &assessment,
        &rows,
        &label,
        baseline_label.as_deref(),
    );
    let title = format!("Sunlight and skylight — {label}");
    let svg = site_plan_svg(&scene, &assessment.proposed, &rows, &title);
    let html = report_html(&scene, &assessment, &rows, &svg, &title, &json["method"]);
    let staging = Staging::beside(&args.out, &inputs)
        .map_err(|e| CliError::failure(anyhow!("{}: {e}", args.out.display())))?;
    let dir = staging.dir();
    let write =
        |name: &str, bytes: &[u8]| write_atomic(&dir.join(name), bytes).map_err(CliError::failure);
    write(
        "sunlight.json",
        serde_json::to_string_pretty(&json)
            .map_err(CliError::failure)?
            .as_bytes(),
    )?;
    if !rows.is_empty() {
        write("windows.csv", windows_csv(&rows).as_bytes())?;
    }
    for (k, o) in scene.planning.open_spaces.iter().enumerate() {
        let former = assessment
            .baseline
            .as_ref()
            .map(|b| b.open_spaces[k].hours.as_slice());
        let csv = open_space_csv(
            &o.grid.points,
            &assessment.proposed.open_spaces[k].hours,
            former,
        );
        write(&open_space_file(&o.entry.name), csv.as_bytes())?;
    }
    write("plan.svg", svg.as_bytes())?;
    write("report.html", html.as_bytes())?;
    if cancel.load(std::sync::atomic::Ordering::Relaxed) {
        return Err(planning_error(PlanningError::Cancelled));
    }
    staging
        .commit()
        .map_err(|e| CliError::failure(anyhow!("{}: {e:#}", args.out.display())))?;
    print_summary(&rows, &json);
    println!("wrote {}", args.out.join("sunlight.json").display());
    Ok(())
}

/// Whether a library key names the scene file's keys (rather than an option).
fn scene_key(key: &str) -> bool {
    key.starts_with("site") || key.starts_with("window") || key.starts_with("open_space")
}

/// The CSV of an open space's hours.
fn open_space_file(name: &str) -> String {
    format!("open-space-{}", csv_name(name))
}

/// Refuses outputs that would replace an input, before any work.
fn check_outputs(
    args: &SunlightArgs,
    scene: &crate::scene::Scene,
    inputs: &[PathBuf],
) -> Result<(), CliError> {
    if args.out.is_file() {
        return Err(CliError::input(anyhow!(
            "--out {}: is a file, not a folder",
            args.out.display()
        )));
    }
    let mut outputs = OutputCheck::new();
    for f in inputs {
        outputs.input(f);
    }
    for name in ["sunlight.json", "windows.csv", "plan.svg", "report.html"] {
        outputs.output(args.out.join(name));
    }
    for o in &scene.planning.open_spaces {
        outputs.output(args.out.join(open_space_file(&o.entry.name)));
    }
    outputs.check().map_err(|e| CliError::input(anyhow!("{e}")))
}

/// One line per window and per open space on stdout.
fn print_summary(rows: &[crate::planning::output::WindowRow], json: &serde_json::Value) {
    let word = |p: Option<bool>| match p {
        Some(true) => "pass",
        Some(false) => "FAIL",
        None => "—",
    };
    if !rows.is_empty() {
        println!(
            "{:<24} {:>7} {:>5} {:>7} {:>7} {:>9} {:>6} {:>9} {:>8}",
            "window", "VSC %", "", "APSH %", "WPSH %", "sunlight", "EN h", "level", "EN 17037"
        );
    }
    for r in rows {
        let opt = |v: Option<f64>| v.map_or("—".into(), |v| format!("{v:.1}"));
        println!(
            "{:<24} {:>7.1} {:>5} {:>7} {:>7} {:>9} {:>6.2} {:>9} {:>8}",
            printable(&r.window.entry.name),
            r.now.vsc,
            word(Some(r.verdict.vsc)),
            opt(r.now.apsh),
            opt(r.now.wpsh),
            word(r.verdict.sunlight),
            r.now.en17037_hours,
            en17037_level(r.now.en17037_hours),
            word(Some(r.verdict.en17037)),
        );
    }
    for a in json["areas"].as_array().into_iter().flatten() {
        println!(
            "open space {:<24} {:>5.1} % with ≥ 2 h of sun  {}",
            printable(a["name"].as_str().unwrap_or("")),
            a["sunlit_fraction_2h"].as_f64().unwrap_or(0.0) * 100.0,
            word(a["pass"].as_bool())
        );
    }
}
