//! `ldt check` over one file or a catalogue: the single-file report as before; for many
//! files one table (rows: files; columns: each method's figures), a summary over the
//! catalogue (median, worst and wins per method), and per file the residuals written
//! as CSV, an error-vs-γ chart and a heat map.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use serde_json::json;

use super::inputs::{Inputs, OutputNames};
use super::{about, create_dir, load, CheckArgs, CliError};
use crate::io::write_atomic;
use crate::photometry::catalogue::{summarise, CatalogueSummary, Metric};
use crate::photometry::check::{self, method_key, CheckReport};
use crate::photometry::grid::Interp;
use crate::photometry::info::csv_line;
use crate::photometry::residual_plot::{gamma_error_svg, heat_map_png};

/// Runs `ldt check` as `args` asks.
pub(super) fn check(args: &CheckArgs) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(&args.files);
    if args.reference.is_some() && !inputs.single {
        return Err(CliError::input(anyhow!(
            "--reference compares one coarse file with a finer measurement of it; give one file"
        )));
    }
    create_dir("--residuals", args.residuals.as_deref())?;
    let mut names = OutputNames::default();
    let reports = inputs.each(|file| {
        let report = check_one(file, args)?;
        if let Some(dir) = &args.residuals {
            write_residuals(file, &report, dir, &mut names)?;
        }
        Ok(report)
    })?;
    if args.csv {
        print_csv(&reports);
    } else if inputs.single {
        print_check(&reports[0].1, args.json);
    } else if args.json {
        print_catalogue_json(&reports, inputs.errors())?;
    } else {
        print_catalogue(&reports);
    }
    inputs.finish()
}

/// The check of one file.
fn check_one(file: &Path, args: &CheckArgs) -> Result<CheckReport, CliError> {
    let lum = load(file)?;
    let report = if let Some(fine) = &args.reference {
        let fine = load(fine)?;
        check::against_reference(&lum.distribution, &fine.distribution)
    } else if let Some((dc, dg)) = args.downsample {
        check::downsample(&lum.distribution, dc, dg)
    } else {
        check::leave_out(&lum.distribution, args.leave_out)
    };
    report.map_err(|e| about(file, e))
}

/// Writes `STEM.csv`, `STEM-gamma.svg` and `STEM-heatmap.png` of `report` into `dir`.
fn write_residuals(
    file: &Path,
    report: &CheckReport,
    dir: &Path,
    names: &mut OutputNames,
) -> Result<(), CliError> {
    let csv = names.claim(file, Some(dir), "csv")?;
    let stem = csv
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let title = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let svg = gamma_error_svg(report, &title).map_err(|e| CliError::failure(anyhow!(e)))?;
    let png = heat_map_png(report, &title).map_err(|e| CliError::failure(anyhow!(e)))?;
    write_atomic(&csv, report.residuals_csv().as_bytes()).map_err(CliError::failure)?;
    write_atomic(&dir.join(format!("{stem}-gamma.svg")), svg.as_bytes())
        .map_err(CliError::failure)?;
    write_atomic(&dir.join(format!("{stem}-heatmap.png")), &png).map_err(CliError::failure)
}

/// One row per file and method.
fn print_csv(reports: &[(PathBuf, CheckReport)]) {
    let header = [
        "path",
        "mode",
        "held_out",
        "i_max_cd_klm",
        "method",
        "rms",
        "max_abs",
        "max_rel",
        "overshoot_count",
        "overshoot_max",
        "flux_error_percent",
        "hausdorff",
    ];
    let mut out = csv_line(&header);
    for (path, r) in reports {
        for (method, m) in &r.methods {
            out.push_str(&csv_line(&[
                path.display().to_string(),
                r.mode.clone(),
                r.held_out.to_string(),
                r.i_max.to_string(),
                method.clone(),
                m.rms.to_string(),
                m.max_abs.to_string(),
                m.max_rel.to_string(),
                m.overshoot_count.to_string(),
                m.overshoot_max.to_string(),
                m.flux_error_percent.to_string(),
                m.hausdorff.to_string(),
            ]));
        }
    }
    print!("{out}");
}

fn summary_of(reports: &[(PathBuf, CheckReport)]) -> CatalogueSummary {
    let refs: Vec<&CheckReport> = reports.iter().map(|(_, r)| r).collect();
    summarise(&refs)
}

/// `{"files": [{"path", "report"}], "errors": [...], "summary": {...}}`; each `report` is
/// what `ldt check --json` prints for that file alone.
fn print_catalogue_json(
    reports: &[(PathBuf, CheckReport)],
    errors: &[String],
) -> Result<(), CliError> {
    let files: Vec<serde_json::Value> = reports
        .iter()
        .map(|(path, r)| json!({"path": path.display().to_string(), "report": r}))
        .collect();
    let v = json!({"files": files, "errors": errors, "summary": summary_of(reports)});
    println!(
        "{}",
        serde_json::to_string_pretty(&v).map_err(CliError::failure)?
    );
    Ok(())
}

/// How a table prints one metric's value.
type Format = fn(f64) -> String;

/// The metrics of the catalogue table, with their headings and how to print them.
const TABLE: [(Metric, &str, Format); 4] = [
    (Metric::Rms, "RMS (cd/klm)", |v| format!("{v:.3}")),
    (Metric::MaxRel, "max rel (%)", |v| {
        format!("{:.2}", v * 100.0)
    }),
    (Metric::Overshoots, "overshoots", |v| format!("{v:.0}")),
    (Metric::FluxError, "|flux err| (%)", |v| format!("{v:.4}")),
];

const CELL: usize = 9;
const FILE_COLUMN: usize = 26;

/// The catalogue table (the best method of each group marked with `*`) and the summary.
fn print_catalogue(reports: &[(PathBuf, CheckReport)]) {
    let methods: Vec<&str> = Interp::ALL.iter().map(|&i| method_key(i)).collect();
    let short = ["nearest", "bilinear", "catmull", "monotone"];
    let group = CELL * methods.len() + 2;
    let base = common_folder(reports.iter().map(|(p, _)| p.as_path()));
    if let Some((_, first)) = reports.first() {
        println!(
            "{}: {} in {}",
            first.mode,
            files(reports.len()),
            base.display()
        );
    }
    let mut line = format!("{:<FILE_COLUMN$}", "");
    for (_, heading, _) in TABLE {
        line.push_str(&format!("{heading:<group$}"));
    }
    println!("{}", line.trim_end());
    let mut line = format!("{:<FILE_COLUMN$}", "file");
    for _ in TABLE {
        for s in short {
            line.push_str(&format!("{s:>CELL$}"));
        }
        line.push_str("  ");
    }
    println!("{}", line.trim_end());
    for (path, r) in reports {
        let name = path.strip_prefix(&base).unwrap_or(path);
        let mut line = format!("{:<FILE_COLUMN$}", shorten(&name.display().to_string()));
        for (metric, _, fmt) in TABLE {
            let values: Vec<f64> = methods
                .iter()
                .map(|m| metric.of(r, &r.methods[*m]))
                .collect();
            let best = values.iter().cloned().fold(f64::INFINITY, f64::min);
            for v in values {
                let mark = if v <= best { "*" } else { " " };
                line.push_str(&format!("{:>w$}{mark}", fmt(v), w = CELL - 1));
            }
            line.push_str("  ");
        }
        println!("{}", line.trim_end());
    }
    let summary = summary_of(reports);
    println!();
    println!(
        "summary over {}: median / worst / files won (* above; ties count for each)",
        files(summary.files)
    );
    let width = 26;
    let mut line = format!("{:<22}", "metric");
    for s in methods.iter() {
        line.push_str(&format!("{s:>width$}"));
    }
    println!("{line}");
    for metric in Metric::ALL {
        let (label, fmt): (&str, Format) = match metric {
            Metric::RmsPercent => ("RMS (% of I_max)", |v| format!("{v:.3}")),
            _ => TABLE
                .iter()
                .find(|t| t.0 == metric)
                .map_or(("", |v| format!("{v}")), |t| (t.1, t.2)),
        };
        let mut line = format!("{label:<22}");
        for m in &methods {
            let s = &summary.metrics[metric.key()][*m];
            let cell = format!("{} / {} / {}", fmt(s.median), fmt(s.worst), s.wins);
            line.push_str(&format!("{cell:>width$}"));
        }
        println!("{line}");
    }
}

/// "1 file", "2 files".
fn files(n: usize) -> String {
    if n == 1 {
        "1 file".to_string()
    } else {
        format!("{n} files")
    }
}

/// The deepest folder holding every one of `paths`.
fn common_folder<'a>(mut paths: impl Iterator<Item = &'a Path>) -> PathBuf {
    let Some(first) = paths.next() else {
        return PathBuf::new();
    };
    let mut base = first.parent().unwrap_or(Path::new("")).to_path_buf();
    for p in paths {
        while !p.starts_with(&base) {
            if !base.pop() {
                return PathBuf::new();
            }
        }
    }
    base
}

/// A path cut to the file column's width, keeping its end.
fn shorten(path: &str) -> String {
    let n = path.chars().count();
    if n < FILE_COLUMN {
        return path.to_string();
    }
    let tail: String = path.chars().skip(n + 3 - FILE_COLUMN).collect();
    format!("…{tail}")
}

/// Prints a check report as JSON or as a table.
pub(in crate::cli) fn print_check(report: &CheckReport, as_json: bool) {
    if as_json {
        println!(
            "{}",
            serde_json::to_string_pretty(report).expect("report serialises")
        );
        return;
    }
    println!(
        "{}: {} values reconstructed (I_max {:.1} cd/klm)",
        report.mode, report.held_out, report.i_max
    );
    println!(
        "{:<12} {:>10} {:>10} {:>9} {:>10} {:>12} {:>10} {:>10}",
        "method",
        "rms",
        "max_abs",
        "max_rel",
        "overshoot",
        "overshoot_max",
        "flux_err%",
        "hausdorff"
    );
    for (name, m) in &report.methods {
        println!(
            "{:<12} {:>10.3} {:>10.3} {:>8.2}% {:>10} {:>12.3} {:>+10.4} {:>10.3}",
            name,
            m.rms,
            m.max_abs,
            m.max_rel * 100.0,
            m.overshoot_count,
            m.overshoot_max,
            m.flux_error_percent,
            m.hausdorff
        );
    }
    if let Some(best) = report.best_by_rms() {
        println!("lowest RMS error: {best}");
    }
}
