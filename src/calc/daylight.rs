//! Daylight in a calculation: the light of the scene's `[sky]` alone at the grids' points
//! (direct, and interreflected with radiosity), added to the luminaires' maintained light
//! (the maintenance factor is the luminaires'; daylight is not scaled), and under the CIE
//! overcast sky the daylight factor: the daylight at a point as a percentage of the
//! unobstructed horizontal illuminance from the sky.

use serde::Serialize;

use super::stats::grid_stats;
use crate::daylight::SkyDistribution;
use crate::scene::Scene;

/// Daylight factor statistics of a grid, per cent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FactorStats {
    /// Mean.
    pub mean: f64,
    /// Median (the mean of the middle two of an even count).
    pub median: f64,
    /// Minimum.
    pub min: f64,
    /// Maximum.
    pub max: f64,
    /// Uniformity min / mean (0 when the mean is 0).
    pub u0: f64,
}

/// The statistics of `values` (at least one), per cent: a grid's statistics
/// ([`grid_stats`]) with the median.
pub fn factor_stats(values: &[f64]) -> FactorStats {
    let s = grid_stats(values);
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    };
    FactorStats {
        mean: s.em,
        median,
        min: s.emin,
        max: s.emax,
        u0: s.u0,
    }
}

/// The daylight at every grid point, and its daylight factor.
#[derive(Debug, Clone, PartialEq)]
pub struct DaylightGrids {
    /// Per grid, per point, lux (daylight alone; not maintained).
    pub lux: Vec<Vec<f64>>,
    /// Per grid, per point, the daylight factor in per cent (CIE overcast sky only).
    pub factor: Option<Vec<Vec<f64>>>,
    /// Per grid, the daylight factor's statistics (CIE overcast sky only).
    pub factor_stats: Option<Vec<FactorStats>>,
    /// The daylight's radiosity convergence, with interreflections.
    pub convergence: Option<f64>,
    /// The sky in words, for reports ("CIE overcast sky, 10000 lx diffuse horizontal").
    pub sky: String,
}

impl DaylightGrids {
    /// The grids' daylight `lux` (combined per point) in `scene`: with the daylight factor
    /// when its sky is the CIE standard overcast sky without sun.
    pub fn new(scene: &Scene, lux: Vec<Vec<f64>>, convergence: Option<f64>) -> DaylightGrids {
        let sky = &scene.daylight.as_ref().expect("a scene with a sky").sky;
        let e_h = sky.diffuse_horizontal_lux;
        let factor: Option<Vec<Vec<f64>>> = has_daylight_factor(scene).then(|| {
            lux.iter()
                .map(|g| g.iter().map(|v| 100.0 * v / e_h).collect())
                .collect()
        });
        let factor_stats = factor
            .as_ref()
            .map(|f| f.iter().map(|g| factor_stats(g)).collect());
        let mut words = format!("{}, {e_h} lx", sky_name(sky.distribution));
        if let Some(sun) = sky.sun {
            words.push_str(&format!(" + sun {:.0} lx", sun.normal_lux));
        }
        DaylightGrids {
            lux,
            factor,
            factor_stats,
            convergence,
            sky: words,
        }
    }
}

/// Whether a calculation of `scene` gives the daylight factor: its sky is the CIE
/// standard overcast sky, without sun, of some illuminance.
pub fn has_daylight_factor(scene: &Scene) -> bool {
    scene.daylight.as_ref().is_some_and(|d| {
        d.sky.distribution == SkyDistribution::CieOvercast
            && d.sky.sun.is_none()
            && d.sky.diffuse_horizontal_lux > 0.0
    })
}

/// A sky model's name in reports.
fn sky_name(d: SkyDistribution) -> String {
    match d {
        SkyDistribution::CieOvercast => "CIE overcast".into(),
        SkyDistribution::Uniform => "uniform sky".into(),
        SkyDistribution::CieGeneral(n) => format!("CIE sky type {n}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_statistics_of_a_small_grid() {
        let s = factor_stats(&[4.0, 1.0, 2.0, 3.0]);
        assert_eq!((s.mean, s.median, s.min, s.max), (2.5, 2.5, 1.0, 4.0));
        assert_eq!(s.u0, 0.4);
        assert_eq!(factor_stats(&[3.0, 1.0, 2.0]).median, 2.0);
        assert_eq!(factor_stats(&[0.0]).u0, 0.0);
    }
}
