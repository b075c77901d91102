//! Converting a luminaire between the four file formats — EULUMDAT, IES LM-63, TM-33-23
//! XML and ATLA S001 JSON — with the list of what each conversion loses.

use std::path::Path;

use super::ies::write_ies;
use super::tm33::{self, Dialect};
use super::{Luminaire, PhotometryError};

/// A format `ldt convert` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum OutputFormat {
    /// EULUMDAT (`.ldt`).
    Ldt,
    /// IES LM-63-2002 (`.ies`).
    Ies,
    /// ANSI/IES TM-33-23 XML (`.xml`).
    Tm33,
    /// ATLA S001 JSON (`.json`).
    Atla,
}

impl OutputFormat {
    /// The file extension, without the dot.
    pub fn ext(self) -> &'static str {
        match self {
            OutputFormat::Ldt => "ldt",
            OutputFormat::Ies => "ies",
            OutputFormat::Tm33 => "xml",
            OutputFormat::Atla => "json",
        }
    }

    /// The format a path's extension names (any letter case).
    pub fn of_path(path: &Path) -> Option<OutputFormat> {
        OutputFormat::of_ext(&path.extension()?.to_string_lossy())
    }

    /// The format an extension (without the dot, any letter case) names.
    pub fn of_ext(ext: &str) -> Option<OutputFormat> {
        [
            OutputFormat::Ldt,
            OutputFormat::Ies,
            OutputFormat::Tm33,
            OutputFormat::Atla,
        ]
        .into_iter()
        .find(|f| f.ext().eq_ignore_ascii_case(ext))
    }

    /// The format's name.
    pub fn label(self) -> &'static str {
        match self {
            OutputFormat::Ldt => "EULUMDAT",
            OutputFormat::Ies => "IES LM-63",
            OutputFormat::Tm33 => "TM-33-23 XML",
            OutputFormat::Atla => "ATLA S001 JSON",
        }
    }
}

/// A converted file: its text, notes about how fields were fitted, and what the target
/// format could not hold.
#[derive(Debug, Clone)]
pub struct Converted {
    /// The file's content.
    pub text: String,
    /// How values were fitted to the format (EULUMDAT's field widths).
    pub notes: Vec<String>,
    /// What the conversion loses: data of the source the target cannot hold.
    pub losses: Vec<String>,
}

/// Converts `lum` to `to`. For EULUMDAT, `exact` prints every number exactly and every
/// text in full instead of fitting the format's field widths (which may refuse data that
/// does not fit, naming the field).
pub fn convert(
    lum: &Luminaire,
    to: OutputFormat,
    exact: bool,
) -> Result<Converted, PhotometryError> {
    let mut notes = Vec::new();
    let text = match to {
        OutputFormat::Ies => write_ies(&lum.data, lum.source_label()),
        OutputFormat::Ldt if exact => lum.data.to_ldt_string(),
        OutputFormat::Ldt => {
            let ldt = lum
                .data
                .to_ldt_standard()
                .map_err(|e| PhotometryError::Invalid(e.to_string()))?;
            notes = ldt.notes;
            ldt.text
        }
        OutputFormat::Tm33 => tm33::to_tm33_xml(&document(lum, Dialect::Tm33Xml)),
        OutputFormat::Atla => tm33::to_atla_json(&document(lum, Dialect::AtlaJson)),
    };
    Ok(Converted {
        text,
        notes,
        losses: losses(lum, to),
    })
}

/// The TM-33 document written for `lum`: its distribution, names and lamps, with the
/// spectrum, luminous openings, colour data and laboratory of a TM-33 source kept.
fn document(lum: &Luminaire, dialect: Dialect) -> tm33::Tm33 {
    let mut doc = tm33::from_eulumdat(&lum.data, dialect);
    if let Some(src) = &lum.tm33 {
        doc.header.laboratory = src.header.laboratory.clone();
        let e = &mut doc.emitters[0];
        if let Some((from, spectrum)) = src.spectrum() {
            e.spectrum = Some(spectrum.clone());
            e.cct_k = from.cct_k.or(e.cct_k);
        }
        e.openings = src.openings();
    }
    doc
}

/// What converting `lum` to `to` loses, in words (empty when nothing).
pub fn losses(lum: &Luminaire, to: OutputFormat) -> Vec<String> {
    let d = &lum.data;
    let mut lost = Vec::new();
    let tm33_target = matches!(to, OutputFormat::Tm33 | OutputFormat::Atla);
    if let Some(src) = &lum.tm33 {
        let with_data = src
            .emitters
            .iter()
            .filter(|e| e.intensity.is_some())
            .count();
        if with_data > 1 {
            lost.push(format!(
                "{with_data} emitters are written as one (their summed distribution)"
            ));
        }
        if !tm33_target {
            if src.spectrum().is_some() {
                lost.push(
                    "the spectral distribution (and the melanopic and PPF figures drawn from it)"
                        .into(),
                );
            }
            if src.openings().len() > 1 {
                lost.push(format!(
                    "the {} luminous openings become one luminous area around them",
                    src.openings().len()
                ));
            }
            if !src.header.laboratory.is_empty() {
                lost.push("the test laboratory".into());
            }
        }
    }
    if d.direct_ratios.iter().any(|r| *r != 0.0) && to != OutputFormat::Ldt {
        lost.push(
            "the direct ratios (EULUMDAT field 27; recomputable from the distribution)".into(),
        );
    }
    if d.lamp_sets.len() > 1 && to != OutputFormat::Ldt {
        lost.push(format!(
            "{} lamp sets become one lamp set (their fluxes and watts summed)",
            d.lamp_sets.len()
        ));
    }
    if d.dimensions.area_heights.iter().any(|h| *h != 0.0) && to != OutputFormat::Ldt {
        lost.push("the luminous area's heights in the C0/C90/C180/C270 planes".into());
    }
    if to == OutputFormat::Ies {
        let set = d.lamp_sets.first();
        if set.is_some_and(|s| !s.color.is_empty() || !s.cri.is_empty()) {
            lost.push("the lamps' colour and colour rendering".into());
        }
        if d.dimensions.area_length > 0.0
            && (d.dimensions.area_length != d.dimensions.length
                || d.dimensions.area_width != d.dimensions.width)
        {
            lost.push("the luminous area where it differs from the luminaire's size".into());
        }
    }
    if d.is_absolute()
        && matches!(
            to,
            OutputFormat::Tm33 | OutputFormat::Atla | OutputFormat::Ies
        )
    {
        let flux = lum.distribution.flux_lm();
        if (d.lamp_flux_lm() - flux).abs() > 1e-6 * flux {
            lost.push(format!(
                "the lamp flux an absolute-photometry file states ({} lm): absolute photometry carries none, and reading it back gives the luminaire's {} lm",
                super::text::show(d.lamp_flux_lm()),
                super::text::show(flux)
            ));
        }
    }
    if d.symmetry == super::Symmetry::Rotational && d.mc() > 1 && to != OutputFormat::Ldt {
        lost.push(format!(
            "the {} C angles a rotationally symmetric EULUMDAT file lists (one plane is written: the same distribution)",
            d.mc()
        ));
    }
    if d.tilt_deg != 0.0 && to != OutputFormat::Ldt {
        lost.push(format!("the measurement tilt of {}°", d.tilt_deg));
    }
    if lum
        .ies
        .as_ref()
        .is_some_and(|ies| !matches!(ies.tilt, super::ies::Tilt::None))
    {
        lost.push("the IES tilt table".into());
    }
    lost
}
