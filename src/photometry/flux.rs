//! Luminous flux of a measured distribution: intensities integrated over exact solid-angle
//! bands around each measured value (the one integration every photometry module uses).

/// Integrates intensity planes `(C angle, values over γ)` over the sphere.
///
/// Each measured value stands for the band between the midpoints to its neighbours (clipped
/// to the measured γ range) and between the midpoints to the neighbouring C planes; a band's
/// solid angle is exact: ΔC · (cos γ_lo − cos γ_hi). Returns `(total, downward)` in
/// intensity unit × sr (lm for cd, lm/klm for cd/klm); downward counts γ < 90°.
pub fn integrate_flux(planes: &[(f64, Vec<f64>)], gammas: &[f64]) -> (f64, f64) {
    let bands = gamma_bands(gammas);
    let widths = c_widths(planes.iter().map(|p| p.0).collect::<Vec<_>>().as_slice());
    let mut total = 0.0;
    let mut down = 0.0;
    for ((_, values), dc) in planes.iter().zip(widths) {
        for (v, (lo, hi)) in values.iter().zip(&bands) {
            total += v * dc * (lo.cos() - hi.cos());
            if *lo < std::f64::consts::FRAC_PI_2 {
                let top = hi.min(std::f64::consts::FRAC_PI_2);
                down += v * dc * (lo.cos() - top.cos());
            }
        }
    }
    (total, down)
}

/// γ band edges (radians) of each angle: midpoints, clipped to the first and last angle.
fn gamma_bands(g: &[f64]) -> Vec<(f64, f64)> {
    let n = g.len();
    (0..n)
        .map(|i| {
            let lo = if i == 0 {
                g[0]
            } else {
                0.5 * (g[i - 1] + g[i])
            };
            let hi = if i + 1 == n {
                g[n - 1]
            } else {
                0.5 * (g[i] + g[i + 1])
            };
            (lo.to_radians(), hi.to_radians())
        })
        .collect()
}

/// C width (radians) of each plane: half the gaps to its neighbours, wrapping at 360°.
fn c_widths(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    if n == 1 {
        return vec![std::f64::consts::TAU];
    }
    let gap = |a: f64, b: f64| {
        let d = (b - a).rem_euclid(360.0);
        if d == 0.0 {
            360.0
        } else {
            d
        }
    };
    (0..n)
        .map(|j| {
            let before = gap(c[(j + n - 1) % n], c[j]);
            let after = gap(c[j], c[(j + 1) % n]);
            (0.5 * (before + after)).to_radians()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isotropic_source_integrates_to_four_pi() {
        let g: Vec<f64> = (0..=36).map(|i| i as f64 * 5.0).collect();
        let planes: Vec<(f64, Vec<f64>)> =
            (0..24).map(|j| (j as f64 * 15.0, vec![1.0; 37])).collect();
        let (total, down) = integrate_flux(&planes, &g);
        assert!((total - 4.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!((down - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn lambertian_downlight_integrates_to_pi() {
        // I = cos γ below the horizon: Φ = π exactly; midpoint bands converge as h².
        let g: Vec<f64> = (0..=180).map(|i| i as f64).collect();
        let row: Vec<f64> = g.iter().map(|a| a.to_radians().cos().max(0.0)).collect();
        let (total, _) = integrate_flux(&[(0.0, row)], &g);
        assert!((total / std::f64::consts::PI - 1.0).abs() < 1e-4, "{total}");
    }
}
