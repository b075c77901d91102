//! The verification of a scene's EN 12464-1 areas (`[[area]]`): each requirement of
//! each area against what the calculation achieved on the area's grids, at its
//! observers and in its luminaires' files — pass, fail, or unknown where the input does
//! not state it (a luminaire file without a colour rendering index).

use serde::Serialize;

use super::glare::ObserverGlare;
use super::stats::GridStats;
use crate::scene::area::{Area, AreaPart, Quantity, Requirement};
use crate::scene::Scene;

/// One requirement of one area, judged.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// The area's name.
    pub area: String,
    /// The part of the area judged.
    pub part: AreaPart,
    /// The grid it was judged on (none for UGR and Ra).
    pub grid: Option<String>,
    /// The quantity.
    pub quantity: Quantity,
    /// Its unit (`lx`, or empty for a ratio or an index).
    pub unit: &'static str,
    /// The limit: at least this, or for UGR at most this.
    pub required: f64,
    /// The value reached (maintained); none where the input does not state it.
    pub achieved: Option<f64>,
    /// Met, not met, or unknown (none).
    pub pass: Option<bool>,
    /// Where the limit comes from: `"given"` (the scene file) or the standard's rule.
    pub basis: String,
    /// What the reader should know about the value (an unknown's reason).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl Verdict {
    /// The verdict in words: `pass`, `fail` or `unknown`.
    pub fn outcome(&self) -> &'static str {
        match self.pass {
            Some(true) => "pass",
            Some(false) => "fail",
            None => "unknown",
        }
    }

    /// The requirement as a reader writes it: `≥ 500 lx`, `≤ 19`.
    pub fn limit_text(&self) -> String {
        let sign = if self.quantity.is_upper_limit() {
            "≤"
        } else {
            "≥"
        };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        format!("{sign} {}{unit}", number(self.quantity, self.required))
    }

    /// The achieved value as a reader writes it (`—` where unknown).
    pub fn achieved_text(&self) -> String {
        self.achieved.map_or("—".into(), |v| {
            let unit = if self.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.unit)
            };
            format!("{}{unit}", number(self.quantity, v))
        })
    }
}

/// A value of `quantity` with the decimals a reader needs: U0 three, lux and UGR one,
/// Ra none.
fn number(quantity: Quantity, v: f64) -> String {
    match quantity {
        Quantity::U0 => format!("{v:.3}"),
        Quantity::Ra => format!("{v:.0}"),
        _ => format!("{v:.1}"),
    }
}

/// Every requirement of every area of `scene`, judged against the grids' results
/// (`grids`: their statistics, in the scene's order) and the observers' glare (`glare`);
/// `direct_only` when the values hold no interreflected light (walls and ceilings are
/// then noted: their light is mostly interreflected).
pub fn judge(
    scene: &Scene,
    grids: &[GridStats],
    glare: &[ObserverGlare],
    direct_only: bool,
) -> Vec<Verdict> {
    scene
        .areas
        .iter()
        .flat_map(|area| {
            area.requirements.iter().map(move |r| {
                let mut v = judge_one(scene, area, r, grids, glare);
                if direct_only && matches!(r.part, AreaPart::Wall(_) | AreaPart::Ceiling) {
                    v.note.get_or_insert_with(|| {
                        "direct light only: walls and ceilings are lit mostly by interreflected light (indirect radiosity)".into()
                    });
                }
                v
            })
        })
        .collect()
}

fn judge_one(
    scene: &Scene,
    area: &Area,
    r: &Requirement,
    grids: &[GridStats],
    glare: &[ObserverGlare],
) -> Verdict {
    let grid = match r.quantity {
        Quantity::Ugr | Quantity::Ra => None,
        _ => area.grid_of(r.part),
    };
    let (achieved, note) = match r.quantity {
        Quantity::Em | Quantity::Ez => (grid.map(|k| grids[k].em), None),
        Quantity::U0 => (grid.map(|k| grids[k].u0), None),
        Quantity::Ugr => highest_ugr(scene, area, glare),
        Quantity::Ra => lowest_ra(scene),
    };
    let pass = match (r.quantity, achieved) {
        (Quantity::Ugr, None) => Some(true),
        (_, None) => None,
        (q, Some(v)) if q.is_upper_limit() => Some(v <= r.required),
        (_, Some(v)) => Some(v >= r.required),
    };
    Verdict {
        area: area.entry.name.clone(),
        part: r.part,
        grid: grid.map(|k| scene.grids[k].entry.name.clone()),
        quantity: r.quantity,
        unit: match r.quantity {
            Quantity::Em | Quantity::Ez => "lx",
            _ => "",
        },
        required: r.required,
        achieved,
        pass,
        basis: r.derived.unwrap_or("given").to_string(),
        note,
    }
}

/// The highest UGR at the area's observers (all of the scene's unless it names some).
fn highest_ugr(
    scene: &Scene,
    area: &Area,
    glare: &[ObserverGlare],
) -> (Option<f64>, Option<String>) {
    let named = area.entry.observers.as_ref();
    let ugr = scene
        .observers
        .iter()
        .zip(glare)
        .filter(|(o, _)| named.is_none_or(|n| n.iter().any(|m| m.trim() == o.entry.name.trim())))
        .filter_map(|(_, g)| g.ugr)
        .fold(None, |hi: Option<f64>, u| Some(hi.map_or(u, |h| h.max(u))));
    let note = ugr
        .is_none()
        .then(|| "no luminaire in any observer's field of view".to_string());
    (ugr, note)
}

/// The lowest colour rendering index the luminaires' files state; unknown (with the
/// first luminaire that states none) where one does not.
fn lowest_ra(scene: &Scene) -> (Option<f64>, Option<String>) {
    let mut lowest = f64::INFINITY;
    for (i, l) in scene.luminaires.iter().enumerate() {
        match l.luminaire.data.colour_rendering_ra() {
            Some(ra) => lowest = lowest.min(ra),
            None => {
                let file = l
                    .file
                    .file_name()
                    .map_or(String::new(), |n| n.to_string_lossy().into_owned());
                return (
                    None,
                    Some(format!(
                        "L{} ({file}) states no colour rendering index",
                        i + 1
                    )),
                );
            }
        }
    }
    if lowest.is_finite() {
        (Some(lowest), None)
    } else {
        (None, Some("no luminaire".into()))
    }
}
