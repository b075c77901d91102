//! The numeric outputs of an hours map: `hours.asc` (ESRI ASCII grid), `hours.csv` (cell
//! centres) and `hours.exr` (32-bit float), all in the model file's plan coordinates
//! (metres); the pass/fail test against a threshold and the passing fraction of analysis
//! areas given as polygons (GeoJSON).

use std::fmt::Write as _;

use glam::DVec2;

use super::shadow_profile::{Profile, SURFACE_NONE};

/// The value written for cells that see neither ground nor model.
pub const NODATA: f64 = -9999.0;

/// `hours.asc`: the ESRI ASCII grid (row 1 is the north edge, as the format wants), hours
/// per cell; cells outside the ground and model get `NODATA_value`.
pub fn ascii_grid(profile: &Profile, hours: &[f32]) -> String {
    let n = profile.resolution;
    let cell = profile.extent_m / n as f64;
    let sw = profile.pixel_center(0, n - 1) - DVec2::splat(cell / 2.0) + profile.origin;
    let mut out = format!(
        "ncols {n}\nnrows {n}\nxllcorner {:.6}\nyllcorner {:.6}\ncellsize {}\nNODATA_value {NODATA}\n",
        sw.x, sw.y, cell
    );
    for py in 0..n {
        let row: Vec<String> = (0..n)
            .map(|px| {
                let k = (py * n + px) as usize;
                if profile.surface[k] == SURFACE_NONE {
                    format!("{NODATA}")
                } else {
                    format!("{:.4}", hours[k])
                }
            })
            .collect();
        out.push_str(&row.join(" "));
        out.push('\n');
    }
    out
}

/// Every cell that sees ground or model, in the order of `hours.csv` (rows from the top):
/// its index in the plan and its centre in the model file's plan coordinates, metres.
pub fn surface_cells(profile: &Profile) -> impl Iterator<Item = (usize, DVec2)> + '_ {
    let n = profile.resolution;
    (0..n)
        .flat_map(move |py| (0..n).map(move |px| (px, py)))
        .map(move |(px, py)| {
            let k = (py * n + px) as usize;
            (k, profile.pixel_center(px, py) + profile.origin)
        })
        .filter(|&(k, _)| profile.surface[k] != SURFACE_NONE)
}

/// `hours.csv`: `x,y,hours` at every cell centre that sees ground or model.
pub fn hours_csv(profile: &Profile, hours: &[f32]) -> String {
    let mut out = String::from("x,y,hours\n");
    for (k, c) in surface_cells(profile) {
        let _ = writeln!(out, "{:.4},{:.4},{:.4}", c.x, c.y, hours[k]);
    }
    out
}

/// `hours.exr`: hours in every channel (0 outside the ground and model).
pub fn hours_exr(profile: &Profile, hours: &[f32]) -> image::Rgb32FImage {
    let n = profile.resolution;
    image::Rgb32FImage::from_fn(n, n, |x, y| image::Rgb([hours[(y * n + x) as usize]; 3]))
}

pub use crate::geometry::areas::{parse_areas, read_areas, AnalysisArea, AreasError, GeoJsonError};

/// The fraction of the plan's cells (inside `area`, when given) whose hours reach
/// `threshold_h`, over every cell that sees a surface from above: the ground, and the
/// model's roofs and terrain (an area drawn round a garden leaves the building out);
/// `None` when no such cell is inside.
pub fn pass_fraction(
    profile: &Profile,
    hours: &[f32],
    threshold_h: f64,
    area: Option<&AnalysisArea>,
) -> Option<f64> {
    let n = profile.resolution;
    let (mut inside, mut pass) = (0usize, 0usize);
    for py in 0..n {
        for px in 0..n {
            let k = (py * n + px) as usize;
            if profile.surface[k] == SURFACE_NONE {
                continue;
            }
            if let Some(a) = area {
                if !a.contains(profile.pixel_center(px, py) + profile.origin) {
                    continue;
                }
            }
            inside += 1;
            // Hours are sums of f32 step weights: a hair's tolerance keeps 2.0 h ≥ 2 h.
            pass += (hours[k] as f64 >= threshold_h - 1e-4) as usize;
        }
    }
    (inside > 0).then(|| pass as f64 / inside as f64)
}

/// The mean hours over the cells that see a surface from above (ground, roofs, terrain).
pub fn surface_mean(profile: &Profile, hours: &[f32]) -> f64 {
    let (sum, count) = profile
        .surface
        .iter()
        .zip(hours)
        .filter(|(&s, _)| s != SURFACE_NONE)
        .fold((0.0, 0usize), |(s, c), (_, &h)| (s + h as f64, c + 1));
    sum / count.max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: &str = r#"{"type": "Feature", "properties": {"name": "garden"},
        "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [4, 0], [4, 3], [0, 3]]]}}"#;

    #[test]
    fn a_polygon_feature_is_an_area_with_its_name() {
        let areas = parse_areas(SQUARE).unwrap();
        assert_eq!(areas.len(), 1);
        assert_eq!(areas[0].name, "garden");
        assert!(areas[0].contains(DVec2::new(2.0, 1.5)));
        assert!(!areas[0].contains(DVec2::new(5.0, 1.5)));
    }

    #[test]
    fn errors_name_the_field_that_is_wrong() {
        let cases = [
            ("[1, 2", "not JSON"),
            (r#"{"type": "Point"}"#, "`type` is Some(\"Point\")"),
            (
                r#"{"type": "FeatureCollection", "features": 3}"#,
                "`features` is not a list",
            ),
            (
                r#"{"type": "FeatureCollection", "features": []}"#,
                "no features",
            ),
            (
                r#"{"type": "FeatureCollection", "features": [{"geometry": {"type": "Line"}}]}"#,
                "features[0].geometry.type is Some(\"Line\")",
            ),
            (
                r#"{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, 1]]]}}"#,
                "features[0]: a ring has fewer than 3 points",
            ),
            (
                r#"{"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[0, 0], [1, "a"], [2, 2]]]}}"#,
                "features[0].geometry.coordinates: a polygon is a list of rings",
            ),
        ];
        for (text, expected) in cases {
            let e = parse_areas(text).unwrap_err();
            assert!(e.0.starts_with(expected), "{text}: {e}");
        }
    }

    #[test]
    fn a_file_error_names_the_file() {
        let e = read_areas(std::path::Path::new("/nonexistent/areas.geojson")).unwrap_err();
        assert!(matches!(e, AreasError::Read { .. }), "{e:?}");
        assert!(
            e.to_string()
                .starts_with("reading /nonexistent/areas.geojson: "),
            "{e}"
        );
    }
}
