//! The planning tests' outputs: `sunlight.json` (the figures, the verdicts and the method
//! a reviewer needs to reproduce them), `windows.csv`, `NAME-hours.csv` per open space,
//! and the report page.

use serde_json::{json, Value};

use super::suns::SUNSHINE_THRESHOLD_W;
use super::verdicts::{
    en17037_level, faces_the_sun_side, judge_open_space, judge_window, WindowVerdict,
    APSH_LOSS_POINTS, APSH_TARGET_PCT, EN17037_MINIMUM_H, FORMER_VALUE_RATIO, OPEN_SPACE_SHARE,
    WPSH_TARGET_PCT,
};
use super::vsc::VSC_TARGET_PCT;
use super::{SunlightAssessment, OPEN_SPACE_HOURS};
use crate::photometry::info::csv_line;
use crate::scene::planning::Window;
use crate::scene::Scene;

/// One window's figures and verdicts together.
#[derive(Debug, Clone)]
pub struct WindowRow<'a> {
    /// The window.
    pub window: &'a Window,
    /// Whether it faces within 90° of due south (north south of the equator).
    pub sun_side: bool,
    /// The proposed scene's figures.
    pub now: super::WindowFigures,
    /// The baseline's.
    pub former: Option<super::WindowFigures>,
    /// The verdicts.
    pub verdict: WindowVerdict,
}

/// The windows' rows of `assessment` of `scene`.
pub fn window_rows<'a>(scene: &'a Scene, assessment: &SunlightAssessment) -> Vec<WindowRow<'a>> {
    let (latitude, north) = scene
        .site
        .as_ref()
        .map_or((0.0, 0.0), |s| (s.latitude, s.north_offset_deg));
    scene
        .planning
        .windows
        .iter()
        .enumerate()
        .map(|(k, w)| {
            let now = assessment.proposed.windows[k];
            let former = assessment.baseline.as_ref().map(|b| b.windows[k]);
            let sun_side = faces_the_sun_side(w.normal, latitude, north);
            WindowRow {
                window: w,
                sun_side,
                now,
                former,
                verdict: judge_window(&now, former.as_ref(), sun_side),
            }
        })
        .collect()
}

/// A number rounded to `digits` decimals for JSON.
fn round(v: f64, digits: i32) -> f64 {
    let f = 10f64.powi(digits);
    (v * f).round() / f
}

/// `sunlight.json` of `assessment` of `scene`, its windows' `rows` ([`window_rows`])
/// (`label` names the scene, `baseline_label` the baseline's).
pub fn sunlight_json(
    scene: &Scene,
    assessment: &SunlightAssessment,
    rows: &[WindowRow],
    label: &str,
    baseline_label: Option<&str>,
) -> Value {
    let windows: Vec<Value> = rows
        .iter()
        .map(|r| {
            let figures = |f: &super::WindowFigures| {
                json!({
                    "vsc": round(f.vsc, 2),
                    "apsh": f.apsh.map(|v| round(v, 2)),
                    "wpsh": f.wpsh.map(|v| round(v, 2)),
                    "en17037_hours": round(f.en17037_hours, 3),
                })
            };
            json!({
                "name": r.window.entry.name,
                "position": r.window.entry.position,
                "normal": r.window.normal.to_array(),
                "faces_sun_side": r.sun_side,
                "vsc": round(r.now.vsc, 2),
                "apsh": r.now.apsh.map(|v| round(v, 2)),
                "wpsh": r.now.wpsh.map(|v| round(v, 2)),
                "en17037_hours": round(r.now.en17037_hours, 3),
                "en17037_rating": en17037_level(r.now.en17037_hours),
                "baseline": r.former.as_ref().map(figures),
                "pass": {
                    "vsc": r.verdict.vsc,
                    "sunlight": r.verdict.sunlight,
                    "en17037": r.verdict.en17037,
                },
            })
        })
        .collect();
    let areas: Vec<Value> = scene
        .planning
        .open_spaces
        .iter()
        .enumerate()
        .map(|(k, o)| {
            let now = &assessment.proposed.open_spaces[k];
            let former = assessment.baseline.as_ref().map(|b| &b.open_spaces[k]);
            let cell = o.grid.spacing[0] * o.grid.spacing[1];
            json!({
                "name": o.entry.name,
                "area_m2": round(cell * o.grid.points.len() as f64, 2),
                "points": o.grid.points.len(),
                "sunlit_fraction_2h": round(now.sunlit_fraction_2h, 4),
                "baseline": former.map(|f| json!({"sunlit_fraction_2h": round(f.sunlit_fraction_2h, 4)})),
                "pass": judge_open_space(now, former),
            })
        })
        .collect();
    json!({
        "scene": label,
        "windows": windows,
        "areas": areas,
        "method": method_json(scene, assessment, baseline_label),
    })
}

/// How the figures were computed, for a reviewer.
fn method_json(scene: &Scene, a: &SunlightAssessment, baseline_label: Option<&str>) -> Value {
    let o = &a.options;
    let probable = a.options.weather.as_ref().zip(a.probable_hours).map(|(w, h)| {
        json!({
            "weather": w.path.display().to_string(),
            "location": {
                "city": w.location.city,
                "latitude": w.location.latitude,
                "longitude": w.location.longitude,
                "time_zone_h": w.location.time_zone_h,
            },
            "sunshine_threshold_w_m2": SUNSHINE_THRESHOLD_W,
            "annual_probable_sunlight_hours": h.annual,
            "winter_probable_sunlight_hours": h.winter,
            "hours_missing_direct_normal": h.missing,
            "hour": "the sun's position at the middle of each hour of the file (local standard time of the file's zone); an hour counts at a window when its direct normal irradiance exceeds the threshold, the sun is above the horizon and within 90° of the window's normal, and the ray toward it meets nothing",
            "winter": "21 September to 21 March; WPSH is per cent of the annual probable sunlight hours",
        })
    });
    json!({
        "standards": {
            "vsc": format!("BRE 209 (2022) section 2.2: VSC ≥ {VSC_TARGET_PCT} % or ≥ {FORMER_VALUE_RATIO} × the baseline's"),
            "sunlight": format!("BRE 209 (2022) section 3.2: windows facing within 90° of due south (north south of the equator); affected when APSH < {APSH_TARGET_PCT} % or WPSH < {WPSH_TARGET_PCT} %, and < {FORMER_VALUE_RATIO} × the baseline's in either period, and the annual loss > {APSH_LOSS_POINTS} points"),
            "en17037": format!("EN 17037:2018+A1:2021 clause 5.4 and Annex A: sunlight exposure on one day from 1 February to 21 March; minimum {EN17037_MINIMUM_H} h, medium 3 h, high 4 h"),
            "open_spaces": format!("BRE 209 (2022) section 3.3: at least {} % of the area with {OPEN_SPACE_HOURS} h of sun on the day, or ≥ {FORMER_VALUE_RATIO} × the baseline's share", OPEN_SPACE_SHARE * 100.0),
        },
        "site": scene.site.as_ref().map(|s| json!({
            "latitude": s.latitude,
            "longitude": s.longitude,
            "timezone": s.timezone,
            "north_offset_deg": s.north_offset_deg,
        })),
        "vsc": {
            "sky": "CIE standard overcast sky (traditional: L(Z) = L_z (1 + 2 cos Z) / 3), sky component only: no light reflected by the ground or the buildings",
            "reference": "per cent of the simultaneous illuminance on an unobstructed horizontal plane; an unobstructed vertical window gets 39.6 %",
            "sampling": "the window's hemisphere in 128 × 512 cells, refined across the edges of obstructions (CPU ray casts through the model, every triangle opaque)",
        },
        "probable_sunlight": probable,
        "days": {
            "open_spaces": o.open_space_date.to_string(),
            "en17037": o.en17037_date.to_string(),
            "step_min": o.step_min,
            "sun_hours_open_spaces_day": round(a.day_sun_hours.0, 3),
            "sun_hours_en17037_day": round(a.day_sun_hours.1, 3),
            "en17037_min_elevation_deg": o.min_elevation_deg,
            "rule": "the sun at the middle of each step from midnight to midnight (local time), above the horizon; a point counts a step when the sun is in front of its surface and the ray toward it meets nothing",
        },
        "baseline": baseline_label,
        "sun_position": "NREL SPA (Reda & Andreas 2004) with refraction at 1013.25 hPa and 12 °C",
        "version": env!("CARGO_PKG_VERSION"),
    })
}

/// `windows.csv`: one row per window.
pub fn windows_csv(rows: &[WindowRow]) -> String {
    let mut csv = String::from(
        "name,x,y,z,nx,ny,nz,vsc,apsh,wpsh,en17037_hours,en17037_rating,baseline_vsc,baseline_apsh,baseline_wpsh,pass_vsc,pass_sunlight,pass_en17037\n",
    );
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.2}"));
    for r in rows {
        let p = r.window.position;
        let n = r.window.normal;
        csv += &csv_line(&[
            r.window.entry.name.clone(),
            p.x.to_string(),
            p.y.to_string(),
            p.z.to_string(),
            format!("{:.6}", n.x),
            format!("{:.6}", n.y),
            format!("{:.6}", n.z),
            format!("{:.2}", r.now.vsc),
            opt(r.now.apsh),
            opt(r.now.wpsh),
            format!("{:.3}", r.now.en17037_hours),
            en17037_level(r.now.en17037_hours).to_string(),
            opt(r.former.map(|f| f.vsc)),
            opt(r.former.and_then(|f| f.apsh)),
            opt(r.former.and_then(|f| f.wpsh)),
            r.verdict.vsc.to_string(),
            r.verdict.sunlight.map_or(String::new(), |b| b.to_string()),
            r.verdict.en17037.to_string(),
        ]);
    }
    csv
}

/// An open space's hours of sun per point: `x,y,z,hours` (and `baseline_hours`).
pub fn open_space_csv(points: &[glam::DVec3], hours: &[f64], former: Option<&[f64]>) -> String {
    let mut csv = String::from(if former.is_some() {
        "x,y,z,hours,baseline_hours\n"
    } else {
        "x,y,z,hours\n"
    });
    for (k, (p, h)) in points.iter().zip(hours).enumerate() {
        csv += &format!("{},{},{},{h:.3}", p.x, p.y, p.z);
        if let Some(f) = former {
            csv += &format!(",{:.3}", f[k]);
        }
        csv.push('\n');
    }
    csv
}
