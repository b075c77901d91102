//! EnergyPlus weather files (EPW): the `LOCATION` header and the hourly records after
//! `DATA PERIODS`, of which the sun and sky fields are kept (global, direct normal and
//! diffuse horizontal irradiance and illuminance). Every error names the file, the line
//! and the field.
//!
//! An EPW record's hour `h` (1 … 24) is the hour that ends at `h`:00 local standard time
//! (no daylight saving), the zone the `LOCATION` line gives; missing values are 9999
//! (irradiance) and 999999 (illuminance) and read as absent.

use std::fmt;
use std::path::{Path, PathBuf};

use chrono::{DateTime, NaiveDate, NaiveDateTime, Utc};

/// The largest weather file read, bytes (a year of hourly records is about 1.6 MB; a
/// year of one-minute records about 100 MB).
pub const MAX_EPW_BYTES: u64 = 256 * 1024 * 1024;

/// The weather file bundled with goniolight (Chicago O'Hare, NREL TMY3), relative to the
/// data root.
pub const BUNDLED_EPW: &str = "assets/weather/USA_IL_Chicago.OHare.Intl.AP.725300_TMY3.epw";

/// Where the weather was measured, from the `LOCATION` line.
#[derive(Debug, Clone, PartialEq)]
pub struct WeatherLocation {
    /// City (or the name the file gives).
    pub city: String,
    /// Country.
    pub country: String,
    /// Degrees north.
    pub latitude: f64,
    /// Degrees east.
    pub longitude: f64,
    /// The records' zone: hours east of UTC (standard time).
    pub time_zone_h: f64,
    /// Metres above sea level.
    pub elevation_m: f64,
}

/// One record: the hour that ends at `hour`:00 local standard time on `month`/`day`, and
/// its sun and sky (absent where the file marks the value missing).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeatherHour {
    /// The record's year (typical-year files mix years).
    pub year: i32,
    /// 1 … 12.
    pub month: u32,
    /// 1 … 31.
    pub day: u32,
    /// 1 … 24: the hour ending then.
    pub hour: u32,
    /// Global horizontal irradiance, W/m².
    pub global_horizontal_w: Option<f64>,
    /// Direct normal irradiance, W/m².
    pub direct_normal_w: Option<f64>,
    /// Diffuse horizontal irradiance, W/m².
    pub diffuse_horizontal_w: Option<f64>,
    /// Global horizontal illuminance, lux.
    pub global_horizontal_lux: Option<f64>,
    /// Direct normal illuminance, lux.
    pub direct_normal_lux: Option<f64>,
    /// Diffuse horizontal illuminance, lux.
    pub diffuse_horizontal_lux: Option<f64>,
}

impl WeatherHour {
    /// The middle of the record's hour, local standard time.
    pub fn local_midpoint(&self) -> NaiveDateTime {
        let date = NaiveDate::from_ymd_opt(self.year, self.month, self.day)
            .expect("dates are checked when read");
        date.and_hms_opt(0, 30, 0).expect("a valid time")
            + chrono::Duration::hours(i64::from(self.hour) - 1)
    }

    /// The middle of the record's hour, UTC, for records in a zone `time_zone_h` east of
    /// UTC.
    pub fn utc_midpoint(&self, time_zone_h: f64) -> DateTime<Utc> {
        let offset = chrono::Duration::seconds((time_zone_h * 3600.0).round() as i64);
        (self.local_midpoint() - offset).and_utc()
    }
}

/// A weather file: where, and its hourly records in the file's order.
#[derive(Debug, Clone)]
pub struct Weather {
    /// The file read.
    pub path: PathBuf,
    /// The `LOCATION` line.
    pub location: WeatherLocation,
    /// The records.
    pub hours: Vec<WeatherHour>,
}

/// What went wrong reading a weather file.
#[derive(Debug)]
pub enum WeatherError {
    /// The file could not be read.
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A line or field is not what an EPW file has there.
    Format {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// The field's name.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
}

impl fmt::Display for WeatherError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WeatherError::Io { path, source } => write!(f, "{}: {source}", path.display()),
            WeatherError::Format {
                path,
                line,
                field,
                message,
            } => write!(f, "{}:{line}: {field}: {message}", path.display()),
        }
    }
}

impl std::error::Error for WeatherError {}

/// Reads the EPW file at `path`.
pub fn read_epw(path: &Path) -> Result<Weather, WeatherError> {
    let text =
        crate::io::read_text_limited(path, MAX_EPW_BYTES).map_err(|source| WeatherError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    parse_epw(path, &text)
}

/// The fields of a record kept, by their 0-based column: global, direct normal and
/// diffuse horizontal irradiance (W/m²), then the same as illuminance (lux).
const SKY_COLUMNS: [(usize, &str, f64); 6] = [
    (13, "global horizontal radiation", 9999.0),
    (14, "direct normal radiation", 9999.0),
    (15, "diffuse horizontal radiation", 9999.0),
    (16, "global horizontal illuminance", 999_900.0),
    (17, "direct normal illuminance", 999_900.0),
    (18, "diffuse horizontal illuminance", 999_900.0),
];

/// Reads EPW text (`path` names it in errors).
pub fn parse_epw(path: &Path, text: &str) -> Result<Weather, WeatherError> {
    let err = |line: usize, field: &'static str, message: String| WeatherError::Format {
        path: path.to_path_buf(),
        line,
        field,
        message,
    };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let (n, first) = lines
        .next()
        .ok_or_else(|| err(1, "LOCATION", "the file is empty".into()))?;
    let location = parse_location(first.trim_start_matches('\u{feff}'))
        .map_err(|(field, m)| err(n, field, m))?;
    let mut in_data = false;
    let mut hours = Vec::new();
    for (n, line) in lines {
        if !in_data {
            in_data = line.starts_with("DATA PERIODS");
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        hours.push(parse_record(line).map_err(|(field, m)| err(n, field, m))?);
    }
    if !in_data {
        return Err(err(
            text.lines().count().max(1),
            "DATA PERIODS",
            "no DATA PERIODS line: the header is not an EPW file's".into(),
        ));
    }
    if hours.is_empty() {
        return Err(err(
            text.lines().count(),
            "data",
            "no hourly records".into(),
        ));
    }
    Ok(Weather {
        path: path.to_path_buf(),
        location,
        hours,
    })
}

/// A field parsed as a finite number.
fn number(fields: &[&str], k: usize, name: &'static str) -> Result<f64, (&'static str, String)> {
    let text = fields.get(k).ok_or_else(|| {
        (
            name,
            format!("missing (the line has {} fields)", fields.len()),
        )
    })?;
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            (
                name,
                format!("{:?} is not a number", crate::io::printable(text)),
            )
        })
}

/// `LOCATION,city,state,country,source,WMO,latitude,longitude,time zone,elevation`.
fn parse_location(line: &str) -> Result<WeatherLocation, (&'static str, String)> {
    let fields: Vec<&str> = line.split(',').collect();
    if fields[0].trim() != "LOCATION" {
        return Err((
            "LOCATION",
            "the first line does not start with LOCATION: not an EPW file".into(),
        ));
    }
    let latitude = number(&fields, 6, "latitude")?;
    let longitude = number(&fields, 7, "longitude")?;
    let time_zone_h = number(&fields, 8, "time zone")?;
    let elevation_m = number(&fields, 9, "elevation")?;
    if latitude.abs() > 90.0 {
        return Err(("latitude", format!("{latitude} is not within ±90°")));
    }
    if longitude.abs() > 180.0 {
        return Err(("longitude", format!("{longitude} is not within ±180°")));
    }
    if !(-12.0..=14.0).contains(&time_zone_h) {
        return Err((
            "time zone",
            format!("{time_zone_h} h is not a zone (−12 … +14)"),
        ));
    }
    let text = |k: usize| {
        fields
            .get(k)
            .map_or(String::new(), |s| s.trim().to_string())
    };
    Ok(WeatherLocation {
        city: text(1),
        country: text(3),
        latitude,
        longitude,
        time_zone_h,
        elevation_m,
    })
}

/// One hourly record.
fn parse_record(line: &str) -> Result<WeatherHour, (&'static str, String)> {
    let fields: Vec<&str> = line.split(',').collect();
    let integer = |k: usize, name: &'static str, lo: i64, hi: i64| {
        let v = number(&fields, k, name)?;
        if v.fract() != 0.0 || v < lo as f64 || v > hi as f64 {
            return Err((name, format!("{v} is not a whole number in {lo} … {hi}")));
        }
        Ok(v as i64)
    };
    let year = integer(0, "year", 1, 9999)? as i32;
    let month = integer(1, "month", 1, 12)? as u32;
    let day = integer(2, "day", 1, 31)? as u32;
    let hour = integer(3, "hour", 1, 24)? as u32;
    if NaiveDate::from_ymd_opt(year, month, day).is_none() {
        return Err(("day", format!("{year}-{month:02}-{day:02} is not a date")));
    }
    let mut sky = [None; 6];
    for (value, &(k, name, missing)) in sky.iter_mut().zip(&SKY_COLUMNS) {
        let v = number(&fields, k, name)?;
        if v >= missing {
            continue;
        }
        if v < 0.0 {
            return Err((name, format!("{v} is negative")));
        }
        *value = Some(v);
    }
    Ok(WeatherHour {
        year,
        month,
        day,
        hour,
        global_horizontal_w: sky[0],
        direct_normal_w: sky[1],
        diffuse_horizontal_w: sky[2],
        global_horizontal_lux: sky[3],
        direct_normal_lux: sky[4],
        diffuse_horizontal_lux: sky[5],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0
DESIGN CONDITIONS,0
TYPICAL/EXTREME PERIODS,0
GROUND TEMPERATURES,0
HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0
COMMENTS 1,test
COMMENTS 2,test
DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31
";

    fn record(month: u32, day: u32, hour: u32, dni: &str) -> String {
        format!(
            "1986,{month},{day},{hour},0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9*9,-3.9,-6.1,84,99600,0,0,250,300,{dni},150,32000,999999,15000,2000,210,3.6,10,10,16.1,1280,9,999999999,0,0.0570,0,88,0.000,0.0,0.0\n"
        )
    }

    #[test]
    fn reads_the_location_and_the_sky_fields() {
        let text = format!(
            "{HEADER}{}{}",
            record(3, 21, 13, "700"),
            record(3, 21, 14, "9999")
        );
        let w = parse_epw(Path::new("t.epw"), &text).unwrap();
        assert_eq!(w.location.city, "Chicago Ohare Intl Ap");
        assert_eq!(w.location.latitude, 41.98);
        assert_eq!(w.location.time_zone_h, -6.0);
        assert_eq!(w.hours.len(), 2);
        let h = w.hours[0];
        assert_eq!((h.month, h.day, h.hour), (3, 21, 13));
        assert_eq!(h.global_horizontal_w, Some(300.0));
        assert_eq!(h.direct_normal_w, Some(700.0));
        assert_eq!(h.diffuse_horizontal_w, Some(150.0));
        assert_eq!(h.global_horizontal_lux, Some(32000.0));
        assert_eq!(h.direct_normal_lux, None);
        assert_eq!(h.diffuse_horizontal_lux, Some(15000.0));
        assert_eq!(w.hours[1].direct_normal_w, None);
        // Hour 13 is 12:00–13:00 local standard time: its middle is 12:30, 18:30 UTC.
        assert_eq!(
            h.utc_midpoint(-6.0).to_rfc3339(),
            "1986-03-21T18:30:00+00:00"
        );
    }

    #[test]
    fn errors_name_the_line_and_the_field() {
        let text = format!("{HEADER}{}", record(2, 30, 1, "0"));
        let e = parse_epw(Path::new("t.epw"), &text)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "t.epw:9: day: 1986-02-30 is not a date");
        let text = format!("{HEADER}{}", record(3, 1, 25, "0"));
        let e = parse_epw(Path::new("t.epw"), &text)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("t.epw:9: hour: 25 is not a whole number"),
            "{e}"
        );
        let text = format!("{HEADER}{}", record(3, 1, 2, "x"));
        let e = parse_epw(Path::new("t.epw"), &text)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "t.epw:9: direct normal radiation: \"x\" is not a number");
        let e = parse_epw(Path::new("t.epw"), "hello\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.epw:1: LOCATION"), "{e}");
        let e = parse_epw(
            Path::new("t.epw"),
            HEADER.replace("DATA PERIODS", "DATA").as_str(),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("DATA PERIODS"), "{e}");
        let e = parse_epw(Path::new("t.epw"), HEADER)
            .unwrap_err()
            .to_string();
        assert!(e.contains("no hourly records"), "{e}");
        let short = "1986,3,1,2,0,?,1,2\n";
        let e = parse_epw(Path::new("t.epw"), &format!("{HEADER}{short}"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("t.epw:9: global horizontal radiation: missing"),
            "{e}"
        );
    }

    #[test]
    fn reads_the_bundled_weather_file() {
        let path = crate::io::data_root().join(BUNDLED_EPW);
        let w = read_epw(&path).unwrap();
        assert_eq!(w.hours.len(), 8760);
        assert!((w.location.latitude - 41.98).abs() < 0.01);
        assert_eq!(w.location.time_zone_h, -6.0);
        // The year's direct normal irradiation, kWh/m² (the figure the weather folder's
        // SOURCES.md gives for the file).
        let dni: f64 = w
            .hours
            .iter()
            .filter_map(|h| h.direct_normal_w)
            .sum::<f64>()
            / 1000.0;
        assert!((dni - 1292.0).abs() < 1.0, "{dni}");
        assert!(w.hours.iter().all(|h| h.diffuse_horizontal_lux.is_some()));
    }
}
