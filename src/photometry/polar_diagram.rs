//! A luminaire's polar diagram written to a file, from its measured grid or a downsampled
//! copy (what `ldt plot` and `demo` write).

use std::path::Path;

use super::plot::PolarPlot;
use super::{check, Interp, Luminaire, PhotometryError};
use crate::io::WriteError;

/// Why a luminaire's polar diagram was not written.
#[derive(Debug, thiserror::Error)]
pub enum PolarDiagramError {
    /// The downsampling asked for does not fit the measured grid.
    #[error(transparent)]
    Downsample(#[from] PhotometryError),
    /// The file could not be drawn or written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Writes the polar diagram of `lum` to `out` (SVG or PNG by its extension): the
/// bilinear, Catmull-Rom and monotone curves through every measured value; with
/// `downsample` (ΔC, Δγ degrees) the curves come from that coarser copy and the title
/// says so, the measured values still marked.
pub fn write_polar_diagram(
    lum: &Luminaire,
    title: &str,
    out: &Path,
    downsample: Option<(f64, f64)>,
) -> Result<(), PolarDiagramError> {
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
    Ok(plot.save(out)?)
}
