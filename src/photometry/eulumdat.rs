//! EULUMDAT (`.ldt`) reader and writer.
//!
//! Field numbers follow the format description (lines 1–26, then the lamp sets, direct
//! ratios, C angles, γ angles and intensities). Lamp sets are read set by set, six lines
//! each, as real files and the other readers do.

use super::error::ParseError;
use super::flux::integrate_flux;
use super::grid::angle_eq;
use super::symmetry::Symmetry;
use super::text::{
    check_increasing, decode_text, parse_number, show, NumberStream, SourceText, Trailing,
};

/// Largest number of C planes or γ angles accepted: a 0.1° grid, far beyond any goniometer.
pub const MAX_ANGLES: usize = 3601;
/// Largest luminaire dimension accepted, millimetres (100 km, as for IES files).
pub const MAX_SIZE_MM: f64 = 1e8;
/// Largest number of lamp sets accepted.
pub const MAX_LAMP_SETS: usize = 64;

/// One standard set of lamps (fields 26a–26f).
#[derive(Debug, Clone, PartialEq)]
pub struct LampSet {
    /// Number of lamps; negative means absolute photometry.
    pub count: i32,
    /// Type of lamps.
    pub lamp_type: String,
    /// Total luminous flux of the lamps of this set, lm.
    pub flux_lm: f64,
    /// Colour appearance / colour temperature.
    pub color: String,
    /// Colour rendering group or index.
    pub cri: String,
    /// Wattage including ballast, W.
    pub watts: f64,
}

/// Luminaire dimensions in millimetres (fields 13–21).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Dimensions {
    /// Length or diameter of the luminaire.
    pub length: f64,
    /// Width of the luminaire (0 for circular).
    pub width: f64,
    /// Height of the luminaire.
    pub height: f64,
    /// Length or diameter of the luminous area.
    pub area_length: f64,
    /// Width of the luminous area (0 for circular).
    pub area_width: f64,
    /// Height of the luminous area in the C0, C90, C180 and C270 planes.
    pub area_heights: [f64; 4],
}

/// The whole content of an EULUMDAT file, as stored (planes in file order and symmetry).
#[derive(Debug, Clone, PartialEq)]
pub struct Eulumdat {
    /// Line 1: company identification.
    pub company: String,
    /// Line 2: type indicator Ityp (0–3).
    pub ityp: u8,
    /// Line 3: symmetry indicator Isym.
    pub symmetry: Symmetry,
    /// Line 5: distance between C planes (0 for non-equidistant).
    pub dc: f64,
    /// Line 7: distance between γ angles (0 for non-equidistant).
    pub dg: f64,
    /// Line 8: measurement report number.
    pub report_number: String,
    /// Line 9: luminaire name.
    pub luminaire_name: String,
    /// Line 10: luminaire number.
    pub luminaire_number: String,
    /// Line 11: file name.
    pub file_name: String,
    /// Line 12: date / user.
    pub date_user: String,
    /// Lines 13–21.
    pub dimensions: Dimensions,
    /// Line 22: downward flux fraction, percent.
    pub dff_percent: f64,
    /// Line 23: light output ratio of the luminaire, percent.
    pub lorl_percent: f64,
    /// Line 24: conversion factor for the luminous intensities.
    pub conversion_factor: f64,
    /// Line 25: tilt of the luminaire during measurement, degrees.
    pub tilt_deg: f64,
    /// Line 26 and its sets.
    pub lamp_sets: Vec<LampSet>,
    /// Line 27: direct ratios for room indices k = 0.6 … 5.
    pub direct_ratios: [f64; 10],
    /// Line 28: all Mc C angles of the full circle, degrees.
    pub c_angles: Vec<f64>,
    /// Line 29: the Ng γ angles, degrees.
    pub gamma_angles: Vec<f64>,
    /// Line 30: intensities in cd/klm, one row per stored C plane (file order), Ng each.
    pub intensities: Vec<Vec<f64>>,
}

/// A parsed file with the warnings its reading produced.
#[derive(Debug, Clone)]
pub struct Parsed<T> {
    /// The data.
    pub data: T,
    /// Notes about things accepted with a repair (comma decimals, missing values, …).
    pub warnings: Vec<String>,
}

impl Eulumdat {
    /// Number of C planes of the full circle (Mc).
    pub fn mc(&self) -> usize {
        self.c_angles.len()
    }

    /// Number of γ angles (Ng).
    pub fn ng(&self) -> usize {
        self.gamma_angles.len()
    }

    /// True for absolute photometry (a negative lamp count).
    pub fn is_absolute(&self) -> bool {
        self.lamp_sets.iter().any(|s| s.count < 0)
    }

    /// The colour rendering index Ra the file states: the lowest over its lamp sets, none
    /// where a set states none ([`super::colour_rendering::ra_of`]).
    pub fn colour_rendering_ra(&self) -> Option<f64> {
        self.lamp_sets
            .iter()
            .map(|s| super::colour_rendering::ra_of(&s.cri))
            .try_fold(f64::INFINITY, |lo, ra| ra.map(|r| lo.min(r)))
            .filter(|r| r.is_finite())
    }

    /// Sum of the lamp fluxes of all sets, lm.
    pub fn lamp_flux_lm(&self) -> f64 {
        self.lamp_sets.iter().map(|s| s.flux_lm).sum()
    }

    /// Indices into `c_angles` of the stored planes, in file order.
    pub fn stored_plane_indices(&self) -> Vec<usize> {
        self.symmetry.stored_plane_indices(self.mc())
    }

    /// The full circle: every C angle with its intensities (cd/klm, conversion factor
    /// applied), expanded from the stored planes by the symmetry.
    pub fn expanded(&self) -> Vec<(f64, Vec<f64>)> {
        let stored = self.stored_plane_indices();
        let find = |c: f64| -> &Vec<f64> {
            match self.symmetry {
                Symmetry::Rotational => return &self.intensities[0],
                Symmetry::None => {
                    if let Some(k) = self.c_angles.iter().position(|&a| a == c) {
                        return &self.intensities[k];
                    }
                }
                _ => {}
            }
            let folded = self.symmetry.fold(c);
            let k = stored
                .iter()
                .position(|&i| angle_eq(self.c_angles[i], folded))
                .expect("plane lookup validated when parsing");
            &self.intensities[k]
        };
        let f = self.conversion_factor;
        // A rotationally symmetric file stores one plane, whatever Mc says: its table is
        // that plane (as an IES file of the same luminaire has it).
        let circle: Vec<f64> = if self.symmetry == Symmetry::Rotational {
            vec![0.0]
        } else {
            self.c_angles.clone()
        };
        circle
            .into_iter()
            .map(|c| (c, find(c).iter().map(|v| v * f).collect()))
            .collect()
    }

    /// Reads EULUMDAT bytes; `name` is used in messages.
    pub fn parse(name: &str, bytes: &[u8]) -> Result<Parsed<Eulumdat>, ParseError> {
        let (text, decode_warnings) = decode_text(bytes);
        let src = SourceText::new(name, &text, decode_warnings);
        let mut reader = HeaderReader::new(&src);
        let data = reader.read()?;
        let mut warnings = src.warnings.clone();
        warnings.extend(reader.warnings);
        Ok(Parsed { data, warnings })
    }
}

/// Reads the fixed-position header fields, tracking the line and collecting warnings.
struct HeaderReader<'a, 't> {
    src: &'a SourceText<'t>,
    line: usize,
    warnings: Vec<String>,
    comma_warned: bool,
}

impl<'a, 't> HeaderReader<'a, 't> {
    fn new(src: &'a SourceText<'t>) -> Self {
        HeaderReader {
            src,
            line: 0,
            warnings: Vec::new(),
            comma_warned: false,
        }
    }

    fn warn(&mut self, line: usize, msg: impl AsRef<str>) {
        self.warnings.push(format!("line {line}: {}", msg.as_ref()));
    }

    fn note_comma(&mut self, comma: bool) {
        if comma && !self.comma_warned {
            self.comma_warned = true;
            self.warnings
                .push("decimal commas read as decimal points".to_string());
        }
    }

    fn text(&mut self, what: &str) -> Result<String, ParseError> {
        self.line += 1;
        match self.src.lines.get(self.line - 1) {
            Some(s) => Ok(s.trim().to_string()),
            None => Err(self.src.error(
                self.line,
                format!("unexpected end of file: expected {what}"),
            )),
        }
    }

    /// The number in `s` (the current line's text).
    fn number(&mut self, s: &str, what: &str) -> Result<f64, ParseError> {
        match parse_number(s) {
            Some((v, comma)) => {
                self.note_comma(comma);
                Ok(v)
            }
            None => Err(self
                .src
                .error(self.line, format!("expected {what}, found {s:?}"))),
        }
    }

    /// A required number on its own line.
    fn required(&mut self, what: &str) -> Result<f64, ParseError> {
        let s = self.text(what)?;
        self.number(&s, what)
    }

    /// A required whole number within `lo..=hi`.
    fn integer(&mut self, what: &str, lo: i64, hi: i64) -> Result<i64, ParseError> {
        let v = self.required(what)?;
        if v.fract() != 0.0 {
            return Err(self.src.error(
                self.line,
                format!("{what} must be a whole number, found {v}"),
            ));
        }
        let v = v as i64;
        if v < lo || v > hi {
            return Err(self.src.error(
                self.line,
                format!("{what} must be between {lo} and {hi}, found {v}"),
            ));
        }
        Ok(v)
    }

    /// An optional number: an empty line becomes `default` with a warning.
    fn optional(&mut self, what: &str, default: f64) -> Result<f64, ParseError> {
        let s = self.text(what)?;
        if s.is_empty() {
            let line = self.line;
            self.warn(line, format!("{what} missing: {default} assumed"));
            return Ok(default);
        }
        self.number(&s, what)
    }

    fn read(&mut self) -> Result<Eulumdat, ParseError> {
        let company = self.text("company identification")?;
        let ityp_line = self.line + 1;
        let ityp = match self.optional("type indicator Ityp", 0.0)? {
            v if v.fract() == 0.0 && (0.0..=3.0).contains(&v) => v as u8,
            v => {
                self.warn(
                    ityp_line,
                    format!("type indicator Ityp {v} outside 0–3: 0 assumed"),
                );
                0
            }
        };
        let isym = self.integer("symmetry indicator Isym", 0, 4)?;
        let symmetry = Symmetry::from_isym(isym as u8).expect("range checked");
        let mc_line = self.line + 1;
        let mc = self.integer("number of C planes Mc", 1, MAX_ANGLES as i64)? as usize;
        if let Err(msg) = symmetry.check_plane_count(mc) {
            return Err(self.src.error(mc_line, msg));
        }
        let dc = self.optional("distance between C planes Dc", 0.0)?;
        let ng = self.integer("number of γ angles Ng", 2, MAX_ANGLES as i64)? as usize;
        let dg = self.optional("distance between γ angles Dg", 0.0)?;
        let report_number = self.text("measurement report number")?;
        let luminaire_name = self.text("luminaire name")?;
        let luminaire_number = self.text("luminaire number")?;
        let file_name = self.text("file name")?;
        let date_user = self.text("date/user")?;
        let dimensions = self.read_dimensions()?;
        let dff_percent = self.optional("downward flux fraction DFF", 0.0)?;
        let lorl_percent = self.optional("light output ratio LORL", 0.0)?;
        let conversion_factor = self.optional("conversion factor", 1.0)?;
        if conversion_factor <= 0.0 {
            return Err(self.src.error(
                self.line,
                format!(
                    "conversion factor must be positive, found {}",
                    show(conversion_factor)
                ),
            ));
        }
        let tilt_deg = self.optional("tilt during measurement", 0.0)?;
        let n_sets = self.integer("number of lamp sets", 1, MAX_LAMP_SETS as i64)? as usize;
        let lamp_sets = self.read_lamp_sets(n_sets)?;
        let first_data_line = self.line + 1;
        let mut numbers = NumberStream::new(self.src, first_data_line, &[]);
        let direct_ratios = self.read_direct_ratios(&mut numbers)?;
        let c_tokens = numbers.take(mc, "C angle")?;
        let g_tokens = numbers.take(ng, "γ angle")?;
        check_increasing(self.src, &c_tokens, 0.0..360.0, "C")?;
        // The format's C angles begin with 0° (every writer's full circle starts there).
        if c_tokens[0].value != 0.0 {
            return Err(self.src.error(
                c_tokens[0].line,
                format!(
                    "the C angles must begin with 0°, found {}",
                    show(c_tokens[0].value)
                ),
            ));
        }
        check_increasing(self.src, &g_tokens, 0.0..=180.0, "γ")?;
        let c_angles: Vec<f64> = c_tokens.iter().map(|t| t.value).collect();
        let gamma_angles: Vec<f64> = g_tokens.iter().map(|t| t.value).collect();
        let stored = symmetry.stored_plane_indices(mc);
        self.check_symmetric_angles(symmetry, &c_angles, &stored, c_tokens[0].line)?;
        let intensities = self.read_intensities(&mut numbers, stored.len(), ng)?;
        self.note_comma(numbers.saw_comma);
        let trailing = numbers.trailing();
        self.note_blank_tail();
        self.check_steps(dc, &c_angles, "Dc", 5, symmetry);
        self.check_steps(dg, &gamma_angles, "Dg", 7, symmetry);
        if lorl_percent > 100.0 + 1e-9 {
            self.warn(23, format!("LORL {lorl_percent} % exceeds 100 %"));
        }
        let data = Eulumdat {
            company,
            ityp,
            symmetry,
            dc,
            dg,
            report_number,
            luminaire_name,
            luminaire_number,
            file_name,
            date_user,
            dimensions,
            dff_percent,
            lorl_percent,
            conversion_factor,
            tilt_deg,
            lamp_sets,
            direct_ratios,
            c_angles,
            gamma_angles,
            intensities,
        };
        if let Some(t) = trailing {
            self.accept_trailing(&data, t)?;
        }
        Ok(data)
    }

    /// The nine dimension lines (mm): the luminaire, its luminous area and the area's
    /// heights at C0, C90, C180 and C270; a size no luminaire has is refused.
    fn read_dimensions(&mut self) -> Result<Dimensions, ParseError> {
        let mut dims = [0.0; 9];
        for (i, what) in [
            "luminaire length/diameter",
            "luminaire width",
            "luminaire height",
            "luminous area length/diameter",
            "luminous area width",
            "luminous area height C0",
            "luminous area height C90",
            "luminous area height C180",
            "luminous area height C270",
        ]
        .iter()
        .enumerate()
        {
            dims[i] = self.optional(what, 0.0)?;
        }
        if let Some(k) = dims.iter().position(|d| d.abs() > MAX_SIZE_MM) {
            return Err(self.src.error(
                13 + k,
                format!("{} mm is not the size of a luminaire", show(dims[k])),
            ));
        }
        Ok(Dimensions {
            length: dims[0],
            width: dims[1],
            height: dims[2],
            area_length: dims[3],
            area_width: dims[4],
            area_heights: [dims[5], dims[6], dims[7], dims[8]],
        })
    }

    /// `n_sets` lamp sets (count, type, flux, colour, rendering, watts); refused when every
    /// set's flux is 0 (the intensities, cd/klm, could not become candela).
    fn read_lamp_sets(&mut self, n_sets: usize) -> Result<Vec<LampSet>, ParseError> {
        let mut lamp_sets = Vec::with_capacity(n_sets);
        let first_lamp_line = self.line + 1;
        for k in 1..=n_sets {
            let count_line = self.line + 1;
            let count = self.required(&format!("number of lamps of set {k}"))?;
            if count.fract() != 0.0 || count.abs() > 1e6 {
                return Err(self.src.error(
                    count_line,
                    format!("number of lamps of set {k} must be a whole number, found {count}"),
                ));
            }
            let lamp_type = self.text(&format!("lamp type of set {k}"))?;
            let flux_line = self.line + 1;
            let flux_lm = self.required(&format!("lamp flux of set {k}"))?;
            if flux_lm < 0.0 {
                return Err(self.src.error(
                    flux_line,
                    format!("lamp flux of set {k} is negative ({flux_lm})"),
                ));
            }
            let color = self.text(&format!("colour temperature of set {k}"))?;
            let cri = self.text(&format!("colour rendering of set {k}"))?;
            let watts = self.optional(&format!("wattage of set {k}"), 0.0)?;
            lamp_sets.push(LampSet {
                count: count as i32,
                lamp_type,
                flux_lm,
                color,
                cri,
                watts,
            });
        }
        if lamp_sets.iter().map(|s| s.flux_lm).sum::<f64>() <= 0.0 {
            return Err(self.src.error(
                first_lamp_line + 2,
                "the lamp flux of every set is 0: the intensities (cd/klm) cannot become candela",
            ));
        }
        Ok(lamp_sets)
    }

    /// The ten direct ratios; EULUMDAT is line-oriented, so a blank line is an empty
    /// field (0, with a warning), not nothing.
    fn read_direct_ratios(
        &mut self,
        numbers: &mut NumberStream<'_, '_>,
    ) -> Result<[f64; 10], ParseError> {
        let mut direct_ratios = [0.0; 10];
        let mut blank_ratios = Vec::new();
        for (i, r) in direct_ratios.iter_mut().enumerate() {
            match numbers.next_or_blank(&format!("direct ratio {}", i + 1))? {
                Some(t) => *r = t.value,
                None => blank_ratios.push(numbers.line()),
            }
        }
        if let (Some(first), Some(last)) = (blank_ratios.first(), blank_ratios.last()) {
            self.warnings.push(format!(
                "lines {first}–{last}: {} direct ratio(s) blank: read as empty fields (0)",
                blank_ratios.len()
            ));
        }
        Ok(direct_ratios)
    }

    /// `planes` × `ng` intensities (cd/klm), none negative; a short table says how many
    /// were expected and found.
    fn read_intensities(
        &mut self,
        numbers: &mut NumberStream<'_, '_>,
        planes: usize,
        ng: usize,
    ) -> Result<Vec<Vec<f64>>, ParseError> {
        let expected = planes * ng;
        let mut flat = Vec::with_capacity(expected.min(self.src.lines.len() * 8));
        for found in 0..expected {
            let t = numbers.next("intensity").map_err(|e| {
                if e.message.starts_with("unexpected end") {
                    self.src.error(
                        e.line,
                        format!(
                            "unexpected end of file: expected {expected} intensities ({} stored planes × {ng} γ angles), found {found}",
                            planes
                        ),
                    )
                } else {
                    e
                }
            })?;
            if t.value < 0.0 {
                return Err(self
                    .src
                    .error(t.line, format!("negative intensity {}", t.value)));
            }
            flat.push(t.value);
        }
        Ok(flat.chunks(ng).map(<[f64]>::to_vec).collect())
    }

    /// Blank lines at the end of the file: ignored, with a warning.
    fn note_blank_tail(&mut self) {
        let blank_tail = self
            .src
            .lines
            .iter()
            .rev()
            .take_while(|l| l.trim().is_empty())
            .count();
        if blank_tail > 0 {
            self.warnings
                .push(format!("{blank_tail} trailing blank line(s) ignored"));
        }
    }

    /// Data after the table is accepted with a warning when it cannot be misread table
    /// data: end markers and words always; numbers only when the table as read reproduces
    /// the declared LORL (so the header's counts did not cut the table short).
    fn accept_trailing(&mut self, data: &Eulumdat, t: Trailing) -> Result<(), ParseError> {
        let announced = format!(
            "Isym {} × Mc {} × Ng {} announce {} values",
            data.symmetry.isym(),
            data.mc(),
            data.ng(),
            data.stored_plane_indices().len() * data.ng()
        );
        if t.numbers > 0 {
            let lorl = integrate_flux(&data.expanded(), &data.gamma_angles).0 / 10.0;
            let agrees = data.lorl_percent > 0.0
                && (lorl - data.lorl_percent).abs() <= 0.01 * data.lorl_percent.max(1.0);
            if !agrees {
                return Err(self.src.error(
                    t.first_line,
                    format!(
                        "more data than {announced}: {} follow the table, and the table as read gives LORL {lorl:.2} % against {} % declared, so the counts may be wrong",
                        t.describe(),
                        data.lorl_percent
                    ),
                ));
            }
        }
        self.warn(
            t.first_line,
            format!(
                "{} after the table ignored ({announced}{})",
                t.describe(),
                if t.numbers > 0 {
                    "; the table reproduces the declared LORL"
                } else {
                    ""
                }
            ),
        );
        Ok(())
    }

    /// Every plane of the full circle must fold onto a stored plane.
    fn check_symmetric_angles(
        &self,
        symmetry: Symmetry,
        c: &[f64],
        stored: &[usize],
        line: usize,
    ) -> Result<(), ParseError> {
        if matches!(symmetry, Symmetry::Rotational | Symmetry::None) {
            return Ok(());
        }
        for &angle in c {
            let folded = symmetry.fold(angle);
            if !stored.iter().any(|&i| angle_eq(c[i], folded)) {
                return Err(self.src.error(
                    line,
                    format!(
                        "C angle {angle}° has no stored mirror plane at C{folded} for Isym {}",
                        symmetry.isym()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Declared steps that disagree with the angles get a warning (the angles win).
    fn check_steps(&mut self, step: f64, angles: &[f64], name: &str, line: usize, sym: Symmetry) {
        if step == 0.0 || angles.len() < 2 || (name == "Dc" && sym == Symmetry::Rotational) {
            return;
        }
        let uniform = angles
            .windows(2)
            .all(|w| ((w[1] - w[0]) - step).abs() < 1e-3);
        if !uniform {
            self.warn(
                line,
                format!("{name} = {step} disagrees with the listed angles: the angles are used"),
            );
        }
    }
}
