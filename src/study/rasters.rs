//! The numeric outputs of an hours map: `hours.asc` (ESRI ASCII grid), `hours.csv` (cell
//! centres) and `hours.exr` (32-bit float), all in the model file's plan coordinates
//! (metres); the pass/fail test against a threshold and the passing fraction of analysis
//! areas given as polygons (GeoJSON).

use std::fmt::Write as _;
use std::path::Path;

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

/// A named analysis area: one or more polygons (outer ring, then holes) in the model
/// file's plan coordinates.
#[derive(Debug, Clone)]
pub struct AnalysisArea {
    /// Its name (the feature's `name` property, or `area N`).
    pub name: String,
    /// Polygons, each a list of rings (the first the outline, the rest holes).
    pub polygons: Vec<Vec<Vec<DVec2>>>,
}

impl AnalysisArea {
    /// Whether `p` lies inside (even-odd over every ring of every polygon).
    pub fn contains(&self, p: DVec2) -> bool {
        self.polygons
            .iter()
            .any(|rings| rings.iter().filter(|ring| ring_contains(ring, p)).count() % 2 == 1)
    }
}

fn ring_contains(ring: &[DVec2], p: DVec2) -> bool {
    let mut inside = false;
    let mut j = ring.len().wrapping_sub(1);
    for i in 0..ring.len() {
        let (a, b) = (ring[i], ring[j]);
        if (a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// Why analysis areas could not be read.
#[derive(Debug, thiserror::Error)]
pub enum AreasError {
    /// The file could not be read.
    #[error("reading {}: {source}", path.display())]
    Read {
        /// The file.
        path: std::path::PathBuf,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not the GeoJSON of polygons that an analysis area is.
    #[error("{}: {source}", path.display())]
    Invalid {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong, naming the field.
        #[source]
        source: GeoJsonError,
    },
}

/// What is wrong with a GeoJSON text of analysis areas, naming the field
/// (`features[2].geometry.type`).
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("{0}")]
pub struct GeoJsonError(pub String);

/// Reads analysis areas from a GeoJSON FeatureCollection (or one Feature) of Polygon and
/// MultiPolygon geometries in the model file's plan coordinates, metres.
pub fn read_areas(path: &Path) -> Result<Vec<AnalysisArea>, AreasError> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_TEXT_BYTES).map_err(|source| {
        AreasError::Read {
            path: path.to_path_buf(),
            source,
        }
    })?;
    parse_areas(&text).map_err(|source| AreasError::Invalid {
        path: path.to_path_buf(),
        source,
    })
}

/// Parses analysis areas from GeoJSON text (see [`read_areas`]).
pub fn parse_areas(text: &str) -> Result<Vec<AnalysisArea>, GeoJsonError> {
    let v: serde_json::Value =
        serde_json::from_str(text).map_err(|e| GeoJsonError(format!("not JSON: {e}")))?;
    let features: Vec<&serde_json::Value> = match v["type"].as_str() {
        Some("FeatureCollection") => v["features"]
            .as_array()
            .ok_or_else(|| GeoJsonError("`features` is not a list".into()))?
            .iter()
            .collect(),
        Some("Feature") => vec![&v],
        other => {
            return Err(GeoJsonError(format!(
                "`type` is {other:?}, not \"FeatureCollection\" or \"Feature\""
            )))
        }
    };
    let mut areas = Vec::new();
    for (k, f) in features.iter().enumerate() {
        let at = format!("features[{k}]");
        let name = f["properties"]["name"]
            .as_str()
            .map_or_else(|| format!("area {}", k + 1), str::to_string);
        let g = &f["geometry"];
        let polygons = match g["type"].as_str() {
            Some("Polygon") => vec![rings(&g["coordinates"], &at)?],
            Some("MultiPolygon") => g["coordinates"]
                .as_array()
                .ok_or_else(|| GeoJsonError(format!("{at}.geometry.coordinates is not a list")))?
                .iter()
                .map(|p| rings(p, &at))
                .collect::<Result<_, _>>()?,
            other => {
                return Err(GeoJsonError(format!(
                    "{at}.geometry.type is {other:?}, not Polygon or MultiPolygon"
                )))
            }
        };
        areas.push(AnalysisArea { name, polygons });
    }
    if areas.is_empty() {
        return Err(GeoJsonError("no features".into()));
    }
    Ok(areas)
}

fn rings(v: &serde_json::Value, at: &str) -> Result<Vec<Vec<DVec2>>, GeoJsonError> {
    let bad = || {
        GeoJsonError(format!(
            "{at}.geometry.coordinates: a polygon is a list of rings of [x, y]"
        ))
    };
    let rings = v.as_array().ok_or_else(bad)?;
    let mut out = Vec::new();
    for ring in rings {
        let points = ring
            .as_array()
            .ok_or_else(bad)?
            .iter()
            .map(|p| match (p[0].as_f64(), p[1].as_f64()) {
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => Ok(DVec2::new(x, y)),
                _ => Err(bad()),
            })
            .collect::<Result<Vec<_>, _>>()?;
        if points.len() < 3 {
            return Err(GeoJsonError(format!(
                "{at}: a ring has fewer than 3 points"
            )));
        }
        out.push(points);
    }
    if out.is_empty() {
        return Err(GeoJsonError(format!("{at}: a polygon without rings")));
    }
    Ok(out)
}

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
        let e = read_areas(Path::new("/nonexistent/areas.geojson")).unwrap_err();
        assert!(matches!(e, AreasError::Read { .. }), "{e:?}");
        assert!(
            e.to_string()
                .starts_with("reading /nonexistent/areas.geojson: "),
            "{e}"
        );
    }
}
