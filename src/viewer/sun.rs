//! The sun in the viewer: a site, a date and a time of day (with an animation over the
//! day), the sun's position from `crate::sun`, and the sun as a light — a distant
//! isotropic source whose intensity gives the clear-sky direct normal illuminance.

use chrono::{NaiveDate, NaiveTime, Timelike};
use glam::DVec3;

use crate::photometry::{Distribution, Eulumdat, Format, Luminaire, Symmetry};
use crate::scene::PlacedLuminaire;
use crate::sun::{Site, SunOptions, SunPosition, Zone};

/// Extraterrestrial illuminance used by the clear-sky model, lux (IES Lighting
/// Handbook: 127.5 klx).
pub const EXTRATERRESTRIAL_LUX: f64 = 127_500.0;
/// Optical extinction coefficient of a clear sky (IES Lighting Handbook).
pub const CLEAR_SKY_EXTINCTION: f64 = 0.21;
/// The sun is placed this many scene radii away: its direction varies by less than
/// 0.06° and its illuminance by less than 0.2 % over the scene.
pub const SUN_DISTANCE_RADII: f64 = 1000.0;

/// Direct normal illuminance of a clear sky with the sun at `elevation_deg`, lux:
/// E = E_xt · exp(−c · m), air mass m = 1 / sin(elevation); 0 below the horizon.
pub fn clear_sky_direct_normal_lux(elevation_deg: f64) -> f64 {
    if elevation_deg <= 0.0 {
        return 0.0;
    }
    let air_mass = 1.0 / elevation_deg.to_radians().sin();
    EXTRATERRESTRIAL_LUX * (-CLEAR_SKY_EXTINCTION * air_mass).exp()
}

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

/// An isotropic luminaire of 1000 cd at 1000 lm (what the sun light is scaled from).
fn isotropic() -> Luminaire {
    let data = Eulumdat {
        company: "goniolight".into(),
        ityp: 1,
        symmetry: Symmetry::Rotational,
        dc: 0.0,
        dg: 90.0,
        report_number: String::new(),
        luminaire_name: "sun".into(),
        luminaire_number: String::new(),
        file_name: "sun".into(),
        date_user: String::new(),
        dimensions: Default::default(),
        dff_percent: 50.0,
        lorl_percent: 100.0,
        conversion_factor: 1.0,
        tilt_deg: 0.0,
        lamp_sets: vec![crate::photometry::eulumdat::LampSet {
            count: 1,
            lamp_type: "sun".into(),
            flux_lm: 1000.0,
            color: String::new(),
            cri: String::new(),
            watts: 0.0,
        }],
        direct_ratios: [0.0; 10],
        c_angles: vec![0.0],
        gamma_angles: vec![0.0, 90.0, 180.0],
        intensities: vec![vec![1000.0; 3]],
    };
    let (distribution, warnings) = Distribution::from_eulumdat(&data);
    Luminaire {
        format: Format::Eulumdat,
        data,
        ies: None,
        distribution,
        warnings,
    }
}

/// The sun as a light for a scene centred at `center` of radius `radius` metres: an
/// isotropic source `SUN_DISTANCE_RADII` radii away toward `direction` giving
/// `normal_lux` on a surface facing it at the centre.
pub fn sun_luminaire(
    direction: DVec3,
    normal_lux: f64,
    center: DVec3,
    radius: f64,
) -> PlacedLuminaire {
    let distance = SUN_DISTANCE_RADII * radius.max(10.0);
    let mut sun = PlacedLuminaire::new(
        "sun",
        isotropic(),
        center + direction.normalize() * distance,
    );
    // 1000 cd × multiplier / d² = normal_lux.
    sun.multiplier = normal_lux * distance * distance / 1000.0;
    sun.color = DVec3::ONE;
    sun
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::Interp;

    #[test]
    fn clear_sky_model_matches_the_handbook_values() {
        // Zenith sun: 127.5 klx · e^−0.21 = 103.35 klx; 30°: air mass 2 → 83.8 klx.
        assert!((clear_sky_direct_normal_lux(90.0) - 103_350.0).abs() < 10.0);
        assert!((clear_sky_direct_normal_lux(30.0) - 83_779.0).abs() < 10.0);
        assert_eq!(clear_sky_direct_normal_lux(-1.0), 0.0);
    }

    #[test]
    fn sun_light_gives_the_normal_illuminance_at_the_centre() {
        let dir = DVec3::new(1.0, 0.5, 2.0).normalize();
        let sun = sun_luminaire(dir, 80_000.0, DVec3::new(3.0, 2.0, 0.0), 5.0);
        let to_sun = sun.position - DVec3::new(3.0, 2.0, 0.0);
        assert!((to_sun.normalize() - dir).length() < 1e-12);
        let cd = sun
            .luminaire
            .distribution
            .candela(0.0, 37.0, Interp::CatmullRom, sun.multiplier);
        let lux = cd / to_sun.length_squared();
        assert!((lux - 80_000.0).abs() < 1e-6 * 80_000.0, "{lux}");
        // The GPU texture says the same in every direction.
        for (c, g) in [(0.0, 0.0), (90.0, 45.0), (200.0, 120.0), (300.0, 180.0)] {
            let texel = sun.texture.sample(c, g, Interp::CatmullRom) * sun.candela_scale();
            assert!(
                (texel / cd - 1.0).abs() < 1e-6,
                "C{c} γ{g}: {texel} vs {cd}"
            );
        }
    }

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
    }
}
