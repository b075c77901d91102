//! The colours of a study's drawings: time of day (early blue, noon green, late red) and
//! hours on the false-colour scale.

use crate::render::tonemap::{false_colour, linear_to_srgb};

/// The colour of time `t` in 0..1 (early = blue, noon = green, late = red).
pub fn time_colour(t: f32) -> [u8; 3] {
    let hue = 240.0 * (1.0 - t.clamp(0.0, 1.0));
    let c = hue / 60.0;
    let x = 1.0 - (c % 2.0 - 1.0).abs();
    let (r, g, b) = match c as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        _ => (x, 0.0, 1.0),
    };
    [r, g, b].map(|v: f32| (v * 220.0) as u8)
}

/// The colour of `hours` in shadow on a scale whose top is `scale_hours`.
pub fn hours_colour(hours: f32, scale_hours: f32) -> [u8; 3] {
    let c = false_colour(hours / scale_hours.max(1e-6));
    [
        linear_to_srgb(c.x),
        linear_to_srgb(c.y),
        linear_to_srgb(c.z),
    ]
}
