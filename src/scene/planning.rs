//! `[[window]]` and `[[open_space]]`: the window reference points and the gardens and
//! open spaces of the planning tests ([`crate::planning`]: VSC, probable sunlight hours,
//! EN 17037 sunlight exposure, the 2-hour sun test on 21 March).
//!
//! ```toml
//! [[window]]
//! name = "flat 1.02 living room"
//! position = [12.0, -0.05, 4.5]   # the centre of the window on its outside face, metres
//! normal = [0, -1, 0]             # outward
//!
//! [[open_space]]
//! name = "garden"
//! corner = [0.0, -25.0]           # or outline = [[x, y], …], as [[grid]]
//! size = [20.0, 20.0]
//! height = 0.0                    # the ground's height, metres (default 0)
//! spacing = 0.25                  # metres between the points judged (default 0.25)
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::grid::{CalcGrid, GridEntry, GridKind, Spacing};

/// `[[window]]` as written in the scene file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WindowEntry {
    /// The window's name.
    pub name: String,
    /// The reference point: the centre of the window on its outside face, metres.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub position: [f64; 3],
    /// The window's outward normal.
    #[serde(deserialize_with = "crate::io::exact::array")]
    pub normal: [f64; 3],
}

/// A window reference point ready to judge.
#[derive(Debug, Clone, PartialEq)]
pub struct Window {
    /// The entry as written.
    pub entry: WindowEntry,
    /// The reference point, metres.
    pub position: DVec3,
    /// The outward unit normal.
    pub normal: DVec3,
}

impl WindowEntry {
    /// The window, or the key (relative to this entry) and what is wrong.
    pub fn resolve(&self) -> Result<Window, (String, String)> {
        if self.name.trim().is_empty() {
            return Err(("name".into(), "give the window a name".into()));
        }
        let position = DVec3::from_array(self.position);
        if !position.is_finite() {
            return Err((
                "position".into(),
                format!("{:?} is not a point", self.position),
            ));
        }
        let normal = crate::geometry::unit(DVec3::from_array(self.normal)).ok_or_else(|| {
            (
                "normal".to_string(),
                format!("{:?} is not a direction", self.normal),
            )
        })?;
        Ok(Window {
            entry: self.clone(),
            position,
            normal,
        })
    }
}

/// Metres between the points of an open space, by default.
pub const DEFAULT_OPEN_SPACE_SPACING: f64 = 0.25;

/// `[[open_space]]` as written in the scene file: a garden or amenity area on the ground.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct OpenSpaceEntry {
    /// The open space's name.
    pub name: String,
    /// Plan position of one corner of a rectangle, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub corner: Option<[f64; 2]>,
    /// The rectangle's size along x and y, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub size: Option<[f64; 2]>,
    /// A polygon outline in plan instead of a rectangle, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub outline: Option<Vec<[f64; 2]>>,
    /// The ground's height, metres (default 0).
    #[serde(default)]
    pub height: f64,
    /// Metres between the points judged (default 0.25).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
}

/// An open space ready to judge: its points on the ground, one per equal cell.
#[derive(Debug, Clone)]
pub struct OpenSpace {
    /// The entry as written (for an area read from GeoJSON: its name, its first outline).
    pub entry: OpenSpaceEntry,
    /// The points (cell centres inside the outline), as a horizontal grid.
    pub grid: CalcGrid,
    /// The outlines drawn on plans: the outline, or every ring of an area's polygons.
    pub outlines: Vec<Vec<[f64; 2]>>,
}

impl OpenSpace {
    /// The open space of an analysis area (GeoJSON; holes and several polygons allowed)
    /// on the ground at z = 0: the centres of `spacing` m cells inside it; an error when
    /// none is.
    pub fn from_area(
        area: &crate::geometry::areas::AnalysisArea,
        spacing: f64,
    ) -> Result<OpenSpace, String> {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(format!("{spacing}: give metres > 0"));
        }
        let rings: Vec<Vec<[f64; 2]>> = area
            .polygons
            .iter()
            .flatten()
            .map(|ring| ring.iter().map(|p| p.to_array()).collect())
            .collect();
        let (lo, hi) = crate::geometry::polygon::bounds(&rings.concat());
        let n = [0, 1].map(|i| ((hi[i] - lo[i]) / spacing).ceil().max(1.0) as usize);
        if n[0].saturating_mul(n[1]) > super::grid::MAX_POINTS {
            return Err(format!(
                "{} × {} points; at most {} per area",
                n[0],
                n[1],
                super::grid::MAX_POINTS
            ));
        }
        let mut points = Vec::new();
        for j in 0..n[1] {
            for i in 0..n[0] {
                let p = glam::DVec2::new(
                    lo[0] + (i as f64 + 0.5) * spacing,
                    lo[1] + (j as f64 + 0.5) * spacing,
                );
                if area.contains(p) {
                    points.push(DVec3::new(p.x, p.y, 0.0));
                }
            }
        }
        if points.is_empty() {
            return Err(format!("no point of a {spacing} m grid lies inside"));
        }
        let entry = OpenSpaceEntry {
            name: area.name.clone(),
            corner: None,
            size: None,
            outline: rings.first().cloned(),
            height: 0.0,
            spacing: Some(spacing),
        };
        let grid = CalcGrid {
            entry: entry.grid_entry(),
            points,
            spacing: [spacing, spacing],
            facing: None,
        };
        Ok(OpenSpace {
            entry,
            grid,
            outlines: rings,
        })
    }
}

impl OpenSpaceEntry {
    /// The open space's points, or the key (relative to this entry) and what is wrong.
    pub fn resolve(&self) -> Result<OpenSpace, (String, String)> {
        let grid = self.grid_entry().resolve()?;
        let outline = grid.entry.plan_outline()?;
        Ok(OpenSpace {
            entry: self.clone(),
            grid,
            outlines: vec![outline],
        })
    }

    /// The horizontal grid the entry describes.
    fn grid_entry(&self) -> GridEntry {
        GridEntry {
            name: self.name.clone(),
            corner: self.corner,
            size: self.size,
            outline: self.outline.clone(),
            exclude: None,
            height: self.height,
            spacing: Spacing::Metres(self.spacing.unwrap_or(DEFAULT_OPEN_SPACE_SPACING)),
            border: 0.0,
            kind: GridKind::Horizontal,
            normal: None,
        }
    }
}

/// The planning tests' places of a scene.
#[derive(Debug, Clone, Default)]
pub struct PlanningPlaces {
    /// `[[window]]`s.
    pub windows: Vec<Window>,
    /// `[[open_space]]`s.
    pub open_spaces: Vec<OpenSpace>,
}

impl PlanningPlaces {
    /// Whether there is nothing to judge.
    pub fn is_empty(&self) -> bool {
        self.windows.is_empty() && self.open_spaces.is_empty()
    }

    /// Adds the windows of a `profile --points` file's text ([`parse_window_points`]);
    /// errors name the point and key, or a name that a window has already (ignoring case
    /// and surrounding blanks).
    pub fn add_points(&mut self, text: &str) -> Result<(), String> {
        for (k, window) in parse_window_points(text)?.into_iter().enumerate() {
            let name = window.entry.name.trim().to_lowercase();
            if self
                .windows
                .iter()
                .any(|w| w.entry.name.trim().to_lowercase() == name)
            {
                return Err(format!(
                    "point[{k}].name: {:?} names a window already; give each its own name",
                    window.entry.name
                ));
            }
            self.windows.push(window);
        }
        Ok(())
    }
}

/// The windows of a `profile --points` file's text: `[[point]]` tables with a window's
/// keys (name, position, normal), at least one; errors name the point and key.
pub fn parse_window_points(text: &str) -> Result<Vec<Window>, String> {
    let file: PointsFile = toml::from_str(text).map_err(|e| e.to_string())?;
    if file.point.is_empty() {
        return Err("no [[point]]".into());
    }
    file.point
        .iter()
        .enumerate()
        .map(|(k, entry)| {
            entry
                .resolve()
                .map_err(|(key, msg)| format!("point[{k}].{key}: {msg}"))
        })
        .collect()
}

/// A `profile --points` file: `[[point]]` tables with a window's keys.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PointsFile {
    #[serde(default)]
    point: Vec<WindowEntry>,
}
