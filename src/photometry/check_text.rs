//! The text of `ldt check`'s reports: one file's table, a catalogue's table with its
//! summary (median, worst and wins per method), the catalogue as CSV and as JSON. The
//! command prints these strings; the figures and their layout are made here.

use std::path::{Path, PathBuf};

use serde_json::json;

use super::catalogue::{summarise, CatalogueSummary, Metric};
use super::check::{method_key, CheckReport};
use super::grid::Interp;
use super::info::csv_line;

/// Appends `line` and a newline.
fn push_line(out: &mut String, line: String) {
    out.push_str(&line);
    out.push('\n');
}

/// The catalogue as CSV: one row per file and method (`ldt check --csv`).
pub fn catalogue_csv(reports: &[(PathBuf, CheckReport)]) -> String {
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
    out
}

/// The summary over the catalogue's reports.
pub fn summary_of(reports: &[(PathBuf, CheckReport)]) -> CatalogueSummary {
    let refs: Vec<&CheckReport> = reports.iter().map(|(_, r)| r).collect();
    summarise(&refs)
}

/// `{"files": [{"path", "report"}], "errors": [...], "summary": {...}}`; each `report` is
/// what `ldt check --json` prints for that file alone; `errors` are the files that could
/// not be checked.
pub fn catalogue_json(reports: &[(PathBuf, CheckReport)], errors: &[String]) -> serde_json::Value {
    let files: Vec<serde_json::Value> = reports
        .iter()
        .map(|(path, r)| json!({"path": path.display().to_string(), "report": r}))
        .collect();
    json!({"files": files, "errors": errors, "summary": summary_of(reports)})
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

/// The catalogue table (the best method of each group marked with `*`) and the summary:
/// median, worst and files won per metric and method (`ldt check` on many files).
pub fn catalogue_table(reports: &[(PathBuf, CheckReport)]) -> String {
    let mut out = String::new();
    let methods: Vec<&str> = Interp::ALL.iter().map(|&i| method_key(i)).collect();
    let short = ["nearest", "bilinear", "catmull", "monotone"];
    let group = CELL * methods.len() + 2;
    let base = common_folder(reports.iter().map(|(p, _)| p.as_path()));
    if let Some((_, first)) = reports.first() {
        push_line(
            &mut out,
            format!(
                "{}: {} in {}",
                first.mode,
                files(reports.len()),
                base.display()
            ),
        );
    }
    let mut line = format!("{:<FILE_COLUMN$}", "");
    for (_, heading, _) in TABLE {
        line.push_str(&format!("{heading:<group$}"));
    }
    push_line(&mut out, line.trim_end().to_string());
    let mut line = format!("{:<FILE_COLUMN$}", "file");
    for _ in TABLE {
        for s in short {
            line.push_str(&format!("{s:>CELL$}"));
        }
        line.push_str("  ");
    }
    push_line(&mut out, line.trim_end().to_string());
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
        push_line(&mut out, line.trim_end().to_string());
    }
    let summary = summary_of(reports);
    out.push('\n');
    push_line(
        &mut out,
        format!(
            "summary over {}: median / worst / files won (* above; ties count for each)",
            files(summary.files)
        ),
    );
    let width = 26;
    let mut line = format!("{:<22}", "metric");
    for s in methods.iter() {
        line.push_str(&format!("{s:>width$}"));
    }
    push_line(&mut out, line);
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
        push_line(&mut out, line);
    }
    out
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

/// A check report as a table: the mode and held-out count, one row per method (RMS,
/// maximum absolute and relative error, overshoots, flux error, Hausdorff distance) and the
/// method with the lowest RMS error (`ldt check` on one file).
pub fn check_table(report: &CheckReport) -> String {
    let mut out = String::new();
    push_line(
        &mut out,
        format!(
            "{}: {} values reconstructed (I_max {:.1} cd/klm)",
            report.mode, report.held_out, report.i_max
        ),
    );
    push_line(
        &mut out,
        format!(
            "{:<12} {:>10} {:>10} {:>9} {:>10} {:>12} {:>10} {:>10}",
            "method",
            "rms",
            "max_abs",
            "max_rel",
            "overshoot",
            "overshoot_max",
            "flux_err%",
            "hausdorff"
        ),
    );
    for (name, m) in &report.methods {
        push_line(
            &mut out,
            format!(
                "{:<12} {:>10.3} {:>10.3} {:>8.2}% {:>10} {:>12.3} {:>+10.4} {:>10.3}",
                name,
                m.rms,
                m.max_abs,
                m.max_rel * 100.0,
                m.overshoot_count,
                m.overshoot_max,
                m.flux_error_percent,
                m.hausdorff
            ),
        );
    }
    if let Some(best) = report.best_by_rms() {
        push_line(&mut out, format!("lowest RMS error: {best}"));
    }
    out
}
