//! The interpolation check over a catalogue of luminaire files: per error metric, each
//! method's median and worst value over the files and the number of files on which it is
//! the best method.

use std::collections::BTreeMap;

use serde::Serialize;

use super::check::{CheckReport, MethodResult};

/// An error metric of the check, compared across files (lower is better for each).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// RMS error, cd/klm.
    Rms,
    /// RMS error relative to the file's I_max, percent: comparable between a narrow spot
    /// and a wide flood, whose cd/klm differ by orders of magnitude.
    RmsPercent,
    /// Largest relative error over values above 1 % of I_max.
    MaxRel,
    /// Number of reconstructed values outside their cell's measured range.
    Overshoots,
    /// Magnitude of the reconstruction's flux error, percent.
    FluxError,
}

impl Metric {
    /// Every metric, in the order of the tables.
    pub const ALL: [Metric; 5] = [
        Metric::Rms,
        Metric::RmsPercent,
        Metric::MaxRel,
        Metric::Overshoots,
        Metric::FluxError,
    ];

    /// The key in JSON and CSV.
    pub fn key(self) -> &'static str {
        match self {
            Metric::Rms => "rms",
            Metric::RmsPercent => "rms_percent_of_i_max",
            Metric::MaxRel => "max_rel",
            Metric::Overshoots => "overshoots",
            Metric::FluxError => "abs_flux_error_percent",
        }
    }

    /// The metric's value for one method of one file's report.
    pub fn of(self, report: &CheckReport, method: &MethodResult) -> f64 {
        match self {
            Metric::Rms => method.rms,
            Metric::RmsPercent if report.i_max > 0.0 => method.rms / report.i_max * 100.0,
            Metric::RmsPercent => 0.0,
            Metric::MaxRel => method.max_rel,
            Metric::Overshoots => method.overshoot_count as f64,
            Metric::FluxError => method.flux_error_percent.abs(),
        }
    }
}

/// One method's figures for one metric over the catalogue.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MethodStats {
    /// Median over the files (the mean of the middle two for an even count).
    pub median: f64,
    /// Largest value over the files.
    pub worst: f64,
    /// Files on which this method has the lowest value (tied methods each count).
    pub wins: usize,
}

/// Per metric (by [`Metric::key`]), per method: median, worst and wins over the files.
#[derive(Debug, Clone, Serialize)]
pub struct CatalogueSummary {
    /// Number of files summarised.
    pub files: usize,
    /// Metric key → method key → figures.
    pub metrics: BTreeMap<String, BTreeMap<String, MethodStats>>,
}

/// Two values within this relative distance tie for a win.
const TIE: f64 = 1e-9;

/// Summarises the check reports of a catalogue (every report has the same methods).
pub fn summarise(reports: &[&CheckReport]) -> CatalogueSummary {
    let methods: Vec<&String> = reports
        .first()
        .map(|r| r.methods.keys().collect())
        .unwrap_or_default();
    let mut metrics = BTreeMap::new();
    for metric in Metric::ALL {
        // values[m][f]: method m on file f.
        let values: Vec<Vec<f64>> = methods
            .iter()
            .map(|m| {
                reports
                    .iter()
                    .map(|r| metric.of(r, &r.methods[*m]))
                    .collect()
            })
            .collect();
        let mut wins = vec![0usize; methods.len()];
        for f in 0..reports.len() {
            let best = values.iter().map(|v| v[f]).fold(f64::INFINITY, f64::min);
            for (m, v) in values.iter().enumerate() {
                if v[f] <= best + TIE * best.abs() {
                    wins[m] += 1;
                }
            }
        }
        let per_method = methods
            .iter()
            .zip(&values)
            .zip(&wins)
            .map(|((name, v), &wins)| {
                let stats = MethodStats {
                    median: median(v),
                    worst: v.iter().cloned().fold(0.0, f64::max),
                    wins,
                };
                ((*name).clone(), stats)
            })
            .collect();
        metrics.insert(metric.key().to_string(), per_method);
    }
    CatalogueSummary {
        files: reports.len(),
        metrics,
    }
}

/// The median of `values` (0 for none).
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(i_max: f64, rms: [f64; 2], overshoots: [usize; 2]) -> CheckReport {
        let method = |rms: f64, over: usize| MethodResult {
            rms,
            max_abs: rms,
            max_rel: rms / i_max,
            overshoot_count: over,
            overshoot_max: 0.0,
            flux_error_percent: -rms,
            hausdorff: rms,
        };
        CheckReport {
            mode: "test".into(),
            held_out: 10,
            i_max,
            methods: [
                ("a".to_string(), method(rms[0], overshoots[0])),
                ("b".to_string(), method(rms[1], overshoots[1])),
            ]
            .into_iter()
            .collect(),
            residuals: Vec::new(),
        }
    }

    #[test]
    fn medians_worst_and_wins() {
        let reports = [
            report(100.0, [1.0, 2.0], [0, 3]),
            report(1000.0, [5.0, 4.0], [0, 0]),
            report(10.0, [3.0, 9.0], [2, 1]),
        ];
        let refs: Vec<&CheckReport> = reports.iter().collect();
        let s = summarise(&refs);
        assert_eq!(s.files, 3);
        let rms = &s.metrics["rms"];
        assert_eq!(rms["a"].median, 3.0);
        assert_eq!(rms["b"].median, 4.0);
        assert_eq!(rms["a"].worst, 5.0);
        assert_eq!(rms["b"].worst, 9.0);
        assert_eq!((rms["a"].wins, rms["b"].wins), (2, 1));
        // Relative to I_max: a = 1 %, 0.5 %, 30 %; b = 2 %, 0.4 %, 90 %.
        let rel = &s.metrics["rms_percent_of_i_max"];
        assert!((rel["a"].median - 1.0).abs() < 1e-12);
        assert!((rel["b"].worst - 90.0).abs() < 1e-12);
        // Overshoots tie on the second file: both methods win it.
        let over = &s.metrics["overshoots"];
        assert_eq!((over["a"].wins, over["b"].wins), (2, 2));
        // The flux error is compared by magnitude.
        assert_eq!(s.metrics["abs_flux_error_percent"]["b"].worst, 9.0);
    }

    #[test]
    fn median_of_even_and_empty() {
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), 2.5);
        assert_eq!(median(&[]), 0.0);
    }
}
