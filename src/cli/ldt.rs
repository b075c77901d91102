//! `goniolight ldt …`: luminaire file tools.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use super::CliError;
use crate::io::write_atomic;
use crate::photometry::check::{self, CheckReport, LeaveOut};
use crate::photometry::ies::write_ies;
use crate::photometry::plot::PolarPlot;
use crate::photometry::{Interp, LdtTexture, Luminaire};

/// Luminaire file subcommands.
#[derive(Debug, Subcommand)]
pub enum LdtCommand {
    /// Print the data and photometric summary of a .ldt or .ies file.
    Info {
        /// The luminaire file.
        file: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Read lines "C GAMMA" (degrees) from stdin and print one intensity (cd/klm) per line.
    Sample {
        /// The luminaire file.
        file: PathBuf,
        /// Interpolation between the measured angles.
        #[arg(long, value_enum, default_value = "catmull-rom")]
        interp: Interp,
    },
    /// Check how well each interpolation reconstructs measured values it did not see.
    Check(CheckArgs),
    /// Write the polar goniometric diagram (C0–C180 and C90–C270) as PNG.
    Plot {
        /// The luminaire file.
        file: PathBuf,
        /// Output PNG.
        #[arg(long)]
        out: PathBuf,
        /// Draw the curves from the file downsampled to these C,γ steps (degrees), with
        /// every measured value marked: a picture of the interpolation check.
        #[arg(long, value_parser = parse_pair)]
        downsample: Option<(f64, f64)>,
    },
    /// Convert between EULUMDAT and IES (the output's extension picks the format).
    Convert {
        /// The luminaire file.
        file: PathBuf,
        /// Output .ldt or .ies.
        #[arg(long)]
        out: PathBuf,
    },
}

/// Options of `ldt check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The luminaire file (the coarse one with --reference).
    pub file: PathBuf,
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
    #[arg(long)]
    pub json: bool,
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
        LdtCommand::Info { file, json } => info(&file, json),
        LdtCommand::Sample { file, interp } => sample(&file, interp),
        LdtCommand::Check(args) => {
            let report = run_check(&args)?;
            print_check(&report, args.json);
            Ok(())
        }
        LdtCommand::Plot {
            file,
            out,
            downsample,
        } => plot(&file, &out, downsample),
        LdtCommand::Convert { file, out } => convert(&file, &out),
    }
}

fn info(file: &Path, as_json: bool) -> Result<(), CliError> {
    let lum = load(file)?;
    let s = lum.summary();
    let grid = lum.distribution.grid();
    let tex = LdtTexture::from_distribution(&lum.distribution);
    if as_json {
        let v = lum.info_json();
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(CliError::failure)?
        );
        return Ok(());
    }
    let d = &lum.data;
    let angle = |v: Option<f64>| v.map_or("—".to_string(), |a| format!("{a:.1}°"));
    println!(
        "{}  ({:?}, Isym {})",
        file.display(),
        lum.format,
        d.symmetry.isym()
    );
    println!("  luminaire      {} — {}", d.company, d.luminaire_name);
    println!(
        "  grid           {} C planes × {} γ angles (expanded from {} stored planes)",
        grid.c_angles().len(),
        grid.gamma_angles().len(),
        d.intensities.len()
    );
    for (i, l) in d.lamp_sets.iter().enumerate() {
        println!(
            "  lamp set {}     {} × {} — {} lm, {} W{}",
            i + 1,
            l.count.abs(),
            l.lamp_type,
            l.flux_lm,
            l.watts,
            if l.count < 0 {
                " (absolute photometry)"
            } else {
                ""
            }
        );
    }
    println!(
        "  flux           {:.1} lm (lamps {:.1} lm)",
        s.flux_lm, s.lamp_flux_lm
    );
    println!(
        "  LORL           {:.2} % computed, {:.2} % declared",
        s.lorl_computed, s.lorl_declared
    );
    println!(
        "  DFF            {:.2} % computed, {:.2} % declared",
        s.dff_computed, s.dff_declared
    );
    println!(
        "  I_max          {:.2} cd/klm at C{:.1} γ{:.1}",
        s.max_intensity, s.max_direction_deg[0], s.max_direction_deg[1]
    );
    println!(
        "  beam (50 %)    C0–C180 {}, C90–C270 {}",
        angle(s.beam_angle_deg.c0_c180),
        angle(s.beam_angle_deg.c90_c270)
    );
    println!(
        "  field (10 %)   C0–C180 {}, C90–C270 {}",
        angle(s.field_angle_deg.c0_c180),
        angle(s.field_angle_deg.c90_c270)
    );
    println!("  emits          {:?} hemisphere", tex.hemisphere);
    Ok(())
}

fn sample(file: &Path, interp: Interp) -> Result<(), CliError> {
    let lum = load(file)?;
    let angles = crate::lighting::read_angles(std::io::stdin().lock(), "<stdin>")?;
    let mut out = String::new();
    for (c, g) in angles {
        out.push_str(&format!("{}\n", lum.distribution.sample(c, g, interp)));
    }
    std::io::stdout()
        .write_all(out.as_bytes())
        .map_err(CliError::failure)
}

/// Runs the check `args` asks for.
pub(super) fn run_check(args: &CheckArgs) -> Result<CheckReport, CliError> {
    let lum = load(&args.file)?;
    let report = if let Some(fine) = &args.reference {
        let fine = load(fine)?;
        check::against_reference(&lum.distribution, &fine.distribution)?
    } else if let Some((dc, dg)) = args.downsample {
        check::downsample(&lum.distribution, dc, dg)?
    } else {
        check::leave_out(&lum.distribution, args.leave_out)?
    };
    Ok(report)
}

/// Prints a check report as JSON or as a table.
pub(super) fn print_check(report: &CheckReport, as_json: bool) {
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

/// Writes the polar diagram of `lum`, optionally from a downsampled copy.
pub(super) fn write_plot(
    lum: &Luminaire,
    title: &str,
    out: &Path,
    downsample: Option<(f64, f64)>,
) -> Result<(), CliError> {
    let measured = lum.distribution.grid();
    let coarse;
    let (curves, title) = match downsample {
        Some((dc, dg)) => {
            coarse = check::downsampled_grid(&lum.distribution, dc, dg)?;
            (
                &coarse,
                format!("{title} — curves from {dc}° × {dg}° samples, all measured values marked"),
            )
        }
        None => (measured, title.to_string()),
    };
    let plot = PolarPlot {
        title,
        curves,
        measured,
        methods: vec![Interp::Bilinear, Interp::CatmullRom, Interp::Monotone],
    };
    plot.save(out).map_err(CliError::failure)
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
    let same = match (input.canonicalize(), out.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same {
        return Err(CliError::input(anyhow::anyhow!(
            "{}: --out is the input file; choose another name",
            out.display()
        )));
    }
    Ok(())
}

fn plot(file: &Path, out: &Path, downsample: Option<(f64, f64)>) -> Result<(), CliError> {
    check_output(file, out, &["png"])?;
    let lum = load(file)?;
    let name = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    write_plot(&lum, &name, out, downsample)
}

fn convert(file: &Path, out: &Path) -> Result<(), CliError> {
    check_output(file, out, &["ldt", "ies"])?;
    let lum = load(file)?;
    let ies = out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ies"));
    let text = if ies {
        write_ies(&lum.data, lum.source_label())
    } else {
        lum.data.to_ldt_string()
    };
    write_atomic(out, text.as_bytes()).map_err(CliError::failure)
}
