//! The machine-readable description of a luminaire file: what `ldt info --json` prints
//! and the Python package's `Luminaire.info` holds (one builder for both).

use serde_json::json;

use super::{LdtTexture, Luminaire};

impl Luminaire {
    /// Data, flux, ratios, peak, beam and field angles and warnings as JSON (the keys the
    /// README documents for `ldt info --json`).
    pub fn info_json(&self) -> serde_json::Value {
        let lum = self;
        let s = lum.summary();
        let grid = lum.distribution.grid();
        let tex = LdtTexture::from_distribution(&lum.distribution);
        // The values as stored (expanded by the symmetry), the same table `ldt convert`
        // writes; the distribution may have averaged unequal pole values for sampling.
        let intensities: Vec<Vec<f64>> = lum.data.expanded().into_iter().map(|p| p.1).collect();
        json!({
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
            "beam_angle_deg": s.beam_angle_deg,
            "field_angle_deg": s.field_angle_deg,
            "hemisphere": tex.hemisphere,
            "warnings": lum.warnings,
        })
    }
}
