//! `ldt check` over one file or a catalogue: the single-file report as before; for many
//! files one table (rows: files; columns: each method's figures), a summary over the
//! catalogue (median, worst and wins per method), and per file the residuals written
//! as CSV, an error-vs-γ chart and a heat map.

use std::path::Path;

use anyhow::anyhow;

use super::inputs::{Inputs, OutputNames};
use super::{about, create_dir, load, CheckArgs, CliError};
use crate::io::write_atomic;
use crate::photometry::check::{self, CheckReport};
use crate::photometry::check_text;
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
        print!("{}", check_text::catalogue_csv(&reports));
    } else if inputs.single {
        print_check(&reports[0].1, args.json);
    } else if args.json {
        let v = check_text::catalogue_json(&reports, inputs.errors());
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(CliError::failure)?
        );
    } else {
        print!("{}", check_text::catalogue_table(&reports));
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
    let svg = gamma_error_svg(report, &title).map_err(CliError::failure)?;
    let png = heat_map_png(report, &title).map_err(CliError::failure)?;
    write_atomic(&csv, report.residuals_csv().as_bytes()).map_err(CliError::failure)?;
    write_atomic(&dir.join(format!("{stem}-gamma.svg")), svg.as_bytes())
        .map_err(CliError::failure)?;
    write_atomic(&dir.join(format!("{stem}-heatmap.png")), &png).map_err(CliError::failure)
}

/// Prints a check report as JSON or as a table.
fn print_check(report: &CheckReport, as_json: bool) {
    if as_json {
        println!(
            "{}",
            serde_json::to_string_pretty(report).expect("report serialises")
        );
    } else {
        print!("{}", check_text::check_table(report));
    }
}
