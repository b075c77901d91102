//! `ldt info`'s text: the summary rows of [`crate::photometry::datasheet::summary`],
//! printed.

use std::path::Path;

use crate::photometry::datasheet::summary::summary_rows;
use crate::photometry::{Luminaire, PhotometryError};

/// Prints the summary of `lum` read from `file` as text.
pub(super) fn print_info(
    file: &Path,
    lum: &Luminaire,
    lamp_set: Option<usize>,
) -> Result<(), PhotometryError> {
    println!("{}", file.display());
    for (label, value) in summary_rows(lum, lamp_set)? {
        println!("  {label:<14} {value}");
    }
    if !lum.warnings.is_empty() {
        println!(
            "  {:<14} {} (on standard error)",
            "warnings",
            lum.warnings.len()
        );
    }
    Ok(())
}
