//! The planning tests' report page (HTML, self-contained): the site plan, the windows'
//! and open spaces' verification tables (green pass, red fail) and the method.

use std::fmt::Write as _;

use super::output::WindowRow;
use super::verdicts::{en17037_level, judge_open_space};
use super::SunlightAssessment;
use crate::io::xml_escape;
use crate::scene::Scene;

/// A verdict cell.
fn verdict(pass: Option<bool>) -> &'static str {
    match pass {
        Some(true) => r#"<td class="pass">pass</td>"#,
        Some(false) => r#"<td class="fail">fail</td>"#,
        None => r#"<td class="na">—</td>"#,
    }
}

/// A per-cent figure, or a dash.
fn pct(v: Option<f64>) -> String {
    v.map_or("—".into(), |v| format!("{v:.1} %"))
}

/// The report page: `title`, the plan `svg`, the tables of `rows` and the open spaces of
/// `scene` in `assessment`, and the method as `method` (JSON, pretty-printed).
pub fn report_html(
    scene: &Scene,
    assessment: &SunlightAssessment,
    rows: &[WindowRow],
    svg: &str,
    title: &str,
    method: &serde_json::Value,
) -> String {
    let baseline = assessment.baseline.is_some();
    let mut html = format!(
        r#"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{t}</title>
<style>
body {{ font-family: "DejaVu Sans", sans-serif; margin: 2em; color: #222; }}
table {{ border-collapse: collapse; margin: 1em 0; }}
th, td {{ border: 1px solid #bbb; padding: 4px 8px; text-align: right; }}
th {{ background: #eee; }} td:first-child, th:first-child {{ text-align: left; }}
td.pass {{ background: #d8f0dc; color: #1a7f37; font-weight: bold; }}
td.fail {{ background: #f8d7d7; color: #c62828; font-weight: bold; }}
td.na {{ color: #888; }}
pre {{ background: #f6f6f6; padding: 1em; white-space: pre-wrap; }}
</style></head><body>
<h1>{t}</h1>
<p>BRE 209 (2022) skylight and sunlight to windows, sunlight to gardens and open spaces; EN 17037 sunlight exposure.{b}</p>
{svg}
<h2>Windows</h2>
<table><tr><th>window</th><th>VSC</th>"#,
        t = xml_escape(title),
        b = if baseline {
            " Figures in brackets: the baseline (existing situation)."
        } else {
            ""
        },
    );
    html += "<th>VSC test</th><th>APSH</th><th>WPSH</th><th>sunlight test</th><th>EN 17037 hours</th><th>level</th><th>EN 17037 test</th></tr>\n";
    for r in rows {
        let former = |f: &dyn Fn(&super::WindowFigures) -> Option<f64>| {
            r.former
                .as_ref()
                .map_or(String::new(), |w| format!(" ({})", pct(f(w))))
        };
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td>{}{}</td>{}<td>{}{}</td><td>{}{}</td>{}<td>{:.2} h</td><td>{}</td>{}</tr>",
            xml_escape(&r.window.entry.name),
            pct(Some(r.now.vsc)),
            former(&|w| Some(w.vsc)),
            verdict(Some(r.verdict.vsc)),
            pct(r.now.apsh),
            former(&|w| w.apsh),
            pct(r.now.wpsh),
            former(&|w| w.wpsh),
            verdict(r.verdict.sunlight),
            r.now.en17037_hours,
            en17037_level(r.now.en17037_hours),
            verdict(Some(r.verdict.en17037)),
        );
    }
    html += "</table>\n<p>VSC: at least 27 % or 0.8 × the baseline's. Sunlight (windows within 90° of due south; — where not tested or without a weather file): APSH ≥ 25 % and WPSH ≥ 5 % of the year's probable sunlight hours, or no loss below 0.8 × the baseline's of more than 4 points a year. EN 17037: minimum 1.5 h, medium 3 h, high 4 h on the day.</p>\n";
    html += "<h2>Gardens and open spaces</h2>\n<table><tr><th>open space</th><th>area</th><th>share with ≥ 2 h of sun</th><th>test</th></tr>\n";
    for (k, o) in scene.planning.open_spaces.iter().enumerate() {
        let now = &assessment.proposed.open_spaces[k];
        let former = assessment.baseline.as_ref().map(|b| &b.open_spaces[k]);
        let cell = o.grid.spacing[0] * o.grid.spacing[1];
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td>{:.1} m²</td><td>{:.1} %{}</td>{}</tr>",
            xml_escape(&o.entry.name),
            cell * o.grid.points.len() as f64,
            now.sunlit_fraction_2h * 100.0,
            former.map_or(String::new(), |f| format!(
                " ({:.1} %)",
                f.sunlit_fraction_2h * 100.0
            )),
            verdict(Some(judge_open_space(now, former))),
        );
    }
    html += "</table>\n<p>At least half of each area should get 2 hours of sun on the day, or 0.8 × the baseline's share.</p>\n";
    let _ = write!(
        html,
        "<h2>Method</h2>\n<pre>{}</pre>\n</body></html>\n",
        xml_escape(&serde_json::to_string_pretty(method).unwrap_or_default())
    );
    html
}
