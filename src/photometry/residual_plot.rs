//! Pictures of an interpolation check's residuals (`ldt check --residuals`): the RMS error
//! against γ per method (SVG) and a C × γ heat map of every residual per method (PNG).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::catalogue::median;
use super::check::CheckReport;
use super::grid::Interp;
use super::plot::{png_bytes, style, svg_string, DrawError, DrawResult};

/// The heat map's colour for angles that were not hidden (kept measured values).
const NOT_HIDDEN: RGBColor = RGBColor(165, 165, 165);

/// Width of the legend or colour bar drawn beside a chart.
const SIDE: u32 = 230;

/// The RMS of each method's residuals at each γ angle, as an SVG line chart with the
/// legend beside it; `title` names the file.
pub fn gamma_error_svg(report: &CheckReport, title: &str) -> Result<String, DrawError> {
    let gammas = distinct(report.residuals.iter().map(|r| r.gamma_deg));
    // rms[m][k]: method m at gammas[k].
    let rms: Vec<Vec<f64>> = (0..Interp::ALL.len())
        .map(|m| {
            gammas
                .iter()
                .map(|&g| {
                    let at: Vec<f64> = report
                        .residuals
                        .iter()
                        .filter(|r| r.gamma_deg == g)
                        .map(|r| r.error[m] * r.error[m])
                        .collect();
                    (at.iter().sum::<f64>() / at.len().max(1) as f64).sqrt()
                })
                .collect()
        })
        .collect();
    let y_max = rms.iter().flatten().cloned().fold(0.0, f64::max).max(1e-9) * 1.08;
    let (g_lo, g_hi) = match (gammas.first(), gammas.last()) {
        (Some(&a), Some(&b)) if b > a => (a, b),
        _ => (0.0, 180.0),
    };
    svg_string(1000, 520, "the error-vs-γ chart", |root| {
        let (plot, side) = root.split_horizontally(1000 - SIDE);
        let mut chart = ChartBuilder::on(&plot)
            .caption(
                format!("{title}: RMS error per γ ({})", report.mode),
                ("sans-serif", 20),
            )
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(g_lo..g_hi, 0.0..y_max)?;
        chart
            .configure_mesh()
            .x_desc("γ (°)")
            .y_desc("RMS of reconstructed − measured (cd/klm)")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .label_style(("sans-serif", 14))
            .draw()?;
        for (m, interp) in Interp::ALL.into_iter().enumerate() {
            let (color, _) = style(interp);
            let points: Vec<(f64, f64)> = gammas.iter().cloned().zip(rms[m].clone()).collect();
            chart.draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?;
            chart.draw_series(
                points
                    .into_iter()
                    .map(|p| Circle::new(p, 3, color.filled())),
            )?;
        }
        legend(&side, report)
    })
}

/// The methods' names, colours and overall RMS beside a chart.
fn legend(side: &DrawingArea<SVGBackend, Shift>, report: &CheckReport) -> DrawResult {
    side.draw(&Text::new(
        "method (RMS, cd/klm)",
        (10, 60),
        ("sans-serif", 15).into_font(),
    ))?;
    for (m, interp) in Interp::ALL.into_iter().enumerate() {
        let (color, name) = style(interp);
        let y = 92 + 28 * m as i32;
        side.draw(&PathElement::new([(10, y), (40, y)], color.stroke_width(3)))?;
        let rms = report
            .methods
            .get(super::check::method_key(interp))
            .map_or(f64::NAN, |r| r.rms);
        side.draw(&Text::new(
            format!("{name} ({rms:.3})"),
            (48, y - 8),
            ("sans-serif", 14).into_font(),
        ))?;
    }
    Ok(())
}

/// A C × γ heat map of every residual, one panel per method on one shared diverging
/// scale (clipped at the 99th percentile of |error|), with the colour bar beside; angles
/// that were not hidden are grey. PNG bytes.
pub fn heat_map_png(report: &CheckReport, title: &str) -> Result<Vec<u8>, DrawError> {
    let res = &report.residuals;
    let cs = distinct(res.iter().map(|r| r.c_deg));
    let gs = distinct(res.iter().map(|r| r.gamma_deg));
    let c_edges = edges(&cs, 7.5);
    let g_edges = edges(&gs, 2.5);
    // The scale follows the smooth methods (nearest's steps would wash them out; its
    // panel saturates instead, which shows just as plainly).
    let mut magnitudes: Vec<f64> = res
        .iter()
        .flat_map(|r| r.error[1..].iter().map(|e| e.abs()))
        .collect();
    magnitudes.sort_by(f64::total_cmp);
    let scale = magnitudes
        .get(((magnitudes.len() as f64 * 0.99) as usize).min(magnitudes.len().saturating_sub(1)))
        .cloned()
        .unwrap_or(0.0)
        .max(1e-9);
    let (w, h) = (1400u32, 900u32);
    png_bytes(w, h, "the residual heat map", |root| {
        root.fill(&WHITE)?;
        let (head, body) = root.split_vertically(64);
        head.draw(&Text::new(
            format!(
                "{title}: reconstructed − measured ({}, {} values)",
                report.mode,
                res.len()
            ),
            (16, 10),
            ("sans-serif", 20).into_font(),
        ))?;
        head.draw(&Text::new(
            format!(
                "one colour scale for all four: the 99th percentile of the smooth methods' |error| ({scale:.3} cd/klm; their median {:.3})",
                median(&magnitudes)
            ),
            (16, 38),
            ("sans-serif", 15).into_font(),
        ))?;
        let (panels, bar) = body.split_horizontally(w - SIDE);
        for (m, (panel, interp)) in panels
            .split_evenly((2, 2))
            .iter()
            .zip(Interp::ALL)
            .enumerate()
        {
            let x_range = c_edges[0]..c_edges[c_edges.len() - 1];
            let y_range = g_edges[g_edges.len() - 1]..g_edges[0];
            let mut chart = ChartBuilder::on(panel)
                .caption(style(interp).1, ("sans-serif", 17))
                .margin(10)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(x_range, y_range)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc("C (°)")
                .y_desc("γ (°)")
                .x_labels(13)
                .y_labels(10)
                .x_label_formatter(&|v| format!("{v:.0}"))
                .y_label_formatter(&|v| format!("{v:.0}"))
                .label_style(("sans-serif", 12))
                .draw()?;
            chart.plotting_area().fill(&NOT_HIDDEN)?;
            chart.draw_series(res.iter().map(|r| {
                let (ci, gi) = (index_of(&cs, r.c_deg), index_of(&gs, r.gamma_deg));
                Rectangle::new(
                    [
                        (c_edges[ci], g_edges[gi]),
                        (c_edges[ci + 1], g_edges[gi + 1]),
                    ],
                    diverging(r.error[m] / scale).filled(),
                )
            }))?;
        }
        colour_bar(&bar, scale)
    })
}

/// The diverging colour bar from −`scale` to +`scale` cd/klm.
fn colour_bar(area: &DrawingArea<BitMapBackend, Shift>, scale: f64) -> DrawResult {
    let (x0, x1, y0, y1) = (30, 62, 60, 760);
    for y in y0..y1 {
        let t = 1.0 - 2.0 * (y - y0) as f64 / (y1 - y0) as f64;
        area.draw(&PathElement::new([(x0, y), (x1, y)], diverging(t)))?;
    }
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK))?;
    for k in 0..=4 {
        let t = 1.0 - k as f64 / 2.0;
        let y = y0 + (y1 - y0) * k / 4;
        let prefix = match k {
            0 => "≥ ",
            4 => "≤ ",
            _ => "",
        };
        area.draw(&PathElement::new([(x1, y), (x1 + 6, y)], BLACK))?;
        area.draw(&Text::new(
            format!("{prefix}{:+.3}", t * scale),
            (x1 + 10, y - 7),
            ("sans-serif", 14).into_font(),
        ))?;
    }
    area.draw(&Text::new(
        "cd/klm",
        (x0, y0 - 28),
        ("sans-serif", 15).into_font(),
    ))?;
    area.draw(&Rectangle::new(
        [(x0, y1 + 24), (x1, y1 + 40)],
        NOT_HIDDEN.filled(),
    ))?;
    area.draw(&Text::new(
        "kept (not hidden)",
        (x1 + 10, y1 + 25),
        ("sans-serif", 13).into_font(),
    ))?;
    Ok(())
}

/// Blue (−1) through white (0) to red (+1); values beyond ±1 are clipped.
fn diverging(t: f64) -> RGBColor {
    let t = t.clamp(-1.0, 1.0);
    let white = [247.0, 247.0, 247.0];
    let end = if t < 0.0 {
        [33.0, 102.0, 172.0]
    } else {
        [178.0, 24.0, 43.0]
    };
    let a = t.abs();
    let mix = |k: usize| (white[k] + (end[k] - white[k]) * a).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

/// The sorted distinct values.
fn distinct(values: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = values.collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// Cell edges around sorted `centres`: midpoints between neighbours, half a step beyond
/// the ends (`half` for a single centre).
fn edges(centres: &[f64], half: f64) -> Vec<f64> {
    match centres {
        [] => vec![0.0, 1.0],
        [c] => vec![c - half, c + half],
        _ => {
            let n = centres.len();
            let mut e = vec![centres[0] - 0.5 * (centres[1] - centres[0])];
            e.extend(centres.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            e.push(centres[n - 1] + 0.5 * (centres[n - 1] - centres[n - 2]));
            e
        }
    }
}

fn index_of(sorted: &[f64], v: f64) -> usize {
    sorted.partition_point(|&x| x < v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_surround_each_centre() {
        assert_eq!(edges(&[0.0, 10.0, 30.0], 1.0), vec![-5.0, 5.0, 20.0, 40.0]);
        assert_eq!(edges(&[90.0], 7.5), vec![82.5, 97.5]);
    }

    #[test]
    fn diverging_ends_and_middle() {
        assert_eq!(diverging(0.0), RGBColor(247, 247, 247));
        assert_eq!(diverging(-3.0), RGBColor(33, 102, 172));
        assert_eq!(diverging(1.0), RGBColor(178, 24, 43));
    }
}
