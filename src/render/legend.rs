//! The false-colour legend: a colour bar with lux labels drawn into the image's right
//! edge (plotters, bundled font).

use plotters::prelude::*;

use super::tonemap::{false_colour, linear_to_srgb};
use crate::photometry::plot::register_font;

/// Draws the legend for a scale from 0 to `lux_max` into `image`.
pub fn draw_legend(image: &mut image::RgbaImage, lux_max: f64) {
    register_font();
    let (w, h) = image.dimensions();
    let font_px = (h / 40).clamp(9, 22);
    let panel_w = font_px * 6;
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
        let _ = root.draw(&Text::new(
            "lux",
            (x0 + margin / 2, margin / 2),
            style.clone(),
        ));
        let top = margin * 2;
        let bottom = h as i32 - margin;
        let bar_x = x0 + margin / 2;
        let bar_w = (font_px as i32).max(8);
        let span = (bottom - top).max(1);
        for y in top..bottom {
            let t = (bottom - y) as f32 / span as f32;
            let c = false_colour(t);
            let colour = RGBColor(
                linear_to_srgb(c.x),
                linear_to_srgb(c.y),
                linear_to_srgb(c.z),
            );
            let _ = root.draw(&PathElement::new([(bar_x, y), (bar_x + bar_w, y)], colour));
        }
        for k in 0..=4 {
            let v = lux_max * k as f64 / 4.0;
            let y = bottom - span * k / 4;
            let label = if k == 4 {
                format!("≥{}", format_lux(v))
            } else {
                format_lux(v)
            };
            let _ = root.draw(&PathElement::new(
                [(bar_x + bar_w, y), (bar_x + bar_w + 4, y)],
                BLACK,
            ));
            let _ = root.draw(&Text::new(
                label,
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

fn format_lux(v: f64) -> String {
    if v >= 100.0 || v == 0.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}
