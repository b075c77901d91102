//! A study's files beside each date's plans: the sun-path diagrams (the site's and one per
//! window point) and, for several dates, the dates' table.

use std::path::Path;

use chrono::NaiveDate;

use super::annotate::PlanLabels;
use super::mask::ObstructionMask;
use super::output::StudySummary;
use super::shadow_profile::{Profile, ProfileSpec};
use super::sunpath::{Projection, SunPathDiagram};
use crate::io::{write_atomic, WriteError};

/// The sun-path diagram of the study's site with this date's steps marked, stereographic
/// (`sunpath.svg`) and cylindrical (`sunpath-cylindrical.svg`), and one per window point with the sky the model hides from it
/// (`sunpath-NAME.svg`, the name's other characters than letters, digits, `-` and `_` as
/// `_`; a name taken already gets `-2`, `-3` …).
pub fn write_sun_path(
    spec: &ProfileSpec,
    profile: &Profile,
    dir: &Path,
    labels: &PlanLabels,
    masks: &[ObstructionMask],
) -> Result<(), WriteError> {
    let suns: Vec<_> = profile
        .steps
        .iter()
        .map(|s| (s.time, s.azimuth_deg, s.elevation_deg))
        .collect();
    let mut diagram = SunPathDiagram {
        site: spec.site,
        zone: spec.zone,
        year: chrono::Datelike::year(&spec.date),
        sun: spec.sun,
        title: format!("Sun path — {}", labels.title),
        marked: suns,
        mask: None,
        projection: Projection::Cylindrical,
    };
    let write = |diagram: &SunPathDiagram, name: &str| {
        let path = dir.join(name);
        let svg = diagram.svg().map_err(|e| WriteError::encode(&path, e))?;
        write_atomic(&path, svg.as_bytes())
    };
    write(&diagram, "sunpath-cylindrical.svg")?;
    diagram.projection = Projection::Stereographic;
    write(&diagram, "sunpath.svg")?;
    let title = diagram.title.clone();
    let names = diagram_names(masks.iter().map(|m| m.name.as_str()));
    for (mask, name) in masks.iter().zip(names) {
        diagram.title = format!("{title} — seen from {}", mask.name);
        diagram.mask = Some(mask.clone());
        write(&diagram, &name)?;
    }
    Ok(())
}

/// The files of the points' diagrams: `sunpath-NAME.svg` with [`file_safe`] names; two
/// names alike but for their odd characters get `-2`, `-3` … after the first, and so does a
/// point named like the site's cylindrical diagram.
fn diagram_names<'a>(points: impl Iterator<Item = &'a str>) -> Vec<String> {
    let mut used = std::collections::HashSet::from(["sunpath-cylindrical.svg".to_string()]);
    points
        .map(|point| {
            let stem = file_safe(point);
            (1..)
                .map(|k| match k {
                    1 => format!("sunpath-{stem}.svg"),
                    k => format!("sunpath-{stem}-{k}.svg"),
                })
                .find(|n| used.insert(n.clone()))
                .expect("an unused name")
        })
        .collect()
}

/// `name` with every character but ASCII letters, digits, `-` and `_` as `_`.
fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// `dates.csv` and `dates.json` beside the per-date folders: one row per date.
pub fn write_dates_table(
    dir: &Path,
    summaries: &[(NaiveDate, StudySummary)],
) -> Result<(), WriteError> {
    use std::fmt::Write as _;
    let mut csv = String::from("date,metric,period_h,sun_up_h,mean_h,threshold_h,pass_fraction\n");
    for (date, s) in summaries {
        let _ = writeln!(
            csv,
            "{date},{},{:.4},{:.4},{:.4},{},{}",
            s.metric,
            s.period_h,
            s.sun_up_h,
            s.mean_h,
            s.threshold_h.map_or(String::new(), |t| t.to_string()),
            s.pass_fraction.map_or(String::new(), |f| format!("{f:.6}"))
        );
    }
    write_atomic(&dir.join("dates.csv"), csv.as_bytes())?;
    let json: Vec<_> = summaries
        .iter()
        .map(|(d, s)| serde_json::json!({ "date": d.to_string(), "study": s }))
        .collect();
    let path = dir.join("dates.json");
    let text = serde_json::to_string_pretty(&json).map_err(|e| WriteError::encode(&path, e))?;
    write_atomic(&path, text.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::diagram_names;

    #[test]
    fn point_diagrams_get_safe_distinct_file_names() {
        let names = diagram_names(["a b", "a_b", "a/b", "Süd-1", "cylindrical"].into_iter());
        assert_eq!(
            names,
            [
                "sunpath-a_b.svg",
                "sunpath-a_b-2.svg",
                "sunpath-a_b-3.svg",
                "sunpath-S_d-1.svg",
                "sunpath-cylindrical-2.svg"
            ]
        );
    }
}
