//! Clear glazing's transmittance at any angle of incidence, as for a single pane of
//! uncoated glass of refractive index 1.52 (Radiance's `glass` material): Fresnel
//! reflection at both faces for each polarisation, absorption along the refracted path,
//! and the pane's inter-reflections summed. A material gives its transmittance at normal
//! incidence (`specular_transmittance`); the pane's transmissivity (per pass, at normal
//! incidence) is the one that gives it.

/// Refractive index of the glass.
pub const GLASS_INDEX: f64 = 1.52;

/// A pane of clear glass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Glazing {
    /// Transmissivity of one pass through the pane at normal incidence (absorption only).
    transmissivity: f64,
    /// Transmittance at normal incidence.
    normal_transmittance: f64,
}

impl Glazing {
    /// The pane whose transmittance at normal incidence is `t_n`; `None` unless `t_n` is
    /// in (0, the transmittance of a non-absorbing pane, 0.9158].
    pub fn with_normal_transmittance(t_n: f64) -> Option<Glazing> {
        let most = pane_transmittance(1.0, 1.0);
        if !(t_n > 0.0 && t_n <= most + 1e-12) {
            return None;
        }
        // The pane's transmittance grows with its transmissivity: bisect.
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if pane_transmittance(1.0, mid) < t_n {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(Glazing {
            transmissivity: 0.5 * (lo + hi),
            normal_transmittance: t_n,
        })
    }

    /// A non-absorbing pane: the clearest glazing there is (0.918 at normal incidence).
    pub fn clearest() -> Glazing {
        Glazing {
            transmissivity: 1.0,
            normal_transmittance: pane_transmittance(1.0, 1.0),
        }
    }

    /// Transmittance at normal incidence, as given.
    pub fn normal_transmittance(&self) -> f64 {
        self.normal_transmittance
    }

    /// Transmittance for light arriving at `cos_incidence` (|cos| of the angle to the
    /// pane's normal; either side).
    pub fn transmittance(&self, cos_incidence: f64) -> f64 {
        pane_transmittance(cos_incidence.abs().min(1.0), self.transmissivity)
    }
}

/// A pane's transmittance at `cos_i` with per-pass transmissivity `tau` at normal
/// incidence: the mean over both polarisations of (1−ρ)² τ' / (1 − ρ² τ'²), τ' = τ^(1/cos θ_t).
fn pane_transmittance(cos_i: f64, tau: f64) -> f64 {
    if cos_i <= 0.0 {
        return 0.0;
    }
    let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
    let sin_t = sin_i / GLASS_INDEX;
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let n = GLASS_INDEX;
    let rs = ((cos_i - n * cos_t) / (cos_i + n * cos_t)).powi(2);
    let rp = ((n * cos_i - cos_t) / (n * cos_i + cos_t)).powi(2);
    let pass = tau.powf(1.0 / cos_t);
    let through = |r: f64| (1.0 - r).powi(2) * pass / (1.0 - r * r * pass * pass);
    0.5 * (through(rs) + through(rp))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-absorbing pane of n = 1.52: ρ = (0.52/2.52)² = 0.042580 at normal incidence,
    /// T = (1−ρ)/(1+ρ) = 0.91832 (the textbook two-face result); the transmissivity of a
    /// pane of 88 % is the one Radiance's `glass` documentation gives in closed form
    /// ((√(0.8402528435 + 0.0072522239 T²) − 0.9166530661) / 0.0036261119 / T); grazing
    /// light is not transmitted.
    #[test]
    fn a_pane_transmits_as_fresnel_and_absorption_say() {
        let r: f64 = (0.52f64 / 2.52).powi(2);
        assert!((pane_transmittance(1.0, 1.0) - (1.0 - r) / (1.0 + r)).abs() < 1e-12);
        let g = Glazing::with_normal_transmittance(0.88).unwrap();
        assert!((g.transmittance(1.0) - 0.88).abs() < 1e-12);
        let radiance = ((0.8402528435f64 + 0.0072522239 * 0.88 * 0.88).sqrt() - 0.9166530661)
            / 0.0036261119
            / 0.88;
        assert!(
            (g.transmissivity - radiance).abs() < 1e-6,
            "{} {radiance}",
            g.transmissivity
        );
        assert!(g.transmittance(0.0) == 0.0);
        // Falls monotonically with the angle, slowly at first (Fresnel: 60° keeps ~90 %).
        let t60 = g.transmittance(0.5) / 0.88;
        assert!((0.85..0.95).contains(&t60), "{t60}");
        let mut last = 1.0;
        for k in (1..=100).rev() {
            let t = g.transmittance(k as f64 / 100.0);
            assert!(t <= last + 1e-15);
            last = t;
        }
        assert!(Glazing::with_normal_transmittance(0.95).is_none());
        assert!(Glazing::with_normal_transmittance(0.0).is_none());
    }
}
