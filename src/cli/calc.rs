//! `calc`: the scene's calculation surfaces — per grid the illuminance at every point,
//! maintained (times the maintenance factor), its statistics in `calc.json`, the points
//! in one CSV per grid and its plan (PNG and SVG).

use std::path::PathBuf;

use anyhow::anyhow;
use clap::Args;
use serde_json::json;

use super::calc_report::{report_html, ReportGrid};
use super::render::scene_at;
use super::CliError;
use crate::calc::directions::{combine, surface_points};
use crate::calc::plan::Plan;
use crate::calc::{grid_stats, CalcGrid, CalcSettings};
use crate::gpu::Gpu;
use crate::io::write_atomic;
use crate::photometry::Interp;
use crate::render::illuminance::scene_illuminance;
use crate::render::ShadowTechnique;
use crate::scene::Scene;

/// Options of `calc`.
#[derive(Debug, Args)]
pub struct CalcArgs {
    /// The scene file (TOML) with its `[[grid]]` calculation surfaces.
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
    /// statistics and plan.
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
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

/// Runs `calc`.
pub fn run(args: CalcArgs) -> Result<(), CliError> {
    let scene = scene_at(Scene::load(&args.scene)?, args.time)?;
    if scene.grids.is_empty() {
        return Err(CliError::input(anyhow!(
            "{}: no [[grid]] to compute; add a calculation surface (README: \"Lighting calculations\")",
            args.scene.display()
        )));
    }
    let mf = CalcSettings::check(
        args.maintenance_factor
            .unwrap_or(scene.calc.maintenance_factor),
    )
    .map_err(|e| CliError::input(anyhow!("--maintenance-factor {e}")))?;
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
    let gpu = if args.cpu { None } else { Some(Gpu::shared()?) };
    let mut computed = Vec::new();
    for g in &scene.grids {
        let points = surface_points(g);
        let lux = scene_illuminance(gpu.as_ref(), &scene, &points, args.interp, args.shadows)?;
        if let Some((i, v)) = lux
            .iter()
            .enumerate()
            .find(|(_, v)| !v.is_finite() || **v < -1e-6)
        {
            return Err(CliError::failure(anyhow!(
                "grid {:?}, point {}: the computed illuminance {v} lx is not a usable number",
                g.entry.name,
                i + 1
            )));
        }
        let values: Vec<f64> = combine(g, &lux)
            .into_iter()
            .map(|v| v.max(0.0) * mf)
            .collect();
        computed.push((g, values));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::failure(anyhow!("{}: {e}", args.out.display())))?;
    let mut grids_json = Vec::new();
    let mut report_grids = Vec::new();
    println!(
        "{:<24} {:>15} {:>7} {:>9} {:>9} {:>9} {:>6} {:>6}",
        "grid", "kind", "points", "Em lx", "Emin lx", "Emax lx", "U0", "g2"
    );
    for (g, values) in &computed {
        let s = grid_stats(values);
        let csv = csv_name(&g.entry.name);
        write_atomic(&args.out.join(&csv), grid_csv(g, values).as_bytes())
            .map_err(CliError::failure)?;
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
            palette: (
                args.palette.or(scene.display.palette).unwrap_or_default(),
                args.steps.or(scene.display.steps).unwrap_or(0),
            ),
            values_at_points: args.values,
        };
        let stem = csv.trim_end_matches(".csv");
        let png = plan.png().map_err(|e| CliError::failure(anyhow!(e)))?;
        write_atomic(&args.out.join(format!("{stem}.png")), &png).map_err(CliError::failure)?;
        let svg = plan.svg().map_err(|e| CliError::failure(anyhow!(e)))?;
        write_atomic(&args.out.join(format!("{stem}.svg")), svg.as_bytes())
            .map_err(CliError::failure)?;
        report_grids.push(ReportGrid {
            name: &g.entry.name,
            kind: format!("{:?}", g.entry.kind).to_lowercase(),
            stats: s,
            plan_svg: svg,
        });
        println!(
            "{:<24} {:>15} {:>7} {:>9.1} {:>9.1} {:>9.1} {:>6.2} {:>6.2}",
            g.entry.name,
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
            "indirect": false,
            "spacing_m": g.spacing,
            "plans": [csv.replace(".csv", ".png"), csv.replace(".csv", ".svg")],
            "csv": csv,
        }));
    }
    let doc = json!({
        "scene": args.scene.display().to_string(),
        "interp": format!("{:?}", args.interp).to_lowercase(),
        "shadows": format!("{:?}", args.shadows).to_lowercase(),
        "device": if args.cpu { "cpu" } else { "gpu" },
        "grids": grids_json,
    });
    let text = serde_json::to_string_pretty(&doc).map_err(CliError::failure)?;
    write_atomic(&args.out.join("calc.json"), text.as_bytes()).map_err(CliError::failure)?;
    if let Some(path) = &args.report {
        let settings = [
            ("scene", args.scene.display().to_string()),
            ("maintenance factor", mf.to_string()),
            (
                "light",
                match (args.shadows, args.cpu) {
                    (ShadowTechnique::None, _) => "direct, no shadows",
                    (ShadowTechnique::Paraboloid, false) => "direct, paraboloid shadow maps",
                    _ => "direct, exact shadows (a ray from each point to each luminaire)",
                }
                .to_string(),
            ),
            ("interpolation", format!("{:?}", args.interp).to_lowercase()),
            (
                "computed on",
                if args.cpu { "CPU" } else { "GPU" }.to_string(),
            ),
        ];
        let html = report_html(&scene, &settings, &report_grids);
        write_atomic(path, html.as_bytes())
            .map_err(|e| CliError::input(anyhow!("--report {}: {e:#}", path.display())))?;
    }
    println!(
        "maintenance factor {mf}; direct light only; wrote {} and, per grid, a CSV and a plan (PNG, SVG); {} grid(s)",
        args.out.join("calc.json").display(),
        computed.len()
    );
    Ok(())
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
