//! `goniolight sun`: the sun's position for a site and an instant.

use clap::Args;

use super::error::CliError;
use crate::sun::{self, parse_time, Site, SunOptions, Zone};

/// Options of `sun`.
#[derive(Debug, Args)]
pub struct SunArgs {
    /// Latitude, degrees north.
    #[arg(long, allow_hyphen_values = true)]
    pub lat: f64,
    /// Longitude, degrees east.
    #[arg(long, allow_hyphen_values = true)]
    pub lon: f64,
    /// ISO 8601 with an offset, or local time without one when --tz is given.
    #[arg(long)]
    pub time: String,
    /// Time zone: an IANA name (Europe/Vienna) or an offset (+02:00).
    #[arg(long)]
    pub tz: Option<String>,
    /// Site elevation above sea level, metres.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub elevation: f64,
    /// ΔT = TT − UT1 in seconds (default: an estimate for the date).
    #[arg(long, allow_hyphen_values = true)]
    pub delta_t: Option<f64>,
    /// Air pressure for refraction, hPa.
    #[arg(long, default_value_t = 1013.25)]
    pub pressure: f64,
    /// Air temperature for refraction, °C.
    #[arg(long, default_value_t = 12.0, allow_hyphen_values = true)]
    pub temperature: f64,
    /// Angle from the model's +Y axis clockwise (seen from above) to true north, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub north_offset: f64,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `sun`.
pub fn run(a: SunArgs) -> Result<(), CliError> {
    let site = Site::new(a.lat, a.lon, a.elevation)?;
    let zone = a.tz.as_deref().map(Zone::parse).transpose()?;
    let (utc, repeated) = parse_time(&a.time, zone.as_ref())?;
    if repeated {
        eprintln!(
            "warning: {} occurs twice (daylight saving ends): the first is used",
            a.time
        );
    }
    let opts = SunOptions {
        delta_t: a.delta_t,
        pressure_hpa: a.pressure,
        temperature_c: a.temperature,
        north_offset_deg: a.north_offset,
    };
    let p = sun::position(&site, utc, &opts)?;
    if a.json {
        let v = p.to_json();
        println!("{v}");
    } else {
        println!(
            "utc              {}",
            p.utc.to_rfc3339_opts(chrono::SecondsFormat::Secs, true)
        );
        println!(
            "azimuth          {:.5}° (clockwise from north)",
            p.azimuth_deg
        );
        println!("elevation        {:.5}° (apparent)", p.elevation_deg);
        println!(
            "zenith           {:.5}° topocentric, {:.5}° apparent",
            p.zenith_deg, p.apparent_zenith_deg
        );
        println!(
            "direction        [{:.6}, {:.6}, {:.6}] toward the sun (x east, y north, z up)",
            p.direction[0], p.direction[1], p.direction[2]
        );
        println!("ΔT               {:.1} s", p.delta_t_s);
        if let Some(z) = &zone {
            let local = p.utc.date_naive();
            if let Ok(ev) = sun::day_events(&site, local, z, &opts) {
                // Local time in the zone, to the second, with its offset.
                let fmt = |v: &[chrono::DateTime<chrono::Utc>]| {
                    v.iter()
                        .map(|t| local_time(z, *t))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                println!("sunrise          {}", fmt(&ev.sunrise));
                println!("transit          {}", fmt(&ev.transit));
                println!("sunset           {}", fmt(&ev.sunset));
            }
        }
    }
    Ok(())
}

/// `t` in `zone`'s local time to the second, with the offset in force
/// (`2026-03-21T06:02:41+01:00`).
pub fn local_time(zone: &Zone, t: chrono::DateTime<chrono::Utc>) -> String {
    match chrono::FixedOffset::east_opt(zone.offset_seconds(t)) {
        Some(off) => t
            .with_timezone(&off)
            .to_rfc3339_opts(chrono::SecondsFormat::Secs, false),
        None => t.to_rfc3339_opts(chrono::SecondsFormat::Secs, true),
    }
}
