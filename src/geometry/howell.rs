//! Analytic form factors (Howell, "A Catalog of Radiation Heat Transfer Configuration
//! Factors"): the references of the radiosity tests and the UGR table's room.

use std::f64::consts::PI;

/// Between identical, directly opposed parallel rectangles a × b at distance c (C-11).
pub fn parallel_rectangles(a: f64, b: f64, c: f64) -> f64 {
    let (x, y) = (a / c, b / c);
    let (x2, y2) = (x * x, y * y);
    2.0 / (PI * x * y)
        * (((1.0 + x2) * (1.0 + y2) / (1.0 + x2 + y2)).sqrt().ln()
            + x * (1.0 + y2).sqrt() * (x / (1.0 + y2).sqrt()).atan()
            + y * (1.0 + x2).sqrt() * (y / (1.0 + x2).sqrt()).atan()
            - x * x.atan()
            - y * y.atan())
}

/// From a rectangle w × l to a perpendicular rectangle h × l sharing the edge of
/// length l (C-14).
pub fn perpendicular_rectangles(w: f64, h: f64, l: f64) -> f64 {
    let (w, h) = (w / l, h / l);
    let (w2, h2) = (w * w, h * h);
    let s = (h2 + w2).sqrt();
    let log = ((1.0 + w2) * (1.0 + h2) / (1.0 + w2 + h2)).ln()
        + w2 * (w2 * (1.0 + w2 + h2) / ((1.0 + w2) * (w2 + h2))).ln()
        + h2 * (h2 * (1.0 + h2 + w2) / ((1.0 + h2) * (h2 + w2))).ln();
    (w * (1.0 / w).atan() + h * (1.0 / h).atan() - s * (1.0 / s).atan() + 0.25 * log) / (PI * w)
}

/// From a disc of radius r1 to a coaxial parallel disc of radius r2 at distance h (C-41).
pub fn coaxial_discs(r1: f64, r2: f64, h: f64) -> f64 {
    let (a, b) = (r1 / h, r2 / h);
    let x = 1.0 + (1.0 + b * b) / (a * a);
    0.5 * (x - (x * x - 4.0 * (b / a).powi(2)).sqrt())
}
