//! EN 12464-1 areas (`[[area]]` in the scene file): a task area with the requirements of
//! its activity, and the calculation grids the standard judges it on. A task area's
//! immediate surrounding (a band of at least 0.5 m around it) and background (a band of
//! at least 3 m around that, within the room) are generated; their requirements follow
//! from the task's by the standard's relations unless given.
//!
//! ```toml
//! [[area]]
//! name = "desk"
//! kind = "task"               # or "area": its own grid only, nothing generated
//! corner = [1.0, 1.0]         # or outline = [[x, y], …] (a task area: convex)
//! size = [1.6, 0.8]
//! height = 0.75               # metres above z = 0
//! room = [[0, 0], [6, 0], …]  # the room's outline (default: the models' extent in plan)
//! em = 500                    # required maintained Em, lx
//! u0 = 0.6                    # required Emin/Em
//! ez = 150                    # required cylindrical Em at ez_height (1.2 m), lx
//! ugr_l = 19                  # the highest UGR allowed at the [[observer]]s
//! ra = 80                     # the lowest colour rendering index allowed
//! surrounding_width = 0.5     # at least 0.5 m
//! background_width = 3.0      # at least 3 m
//! # surrounding_em, surrounding_u0, background_em, background_u0: the standard's
//! # relations when not given
//! ```
//!
//! The grids are named after the area: `desk` (the task), `desk surrounding`,
//! `desk background` and, with `ez`, `desk Ez`; their points follow the grid spacing
//! rule of EN 12464-1 over each one's extent.

use serde::{Deserialize, Serialize};

use super::grid::{GridEntry, GridKind, Spacing};
pub use super::requirement::{AreaPart, Quantity, Requirement, Standard};
use crate::geometry::polygon::{self, Polygon};

/// What an area is.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum AreaKind {
    /// A task area: its immediate surrounding and background are generated and judged.
    #[default]
    Task,
    /// An area judged on its own (an activity area, a circulation zone).
    Area,
    /// A room: its outline is the room's; judged are its activity area (less a border
    /// along the walls), each wall and the ceiling.
    Room,
}

/// `[[area]]` as written in the scene file.
#[derive(Debug, Clone, Default, Deserialize, Serialize, PartialEq, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AreaEntry {
    /// The area's name (and its grids' names).
    pub name: String,
    /// Task area (default) or an area on its own.
    #[serde(default)]
    pub kind: AreaKind,
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
    /// A polygon outline in plan instead of a rectangle (convex for a task area), metres.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub outline: Option<Vec<[f64; 2]>>,
    /// Height of the task plane above z = 0, metres.
    #[serde(default = "default_height")]
    pub height: f64,
    /// Metres between points, or `"en12464"` (the default, over each grid's extent).
    #[serde(default)]
    pub spacing: Spacing,
    /// The room's outline in plan: the surrounding and background stay inside it
    /// (default: the models' extent in plan).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::io::exact::option_vec"
    )]
    pub room: Option<Vec<[f64; 2]>>,
    /// Required maintained illuminance Em, lx.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub em: Option<f64>,
    /// Required uniformity U0 = Emin/Em.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub u0: Option<f64>,
    /// Required maintained cylindrical illuminance Ez at `ez_height`, lx.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ez: Option<f64>,
    /// Height of the cylindrical illuminance, metres (default 1.2, seated).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ez_height: Option<f64>,
    /// The highest unified glare rating allowed at the observers (UGR_L).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ugr_l: Option<f64>,
    /// The observers `ugr_l` is checked at, by name (default: every observer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observers: Option<Vec<String>>,
    /// The lowest colour rendering index Ra allowed (of every luminaire's file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ra: Option<f64>,
    /// Width of the immediate surrounding, metres (at least 0.5, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surrounding_width: Option<f64>,
    /// Width of the background, metres (at least 3, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background_width: Option<f64>,
    /// A room: the band along its walls left out of the activity area, metres (default
    /// 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub border: Option<f64>,
    /// A room: the ceiling's height above z = 0, metres (default: the models' top).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ceiling_height: Option<f64>,
    /// A room: required Em on each wall, lx (default 50).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_em: Option<f64>,
    /// A room: required U0 on each wall (default 0.10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_u0: Option<f64>,
    /// A room: required Em on the ceiling, lx (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ceiling_em: Option<f64>,
    /// A room: required U0 on the ceiling (default 0.10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ceiling_u0: Option<f64>,
    /// Required Em of the immediate surrounding, lx (default from the task's Em).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surrounding_em: Option<f64>,
    /// Required U0 of the immediate surrounding (default 0.40).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surrounding_u0: Option<f64>,
    /// Required Em of the background, lx (default a third of the surrounding's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background_em: Option<f64>,
    /// Required U0 of the background (default 0.10).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub background_u0: Option<f64>,
}

fn default_height() -> f64 {
    0.8
}

/// The narrowest immediate surrounding EN 12464-1 allows, metres.
pub const MIN_SURROUNDING_WIDTH: f64 = 0.5;
/// The narrowest background EN 12464-1 allows, metres.
pub const MIN_BACKGROUND_WIDTH: f64 = 3.0;
/// Default height of the cylindrical illuminance (seated), metres.
pub const EZ_HEIGHT: f64 = 1.2;
/// Required U0 of the immediate surrounding unless given.
pub const SURROUNDING_U0: f64 = 0.40;
/// Required U0 of the background unless given.
pub const BACKGROUND_U0: f64 = 0.10;
/// Required Em on a room's walls unless given, lx.
pub const WALL_EM: f64 = 50.0;
/// Required Em on a room's ceiling unless given, lx.
pub const CEILING_EM: f64 = 30.0;
/// Required U0 on a room's walls and ceiling unless given.
pub const WALL_CEILING_U0: f64 = 0.10;
/// The band along a room's walls left out of its activity area unless given, metres.
pub const ROOM_BORDER: f64 = 0.5;

/// EN 12464-1's required Em of the immediate surrounding for a task area's `task_em`:
/// 500 lx from 750 up, 300 from 500, 200 from 300, 150 from 200, below that the task's.
pub fn surrounding_em(task_em: f64) -> f64 {
    [
        (750.0, 500.0),
        (500.0, 300.0),
        (300.0, 200.0),
        (200.0, 150.0),
    ]
    .iter()
    .find(|(from, _)| task_em >= *from)
    .map_or(task_em, |(_, e)| *e)
}

/// An area ready to compute: its grids (indices into the scene's grids) and its
/// requirements.
#[derive(Debug, Clone)]
pub struct Area {
    /// The entry it came from (an emergency area's: its name, kind `area`).
    pub entry: AreaEntry,
    /// The standard it is judged by.
    pub standard: Standard,
    /// The task area's outline in plan.
    pub outline: Vec<[f64; 2]>,
    /// Each part's grid, as an index into [`super::Scene::grids`].
    pub grids: Vec<(AreaPart, usize)>,
    /// What the area must meet.
    pub requirements: Vec<Requirement>,
}

impl Area {
    /// The index of `part`'s grid.
    pub fn grid_of(&self, part: AreaPart) -> Option<usize> {
        self.grids.iter().find(|(p, _)| *p == part).map(|g| g.1)
    }
}

/// What the models say of the room where an area does not: its outline in plan and its
/// ceiling's height.
#[derive(Debug, Clone, Default)]
pub struct ModelExtent {
    /// The models' extent in plan (a rectangle), if there are models.
    pub outline: Option<Vec<[f64; 2]>>,
    /// The models' top, metres above z = 0.
    pub top: Option<f64>,
}

/// An area resolved before its grids are: what [`AreaEntry::resolve`] gives.
#[derive(Debug, Clone)]
pub struct AreaPlan {
    /// The task area's outline in plan.
    pub outline: Vec<[f64; 2]>,
    /// Each part's grid entry.
    pub grids: Vec<(AreaPart, GridEntry)>,
    /// What the area must meet.
    pub requirements: Vec<Requirement>,
}

type KeyError = (String, String);

fn bad<T>(key: &str, message: String) -> Result<T, KeyError> {
    Err((key.to_string(), message))
}

/// `value` if it is finite and above `min`.
fn check_limit(key: &str, value: Option<f64>, min: f64, unit: &str) -> Result<(), KeyError> {
    match value {
        Some(v) if !(v.is_finite() && v >= min) => {
            bad(key, format!("{v}: give {unit} (at least {min})"))
        }
        _ => Ok(()),
    }
}

impl AreaEntry {
    fn check_requirements(&self) -> Result<(), KeyError> {
        for (key, v) in [
            ("em", self.em),
            ("ez", self.ez),
            ("surrounding_em", self.surrounding_em),
            ("background_em", self.background_em),
            ("wall_em", self.wall_em),
            ("ceiling_em", self.ceiling_em),
        ] {
            check_limit(key, v, 0.0, "an illuminance in lux")?;
        }
        for (key, v) in [
            ("u0", self.u0),
            ("surrounding_u0", self.surrounding_u0),
            ("background_u0", self.background_u0),
            ("wall_u0", self.wall_u0),
            ("ceiling_u0", self.ceiling_u0),
        ] {
            if let Some(u) = v {
                if !(u.is_finite() && (0.0..=1.0).contains(&u)) {
                    return bad(key, format!("{u}: a uniformity Emin/Em is between 0 and 1"));
                }
            }
        }
        if let Some(u) = self.ugr_l {
            if !(u.is_finite() && (5.0..=40.0).contains(&u)) {
                return bad("ugr_l", format!("{u}: a UGR limit is between 5 and 40"));
            }
        }
        if let Some(r) = self.ra {
            if !(r.is_finite() && (0.0..=100.0).contains(&r)) {
                return bad("ra", format!("{r}: a colour rendering index is 0 to 100"));
            }
        }
        check_limit(
            "surrounding_width",
            self.surrounding_width,
            MIN_SURROUNDING_WIDTH,
            "metres (EN 12464-1)",
        )?;
        check_limit(
            "background_width",
            self.background_width,
            MIN_BACKGROUND_WIDTH,
            "metres (EN 12464-1)",
        )?;
        check_limit("border", self.border, 0.0, "metres")?;
        for (key, h) in [
            ("ez_height", self.ez_height),
            ("ceiling_height", self.ceiling_height),
        ] {
            if h.is_some_and(|h| !h.is_finite()) {
                return bad(key, format!("{h:?} is not a height"));
            }
        }
        self.check_keys_of_kind()?;
        if self.kind == AreaKind::Task && self.em.is_none() {
            return bad("em", "a task area needs its required maintained illuminance (EN 12464-1's tables of activities)".into());
        }
        if self.kind == AreaKind::Area
            && [self.em, self.u0, self.ez, self.ugr_l, self.ra]
                .iter()
                .all(Option::is_none)
        {
            return bad(
                "em",
                "give what the area must meet: em, u0, ez, ugr_l or ra".into(),
            );
        }
        Ok(())
    }

    /// Keys of one kind refused on another.
    fn check_keys_of_kind(&self) -> Result<(), KeyError> {
        let task_only = [
            ("surrounding_width", self.surrounding_width.is_some()),
            ("background_width", self.background_width.is_some()),
            ("surrounding_em", self.surrounding_em.is_some()),
            ("surrounding_u0", self.surrounding_u0.is_some()),
            ("background_em", self.background_em.is_some()),
            ("background_u0", self.background_u0.is_some()),
        ];
        let room_only = [
            ("border", self.border.is_some()),
            ("ceiling_height", self.ceiling_height.is_some()),
            ("wall_em", self.wall_em.is_some()),
            ("wall_u0", self.wall_u0.is_some()),
            ("ceiling_em", self.ceiling_em.is_some()),
            ("ceiling_u0", self.ceiling_u0.is_some()),
        ];
        if self.kind != AreaKind::Task {
            if let Some((key, _)) = task_only.iter().find(|(_, given)| *given) {
                return bad(
                    key,
                    "only a task area (kind = \"task\") has a surrounding and background".into(),
                );
            }
        }
        if self.kind != AreaKind::Room {
            if let Some((key, _)) = room_only.iter().find(|(_, given)| *given) {
                return bad(
                    key,
                    "only a room (kind = \"room\") has walls, a ceiling and a border".into(),
                );
            }
        } else if self.room.is_some() {
            return bad(
                "room",
                "a room's outline is its own (corner and size, or outline)".into(),
            );
        }
        Ok(())
    }

    /// The requirements, the standard's relations filling what is not given; `walls`:
    /// a room's number of walls.
    fn requirements(&self, walls: usize) -> Vec<Requirement> {
        use AreaPart::*;
        use Quantity::*;
        let given = |part, quantity, v: Option<f64>| {
            v.map(|required| Requirement {
                part,
                quantity,
                required,
                derived: None,
            })
        };
        let or_rule = |part, quantity, v: Option<f64>, rule: f64, why| Requirement {
            part,
            quantity,
            required: v.unwrap_or(rule),
            derived: v.is_none().then_some(why),
        };
        let mut out: Vec<Requirement> = [
            given(Task, Em, self.em),
            given(Task, U0, self.u0),
            given(Cylindrical, Ez, self.ez),
            given(Task, Ugr, self.ugr_l),
            given(Task, Ra, self.ra),
        ]
        .into_iter()
        .flatten()
        .collect();
        if let (AreaKind::Task, Some(task_em)) = (self.kind, self.em) {
            let surrounding = or_rule(
                Surrounding,
                Em,
                self.surrounding_em,
                surrounding_em(task_em),
                "EN 12464-1: the immediate surrounding's Em from the task area's (750 → 500, 500 → 300, 300 → 200, 200 → 150 lx, else the task's)",
            );
            let background_em = or_rule(
                Background,
                Em,
                self.background_em,
                surrounding.required / 3.0,
                "EN 12464-1: the background's Em at least a third of the immediate surrounding's",
            );
            out.extend([
                surrounding,
                or_rule(
                    Surrounding,
                    U0,
                    self.surrounding_u0,
                    SURROUNDING_U0,
                    "EN 12464-1: U0 of the immediate surrounding at least 0.40",
                ),
                background_em,
                or_rule(
                    Background,
                    U0,
                    self.background_u0,
                    BACKGROUND_U0,
                    "EN 12464-1: U0 of the background at least 0.10",
                ),
            ]);
        }
        if self.kind == AreaKind::Room {
            for k in 0..walls {
                out.push(or_rule(
                    Wall(k),
                    Em,
                    self.wall_em,
                    WALL_EM,
                    "EN 12464-1: walls at least 50 lx (the activity's table may ask more)",
                ));
                out.push(or_rule(
                    Wall(k),
                    U0,
                    self.wall_u0,
                    WALL_CEILING_U0,
                    "EN 12464-1: U0 on walls at least 0.10",
                ));
            }
            out.push(or_rule(
                Ceiling,
                Em,
                self.ceiling_em,
                CEILING_EM,
                "EN 12464-1: ceiling at least 30 lx (the activity's table may ask more)",
            ));
            out.push(or_rule(
                Ceiling,
                U0,
                self.ceiling_u0,
                WALL_CEILING_U0,
                "EN 12464-1: U0 on the ceiling at least 0.10",
            ));
        }
        out
    }

    /// A grid of this area named with `part`'s suffix, over `outline` less `exclude`.
    fn grid(
        &self,
        part: AreaPart,
        outline: Vec<[f64; 2]>,
        exclude: Option<Vec<[f64; 2]>>,
    ) -> GridEntry {
        let cylindrical = part == AreaPart::Cylindrical;
        GridEntry {
            name: format!("{}{}", self.name, part.suffix()),
            corner: None,
            size: None,
            outline: Some(outline),
            exclude,
            height: if cylindrical {
                self.ez_height.unwrap_or(EZ_HEIGHT)
            } else {
                self.height
            },
            spacing: self.spacing.clone(),
            border: 0.0,
            kind: if cylindrical {
                GridKind::Cylindrical
            } else {
                GridKind::Horizontal
            },
            normal: None,
        }
    }

    /// The area's outline, its grids (as grid entries, with their parts) and its
    /// requirements; `models` gives the room's outline and ceiling where the entry gives
    /// none. Errors name the key (relative to this area) and what is wrong.
    pub fn resolve(&self, models: &ModelExtent) -> Result<AreaPlan, KeyError> {
        if self.name.trim().is_empty() {
            return bad("name", "give the area a name".into());
        }
        if !self.height.is_finite() {
            return bad("height", format!("{} is not a height", self.height));
        }
        self.check_requirements()?;
        let shape = GridEntry {
            corner: self.corner,
            size: self.size,
            outline: self.outline.clone(),
            border: match self.kind {
                AreaKind::Room => self.border.unwrap_or(ROOM_BORDER),
                _ => 0.0,
            },
            ..self.grid(AreaPart::Task, Vec::new(), None)
        };
        let outline = shape.plan_outline()?;
        let mut grids = vec![(AreaPart::Task, shape)];
        if self.ez.is_some() {
            grids.push((
                AreaPart::Cylindrical,
                self.grid(AreaPart::Cylindrical, outline.clone(), None),
            ));
        }
        let mut walls = 0;
        match self.kind {
            AreaKind::Task => grids.extend(self.bands(&outline, models.outline.as_deref())?),
            AreaKind::Room => {
                let surfaces = self.walls_and_ceiling(&outline, models.top)?;
                walls = surfaces.len() - 1;
                grids.extend(surfaces);
            }
            AreaKind::Area => {}
        }
        Ok(AreaPlan {
            outline,
            grids,
            requirements: self.requirements(walls),
        })
    }

    /// A room's walls (one vertical grid per side of its outline, from the floor at
    /// z = 0 to the ceiling, facing in) and its ceiling (facing down).
    fn walls_and_ceiling(
        &self,
        outline: &Polygon,
        top: Option<f64>,
    ) -> Result<Vec<(AreaPart, GridEntry)>, KeyError> {
        let ceiling = match self.ceiling_height.or(top) {
            Some(h) if h > 0.0 && h > self.height => h,
            Some(h) => {
                return bad(
                    "ceiling_height",
                    format!("{h}: the ceiling is above the floor (z = 0) and the work plane"),
                )
            }
            None => {
                return bad(
                    "ceiling_height",
                    "no model gives the room's height: give ceiling_height".into(),
                )
            }
        };
        let p = polygon::counter_clockwise(outline);
        let n = p.len();
        let mut out: Vec<(AreaPart, GridEntry)> = (0..n)
            .map(|k| {
                let (a, b) = (p[k], p[(k + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let len = dx.hypot(dy);
                // Facing into the room (the left of a counter-clockwise side); seen from
                // the front, the wall runs from b to a.
                let part = AreaPart::Wall(k);
                let wall = GridEntry {
                    corner: Some(b),
                    size: Some([len, ceiling]),
                    outline: None,
                    height: 0.0,
                    kind: GridKind::Vertical,
                    normal: Some([-dy / len, dx / len, 0.0]),
                    ..self.grid(part, Vec::new(), None)
                };
                (part, wall)
            })
            .collect();
        let top = GridEntry {
            height: ceiling,
            kind: GridKind::Ceiling,
            ..self.grid(AreaPart::Ceiling, outline.to_vec(), None)
        };
        out.push((AreaPart::Ceiling, top));
        Ok(out)
    }

    /// A task area's immediate surrounding and background: bands around `task` clipped
    /// to the room.
    fn bands(
        &self,
        task: &Polygon,
        room: Option<&Polygon>,
    ) -> Result<Vec<(AreaPart, GridEntry)>, KeyError> {
        if !polygon::is_convex(task) {
            return bad(
                "outline",
                "a task area's outline is convex (split an L-shaped task area into two)".into(),
            );
        }
        let room: Vec<[f64; 2]> = match (&self.room, room) {
            (Some(r), _) => {
                if r.len() < 3 || r.iter().flatten().any(|v| !v.is_finite()) || polygon::signed_area2(r) == 0.0 {
                    return bad("room", "give the room's outline: at least three finite [x, y] points around an area".into());
                }
                r.clone()
            }
            (None, Some(r)) => r.to_vec(),
            (None, None) => {
                return bad("room", "no model gives the room's extent: give the room's outline in plan (room = [[x, y], …])".into())
            }
        };
        let centre = task
            .iter()
            .fold([0.0, 0.0], |c, p| [c[0] + p[0], c[1] + p[1]]);
        let n = task.len() as f64;
        if !polygon::inside(&room, centre[0] / n, centre[1] / n) {
            return bad(
                "corner",
                "the task area is outside the room's outline".into(),
            );
        }
        let ws = self.surrounding_width.unwrap_or(MIN_SURROUNDING_WIDTH);
        let wb = self.background_width.unwrap_or(MIN_BACKGROUND_WIDTH);
        let surrounding_edge = polygon::grow_convex(task, ws);
        let surrounding = polygon::clip_to_convex(&room, &surrounding_edge);
        let background = polygon::clip_to_convex(&room, &polygon::grow_convex(task, ws + wb));
        Ok(vec![
            (
                AreaPart::Surrounding,
                self.grid(AreaPart::Surrounding, surrounding, Some(task.to_vec())),
            ),
            (
                AreaPart::Background,
                self.grid(AreaPart::Background, background, Some(surrounding_edge)),
            ),
        ])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grids of a 1.1 m square task area near the inner corner of an L-shaped room
    /// (8 × 8 m less the 4 × 4 m notch at the top right).
    fn l_room_grids() -> Vec<(AreaPart, super::super::grid::CalcGrid)> {
        let entry: AreaEntry = toml::from_str(
            "name = \"bench\"\ncorner = [2.45, 2.45]\nsize = [1.1, 1.1]\nem = 500\nroom = [[0, 0], [8, 0], [8, 4], [4, 4], [4, 8], [0, 8]]\n",
        )
        .unwrap();
        let plan = entry.resolve(&ModelExtent::default()).unwrap();
        plan.grids
            .into_iter()
            .map(|(part, g)| (part, g.resolve().unwrap()))
            .collect()
    }

    #[test]
    fn surrounding_and_background_sit_where_the_standard_puts_them_in_an_l_shaped_room() {
        let in_room = |x: f64, y: f64| {
            (0.0..8.0).contains(&x) && (0.0..8.0).contains(&y) && (x < 4.0 || y < 4.0)
        };
        // How far outside the task square a point is, across its nearest side or corner
        // (the band of a rectangle is the rectangle grown on every side).
        let outside = |x: f64, y: f64| (2.45 - x).max(x - 3.55).max((2.45 - y).max(y - 3.55));
        let grids = l_room_grids();
        assert_eq!(
            grids.iter().map(|g| g.0).collect::<Vec<_>>(),
            [AreaPart::Task, AreaPart::Surrounding, AreaPart::Background]
        );
        // (part, band from, band to, the band's extent in the room).
        type Band = (usize, f64, f64, ([f64; 2], [f64; 2]));
        let bands: [Band; 2] = [
            (1, 0.0, 0.5, ([1.95, 1.95], [4.05, 4.05])),
            (2, 0.5, 3.5, ([0.0, 0.0], [7.05, 7.05])),
        ];
        for (k, from, to, extent) in bands {
            let g = &grids[k].1;
            let (lo, hi) = extent;
            let d = (hi[0] - lo[0]).max(hi[1] - lo[1]);
            let n = (d / super::super::grid::en12464_spacing(d)).round();
            let cell = d / n;
            assert!((g.spacing[0] - cell).abs() < 1e-12 && (g.spacing[1] - cell).abs() < 1e-12);
            // Every point in the band and the room; every cell centre in them is a point.
            let mut want = 0;
            for i in 0..n as usize {
                for j in 0..n as usize {
                    let (x, y) = (
                        lo[0] + (i as f64 + 0.5) * cell,
                        lo[1] + (j as f64 + 0.5) * cell,
                    );
                    let o = outside(x, y);
                    if in_room(x, y) && o > from && o <= to {
                        want += 1;
                        assert!(
                            g.points
                                .iter()
                                .any(|p| (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9),
                            "{x} {y}"
                        );
                    }
                }
            }
            assert_eq!(g.points.len(), want, "{}", g.entry.name);
            assert!(g.points.iter().all(|p| in_room(p.x, p.y) && p.z == 0.8));
        }
        // The background reaches round the corner of the L on both arms, not into the notch.
        let bg = &grids[2].1.points;
        assert!(bg.iter().any(|p| p.x > 4.0) && bg.iter().any(|p| p.y > 4.0));
        assert!(!bg.iter().any(|p| p.x > 4.0 && p.y > 4.0));
        assert_eq!(grids[0].1.points.len(), 25); // 1.1 m: p = 0.21 m, 5 × 5
    }

    #[test]
    fn a_rooms_walls_face_in_and_its_ceiling_down() {
        let entry: AreaEntry = toml::from_str(
            "name = \"lab\"\nkind = \"room\"\noutline = [[0, 8], [0, 0], [8, 0], [8, 4], [4, 4], [4, 8]]\nem = 300\n",
        )
        .unwrap();
        let models = ModelExtent {
            outline: None,
            top: Some(3.0),
        };
        let plan = entry.resolve(&models).unwrap();
        let in_room = |x: f64, y: f64| {
            (0.0..8.0).contains(&x) && (0.0..8.0).contains(&y) && (x < 4.0 || y < 4.0)
        };
        let mut walls = 0;
        for (part, g) in &plan.grids {
            let g = g.resolve().unwrap();
            match part {
                AreaPart::Wall(_) => {
                    walls += 1;
                    let f = g.facing.unwrap();
                    for p in &g.points {
                        assert!(p.z > 0.0 && p.z < 3.0);
                        // On the room's outline, and 1 cm in front of it inside the room.
                        assert!(polygon::distance_to_outline(&plan.outline, p.x, p.y) < 1e-9);
                        let q = *p + 0.01 * f;
                        assert!(in_room(q.x, q.y), "{} at {p}", g.entry.name);
                    }
                }
                AreaPart::Ceiling => {
                    assert_eq!(g.entry.kind, GridKind::Ceiling);
                    assert!(g.points.iter().all(|p| p.z == 3.0 && in_room(p.x, p.y)));
                }
                AreaPart::Task => {
                    // The activity area less 0.5 m along the walls.
                    assert!(g.points.iter().all(|p| {
                        polygon::distance_to_outline(&plan.outline, p.x, p.y) >= 0.5
                            && in_room(p.x, p.y)
                    }));
                }
                other => panic!("{other:?}"),
            }
        }
        assert_eq!(walls, 6);
        // Em and U0 on each wall and the ceiling at the standard's minimums, the activity's Em.
        let r = &plan.requirements;
        assert_eq!(r.len(), 1 + 2 * 7);
        assert!(r
            .iter()
            .filter(|x| matches!(x.part, AreaPart::Wall(_)) && x.quantity == Quantity::Em)
            .all(|x| x.required == 50.0));
        assert!(r.iter().any(|x| x.part == AreaPart::Ceiling
            && x.quantity == Quantity::Em
            && x.required == 30.0));
        // Without a ceiling height or a model's top, the room is refused by key.
        assert_eq!(
            entry.resolve(&ModelExtent::default()).unwrap_err().0,
            "ceiling_height"
        );
    }

    #[test]
    fn requirements_follow_the_standards_relations_unless_given() {
        let entry: AreaEntry = toml::from_str(
            "name = \"d\"\ncorner = [1, 1]\nsize = [1, 1]\nem = 750\nbackground_u0 = 0.2\n",
        )
        .unwrap();
        let r = entry.requirements(0);
        let find = |part, q| {
            r.iter()
                .find(|x| x.part == part && x.quantity == q)
                .unwrap()
        };
        assert_eq!(find(AreaPart::Surrounding, Quantity::Em).required, 500.0);
        assert!((find(AreaPart::Background, Quantity::Em).required - 500.0 / 3.0).abs() < 1e-12);
        assert_eq!(find(AreaPart::Background, Quantity::U0).required, 0.2);
        assert!(find(AreaPart::Background, Quantity::U0).derived.is_none());
        assert!(find(AreaPart::Surrounding, Quantity::U0).derived.is_some());
        assert_eq!(r.len(), 5);
    }

    #[test]
    fn the_surrounding_follows_the_standards_table() {
        for (task, surrounding) in [
            (1000.0, 500.0),
            (750.0, 500.0),
            (500.0, 300.0),
            (400.0, 200.0),
            (300.0, 200.0),
            (200.0, 150.0),
            (150.0, 150.0),
            (100.0, 100.0),
            (50.0, 50.0),
        ] {
            assert_eq!(surrounding_em(task), surrounding, "task {task} lx");
        }
    }
}
