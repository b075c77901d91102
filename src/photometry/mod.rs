//! Photometry: EULUMDAT and IES files, the full-sphere light distribution and its
//! interpolation, the GPU texture data, the photometric summary, the interpolation check
//! and polar plots.

pub mod catalogue;
pub mod check;
pub mod check_text;
pub mod colour_rendering;
pub mod convert;
pub mod datasheet;
pub mod datasheet_plot;
pub mod distribution;
pub mod error;
pub mod eulumdat;
pub mod flux;
pub mod grid;
pub mod ies;
pub mod info;
pub mod isocandela;
pub mod ldt_writer;
pub mod luminance;
pub mod plot;
pub mod polar_diagram;
pub mod residual_plot;
pub mod spectral;
pub mod summary;
pub mod symmetry;
pub mod synthetic;
pub mod text;
pub mod texture;
pub mod tm33;
pub mod type_b;
pub mod ugr;

use std::path::Path;

pub use distribution::{angles_to_direction, direction_to_angles, Distribution};
pub use error::{ParseError, PhotometryError};
pub use eulumdat::Eulumdat;
pub use grid::{Grid, Interp};
pub use ies::IesFile;
pub use summary::Summary;
pub use symmetry::Symmetry;
pub use texture::LdtTexture;
pub use tm33::Tm33;

/// The format a luminaire file came in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// EULUMDAT `.ldt`.
    Eulumdat,
    /// IES LM-63 `.ies`.
    Ies,
    /// ANSI/IES TM-33-23 or ATLA S001, XML or JSON.
    Tm33,
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
    /// The TM-33 / ATLA document as read, for such input (spectra, emitters, openings).
    pub tm33: Option<Tm33>,
    /// The full-sphere distribution.
    pub distribution: Distribution,
    /// Notes about what was accepted with a repair.
    pub warnings: Vec<String>,
}

impl Luminaire {
    /// Reads `.ldt`, `.ies`, or TM-33 / ATLA `.xml` / `.json` bytes; the format is told by
    /// `name`'s extension, or by the content (an `IES…` first line; `<` or `{` for TM-33)
    /// when the name has none of these.
    pub fn from_bytes(name: &str, bytes: &[u8]) -> Result<Luminaire, PhotometryError> {
        // The extension decides; the content only where there is none to go by (an LDT
        // whose company line starts with "IES" is still an LDT).
        let lower = name.to_ascii_lowercase();
        let format = if lower.ends_with(".ies") {
            Format::Ies
        } else if lower.ends_with(".ldt") {
            Format::Eulumdat
        } else if lower.ends_with(".xml") || lower.ends_with(".json") || tm33::looks_like(bytes) {
            Format::Tm33
        } else if bytes.starts_with(b"IES") || bytes.starts_with(b"\xEF\xBB\xBFIES") {
            Format::Ies
        } else {
            Format::Eulumdat
        };
        let stem = Path::new(name)
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut tm33_doc = None;
        let (format, data, ies, mut warnings) = if format == Format::Tm33 {
            let parsed = Tm33::parse(name, bytes)?;
            let mut warnings = parsed.warnings;
            let ldt = parsed.data.to_eulumdat(name, &stem, &mut warnings)?;
            tm33_doc = Some(parsed.data);
            (Format::Tm33, ldt, None, warnings)
        } else if format == Format::Ies {
            let parsed = IesFile::parse(name, bytes)?;
            let ldt = parsed.data.to_eulumdat(&stem);
            (Format::Ies, ldt, Some(parsed.data), parsed.warnings)
        } else {
            let parsed = Eulumdat::parse(name, bytes)?;
            (Format::Eulumdat, parsed.data, None, parsed.warnings)
        };
        let (distribution, dist_warnings) = Distribution::from_eulumdat(&data);
        warnings.extend(dist_warnings);
        let lum = Luminaire {
            format,
            data,
            ies,
            tm33: tm33_doc,
            distribution,
            warnings,
        };
        lum.checked(name)
    }

    /// Refuses data whose numbers are not usable (overflowing or vanishing factors), and
    /// notes a computed LORL above 100 %.
    fn checked(mut self, name: &str) -> Result<Luminaire, PhotometryError> {
        let (field, line) = match self.format {
            Format::Eulumdat => ("intensities × conversion factor", 24),
            Format::Ies => ("candela × multiplier × ballast factor ÷ lamp lumens", 0),
            Format::Tm33 => ("intensities × Multiplier ÷ rated lumens", 0),
        };
        let grid = self.distribution.grid();
        if let Some(v) = grid.values().iter().find(|v| !v.is_finite()) {
            return Err(ParseError::new(
                name,
                line,
                format!("{field} give {v}: the values overflow"),
            )
            .into());
        }
        let lamp_flux = self.distribution.lamp_flux_lm();
        let flux = self.distribution.flux_lm();
        if !(lamp_flux.is_finite() && lamp_flux > 0.0 && flux.is_finite()) {
            return Err(ParseError::new(
                name,
                0,
                format!(
                    "lamp flux {} lm and luminaire flux {} lm are not usable numbers",
                    text::show(lamp_flux),
                    text::show(flux)
                ),
            )
            .into());
        }
        let peak_cd = self.distribution.max_intensity().0 * lamp_flux / 1000.0;
        if peak_cd < 1e-9 {
            return Err(ParseError::new(
                name,
                0,
                format!(
                    "the luminaire emits no light: its peak intensity is {} cd (lamp flux {} lm)",
                    text::show(peak_cd),
                    text::show(lamp_flux)
                ),
            )
            .into());
        }
        if !peak_cd.is_finite() {
            return Err(ParseError::new(
                name,
                line,
                format!("{field} × lamp flux overflow: the peak intensity is not a finite number of candela"),
            )
            .into());
        }
        let lorl = self.distribution.relative_flux().0 / 10.0;
        if lorl > 100.5 {
            self.warnings.push(format!(
                "the intensities integrate to {lorl:.2} % of the lamp flux (LORL above 100 %): check the lamp flux and the conversion factor"
            ));
        }
        Ok(self)
    }

    /// Where the data came from, for the labels of converted files: "EULUMDAT", "IES",
    /// "IES Type B" / "IES Type A", or the TM-33 dialect ("TM-33-23 XML", "ATLA S001 JSON" …).
    pub fn source_label(&self) -> &'static str {
        if let Some(doc) = &self.tm33 {
            return doc.dialect.label();
        }
        match (self.format, self.ies.as_ref().map(|f| f.photometric_type)) {
            (Format::Eulumdat, _) => "EULUMDAT",
            (Format::Ies, Some(2)) => "IES Type B",
            (Format::Ies, Some(3)) => "IES Type A",
            (Format::Ies, _) => "IES",
            (Format::Tm33, _) => "TM-33",
        }
    }

    /// Reads a `.ldt`, `.ies` or TM-33 / ATLA (`.xml`, `.json`) file.
    pub fn load(path: &Path) -> Result<Luminaire, PhotometryError> {
        let name = path.display().to_string();
        let bytes =
            crate::io::read_limited(path, crate::io::MAX_LUMINAIRE_BYTES).map_err(|source| {
                PhotometryError::Io {
                    file: name.clone(),
                    source,
                }
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
