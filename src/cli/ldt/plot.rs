//! `ldt plot`: datasheet diagrams (polar, cartesian) or the interpolation check's picture,
//! as PNG or SVG, for one file or many.

use std::path::PathBuf;

use clap::Args;

use super::{parse_pair, write_each, CliError, Outputs};
use crate::io::write_atomic;
use crate::photometry::datasheet_plot::{Diagram, DiagramKind};
use crate::photometry::luminance::lamp_set_flux;
use crate::photometry::polar_diagram::write_polar_diagram;
use crate::photometry::Interp;

/// A picture format, by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PictureFormat {
    /// Raster.
    Png,
    /// Vector.
    Svg,
}

/// Options of `ldt plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// Luminaire files or directories.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Output .png or .svg (one input file; the extension picks the format).
    #[arg(long, required_unless_present = "out_dir", conflicts_with = "out_dir")]
    pub out: Option<PathBuf>,
    /// Write one diagram per input here, named after the input (`sample.ldt` →
    /// `sample.png`, or `.svg` with --format svg).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// The format of the diagrams written into --out-dir.
    #[arg(long, value_enum, default_value = "png", requires = "out_dir")]
    pub format: PictureFormat,
    /// The diagram.
    #[arg(
        long,
        value_enum,
        default_value = "polar",
        conflicts_with = "downsample"
    )]
    pub kind: DiagramKind,
    /// The plane pairs drawn, by their first C angle (each with its C + 180° half).
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 90.0], value_parser = parse_plane, conflicts_with = "downsample")]
    pub planes: Vec<f64>,
    /// Interpolation between the measured angles.
    #[arg(
        long,
        value_enum,
        default_value = "catmull-rom",
        conflicts_with = "downsample"
    )]
    pub interp: Interp,
    /// The lamp set whose flux the title states (1-based; default all sets summed). The
    /// curves are in cd/klm either way.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..), conflicts_with = "downsample")]
    pub lamp_set: Option<u16>,
    /// Draw the interpolation check instead: the curves of each method from the file
    /// downsampled to these C,γ steps (degrees), every measured value marked.
    #[arg(long, value_parser = parse_pair)]
    pub downsample: Option<(f64, f64)>,
}

fn parse_plane(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|c| (0.0..180.0).contains(c))
        .ok_or_else(|| {
            format!("a plane is a C angle from 0 to below 180 (its pair adds 180°), got {s:?}")
        })
}

/// Writes the diagrams `args` asks for.
pub(super) fn run(args: &PlotArgs) -> Result<(), CliError> {
    let ext = match args.format {
        PictureFormat::Png => "png",
        PictureFormat::Svg => "svg",
    };
    let outputs = Outputs {
        out: args.out.as_deref(),
        out_dir: args.out_dir.as_deref(),
        ext,
        allowed: &["png", "svg"],
    };
    write_each(&args.files, outputs, |file, lum, target| {
        let name = file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        if args.downsample.is_some() {
            return Ok(write_polar_diagram(lum, &name, target, args.downsample)?);
        }
        let lamp_flux_lm = match args.lamp_set {
            Some(k) => {
                Some(lamp_set_flux(lum, Some(usize::from(k))).map_err(|e| super::about(file, e))?)
            }
            None => None,
        };
        let diagram = Diagram {
            lum,
            file_name: name,
            planes: args.planes.clone(),
            interp: args.interp,
            lamp_flux_lm,
        };
        let svg = target
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let bytes = if svg {
            diagram.svg(args.kind).map(String::into_bytes)
        } else {
            diagram.png(args.kind)
        }
        .map_err(CliError::failure)?;
        write_atomic(target, &bytes).map_err(CliError::failure)
    })
}
