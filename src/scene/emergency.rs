//! EN 1838 emergency lighting (`[[emergency]]` in the scene file, judged by `calc
//! --emergency`): escape routes, open (anti-panic) areas, high-risk task areas and points
//! of safety equipment, lit by the luminaires that have an emergency output
//! (`emergency_flux_lm` or `ballast_lumen_factor` in their `[[luminaire]]`), direct light
//! only, as the standard requires.
//!
//! ```toml
//! [[emergency]]
//! name = "corridor"
//! kind = "route"                # a centre line with its band (at most 2 m wide)
//! line = [[0.5, 1.0], [19.5, 1.0]]
//! width = 2.0
//!
//! [[emergency]]
//! name = "hall"
//! kind = "open-area"            # anti-panic: the area less a 0.5 m border
//! corner = [0.0, 2.0]           # or outline = [[x, y], …]
//! size = [10.0, 8.0]
//!
//! [[emergency]]
//! name = "saw"
//! kind = "high-risk"
//! corner = [12.0, 3.0]
//! size = [2.0, 1.0]
//! height = 0.9
//! em = 500                      # the task's required maintained illuminance (normal)
//!
//! [[emergency]]
//! name = "extinguisher"
//! kind = "point"                # safety equipment: vertical illuminance on its front
//! position = [5.0, 0.05, 1.2]
//! normal = [0.0, 1.0, 0.0]
//! ```
//!
//! Requirements (EN 1838:2013): a route's centre line Emin ≥ 1 lx and Emax/Emin ≤ 40, its
//! central band (half its width) Emin ≥ 0.5 lx; an open area Emin ≥ 0.5 lx and
//! Emax/Emin ≤ 40 over the area less 0.5 m along its outline; a high-risk task area Emin
//! ≥ 10 % of the task's maintained illuminance and at least 15 lx (Emin: the stricter
//! reading), Emin/Emax ≥ 0.1; a point of safety equipment ≥ 5 lx vertical; every
//! emergency luminaire's intensity 60–90° from the downward vertical within the
//! standard's table for its mounting height.

use serde::{Deserialize, Serialize};

use super::grid::{GridEntry, GridKind, Spacing};
use super::requirement::{AreaPart, Quantity, Requirement};
use crate::geometry::polygon;

/// What an emergency area is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum EmergencyKind {
    /// An escape route: a centre line with its band.
    Route,
    /// An open (anti-panic) area.
    OpenArea,
    /// A high-risk task area.
    HighRisk,
    /// A point of safety equipment (a fire extinguisher, a call point, a first-aid box).
    Point,
}

/// `[[emergency]]` as written in the scene file.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EmergencyEntry {
    /// The area's name (and its grids').
    pub name: String,
    /// What it is.
    pub kind: EmergencyKind,
    /// A route's centre line in plan, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub line: Option<Vec<[f64; 2]>>,
    /// A route's width, metres (more than 0, at most 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
    /// An area's corner in plan, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub corner: Option<[f64; 2]>,
    /// An area's size along x and y, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub size: Option<[f64; 2]>,
    /// An area's outline in plan, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub outline: Option<Vec<[f64; 2]>>,
    /// Height of the plane above z = 0, metres (default 0: the floor).
    #[serde(default)]
    pub height: f64,
    /// Metres between points (default 0.2 for routes, the EN 12464-1 rule for areas).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spacing: Option<f64>,
    /// A high-risk task's required maintained illuminance under normal lighting, lx.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub em: Option<f64>,
    /// A point's position, metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub position: Option<[f64; 3]>,
    /// A point's front (horizontal), the way the equipment faces.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option"
    )]
    pub normal: Option<[f64; 3]>,
}

/// The widest escape route judged as one, metres (wider: several routes or an open area).
pub const MAX_ROUTE_WIDTH: f64 = 2.0;
/// Default spacing of a route's points, metres.
pub const ROUTE_SPACING: f64 = 0.2;
/// The border left out of an open area, metres.
pub const OPEN_AREA_BORDER: f64 = 0.5;

/// EN 1838's highest intensity (cd) 60–90° from the downward vertical for a luminaire
/// mounted `h` metres above the floor: escape routes and open areas, or high-risk task
/// areas.
pub fn glare_limit_cd(h: f64, high_risk: bool) -> f64 {
    const HEIGHTS: [f64; 5] = [2.5, 3.0, 3.5, 4.0, 4.5];
    const ROUTES: [f64; 6] = [500.0, 900.0, 1600.0, 2500.0, 3500.0, 5000.0];
    const HIGH_RISK: [f64; 6] = [1000.0, 1800.0, 3200.0, 5000.0, 7000.0, 10000.0];
    let row = HEIGHTS.iter().take_while(|&&top| h >= top).count();
    if high_risk {
        HIGH_RISK[row]
    } else {
        ROUTES[row]
    }
}

type KeyError = (String, String);

fn bad<T>(key: &str, message: String) -> Result<T, KeyError> {
    Err((key.to_string(), message))
}

/// An emergency area resolved: its grids (as entries, or a route's centre line as points)
/// and its requirements.
#[derive(Debug, Clone)]
pub struct EmergencyPlan {
    /// The entry.
    pub entry: EmergencyEntry,
    /// The outline drawn on the plans (a route's band, an area's outline).
    pub outline: Vec<[f64; 2]>,
    /// Each part's grid entry.
    pub grids: Vec<(AreaPart, GridEntry)>,
    /// A route's centre-line points in plan (its grid is built from them).
    pub centre_line: Vec<[f64; 2]>,
    /// What it must meet.
    pub requirements: Vec<Requirement>,
}

fn need(part: AreaPart, quantity: Quantity, required: f64, why: &'static str) -> Requirement {
    Requirement {
        part,
        quantity,
        required,
        derived: Some(why),
    }
}

impl EmergencyEntry {
    fn grid(&self, part: AreaPart, outline: Vec<[f64; 2]>, spacing: Spacing) -> GridEntry {
        GridEntry {
            name: format!("{}{}", self.name, part.suffix()),
            corner: None,
            size: None,
            outline: Some(outline),
            exclude: None,
            height: self.height,
            spacing,
            border: 0.0,
            kind: GridKind::Horizontal,
            normal: None,
        }
    }

    fn spacing_or(&self, default: Spacing) -> Result<Spacing, KeyError> {
        match self.spacing {
            Some(s) if !(s.is_finite() && s > 0.0) => {
                bad("spacing", format!("{s}: give metres > 0"))
            }
            Some(s) => Ok(Spacing::Metres(s)),
            None => Ok(default),
        }
    }

    /// The area resolved. Errors name the key (relative to this entry) and what is wrong.
    pub fn resolve(&self) -> Result<EmergencyPlan, KeyError> {
        if self.name.trim().is_empty() {
            return bad("name", "give the area a name".into());
        }
        if !self.height.is_finite() {
            return bad("height", format!("{} is not a height", self.height));
        }
        let used = [
            ("line", self.line.is_some(), EmergencyKind::Route),
            ("width", self.width.is_some(), EmergencyKind::Route),
            ("em", self.em.is_some(), EmergencyKind::HighRisk),
            ("position", self.position.is_some(), EmergencyKind::Point),
            ("normal", self.normal.is_some(), EmergencyKind::Point),
        ];
        if let Some((key, _, _)) = used
            .iter()
            .find(|(_, given, kind)| *given && *kind != self.kind)
        {
            return bad(
                key,
                format!("not a key of a {:?} area", self.kind).to_lowercase(),
            );
        }
        match self.kind {
            EmergencyKind::Route => self.route(),
            EmergencyKind::OpenArea | EmergencyKind::HighRisk => self.area(),
            EmergencyKind::Point => self.point(),
        }
    }

    fn route(&self) -> Result<EmergencyPlan, KeyError> {
        let line = match &self.line {
            Some(l) if l.len() >= 2 && l.iter().flatten().all(|v| v.is_finite()) => l.clone(),
            _ => {
                return bad(
                    "line",
                    "give the route's centre line: at least two finite [x, y] points".into(),
                )
            }
        };
        let width = match self.width {
            Some(w) if w.is_finite() && w > 0.0 && w <= MAX_ROUTE_WIDTH => w,
            Some(w) => return bad("width", format!("{w}: a route is more than 0 and at most 2 m wide (EN 1838: wider routes are several 2 m strips, or an open area)")),
            None => return bad("width", "give the route's width, metres".into()),
        };
        let length: f64 = line
            .windows(2)
            .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
            .sum();
        if line.windows(2).any(|s| s[0] == s[1]) || length.is_nan() || length <= 0.0 {
            return bad("line", "the centre line repeats a point".into());
        }
        let spacing = match self.spacing_or(Spacing::Metres(ROUTE_SPACING))? {
            Spacing::Metres(s) => s,
            Spacing::Rule(_) => ROUTE_SPACING,
        };
        let n = ((length / spacing).round() as usize).max(1);
        if n > super::grid::MAX_POINTS {
            return bad(
                "spacing",
                format!(
                    "{n} points along the route; at most {}",
                    super::grid::MAX_POINTS
                ),
            );
        }
        let centre_line = (0..n)
            .map(|k| point_along(&line, (k as f64 + 0.5) * length / n as f64))
            .collect();
        let band = band_outline(&line, width / 4.0);
        let outline = band_outline(&line, width / 2.0);
        Ok(EmergencyPlan {
            entry: self.clone(),
            outline,
            grids: vec![(AreaPart::CentralBand, self.grid(AreaPart::CentralBand, band, Spacing::Metres(spacing)))],
            centre_line,
            requirements: vec![
                need(AreaPart::CentreLine, Quantity::Emin, 1.0, "EN 1838: escape route, at least 1 lx on the centre line"),
                need(AreaPart::CentreLine, Quantity::MaxToMin, 40.0, "EN 1838: escape route, Emax/Emin at most 40 along the centre line"),
                need(AreaPart::CentralBand, Quantity::Emin, 0.5, "EN 1838: escape route, at least 0.5 lx over the central band of half its width"),
            ],
        })
    }

    fn area(&self) -> Result<EmergencyPlan, KeyError> {
        let shape = GridEntry {
            corner: self.corner,
            size: self.size,
            outline: self.outline.clone(),
            border: if self.kind == EmergencyKind::OpenArea {
                OPEN_AREA_BORDER
            } else {
                0.0
            },
            ..self.grid(
                AreaPart::Task,
                Vec::new(),
                self.spacing_or(Spacing::default())?,
            )
        };
        let outline = shape.plan_outline()?;
        let requirements = if self.kind == EmergencyKind::OpenArea {
            vec![
                need(
                    AreaPart::Task,
                    Quantity::Emin,
                    0.5,
                    "EN 1838: open (anti-panic) area, at least 0.5 lx less a 0.5 m border",
                ),
                need(
                    AreaPart::Task,
                    Quantity::MaxToMin,
                    40.0,
                    "EN 1838: open (anti-panic) area, Emax/Emin at most 40",
                ),
            ]
        } else {
            let em =
                match self.em {
                    Some(e) if e.is_finite() && e > 0.0 => e,
                    _ => return bad(
                        "em",
                        "give the task's required maintained illuminance under normal lighting, lx"
                            .into(),
                    ),
                };
            vec![
                need(AreaPart::Task, Quantity::Emin, (0.1 * em).max(15.0), "EN 1838: high-risk task area, at least 10 % of the task's maintained illuminance and 15 lx"),
                need(AreaPart::Task, Quantity::G2, 0.1, "EN 1838: high-risk task area, Emin/Emax at least 0.1"),
            ]
        };
        Ok(EmergencyPlan {
            entry: self.clone(),
            outline,
            grids: vec![(AreaPart::Task, shape)],
            centre_line: Vec::new(),
            requirements,
        })
    }

    fn point(&self) -> Result<EmergencyPlan, KeyError> {
        let Some(p) = self.position.filter(|p| p.iter().all(|v| v.is_finite())) else {
            return bad("position", "give the equipment's position [x, y, z]".into());
        };
        let f = match self
            .normal
            .map(|n| crate::geometry::unit(glam::DVec3::from_array(n)))
        {
            Some(Some(f)) if f.z.abs() <= 1e-9 => f,
            _ => {
                return bad(
                    "normal",
                    "give the way the equipment faces, horizontal [x, y, 0]".into(),
                )
            }
        };
        // One point: a 0.2 m square on the equipment's front centred on it.
        let along = glam::DVec3::Z.cross(f);
        let half = 0.1;
        let grid = GridEntry {
            corner: Some([p[0] - half * along.x, p[1] - half * along.y]),
            size: Some([2.0 * half, 2.0 * half]),
            outline: None,
            height: p[2] - half,
            kind: GridKind::Vertical,
            normal: Some([f.x, f.y, 0.0]),
            ..self.grid(AreaPart::Task, Vec::new(), Spacing::Metres(2.0 * half))
        };
        Ok(EmergencyPlan {
            entry: self.clone(),
            outline: Vec::new(),
            grids: vec![(AreaPart::Task, grid)],
            centre_line: Vec::new(),
            requirements: vec![need(
                AreaPart::Task,
                Quantity::Emin,
                5.0,
                "EN 1838: safety equipment, at least 5 lx vertical",
            )],
        })
    }
}

impl super::Scene {
    /// The scene in emergency mode (EN 1838): only the luminaires with an emergency
    /// output, each at it (numbered L1, L2, … among themselves); the `[[emergency]]`
    /// areas as its grids and areas, and each emergency luminaire's glare limit as an
    /// area named after it; no `[[grid]]`, `[[area]]` or observer (their requirements
    /// are for the normal lighting); direct light only; no daylight (EN 1838 is judged
    /// without it: the mains fail at night too).
    pub fn in_emergency(&self) -> Result<super::Scene, super::SceneError> {
        use super::area::{Area, AreaEntry, AreaKind, Standard};
        let err = |key: &str, msg: &str| super::SceneError::new(&self.path, key, msg);
        if self.emergency.is_empty() {
            return Err(err("emergency", "no [[emergency]] area to judge: add an escape route, open area, high-risk task area or safety point"));
        }
        let mut scene = self.clone();
        scene.luminaires = self
            .luminaires
            .iter()
            .filter_map(|l| {
                l.emergency_multiplier().map(|m| {
                    let mut l = l.clone();
                    l.multiplier = m;
                    l
                })
            })
            .collect();
        if scene.luminaires.is_empty() {
            return Err(err("luminaire", "no luminaire has an emergency output: give emergency_flux_lm or ballast_lumen_factor to the emergency luminaires"));
        }
        scene.grids.clear();
        scene.areas.clear();
        scene.observers.clear();
        scene.calc.indirect = None;
        scene.daylight = None;
        let named = |name: &str, kind| AreaEntry {
            name: name.to_string(),
            kind,
            ..Default::default()
        };
        for plan in &self.emergency {
            let mut grids = Vec::new();
            if !plan.centre_line.is_empty() {
                grids.push((AreaPart::CentreLine, scene.grids.len()));
                scene.grids.push(plan.centre_line_grid());
            }
            for (part, entry) in &plan.grids {
                let g = entry.resolve().map_err(|(key, msg)| {
                    err(&format!("emergency ({}).{key}", entry.name), &msg)
                })?;
                grids.push((*part, scene.grids.len()));
                scene.grids.push(g);
            }
            scene.areas.push(Area {
                entry: named(&plan.entry.name, AreaKind::Area),
                standard: Standard::En1838,
                outline: plan.outline.clone(),
                grids,
                requirements: plan.requirements.clone(),
            });
        }
        let high_risk = self
            .emergency
            .iter()
            .all(|e| e.entry.kind == EmergencyKind::HighRisk);
        let why = if high_risk {
            "EN 1838: disability glare, the highest intensity 60–90° from the downward vertical for the mounting height (high-risk task areas)"
        } else {
            "EN 1838: disability glare, the highest intensity 60–90° from the downward vertical for the mounting height (escape routes and open areas)"
        };
        let heights: Vec<f64> = scene.luminaires.iter().map(|l| l.position.z).collect();
        for (k, h) in heights.into_iter().enumerate() {
            let limit = glare_limit_cd(h, high_risk);
            scene.areas.push(Area {
                entry: named(&format!("L{}", k + 1), AreaKind::Area),
                standard: Standard::En1838,
                outline: Vec::new(),
                grids: Vec::new(),
                requirements: vec![need(
                    AreaPart::Luminaire(k),
                    Quantity::GlareIntensity,
                    limit,
                    why,
                )],
            });
        }
        Ok(scene)
    }
}

impl EmergencyPlan {
    /// A route's centre line as a grid: its points at the route's height.
    fn centre_line_grid(&self) -> super::grid::CalcGrid {
        let e = &self.entry;
        let length: f64 = self
            .centre_line
            .windows(2)
            .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
            .sum::<f64>()
            / (self.centre_line.len() - 1).max(1) as f64;
        let step = if self.centre_line.len() > 1 {
            length
        } else {
            e.spacing.unwrap_or(ROUTE_SPACING)
        };
        super::grid::CalcGrid {
            entry: GridEntry {
                spacing: Spacing::Metres(step),
                ..e.grid(
                    AreaPart::CentreLine,
                    self.outline.clone(),
                    Spacing::Metres(step),
                )
            },
            points: self
                .centre_line
                .iter()
                .map(|p| glam::DVec3::new(p[0], p[1], e.height))
                .collect(),
            spacing: [step, step],
            facing: None,
        }
    }
}

/// The point `distance` metres along the polyline `line`.
fn point_along(line: &[[f64; 2]], mut distance: f64) -> [f64; 2] {
    for s in line.windows(2) {
        let len = (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]);
        if distance <= len {
            let t = distance / len;
            return [
                s[0][0] + t * (s[1][0] - s[0][0]),
                s[0][1] + t * (s[1][1] - s[0][1]),
            ];
        }
        distance -= len;
    }
    line[line.len() - 1]
}

/// The band `half` metres either side of the polyline `line` as a polygon (joints
/// mitred).
fn band_outline(line: &[[f64; 2]], half: f64) -> Vec<[f64; 2]> {
    let n = line.len();
    let normal = |k: usize| {
        let (a, b) = (line[k], line[k + 1]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        [-dy / len, dx / len]
    };
    let offset = |k: usize, side: f64| {
        // At a joint, the mitre: the mean of the two sides' normals, lengthened.
        let m = match k {
            0 => normal(0),
            k if k == n - 1 => normal(n - 2),
            k => {
                let (a, b) = (normal(k - 1), normal(k));
                let m = [a[0] + b[0], a[1] + b[1]];
                let dot = (m[0] * a[0] + m[1] * a[1]).max(1e-6);
                [m[0] / dot, m[1] / dot]
            }
        };
        [
            line[k][0] + side * half * m[0],
            line[k][1] + side * half * m[1],
        ]
    };
    let left = (0..n).map(|k| offset(k, 1.0));
    let right: Vec<[f64; 2]> = (0..n).rev().map(|k| offset(k, -1.0)).collect();
    let mut out: Vec<[f64; 2]> = left.chain(right).collect();
    if polygon::signed_area2(&out) < 0.0 {
        out.reverse();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glare_limits_follow_the_table() {
        for (h, route, high) in [
            (2.0, 500.0, 1000.0),
            (2.5, 900.0, 1800.0),
            (3.2, 1600.0, 3200.0),
            (3.9, 2500.0, 5000.0),
            (4.2, 3500.0, 7000.0),
            (6.0, 5000.0, 10000.0),
        ] {
            assert_eq!(glare_limit_cd(h, false), route, "{h} m");
            assert_eq!(glare_limit_cd(h, true), high, "{h} m");
        }
    }

    #[test]
    fn a_route_has_its_centre_line_and_central_band() {
        let e: EmergencyEntry = toml::from_str(
            "name = \"c\"\nkind = \"route\"\nline = [[0, 1], [10, 1], [10, 5]]\nwidth = 2.0\n",
        )
        .unwrap();
        let plan = e.resolve().unwrap();
        // 14 m at 0.2 m: 70 points at the middles of equal pieces, on the line.
        assert_eq!(plan.centre_line.len(), 70);
        assert_eq!(plan.centre_line[0], [0.1, 1.0]);
        assert!(plan
            .centre_line
            .iter()
            .all(|p| p[1] == 1.0 || (p[0] - 10.0).abs() < 1e-12));
        // The band: half the width, 0.5 m either side, round the corner (mitred: square).
        let band = plan.grids[0].1.resolve().unwrap();
        assert!(band.points.iter().all(|p| {
            let (x, y) = (p.x, p.y);
            // Along the first leg, the square corner, along the second.
            (x <= 10.5 && (y - 1.0).abs() <= 0.5) || (y >= 0.5 && (x - 10.0).abs() <= 0.5)
        }));
        assert!(band.points.iter().any(|p| p.y > 4.0) && band.points.iter().any(|p| p.x < 1.0));
        let wide: EmergencyEntry =
            toml::from_str("name = \"w\"\nkind = \"route\"\nline = [[0, 0], [5, 0]]\nwidth = 3\n")
                .unwrap();
        assert_eq!(wide.resolve().unwrap_err().0, "width");
    }

    #[test]
    fn a_point_is_one_point_on_the_equipments_front() {
        let e: EmergencyEntry = toml::from_str(
            "name = \"x\"\nkind = \"point\"\nposition = [5.0, 0.05, 1.2]\nnormal = [0.0, 1.0, 0.0]\n",
        )
        .unwrap();
        let g = e.resolve().unwrap().grids[0].1.resolve().unwrap();
        assert_eq!(g.points.len(), 1);
        assert!((g.points[0] - glam::DVec3::new(5.0, 0.05, 1.2)).length() < 1e-12);
        assert_eq!(g.facing, Some(glam::DVec3::Y));
    }
}
