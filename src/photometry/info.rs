//! The machine-readable description of a luminaire file: what `ldt info --json` prints
//! and the Python package's `Luminaire.info` holds (one builder for both).

use serde_json::json;

use super::spectral::{SpectralSummary, Spectrum};
use super::{LdtTexture, Luminaire};

impl Luminaire {
    /// Data, flux, ratios, peak, beam and field angles and warnings as JSON (the keys the
    /// reference (docs/src/reference/commands.md) documents for `ldt info --json`).
    pub fn info_json(&self) -> serde_json::Value {
        let lum = self;
        let s = lum.summary();
        let grid = lum.distribution.grid();
        let tex = LdtTexture::from_distribution(&lum.distribution);
        // The values as stored (expanded by the symmetry), the same table `ldt convert`
        // writes; the distribution may have averaged unequal pole values for sampling.
        let intensities: Vec<Vec<f64>> = lum.data.expanded().into_iter().map(|p| p.1).collect();
        let mut info = json!({
            "format": lum.format,
            "source": lum.source_label(),
            "symmetry": lum.data.symmetry.isym(),
            "ityp": lum.data.ityp,
            "company": lum.data.company,
            "luminaire_name": lum.data.luminaire_name,
            "absolute_photometry": lum.data.is_absolute(),
            "lamp_sets": lum.data.lamp_sets.iter().map(|l| json!({
                "count": l.count, "type": l.lamp_type, "flux_lm": l.flux_lm,
                "color": l.color, "cri": l.cri, "watts": l.watts})).collect::<Vec<_>>(),
            "c_angles": grid.c_angles(),
            "gamma_angles": lum.data.gamma_angles,
            "intensities": intensities,
            "max_intensity": s.max_intensity,
            "max_direction_deg": s.max_direction_deg,
            "lamp_flux_lm": s.lamp_flux_lm,
            "flux_lm": s.flux_lm,
            "lorl_declared": s.lorl_declared,
            "lorl_computed": s.lorl_computed,
            "dff_declared": s.dff_declared,
            "dff_computed": s.dff_computed,
            "cie_flux_code": super::summary::cie_flux_code(&lum.distribution),
            "beam_angle_deg": s.beam_angle_deg,
            "field_angle_deg": s.field_angle_deg,
            "hemisphere": tex.hemisphere,
            "warnings": lum.warnings,
        });
        if let Some(tm33) = lum.tm33_json() {
            info["tm33"] = tm33;
        }
        info
    }

    /// The spectrum of a TM-33 / ATLA file (the first emitter's that has one) and its
    /// figures for the whole luminaire's flux and input power.
    pub fn spectral_summary(&self) -> Option<(&Spectrum, SpectralSummary)> {
        let (_, spectrum) = self.tm33.as_ref()?.spectrum()?;
        let watts: f64 = self.data.lamp_sets.iter().map(|s| s.watts).sum();
        let flux = self.distribution.flux_lm();
        Some((spectrum, spectrum.summary(flux, Some(watts))))
    }

    /// What a TM-33 / ATLA file holds beyond the EULUMDAT model, as JSON (none for other
    /// files): its dialect, emitters, luminous openings (metres) and spectral figures.
    fn tm33_json(&self) -> Option<serde_json::Value> {
        let doc = self.tm33.as_ref()?;
        let emitters: Vec<serde_json::Value> = doc
            .emitters
            .iter()
            .map(|e| {
                json!({
                    "description": e.description,
                    "quantity": e.quantity,
                    "rated_lumens": e.rated_lumens,
                    "input_watts": e.input_watts,
                    "cct_k": e.cct_k,
                    "ra": e.ra,
                    "has_intensity": e.intensity.is_some(),
                    "spectrum": e.spectrum,
                })
            })
            .collect();
        Some(json!({
            "dialect": doc.dialect,
            "laboratory": doc.header.laboratory,
            "emitters": emitters,
            "openings": doc.openings(),
            "spectral": self.spectral_summary().map(|(_, s)| s),
        }))
    }
}

/// The columns of the catalogue table (`ldt info --csv`), one row per file.
pub const CATALOGUE_COLUMNS: [&str; 18] = [
    "path",
    "name",
    "company",
    "format",
    "isym",
    "flux_lm",
    "lamp_flux_lm",
    "lor_percent",
    "lor_declared_percent",
    "dff_percent",
    "i_max_cd_klm",
    "beam_c0_c180_deg",
    "beam_c90_c270_deg",
    "field_c0_c180_deg",
    "field_c90_c270_deg",
    "watts",
    "efficacy_lm_w",
    "warning_count",
];

impl Luminaire {
    /// This file's row of the catalogue table, in the order of [`CATALOGUE_COLUMNS`]
    /// (unquoted; an angle that does not exist and the efficacy of a file without watts
    /// are empty). `path` is the file's name as the user gave it.
    pub fn catalogue_row(&self, path: &str) -> Vec<String> {
        let s = self.summary();
        let angle = |v: Option<f64>| v.map_or(String::new(), |a| format!("{a:.1}"));
        let watts: f64 = self.data.lamp_sets.iter().map(|l| l.watts).sum();
        let efficacy = if watts > 0.0 {
            format!("{:.1}", s.flux_lm / watts)
        } else {
            String::new()
        };
        vec![
            path.to_string(),
            self.data.luminaire_name.trim().to_string(),
            self.data.company.trim().to_string(),
            self.source_label().to_string(),
            self.data.symmetry.isym().to_string(),
            format!("{:.1}", s.flux_lm),
            format!("{:.1}", s.lamp_flux_lm),
            format!("{:.2}", s.lorl_computed),
            format!("{:.2}", s.lorl_declared),
            format!("{:.2}", s.dff_computed),
            format!("{:.2}", s.max_intensity),
            angle(s.beam_angle_deg.c0_c180),
            angle(s.beam_angle_deg.c90_c270),
            angle(s.field_angle_deg.c0_c180),
            angle(s.field_angle_deg.c90_c270),
            format!("{watts}"),
            efficacy,
            self.warnings.len().to_string(),
        ]
    }
}

/// One CSV line of `fields`, each quoted where it holds a comma, a quote or a line break
/// (RFC 4180), ending in a newline.
pub fn csv_line<S: AsRef<str>>(fields: &[S]) -> String {
    let mut line = fields
        .iter()
        .map(|f| {
            let f = f.as_ref();
            if f.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", f.replace('"', "\"\""))
            } else {
                f.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(",");
    line.push('\n');
    line
}

#[cfg(test)]
mod tests {
    use super::csv_line;

    #[test]
    fn csv_quotes_only_where_needed() {
        assert_eq!(
            csv_line(&["a", "b,c", "say \"x\""]),
            "a,\"b,c\",\"say \"\"x\"\"\"\n"
        );
    }
}
