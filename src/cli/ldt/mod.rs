//! `goniolight ldt …`: luminaire file tools.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

mod catalogue;
mod info;
mod inputs;
mod luminance;
mod plot;
mod report;
mod ugr;

use inputs::{Inputs, OutputNames};

use super::error::CliError;
use crate::io::write_atomic;
use crate::photometry::check::LeaveOut;
use crate::photometry::convert::OutputFormat;
use crate::photometry::info::{csv_line, CATALOGUE_COLUMNS};
use crate::photometry::{Interp, Luminaire};

/// Luminaire file subcommands. Each takes one or more files or directories (walked for
/// `.ldt` and `.ies` files and TM-33 / ATLA documents); with several, a file that fails is reported and the others go
/// on, and the command exits 2 at the end.
#[derive(Debug, Subcommand)]
pub enum LdtCommand {
    /// Print the data and photometric summary of .ldt, .ies or TM-33 / ATLA (.xml, .json)
    /// files (with their spectral figures: melanopic DER, PPF).
    Info {
        /// Luminaire files or directories.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print JSON instead of text (an array of objects, each with its "path", for
        /// several files).
        #[arg(long, conflicts_with = "csv")]
        json: bool,
        /// Print a catalogue table as CSV: a header, then one row per file.
        #[arg(long)]
        csv: bool,
        /// Give the text's flux, efficacy and candela for this lamp set (1-based; default
        /// all sets summed, as the JSON's figures).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..), conflicts_with_all = ["json", "csv"])]
        lamp_set: Option<u16>,
    },
    /// Read lines "C GAMMA" (degrees) from stdin and print one intensity (cd/klm) per line
    /// (several files: one column per file, after a "# columns:" line naming them).
    Sample {
        /// Luminaire files or directories.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Interpolation between the measured angles.
        #[arg(long, value_enum, default_value = "catmull-rom")]
        interp: Interp,
    },
    /// Check how well each interpolation reconstructs measured values it did not see
    /// (several files: one table and a summary over the catalogue).
    Check(CheckArgs),
    /// Print the luminance table: cd/m² of the luminous area by C plane (0–345° every 15°)
    /// and γ (65–85° every 5°, the UGR grid; --gamma-from to start lower).
    Luminance {
        /// Luminaire files or directories.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print JSON: {"c_angles", "gamma_angles", "cd_m2": one array per C angle, "flux_lm"}
        /// (an array of them, each with its "path", for several files).
        #[arg(long)]
        json: bool,
        /// The lamp set whose flux turns cd/klm into candela (1-based; default the first,
        /// as Relux and DIALux read EULUMDAT's sets as alternatives).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
        lamp_set: Option<u16>,
        /// The first γ row, degrees (a multiple of 5 below 90; datasheets print 45 or 65).
        #[arg(long, default_value_t = 65, value_parser = clap::value_parser!(u16).range(0..90))]
        gamma_from: u16,
        /// Interpolation between the measured angles (the grid's own angles are exact).
        #[arg(long, value_enum, default_value = "bilinear")]
        interp: Interp,
    },
    /// Print the UGR table (CIE 117 formula, CIE 190 tabular method): 19 room sizes × 5
    /// reflectance combinations, viewed crosswise and endwise, at spacing SHR · H.
    Ugr {
        /// Luminaire files or directories.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print JSON: {"shr", "rooms", "reflectances", "crosswise", "endwise", "flux_lm"}
        /// (an array of them, each with its "path", for several files).
        #[arg(long)]
        json: bool,
        /// Spacing-to-height ratio of the luminaire grid (CIE 190's standard table: 0.25).
        #[arg(long, default_value_t = 0.25)]
        shr: f64,
        /// The lamp set whose flux the table is for (1-based; default the first).
        #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
        lamp_set: Option<u16>,
    },
    /// Write a datasheet diagram (polar or cartesian, C0–C180 and C90–C270 overlaid) as
    /// PNG or SVG; with --downsample, the interpolation check's picture instead.
    Plot(plot::PlotArgs),
    /// Write a one-page datasheet as one self-contained HTML file: summary, polar and
    /// cartesian diagrams, UGR table, luminance table, warnings.
    Report(report::ReportArgs),
    /// Convert between EULUMDAT, IES, TM-33-23 XML and ATLA S001 JSON (the output's
    /// extension, or --to, picks the format); notes what the target format cannot hold.
    Convert {
        /// Luminaire files or directories.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Output .ldt, .ies, .xml (TM-33-23) or .json (ATLA S001) (one input file).
        #[arg(long, conflicts_with_all = ["out_dir", "to"])]
        out: Option<PathBuf>,
        /// The format to write for each input: next to it, or into --out-dir, named after it.
        #[arg(long, value_enum, required_unless_present = "out")]
        to: Option<OutputFormat>,
        /// Write the converted files here instead of next to their inputs.
        #[arg(long, requires = "to")]
        out_dir: Option<PathBuf>,
        /// EULUMDAT output: print every number exactly and every text in full (reads back
        /// as the same data) instead of fitting the format's fixed field widths.
        #[arg(long)]
        exact: bool,
    },
}

/// Options of `ldt check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Luminaire files or directories (one file, the coarse one, with --reference).
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// A finer measurement of the same luminaire to reconstruct at every angle.
    #[arg(long, conflicts_with = "downsample")]
    pub reference: Option<PathBuf>,
    /// Downsample the file to these C,γ steps (degrees) and reconstruct the rest.
    #[arg(long, value_parser = parse_pair)]
    pub downsample: Option<(f64, f64)>,
    /// Which angles the leave-out check hides (without --reference or --downsample).
    #[arg(long, value_enum, default_value = "both")]
    pub leave_out: LeaveOut,
    /// Print JSON instead of a table.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print the table as CSV (one row per file and method).
    #[arg(long)]
    pub csv: bool,
    /// Write each file's residuals here: `STEM.csv` (every hidden angle, each method's
    /// reconstructed − measured), `STEM-gamma.svg` (RMS error against γ) and
    /// `STEM-heatmap.png` (C × γ map of the residuals per method).
    #[arg(long, value_name = "DIR")]
    pub residuals: Option<PathBuf>,
}

fn parse_pair(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(',')
        .ok_or_else(|| format!("expected two numbers 'DC,DG', got {s:?}"))?;
    let num = |t: &str| {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v > 0.0)
            .ok_or_else(|| format!("expected a positive number, got {t:?}"))
    };
    Ok((num(a)?, num(b)?))
}

/// Loads a luminaire and prints its warnings to stderr.
pub(super) fn load(path: &Path) -> Result<Luminaire, CliError> {
    let lum = Luminaire::load(path)?;
    for w in &lum.warnings {
        eprintln!("warning: {}: {w}", path.display());
    }
    Ok(lum)
}

/// Runs an `ldt` subcommand.
pub fn run(cmd: LdtCommand) -> Result<(), CliError> {
    match cmd {
        LdtCommand::Info {
            files,
            json,
            csv,
            lamp_set,
        } => info(&files, json, csv, lamp_set.map(usize::from)),
        LdtCommand::Sample { files, interp } => sample(&files, interp),
        LdtCommand::Check(args) => catalogue::check(&args),
        LdtCommand::Ugr {
            files,
            json,
            shr,
            lamp_set,
        } => ugr::run(&files, json, shr, lamp_set.map(usize::from)),
        LdtCommand::Luminance {
            files,
            json,
            lamp_set,
            gamma_from,
            interp,
        } => luminance::run(&files, json, lamp_set.map(usize::from), gamma_from, interp),
        LdtCommand::Plot(args) => plot::run(&args),
        LdtCommand::Report(args) => report::run(&args),
        LdtCommand::Convert {
            files,
            out,
            to,
            out_dir,
            exact,
        } => convert(&files, out.as_deref(), to, out_dir.as_deref(), exact),
    }
}

fn info(
    files: &[PathBuf],
    as_json: bool,
    as_csv: bool,
    lamp_set: Option<usize>,
) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(files);
    if as_csv {
        print!("{}", csv_line(&CATALOGUE_COLUMNS));
        inputs.each(|file| {
            let lum = load(file)?;
            print!(
                "{}",
                csv_line(&lum.catalogue_row(&file.display().to_string()))
            );
            Ok(())
        })?;
    } else if as_json && !inputs.single {
        let all = inputs.each(|file| {
            let mut v = load(file)?.info_json();
            v["path"] = serde_json::Value::from(file.display().to_string());
            Ok(v)
        })?;
        let all: Vec<serde_json::Value> = all.into_iter().map(|(_, v)| v).collect();
        println!(
            "{}",
            serde_json::to_string_pretty(&all).map_err(CliError::failure)?
        );
    } else {
        let mut first = true;
        inputs.each(|file| {
            let lum = load(file)?;
            if as_json {
                let v = lum.info_json();
                println!(
                    "{}",
                    serde_json::to_string_pretty(&v).map_err(CliError::failure)?
                );
                return Ok(());
            }
            if !std::mem::take(&mut first) {
                println!();
            }
            info::print_info(file, &lum, lamp_set).map_err(|e| about(file, e))
        })?;
    }
    inputs.finish()
}

fn sample(files: &[PathBuf], interp: Interp) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(files);
    let lums = inputs.each(load)?;
    if lums.is_empty() {
        return inputs.finish();
    }
    let angles = crate::lighting::read_angles(std::io::stdin().lock(), "<stdin>")?;
    let mut out = String::new();
    if !inputs.single {
        let names: Vec<String> = lums.iter().map(|(p, _)| p.display().to_string()).collect();
        out.push_str(&format!("# columns: {}\n", names.join(" ")));
    }
    for (c, g) in angles {
        let row: Vec<String> = lums
            .iter()
            .map(|(_, lum)| lum.distribution.sample(c, g, interp).to_string())
            .collect();
        out.push_str(&row.join(" "));
        out.push('\n');
    }
    std::io::stdout()
        .write_all(out.as_bytes())
        .map_err(CliError::failure)?;
    inputs.finish()
}

/// Refuses an output that is the input itself, or that lacks one of `exts`, before any
/// work: a mistyped `--out` must not replace the luminaire file.
fn check_output(input: &Path, out: &Path, exts: &[&str]) -> Result<(), CliError> {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if !exts.contains(&ext.as_str()) {
        return Err(CliError::input(anyhow::anyhow!(
            "{}: --out must end in .{}",
            out.display(),
            exts.join(" or .")
        )));
    }
    let mut check = crate::io::outputs::OutputCheck::new();
    check.named_output(&format!("--out {}", out.display()), out);
    check.check()?;
    if crate::io::outputs::same_file(input, out) {
        return Err(CliError::input(anyhow::anyhow!(
            "{}: the output would replace the input file; choose another name with --out or --out-dir",
            out.display()
        )));
    }
    Ok(())
}

fn convert(
    files: &[PathBuf],
    out: Option<&Path>,
    to: Option<OutputFormat>,
    out_dir: Option<&Path>,
    exact: bool,
) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(files);
    let mut names = OutputNames::default();
    one_output_for_one_file(&inputs, out)?;
    create_dir("--out-dir", out_dir)?;
    inputs.each(|file| {
        let target = match (out, to) {
            (Some(out), _) => out.to_path_buf(),
            (None, Some(to)) if out_dir.is_none() && OutputFormat::of_path(file) == Some(to) => {
                eprintln!(
                    "note: {}: already .{}; left as it is",
                    file.display(),
                    to.ext()
                );
                return Ok(());
            }
            (None, Some(to)) => names.claim(file, out_dir, to.ext())?,
            (None, None) => {
                return Err(CliError::input(anyhow::anyhow!(
                    "say where to write: --out FILE.ldt|.ies|.xml|.json, or --to ldt|ies|tm33|atla"
                )))
            }
        };
        check_output(file, &target, &["ldt", "ies", "xml", "json"])?;
        let lum = load(file)?;
        let format = OutputFormat::of_path(&target).expect("checked extension");
        let converted = crate::photometry::convert::convert(&lum, format, exact).map_err(|e| {
            let message = super::error::flags_in(&e.to_string());
            CliError::input(anyhow::anyhow!("{}: {message}", file.display()))
        })?;
        for note in &converted.notes {
            eprintln!("note: {}: {note}", target.display());
        }
        for lost in &converted.losses {
            eprintln!(
                "note: {}: {} cannot hold {lost}",
                target.display(),
                format.label()
            );
        }
        write_atomic(&target, converted.text.as_bytes()).map_err(CliError::failure)
    })?;
    inputs.finish()
}

/// `--out` names one file: refuse it for several inputs before any work.
fn one_output_for_one_file(inputs: &Inputs, out: Option<&Path>) -> Result<(), CliError> {
    match out {
        Some(out) if !inputs.single => Err(CliError::input(anyhow::anyhow!(
            "--out {} names one output, but {} luminaire files were given; use --out-dir",
            out.display(),
            inputs.files.len()
        ))),
        _ => Ok(()),
    }
}

/// Creates the folder an option names (and its parents), if one is named.
fn create_dir(option: &str, dir: Option<&Path>) -> Result<(), CliError> {
    let Some(dir) = dir else { return Ok(()) };
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::input(anyhow::anyhow!("{option} {}: {e}", dir.display())))
}

/// A library error about one file, named by the file (in a catalogue it must say which).
fn about(file: &Path, e: crate::photometry::PhotometryError) -> CliError {
    let bad_input = e.is_bad_input();
    CliError::classified(
        super::error::photometry_message(e).context(file.display().to_string()),
        bad_input,
    )
}

/// Makes a table of each file with `make` and prints them: as JSON (a single file's
/// object, else an array of them, each with its "path"), or as text by `print` (path,
/// luminaire name, table), a blank line between files.
fn tables_per_file<T: serde::Serialize>(
    files: &[PathBuf],
    as_json: bool,
    make: impl Fn(&Luminaire) -> Result<T, crate::photometry::PhotometryError>,
    print: impl Fn(&Path, &str, &T),
) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(files);
    let tables = inputs.each(|file| {
        let lum = load(file)?;
        let table = make(&lum).map_err(|e| about(file, e))?;
        Ok((lum.data.luminaire_name.trim().to_string(), table))
    })?;
    if as_json {
        let mut values = Vec::new();
        for (path, (_, table)) in &tables {
            let mut v = serde_json::to_value(table).map_err(CliError::failure)?;
            if !inputs.single {
                v["path"] = serde_json::Value::from(path.display().to_string());
            }
            values.push(v);
        }
        let out = if inputs.single {
            values.remove(0)
        } else {
            serde_json::Value::Array(values)
        };
        println!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(CliError::failure)?
        );
    } else {
        for (k, (path, (name, table))) in tables.iter().enumerate() {
            if k > 0 {
                println!();
            }
            print(path, name, table);
        }
    }
    inputs.finish()
}

/// Where each input's output goes: `--out` (one input file) or a file named after the input
/// in `--out-dir` with `ext`.
struct Outputs<'a> {
    out: Option<&'a Path>,
    out_dir: Option<&'a Path>,
    ext: &'a str,
    /// The extensions `--out` may have.
    allowed: &'a [&'a str],
}

/// Loads each input and runs `write(file, luminaire, output path)`, with the per-file
/// bookkeeping of a catalogue run (refusals before any work, outputs never replacing
/// inputs or each other).
fn write_each(
    files: &[PathBuf],
    outputs: Outputs,
    mut write: impl FnMut(&Path, &Luminaire, &Path) -> Result<(), CliError>,
) -> Result<(), CliError> {
    let mut inputs = Inputs::expand(files);
    let mut names = OutputNames::default();
    one_output_for_one_file(&inputs, outputs.out)?;
    create_dir("--out-dir", outputs.out_dir)?;
    inputs.each(|file| {
        let target = match outputs.out {
            Some(out) => out.to_path_buf(),
            None => names.claim(file, outputs.out_dir, outputs.ext)?,
        };
        check_output(file, &target, outputs.allowed)?;
        let lum = load(file)?;
        write(file, &lum, &target)
    })?;
    inputs.finish()
}
