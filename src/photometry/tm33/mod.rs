//! ANSI/IES TM-33-23 and ATLA S001 luminaire files: reading (XML and JSON), the data they
//! carry beyond EULUMDAT and IES (several emitters, luminous openings, spectra) and the
//! conversion to the EULUMDAT model every calculation uses.
//!
//! Five dialects are read, told apart by their root:
//! - ATLA S001 XML (`<ATLA_S001_A>`, `IntData h= v=`) and its JSON twin (`"FileType":
//!   "ATLA_S001_A"`, `IntDataSymm`);
//! - TM-33-23 XML (`<IESTM33-22>`, `IntensityData horz= vert=`, `SymmType`, `Multiplier`);
//! - the `<LuminaireOpticalData>` XML and camelCase JSON of the eulumdat-rs library (TM-33-18
//!   element names), whose intensities are in cd/klm as that library converts them to and
//!   from EULUMDAT.
//!
//! Units: the standard dialects give candela: absolute photometry where
//! `AbsolutePhotometry` is true or no rated lumens are given, otherwise the candela of the
//! emitter at its rated lumens (as an IES file's candela are for its lamps). `RatedLumens`
//! is the emitter's total (all `Quantity` lamps), as the EULUMDAT twin of the shared
//! fluorescent sample states it. Dimensions are metres in ATLA S001 and TM-33-23 (values
//! above 20 are read as millimetres, with a warning) and millimetres in the eulumdat-rs
//! dialect.

mod convert;
mod json;
mod write;
mod xml;

pub use write::{from_eulumdat, to_atla_json, to_tm33_xml};

use super::error::ParseError;
use super::spectral::Spectrum;

/// Largest number of emitters accepted.
pub const MAX_EMITTERS: usize = 64;

/// Which of the file kinds a document came in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dialect {
    /// ATLA S001 XML.
    AtlaXml,
    /// ATLA S001 JSON.
    AtlaJson,
    /// ANSI/IES TM-33-23 XML.
    Tm33Xml,
    /// eulumdat-rs's `<LuminaireOpticalData>` XML (intensities in cd/klm).
    OpticalDataXml,
    /// eulumdat-rs's camelCase JSON (intensities in cd/klm).
    OpticalDataJson,
}

impl Dialect {
    /// The name people know the format by.
    pub fn label(self) -> &'static str {
        match self {
            Dialect::AtlaXml => "ATLA S001 XML",
            Dialect::AtlaJson => "ATLA S001 JSON",
            Dialect::Tm33Xml => "TM-33-23 XML",
            Dialect::OpticalDataXml => "TM-33 XML (LuminaireOpticalData)",
            Dialect::OpticalDataJson => "TM-33 JSON (camelCase)",
        }
    }

    /// True where the intensities are cd/klm rather than candela.
    fn per_klm(self) -> bool {
        matches!(self, Dialect::OpticalDataXml | Dialect::OpticalDataJson)
    }

    /// True where dimensions are millimetres by the dialect's convention.
    fn millimetres(self) -> bool {
        self.per_klm()
    }
}

/// A TM-33 / ATLA document as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Tm33 {
    /// The file kind.
    pub dialect: Dialect,
    /// Who made and measured the luminaire.
    pub header: Header,
    /// Length, width and height of the luminaire, metres (0 where not given).
    pub dimensions_m: [f64; 3],
    /// The emitters, in file order.
    pub emitters: Vec<Emitter>,
}

/// The document's header.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Header {
    /// Manufacturer.
    pub manufacturer: String,
    /// Catalogue number.
    pub catalog_number: String,
    /// Description (the luminaire's name).
    pub description: String,
    /// Test laboratory.
    pub laboratory: String,
    /// Report number.
    pub report_number: String,
    /// Report or test date.
    pub report_date: String,
}

impl Header {
    /// The header from `text`, which gives the text of the first element (or key) of the
    /// names it is given that the file has ("" if none): the names are those of all
    /// dialects.
    fn from_lookup(text: impl Fn(&[&str]) -> String) -> Header {
        Header {
            manufacturer: text(&["Manufacturer"]),
            catalog_number: text(&["CatalogNumber"]),
            description: text(&["Description"]),
            laboratory: text(&["Laboratory"]),
            report_number: text(&["ReportNumber"]),
            report_date: text(&["ReportDate", "TestDate"]),
        }
    }
}

/// One emitter: a light source with its own data.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Emitter {
    /// Description (the lamp or module).
    pub description: String,
    /// Number of identical lamps this emitter stands for.
    pub quantity: u32,
    /// Rated lumens of the emitter (all its lamps), if given and above 0.
    pub rated_lumens: Option<f64>,
    /// Input power, W.
    pub input_watts: Option<f64>,
    /// Correlated colour temperature, K.
    pub cct_k: Option<f64>,
    /// CIE colour rendering index Ra.
    pub ra: Option<f64>,
    /// The intensity distribution, if the emitter has one.
    pub intensity: Option<Intensity>,
    /// The relative spectral distribution, if given.
    pub spectrum: Option<Spectrum>,
    /// Luminous openings on the bottom face, metres.
    pub openings: Vec<Opening>,
}

/// A rectangular luminous opening on the luminaire's bottom face.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Opening {
    /// Length (along C0–C180), metres.
    pub length_m: f64,
    /// Width (along C90–C270), metres.
    pub width_m: f64,
    /// Offset of its centre along the length, metres.
    pub length_offset_m: f64,
    /// Offset of its centre along the width, metres.
    pub width_offset_m: f64,
}

/// An emitter's intensity table as stored.
#[derive(Debug, Clone, PartialEq)]
pub struct Intensity {
    /// The photometry type letter: 'C' (the only one converted), 'B' or 'A'.
    pub photometry_type: char,
    /// The declared symmetry as written, with its line, if any.
    pub symmetry: Option<(String, usize)>,
    /// The declared absolute/relative photometry, if any.
    pub absolute: Option<bool>,
    /// Multiplier of the stored values.
    pub multiplier: f64,
    /// Horizontal (C) angles, degrees, increasing.
    pub horizontal: Vec<f64>,
    /// Vertical (γ) angles, degrees, increasing.
    pub vertical: Vec<f64>,
    /// Values as stored, one row per horizontal angle.
    pub values: Vec<Vec<f64>>,
    /// Line of the first value (0 in JSON without one).
    pub line: usize,
}

/// A parsed document with the warnings its reading produced.
#[derive(Debug, Clone)]
pub struct ParsedTm33 {
    /// The document.
    pub data: Tm33,
    /// Notes about things accepted with a repair or left out.
    pub warnings: Vec<String>,
}

/// True when `bytes` look like an XML or JSON document (the first character after a byte
/// order mark and white space is `<` or `{`).
pub fn looks_like(bytes: &[u8]) -> bool {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    matches!(
        bytes.iter().find(|b| !b.is_ascii_whitespace()),
        Some(b'<') | Some(b'{')
    )
}

/// True when the beginning of a file names a TM-33 or ATLA document: the root elements
/// `<IESTM33…>`, `<ATLA_S001…>`, `<LuminaireOpticalData`, or the JSON keys
/// `"FileType": "ATLA…` / an `"emitters"` array beside `"intensityDistribution"`.
pub fn names_itself(head: &[u8]) -> bool {
    let text = String::from_utf8_lossy(head);
    [
        "<IESTM33",
        "<ATLA_S001",
        "<LuminaireOpticalData",
        "\"ATLA_S001",
    ]
    .iter()
    .any(|m| text.contains(m))
        || (text.contains("\"emitters\"") && text.contains("\"header\""))
}

impl Tm33 {
    /// Reads a TM-33 or ATLA document (XML or JSON, told by its first character).
    pub fn parse(name: &str, bytes: &[u8]) -> Result<ParsedTm33, ParseError> {
        let text = std::str::from_utf8(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes))
            .map_err(|e| {
                ParseError::new(
                    name,
                    line_at(bytes, e.valid_up_to()),
                    "the file is not UTF-8 text (TM-33 and ATLA files are UTF-8)",
                )
            })?;
        let mut warnings = Vec::new();
        let mut doc = if text.trim_start().starts_with('{') {
            json::read(name, text)?
        } else {
            xml::read(name, text, &mut warnings)?
        };
        doc.fix_units(&mut warnings);
        if doc.emitters.is_empty() {
            return Err(ParseError::new(name, 0, "the file has no Emitter"));
        }
        if doc.emitters.len() > MAX_EMITTERS {
            return Err(ParseError::new(
                name,
                0,
                format!(
                    "{} emitters (at most {MAX_EMITTERS} are read)",
                    doc.emitters.len()
                ),
            ));
        }
        Ok(ParsedTm33 {
            data: doc,
            warnings,
        })
    }

    /// Turns millimetre dimensions into metres, by the dialect or, for values above 20,
    /// by their size.
    fn fix_units(&mut self, warnings: &mut Vec<String>) {
        let mm = self.dialect.millimetres();
        let guessed = !mm && self.dimensions_m.iter().any(|v| *v > 20.0);
        if guessed {
            warnings.push(format!(
                "Luminaire dimensions {} read as millimetres (above 20, too large for metres)",
                self.dimensions_m.map(super::text::show).join(" × ")
            ));
        }
        if mm || guessed {
            self.dimensions_m = self.dimensions_m.map(|v| v / 1000.0);
            for e in &mut self.emitters {
                for o in &mut e.openings {
                    o.length_m /= 1000.0;
                    o.width_m /= 1000.0;
                    o.length_offset_m /= 1000.0;
                    o.width_offset_m /= 1000.0;
                }
            }
        }
    }

    /// The spectrum of the first emitter that has one, with that emitter.
    pub fn spectrum(&self) -> Option<(&Emitter, &Spectrum)> {
        self.emitters
            .iter()
            .find_map(|e| e.spectrum.as_ref().map(|s| (e, s)))
    }

    /// The luminous openings of all emitters.
    pub fn openings(&self) -> Vec<Opening> {
        self.emitters
            .iter()
            .flat_map(|e| e.openings.iter().copied())
            .collect()
    }
}

/// The 1-based line of byte `offset` in `bytes`.
fn line_at(bytes: &[u8], offset: usize) -> usize {
    1 + bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// Parses a number of element `what` at `line`.
fn number(name: &str, line: usize, what: &str, text: &str) -> Result<f64, ParseError> {
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            ParseError::new(
                name,
                line,
                format!("{what}: expected a number, found {:?}", text.trim()),
            )
        })
}

/// One stored intensity: horizontal angle, vertical angle, value, line (0 if unknown).
type Point = (f64, f64, f64, usize);

/// An intensity table: horizontal angles, vertical angles, values by horizontal angle.
type Table = (Vec<f64>, Vec<f64>, Vec<Vec<f64>>);

/// Builds the table of an intensity element from its `(h, v, value, line)` entries: every
/// horizontal angle must have a value at every vertical angle, once.
fn grid_from_points(name: &str, element: &str, points: &[Point]) -> Result<Table, ParseError> {
    let first_line = points.first().map_or(0, |p| p.3);
    if points.is_empty() {
        return Err(ParseError::new(
            name,
            first_line,
            format!("{element}: no intensity values"),
        ));
    }
    let unique = |f: fn(&Point) -> f64| {
        let mut a: Vec<f64> = points.iter().map(f).collect();
        a.sort_by(f64::total_cmp);
        a.dedup();
        a
    };
    let horizontal = unique(|p| p.0);
    let vertical = unique(|p| p.1);
    let too_many = horizontal.len().max(vertical.len());
    if too_many > super::eulumdat::MAX_ANGLES {
        return Err(ParseError::new(
            name,
            first_line,
            format!(
                "{element}: {too_many} distinct angles (at most {} are read)",
                super::eulumdat::MAX_ANGLES
            ),
        ));
    }
    let mut values = vec![vec![f64::NAN; vertical.len()]; horizontal.len()];
    for &(h, v, value, line) in points {
        if value < 0.0 {
            return Err(ParseError::new(
                name,
                line,
                format!("{element}: negative intensity {value} at h = {h}°, v = {v}°"),
            ));
        }
        let i = horizontal.partition_point(|&x| x < h);
        let j = vertical.partition_point(|&x| x < v);
        if !values[i][j].is_nan() {
            return Err(ParseError::new(
                name,
                line,
                format!("{element}: a second value for h = {h}°, v = {v}°"),
            ));
        }
        values[i][j] = value;
    }
    for (i, row) in values.iter().enumerate() {
        if let Some(j) = row.iter().position(|x| x.is_nan()) {
            return Err(ParseError::new(
                name,
                first_line,
                format!(
                    "{element}: no value for h = {}°, v = {}° (every horizontal angle needs a value at every vertical angle)",
                    horizontal[i], vertical[j]
                ),
            ));
        }
    }
    Ok((horizontal, vertical, values))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_needs_every_pair_once() {
        let p = |h, v, x, l| (h, v, x, l);
        let ok =
            grid_from_points("f", "IntData", &[p(0.0, 0.0, 1.0, 3), p(0.0, 90.0, 2.0, 4)]).unwrap();
        assert_eq!(ok, (vec![0.0], vec![0.0, 90.0], vec![vec![1.0, 2.0]]));
        let twice = grid_from_points("f", "IntData", &[p(0.0, 0.0, 1.0, 3), p(0.0, 0.0, 2.0, 4)])
            .unwrap_err();
        assert_eq!(twice.line, 4);
        let hole = grid_from_points(
            "f",
            "IntData",
            &[
                p(0.0, 0.0, 1.0, 3),
                p(90.0, 0.0, 1.0, 4),
                p(0.0, 10.0, 1.0, 5),
            ],
        )
        .unwrap_err();
        assert!(hole.message.contains("h = 90°, v = 10°"), "{hole}");
    }

    #[test]
    fn documents_are_told_by_their_first_character() {
        assert!(looks_like(b"\xEF\xBB\xBF  <?xml"));
        assert!(looks_like(b"\n{\"a\":1}"));
        assert!(!looks_like(b"IESNA:LM-63-2002"));
    }
}
