//! `ldt report`: a one-page datasheet of a luminaire as one self-contained HTML or SVG
//! file ([`crate::photometry::datasheet`] makes it).

use std::path::PathBuf;

use clap::Args;

use super::{write_each, CliError, Outputs};
use crate::io::write_atomic;
use crate::photometry::datasheet;

/// Options of `ldt report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Luminaire files or directories.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output .html or .svg (one input file; the extension picks the format).
    #[arg(long, required_unless_present = "out_dir", conflicts_with = "out_dir")]
    pub out: Option<PathBuf>,
    /// Write one `NAME.html` per input here.
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// The lamp set the sheet's fluxes, UGR and luminance are for (1-based; default the
    /// first, as Relux and DIALux read EULUMDAT's sets as alternatives).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    pub lamp_set: u16,
}

/// Writes the report of each file.
pub(super) fn run(args: &ReportArgs) -> Result<(), CliError> {
    let lamp_set = Some(usize::from(args.lamp_set));
    let outputs = Outputs {
        out: args.out.as_deref(),
        out_dir: args.out_dir.as_deref(),
        ext: "html",
        allowed: &["html", "htm", "svg"],
    };
    write_each(&args.files, outputs, |file, lum, target| {
        let file_name = file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let sheet =
            datasheet::sheet(&file_name, lum, lamp_set).map_err(|e| super::about(file, e))?;
        let svg = target
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let text = datasheet::page(&sheet, svg);
        write_atomic(target, text.as_bytes()).map_err(CliError::failure)
    })
}
