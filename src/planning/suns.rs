//! The suns the planning tests count: every few minutes of one day (the 2-hour test of
//! gardens on 21 March, EN 17037's sunlight exposure), and the hours of a weather file with
//! sunshine (probable sunlight hours).

use chrono::{Datelike, NaiveDate};
use glam::DVec3;

use super::PlanningError;
use crate::shadow::sun_rays::Sun;
use crate::sun::{Site, SunOptions, Zone};
use crate::weather::Weather;

/// The WMO's sunshine threshold: direct normal irradiance above it counts as sunshine,
/// W/m².
pub const SUNSHINE_THRESHOLD_W: f64 = 120.0;

/// The suns of `date` (local day in `zone`), one at the middle of every `step_min` minutes
/// from midnight to midnight, each standing for its step, those above the horizon only.
pub fn day_suns(
    site: &Site,
    zone: &Zone,
    date: NaiveDate,
    step_min: f64,
    options: &SunOptions,
) -> Result<Vec<Sun>, PlanningError> {
    let midnight = |d: NaiveDate| {
        zone.resolve(d.and_hms_opt(0, 0, 0).expect("midnight"))
            .map(|(utc, _)| utc)
            .map_err(|e| PlanningError::input("date", e.to_string()))
    };
    let start = midnight(date)?;
    let end = midnight(date.succ_opt().ok_or_else(|| {
        PlanningError::input("date", format!("{date} is the last day of the calendar"))
    })?)?;
    let step_s = step_min * 60.0;
    let steps = ((end - start).num_seconds() as f64 / step_s).round() as usize;
    let mut suns = Vec::new();
    for k in 0..steps {
        let at = start + chrono::Duration::milliseconds(((k as f64 + 0.5) * step_s * 1e3) as i64);
        let p = crate::sun::position(site, at, options)
            .map_err(|e| PlanningError::input("date", e.to_string()))?;
        if p.elevation_deg > 0.0 {
            suns.push(Sun {
                direction: DVec3::from_array(p.direction),
                elevation_deg: p.elevation_deg,
                weight_h: step_min / 60.0,
            });
        }
    }
    Ok(suns)
}

/// Whether `month`/`day` lies in BRE 209's winter period, 21 September to 21 March.
pub fn in_winter(month: u32, day: u32) -> bool {
    (month, day) >= (9, 21) || (month, day) <= (3, 21)
}

/// The probable sunlight hours of a weather file at a site: every hour with direct normal
/// irradiance above [`SUNSHINE_THRESHOLD_W`] and the sun above the horizon at its middle,
/// its sun weighing one hour.
#[derive(Debug, Clone)]
pub struct ProbableSun {
    /// The hours of the year.
    pub annual: Vec<Sun>,
    /// Those from 21 September to 21 March.
    pub winter: Vec<Sun>,
    /// Hours without a direct normal irradiance in the file (counted as no sunshine).
    pub missing_hours: usize,
}

impl ProbableSun {
    /// The hours of `weather` with sunshine at `site` (the file's own time zone, standard
    /// time, places its hours).
    pub fn of(
        weather: &Weather,
        site: &Site,
        options: &SunOptions,
    ) -> Result<ProbableSun, PlanningError> {
        let mut out = ProbableSun {
            annual: Vec::new(),
            winter: Vec::new(),
            missing_hours: 0,
        };
        for h in &weather.hours {
            let Some(dni) = h.direct_normal_w else {
                out.missing_hours += 1;
                continue;
            };
            if dni <= SUNSHINE_THRESHOLD_W {
                continue;
            }
            let at = h.utc_midpoint(weather.location.time_zone_h);
            let p = crate::sun::position(site, at, options).map_err(|e| {
                PlanningError::input(
                    "weather",
                    format!(
                        "{}: {}-{:02}-{:02} hour {}: {e}",
                        weather.path.display(),
                        at.year(),
                        h.month,
                        h.day,
                        h.hour
                    ),
                )
            })?;
            if p.elevation_deg <= 0.0 {
                continue;
            }
            let sun = Sun {
                direction: DVec3::from_array(p.direction),
                elevation_deg: p.elevation_deg,
                weight_h: 1.0,
            };
            out.annual.push(sun);
            if in_winter(h.month, h.day) {
                out.winter.push(sun);
            }
        }
        Ok(out)
    }

    /// The year's probable sunlight hours (at an unobstructed point on level ground).
    pub fn annual_hours(&self) -> f64 {
        self.annual.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn winter_runs_from_the_autumn_to_the_spring_equinox() {
        assert!(in_winter(9, 21) && in_winter(12, 1) && in_winter(3, 21));
        assert!(!in_winter(9, 20) && !in_winter(3, 22) && !in_winter(6, 21));
    }

    #[test]
    fn a_day_of_suns_spans_sunrise_to_sunset() {
        // Vienna, 21 March: about 12 h 10 min between sunrise and sunset (SPA, `sun`).
        let site = Site::new(48.21, 16.37, 0.0).unwrap();
        let zone = Zone::parse("Europe/Vienna").unwrap();
        let date = NaiveDate::from_ymd_opt(2026, 3, 21).unwrap();
        let suns = day_suns(&site, &zone, date, 1.0, &SunOptions::default()).unwrap();
        let hours: f64 = suns.iter().map(|s| s.weight_h).sum();
        assert!((hours - 12.17).abs() < 0.05, "{hours}");
        assert!(suns.iter().all(|s| s.elevation_deg > 0.0));
    }
}
