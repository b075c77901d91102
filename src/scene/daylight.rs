//! `[site]` and `[sky]`: where the building is and the sky and sun of one instant, as
//! daylight sources of the scene ([`crate::daylight`]).
//!
//! ```toml
//! [site]
//! latitude = 48.21           # degrees north
//! longitude = 16.37          # degrees east
//! timezone = "Europe/Vienna" # or "+01:00"; needed for a time without an offset
//! north_offset_deg = 0.0     # as `profile --north-offset`
//!
//! [sky]
//! model = "cie-overcast"     # "cie-clear", "cie:1" … "cie:15", "uniform"
//! diffuse_horizontal_lux = 10000
//! direct_horizontal_lux = 0  # the sun (or direct_normal_lux); 0 or absent: no sun
//! time = "2026-03-21T12:00"  # local time at the site (the sun's position)
//! ground_reflectance = 0.2
//! ```

use std::path::Path;

use chrono::{DateTime, Utc};
use glam::DVec3;
use serde::{Deserialize, Serialize};

use super::SceneError;
// The daylight modules by file: `crate::daylight` itself reaches back into scenes.
use crate::daylight::cie_sky::SkyDistribution;
use crate::daylight::sky::{Sky, SkyInput, SunIlluminance, DEFAULT_GROUND_REFLECTANCE};
use crate::sun::{Site, SunOptions, Zone};

/// `[site]` as written in the scene file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SiteEntry {
    /// Degrees north (−90…90).
    pub latitude: f64,
    /// Degrees east (−180…180).
    pub longitude: f64,
    /// IANA zone (`Europe/Vienna`) or fixed offset (`+01:00`) of the sky's local time.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub timezone: Option<String>,
    /// Angle from the model's +Y axis clockwise (seen from above) to true north, degrees.
    #[serde(default)]
    pub north_offset_deg: f64,
    /// Height above sea level, metres.
    #[serde(default)]
    pub elevation_m: f64,
}

/// `[sky]` as written in the scene file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SkyEntry {
    /// `cie-overcast` (the traditional CIE standard overcast sky), `cie-clear` (general
    /// sky 12), `cie:1` … `cie:15` (ISO 15469 general skies) or `uniform`.
    pub model: String,
    /// The sky's illuminance on an unobstructed horizontal plane, lux (with `weather`:
    /// the weather file's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse_horizontal_lux: Option<f64>,
    /// The sun's illuminance on the horizontal plane, lux (0 or absent: no sun).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_horizontal_lux: Option<f64>,
    /// The sun's illuminance on a plane facing it, lux (instead of `direct_horizontal_lux`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direct_normal_lux: Option<f64>,
    /// Local time at the site (the sun's position), ISO 8601.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<String>,
    /// Reflectance of the ground below the horizon (default 0.2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground_reflectance: Option<f64>,
    /// A weather file (EPW): the sky's and the sun's illuminances of the hour holding
    /// `time` (its illuminance fields; relative to the scene file's folder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weather: Option<String>,
}

/// The scene's daylight: the entries as written and the sky they describe.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneDaylight {
    /// `[site]`, if given.
    pub site: Option<SiteEntry>,
    /// `[sky]`.
    pub entry: SkyEntry,
    /// The instant of `sky.time`, UTC.
    pub instant: Option<DateTime<Utc>>,
    /// The sky and sun.
    pub sky: Sky,
}

/// The daylight of `[site]` and `[sky]` (`None` without a `[sky]`); errors name the key.
pub fn resolve(
    path: &Path,
    site: Option<&SiteEntry>,
    sky: Option<&SkyEntry>,
) -> Result<Option<SceneDaylight>, SceneError> {
    let Some(entry) = sky else {
        return Ok(None);
    };
    let err = |key: &str, message: String| SceneError::new(path, key, message);
    let distribution = SkyDistribution::parse(&entry.model).map_err(|m| err("sky.model", m))?;
    let (instant, sun_direction) = match &entry.time {
        None => (None, None),
        Some(text) => {
            let Some(site) = site else {
                return Err(err(
                    "sky.time",
                    "the sun's position needs a [site] (latitude, longitude, timezone)".into(),
                ));
            };
            let (utc, direction) = sun_at(site, text).map_err(|(k, m)| err(k, m))?;
            (Some(utc), Some(direction))
        }
    };
    let mut entry = entry.clone();
    let (diffuse_horizontal_lux, sun) = match &entry.weather {
        None => given_light(&entry).map_err(|(k, m)| err(k, m))?,
        Some(file) => {
            let file = path.parent().unwrap_or(Path::new("")).join(file);
            let light =
                weather_light(&file, &entry, instant, sun_direction).map_err(|(k, m)| err(k, m))?;
            // Saved elsewhere, the scene still finds its weather file.
            entry.weather = Some(file.to_string_lossy().into_owned());
            light
        }
    };
    let input = SkyInput {
        distribution,
        sun_direction,
        diffuse_horizontal_lux,
        sun,
        ground_reflectance: entry
            .ground_reflectance
            .unwrap_or(DEFAULT_GROUND_REFLECTANCE),
    };
    let sky = Sky::new(input).map_err(|(k, m)| {
        let hint = if sun_direction.is_none() && (k == "model" || k.starts_with("direct")) {
            " (set sky.time and [site])"
        } else {
            ""
        };
        err(&format!("sky.{k}"), format!("{m}{hint}"))
    })?;
    Ok(Some(SceneDaylight {
        site: site.cloned(),
        entry,
        instant,
        sky,
    }))
}

/// The sky's diffuse horizontal illuminance and the sun's as the entry gives them.
fn given_light(entry: &SkyEntry) -> Result<(f64, Option<SunIlluminance>), (&'static str, String)> {
    let diffuse = entry.diffuse_horizontal_lux.ok_or((
        "sky.diffuse_horizontal_lux",
        "give the sky's diffuse horizontal illuminance (lux), or a weather file and a time"
            .to_string(),
    ))?;
    let sun = match (entry.direct_horizontal_lux, entry.direct_normal_lux) {
        (Some(_), Some(_)) => {
            return Err((
                "sky.direct_normal_lux",
                "give the sun's illuminance once: direct_horizontal_lux or direct_normal_lux"
                    .into(),
            ))
        }
        (Some(h), None) => Some(SunIlluminance::Horizontal(h)),
        (None, Some(n)) => Some(SunIlluminance::Normal(n)),
        (None, None) => None,
    };
    Ok((diffuse, sun))
}

/// The sky's diffuse horizontal illuminance and the sun's direct normal illuminance of
/// the weather `file`'s hour that holds `instant` (the file's records are hours of its own
/// zone's standard time, each ending at its hour); no sun while the sun is below the
/// horizon (`sun_direction`).
fn weather_light(
    file: &Path,
    entry: &SkyEntry,
    instant: Option<DateTime<Utc>>,
    sun_direction: Option<DVec3>,
) -> Result<(f64, Option<SunIlluminance>), (&'static str, String)> {
    use chrono::{Datelike, Timelike};
    if entry.diffuse_horizontal_lux.is_some()
        || entry.direct_horizontal_lux.is_some()
        || entry.direct_normal_lux.is_some()
    {
        return Err((
            "sky.weather",
            "the weather file gives the illuminances: leave out diffuse_horizontal_lux and the \
             sun's"
                .into(),
        ));
    }
    let instant = instant.ok_or((
        "sky.time",
        "a weather file's hour needs a time (and a [site])".to_string(),
    ))?;
    let weather = crate::weather::read_epw(file).map_err(|e| ("sky.weather", e.to_string()))?;
    let offset = chrono::Duration::seconds((weather.location.time_zone_h * 3600.0).round() as i64);
    // The hour ending at or after the instant: 12:00 is in hour 12 (11:00–12:00).
    let local = instant.naive_utc() + offset - chrono::Duration::nanoseconds(1);
    let (month, day, hour) = (local.month(), local.day(), local.hour() + 1);
    let record = weather
        .hours
        .iter()
        .find(|h| (h.month, h.day, h.hour) == (month, day, hour))
        .ok_or_else(|| {
            (
                "sky.weather",
                format!(
                    "{}: no record for {month:02}-{day:02} hour {hour}",
                    file.display()
                ),
            )
        })?;
    let missing = |what: &str| {
        (
            "sky.weather",
            format!(
                "{}: {month:02}-{day:02} hour {hour} has no {what} illuminance (999999), and \
                 goniolight derives none from irradiance: give a weather file with \
                 illuminance fields (TMY3 files have them) or the sky's illuminances",
                file.display()
            ),
        )
    };
    let diffuse = record
        .diffuse_horizontal_lux
        .ok_or_else(|| missing("diffuse horizontal"))?;
    let direct = record
        .direct_normal_lux
        .ok_or_else(|| missing("direct normal"))?;
    let sun_up = sun_direction.is_some_and(|d| d.z > 0.0);
    let sun = (direct > 0.0 && sun_up).then_some(SunIlluminance::Normal(direct));
    Ok((diffuse, sun))
}

/// The site of `[site]` (checked) and its zone, if it names one; errors name the key.
pub fn site_of(site: &SiteEntry) -> Result<(Site, Option<Zone>), (&'static str, String)> {
    let where_ = Site::new(site.latitude, site.longitude, site.elevation_m).map_err(|e| {
        let key = match &e {
            crate::sun::SunError::Invalid { field, .. } => match *field {
                "latitude" => "site.latitude",
                "longitude" => "site.longitude",
                _ => "site.elevation_m",
            },
            _ => "site",
        };
        (key, e.to_string())
    })?;
    let zone = site
        .timezone
        .as_deref()
        .map(Zone::parse)
        .transpose()
        .map_err(|e| ("site.timezone", e.to_string()))?;
    if !site.north_offset_deg.is_finite() {
        return Err((
            "site.north_offset_deg",
            format!("{} is not an angle", site.north_offset_deg),
        ));
    }
    Ok((where_, zone))
}

/// The instant of `text` at `site` and the unit vector toward the sun then, in the scene's
/// frame.
fn sun_at(site: &SiteEntry, text: &str) -> Result<(DateTime<Utc>, DVec3), (&'static str, String)> {
    let (where_, zone) = site_of(site)?;
    let (utc, _) =
        crate::sun::parse_time(text, zone.as_ref()).map_err(|e| ("sky.time", e.to_string()))?;
    let options = SunOptions {
        north_offset_deg: site.north_offset_deg,
        ..SunOptions::default()
    };
    let position =
        crate::sun::position(&where_, utc, &options).map_err(|e| ("sky.time", e.to_string()))?;
    Ok((utc, DVec3::from_array(position.direction)))
}

/// Diffuse horizontal illuminance of a sky given only by its model (`--sky`), lux: the
/// usual design overcast sky.
pub const DEFAULT_DIFFUSE_LUX: f64 = 10_000.0;

impl super::Scene {
    /// The scene under another sky: `model` replaces `[sky] model` (a scene without a
    /// `[sky]` gets one of [`DEFAULT_DIFFUSE_LUX`] and no sun), `time` replaces `[sky] time`
    /// (local time at `[site]`). Errors name the key as the scene file would.
    pub fn with_sky(&self, model: Option<&str>, time: Option<&str>) -> Result<Self, SceneError> {
        if model.is_none() && time.is_none() {
            return Ok(self.clone());
        }
        let mut entry = match (&self.daylight, model) {
            (Some(d), _) => d.entry.clone(),
            (None, Some(m)) => SkyEntry {
                model: m.to_string(),
                diffuse_horizontal_lux: Some(DEFAULT_DIFFUSE_LUX),
                direct_horizontal_lux: None,
                direct_normal_lux: None,
                time: None,
                ground_reflectance: None,
                weather: None,
            },
            (None, None) => {
                return Err(SceneError::new(
                    &self.path,
                    "sky.time",
                    "a time of day needs a sky: add [sky] to the scene or give a sky model",
                ))
            }
        };
        if let Some(m) = model {
            entry.model = m.to_string();
        }
        if let Some(t) = time {
            entry.time = Some(t.to_string());
        }
        let site = self.daylight.as_ref().and_then(|d| d.site.as_ref());
        Ok(Self {
            daylight: resolve(&self.path, site, Some(&entry))?,
            ..self.clone()
        })
    }
}

impl super::Scene {
    /// The scene without its sky: the luminaires' light alone.
    pub fn without_daylight(&self) -> Self {
        Self {
            daylight: None,
            ..self.clone()
        }
    }

    /// The scene lit by its sky alone: no luminaires, no emitting surfaces.
    pub fn daylight_only(&self) -> Self {
        let mut materials = self.materials.clone();
        for m in &mut materials {
            m.emission = glam::Vec3::ZERO;
        }
        Self {
            luminaires: Vec::new(),
            materials,
            ..self.clone()
        }
    }

    /// Whether anything in the scene gives light: a luminaire, an emitting surface or a sky.
    pub fn has_light(&self) -> bool {
        self.has_electric_light() || self.daylight.is_some()
    }

    /// Whether a luminaire or an emitting surface gives light.
    pub fn has_electric_light(&self) -> bool {
        !self.luminaires.is_empty()
            || self
                .materials
                .iter()
                .any(|m| m.emission.max_element() > 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Result<super::super::Scene, SceneError> {
        super::super::Scene::from_toml(Path::new("sky.toml"), text)
    }

    const SITE: &str =
        "[site]\nlatitude = 48.21\nlongitude = 16.37\ntimezone = \"Europe/Vienna\"\n";

    /// Vienna, 2026-03-21 12:00 CET: the sun stands about 90° − 48.2° + 0.1° ≈ 42° high,
    /// a little east of south (solar noon is at 12:02); `direct_horizontal_lux` of
    /// 30 000 lx is then 30 000 / sin(elevation) at normal incidence.
    #[test]
    fn a_site_and_a_time_place_the_sun() {
        let text = format!(
            "{SITE}[sky]\nmodel = \"cie-clear\"\ndiffuse_horizontal_lux = 12000\n\
             direct_horizontal_lux = 30000\ntime = \"2026-03-21T12:00\"\n"
        );
        let s = scene(&text).unwrap();
        let d = s.daylight.as_ref().unwrap();
        let sun = d.sky.sun.unwrap();
        let elevation = sun.direction.z.asin().to_degrees();
        assert!((elevation - 41.8).abs() < 0.6, "{elevation}");
        assert!(
            sun.direction.y < 0.0 && sun.direction.x > 0.0,
            "south, a little east (+X)"
        );
        assert!((sun.normal_lux * sun.direction.z - 30_000.0).abs() < 1e-6);
        let saved = s.to_toml(Path::new("sky.toml")).unwrap();
        let again = scene(&saved).unwrap();
        assert_eq!(
            again.daylight, s.daylight,
            "[site] and [sky] survive a save"
        );
    }

    #[test]
    fn bad_skies_are_refused_by_key() {
        let cases = [
            ("[sky]\nmodel = \"cie:16\"\ndiffuse_horizontal_lux = 1\n", "sky.model"),
            ("[sky]\nmodel = \"cie:12\"\ndiffuse_horizontal_lux = 1\n", "sky.model"),
            ("[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = -1\n", "sky.diffuse_horizontal_lux"),
            (
                "[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 1\ntime = \"2026-03-21T12:00\"\n",
                "sky.time",
            ),
            (
                "[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 1\ndirect_normal_lux = 5\n",
                "sky.direct_normal_lux",
            ),
            (
                "[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 1\nweather = \"a.epw\"\n",
                "sky.weather",
            ),
            ("[sky]\nmodel = \"uniform\"\nweather = \"a.epw\"\n", "sky.time"),
            ("[sky]\nmodel = \"uniform\"\n", "sky.diffuse_horizontal_lux"),
            (
                "[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 1\nground_reflectance = 2\n",
                "sky.ground_reflectance",
            ),
        ];
        for (text, key) in cases {
            let e = scene(text).unwrap_err();
            assert!(e.to_string().contains(key), "{text}: {e}");
        }
        let night = format!(
            "{SITE}[sky]\nmodel = \"cie:7\"\ndiffuse_horizontal_lux = 1\ntime = \"2026-03-21T23:00\"\n"
        );
        let e = scene(&night).unwrap_err().to_string();
        assert!(e.contains("sky.model") && e.contains("below"), "{e}");
    }

    #[test]
    fn a_sky_given_apart_from_the_file_replaces_its_model_and_time() {
        let plain = scene("").unwrap();
        let overcast = plain.with_sky(Some("cie-overcast"), None).unwrap();
        let d = overcast.daylight.unwrap();
        assert_eq!(d.sky.diffuse_horizontal_lux, DEFAULT_DIFFUSE_LUX);
        assert!(d.sky.sun.is_none());
        assert!(plain.with_sky(None, Some("2026-01-01T12:00")).is_err());
        let sited = scene(&format!(
            "{SITE}[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 5\n"
        ))
        .unwrap();
        let clear = sited
            .with_sky(Some("cie:12"), Some("2026-06-21T13:00"))
            .unwrap();
        let d = clear.daylight.unwrap();
        assert_eq!(d.sky.distribution, SkyDistribution::CieGeneral(12));
        assert!(
            d.sky.sun_direction.unwrap().z > 0.9,
            "midsummer, 13:00 CEST in Vienna: 65°"
        );
    }
}
