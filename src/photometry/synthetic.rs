//! Luminaires made from a formula rather than a file: rotationally symmetric
//! distributions (the isotropic source behind the sun light, glTF's point and spot
//! lights), written as the EULUMDAT data every other path reads.

use super::distribution::Distribution;
use super::eulumdat::{Eulumdat, LampSet};
use super::Symmetry;
use super::{Format, Luminaire};

/// A rotationally symmetric luminaire named `name` with `candela[k]` cd at
/// `gamma_deg[k]` (ascending from 0 to 180), its lamp flux the flux of that distribution
/// (the trapezoid rule over γ, the integral the distribution's interpolation gives).
/// `None` when it emits nothing or the angles are not an ascending 0…180 list.
pub fn rotational(name: &str, gamma_deg: &[f64], candela: &[f64]) -> Option<Luminaire> {
    let ascending = gamma_deg.windows(2).all(|w| w[0] < w[1]);
    if gamma_deg.len() != candela.len()
        || gamma_deg.first() != Some(&0.0)
        || gamma_deg.last() != Some(&180.0)
        || !ascending
        || candela.iter().any(|c| !(c.is_finite() && *c >= 0.0))
    {
        return None;
    }
    let flux: f64 = gamma_deg
        .windows(2)
        .zip(candela.windows(2))
        .map(|(g, i)| {
            // ∫ I sin γ dγ over the interval, I linear in γ (exact for a linear I).
            let (a, b) = (g[0].to_radians(), g[1].to_radians());
            let h = b - a;
            let (ia, ib) = (i[0], i[1]);
            // ∫_a^b (ia + s(γ − a)) sin γ dγ = ia(cos a − cos b) + s(sin b − sin a − h cos b)
            let slope = (ib - ia) / h;
            ia * (a.cos() - b.cos()) + slope * (b.sin() - a.sin() - h * b.cos())
        })
        .sum::<f64>()
        * std::f64::consts::TAU;
    if !(flux.is_finite() && flux > 0.0) {
        return None;
    }
    let per_klm = 1000.0 / flux;
    let data = Eulumdat {
        company: "goniolight".into(),
        ityp: 1,
        symmetry: Symmetry::Rotational,
        dc: 0.0,
        dg: equal_step(gamma_deg),
        report_number: String::new(),
        luminaire_name: name.into(),
        luminaire_number: String::new(),
        file_name: name.into(),
        date_user: String::new(),
        dimensions: Default::default(),
        dff_percent: 50.0,
        lorl_percent: 100.0,
        conversion_factor: 1.0,
        tilt_deg: 0.0,
        lamp_sets: vec![LampSet {
            count: 1,
            lamp_type: name.into(),
            flux_lm: flux,
            color: String::new(),
            cri: String::new(),
            watts: 0.0,
        }],
        direct_ratios: [0.0; 10],
        c_angles: vec![0.0],
        gamma_angles: gamma_deg.to_vec(),
        intensities: vec![candela.iter().map(|c| c * per_klm).collect()],
    };
    let (distribution, warnings) = Distribution::from_eulumdat(&data);
    Some(Luminaire {
        format: Format::Eulumdat,
        data,
        ies: None,
        tm33: None,
        distribution,
        warnings,
    })
}

/// The step of equally spaced angles, 0 for others (EULUMDAT's Dg).
fn equal_step(angles: &[f64]) -> f64 {
    let step = angles[1] - angles[0];
    let equal = angles
        .windows(2)
        .all(|w| ((w[1] - w[0]) - step).abs() < 1e-9);
    if equal {
        step
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::Interp;

    #[test]
    fn an_isotropic_source_has_four_pi_times_its_intensity() {
        let l = rotational("point", &[0.0, 90.0, 180.0], &[100.0; 3]).unwrap();
        let flux = l.data.lamp_sets[0].flux_lm;
        assert!((flux - 400.0 * std::f64::consts::PI).abs() < 1e-9, "{flux}");
        assert!((l.distribution.candela(30.0, 47.0, Interp::Bilinear, 1.0) - 100.0).abs() < 1e-9);
        assert!((l.distribution.flux_lm() - flux).abs() < 1e-6 * flux);
    }

    #[test]
    fn a_linear_ramp_integrates_exactly() {
        // I = 100 (1 − γ/π) on 0…180°: Φ = 2π·100·∫(1 − γ/π) sin γ dγ = 2π·100·(2 − 1) .
        let g: Vec<f64> = vec![0.0, 180.0];
        let l = rotational("ramp", &g, &[100.0, 0.0]).unwrap();
        let expected = std::f64::consts::TAU * 100.0;
        let flux = l.data.lamp_sets[0].flux_lm;
        assert!(
            (flux - expected).abs() < 1e-9 * expected,
            "{flux} vs {expected}"
        );
        assert!(rotational("dark", &g, &[0.0, 0.0]).is_none());
        assert!(rotational("bad", &[0.0, 90.0], &[1.0, 1.0]).is_none());
    }
}
