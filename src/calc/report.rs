//! The calculation's report (`calc --report report.html`): one self-contained HTML page a designer hands over — the
//! settings used, the luminaires, the verification of the EN 12464-1 areas (a table,
//! green where met, red where not), and per grid its statistics and plan (inline SVG).

use std::fmt::Write as _;

use crate::calc::daylight::FactorStats;
use crate::calc::requirements::Verdict;
use crate::calc::GridStats;
use crate::io::xml_escape as escape;
use crate::scene::Scene;

/// One grid's part of the report.
pub struct ReportGrid<'a> {
    /// The grid's name.
    pub name: &'a str,
    /// Its kind, as the scene file names it.
    pub kind: String,
    /// Its statistics (maintained).
    pub stats: GridStats,
    /// Its plan, as an SVG document.
    pub plan_svg: String,
    /// Its daylight factor's statistics and plan (SVG), under the CIE overcast sky.
    pub daylight_factor: Option<(FactorStats, String)>,
}

/// One observer's part of the report.
pub struct ReportObserver<'a> {
    /// The observer's name.
    pub name: &'a str,
    /// The eye, metres.
    pub eye: glam::DVec3,
    /// The line of sight.
    pub forward: glam::DVec3,
    /// The glare there.
    pub glare: &'a crate::calc::glare::ObserverGlare,
}

const STYLE: &str = "body{font-family:sans-serif;max-width:1200px;margin:2em auto;color:#222}\
table{border-collapse:collapse;margin:.5em 0 1.5em}td,th{padding:2px 10px;border-bottom:1px solid #ddd;text-align:left}\
th{background:#f3f3f3}td.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}\
tr.pass td.v{background:#d6f5d6;color:#135e13}tr.fail td.v{background:#f9d4d4;color:#8a1010}\
tr.unknown td.v{background:#fff1c2;color:#6b5200}td.v{font-weight:bold}td.b{color:#666;font-size:85%}\
svg{max-width:100%;height:auto}footer{color:#777;font-size:80%;margin-top:2em}";

/// A luminaire's dimming as a reader writes it: at most four decimals, zeros dropped.
fn dimming(m: f64) -> String {
    let s = format!("{m:.4}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The verification table: one row per requirement, its outcome coloured.
fn verification(h: &mut String, verdicts: &[Verdict]) {
    if verdicts.is_empty() {
        return;
    }
    let failed = verdicts.iter().filter(|v| v.pass != Some(true)).count();
    let mut standards: Vec<&str> = verdicts.iter().map(|v| v.standard).collect();
    standards.dedup();
    let _ = write!(
        h,
        "<h2>Verification ({})</h2><p>{}</p><table><tr><th>area</th><th>part</th><th>quantity</th><th>required</th><th>achieved (maintained)</th><th>result</th><th>limit from</th></tr>",
        escape(&standards.join(", ")),
        if failed == 0 {
            format!("All {} requirements are met.", verdicts.len())
        } else {
            format!("{failed} of {} requirements are not met or not known.", verdicts.len())
        }
    );
    for v in verdicts {
        let basis = match &v.note {
            Some(n) => format!("{} — {n}", v.basis),
            None => v.basis.clone(),
        };
        let _ = write!(
            h,
            "<tr class=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"v\">{}</td><td class=\"b\">{}</td></tr>",
            v.outcome(),
            escape(&v.area),
            v.part.label(),
            v.quantity.name(),
            escape(&v.limit_text()),
            escape(&v.achieved_text()),
            v.outcome(),
            escape(&basis)
        );
    }
    h.push_str("</table>");
}

/// The daylight factor table (CIE overcast sky), where the grids have one.
fn daylight_factors(h: &mut String, grids: &[ReportGrid]) {
    if grids.iter().all(|g| g.daylight_factor.is_none()) {
        return;
    }
    h.push_str("<h2>Daylight factor (CIE standard overcast sky)</h2><table><tr><th>grid</th><th>mean (%)</th><th>median (%)</th><th>min (%)</th><th>max (%)</th><th>U0 (min/mean)</th></tr>");
    for g in grids {
        if let Some((f, _)) = &g.daylight_factor {
            let _ = write!(
                h,
                "<tr><td>{}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:.2}</td></tr>",
                escape(g.name),
                f.mean,
                f.median,
                f.min,
                f.max,
                f.u0
            );
        }
    }
    h.push_str("</table>");
}

/// The report page.
pub fn report_html(
    scene: &Scene,
    settings: &[(&str, String)],
    grids: &[ReportGrid],
    observers: &[ReportObserver],
    verdicts: &[Verdict],
) -> String {
    let title = scene
        .path
        .file_name()
        .map_or("scene".into(), |n| n.to_string_lossy().into_owned());
    let mut h = String::new();
    let _ = write!(
        h,
        "<!doctype html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{} — lighting calculation</title><style>{STYLE}</style></head><body><h1>Lighting calculation: {}</h1>",
        escape(&title),
        escape(&title)
    );
    h.push_str("<h2>Settings</h2><table>");
    for (k, v) in settings {
        let _ = write!(h, "<tr><th>{}</th><td>{}</td></tr>", escape(k), escape(v));
    }
    h.push_str("</table><h2>Luminaires</h2><table><tr><th></th><th>file</th><th>name</th><th>lamp flux (lm)</th><th>luminaire flux (lm)</th><th>dimming</th><th>position (m)</th></tr>");
    for (i, l) in scene.luminaires.iter().enumerate() {
        let s = l.luminaire.summary();
        let file = l
            .file
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned());
        let p = l.position;
        let _ = write!(
            h,
            "<tr><td>L{}</td><td>{}</td><td>{}</td><td class=\"n\">{:.0}</td><td class=\"n\">{:.0}</td><td class=\"n\">{}</td><td class=\"n\">{:.2}, {:.2}, {:.2}</td></tr>",
            i + 1,
            escape(&file),
            escape(l.luminaire.data.luminaire_name.trim()),
            s.lamp_flux_lm,
            s.flux_lm * l.multiplier,
            dimming(l.multiplier),
            p.x,
            p.y,
            p.z
        );
    }
    h.push_str("</table>");
    verification(&mut h, verdicts);
    h.push_str("<h2>Calculation surfaces</h2><table><tr><th>grid</th><th>kind</th><th>points</th><th>Em (lx)</th><th>Emin (lx)</th><th>Emax (lx)</th><th>U0</th><th>g2</th></tr>");
    for g in grids {
        let s = &g.stats;
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{:.1}</td><td class=\"n\">{:.1}</td><td class=\"n\">{:.1}</td><td class=\"n\">{:.2}</td><td class=\"n\">{:.2}</td></tr>",
            escape(g.name),
            escape(&g.kind),
            s.points,
            s.em,
            s.emin,
            s.emax,
            s.u0,
            s.g2
        );
    }
    h.push_str("</table>");
    daylight_factors(&mut h, grids);
    if !observers.is_empty() {
        h.push_str("<h2>Glare at observers (UGR, CIE 117)</h2><table><tr><th>observer</th><th>eye (m)</th><th>line of sight</th><th>background L<sub>b</sub> (cd/m²)</th><th>luminaires counted</th><th>UGR</th></tr>");
        for o in observers {
            let (e, f) = (o.eye, o.forward);
            let _ = write!(
                h,
                "<tr><td>{}</td><td class=\"n\">{:.2}, {:.2}, {:.2}</td><td class=\"n\">{:.2}, {:.2}, {:.2}</td><td class=\"n\">{:.1}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
                escape(o.name),
                e.x,
                e.y,
                e.z,
                f.x,
                f.y,
                f.z,
                o.glare.background_cd_m2,
                o.glare.luminaires.len(),
                o.glare
                    .ugr
                    .map_or("— (no luminaire in the field)".into(), |u| format!("{u:.1}"))
            );
        }
        h.push_str("</table>");
    }
    for g in grids {
        let _ = write!(h, "<h2>{}</h2><div>{}</div>", escape(g.name), g.plan_svg);
        if let Some((_, svg)) = &g.daylight_factor {
            let _ = write!(
                h,
                "<h2>{}: daylight factor</h2><div>{svg}</div>",
                escape(g.name)
            );
        }
    }
    let _ = write!(
        h,
        "<footer>goniolight {} · calc · maintained illuminance (computed × maintenance factor)</footer></body></html>",
        env!("CARGO_PKG_VERSION")
    );
    h
}
