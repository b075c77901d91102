//! A luminaire's summary for people: one list of labelled rows, which `ldt info` prints
//! as text and the datasheet sets as its first table.

use crate::photometry::luminance::lamp_set_flux;
use crate::photometry::summary::cie_flux_code;
use crate::photometry::{Luminaire, PhotometryError};

/// The labelled rows of a luminaire's summary; the flux, efficacy and candela for lamp
/// set `lamp_set` (all sets summed without one).
pub fn summary_rows(
    lum: &Luminaire,
    lamp_set: Option<usize>,
) -> Result<Vec<(String, String)>, PhotometryError> {
    let d = &lum.data;
    let s = lum.summary();
    let lamp_flux = match lamp_set {
        Some(_) => lamp_set_flux(lum, lamp_set)?,
        None => s.lamp_flux_lm,
    };
    let flux = s.lorl_computed / 100.0 * lamp_flux;
    let grid = lum.distribution.grid();
    let angle = |v: Option<f64>| v.map_or("—".to_string(), |a| format!("{a:.1}°"));
    let name = d.luminaire_name.trim();
    let mut rows: Vec<(String, String)> = Vec::new();
    let mut row = |label: &str, value: String| rows.push((label.to_string(), value));
    row(
        "luminaire",
        format!(
            "{}{}",
            if name.is_empty() { "(no name)" } else { name },
            match d.company.trim() {
                "" => String::new(),
                c => format!(" — {c}"),
            }
        ),
    );
    row(
        "data",
        format!(
            "{}, Isym {} ({}), {} C planes × {} γ angles{}",
            lum.source_label(),
            d.symmetry.isym(),
            d.symmetry.describe(),
            grid.c_angles().len(),
            grid.gamma_angles().len(),
            if d.is_absolute() {
                ", absolute photometry"
            } else {
                ""
            }
        ),
    );
    let dims = &d.dimensions;
    row(
        "dimensions",
        format!(
            "luminaire {}; luminous area {}",
            outline(dims.length, dims.width, Some(dims.height)),
            luminous_area(dims)
        ),
    );
    for (i, l) in d.lamp_sets.iter().enumerate() {
        let chosen = if lamp_set == Some(i + 1) {
            "  ← used"
        } else {
            ""
        };
        row(
            &format!("lamp set {}", i + 1),
            format!(
                "{} × {} — {}, {} W{chosen}",
                l.count.abs(),
                l.lamp_type.trim(),
                lumens(l.flux_lm),
                round_to(l.watts, 1)
            ),
        );
    }
    row(
        "flux",
        format!("{} from {} of lamps", lumens(flux), lumens(lamp_flux)),
    );
    let watts: f64 = match lamp_set {
        Some(k) => d.lamp_sets.get(k - 1).map_or(0.0, |l| l.watts),
        None => d.lamp_sets.iter().map(|l| l.watts).sum(),
    };
    if watts > 0.0 {
        row("efficacy", format!("{:.1} lm/W", flux / watts));
    }
    row(
        "LOR",
        format!(
            "{:.1} % (declared {:.1} %)",
            s.lorl_computed, s.lorl_declared
        ),
    );
    let direction = match s.dff_computed {
        v if v >= 99.95 => "downward only",
        v if v <= 0.05 => "upward only",
        v if v >= 60.0 => "mostly downward",
        v if v <= 40.0 => "mostly upward",
        _ => "up and down",
    };
    row(
        "DFF",
        format!(
            "{:.1} % (declared {:.1} %): {direction}",
            s.dff_computed, s.dff_declared
        ),
    );
    if let Some(c) = cie_flux_code(&lum.distribution) {
        row(
            "CIE flux code",
            format!("{} {} {} {} {}", c[0], c[1], c[2], c[3], c[4]),
        );
    }
    row(
        "I_max",
        format!(
            "{} cd/klm ({} cd) at C {:.1}°, γ {:.1}°",
            round_to(s.max_intensity, 1),
            round_to(s.max_intensity * lamp_flux / 1000.0, 0),
            s.max_direction_deg[0],
            s.max_direction_deg[1]
        ),
    );
    for (label, pair) in [
        ("beam (50 %)", &s.beam_angle_deg),
        ("field (10 %)", &s.field_angle_deg),
    ] {
        row(
            label,
            format!(
                "{} in C0–C180, {} in C90–C270",
                angle(pair.c0_c180),
                angle(pair.c90_c270)
            ),
        );
    }
    tm33_rows(lum, &mut row);
    Ok(rows)
}

/// The rows only a TM-33 / ATLA file fills: emitters, luminous openings, the spectrum and
/// what it says (melanopic DER; PPF and photon efficacy).
fn tm33_rows(lum: &Luminaire, row: &mut impl FnMut(&str, String)) {
    let Some(doc) = &lum.tm33 else {
        return;
    };
    let with_data = doc
        .emitters
        .iter()
        .filter(|e| e.intensity.is_some())
        .count();
    if doc.emitters.len() > 1 {
        row(
            "emitters",
            format!(
                "{} ({with_data} with intensity data, summed)",
                doc.emitters.len()
            ),
        );
    }
    let openings = doc.openings();
    if !openings.is_empty() {
        let list: Vec<String> = openings
            .iter()
            .map(|o| {
                format!(
                    "{} × {} mm at ({}, {}) mm",
                    round_to(o.length_m * 1000.0, 1),
                    round_to(o.width_m * 1000.0, 1),
                    round_to(o.length_offset_m * 1000.0, 1),
                    round_to(o.width_offset_m * 1000.0, 1)
                )
            })
            .collect();
        row("openings", list.join("; "));
    }
    if let Some((spectrum, figures)) = lum.spectral_summary() {
        let w = &spectrum.wavelengths_nm;
        row(
            "spectrum",
            format!(
                "{}–{} nm, {} values; melanopic DER {:.3}; {:.0} lm/W of radiation",
                round_to(w[0], 1),
                round_to(w[w.len() - 1], 1),
                w.len(),
                figures.melanopic_der,
                figures.luminous_efficacy_of_radiation_lm_per_w
            ),
        );
        if let Some(ppf) = figures.ppf_umol_per_s {
            let efficacy = figures
                .photon_efficacy_umol_per_j
                .map_or(String::new(), |e| {
                    format!(", photon efficacy {e:.2} µmol/J")
                });
            row("PPF", format!("{ppf:.1} µmol/s (400–700 nm){efficacy}"));
        }
    }
}

/// `v` rounded to `digits` decimals, without trailing zeros.
fn round_to(v: f64, digits: usize) -> String {
    let text = format!("{v:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// A flux as people read it: whole lumens from 100 lm up, one decimal below.
fn lumens(v: f64) -> String {
    if v.abs() >= 100.0 {
        format!("{v:.0} lm")
    } else {
        format!("{} lm", round_to(v, 1))
    }
}

/// A rectangle L × W (× H) mm, or a disc Ø L mm when the width is 0; "none" for zeros.
fn outline(length: f64, width: f64, height: Option<f64>) -> String {
    if length <= 0.0 && width <= 0.0 {
        return "not given".into();
    }
    let h = height
        .filter(|h| *h > 0.0)
        .map_or(String::new(), |h| format!(", height {} mm", round_to(h, 1)));
    if width <= 0.0 {
        format!("Ø {} mm{h}", round_to(length, 1))
    } else {
        format!("{} × {} mm{h}", round_to(length, 1), round_to(width, 1))
    }
}

fn luminous_area(d: &crate::photometry::eulumdat::Dimensions) -> String {
    let base = outline(d.area_length, d.area_width, None);
    if d.area_heights.iter().all(|h| *h <= 0.0) {
        return base;
    }
    let [a, b, c, e] = d.area_heights.map(|h| round_to(h, 1));
    format!("{base}, side heights C0/C90/C180/C270 {a}/{b}/{c}/{e} mm")
}
