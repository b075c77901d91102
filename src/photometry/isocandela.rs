//! Isocandela lines: where the intensity equals round levels, over the sphere of
//! directions drawn as a plan seen from above (azimuthal equidistant about the nadir: the
//! direction (C, γ) at (γ cos C, γ sin C), so C0 points right, C90 up and the radius is γ).
//! Lines come from marching squares (the `contour` crate) over that plane, so they have
//! no seam at C = 0/360°.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::plot::{DrawError, DrawResult};

/// One isocandela level and its lines in the plan (degrees of γ along each axis).
#[derive(Debug, Clone)]
pub struct IsoLine {
    /// The intensity of the line, cd/klm.
    pub level: f64,
    /// The line's pieces, each a polyline of `[x, y]` points.
    pub pieces: Vec<Vec<[f64; 2]>>,
}

/// The isocandela map of a distribution.
#[derive(Debug, Clone)]
pub struct IsocandelaMap {
    /// The largest γ shown (the disc's radius), degrees.
    pub gamma_limit: f64,
    /// The levels from the lowest up, each with its lines.
    pub lines: Vec<IsoLine>,
}

/// Round levels below `peak`: multiples of a 1-2-2.5-5 step giving five to ten lines.
pub fn round_levels(peak: f64) -> Vec<f64> {
    if peak <= 0.0 || !peak.is_finite() {
        return Vec::new();
    }
    let mag = 10f64.powf((peak / 10.0).log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .into_iter()
        .map(|m| m * mag)
        .find(|s| peak / s <= 10.0)
        .unwrap_or(10.0 * mag);
    // Rounded to the step's decimals, so 3 × 0.1 prints as 0.3.
    let exponent = step.log10().floor() as i32 - 1;
    let round = |v: f64| {
        if exponent < 0 {
            let per_unit = 10f64.powi(-exponent);
            (v * per_unit).round() / per_unit
        } else {
            v
        }
    };
    (1..)
        .map(|k| round(k as f64 * step))
        .take_while(|&v| v < peak * (1.0 - 1e-9))
        .collect()
}

/// Lines of `sample(C, γ)` (cd/klm) at `levels`, over directions up to `gamma_limit`,
/// sampled every `step_deg` in the plan.
pub fn isocandela_map(
    sample: impl Fn(f64, f64) -> f64,
    levels: &[f64],
    gamma_limit: f64,
    step_deg: f64,
) -> Result<IsocandelaMap, DrawError> {
    let n = (2.0 * gamma_limit / step_deg).round() as usize + 1;
    let coord = |i: usize| -gamma_limit + i as f64 * step_deg;
    let mut values = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (coord(i), coord(j));
            let g = x.hypot(y);
            values.push(if g > 180.0 {
                0.0
            } else {
                sample(y.atan2(x).to_degrees().rem_euclid(360.0), g)
            });
        }
    }
    // The crate puts value i at origin + (i + ½)·step.
    let origin = -gamma_limit - 0.5 * step_deg;
    let lines = contour::ContourBuilder::new(n, n, true)
        .x_origin(origin)
        .y_origin(origin)
        .x_step(step_deg)
        .y_step(step_deg)
        .lines(&values, levels)
        .map_err(|e| DrawError::new("the isocandela lines", format!("{e:?}")))?;
    Ok(IsocandelaMap {
        gamma_limit,
        lines: lines
            .into_iter()
            .map(|line| {
                let (geometry, level) = line.into_inner();
                IsoLine {
                    level,
                    pieces: geometry
                        .0
                        .into_iter()
                        .map(|ls| ls.0.into_iter().map(|c| [c.x, c.y]).collect())
                        .collect(),
                }
            })
            .collect(),
    })
}

/// The smallest γ range, in 10° steps, outside which `sample` stays below `floor`
/// (at least 30°).
pub fn gamma_reach(sample: impl Fn(f64, f64) -> f64, floor: f64) -> f64 {
    let mut reach: f64 = 30.0;
    for k in 0..=180 {
        let g = k as f64;
        if (0..72).any(|c| sample(c as f64 * 5.0, g) > floor) {
            reach = reach.max(g);
        }
    }
    ((reach / 10.0).ceil() * 10.0).min(180.0)
}

/// The colour of level `k` of `n`: light amber for the lowest to dark red for the highest.
fn level_colour(k: usize, n: usize) -> RGBColor {
    let t = if n > 1 {
        k as f64 / (n - 1) as f64
    } else {
        1.0
    };
    let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
    RGBColor(mix(240.0, 120.0), mix(170.0, 0.0), mix(40.0, 30.0))
}

impl IsocandelaMap {
    /// Draws the plan: rings of γ every 10° (labelled every 30°), C radials every 30°,
    /// each level's lines in its colour with its value on the longest piece.
    pub fn draw<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let (w, h) = area.dim_in_pixel();
        let side = w.min(h);
        let square = area
            .clone()
            .shrink(((w - side) / 2, (h - side) / 2), (side, side));
        let lim = self.gamma_limit;
        let span = lim * 1.13;
        let mut chart = ChartBuilder::on(&square)
            .margin(16)
            .build_cartesian_2d(-span..span, -span..span)?;
        let grey = RGBColor(205, 205, 205);
        let label = ("sans-serif", 13)
            .into_font()
            .color(&RGBColor(100, 100, 100));
        let at = |r: f64, c: f64| {
            let t = c.to_radians();
            (r * t.cos(), r * t.sin())
        };
        for ring in (1..).map(|k| k as f64 * 10.0).take_while(|&r| r <= lim) {
            chart.draw_series(LineSeries::new((0..=360).map(|c| at(ring, c as f64)), grey))?;
            if ring % 30.0 == 0.0 || ring == lim {
                chart.draw_series(std::iter::once(Text::new(
                    format!("{ring}°"),
                    at(ring, 75.0),
                    label.clone(),
                )))?;
            }
        }
        for c in (0..360).step_by(30) {
            let c = c as f64;
            chart.draw_series(LineSeries::new([(0.0, 0.0), at(lim, c)], grey))?;
            let (x, y) = at(lim * 1.065, c);
            chart.draw_series(std::iter::once(Text::new(
                format!("C{c}"),
                (x - span * 0.04, y + span * 0.02),
                ("sans-serif", 14).into_font(),
            )))?;
        }
        let n = self.lines.len();
        for (k, line) in self.lines.iter().enumerate() {
            let colour = level_colour(k, n);
            for piece in &line.pieces {
                chart.draw_series(LineSeries::new(
                    piece.iter().map(|p| (p[0], p[1])),
                    colour.stroke_width(2),
                ))?;
            }
            if let Some(longest) = line.pieces.iter().max_by_key(|p| p.len()) {
                let [x, y] = longest[longest.len() / 2];
                chart.draw_series(std::iter::once(Text::new(
                    format!("{}", line.level),
                    (x, y),
                    ("sans-serif", 13).into_font().color(&colour.mix(1.0)),
                )))?;
            }
        }
        Ok(())
    }

    /// Draws the legend column: each level with its colour, then how to read the plan.
    pub fn draw_legend<DB: DrawingBackend>(
        &self,
        side: &DrawingArea<DB, Shift>,
        notes: &[String],
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        side.draw(&Text::new(
            "isocandela (cd/klm)",
            (10, 40),
            ("sans-serif", 16).into_font(),
        ))?;
        let n = self.lines.len();
        for (k, line) in self.lines.iter().enumerate().rev() {
            let y = 70 + 24 * (n - 1 - k) as i32;
            let colour = level_colour(k, n);
            side.draw(&PathElement::new(
                [(10, y), (44, y)],
                colour.stroke_width(3),
            ))?;
            side.draw(&Text::new(
                format!("{}", line.level),
                (54, y - 8),
                ("sans-serif", 15).into_font(),
            ))?;
        }
        let note = ("sans-serif", 13).into_font().color(&RGBColor(90, 90, 90));
        let below = 84 + 24 * n as i32;
        for (k, line) in notes.iter().enumerate() {
            side.draw(&Text::new(
                line.as_str(),
                (10, below + 18 * k as i32),
                note.clone(),
            ))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_levels_step_through_the_peak() {
        assert_eq!(
            round_levels(700.0),
            vec![100.0, 200.0, 300.0, 400.0, 500.0, 600.0]
        );
        assert_eq!(round_levels(230.0).len(), 9); // 25 … 225
        assert_eq!(round_levels(1000.0).len(), 9); // 100 … 900
        assert!(round_levels(0.0).is_empty());
        assert_eq!(format!("{}", round_levels(0.7)[2]), "0.3");
    }

    #[test]
    fn a_cone_gives_circles_at_the_right_gamma() {
        // I = 100 − γ: the line at level L is the circle γ = 100 − L.
        let map = isocandela_map(|_, g| (100.0 - g).max(0.0), &[30.0, 60.0], 90.0, 1.0).unwrap();
        for line in &map.lines {
            let radius = 100.0 - line.level;
            let points: Vec<_> = line.pieces.iter().flatten().collect();
            assert!(points.len() > 100);
            for p in points {
                let r = p[0].hypot(p[1]);
                assert!((r - radius).abs() < 0.3, "level {}: r {r}", line.level);
            }
        }
    }

    #[test]
    fn c_angles_run_counterclockwise_from_the_right() {
        // A lobe toward C90 (up in the plan), γ 45°.
        let lobe = |c: f64, g: f64| {
            let d = ((c - 90.0) / 20.0).powi(2) + ((g - 45.0) / 10.0).powi(2);
            100.0 * (-d).exp()
        };
        let map = isocandela_map(lobe, &[50.0], 90.0, 1.0).unwrap();
        let points: Vec<_> = map.lines[0].pieces.iter().flatten().collect();
        let n = points.len() as f64;
        let (mx, my) = points
            .iter()
            .fold((0.0, 0.0), |(x, y), p| (x + p[0] / n, y + p[1] / n));
        assert!(
            mx.abs() < 1.0 && (my - 45.0).abs() < 3.0,
            "centre ({mx}, {my})"
        );
    }
}
