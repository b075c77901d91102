//! Datasheet diagrams of a luminaire (PNG or SVG, `ldt plot`): the polar diagram with the
//! chosen plane pairs overlaid (C0–C180 and C90–C270 by default) and the cartesian
//! diagram of the same curves, scaled to the planes drawn, titled with the luminaire's
//! name, flux and LOR, the legend beside the chart; and the isocandela plan
//! ([`super::isocandela`]). The curve geometry
//! ([`plane_pair_curve`]) is the viewer's too.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::grid::Interp;
use super::isocandela::{gamma_reach, isocandela_map, round_levels, IsocandelaMap};
use super::plot::{png_bytes, rgb_image, svg_string, DrawError, DrawResult};
use super::Luminaire;

const WIDTH: u32 = 1100;
const HEIGHT: u32 = 860;
/// Width of the legend column at the right.
const SIDE: u32 = 250;

/// The curve of the plane pair (c, c + 180°): points (I sin γ, −I cos γ) of `sample(C, γ)`
/// every `step_deg`, plane c on the right (x ≥ 0) from γ = 0 up to 180°, then plane c + 180°
/// on the left back down; γ = 0 points down.
pub fn plane_pair_curve(
    sample: impl Fn(f64, f64) -> f64,
    c_deg: f64,
    step_deg: f64,
) -> Vec<[f64; 2]> {
    let n = (180.0 / step_deg).round() as usize;
    let point = |side: f64, c: f64, k: usize| {
        let g = k as f64 * step_deg;
        let i = sample(c, g);
        let (s, co) = g.to_radians().sin_cos();
        [side * i * s, -i * co]
    };
    (0..=n)
        .map(|k| point(1.0, c_deg, k))
        .chain((0..=n).rev().map(|k| point(-1.0, c_deg + 180.0, k)))
        .collect()
}

/// Which diagram to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum DiagramKind {
    /// Polar: intensity as the radius, γ as the angle.
    Polar,
    /// Cartesian: intensity against the signed angle (plane c to the right of 0°, c + 180°
    /// to the left).
    Cartesian,
    /// Isocandela: lines of equal intensity over all directions, as a plan seen from above
    /// (C0 right, C90 up, radius γ).
    Isocandela,
}

/// A datasheet diagram of `lum`.
pub struct Diagram<'a> {
    /// The luminaire.
    pub lum: &'a Luminaire,
    /// The file's name, shown in the title.
    pub file_name: String,
    /// The planes c of the pairs (c, c + 180°) drawn, degrees.
    pub planes: Vec<f64>,
    /// Interpolation between the measured angles.
    pub interp: Interp,
    /// The lamp flux the title states, lm: a chosen lamp set's (`None`: all sets summed).
    /// The curves are in cd/klm either way.
    pub lamp_flux_lm: Option<f64>,
}

/// Colours and dash of the curves, by the order of the planes (the first two as
/// datasheets draw C0–C180 and C90–C270).
const STYLES: [(RGBColor, bool); 6] = [
    (RGBColor(200, 30, 30), false),
    (RGBColor(30, 80, 200), true),
    (RGBColor(20, 140, 60), false),
    (RGBColor(150, 60, 170), true),
    (RGBColor(230, 130, 0), false),
    (RGBColor(60, 60, 60), true),
];

impl Diagram<'_> {
    fn curves(&self) -> Vec<Vec<[f64; 2]>> {
        let d = &self.lum.distribution;
        self.planes
            .iter()
            .map(|&c| plane_pair_curve(|c, g| d.sample(c, g, self.interp), c, 0.5))
            .collect()
    }

    /// The outer ring / top of the axis, cd/klm: a round value above the largest
    /// intensity on the planes drawn (not the whole sphere's peak).
    pub fn scale(&self) -> f64 {
        let peak = self
            .curves()
            .iter()
            .flatten()
            .map(|p| p[0].hypot(p[1]))
            .fold(0.0, f64::max);
        super::plot::nice_ceiling(peak)
    }

    fn title(&self) -> (String, String) {
        let s = self.lum.summary();
        let lamps = self.lamp_flux_lm.unwrap_or(s.lamp_flux_lm);
        let flux = if s.lamp_flux_lm > 0.0 {
            s.flux_lm * lamps / s.lamp_flux_lm
        } else {
            s.flux_lm
        };
        let name = self.lum.data.luminaire_name.trim();
        (
            if name.is_empty() {
                self.file_name.clone()
            } else {
                format!("{name} ({})", self.file_name)
            },
            format!(
                "{:.0} lm luminaire flux from {:.0} lm lamps, LOR {:.1} %, DFF {:.1} % — cd/klm",
                flux, lamps, s.lorl_computed, s.dff_computed
            ),
        )
    }

    /// Renders as pixels (what the viewer shows; the PNG holds the same).
    pub fn rgb(&self, kind: DiagramKind) -> Result<image::RgbImage, DrawError> {
        rgb_image(WIDTH, HEIGHT, "the diagram", |root| self.draw(root, kind))
    }

    /// Renders as PNG bytes.
    pub fn png(&self, kind: DiagramKind) -> Result<Vec<u8>, DrawError> {
        png_bytes(WIDTH, HEIGHT, "the diagram", |root| self.draw(root, kind))
    }

    /// Renders as SVG.
    pub fn svg(&self, kind: DiagramKind) -> Result<String, DrawError> {
        svg_string(WIDTH, HEIGHT, "the diagram", |root| self.draw(root, kind))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        kind: DiagramKind,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (head, body) = root.split_vertically(70);
        let (title, subtitle) = self.title();
        head.draw(&Text::new(title, (20, 12), ("sans-serif", 22).into_font()))?;
        head.draw(&Text::new(
            subtitle,
            (20, 42),
            ("sans-serif", 15).into_font(),
        ))?;
        let (chart, side) = body.split_horizontally(WIDTH - SIDE);
        match kind {
            DiagramKind::Polar => self.draw_polar(&chart)?,
            DiagramKind::Cartesian => self.draw_cartesian(&chart)?,
            DiagramKind::Isocandela => {
                let map = self.isocandela()?;
                map.draw(&chart)?;
                let s = self.lum.summary();
                let [c, g] = s.max_direction_deg;
                let notes = [
                    "plan seen from above:".to_string(),
                    "C0 right, C90 up,".to_string(),
                    "radius γ (0° = nadir)".to_string(),
                    format!("peak {:.0} cd/klm", s.max_intensity),
                    format!("at C{c:.0} γ{g:.0}"),
                    format!("{} interpolation", self.interp.name()),
                ];
                return map.draw_legend(&side, &notes);
            }
        }
        self.draw_legend(&side)
    }

    /// The isocandela lines at round levels below the peak, over the directions where the
    /// luminaire gives more than 0.5 % of it.
    pub fn isocandela(&self) -> Result<IsocandelaMap, DrawError> {
        let d = &self.lum.distribution;
        let sample = |c: f64, g: f64| d.sample(c, g, self.interp);
        let peak = self.lum.summary().max_intensity;
        let reach = gamma_reach(sample, 0.005 * peak);
        isocandela_map(sample, &round_levels(peak), reach, reach / 200.0)
    }

    fn draw_legend<DB: DrawingBackend>(&self, side: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        side.draw(&Text::new(
            "planes",
            (10, 40),
            ("sans-serif", 16).into_font(),
        ))?;
        for (k, &c) in self.planes.iter().enumerate() {
            let (color, dashed) = STYLES[k % STYLES.len()];
            let y = 72 + 28 * k as i32;
            if dashed {
                for x in (10..44).step_by(10) {
                    side.draw(&PathElement::new(
                        [(x, y), (x + 6, y)],
                        color.stroke_width(3),
                    ))?;
                }
            } else {
                side.draw(&PathElement::new([(10, y), (44, y)], color.stroke_width(3)))?;
            }
            side.draw(&Text::new(
                format!("C{c}–C{}", c + 180.0),
                (54, y - 8),
                ("sans-serif", 15).into_font(),
            ))?;
        }
        let note = ("sans-serif", 13).into_font().color(&RGBColor(90, 90, 90));
        let below = 86 + 28 * self.planes.len() as i32;
        for (k, line) in [
            "plane C to the right,".to_string(),
            "C + 180° to the left".to_string(),
            format!("{} interpolation", self.interp.name()),
        ]
        .into_iter()
        .enumerate()
        {
            side.draw(&Text::new(line, (10, below + 18 * k as i32), note.clone()))?;
        }
        Ok(())
    }

    /// Each plane pair as (signed γ, I): plane c + 180° from −180° to 0, then plane c to
    /// +180°.
    fn profiles(&self) -> Vec<Vec<(f64, f64)>> {
        let d = &self.lum.distribution;
        self.planes
            .iter()
            .map(|&c| {
                let left = (0..=360).rev().map(|k| {
                    let g = k as f64 * 0.5;
                    (-g, d.sample(c + 180.0, g, self.interp))
                });
                let right = (0..=360).map(|k| {
                    let g = k as f64 * 0.5;
                    (g, d.sample(c, g, self.interp))
                });
                left.chain(right).collect()
            })
            .collect()
    }

    fn draw_curves<DB: DrawingBackend, CT: plotters::coord::CoordTranslate<From = (f64, f64)>>(
        &self,
        chart: &mut ChartContext<DB, CT>,
        curves: Vec<Vec<(f64, f64)>>,
    ) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        for (k, points) in curves.into_iter().enumerate() {
            let (color, dashed) = STYLES[k % STYLES.len()];
            let style = color.stroke_width(2);
            if dashed {
                chart.draw_series(DashedLineSeries::new(points, 8, 5, style))?;
            } else {
                chart.draw_series(LineSeries::new(points, style))?;
            }
        }
        Ok(())
    }

    fn draw_polar<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let r_max = self.scale();
        let lim = r_max * 1.14;
        let mut chart = ChartBuilder::on(area)
            .margin(20)
            .build_cartesian_2d(-lim..lim, -lim..lim)?;
        let grey = RGBColor(205, 205, 205);
        let polar = |r: f64, a: f64| {
            let t = a.to_radians();
            (r * t.sin(), -r * t.cos())
        };
        for k in 1..=5 {
            let r = r_max * k as f64 / 5.0;
            chart.draw_series(LineSeries::new((0..=360).map(|a| polar(r, a as f64)), grey))?;
            // Ring values along the upward axis, clear of the curves of downlights.
            chart.draw_series(std::iter::once(Text::new(
                format!("{}", r),
                (r_max * 0.015, r + r_max * 0.01),
                ("sans-serif", 13)
                    .into_font()
                    .color(&RGBColor(100, 100, 100)),
            )))?;
        }
        for a in (0..360).step_by(15) {
            chart.draw_series(LineSeries::new([(0.0, 0.0), polar(r_max, a as f64)], grey))?;
            if a % 30 == 0 {
                let (lx, ly) = polar(r_max * 1.07, a as f64);
                let label = if a <= 180 { a } else { 360 - a };
                chart.draw_series(std::iter::once(Text::new(
                    format!("{label}°"),
                    (lx - r_max * 0.035, ly + r_max * 0.02),
                    ("sans-serif", 14).into_font(),
                )))?;
            }
        }
        let curves = self
            .curves()
            .into_iter()
            .map(|c| c.into_iter().map(|p| (p[0], p[1])).collect())
            .collect();
        self.draw_curves(&mut chart, curves)
    }

    fn draw_cartesian<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        let top = self.scale();
        // The range where any curve exceeds 0.5 % of the scale, in 10° steps.
        let profiles = self.profiles();
        let reach = profiles
            .iter()
            .flatten()
            .filter(|&&(_, i)| i > 0.005 * top)
            .map(|&(g, _)| g.abs())
            .fold(10.0, f64::max);
        let lim = ((reach / 10.0).ceil() * 10.0).min(180.0);
        let mut chart = ChartBuilder::on(area)
            .margin(20)
            .x_label_area_size(44)
            .y_label_area_size(70)
            .build_cartesian_2d(-lim..lim, 0.0..top)?;
        chart
            .configure_mesh()
            .x_desc("γ (°), plane C + 180° to the left")
            .y_desc("intensity (cd/klm)")
            .x_label_formatter(&|v| format!("{v:.0}"))
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style(("sans-serif", 14))
            .draw()?;
        let clipped = profiles
            .into_iter()
            .map(|p| p.into_iter().filter(|(g, _)| g.abs() <= lim).collect())
            .collect();
        self.draw_curves(&mut chart, clipped)
    }
}
