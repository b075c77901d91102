//! Statistics of a grid's values, as EN 12464-1 and lighting reports give them.

use serde::Serialize;

/// Em, Emin, Emax, U0 and g2 of a grid (lux, maintained when the values are).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct GridStats {
    /// Number of points.
    pub points: usize,
    /// Mean, lx.
    pub em: f64,
    /// Minimum, lx.
    pub emin: f64,
    /// Maximum, lx.
    pub emax: f64,
    /// Uniformity Emin / Em (0 when Em is 0).
    pub u0: f64,
    /// Emin / Emax (0 when Emax is 0).
    pub g2: f64,
}

/// The statistics of `values` (at least one).
pub fn grid_stats(values: &[f64]) -> GridStats {
    let n = values.len();
    let em = values.iter().sum::<f64>() / n as f64;
    let emin = values.iter().copied().fold(f64::INFINITY, f64::min);
    let emax = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let ratio = |a: f64, b: f64| if b > 0.0 { a / b } else { 0.0 };
    GridStats {
        points: n,
        em,
        emin,
        emax,
        u0: ratio(emin, em),
        g2: ratio(emin, emax),
    }
}

#[cfg(test)]
mod tests {
    use super::grid_stats;

    #[test]
    fn stats_of_a_small_grid() {
        let s = grid_stats(&[100.0, 200.0, 300.0, 400.0]);
        assert_eq!((s.points, s.em, s.emin, s.emax), (4, 250.0, 100.0, 400.0));
        assert_eq!((s.u0, s.g2), (0.4, 0.25));
        assert_eq!(grid_stats(&[0.0, 0.0]).u0, 0.0);
    }
}
