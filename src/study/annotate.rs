//! The frame around every raster plan of a study: a title and subtitle (site, date, time
//! range with its zone), metre axes in the model file's plan coordinates, a north arrow and
//! a scale bar — all outside the plan, so nothing covers it.

use plotters::prelude::*;

use super::shadow_profile::Profile;
use crate::photometry::plot::register_font;

/// Pixels left of the plan (the y axis and its labels).
pub const LEFT: u32 = 96;
/// Pixels above the plan (title, subtitle, north arrow).
pub const TOP: u32 = 84;
/// Pixels below the plan (the x axis, its labels and the scale bar).
pub const BOTTOM: u32 = 78;

/// What the frame says.
#[derive(Debug, Clone, Default)]
pub struct PlanLabels {
    /// First line: what the plan shows and where.
    pub title: String,
    /// Second line: date, time and zone (a step's time and sun for a step frame).
    pub subtitle: String,
    /// Angle from the model's +Y clockwise to true north, degrees (the arrow's direction).
    pub north_offset_deg: f64,
}

pub use crate::photometry::plot::round_step;

/// Where a drawing lies in metres: its size in pixels, its scale and the metres at its
/// left and bottom edges, the axes' names, and the north arrow's angle (plans only).
#[derive(Debug, Clone)]
pub struct Frame {
    /// The drawing's width and height, pixels.
    pub size_px: (u32, u32),
    /// Pixels per metre.
    pub px_per_m: f64,
    /// Metres at the left edge (x axis) and the bottom edge (y axis).
    pub left_bottom_m: (f64, f64),
    /// The axes' names.
    pub axes: (String, String),
    /// Angle from the drawing's up to true north, clockwise, degrees (`None`: no arrow).
    pub north_offset_deg: Option<f64>,
}

impl Frame {
    /// The frame of a profile's plan (the model file's coordinates, north arrow).
    pub fn plan(profile: &Profile, north_offset_deg: f64) -> Frame {
        let e = profile.extent_m;
        Frame {
            size_px: (profile.resolution, profile.resolution),
            px_per_m: profile.resolution as f64 / e,
            left_bottom_m: (
                profile.center.x - e / 2.0 + profile.origin.x,
                profile.center.y - e / 2.0 + profile.origin.y,
            ),
            axes: ("x (m), plan north up".into(), "y (m)".into()),
            north_offset_deg: Some(north_offset_deg),
        }
    }
}

/// `body` (the n × n plan at its top-left, a legend panel beside it) inside the plan's
/// frame: the plan lands at ([`LEFT`], [`TOP`]).
pub fn annotate(
    profile: &Profile,
    body: &image::RgbaImage,
    labels: &PlanLabels,
) -> image::RgbaImage {
    framed(&Frame::plan(profile, labels.north_offset_deg), body, labels)
}

/// `body` (the drawing of `frame` at its top-left, anything beside it) inside `frame`: the
/// drawing lands at ([`LEFT`], [`TOP`]).
pub fn framed(frame: &Frame, body: &image::RgbaImage, labels: &PlanLabels) -> image::RgbaImage {
    let (bw, bh) = body.dimensions();
    // The north arrow sits above the plan's right corner, or right of the titles where
    // they reach further (a small plan under a long title), and the image widens for it.
    let arrow_x = arrow_x(frame.size_px.0, labels);
    let width = (LEFT + bw + 12).max(arrow_x + 48);
    compose((width, TOP + bh + BOTTOM), body, LEFT, |root| {
        draw_frame(root, frame, labels, arrow_x as i32)
    })
}

/// The north arrow's centre: above the right corner of a plan `plan_width` pixels wide,
/// or clear of the titles (its circle's radius is 34 pixels).
fn arrow_x(plan_width: u32, labels: &PlanLabels) -> u32 {
    (LEFT + plan_width)
        .saturating_sub(40)
        .max(titles_width(labels) + 44)
}

/// About how wide the title and subtitle are drawn, pixels (sans-serif averages under 0.6
/// of its size per character), with the margins.
fn titles_width(labels: &PlanLabels) -> u32 {
    let text = |line: &str, px: f64| (line.chars().count() as f64 * 0.6 * px) as u32 + 24;
    text(&labels.title, 21.0).max(text(&labels.subtitle, 15.0))
}

/// A white `size` image drawn on by `draw`, with `body` pasted at (`left`, [`TOP`]).
fn compose(
    (w, h): (u32, u32),
    body: &image::RgbaImage,
    left: u32,
    draw: impl FnOnce(
        &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    ) -> Result<
        (),
        DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>,
    >,
) -> image::RgbaImage {
    register_font();
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let _ = draw(&root);
        let _ = root.present();
    }
    let mut out = image::RgbaImage::from_fn(w, h, |x, y| {
        let k = ((y * w + x) * 3) as usize;
        image::Rgba([rgb[k], rgb[k + 1], rgb[k + 2], 255])
    });
    image::imageops::replace(&mut out, body, left as i64, TOP as i64);
    out
}

/// `body` (a view that has no plan axes: a perspective drawing, a legend beside it) under
/// the labels' title and subtitle.
pub fn titled(body: &image::RgbaImage, labels: &PlanLabels) -> image::RgbaImage {
    let (bw, bh) = body.dimensions();
    let width = bw.max(titles_width(labels));
    compose((width, TOP + bh), body, 0, |root| draw_titles(root, labels))
}

fn draw_titles<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    labels: &PlanLabels,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.draw(&Text::new(
        labels.title.as_str(),
        (12, 10),
        ("sans-serif", 21).into_font().color(&BLACK),
    ))?;
    root.draw(&Text::new(
        labels.subtitle.as_str(),
        (12, 42),
        ("sans-serif", 15).into_font().color(&BLACK),
    ))?;
    Ok(())
}

fn draw_frame<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    frame: &Frame,
    labels: &PlanLabels,
    arrow_x: i32,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let black = ("sans-serif", 15).into_font().color(&BLACK);
    draw_titles(root, labels)?;
    let (left, top) = (LEFT as i32, TOP as i32);
    let (w_i, h_i) = (frame.size_px.0 as i32, frame.size_px.1 as i32);
    root.draw(&Rectangle::new(
        [(left - 1, top - 1), (left + w_i, top + h_i)],
        BLACK,
    ))?;
    // Metre axes: ticks at round values of the file's coordinates.
    let px_per_m = frame.px_per_m;
    let (west, south) = frame.left_bottom_m;
    let (width_m, height_m) = (w_i as f64 / px_per_m, h_i as f64 / px_per_m);
    let step = round_step(
        width_m.max(height_m),
        (w_i.max(h_i) as f64 / 110.0).clamp(2.0, 8.0),
    );
    let label = |v: f64| tick_label(v, step);
    let mut v = (west / step).ceil() * step;
    while v <= west + width_m + 1e-9 {
        let x = left + ((v - west) * px_per_m).round() as i32;
        root.draw(&PathElement::new(
            [(x, top + h_i), (x, top + h_i + 6)],
            BLACK,
        ))?;
        root.draw(&Text::new(label(v), (x - 14, top + h_i + 9), black.clone()))?;
        v += step;
    }
    let mut v = (south / step).ceil() * step;
    while v <= south + height_m + 1e-9 {
        let y = top + h_i - ((v - south) * px_per_m).round() as i32;
        root.draw(&PathElement::new([(left - 6, y), (left, y)], BLACK))?;
        let text = label(v);
        let x = left - 10 - 8 * text.chars().count() as i32;
        root.draw(&Text::new(text, (x, y - 8), black.clone()))?;
        v += step;
    }
    root.draw(&Text::new(
        frame.axes.0.as_str(),
        (left, top + h_i + 30),
        black.clone(),
    ))?;
    root.draw(&Text::new(
        frame.axes.1.as_str(),
        (8, top + h_i / 2),
        black.clone(),
    ))?;
    // The scale bar under the drawing's right corner.
    let metres = round_step(150.0 / px_per_m, 1.0);
    let length = (metres * px_per_m).round() as i32;
    let (x1, y) = (left + w_i, top + h_i + 56);
    root.draw(&PathElement::new(
        [(x1 - length, y), (x1, y)],
        BLACK.stroke_width(3),
    ))?;
    for x in [x1 - length, x1] {
        root.draw(&PathElement::new(
            [(x, y - 6), (x, y + 6)],
            BLACK.stroke_width(2),
        ))?;
    }
    let bar = if metres >= 1.0 {
        format!("{metres:.0} m")
    } else {
        format!("{metres} m")
    };
    root.draw(&Text::new(bar, (x1 - length - 70, y - 9), black.clone()))?;
    // The north arrow above the plan's right corner.
    let Some(north) = frame.north_offset_deg else {
        return Ok(());
    };
    crate::photometry::plot::draw_north_arrow(root, (arrow_x, TOP as i32 / 2), 30.0, north, black)
}

/// A metre axis tick's label: `v` on the grid of `step` (so that summed steps print as
/// the round values they stand for, and zero never as "-0"), whole metres for steps of a
/// metre or more.
fn tick_label(v: f64, step: f64) -> String {
    let v = (v / step).round() * step + 0.0;
    if step >= 1.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_north_arrow_keeps_clear_of_a_long_title_over_a_small_plan() {
        let labels = super::PlanLabels {
            title: "Hours of sun — 48.2100° N, 16.3700° E".into(),
            subtitle: "2026-03-21, 08:00–17:00 Europe/Vienna, every 60 min".into(),
            north_offset_deg: 0.0,
        };
        let width = super::titles_width(&labels);
        assert!(super::arrow_x(64, &labels) >= width + 34 + 8);
        // Over a wide plan it stays above the plan's right corner.
        assert_eq!(super::arrow_x(1024, &labels), super::LEFT + 1024 - 40);
    }

    #[test]
    fn tick_labels_never_read_minus_zero() {
        assert_eq!(super::tick_label(-0.0, 50.0), "0");
        assert_eq!(super::tick_label(-1e-13, 50.0), "0");
        assert_eq!(super::tick_label(-50.0 + 1e-12, 50.0), "-50");
        assert_eq!(super::tick_label(0.30000000000000004, 0.1), "0.3");
    }

    use super::round_step;

    #[test]
    fn steps_are_round() {
        assert_eq!(round_step(100.0, 5.0), 20.0);
        assert_eq!(round_step(220.0, 8.0), 50.0);
        assert_eq!(round_step(7.0, 5.0), 2.0);
        assert_eq!(round_step(0.9, 4.0), 0.5);
    }
}
