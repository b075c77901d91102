//! `ldt luminance`: the luminance table of one or many luminaire files.

use std::path::{Path, PathBuf};

use super::{tables_per_file, CliError};
use crate::photometry::luminance::{gamma_rows, luminance_table, ugr_grid, LuminanceTable};
use crate::photometry::Interp;

/// Prints the luminance table of each file, as text or JSON.
pub(super) fn run(
    files: &[PathBuf],
    as_json: bool,
    lamp_set: Option<usize>,
    gamma_from: u16,
    interp: Interp,
) -> Result<(), CliError> {
    let Some(gammas) = gamma_rows(gamma_from) else {
        return Err(CliError::input(anyhow::anyhow!(
            "--gamma-from {gamma_from}: give a multiple of 5 (the rows are 5° apart)"
        )));
    };
    let (c_angles, _) = ugr_grid();
    tables_per_file(
        files,
        as_json,
        |lum| luminance_table(lum, &c_angles, &gammas, lamp_set, interp),
        print_table,
    )
}

fn print_table(path: &Path, name: &str, t: &LuminanceTable) {
    println!(
        "{} — {name}: luminance of the luminous area, cd/m² ({:.0} lm; max {:.0})",
        path.display(),
        t.flux_lm,
        t.max()
    );
    let mut head = format!("{:>7}", "C \\ γ");
    for g in &t.gamma_angles {
        head.push_str(&format!("{:>9}", format!("{g}°")));
    }
    println!("{head}");
    for (c, row) in t.c_angles.iter().zip(&t.cd_m2) {
        let mut line = format!("{:>7}", format!("{c}°"));
        for v in row {
            line.push_str(&format!("{v:>9.0}"));
        }
        println!("{line}");
    }
}
