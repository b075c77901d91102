//! Photometry: EULUMDAT and IES files, the full-sphere light distribution and its
//! interpolation, the GPU texture data, the photometric summary, the interpolation check
//! and polar plots.

pub mod check;
pub mod distribution;
pub mod error;
pub mod eulumdat;
pub mod flux;
pub mod grid;
pub mod ies;
pub mod info;
pub mod plot;
pub mod summary;
pub mod symmetry;
pub mod text;
pub mod texture;

use std::path::Path;

pub use distribution::{angles_to_direction, direction_to_angles, Distribution};
pub use error::{ParseError, PhotometryError};
pub use eulumdat::Eulumdat;
pub use grid::{Grid, Interp};
pub use ies::IesFile;
pub use summary::Summary;
pub use symmetry::Symmetry;
pub use texture::LdtTexture;

/// The format a luminaire file came in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// EULUMDAT `.ldt`.
    Eulumdat,
    /// IES LM-63 `.ies`.
    Ies,
}

/// A loaded luminaire file: its data in the EULUMDAT model, the full-sphere distribution
/// and every warning collected on the way.
#[derive(Debug, Clone)]
pub struct Luminaire {
    /// The file's format.
    pub format: Format,
    /// The data (IES files are converted).
    pub data: Eulumdat,
    /// The IES file as read, for IES input.
    pub ies: Option<IesFile>,
    /// The full-sphere distribution.
    pub distribution: Distribution,
    /// Notes about what was accepted with a repair.
    pub warnings: Vec<String>,
}

impl Luminaire {
    /// Reads `.ldt` or `.ies` bytes; the format is told by the content (an IES file has a
    /// `TILT=` line and usually an `IESNA` header), with `name`'s extension as a hint.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<Luminaire, PhotometryError> {
        let lower = name.to_ascii_lowercase();
        let looks_ies = lower.ends_with(".ies")
            || bytes.starts_with(b"IES")
            || bytes.starts_with(b"\xEF\xBB\xBFIES");
        let (format, data, ies, mut warnings) = if looks_ies {
            let parsed = IesFile::parse(name, bytes)?;
            let stem = Path::new(name)
                .file_name()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            let ldt = parsed.data.to_eulumdat(&stem);
            (Format::Ies, ldt, Some(parsed.data), parsed.warnings)
        } else {
            let parsed = Eulumdat::parse(name, bytes)?;
            (Format::Eulumdat, parsed.data, None, parsed.warnings)
        };
        let (distribution, dist_warnings) = Distribution::from_eulumdat(&data);
        warnings.extend(dist_warnings);
        Ok(Luminaire {
            format,
            data,
            ies,
            distribution,
            warnings,
        })
    }

    /// Reads a `.ldt` or `.ies` file.
    pub fn load(path: &Path) -> Result<Luminaire, PhotometryError> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| PhotometryError::Io {
            file: name.clone(),
            source,
        })?;
        Luminaire::from_bytes(&name, &bytes)
    }

    /// The photometric summary.
    pub fn summary(&self) -> Summary {
        Summary::of(
            &self.distribution,
            self.data.lorl_percent,
            self.data.dff_percent,
        )
    }
}
