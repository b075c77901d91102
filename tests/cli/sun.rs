//! Sun positions against pvlib's SPA (tests/data/sun/make_pvlib_cases.py) and the
//! `goniolight sun` contract.

use crate::common;

use common::{root, run_cli};
use goniolight::sun::{self, parse_time, Site, SunOptions};

#[test]
fn agrees_with_pvlib_spa_within_a_thousandth_of_a_degree() {
    let csv = std::fs::read_to_string(root().join("tests/data/sun/pvlib_cases.csv")).unwrap();
    let mut n = 0;
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let (utc, _) = parse_time(f[0], None).unwrap();
        let site = Site::new(num(1), num(2), num(3)).unwrap();
        let opts = SunOptions {
            delta_t: Some(num(6)),
            pressure_hpa: num(4),
            temperature_c: num(5),
            north_offset_deg: 0.0,
        };
        let p = sun::position(&site, utc, &opts).unwrap();
        let az_err = ((p.azimuth_deg - num(9) + 540.0) % 360.0 - 180.0).abs();
        assert!(
            (p.zenith_deg - num(7)).abs() < 1e-3,
            "{line}: zenith {}",
            p.zenith_deg
        );
        assert!(
            (p.apparent_zenith_deg - num(8)).abs() < 1e-3,
            "{line}: apparent {}",
            p.apparent_zenith_deg
        );
        assert!(az_err < 1e-3, "{line}: azimuth {}", p.azimuth_deg);
        n += 1;
    }
    assert!(n >= 20, "{n} cases");
}

#[test]
fn cli_json_contract_and_spa_example() {
    let (code, out, err) = run_cli(
        &[
            "sun",
            "--lat",
            "39.742476",
            "--lon",
            "-105.1786",
            "--time",
            "2003-10-17T12:30:30-07:00",
            "--elevation",
            "1830.14",
            "--pressure",
            "820",
            "--temperature",
            "11",
            "--delta-t",
            "67",
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for k in [
        "utc",
        "zenith_deg",
        "apparent_zenith_deg",
        "elevation_deg",
        "azimuth_deg",
        "direction",
    ] {
        assert!(v.get(k).is_some(), "{k}");
    }
    assert_eq!(v["utc"], "2003-10-17T19:30:30.000Z");
    assert!((v["apparent_zenith_deg"].as_f64().unwrap() - 50.11162).abs() < 1e-4);
    assert!((v["azimuth_deg"].as_f64().unwrap() - 194.34024).abs() < 1e-4);
    let d: Vec<f64> = v["direction"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let el = v["elevation_deg"].as_f64().unwrap().to_radians();
    assert!((d[2] - el.sin()).abs() < 1e-12);
    // Azimuth 194° is a little west of south: x < 0, y < 0.
    assert!(d[0] < 0.0 && d[1] < 0.0);
}

#[test]
fn local_time_with_a_zone_across_daylight_saving() {
    let at = |time: &str| {
        let (code, out, err) = run_cli(
            &[
                "sun",
                "--lat",
                "48.21",
                "--lon",
                "16.37",
                "--time",
                time,
                "--tz",
                "Europe/Vienna",
                "--json",
            ],
            "",
        );
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        v["utc"].as_str().unwrap().to_string()
    };
    assert_eq!(at("2026-03-29T01:30"), "2026-03-29T00:30:00.000Z");
    assert_eq!(at("2026-03-29T03:30"), "2026-03-29T01:30:00.000Z");
    assert_eq!(at("2026-07-01T12:00"), "2026-07-01T10:00:00.000Z");
    assert_eq!(at("2026-12-01T12:00"), "2026-12-01T11:00:00.000Z");
}

#[test]
fn bad_input_exits_2() {
    // Each refusal names the flag (the library names its field: `latitude`, `zone`, …).
    let time = |t: &'static str| vec!["sun", "--lat", "40", "--lon", "0", "--time", t];
    let with = |mut args: Vec<&'static str>, more: &[&'static str]| {
        args.extend_from_slice(more);
        args
    };
    for (args, said) in [
        (
            vec![
                "sun",
                "--lat",
                "95",
                "--lon",
                "0",
                "--time",
                "2026-06-21T12:00:00Z",
            ],
            "--lat 95 is outside [-90, 90]",
        ),
        (time("noon"), "--time \"noon\" cannot be read"),
        (
            time("2026-06-21T12:00"),
            "--time \"2026-06-21T12:00\" has no UTC offset: add one (e.g. +02:00) or give --tz",
        ),
        (
            with(time("2026-03-29T02:30"), &["--tz", "Europe/Vienna"]),
            "--time 2026-03-29 02:30:00 does not exist in",
        ),
        (
            with(time("2026-06-21T12:00"), &["--tz", "Nowhere/City"]),
            "--tz \"Nowhere/City\" is not a time zone",
        ),
        (
            with(time("2026-06-21T12:00:00Z"), &["--pressure=-3"]),
            "--pressure/--temperature -3/12 is not an atmosphere",
        ),
        (
            vec![
                "sun",
                "--lat",
                "nan",
                "--lon",
                "0",
                "--time",
                "2026-06-21T12:00:00Z",
            ],
            "--lat NaN is outside",
        ),
    ] {
        let (code, out, err) = run_cli(&args, "");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            out.is_empty() && err.starts_with("error:"),
            "{args:?}: {err}"
        );
        assert!(err.contains(said), "{args:?}: {err}");
    }
}

#[test]
fn sunrise_transit_sunset_and_day_path() {
    let site = Site::new(48.21, 16.37, 0.0).unwrap();
    let zone = sun::Zone::parse("Europe/Vienna").unwrap();
    let date = chrono::NaiveDate::from_ymd_opt(2026, 6, 21).unwrap();
    let ev = sun::day_events(&site, date, &zone, &SunOptions::default()).unwrap();
    assert_eq!(
        (ev.sunrise.len(), ev.transit.len(), ev.sunset.len()),
        (1, 1, 1)
    );
    // Vienna at the solstice: sunrise ≈ 04:53 CEST (02:53 UTC), sunset ≈ 21:00 CEST.
    let minutes = |t: chrono::DateTime<chrono::Utc>| {
        use chrono::Timelike;
        t.hour() as i64 * 60 + t.minute() as i64
    };
    assert!(
        (minutes(ev.sunrise[0]) - (2 * 60 + 53)).abs() <= 3,
        "{:?}",
        ev.sunrise
    );
    assert!(
        (minutes(ev.sunset[0]) - (19 * 60)).abs() <= 3,
        "{:?}",
        ev.sunset
    );
    // At transit the sun is due south and at its highest on the day's path.
    let p = sun::position(&site, ev.transit[0], &SunOptions::default()).unwrap();
    assert!((p.azimuth_deg - 180.0).abs() < 0.05, "{}", p.azimuth_deg);
    let start = ev.sunrise[0];
    let path = sun::path(
        &site,
        start,
        ev.sunset[0],
        chrono::Duration::minutes(10),
        &SunOptions::default(),
    )
    .unwrap();
    let highest = path
        .iter()
        .map(|q| q.elevation_deg)
        .fold(f64::MIN, f64::max);
    assert!(highest <= p.elevation_deg + 1e-6);
    assert!(
        (p.elevation_deg - (90.0 - 48.21 + 23.44)).abs() < 0.1,
        "{}",
        p.elevation_deg
    );
}
