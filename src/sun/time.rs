//! Instants for sun computations: ISO 8601 with an offset, or local time in a zone (IANA
//! name or fixed offset), daylight saving handled.

use chrono::{DateTime, FixedOffset, LocalResult, NaiveDateTime, TimeZone, Utc};
use chrono_tz::Tz;

use super::SunError;

/// A time zone given by IANA name (`Europe/Vienna`) or fixed offset (`+02:00`, `UTC`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Zone {
    /// An IANA zone with its daylight-saving rules.
    Iana(Tz),
    /// A fixed offset from UTC.
    Fixed(FixedOffset),
}

impl Zone {
    /// Parses an IANA name or an offset like `+02:00`, `-0700`, `Z`, `UTC`.
    pub fn parse(s: &str) -> Result<Zone, SunError> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("utc") || t == "Z" {
            return Ok(Zone::Fixed(FixedOffset::east_opt(0).expect("zero offset")));
        }
        if let Ok(tz) = t.parse::<Tz>() {
            return Ok(Zone::Iana(tz));
        }
        parse_offset(t).map(Zone::Fixed).ok_or_else(|| {
            SunError::invalid(
                "zone",
                format!("{s:?}"),
                "is not a time zone: use an IANA name such as Europe/Vienna, or an offset \
                     such as +02:00",
            )
        })
    }

    /// The instant of local time `local` in this zone. A local time that daylight saving
    /// skips is an error; one it repeats takes the earlier instant (returned flag true).
    pub fn resolve(&self, local: NaiveDateTime) -> Result<(DateTime<Utc>, bool), SunError> {
        let result = match self {
            Zone::Iana(tz) => map_local(tz.from_local_datetime(&local)),
            Zone::Fixed(off) => map_local(off.from_local_datetime(&local)),
        };
        result.ok_or_else(|| {
            SunError::invalid(
                "time",
                local,
                format!("does not exist in {self:?} (skipped by daylight saving)"),
            )
        })
    }

    /// The UTC offset in force at `instant`, seconds east.
    pub fn offset_seconds(&self, instant: DateTime<Utc>) -> i32 {
        use chrono::Offset;
        match self {
            Zone::Iana(tz) => instant.with_timezone(tz).offset().fix().local_minus_utc(),
            Zone::Fixed(off) => off.local_minus_utc(),
        }
    }
}

fn map_local<T: TimeZone>(r: LocalResult<DateTime<T>>) -> Option<(DateTime<Utc>, bool)> {
    match r {
        LocalResult::Single(t) => Some((t.with_timezone(&Utc), false)),
        LocalResult::Ambiguous(a, b) => {
            let (a, b) = (a.with_timezone(&Utc), b.with_timezone(&Utc));
            Some((a.min(b), true))
        }
        LocalResult::None => None,
    }
}

fn parse_offset(s: &str) -> Option<FixedOffset> {
    let (sign, rest) = match s.as_bytes().first()? {
        b'+' => (1, &s[1..]),
        b'-' => (-1, &s[1..]),
        _ => return None,
    };
    let digits: String = rest.chars().filter(|c| *c != ':').collect();
    if !digits.chars().all(|c| c.is_ascii_digit()) || !(digits.len() == 2 || digits.len() == 4) {
        return None;
    }
    let h: i32 = digits[..2].parse().ok()?;
    let m: i32 = if digits.len() == 4 {
        digits[2..].parse().ok()?
    } else {
        0
    };
    if h > 14 || m > 59 {
        return None;
    }
    FixedOffset::east_opt(sign * (h * 3600 + m * 60))
}

/// What [`parse_time`] says of a local time given without a zone.
pub const NO_OFFSET: &str = "has no UTC offset: add one (e.g. +02:00) or give a time zone";

/// Parses TIME: ISO 8601 with an offset (`2003-10-17T12:30:30-07:00`), or, when `zone`
/// is given, local time without one (`2026-06-21T12:00`, `2026-06-21 12:00:00`).
/// Returns the instant and whether a repeated local hour was resolved to its first
/// occurrence.
pub fn parse_time(s: &str, zone: Option<&Zone>) -> Result<(DateTime<Utc>, bool), SunError> {
    let t = s.trim();
    if let Ok(dt) = DateTime::parse_from_rfc3339(t) {
        return Ok((dt.with_timezone(&Utc), false));
    }
    for fmt in [
        "%Y-%m-%dT%H:%M:%S%.f%:z",
        "%Y-%m-%d %H:%M:%S%.f%:z",
        "%Y-%m-%dT%H:%M%:z",
        "%Y-%m-%d %H:%M%:z",
    ] {
        if let Ok(dt) = DateTime::parse_from_str(t, fmt) {
            return Ok((dt.with_timezone(&Utc), false));
        }
    }
    let local = [
        "%Y-%m-%dT%H:%M:%S%.f",
        "%Y-%m-%d %H:%M:%S%.f",
        "%Y-%m-%dT%H:%M",
        "%Y-%m-%d %H:%M",
    ]
    .iter()
    .find_map(|f| NaiveDateTime::parse_from_str(t, f).ok())
    .ok_or_else(|| {
        SunError::invalid(
            "time",
            format!("{s:?}"),
            "cannot be read: expected ISO 8601 such as 2026-06-21T12:00:00+02:00",
        )
    })?;
    match zone {
        Some(z) => z.resolve(local),
        None => Err(SunError::invalid("time", format!("{s:?}"), NO_OFFSET)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn daylight_saving_boundaries_in_vienna() {
        let z = Zone::parse("Europe/Vienna").unwrap();
        // 2026-03-29: 02:00 CET jumps to 03:00 CEST.
        let (t, _) = parse_time("2026-03-29T01:59:00", Some(&z)).unwrap();
        assert_eq!(t.to_rfc3339(), "2026-03-29T00:59:00+00:00");
        let (t, _) = parse_time("2026-03-29T03:00:00", Some(&z)).unwrap();
        assert_eq!(t.to_rfc3339(), "2026-03-29T01:00:00+00:00");
        assert!(parse_time("2026-03-29T02:30:00", Some(&z)).is_err());
        // 2026-10-25: 03:00 CEST falls back to 02:00 CET; 02:30 happens twice.
        let (t, repeated) = parse_time("2026-10-25T02:30:00", Some(&z)).unwrap();
        assert!(repeated);
        assert_eq!(t.to_rfc3339(), "2026-10-25T00:30:00+00:00");
        let (t, repeated) = parse_time("2026-10-25T03:30:00", Some(&z)).unwrap();
        assert!(!repeated);
        assert_eq!(t.to_rfc3339(), "2026-10-25T02:30:00+00:00");
        assert_eq!(z.offset_seconds(t), 3600);
    }

    #[test]
    fn offsets_and_errors() {
        let (t, _) = parse_time("2003-10-17T12:30:30-07:00", None).unwrap();
        assert_eq!(t.to_rfc3339(), "2003-10-17T19:30:30+00:00");
        let z = Zone::parse("-07:00").unwrap();
        let (u, _) = parse_time("2003-10-17 12:30:30", Some(&z)).unwrap();
        assert_eq!(t, u);
        assert!(parse_time("2003-10-17 12:30:30", None).is_err());
        assert!(parse_time("yesterday", None).is_err());
        assert!(Zone::parse("Mars/Olympus").is_err());
        assert!(Zone::parse("+25:00").is_err());
    }
}
