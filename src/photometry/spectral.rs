//! Spectral quantities of a luminaire's relative spectral distribution: the melanopic
//! daylight efficacy ratio (CIE S 026) and, for horticultural lighting, the photosynthetic
//! photon flux (PPF, 400–700 nm) and photon efficacy.
//!
//! The tables are the standards' published values every 5 nm from 380 to 780 nm: the CIE
//! photopic luminous efficiency function V(λ) (CIE 1924, ISO 23539/CIE S 010) and the
//! melanopic action spectrum s_mel(λ) of CIE S 026/E:2018, Table 2 (CIE 2018, "CIE alpha-opic
//! action spectra", DOI 10.25039/CIE.DS.vqqhzp5a). Between samples they are interpolated
//! linearly, as the spectrum is.

/// Maximum luminous efficacy of radiation for photopic vision, lm/W.
pub const KM_LM_PER_W: f64 = 683.002;
/// Melanopic efficacy of luminous radiation of CIE standard illuminant D65, W/lm
/// (CIE S 026: 1.3262 mW/lm).
pub const K_MEL_D65_W_PER_LM: f64 = 1.3262e-3;
/// Planck constant × speed of light × Avogadro constant, J·m/mol: the energy of one mole of
/// photons of wavelength 1 m.
const HC_NA: f64 = 6.626_070_15e-34 * 299_792_458.0 * 6.022_140_76e23;

/// First wavelength of the tables, nm.
const TABLE_START_NM: f64 = 380.0;
/// Step of the tables, nm.
const TABLE_STEP_NM: f64 = 5.0;

/// V(λ), 380–780 nm every 5 nm.
const V_LAMBDA: [f64; 81] = [
    0.000039, 0.000064, 0.00012, 0.000217, 0.000396, 0.00064, 0.00121, 0.00218, 0.004, 0.0073,
    0.0116, 0.01684, 0.023, 0.0298, 0.038, 0.048, 0.06, 0.0739, 0.09098, 0.1126, 0.13902, 0.1693,
    0.20802, 0.2586, 0.323, 0.4073, 0.503, 0.6082, 0.71, 0.7932, 0.862, 0.91485, 0.954, 0.9803,
    0.99495, 1.0, 0.995, 0.9786, 0.952, 0.9154, 0.87, 0.8163, 0.757, 0.6949, 0.631, 0.5668, 0.503,
    0.4412, 0.381, 0.321, 0.265, 0.217, 0.175, 0.1382, 0.107, 0.0816, 0.061, 0.04458, 0.032,
    0.0232, 0.017, 0.01192, 0.00821, 0.005723, 0.004102, 0.002929, 0.002091, 0.001484, 0.001047,
    0.00074, 0.00052, 0.000361, 0.000249, 0.000172, 0.00012, 0.000085, 0.00006, 0.000042, 0.00003,
    0.000021, 0.000015,
];

/// s_mel(λ), 380–780 nm every 5 nm (CIE S 026, peak 1 at 490 nm).
const S_MEL: [f64; 81] = [
    9.18165e-4, 1.66724e-3, 3.09442e-3, 5.88035e-3, 1.14277e-2, 2.28112e-2, 4.61550e-2, 7.94766e-2,
    1.37237e-1, 1.87096e-1, 2.53865e-1, 3.20679e-1, 4.01587e-1, 4.74002e-1, 5.53715e-1, 6.29654e-1,
    7.08049e-1, 7.85216e-1, 8.60291e-1, 9.17734e-1, 9.65605e-1, 9.90621e-1, 1.0, 9.92022e-1,
    9.65952e-1, 9.22299e-1, 8.62888e-1, 7.85233e-1, 6.99628e-1, 6.09422e-1, 5.19309e-1, 4.32533e-1,
    3.51707e-1, 2.79135e-1, 2.15722e-1, 1.62056e-1, 1.18526e-1, 8.43457e-2, 5.87013e-2, 4.00089e-2,
    2.68747e-2, 1.78624e-2, 1.17901e-2, 7.73430e-3, 5.06686e-3, 3.31766e-3, 2.17698e-3, 1.43314e-3,
    9.47313e-4, 6.27648e-4, 4.17955e-4, 2.79801e-4, 1.88341e-4, 1.27337e-4, 8.65751e-5, 5.91914e-5,
    4.06945e-5, 2.81320e-5, 1.95535e-5, 1.36480e-5, 9.57637e-6, 6.75425e-6, 4.78804e-6, 3.40841e-6,
    2.43819e-6, 1.75252e-6, 1.26560e-6, 9.18078e-7, 6.68991e-7, 4.89531e-7, 3.59766e-7, 2.65493e-7,
    1.96740e-7, 1.46370e-7, 1.09332e-7, 8.19587e-8, 6.16749e-8, 4.65916e-8, 3.53272e-8, 2.68803e-8,
    2.05258e-8,
];

/// A relative spectral distribution: wavelengths (nm, increasing) and values (any scale).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Spectrum {
    /// Wavelengths, nm, strictly increasing.
    pub wavelengths_nm: Vec<f64>,
    /// Relative spectral power at each wavelength (not negative).
    pub values: Vec<f64>,
}

/// What a spectrum says about light's non-visual and plant effects.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpectralSummary {
    /// Melanopic daylight (D65) efficacy ratio, mel-DER (CIE S 026): 1 for D65.
    pub melanopic_der: f64,
    /// Luminous efficacy of the radiation, lm/W (683 × ∫SV / ∫S over the spectrum's range).
    pub luminous_efficacy_of_radiation_lm_per_w: f64,
    /// Photosynthetic photon flux (400–700 nm) for `flux_lm`, µmol/s; `None` where the
    /// spectrum does not cover 400–700 nm.
    pub ppf_umol_per_s: Option<f64>,
    /// PPF ÷ input power, µmol/J; `None` without PPF or input power.
    pub photon_efficacy_umol_per_j: Option<f64>,
}

impl Spectrum {
    /// Checks the spectrum: as many values as wavelengths (at least two), wavelengths
    /// strictly increasing in 100–2000 nm, values finite and not negative, some light
    /// between 380 and 780 nm.
    pub fn validate(&self) -> Result<(), String> {
        let (w, v) = (&self.wavelengths_nm, &self.values);
        if w.len() != v.len() {
            return Err(format!("{} wavelengths but {} values", w.len(), v.len()));
        }
        if w.len() < 2 {
            return Err("a spectrum needs at least two wavelengths".into());
        }
        if let Some(bad) = w
            .iter()
            .find(|x| !(x.is_finite() && (100.0..=2000.0).contains(*x)))
        {
            return Err(format!("wavelength {bad} nm is outside 100–2000 nm"));
        }
        if let Some(k) = w.windows(2).position(|p| p[1] <= p[0]) {
            return Err(format!(
                "wavelengths must increase: {} nm follows {} nm",
                w[k + 1],
                w[k]
            ));
        }
        if let Some(bad) = v.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
            return Err(format!("spectral value {bad} is not a number ≥ 0"));
        }
        if self.weighted(|l| table_at(&V_LAMBDA, l)) <= 0.0 {
            return Err("the spectrum has no visible light (380–780 nm)".into());
        }
        Ok(())
    }

    /// The spectrum at `nm`, linear between samples, 0 outside them.
    pub fn at(&self, nm: f64) -> f64 {
        let w = &self.wavelengths_nm;
        if w.is_empty() || nm < w[0] || nm > w[w.len() - 1] {
            return 0.0;
        }
        let k = w.partition_point(|&x| x <= nm).clamp(1, w.len() - 1);
        let (a, b) = (w[k - 1], w[k]);
        let t = if b > a { (nm - a) / (b - a) } else { 0.0 };
        self.values[k - 1] + t * (self.values[k] - self.values[k - 1])
    }

    /// ∫ S(λ) f(λ) dλ over 380–780 nm (1 nm steps, trapezoids), relative units × nm.
    fn weighted(&self, f: impl Fn(f64) -> f64) -> f64 {
        integrate(380.0, 780.0, |l| self.at(l) * f(l))
    }

    /// True when the spectrum's samples span `lo`–`hi` nm.
    fn covers(&self, lo: f64, hi: f64) -> bool {
        let w = &self.wavelengths_nm;
        !w.is_empty() && w[0] <= lo && w[w.len() - 1] >= hi
    }

    /// The melanopic DER, the efficacy of radiation and, for `flux_lm` lumens of this
    /// spectrum drawing `input_w` watts, the PPF and photon efficacy.
    pub fn summary(&self, flux_lm: f64, input_w: Option<f64>) -> SpectralSummary {
        let v = self.weighted(|l| table_at(&V_LAMBDA, l));
        let mel = self.weighted(|l| table_at(&S_MEL, l));
        let (lo, hi) = (
            self.wavelengths_nm[0],
            self.wavelengths_nm[self.wavelengths_nm.len() - 1],
        );
        let power = integrate(lo, hi, |l| self.at(l));
        // Watts per relative unit × nm, from the luminous flux.
        let watts_per_unit = flux_lm / (KM_LM_PER_W * v);
        let ppf = self.covers(400.0, 700.0).then(|| {
            let photons = integrate(400.0, 700.0, |l| self.at(l) * l * 1e-9);
            photons * watts_per_unit / HC_NA * 1e6
        });
        SpectralSummary {
            melanopic_der: mel / (KM_LM_PER_W * v) / K_MEL_D65_W_PER_LM,
            luminous_efficacy_of_radiation_lm_per_w: KM_LM_PER_W * v / power,
            ppf_umol_per_s: ppf,
            photon_efficacy_umol_per_j: ppf.zip(input_w.filter(|w| *w > 0.0)).map(|(p, w)| p / w),
        }
    }
}

/// A 5 nm table at `nm` (linear; 0 outside 380–780 nm).
fn table_at(table: &[f64; 81], nm: f64) -> f64 {
    let x = (nm - TABLE_START_NM) / TABLE_STEP_NM;
    if !(0.0..=80.0).contains(&x) {
        return 0.0;
    }
    let k = (x.floor() as usize).min(79);
    let t = x - k as f64;
    table[k] + t * (table[k + 1] - table[k])
}

/// ∫ f over `lo`–`hi` nm with 1 nm trapezoids (the last one shorter).
fn integrate(lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    let mut sum = 0.0;
    let mut a = lo;
    while a < hi {
        let b = (a + 1.0).min(hi);
        sum += 0.5 * (f(a) + f(b)) * (b - a);
        a = b;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Planck's law (relative) at `nm` for temperature `k`, with CIE illuminant A's
    /// c2 = 1.435e-2 m·K.
    fn planck(nm: f64, k: f64) -> f64 {
        let l = nm * 1e-9;
        1.0 / (l.powi(5) * ((1.435e-2 / (l * k)).exp() - 1.0))
    }

    #[test]
    fn the_tables_hold_the_published_values() {
        // CIE 1924 V(λ) and CIE S 026 s_mel(λ) at a few wavelengths (the standards' tables).
        for (nm, v, mel) in [
            (380.0, 0.000039, 9.18165e-4),
            (450.0, 0.038, 5.53715e-1),
            (490.0, 0.20802, 1.0),
            (510.0, 0.503, 8.62888e-1),
            (555.0, 1.0, 1.62056e-1),
            (610.0, 0.503, 2.17698e-3),
            (700.0, 0.004102, 2.43819e-6),
            (780.0, 0.000015, 2.05258e-8),
        ] {
            assert_eq!(table_at(&V_LAMBDA, nm), v, "V({nm})");
            assert_eq!(table_at(&S_MEL, nm), mel, "s_mel({nm})");
        }
        assert_eq!(table_at(&V_LAMBDA, 379.0), 0.0);
    }

    #[test]
    fn illuminant_a_has_the_published_melanopic_der() {
        // CIE illuminant A (Planck, 2848 K with c2 = 1.435e-2 m·K, CIE 15): 100 lx of it
        // give a melanopic EDI of 49.58 lx (CIE S 026 via the Lighting Toolbox's `ciemedi`,
        // 1 nm tables), so mel-DER = 0.4958.
        let wavelengths_nm: Vec<f64> = (300..=830).map(f64::from).collect();
        let values = wavelengths_nm.iter().map(|&l| planck(l, 2848.0)).collect();
        let a = Spectrum {
            wavelengths_nm,
            values,
        };
        let s = a.summary(1000.0, None);
        assert!(
            (s.melanopic_der - 0.4958).abs() < 0.002,
            "{}",
            s.melanopic_der
        );
        // Equal-energy radiation: K_mel / K_mel(D65) = 1.2013 / 1.3262 mW/lm.
        let e = Spectrum {
            wavelengths_nm: vec![380.0, 780.0],
            values: vec![1.0, 1.0],
        };
        let der = e.summary(1000.0, None).melanopic_der;
        assert!((der - 0.9058).abs() < 0.002, "{der}");
    }

    #[test]
    fn a_narrow_line_gives_the_photon_count_of_its_watts() {
        // A narrow line at 555 nm: 683 lm ≈ 1 W ≈ 4.64 µmol/s of 555 nm photons.
        let s = Spectrum {
            wavelengths_nm: vec![399.0, 554.0, 555.0, 556.0, 701.0],
            values: vec![0.0, 0.0, 1.0, 0.0, 0.0],
        };
        let r = s.summary(KM_LM_PER_W, Some(2.0));
        let expected = 555e-9 / HC_NA * 1e6;
        let ppf = r.ppf_umol_per_s.unwrap();
        assert!((ppf / expected - 1.0).abs() < 1e-3, "{ppf} vs {expected}");
        assert!((r.photon_efficacy_umol_per_j.unwrap() - ppf / 2.0).abs() < 1e-12);
        // Its luminous efficacy of radiation is Km × V(555 nm) = 683 lm/W.
        let ler = r.luminous_efficacy_of_radiation_lm_per_w;
        assert!((ler / KM_LM_PER_W - 1.0).abs() < 1e-3, "{ler}");
    }

    #[test]
    fn bad_spectra_are_refused() {
        let s = |w: Vec<f64>, v: Vec<f64>| {
            Spectrum {
                wavelengths_nm: w,
                values: v,
            }
            .validate()
        };
        assert!(s(vec![400.0, 500.0], vec![1.0])
            .unwrap_err()
            .contains("2 wavelengths"));
        assert!(s(vec![500.0, 400.0], vec![1.0, 1.0])
            .unwrap_err()
            .contains("increase"));
        assert!(s(vec![400.0, 500.0], vec![1.0, -1.0])
            .unwrap_err()
            .contains("-1"));
        assert!(s(vec![900.0, 1000.0], vec![1.0, 1.0])
            .unwrap_err()
            .contains("visible"));
    }
}
