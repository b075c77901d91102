//! Named analysis areas in plan — gardens, open spaces, courtyards — read from GeoJSON
//! (Polygon and MultiPolygon features, holes allowed) in the model file's plan
//! coordinates, metres: the sun study's `--areas` and the planning tests' open spaces.

use std::path::Path;

use glam::DVec2;

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
