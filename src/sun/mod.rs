//! The sun's position for a site and an instant, to NREL SPA accuracy.
//!
//! The position comes from the `solar-positioning` crate's implementation of the SPA
//! (Reda & Andreas 2004; tested against NREL's reference data, ±0.0003°). This module adds
//! the site and atmosphere, ΔT (an estimate for the date unless given), time zones, the
//! direction in goniolight's world frame (+X east, +Y north, +Z up) with a north offset,
//! sunrise/transit/sunset and a day's path.

pub mod time;

use chrono::{DateTime, Duration, NaiveDate, Utc};
use glam::DVec3;
use serde::Serialize;
use solar_positioning::{
    delta_t, Horizon, Location, RefractionCorrection, SolarEvents, SolarPositions,
};

pub use time::{parse_time, Zone};

/// What can go wrong computing a sun position.
#[derive(Debug, thiserror::Error)]
pub enum SunError {
    /// A bad input value, named as the library names it: `field` is one of `latitude`,
    /// `longitude`, `elevation_m` ([`Site`]), `delta_t`, `pressure_hpa/temperature_c`
    /// ([`SunOptions`]), `zone` ([`Zone::parse`]), `time` ([`parse_time`]) or `step`
    /// ([`path`]); a front end names its own parameter instead (the command line: `--lat`,
    /// `--tz`, …).
    #[error("{field} {value} {problem}")]
    Invalid {
        /// The field.
        field: &'static str,
        /// The value as given.
        value: String,
        /// What is wrong with it, and what would do.
        problem: String,
    },
    /// The algorithm refused (e.g. a date outside its range).
    #[error("sun position: {0}")]
    Model(String),
}

/// Where the observer is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    /// Latitude, degrees north (−90…90).
    pub latitude: f64,
    /// Longitude, degrees east (−180…180).
    pub longitude: f64,
    /// Elevation above sea level, metres.
    pub elevation_m: f64,
}

impl Site {
    /// A site, checked.
    pub fn new(latitude: f64, longitude: f64, elevation_m: f64) -> Result<Site, SunError> {
        if !latitude.is_finite() || !(-90.0..=90.0).contains(&latitude) {
            return Err(SunError::invalid(
                "latitude",
                latitude,
                "is outside [-90, 90]",
            ));
        }
        if !longitude.is_finite() || !(-180.0..=180.0).contains(&longitude) {
            return Err(SunError::invalid(
                "longitude",
                longitude,
                "is outside [-180, 180]",
            ));
        }
        if !elevation_m.is_finite() || !(-500.0..=9000.0).contains(&elevation_m) {
            return Err(SunError::invalid(
                "elevation_m",
                elevation_m,
                "is not plausible (-500 to 9000 m above sea level)",
            ));
        }
        Ok(Site {
            latitude,
            longitude,
            elevation_m,
        })
    }
}

/// Atmosphere and time-scale settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunOptions {
    /// TT − UT1 in seconds; `None` estimates it for the date.
    pub delta_t: Option<f64>,
    /// Pressure for refraction, hPa.
    pub pressure_hpa: f64,
    /// Temperature for refraction, °C.
    pub temperature_c: f64,
    /// Angle from the model's +Y axis clockwise (seen from above) to true north, degrees.
    pub north_offset_deg: f64,
}

impl Default for SunOptions {
    fn default() -> Self {
        SunOptions {
            delta_t: None,
            pressure_hpa: 1013.25,
            temperature_c: 12.0,
            north_offset_deg: 0.0,
        }
    }
}

/// The sun seen from a site at an instant.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct SunPosition {
    /// The instant, UTC.
    pub utc: DateTime<Utc>,
    /// Topocentric zenith angle without refraction, degrees.
    pub zenith_deg: f64,
    /// Zenith angle with refraction, degrees.
    pub apparent_zenith_deg: f64,
    /// Apparent elevation (90° − apparent zenith), degrees.
    pub elevation_deg: f64,
    /// Azimuth clockwise from north, degrees.
    pub azimuth_deg: f64,
    /// Unit vector toward the sun in the world frame (apparent position).
    pub direction: [f64; 3],
    /// ΔT used, seconds.
    pub delta_t_s: f64,
}

impl SunPosition {
    /// The keys of `sun --json` (the instant in RFC 3339 UTC with milliseconds).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "utc": self.utc.to_rfc3339_opts(chrono::SecondsFormat::Millis, true),
            "zenith_deg": self.zenith_deg,
            "apparent_zenith_deg": self.apparent_zenith_deg,
            "elevation_deg": self.elevation_deg,
            "azimuth_deg": self.azimuth_deg,
            "direction": self.direction,
            "delta_t_s": self.delta_t_s,
        })
    }
}

impl SunError {
    /// [`SunError::Invalid`] for `field` holding `value`.
    pub fn invalid(
        field: &'static str,
        value: impl std::fmt::Display,
        problem: impl Into<String>,
    ) -> SunError {
        SunError::Invalid {
            field,
            value: value.to_string(),
            problem: problem.into(),
        }
    }
}

fn model_err(e: impl std::fmt::Display) -> SunError {
    SunError::Model(e.to_string())
}

/// ΔT for `utc`: the given value or the crate's estimate (Espenak–Meeus, updated fits).
fn delta_t_for(utc: &DateTime<Utc>, opts: &SunOptions) -> Result<f64, SunError> {
    match opts.delta_t {
        Some(d) if d.is_finite() => Ok(d),
        Some(d) => Err(SunError::invalid(
            "delta_t",
            d,
            "is not a number of seconds",
        )),
        None => delta_t::estimate_from_date_like(utc).map_err(model_err),
    }
}

/// Unit vector toward a sun at `azimuth_deg` (clockwise from north) and `elevation_deg`,
/// in the world frame whose +Y is `north_offset_deg` counter-clockwise from true north.
pub fn direction_from_angles(azimuth_deg: f64, elevation_deg: f64, north_offset_deg: f64) -> DVec3 {
    let a = (azimuth_deg + north_offset_deg).to_radians();
    let e = elevation_deg.to_radians();
    DVec3::new(a.sin() * e.cos(), a.cos() * e.cos(), e.sin())
}

/// The sun's position for `site` at `utc`.
pub fn position(
    site: &Site,
    utc: DateTime<Utc>,
    opts: &SunOptions,
) -> Result<SunPosition, SunError> {
    let refraction =
        RefractionCorrection::new(opts.pressure_hpa, opts.temperature_c).map_err(|e| {
            SunError::Invalid {
                field: "pressure_hpa/temperature_c",
                value: format!("{}/{}", opts.pressure_hpa, opts.temperature_c),
                problem: format!("is not an atmosphere: {e}"),
            }
        })?;
    let dt = delta_t_for(&utc, opts)?;
    let location = Location {
        latitude: site.latitude,
        longitude: site.longitude,
    };
    let prepared = SolarPositions::new()
        .for_time(&utc, dt)
        .map_err(model_err)?;
    let geometric = prepared
        .at(location, site.elevation_m, None)
        .map_err(model_err)?;
    let apparent = prepared
        .at(location, site.elevation_m, Some(refraction))
        .map_err(model_err)?;
    let elevation = apparent.elevation_angle();
    Ok(SunPosition {
        utc,
        zenith_deg: geometric.zenith_angle(),
        apparent_zenith_deg: apparent.zenith_angle(),
        elevation_deg: elevation,
        azimuth_deg: apparent.azimuth(),
        direction: direction_from_angles(apparent.azimuth(), elevation, opts.north_offset_deg)
            .to_array(),
        delta_t_s: dt,
    })
}

/// Sunrise, transit and sunset of a local date.
#[derive(Debug, Clone, Serialize)]
pub struct DayEvents {
    /// Rises (usually one; none in polar night or day).
    pub sunrise: Vec<DateTime<Utc>>,
    /// Upper meridian transits.
    pub transit: Vec<DateTime<Utc>>,
    /// Sets.
    pub sunset: Vec<DateTime<Utc>>,
}

/// Sunrise, transit and sunset on local `date` in `zone`.
pub fn day_events(
    site: &Site,
    date: NaiveDate,
    zone: &Zone,
    opts: &SunOptions,
) -> Result<DayEvents, SunError> {
    let location = Location {
        latitude: site.latitude,
        longitude: site.longitude,
    };
    let dt = match opts.delta_t {
        Some(d) => d,
        None => delta_t::estimate_from_date_like(&date).map_err(model_err)?,
    };
    let calc = SolarEvents::new();
    let ev = match zone {
        Zone::Iana(tz) => events_utc(calc.for_date(date, tz, location, dt, Horizon::SunriseSunset)),
        Zone::Fixed(off) => {
            events_utc(calc.for_date(date, off, location, dt, Horizon::SunriseSunset))
        }
    }?;
    Ok(ev)
}

fn events_utc<T: chrono::TimeZone>(
    e: solar_positioning::Result<solar_positioning::Events<DateTime<T>>>,
) -> Result<DayEvents, SunError> {
    let e = e.map_err(model_err)?;
    let utc = |v: Vec<DateTime<T>>| v.into_iter().map(|t| t.with_timezone(&Utc)).collect();
    Ok(DayEvents {
        sunrise: utc(e.rises),
        transit: utc(e.transits),
        sunset: utc(e.sets),
    })
}

/// Positions from `start` to `end` (inclusive) every `step`.
pub fn path(
    site: &Site,
    start: DateTime<Utc>,
    end: DateTime<Utc>,
    step: Duration,
    opts: &SunOptions,
) -> Result<Vec<SunPosition>, SunError> {
    if step <= Duration::zero() {
        return Err(SunError::invalid("step", step, "must be positive"));
    }
    let mut out = Vec::new();
    let mut t = start;
    while t <= end {
        out.push(position(site, t, opts)?);
        t += step;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_values_name_their_fields_as_the_library_does() {
        let said = |e: SunError| e.to_string();
        assert_eq!(
            said(Site::new(95.0, 0.0, 0.0).unwrap_err()),
            "latitude 95 is outside [-90, 90]"
        );
        assert!(said(Site::new(0.0, 0.0, f64::NAN).unwrap_err()).starts_with("elevation_m NaN "));
        assert!(said(Zone::parse("Nowhere/City").unwrap_err())
            .starts_with("zone \"Nowhere/City\" is not a time zone"));
        assert_eq!(
            said(parse_time("2026-06-21T12:00", None).unwrap_err()),
            format!("time \"2026-06-21T12:00\" {}", time::NO_OFFSET)
        );
        let site = Site::new(40.0, 0.0, 0.0).unwrap();
        let (utc, _) = parse_time("2026-06-21T12:00:00Z", None).unwrap();
        let thin = SunOptions {
            pressure_hpa: -3.0,
            ..SunOptions::default()
        };
        assert!(said(position(&site, utc, &thin).unwrap_err())
            .starts_with("pressure_hpa/temperature_c -3/12 is not an atmosphere"));
    }

    #[test]
    fn spa_paper_example() {
        // Reda & Andreas 2004, Table A4.1.
        let site = Site::new(39.742476, -105.1786, 1830.14).unwrap();
        let (utc, _) = parse_time("2003-10-17T12:30:30-07:00", None).unwrap();
        let opts = SunOptions {
            delta_t: Some(67.0),
            pressure_hpa: 820.0,
            temperature_c: 11.0,
            north_offset_deg: 0.0,
        };
        let p = position(&site, utc, &opts).unwrap();
        // The paper's zenith (50.11162°) includes refraction at 820 hPa and 11 °C.
        assert!(
            (p.apparent_zenith_deg - 50.11162).abs() < 1e-4,
            "{}",
            p.apparent_zenith_deg
        );
        assert!(
            (p.azimuth_deg - 194.34024).abs() < 1e-4,
            "{}",
            p.azimuth_deg
        );
        // Without refraction the sun is lower: 50.12795°.
        assert!((p.zenith_deg - 50.12795).abs() < 1e-4, "{}", p.zenith_deg);
        assert!((p.elevation_deg - (90.0 - p.apparent_zenith_deg)).abs() < 1e-12);
    }

    #[test]
    fn direction_frame_and_north_offset() {
        let d = direction_from_angles(90.0, 0.0, 0.0);
        assert!((d - DVec3::X).length() < 1e-12, "east is +X");
        let d = direction_from_angles(0.0, 90.0, 0.0);
        assert!((d - DVec3::Z).length() < 1e-12);
        // North 90° counter-clockwise from +Y means true north is −X... and south +X.
        let d = direction_from_angles(180.0, 0.0, -90.0);
        assert!((d - DVec3::X).length() < 1e-12, "{d}");
    }

    #[test]
    fn bad_sites() {
        assert!(Site::new(91.0, 0.0, 0.0).is_err());
        assert!(Site::new(0.0, f64::NAN, 0.0).is_err());
    }
}
