//! A TM-33 / ATLA document to the EULUMDAT model, through the IES model (both store
//! candela at the lamps' rated lumens, or absolute candela): emitters on one angle grid are
//! summed, the declared symmetry is checked against the stored angles, and the colour data
//! and luminous openings go to the lamp set and the luminous area.

use super::{Emitter, Intensity, Tm33};
use crate::photometry::error::ParseError;
use crate::photometry::eulumdat::Eulumdat;
use crate::photometry::ies::{horizontal_symmetry, IesFile, IesVersion, Tilt};
use crate::photometry::symmetry::Symmetry;
use crate::photometry::text::show;

impl Tm33 {
    /// The luminaire in the EULUMDAT model (cd/klm), `file_name` as its file name field;
    /// notes about what was repaired or left out go to `warnings`. Errors name the file
    /// `name` and the line of the intensity data.
    pub fn to_eulumdat(
        &self,
        name: &str,
        file_name: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Eulumdat, ParseError> {
        let with_data: Vec<(usize, &Emitter, &Intensity)> = self
            .emitters
            .iter()
            .enumerate()
            .filter_map(|(i, e)| e.intensity.as_ref().map(|t| (i, e, t)))
            .collect();
        let Some(&(_, first_emitter, first)) = with_data.first() else {
            return Err(ParseError::new(
                name,
                0,
                "no emitter has intensity data (IntData or IntensityData elements): the file cannot light anything",
            ));
        };
        for (i, e) in self.emitters.iter().enumerate() {
            if e.intensity.is_none() {
                warnings.push(format!(
                    "emitter {} ({}) has no intensity data and is left out",
                    i + 1,
                    e.description
                ));
            }
        }
        check_angles(name, first)?;
        let mut candela = vec![vec![0.0; first.vertical.len()]; first.horizontal.len()];
        let mut absolute = None;
        for &(i, e, t) in &with_data {
            if t.horizontal != first.horizontal || t.vertical != first.vertical {
                return Err(ParseError::new(
                    name,
                    t.line,
                    format!(
                        "emitter {} has other angles than emitter {}: emitters are summed only on one angle grid (several grids are not supported)",
                        i + 1,
                        with_data[0].0 + 1
                    ),
                ));
            }
            let (scale, is_absolute) = self.dialect_scale(name, e, t)?;
            if absolute.is_some_and(|a| a != is_absolute) {
                return Err(ParseError::new(
                    name,
                    t.line,
                    "emitters mix absolute and relative photometry; they cannot be summed",
                ));
            }
            absolute = Some(is_absolute);
            for (row, values) in candela.iter_mut().zip(&t.values) {
                for (c, v) in row.iter_mut().zip(values) {
                    *c += v * scale;
                }
            }
        }
        let absolute = absolute.unwrap_or(false);
        if with_data.len() > 1 {
            warnings.push(format!(
                "{} emitters summed into one distribution (one photometric centre)",
                with_data.len()
            ));
        }
        if first.photometry_type == 'C' {
            stored_symmetry(name, first, warnings)?;
        } else {
            warnings.push(format!(
                "Type {} photometry converted to the C-γ frame (docs/src/design/photometry.md: beam axis at γ = 0)",
                first.photometry_type
            ));
        }
        let ies = self.as_ies(&with_data, absolute, candela);
        let mut ldt = ies.to_eulumdat(file_name);
        if !absolute && !self.dialect.per_klm() && ldt.lorl_percent < 10.0 {
            warnings.push(format!(
                "the candela integrate to only {:.1} % of the rated lumens: TM-33 stores candela at the rated lumens; values in cd/klm (as some writers store them) read this low",
                ldt.lorl_percent
            ));
        }
        let set = &mut ldt.lamp_sets[0];
        if let Some(cct) = first_emitter.cct_k {
            set.color = format!("{} K", show(cct));
        }
        if let Some(ra) = first_emitter.ra {
            set.cri = show(ra);
        }
        if let Some((length, width)) = opening_extent(self) {
            ldt.dimensions.area_length = length * 1000.0;
            ldt.dimensions.area_width = width * 1000.0;
        }
        Ok(ldt)
    }

    /// The factor from an emitter's stored values to candela, and whether they are
    /// absolute.
    fn dialect_scale(
        &self,
        name: &str,
        e: &Emitter,
        t: &Intensity,
    ) -> Result<(f64, bool), ParseError> {
        if self.dialect.per_klm() {
            let lumens = e.rated_lumens.ok_or_else(|| {
                ParseError::new(
                    name,
                    t.line,
                    "the intensities are cd/klm (this dialect's unit) but the emitter states no RatedLumens",
                )
            })?;
            return Ok((t.multiplier * lumens / 1000.0, false));
        }
        let absolute = t.absolute.unwrap_or(e.rated_lumens.is_none());
        if !absolute && e.rated_lumens.is_none() {
            return Err(ParseError::new(
                name,
                t.line,
                "relative photometry (AbsolutePhotometry false) needs the emitter's RatedLumens",
            ));
        }
        Ok((t.multiplier, absolute))
    }

    /// The IES model of the summed emitters (Type C, metres, no tilt).
    fn as_ies(
        &self,
        with_data: &[(usize, &Emitter, &Intensity)],
        absolute: bool,
        candela: Vec<Vec<f64>>,
    ) -> IesFile {
        let first = with_data[0].1;
        let lamps: u32 = with_data.iter().map(|(_, e, _)| e.quantity).sum();
        let lumens: f64 = with_data
            .iter()
            .filter_map(|(_, e, _)| e.rated_lumens)
            .sum();
        let watts: f64 = with_data.iter().filter_map(|(_, e, _)| e.input_watts).sum();
        let h = &self.header;
        let keywords = [
            ("MANUFAC", &h.manufacturer),
            ("LUMCAT", &h.catalog_number),
            ("LUMINAIRE", &h.description),
            ("TEST", &h.report_number),
            ("TESTLAB", &h.laboratory),
            ("DATE", &h.report_date),
            ("LAMP", &first.description),
        ]
        .into_iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| (k.to_string(), v.clone()))
        .collect();
        let [length, width, height] = self.dimensions_m;
        let t = with_data[0].2;
        IesFile {
            version: IesVersion::Lm63_2002,
            keywords,
            tilt: Tilt::None,
            lamp_count: f64::from(lamps),
            lumens_per_lamp: if absolute {
                -1.0
            } else {
                lumens / f64::from(lamps)
            },
            multiplier: 1.0,
            photometric_type: match t.photometry_type {
                'B' => 2,
                'A' => 3,
                _ => 1,
            },
            units: 2,
            size: [width, length, height],
            ballast_factor: 1.0,
            ballast_lamp_factor: 1.0,
            input_watts: watts,
            vertical: t.vertical.clone(),
            horizontal: t.horizontal.clone(),
            candela,
        }
    }
}

/// At least two vertical angles; Type C: vertical angles in 0–180°, horizontal angles a
/// range that LM-63 knows (0, 0–90, 0–180, 90–270, 0–360); Types B and A: angles in
/// −90–90°, starting at −90° or 0° (as LM-63 allows).
fn check_angles(name: &str, t: &Intensity) -> Result<(), ParseError> {
    let fail = |m: String| ParseError::new(name, t.line, m);
    if t.vertical.len() < 2 {
        return Err(fail(format!(
            "one vertical angle ({}°): a distribution needs at least two",
            show(t.vertical[0])
        )));
    }
    if t.photometry_type != 'C' {
        let inside = |a: &[f64]| a.iter().all(|x| (-90.0..=90.0).contains(x));
        if !(inside(&t.vertical) && inside(&t.horizontal)) {
            return Err(fail(format!(
                "Type {} angles must lie in -90–90°",
                t.photometry_type
            )));
        }
        return crate::photometry::type_b::check_ranges(&t.vertical, &t.horizontal).map_err(fail);
    }
    if t.vertical.iter().any(|v| !(0.0..=180.0).contains(v)) {
        return Err(fail("vertical angles must lie in 0–180°".into()));
    }
    if t.horizontal.iter().any(|h| !(0.0..=360.0).contains(h)) {
        return Err(fail("horizontal angles must lie in 0–360°".into()));
    }
    horizontal_symmetry(&t.horizontal).map(|_| ()).map_err(fail)
}

/// The symmetry the stored angles imply; a declared symmetry that says otherwise is noted
/// (the values exist only at the stored angles, so those decide).
fn stored_symmetry(
    name: &str,
    t: &Intensity,
    warnings: &mut Vec<String>,
) -> Result<Symmetry, ParseError> {
    let stored =
        horizontal_symmetry(&t.horizontal).map_err(|m| ParseError::new(name, t.line, m))?;
    if let Some((text, line)) = &t.symmetry {
        let key: String = text
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .collect::<String>()
            .to_ascii_uppercase();
        let declared = match key.trim_start_matches("SYMM") {
            "FULL" => Some(Symmetry::Rotational),
            "QUAD" => Some(Symmetry::Quadrant),
            "BI0" => Some(Symmetry::C0C180),
            "BI90" => Some(Symmetry::C90C270),
            "NONE" | "ARBITRARY" | "ARB" => Some(Symmetry::None),
            _ => None,
        };
        let range = format!(
            "{}°–{}°",
            show(t.horizontal[0]),
            show(t.horizontal[t.horizontal.len() - 1])
        );
        match declared {
            None => warnings.push(format!(
                "line {line}: unknown symmetry {text:?}; the horizontal angles ({range}) decide"
            )),
            Some(d) if d != stored => warnings.push(format!(
                "line {line}: symmetry {text:?} does not fit the horizontal angles {range}; read as {} (what the stored angles need)",
                stored.describe()
            )),
            Some(_) => {}
        }
    }
    Ok(stored)
}

/// Length and width of the box around all luminous openings, metres.
fn opening_extent(doc: &Tm33) -> Option<(f64, f64)> {
    let openings = doc.openings();
    if openings.is_empty() {
        return None;
    }
    let span = |lo: fn(&super::Opening) -> (f64, f64)| {
        let (a, b) = openings
            .iter()
            .map(lo)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (l, h)| {
                (a.min(l), b.max(h))
            });
        b - a
    };
    Some((
        span(|o| {
            (
                o.length_offset_m - o.length_m / 2.0,
                o.length_offset_m + o.length_m / 2.0,
            )
        }),
        span(|o| {
            (
                o.width_offset_m - o.width_m / 2.0,
                o.width_offset_m + o.width_m / 2.0,
            )
        }),
    ))
}
