//! Sky luminance distributions: the 15 CIE standard general skies of ISO 15469 / CIE S 011
//! (a gradation function of the zenith angle times a scattering indicatrix of the angle
//! from the sun), the traditional CIE standard overcast sky (Moon & Spencer 1942: the sky
//! of daylight factors and vertical sky components, Radiance's `gensky -c`) and a uniform
//! sky (the textbook case of configuration factors). Each gives luminance relative to the
//! zenith's; [`super::sky::Sky`] scales it to a horizontal illuminance.

use std::f64::consts::FRAC_PI_2;

/// ISO 15469 Table 1: gradation groups I–VI as (a, b).
const GRADATION: [(f64, f64); 6] = [
    (4.0, -0.70),
    (1.1, -0.8),
    (0.0, -1.0),
    (-1.0, -0.55),
    (-1.0, -0.32),
    (-1.0, -0.15),
];

/// ISO 15469 Table 1: indicatrix groups 1–6 as (c, d, e).
const INDICATRIX: [(f64, f64, f64); 6] = [
    (0.0, -1.0, 0.0),
    (2.0, -1.5, 0.15),
    (5.0, -2.5, 0.30),
    (10.0, -3.0, 0.45),
    (16.0, -3.0, 0.30),
    (24.0, -2.8, 0.15),
];

/// ISO 15469 Table 2: the (gradation, indicatrix) group of each sky type 1–15 (1-based
/// group numbers).
const TYPES: [(usize, usize); 15] = [
    (1, 1),
    (1, 2),
    (2, 1),
    (2, 2),
    (3, 1),
    (3, 2),
    (3, 3),
    (3, 4),
    (4, 2),
    (4, 3),
    (4, 4),
    (5, 4),
    (5, 5),
    (6, 5),
    (6, 6),
];

/// The angular shape of a sky.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SkyDistribution {
    /// The same luminance in every direction above the horizon.
    Uniform,
    /// The traditional CIE standard overcast sky: L(Z) = L_z (1 + 2 cos Z) / 3.
    CieOvercast,
    /// CIE standard general sky type 1–15 (1: overcast, steep gradation; 12: clear, low
    /// turbidity; 15: clear, turbid).
    CieGeneral(u8),
}

impl SkyDistribution {
    /// Reads a scene file's `sky.model`: `uniform`, `cie-overcast` (the traditional CIE
    /// standard overcast sky), `cie-clear` (general sky type 12) or `cie:1` … `cie:15`.
    pub fn parse(text: &str) -> Result<SkyDistribution, String> {
        let t = text.trim().to_ascii_lowercase();
        match t.as_str() {
            "uniform" => return Ok(SkyDistribution::Uniform),
            "cie-overcast" => return Ok(SkyDistribution::CieOvercast),
            "cie-clear" => return Ok(SkyDistribution::CieGeneral(12)),
            _ => {}
        }
        t.strip_prefix("cie:")
            .and_then(|n| n.trim().parse::<u8>().ok())
            .filter(|n| (1..=15).contains(n))
            .map(SkyDistribution::CieGeneral)
            .ok_or_else(|| {
                format!(
                    "\"{text}\" is not a sky model: use \"cie-overcast\", \"cie-clear\", \
                     \"cie:1\" … \"cie:15\" or \"uniform\""
                )
            })
    }

    /// The name as the scene file writes it.
    pub fn name(self) -> String {
        match self {
            SkyDistribution::Uniform => "uniform".into(),
            SkyDistribution::CieOvercast => "cie-overcast".into(),
            SkyDistribution::CieGeneral(n) => format!("cie:{n}"),
        }
    }

    /// Whether the distribution depends on where the sun is (it then needs a site and a
    /// time).
    pub fn needs_sun(self) -> bool {
        match self {
            SkyDistribution::Uniform | SkyDistribution::CieOvercast => false,
            SkyDistribution::CieGeneral(n) => INDICATRIX[TYPES[n as usize - 1].1 - 1].0 != 0.0,
        }
    }

    /// Luminance relative to the zenith's at zenith angle `z` (radians, < π/2) and angle
    /// `chi` from the sun, with the sun at zenith angle `z_sun` (ignored by skies that do not
    /// [`needs_sun`](Self::needs_sun)).
    pub fn relative_luminance(self, z: f64, chi: f64, z_sun: f64) -> f64 {
        match self {
            SkyDistribution::Uniform => 1.0,
            SkyDistribution::CieOvercast => (1.0 + 2.0 * z.cos()) / 3.0,
            SkyDistribution::CieGeneral(n) => {
                let (g, i) = TYPES[n as usize - 1];
                let (a, b) = GRADATION[g - 1];
                let (c, d, e) = INDICATRIX[i - 1];
                indicatrix(chi, c, d, e) * gradation(z, a, b)
                    / (indicatrix(z_sun, c, d, e) * gradation(0.0, a, b))
            }
        }
    }
}

/// ISO 15469 gradation function φ(Z) = 1 + a·exp(b / cos Z), 1 at the horizon.
pub fn gradation(z: f64, a: f64, b: f64) -> f64 {
    let cos_z = z.cos();
    if cos_z <= 0.0 {
        1.0
    } else {
        1.0 + a * (b / cos_z).exp()
    }
}

/// ISO 15469 scattering indicatrix f(χ) = 1 + c·(exp(dχ) − exp(dπ/2)) + e·cos²χ.
pub fn indicatrix(chi: f64, c: f64, d: f64, e: f64) -> f64 {
    1.0 + c * ((d * chi).exp() - (d * FRAC_PI_2).exp()) + e * chi.cos().powi(2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn models_read_by_name_and_refuse_others() {
        assert_eq!(
            SkyDistribution::parse("CIE:12"),
            Ok(SkyDistribution::CieGeneral(12))
        );
        assert_eq!(
            SkyDistribution::parse("cie-clear"),
            Ok(SkyDistribution::CieGeneral(12))
        );
        for bad in ["cie:0", "cie:16", "perez2", ""] {
            let e = SkyDistribution::parse(bad).unwrap_err();
            assert!(e.contains("cie:15"), "{e}");
        }
        for n in 1..=15 {
            let s = SkyDistribution::CieGeneral(n);
            assert_eq!(SkyDistribution::parse(&s.name()), Ok(s));
        }
    }

    /// ISO 15469's own definitions: at the zenith every sky is 1; types 1, 3 and 5 are
    /// azimuthally uniform; type 5's gradation is flat (a = 0), so its luminance is the
    /// same everywhere; type 1 at the horizon is 1 / (1 + 4 e^−0.7) = 0.3349.
    #[test]
    fn general_skies_follow_the_standard_s_formulas() {
        for n in 1..=15u8 {
            let s = SkyDistribution::CieGeneral(n);
            for z_sun in [0.2, 0.8, 1.3] {
                let l = s.relative_luminance(0.0, z_sun, z_sun);
                assert!((l - 1.0).abs() < 1e-12, "type {n}: {l}");
            }
        }
        for n in [1u8, 3, 5] {
            assert!(!SkyDistribution::CieGeneral(n).needs_sun());
        }
        assert!(SkyDistribution::CieGeneral(2).needs_sun());
        let five = SkyDistribution::CieGeneral(5);
        assert!((five.relative_luminance(1.2, 0.4, 0.7) - 1.0).abs() < 1e-12);
        let one = SkyDistribution::CieGeneral(1).relative_luminance(FRAC_PI_2, 1.0, 0.5);
        assert!(
            (one - 1.0 / (1.0 + 4.0 * (-0.7f64).exp())).abs() < 1e-6,
            "{one}"
        );
        // Type 12 near the sun is far brighter than the zenith; at Z = 0.9, 2 rad from a sun
        // at Z = 0.9 it is f(2)φ(0.9) / (f(0.9)φ(0)) = 1.0129 · 0.4024 / (1.7558 · 0.2739)
        // = 0.8475 (worked by hand from the table).
        let clear = SkyDistribution::CieGeneral(12);
        assert!(clear.relative_luminance(0.9, 0.05, 0.9) > 3.0);
        let away = clear.relative_luminance(0.9, 2.0, 0.9);
        assert!((away - 0.8475).abs() < 5e-4, "{away}");
    }

    #[test]
    fn the_traditional_overcast_sky_is_three_times_brighter_at_the_zenith() {
        let s = SkyDistribution::CieOvercast;
        assert!((s.relative_luminance(FRAC_PI_2, 0.0, 0.0) - 1.0 / 3.0).abs() < 1e-12);
        assert_eq!(s.relative_luminance(0.0, 0.0, 0.0), 1.0);
    }
}
