//! Calculation surfaces (`[[grid]]` in the scene file): virtual grids of points where
//! illuminance is computed — they never block or reflect light. A rectangle or a polygon
//! outline in plan at a height (horizontal), or a vertical rectangle on a wall; points at
//! the centres of the cells, the spacing given or chosen by EN 12464-1.
//!
//! ```toml
//! [[grid]]
//! name = "work plane"
//! corner = [0.0, 0.0]   # plan position of one corner, metres (or: outline = [[x, y], …])
//! size = [6.0, 4.0]     # metres along x and y (vertical: along the wall, up)
//! height = 0.8          # metres above z = 0 (vertical: of the bottom edge)
//! spacing = 0.5         # metres, or "en12464" (the default)
//! border = 0.0          # band excluded along the outline, metres
//! exclude = [[x, y], …] # a polygon left out (a column), metres
//! kind = "horizontal"   # "vertical", "ceiling" (facing down), "cylindrical", "semicylindrical"
//! normal = [0.0, -1.0, 0.0]  # vertical: the wall's front; semicylindrical: the facing
//! ```

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::geometry::polygon::{self, distance_to_outline, inside};

/// What a grid's points measure.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum GridKind {
    /// Illuminance on a horizontal plane facing up.
    #[default]
    Horizontal,
    /// Illuminance on a vertical plane facing `normal`.
    Vertical,
    /// Illuminance on a horizontal plane facing down (a ceiling's).
    Ceiling,
    /// Cylindrical illuminance: the mean of the vertical illuminance over all horizontal
    /// directions (EN 12464-1's E_z).
    Cylindrical,
    /// Semi-cylindrical illuminance facing `normal`: the mean over the half cylinder that
    /// faces it (EN 12464-1's E_sc).
    Semicylindrical,
}

/// The spacing of a grid's points.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(untagged)]
pub enum Spacing {
    /// Metres between points.
    Metres(f64),
    /// A rule by name: `"en12464"`.
    Rule(String),
}

impl Default for Spacing {
    fn default() -> Self {
        Spacing::Rule("en12464".into())
    }
}

/// `[[grid]]` as written in the scene file.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GridEntry {
    /// The grid's name (also its CSV file's name).
    pub name: String,
    /// Plan position of one corner of a rectangle, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub corner: Option<[f64; 2]>,
    /// The rectangle's size along x and y (vertical grids: along the wall and up), metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub size: Option<[f64; 2]>,
    /// A polygon outline in plan instead of a rectangle (horizontal kinds), metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub outline: Option<Vec<[f64; 2]>>,
    /// A polygon in plan left out of the grid (a column, a task area inside its
    /// surrounding), metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub exclude: Option<Vec<[f64; 2]>>,
    /// Height above z = 0 (vertical grids: of the bottom edge), metres.
    #[serde(default = "default_height")]
    pub height: f64,
    /// Metres between points, or `"en12464"`.
    #[serde(default)]
    pub spacing: Spacing,
    /// A band along the outline left out (the surrounding area of a task area), metres.
    #[serde(default)]
    pub border: f64,
    /// What the points measure.
    #[serde(default)]
    pub kind: GridKind,
    /// Vertical: the direction the wall faces; semi-cylindrical: the facing direction.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub normal: Option<[f64; 3]>,
}

fn default_height() -> f64 {
    0.8
}

/// Most points one grid may hold.
pub const MAX_POINTS: usize = 1_000_000;

/// A grid ready to compute: its points, and the direction each measures.
#[derive(Debug, Clone)]
pub struct CalcGrid {
    /// The entry it came from.
    pub entry: GridEntry,
    /// The points, metres.
    pub points: Vec<DVec3>,
    /// The spacing used along each side, metres.
    pub spacing: [f64; 2],
    /// Vertical and semi-cylindrical: the unit facing direction (horizontal).
    pub facing: Option<DVec3>,
}

/// EN 12464-1's maximum grid spacing for an area whose longer side is `d` metres:
/// p = 0.2 · 5^log10(d) (at most 10 m).
pub fn en12464_spacing(d: f64) -> f64 {
    (0.2 * 5f64.powf(d.log10())).min(10.0)
}

/// Points per side for a side of `length` metres at spacing `p`: the nearest whole number
/// of length / p, at least one.
fn count(length: f64, p: f64) -> usize {
    ((length / p).round() as usize).max(1)
}

/// Centres of `n` equal cells along `length` from `start`.
fn centres(start: f64, length: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| start + (i as f64 + 0.5) * length / n as f64)
}

impl GridEntry {
    /// The outline in the grid's own 2D frame (plan; vertical: along the wall, up),
    /// checked. Errors name the key and what is wrong.
    pub fn plan_outline(&self) -> Result<Vec<[f64; 2]>, (String, String)> {
        let bad = |key: &str, msg: String| Err((key.to_string(), msg));
        match (&self.outline, self.corner, self.size) {
            (Some(o), None, None) => {
                if self.kind == GridKind::Vertical {
                    return bad(
                        "outline",
                        "a vertical grid is a rectangle: give corner and size".into(),
                    );
                }
                if o.len() < 3 || o.iter().flatten().any(|v| !v.is_finite()) {
                    return bad("outline", "give at least three finite [x, y] points".into());
                }
                Ok(o.clone())
            }
            (None, Some(c), Some(s)) => {
                if !c.iter().all(|v| v.is_finite()) {
                    return bad("corner", format!("{c:?}: give two finite coordinates"));
                }
                if !(s.iter().all(|v| v.is_finite()) && s[0] > 0.0 && s[1] > 0.0) {
                    return bad("size", format!("{s:?}: give two positive lengths"));
                }
                Ok(polygon::rectangle(c, s))
            }
            _ => bad(
                "corner",
                "give corner and size, or outline (not both)".into(),
            ),
        }
    }

    /// The grid's points. Errors name the key (relative to this grid) and what is wrong.
    pub fn resolve(&self) -> Result<CalcGrid, (String, String)> {
        let bad = |key: &str, msg: String| Err((key.to_string(), msg));
        if self.name.trim().is_empty() {
            return bad("name", "give the grid a name".into());
        }
        if !self.height.is_finite() {
            return bad("height", format!("{} is not a height", self.height));
        }
        if !(self.border.is_finite() && self.border >= 0.0) {
            return bad(
                "border",
                format!("{} is not a width (metres ≥ 0)", self.border),
            );
        }
        let facing = match (self.kind, self.normal) {
            (GridKind::Vertical | GridKind::Semicylindrical, None) => {
                return bad(
                    "normal",
                    format!("a {:?} grid needs the direction it faces", self.kind).to_lowercase(),
                )
            }
            (GridKind::Vertical | GridKind::Semicylindrical, Some(n)) => {
                match crate::geometry::unit(DVec3::from_array(n)) {
                    Some(v) if v.z.abs() <= 1e-9 => Some(DVec3::new(v.x, v.y, 0.0).normalize()),
                    _ => {
                        return bad(
                            "normal",
                            format!("{n:?}: give a horizontal direction [x, y, 0]"),
                        )
                    }
                }
            }
            (_, Some(_)) => {
                return bad(
                    "normal",
                    "only vertical and semicylindrical grids face a direction".into(),
                )
            }
            (_, None) => None,
        };
        let polygon = self.plan_outline()?;
        let exclude = match &self.exclude {
            Some(_) if self.kind == GridKind::Vertical => {
                return bad("exclude", "only grids in plan leave a polygon out".into())
            }
            Some(o) if o.len() < 3 || o.iter().flatten().any(|v| !v.is_finite()) => {
                return bad("exclude", "give at least three finite [x, y] points".into())
            }
            other => other.as_deref(),
        };
        let (lo, hi) = polygon::bounds(&polygon);
        let extent = [hi[0] - lo[0], hi[1] - lo[1]];
        let longer = extent[0].max(extent[1]);
        let p = match &self.spacing {
            Spacing::Metres(p) if p.is_finite() && *p > 0.0 => *p,
            Spacing::Metres(p) => {
                return bad("spacing", format!("{p}: give metres > 0 or \"en12464\""))
            }
            Spacing::Rule(r) if r == "en12464" => en12464_spacing(longer),
            Spacing::Rule(r) => {
                return bad("spacing", format!("{r:?}: give metres or \"en12464\""))
            }
        };
        let n = [count(extent[0], p), count(extent[1], p)];
        if n[0].saturating_mul(n[1]) > MAX_POINTS {
            return bad(
                "spacing",
                format!("{} × {} points; at most {MAX_POINTS} per grid", n[0], n[1]),
            );
        }
        let rectangle = self.outline.is_none();
        let mut plan = Vec::new();
        for v in centres(lo[1], extent[1], n[1]) {
            for u in centres(lo[0], extent[0], n[0]) {
                let keep = (rectangle || inside(&polygon, u, v))
                    && (self.border == 0.0 || distance_to_outline(&polygon, u, v) >= self.border)
                    && !exclude.is_some_and(|x| inside(x, u, v));
                if keep {
                    plan.push([u, v]);
                }
            }
        }
        if plan.is_empty() {
            return bad(
                "border",
                "no point is left inside the outline, its border and what it leaves out".into(),
            );
        }
        let points = plan
            .into_iter()
            .map(|[u, v]| match (self.kind, facing) {
                (GridKind::Vertical, Some(f)) => {
                    // Along the wall to the right of someone looking at it: z × f.
                    let along = DVec3::Z.cross(f);
                    let c = self.corner.unwrap_or_default();
                    DVec3::new(c[0], c[1], self.height)
                        + along * (u - lo[0])
                        + DVec3::Z * (v - lo[1])
                }
                _ => DVec3::new(u, v, self.height),
            })
            .collect::<Vec<DVec3>>();
        if points.iter().any(|p| !p.is_finite()) {
            return bad(
                "size",
                "the grid reaches beyond any usable coordinate".into(),
            );
        }
        Ok(CalcGrid {
            entry: self.clone(),
            points,
            spacing: [extent[0] / n[0] as f64, extent[1] / n[1] as f64],
            facing,
        })
    }
}

/// `[calc]` in the scene file: settings of `goniolight calc`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CalcSettings {
    /// Maintenance factor: the values reported are the computed ones times it (EN 12464-1's
    /// maintained illuminance). 1 (new installation) when not given.
    #[serde(default = "one")]
    pub maintenance_factor: f64,
    /// Direct light only or total light (`calc --indirect`); none when not given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indirect: Option<Indirect>,
}

/// What light `calc` computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, schemars::JsonSchema)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Indirect {
    /// The luminaires' direct light only.
    None,
    /// Direct plus the interreflected light of a radiosity solution.
    Radiosity,
}

fn one() -> f64 {
    1.0
}

impl Default for CalcSettings {
    fn default() -> Self {
        CalcSettings {
            maintenance_factor: 1.0,
            indirect: None,
        }
    }
}

impl CalcSettings {
    /// Refuses a maintenance factor outside (0, 1].
    pub fn check(maintenance_factor: f64) -> Result<f64, String> {
        if maintenance_factor.is_finite() && maintenance_factor > 0.0 && maintenance_factor <= 1.0 {
            Ok(maintenance_factor)
        } else {
            Err(format!(
                "{maintenance_factor}: a maintenance factor is above 0 and at most 1"
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(size: [f64; 2]) -> GridEntry {
        GridEntry {
            name: "g".into(),
            corner: Some([0.0, 0.0]),
            size: Some(size),
            outline: None,
            exclude: None,
            height: 0.8,
            spacing: Spacing::default(),
            border: 0.0,
            kind: GridKind::Horizontal,
            normal: None,
        }
    }

    #[test]
    fn en12464_counts_follow_the_formula() {
        // p = 0.2 · 5^log10(d); points per side = round(side / p), at cell centres.
        for (size, p, n) in [
            ([1.0, 1.0], 0.2, [5, 5]),
            ([6.0, 4.0], 0.2 * 5f64.powf(6f64.log10()), [9, 6]),
            ([40.0, 20.0], 0.2 * 5f64.powf(40f64.log10()), [15, 8]),
        ] {
            assert!((en12464_spacing(size[0]) - p).abs() < 1e-12);
            let g = rect(size).resolve().unwrap();
            assert_eq!(g.points.len(), n[0] * n[1], "{size:?}");
            let dx = size[0] / n[0] as f64;
            assert!((g.points[0].x - dx / 2.0).abs() < 1e-12);
            assert!((g.points[1].x - g.points[0].x - dx).abs() < 1e-12);
        }
    }

    #[test]
    fn borders_and_outlines_leave_points_out() {
        let mut g = rect([4.0, 4.0]);
        g.spacing = Spacing::Metres(0.5);
        assert_eq!(g.resolve().unwrap().points.len(), 64);
        g.border = 0.5;
        // Centres 0.25 from the edge go: 6 × 6 remain.
        assert_eq!(g.resolve().unwrap().points.len(), 36);
        let mut l = rect([1.0, 1.0]);
        l.corner = None;
        l.size = None;
        l.outline = Some(vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 2.0],
            [2.0, 2.0],
            [2.0, 4.0],
            [0.0, 4.0],
        ]);
        l.spacing = Spacing::Metres(0.5);
        assert_eq!(l.resolve().unwrap().points.len(), 48); // an L: 64 − 16
    }

    #[test]
    fn vertical_grids_stand_on_the_wall_facing_their_normal() {
        let mut g = rect([2.0, 1.0]);
        g.kind = GridKind::Vertical;
        g.normal = Some([0.0, -1.0, 0.0]);
        g.height = 1.0;
        g.spacing = Spacing::Metres(0.5);
        let r = g.resolve().unwrap();
        assert_eq!(r.facing, Some(DVec3::NEG_Y));
        assert_eq!(r.points.len(), 8);
        assert!(r
            .points
            .iter()
            .all(|p| p.y == 0.0 && (1.0..2.0).contains(&p.z)));
        assert!(r.points.iter().all(|p| (0.0..2.0).contains(&p.x)));
        let mut bad = g.clone();
        bad.normal = Some([0.0, 0.0, 1.0]);
        assert_eq!(bad.resolve().unwrap_err().0, "normal");
    }
}
