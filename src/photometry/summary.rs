//! Photometric summary: integrated flux over exact solid-angle bands, light output ratio,
//! downward flux fraction, peak intensity, beam (50 %) and field (10 %) angles.

use serde::Serialize;

use super::distribution::Distribution;
use super::grid::Interp;

/// A value for each of the two main planes.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct PlanePair {
    /// In the C0–C180 plane.
    pub c0_c180: Option<f64>,
    /// In the C90–C270 plane.
    pub c90_c270: Option<f64>,
}

/// The photometric summary of a luminaire.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Sum of the declared lamp fluxes, lm.
    pub lamp_flux_lm: f64,
    /// Integrated luminaire flux, lm.
    pub flux_lm: f64,
    /// Declared light output ratio, percent.
    pub lorl_declared: f64,
    /// Integrated flux over lamp flux, percent.
    pub lorl_computed: f64,
    /// Declared downward flux fraction, percent.
    pub dff_declared: f64,
    /// Computed downward flux fraction, percent.
    pub dff_computed: f64,
    /// Peak intensity, cd/klm.
    pub max_intensity: f64,
    /// Where the peak is: `[C, γ]` in degrees.
    pub max_direction_deg: [f64; 2],
    /// Full angle between the 50 % points around the peak of each plane, degrees.
    pub beam_angle_deg: PlanePair,
    /// Full angle between the 10 % points, degrees.
    pub field_angle_deg: PlanePair,
}

impl Summary {
    /// Computes the summary of `dist` with its declared LORL and DFF.
    pub fn of(dist: &Distribution, lorl_declared: f64, dff_declared: f64) -> Summary {
        let (rel_flux, down) = dist.relative_flux();
        let (max_intensity, c_max, g_max) = dist.max_intensity();
        Summary {
            lamp_flux_lm: dist.lamp_flux_lm(),
            flux_lm: rel_flux * dist.lamp_flux_lm() / 1000.0,
            lorl_declared,
            lorl_computed: rel_flux / 10.0,
            dff_declared,
            dff_computed: if rel_flux > 0.0 {
                down / rel_flux * 100.0
            } else {
                0.0
            },
            max_intensity,
            max_direction_deg: [c_max, g_max],
            beam_angle_deg: PlanePair {
                c0_c180: spread_angle(dist, 0.0, 0.5),
                c90_c270: spread_angle(dist, 90.0, 0.5),
            },
            field_angle_deg: PlanePair {
                c0_c180: spread_angle(dist, 0.0, 0.1),
                c90_c270: spread_angle(dist, 90.0, 0.1),
            },
        }
    }
}

/// Full angle around the peak of the great circle through planes `c` and `c + 180`
/// between the directions where the intensity falls to `fraction` of that peak.
/// `None` when the intensity is zero or never falls that low.
fn spread_angle(dist: &Distribution, c: f64, fraction: f64) -> Option<f64> {
    const STEP: f64 = 0.05;
    // t in (-180, 180]: t ≥ 0 is plane c at γ = t, t < 0 plane c + 180 at γ = −t.
    let n = (360.0 / STEP) as usize;
    let value = |i: usize| {
        let t = -180.0 + (i as f64) * STEP;
        if t >= 0.0 {
            dist.sample(c, t, Interp::Bilinear)
        } else {
            dist.sample(c + 180.0, -t, Interp::Bilinear)
        }
    };
    let samples: Vec<f64> = (0..=n).map(value).collect();
    let (peak_i, &peak) = samples
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))?;
    if peak <= 0.0 {
        return None;
    }
    let threshold = peak * fraction;
    let crossing = |dir: isize| -> Option<f64> {
        let mut i = peak_i as isize;
        loop {
            let next = i + dir;
            if next < 0 || next > n as isize {
                return None;
            }
            let (a, b) = (samples[i as usize], samples[next as usize]);
            if b < threshold {
                let s = (a - threshold) / (a - b);
                return Some((i as f64 + s * dir as f64) * STEP);
            }
            i = next;
        }
    };
    let right = crossing(1)?;
    let left = crossing(-1)?;
    Some(right - left)
}
