//! Polar goniometric diagrams as PNG or SVG: the C0–C180 and C90–C270 planes side by side, the
//! measured values marked, each interpolation drawn over them (as Wallner Fig. 3.6).

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::FontStyle;

use super::grid::{angle_eq, Grid, Interp};
use crate::io::{write_atomic, WriteError};

/// The bundled font (DejaVu Sans, Bitstream Vera licence, see `assets/fonts/`).
pub static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

const WIDTH: u32 = 1400;
const HEIGHT: u32 = 800;

/// Registers the bundled font with plotters as "sans-serif" (once).
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The bundled font is known to be valid; a failure would only lose the labels.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// What to draw: curves reconstructed from `curves`, points of `measured` (both cd/klm).
pub struct PolarPlot<'a> {
    /// Title line.
    pub title: String,
    /// The grid the interpolated curves come from.
    pub curves: &'a Grid,
    /// The measured values to mark (the same grid, or a finer measurement).
    pub measured: &'a Grid,
    /// Methods to draw.
    pub methods: Vec<Interp>,
}

/// A drawing's result: plotters' backends have their own error types.
pub type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Draws a north arrow in a circle of radius `r` pixels round `centre`, pointing
/// `north_deg` clockwise from the drawing's up, with "N" written left of the circle in
/// `font`.
pub fn draw_north_arrow<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (cx, cy): (i32, i32),
    r: f64,
    north_deg: f64,
    font: TextStyle,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let a = north_deg.to_radians();
    let (dx, dy) = (a.sin(), -a.cos());
    let tip = (cx + (r * dx) as i32, cy + (r * dy) as i32);
    let tail = (cx - (r * dx) as i32, cy - (r * dy) as i32);
    area.draw(&Circle::new((cx, cy), r as i32 + 4, BLACK))?;
    area.draw(&PathElement::new([tail, tip], BLACK.stroke_width(3)))?;
    let side = (-dy, dx);
    let barb = |sign: f64| {
        (
            tip.0 - (12.0 * dx + sign * 7.0 * side.0) as i32,
            tip.1 - (12.0 * dy + sign * 7.0 * side.1) as i32,
        )
    };
    area.draw(&Polygon::new(
        vec![tip, barb(1.0), barb(-1.0)],
        BLACK.filled(),
    ))?;
    area.draw(&Text::new("N", (cx - r as i32 - 26, cy - 9), font))?;
    Ok(())
}

/// The drawing area of a bitmap.
pub type BitMapArea<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// Why a picture could not be drawn or encoded: `what` names the picture ("the polar
/// diagram"), `why` is the drawing backend's or encoder's message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("drawing {what}: {why}")]
pub struct DrawError {
    /// The picture.
    pub what: String,
    /// The backend's or encoder's message.
    pub why: String,
}

impl DrawError {
    /// `what` could not be drawn: `why`.
    pub fn new(what: &str, why: impl std::fmt::Display) -> DrawError {
        DrawError {
            what: what.to_string(),
            why: why.to_string(),
        }
    }
}

/// Draws on a white `width` × `height` bitmap; `what` names the picture in the error.
pub fn rgb_image(
    width: u32,
    height: u32,
    what: &str,
    draw: impl FnOnce(&BitMapArea) -> DrawResult,
) -> Result<image::RgbImage, DrawError> {
    register_font();
    let mut buf = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        draw(&root)
            .and_then(|()| root.present().map_err(Into::into))
            .map_err(|e| DrawError::new(what, e))?;
    }
    Ok(image::RgbImage::from_raw(width, height, buf).expect("a buffer of width × height × 3"))
}

/// Draws on a white `width` × `height` bitmap and encodes it as PNG; `what` names the
/// picture in the error.
pub fn png_bytes(
    width: u32,
    height: u32,
    what: &str,
    draw: impl FnOnce(&BitMapArea) -> DrawResult,
) -> Result<Vec<u8>, DrawError> {
    let img = rgb_image(width, height, what, draw)?;
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| DrawError::new(what, e))?;
    Ok(png)
}

/// Draws on a white `width` × `height` SVG canvas; `what` names the picture in the error.
pub fn svg_string(
    width: u32,
    height: u32,
    what: &str,
    draw: impl FnOnce(&DrawingArea<SVGBackend, plotters::coord::Shift>) -> DrawResult,
) -> Result<String, DrawError> {
    register_font();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| DrawError::new(what, e))?;
        draw(&root)
            .and_then(|()| root.present().map_err(Into::into))
            .map_err(|e| DrawError::new(what, e))?;
    }
    Ok(svg)
}

/// Colour and label of each interpolation in every diagram.
pub fn style(interp: Interp) -> (RGBColor, &'static str) {
    match interp {
        Interp::Nearest => (RGBColor(150, 150, 150), "nearest"),
        Interp::Bilinear => (RGBColor(0, 0, 0), "bilinear"),
        Interp::CatmullRom => (RGBColor(30, 90, 230), "Catmull-Rom"),
        Interp::Monotone => (RGBColor(20, 160, 60), "monotone cubic"),
    }
}

/// Intensity along the great circle through planes `c` and `c + 180` at signed angle `t`
/// (t ≥ 0: plane c at γ = t; t < 0: plane c + 180 at γ = −t), as plot coordinates with
/// γ = 0 pointing down.
fn polar_point(value: f64, t_deg: f64) -> (f64, f64) {
    let t = t_deg.to_radians();
    (value * t.sin(), -value * t.cos())
}

/// A round radius for the outer ring.
pub fn nice_ceiling(v: f64) -> f64 {
    if v <= 0.0 {
        return 1.0;
    }
    let mag = 10f64.powf(v.log10().floor());
    for m in [1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0] {
        if m * mag >= v {
            return m * mag;
        }
    }
    10.0 * mag
}

impl PolarPlot<'_> {
    /// Renders the diagram to PNG bytes.
    pub fn render_png(&self) -> Result<Vec<u8>, DrawError> {
        png_bytes(WIDTH, HEIGHT, "the polar diagram", |root| self.draw(root))
    }

    /// Renders the diagram as SVG (the same drawing as the PNG, as vectors).
    pub fn render_svg(&self) -> Result<String, DrawError> {
        svg_string(WIDTH, HEIGHT, "the polar diagram", |root| self.draw(root))
    }

    /// Renders and writes the diagram (atomically): SVG when `path` ends in `.svg` (any
    /// case), else PNG.
    pub fn save(&self, path: &Path) -> Result<(), WriteError> {
        let svg = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let bytes = if svg {
            self.render_svg()
                .map_err(|e| WriteError::encode(path, e))?
                .into_bytes()
        } else {
            self.render_png().map_err(|e| WriteError::encode(path, e))?
        };
        write_atomic(path, &bytes)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, plotters::coord::Shift>) -> DrawResult
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (head, body) = root.split_vertically(48);
        head.draw(&Text::new(
            self.title.clone(),
            (20, 14),
            ("sans-serif", 22).into_font(),
        ))?;
        let r_max = nice_ceiling(
            self.measured
                .values()
                .iter()
                .chain(self.curves.values())
                .cloned()
                .fold(0.0, f64::max),
        );
        for (panel, c) in body.split_evenly((1, 2)).iter().zip([0.0, 90.0]) {
            self.draw_panel(panel, c, r_max)?;
        }
        Ok(())
    }

    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, plotters::coord::Shift>,
        c: f64,
        r_max: f64,
    ) -> Result<(), Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        let lim = r_max * 1.12;
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!("C{1} ←  C{0}–C{1} plane (cd/klm)  → C{0}", c, c + 180.0),
                ("sans-serif", 20),
            )
            .margin(16)
            .build_cartesian_2d(-lim..lim, -lim..lim)?;
        let grey = RGBColor(210, 210, 210);
        for k in 1..=4 {
            let r = r_max * k as f64 / 4.0;
            chart.draw_series(LineSeries::new(
                (0..=360).map(|a| polar_point(r, a as f64)),
                grey,
            ))?;
            chart.draw_series(std::iter::once(Text::new(
                format!("{}", r),
                (r * 0.03, r),
                ("sans-serif", 13)
                    .into_font()
                    .color(&RGBColor(110, 110, 110)),
            )))?;
        }
        for a in (0..360).step_by(30) {
            let (x, y) = polar_point(r_max, a as f64);
            chart.draw_series(LineSeries::new([(0.0, 0.0), (x, y)], grey))?;
            let (lx, ly) = polar_point(r_max * 1.06, a as f64);
            let label = if a <= 180 { a } else { 360 - a };
            chart.draw_series(std::iter::once(Text::new(
                format!("{label}°"),
                (lx - r_max * 0.03, ly + r_max * 0.02),
                ("sans-serif", 13).into_font(),
            )))?;
        }
        let red = RGBColor(220, 30, 30);
        let radius = if self.measured.gamma_angles().len() > 60 {
            2
        } else {
            3
        };
        let mut marks = Vec::new();
        for (plane_c, sign) in [(c, 1.0), (c + 180.0, -1.0)] {
            let Some(ci) = self
                .measured
                .c_angles()
                .iter()
                .position(|&a| angle_eq(a, plane_c))
                .or_else(|| (self.measured.c_angles().len() == 1).then_some(0))
            else {
                continue;
            };
            for (gi, &g) in self.measured.gamma_angles().iter().enumerate() {
                marks.push(polar_point(self.measured.value(ci, gi), sign * g));
            }
        }
        chart
            .draw_series(
                marks
                    .into_iter()
                    .map(|p| Circle::new(p, radius, red.filled())),
            )?
            .label("measured")
            .legend(move |(x, y)| Circle::new((x + 10, y), 3, red.filled()));
        for &interp in &self.methods {
            let (color, name) = style(interp);
            let points: Vec<(f64, f64)> = (-720..=720)
                .map(|i| {
                    let t = i as f64 * 0.25;
                    let v = if t >= 0.0 {
                        self.curves.sample(c, t, interp)
                    } else {
                        self.curves.sample(c + 180.0, -t, interp)
                    };
                    polar_point(v, t)
                })
                .collect();
            let series = if interp == Interp::Bilinear {
                chart.draw_series(DashedLineSeries::new(points, 6, 4, color.stroke_width(2)))?
            } else {
                chart.draw_series(LineSeries::new(points, color.stroke_width(2)))?
            };
            series.label(name).legend(move |(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], color.stroke_width(2))
            });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()?;
        Ok(())
    }
}

/// A round step (1, 2 or 5 × 10^k) giving about `count` intervals over `span`.
pub fn round_step(span: f64, count: f64) -> f64 {
    let raw = (span / count).max(1e-9);
    let magnitude = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * magnitude)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * magnitude)
}
