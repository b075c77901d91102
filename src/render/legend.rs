//! The false-colour legend: a colour bar with lux labels drawn into the image's right
//! edge (plotters, bundled font).

use plotters::prelude::*;

use super::tonemap::{linear_to_srgb, ToneSettings};
use crate::photometry::plot::register_font;

/// `view` widened by a panel on the right carrying the lux legend of `tone`: its
/// palette (stepped when it has steps) and nice labels, the top one marked "≥", under the
/// title "lux" and `light` (what the lux are: "direct", "total", …).
pub fn beside_lux_legend(
    view: &image::RgbaImage,
    tone: &ToneSettings,
    light: &str,
) -> image::RgbaImage {
    let values = tone.legend_labels();
    let last = values.len() - 1;
    let labels: Vec<String> = values
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            if k == last {
                format!("≥{}", format_lux(v))
            } else {
                format_lux(v)
            }
        })
        .collect();
    with_legend_panel(view, &format!("lux\n{light}"), &labels, |t| {
        let c = tone.palette.stepped_colour(t, tone.steps);
        [
            linear_to_srgb(c.x),
            linear_to_srgb(c.y),
            linear_to_srgb(c.z),
        ]
    })
}

/// `plan` widened by a white panel on the right that carries a colour bar (see
/// [`draw_colour_bar`]), so the legend never covers the plan.
pub fn with_legend_panel(
    plan: &image::RgbaImage,
    title: &str,
    labels: &[String],
    colour: impl Fn(f32) -> [u8; 3],
) -> image::RgbaImage {
    let (w, h) = plan.dimensions();
    if h < font_px(h) * 8 {
        return plan.clone(); // too small to carry a legend
    }
    let panel = panel_width(h, title, labels);
    let mut out = image::RgbaImage::from_pixel(w + panel, h, image::Rgba([255, 255, 255, 255]));
    image::imageops::replace(&mut out, plan, 0, 0);
    draw_colour_bar(&mut out, title, labels, colour);
    out
}

fn font_px(height: u32) -> u32 {
    (height / 40).clamp(9, 22)
}

/// Wide enough for the labels beside the bar, and for the title's lines.
fn panel_width(height: u32, title: &str, labels: &[String]) -> u32 {
    let widest = labels.iter().map(|l| l.chars().count()).max().unwrap_or(4) as u32;
    let title = title.lines().map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    font_px(height) * (widest / 2 + 4).max(6).max(title * 3 / 5 + 1)
}

/// Draws a vertical colour bar into a panel at `image`'s right edge: `title` on top (one
/// line per line of it),
/// `colour(t)` (sRGB) from t = 0 at the bottom to 1 at the top, and `labels` spread
/// evenly from bottom to top.
pub fn draw_colour_bar(
    image: &mut image::RgbaImage,
    title: &str,
    labels: &[String],
    colour: impl Fn(f32) -> [u8; 3],
) {
    register_font();
    let (w, h) = image.dimensions();
    let font_px = font_px(h);
    let panel_w = panel_width(h, title, labels);
    if w < panel_w * 2 || h < font_px * 8 {
        return; // too small to carry a legend
    }
    let mut rgb: Vec<u8> = image.pixels().flat_map(|p| [p[0], p[1], p[2]]).collect();
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let x0 = (w - panel_w) as i32;
        let margin = font_px as i32;
        let _ = root.draw(&Rectangle::new(
            [(x0, 0), (w as i32, h as i32)],
            RGBColor(245, 245, 245).mix(0.85).filled(),
        ));
        let style = ("sans-serif", font_px).into_font().color(&BLACK);
        let mut lines = 0;
        for (k, line) in title.lines().enumerate() {
            let _ = root.draw(&Text::new(
                line,
                (x0 + margin / 2, margin / 2 + k as i32 * margin * 6 / 5),
                style.clone(),
            ));
            lines += 1;
        }
        // Under a title of several lines, half a line more before the top label.
        let top = margin * 2 + (lines.max(1) - 1) * (margin * 6 / 5 + margin / 2);
        let bottom = h as i32 - margin;
        let bar_x = x0 + margin / 2;
        let bar_w = (font_px as i32).max(8);
        let span = (bottom - top).max(1);
        for y in top..bottom {
            let [r, g, b] = colour((bottom - y) as f32 / span as f32);
            let _ = root.draw(&PathElement::new(
                [(bar_x, y), (bar_x + bar_w, y)],
                RGBColor(r, g, b),
            ));
        }
        let steps = labels.len().saturating_sub(1).max(1) as i32;
        for (k, label) in labels.iter().enumerate() {
            let y = bottom - span * k as i32 / steps;
            let _ = root.draw(&PathElement::new(
                [(bar_x + bar_w, y), (bar_x + bar_w + 4, y)],
                BLACK,
            ));
            let _ = root.draw(&Text::new(
                label.as_str(),
                (bar_x + bar_w + 6, y - font_px as i32 / 2),
                style.clone(),
            ));
        }
        let _ = root.present();
    }
    for (p, c) in image.pixels_mut().zip(rgb.chunks_exact(3)) {
        *p = image::Rgba([c[0], c[1], c[2], 255]);
    }
}

/// A lux value for a label: whole numbers without decimals (0, 250, 1000), others with
/// up to two (62.5, 0.25).
pub fn format_lux(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 * v.abs().max(1.0) {
        return format!("{v:.0}");
    }
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}
