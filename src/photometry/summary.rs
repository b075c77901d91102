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

/// The CIE flux code (CIE 52): N1–N3 the flux within the cones of 41.4°, 60° and 75.5°
/// (π/2, π and 3π/2 sr) as percent of the downward flux, N4 the downward flux as percent of
/// the luminaire's (DFF), N5 the luminaire's flux as percent of the lamps' (LOR); each
/// rounded to a whole percent as datasheets print it. `None` for a luminaire without
/// downward light (N1–N3 undefined).
pub fn cie_flux_code(dist: &Distribution) -> Option<[u32; 5]> {
    const C_STEPS: usize = 360;
    const G_STEP: f64 = 0.05;
    // Cumulative flux from γ = 0, cd/klm·sr, at each γ step.
    let n = (180.0 / G_STEP).round() as usize;
    let mut cumulative = Vec::with_capacity(n + 1);
    let mut total = 0.0;
    cumulative.push(0.0);
    for k in 0..n {
        let (lo, hi) = (k as f64 * G_STEP, (k + 1) as f64 * G_STEP);
        let g = 0.5 * (lo + hi);
        let mean = (0..C_STEPS)
            .map(|j| dist.sample(360.0 * j as f64 / C_STEPS as f64, g, Interp::Bilinear))
            .sum::<f64>()
            / C_STEPS as f64;
        total +=
            mean * 2.0 * std::f64::consts::PI * (lo.to_radians().cos() - hi.to_radians().cos());
        cumulative.push(total);
    }
    let at = |g: f64| cumulative[(g / G_STEP).round() as usize];
    let (down, all) = (at(90.0), at(180.0));
    if down <= 0.0 {
        return None;
    }
    let pct = |v: f64| (v * 100.0).round().max(0.0) as u32;
    Some([
        pct(at(41.4) / down),
        pct(at(60.0) / down),
        pct(at(75.5) / down),
        pct(down / all),
        pct(all / 1000.0),
    ])
}
