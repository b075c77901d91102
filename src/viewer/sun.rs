//! The sun in the viewer: a site, a date and a time of day (with an animation over the
//! day) and the sun's position from `crate::sun`; the library's
//! [`crate::lighting::sun`] makes it a light.

use chrono::{NaiveDate, NaiveTime, Timelike};

use crate::sun::{Site, SunOptions, SunPosition, Zone};

/// The sun panel's settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SunControls {
    /// Whether the sun lights the scene.
    pub enabled: bool,
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Longitude, degrees east.
    pub longitude: f64,
    /// IANA time zone or a fixed offset (`Europe/Vienna`, `+01:00`).
    pub zone: String,
    /// Local date.
    pub date: NaiveDate,
    /// Local time of day, minutes after midnight.
    pub minutes: f64,
    /// Whether the time runs.
    pub animate: bool,
    /// Animation speed, hours of day per second.
    pub hours_per_second: f64,
    /// Angle from the model's +Y to true north, degrees.
    pub north_offset_deg: f64,
    /// Profile period start and end (local time) and step, minutes.
    pub profile_from: NaiveTime,
    /// End of the profile period.
    pub profile_to: NaiveTime,
    /// Minutes between profile steps.
    pub profile_step: u32,
    /// Side of the profile image, pixels.
    pub profile_resolution: u32,
}

impl Default for SunControls {
    fn default() -> Self {
        let hm = |h, m| NaiveTime::from_hms_opt(h, m, 0).unwrap_or_default();
        SunControls {
            enabled: false,
            latitude: 48.21,
            longitude: 16.37,
            zone: "Europe/Vienna".into(),
            date: NaiveDate::from_ymd_opt(2026, 6, 21).unwrap_or_default(),
            minutes: 12.0 * 60.0,
            animate: false,
            hours_per_second: 1.0,
            north_offset_deg: 0.0,
            profile_from: hm(8, 0),
            profile_to: hm(16, 0),
            profile_step: 15,
            profile_resolution: 512,
        }
    }
}

impl SunControls {
    /// The local time of day.
    pub fn time(&self) -> NaiveTime {
        let s = (self.minutes.clamp(0.0, 24.0 * 60.0 - 1.0 / 60.0) * 60.0).round() as u32;
        NaiveTime::from_num_seconds_from_midnight_opt(s.min(86_399), 0).unwrap_or_default()
    }

    /// The sun options (north offset).
    pub fn options(&self) -> SunOptions {
        SunOptions {
            north_offset_deg: self.north_offset_deg,
            ..SunOptions::default()
        }
    }

    /// The sun's position at the chosen local date and time.
    pub fn position(&self) -> Result<SunPosition, String> {
        let site = Site::new(self.latitude, self.longitude, 0.0).map_err(|e| e.to_string())?;
        let zone = Zone::parse(&self.zone).map_err(|e| e.to_string())?;
        let (utc, _) = zone
            .resolve(self.date.and_time(self.time()))
            .map_err(|e| e.to_string())?;
        crate::sun::position(&site, utc, &self.options()).map_err(|e| e.to_string())
    }

    /// Sets the local time of day.
    pub fn set_time(&mut self, time: NaiveTime) {
        self.minutes = f64::from(time.num_seconds_from_midnight()) / 60.0;
    }

    /// Advances the animated time by `dt_s` seconds (wrapping at midnight).
    pub fn advance(&mut self, dt_s: f64) {
        if self.animate {
            self.minutes = (self.minutes + dt_s * self.hours_per_second * 60.0).rem_euclid(1440.0);
        }
    }

    /// `HH:MM` of the chosen time.
    pub fn time_label(&self) -> String {
        let t = self.time();
        format!("{:02}:{:02}", t.hour(), t.minute())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vienna_summer_noon_sun_is_high_in_the_south() {
        let c = SunControls {
            minutes: 13.0 * 60.0, // 13:00 CEST ≈ solar noon
            ..SunControls::default()
        };
        let p = c.position().expect("sun position");
        // Solar noon at 48.2° N on the solstice: 90 − 48.2 + 23.44 ≈ 65.2°.
        assert!((p.elevation_deg - 65.2).abs() < 1.0, "{}", p.elevation_deg);
        assert!((p.azimuth_deg - 180.0).abs() < 10.0, "{}", p.azimuth_deg);
        let mut a = SunControls {
            animate: true,
            minutes: 23.0 * 60.0,
            hours_per_second: 2.0,
            ..SunControls::default()
        };
        a.advance(1.0);
        assert!((a.minutes - 60.0).abs() < 1e-9);
        assert_eq!(a.time_label(), "01:00");
        a.set_time(NaiveTime::from_hms_opt(14, 30, 0).unwrap());
        assert_eq!((a.minutes, a.time_label()), (870.0, "14:30".to_string()));
    }
}
