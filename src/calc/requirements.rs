//! The verification of a scene's EN 12464-1 areas (`[[area]]`): each requirement of
//! each area against what the calculation achieved on the area's grids, at its
//! observers and in its luminaires' files — pass, fail, or unknown where the input does
//! not state it (a luminaire file without a colour rendering index).

use serde::Serialize;

use super::glare::ObserverGlare;
use super::stats::GridStats;
use crate::photometry::Interp;
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
    /// The standard it is judged by.
    pub standard: &'static str,
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

/// A value of `quantity` with the decimals a reader needs: ratios three, lux, UGR and
/// Emax/Emin one (lux below 10 two), Ra and candela none.
fn number(quantity: Quantity, v: f64) -> String {
    match quantity {
        Quantity::U0 | Quantity::G2 => format!("{v:.3}"),
        Quantity::Ra | Quantity::GlareIntensity => format!("{v:.0}"),
        Quantity::Emin | Quantity::Em if v < 10.0 => format!("{v:.2}"),
        _ => format!("{v:.1}"),
    }
}

/// Every requirement of every area of `scene`, judged against the grids' results
/// (`grids`: their statistics, in the scene's order) and the observers' glare (`glare`);
/// `direct_only` when the values hold no interreflected light (walls and ceilings are
/// then noted: their light is mostly interreflected); `interp` samples the luminaires'
/// intensities (EN 1838's glare limits).
pub fn judge(
    scene: &Scene,
    grids: &[GridStats],
    glare: &[ObserverGlare],
    (direct_only, interp): (bool, Interp),
) -> Vec<Verdict> {
    scene
        .areas
        .iter()
        .flat_map(|area| {
            area.requirements.iter().map(move |r| {
                let mut v = judge_one(scene, area, r, (grids, glare), interp);
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
    (grids, glare): (&[GridStats], &[ObserverGlare]),
    interp: Interp,
) -> Verdict {
    let grid = match r.quantity {
        Quantity::Ugr | Quantity::Ra => None,
        _ => area.grid_of(r.part),
    };
    let stat = |f: fn(&GridStats) -> f64| (grid.map(|k| f(&grids[k])), None);
    let (achieved, note) = match r.quantity {
        Quantity::Em | Quantity::Ez => stat(|s| s.em),
        Quantity::U0 => stat(|s| s.u0),
        Quantity::Emin => stat(|s| s.emin),
        Quantity::G2 => stat(|s| s.g2),
        Quantity::MaxToMin => match grid.map(|k| grids[k]) {
            Some(s) if s.emin > 0.0 => (Some(s.emax / s.emin), None),
            _ => (
                None,
                Some("Emin is 0 lx: the ratio is unbounded".to_string()),
            ),
        },
        Quantity::Ugr => highest_ugr(scene, area, glare),
        Quantity::Ra => lowest_ra(scene),
        Quantity::GlareIntensity => match r.part {
            AreaPart::Luminaire(k) => (Some(glare_zone_peak(&scene.luminaires[k], interp)), None),
            _ => (None, None),
        },
    };
    let pass = match (r.quantity, achieved) {
        (Quantity::Ugr, None) => Some(true),
        (Quantity::MaxToMin, None) => Some(false),
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
            Quantity::Em | Quantity::Ez | Quantity::Emin => "lx",
            Quantity::GlareIntensity => "cd",
            _ => "",
        },
        standard: area.standard.name(),
        required: r.required,
        achieved,
        pass,
        basis: r.derived.unwrap_or("given").to_string(),
        note,
    }
}

/// The highest intensity (cd) of `luminaire` 60–90° from the downward vertical: every
/// 2.5° round, every 1° from 60° to 90°.
fn glare_zone_peak(luminaire: &crate::scene::PlacedLuminaire, interp: Interp) -> f64 {
    let mut peak: f64 = 0.0;
    for c in 0..144 {
        let azimuth = (c as f64 * 2.5).to_radians();
        for g in 60..=90 {
            let down = (g as f64).to_radians();
            let dir = glam::DVec3::new(
                down.sin() * azimuth.cos(),
                down.sin() * azimuth.sin(),
                -down.cos(),
            );
            peak = peak.max(luminaire.intensity_toward(dir, interp));
        }
    }
    peak
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
