//! Sun studies (lavapipe in CI): hours of sun integrated over the period (open ground gets
//! the period's length), every cell against a CPU ray cast with the same step weights, a
//! BRE 209-style garden behind a wall against the analytic passing fraction, several dates
//! on one shared extent equal to single-date runs, the numeric rasters and outlines
//! against each other, the sun-path diagram against `sun --json`, the real models (a Delft
//! city block in national-grid coordinates, high-rises without a ground plane) against a
//! CPU ray cast, and the warnings for missing `--tz` and a wrong up axis.

use crate::common;

use crate::gpu_common;

use std::path::Path;
use std::sync::atomic::AtomicBool;

use chrono::{NaiveDate, NaiveTime};
use common::{root, run_cli};
use glam::{DVec2, DVec3};
use goniolight::geometry::generate::cuboid;
use goniolight::geometry::Mesh;
use goniolight::shadow::bvh::TriangleBvh;
use goniolight::shadow::{IgnoredTriangles, Light, SilhouetteMethod};
use goniolight::study::rasters::{pass_fraction, AnalysisArea};
use goniolight::study::shadow_profile::{compute, HoursMetric, Profile, ProfileSpec, SURFACE_NONE};
use goniolight::sun::{direction_from_angles, Site, SunOptions, Zone};

fn hm(s: &str) -> NaiveTime {
    NaiveTime::parse_from_str(s, "%H:%M").unwrap()
}

#[allow(clippy::too_many_arguments)]
fn spec(
    site: (f64, f64),
    zone: &str,
    date: &str,
    from: &str,
    to: &str,
    step: u32,
    extent: f64,
    resolution: u32,
) -> ProfileSpec {
    ProfileSpec {
        site: Site::new(site.0, site.1, 0.0).unwrap(),
        zone: Zone::parse(zone).unwrap(),
        date: NaiveDate::parse_from_str(date, "%Y-%m-%d").unwrap(),
        from: hm(from),
        to: hm(to),
        step_minutes: step,
        sun: SunOptions::default(),
        extent_m: Some(extent),
        resolution,
        silhouette: SilhouetteMethod::Hextree,
        non_casters: Default::default(),
        volume_ends: Default::default(),
    }
}

fn solve(model: &Mesh, spec: &ProfileSpec) -> Option<Profile> {
    let gpu = gpu_common::gpu()?;
    Some(compute(&gpu, model, spec, |_, _| {}, &AtomicBool::new(false)).unwrap())
}

/// The steps' sun directions (toward the sun, world frame) and weights.
fn suns(p: &Profile) -> Vec<(DVec3, f64)> {
    p.steps
        .iter()
        .map(|s| {
            (
                direction_from_angles(s.azimuth_deg, s.elevation_deg, 0.0),
                s.weight_h,
            )
        })
        .collect()
}

/// Hours of sun at `point` by a CPU ray cast toward every step's sun.
fn cpu_sun_hours(bvh: &TriangleBvh, suns: &[(DVec3, f64)], point: DVec3) -> f64 {
    let none = IgnoredTriangles::default();
    suns.iter()
        .filter(|(d, _)| {
            let light = Light::new([d.x, d.y, d.z, 0.0]).unwrap();
            !bvh.in_shadow(&light, point, 1e-6, &none)
        })
        .map(|(_, w)| w)
        .sum()
}

/// A 20 × 10 × 12 m box turned 30° about the vertical.
fn box_model() -> Mesh {
    let mut m = cuboid(DVec3::new(-10.0, -5.0, 0.0), DVec3::new(10.0, 5.0, 12.0));
    let turn = glam::DMat3::from_rotation_z(30f64.to_radians());
    for p in &mut m.positions {
        *p = turn * *p;
    }
    m
}

#[test]
fn sun_hours_integrate_the_period_and_match_a_cpu_ray_cast() {
    // Vienna in June: the sun is up from 08:00 to 17:00, so open ground gets exactly 9 h
    // (ten hourly samples, the first and last standing for half an hour each).
    let s = spec(
        (48.21, 16.37),
        "Europe/Vienna",
        "2026-06-21",
        "08:00",
        "17:00",
        60,
        120.0,
        192,
    );
    let weights = s.sample_weights_h().unwrap();
    assert_eq!(weights.len(), 10);
    assert_eq!(weights.iter().sum::<f64>(), 9.0);
    assert_eq!((weights[0], weights[1], weights[9]), (0.5, 1.0, 0.5));
    let Some(p) = solve(&box_model(), &s) else {
        return;
    };
    assert_eq!((p.period_h, p.sun_up_h), (9.0, 9.0));
    let sun = p.hours(HoursMetric::Sun);
    let shadow = p.hours(HoursMetric::Shadow);
    let bvh = TriangleBvh::new(&box_model());
    let suns = suns(&p);
    let n = p.resolution;
    let (mut compared, mut equal, mut open) = (0, 0, 0);
    for py in 0..n {
        for px in 0..n {
            let k = (py * n + px) as usize;
            if p.surface[k] == SURFACE_NONE {
                continue;
            }
            // Sun and shadow share the sun-up time.
            assert!((sun[k] + shadow[k] - 9.0).abs() < 1e-5, "cell {k}");
            if p.surface[k] != goniolight::study::shadow_profile::SURFACE_GROUND {
                continue;
            }
            let c = p.pixel_center(px, py);
            let cpu = cpu_sun_hours(&bvh, &suns, DVec3::new(c.x, c.y, 0.0));
            compared += 1;
            equal += ((sun[k] as f64 - cpu).abs() < 1e-4) as usize;
            if cpu == 9.0 {
                open += 1;
                // Open ground: the period's length within one part in 1 000.
                assert!((sun[k] as f64 - 9.0).abs() <= 9e-3, "cell {k}: {}", sun[k]);
            }
        }
    }
    let fraction = equal as f64 / compared as f64;
    eprintln!("sun hours: {equal} of {compared} ground cells equal the ray cast ({open} open)");
    assert!(
        open > 10_000 && open < compared - 1_000,
        "{open} of {compared}"
    );
    assert!(fraction >= 0.999, "{fraction}");
}

#[test]
fn bre_209_garden_behind_a_wall_passes_as_the_analytic_fraction() {
    // London, 21 March: a 10 m wall, 200 m long, along the south edge of a 20 × 20 m
    // garden (x in −10..10, y in 0..20 north of the wall's face at y = 0). BRE 209: at
    // least 2 hours of sun on 21 March.
    const H: f64 = 10.0;
    let wall = cuboid(DVec3::new(-100.0, -0.3, 0.0), DVec3::new(100.0, 0.0, H));
    let s = spec(
        (51.5, -0.12),
        "Europe/London",
        "2026-03-21",
        "06:00",
        "18:00",
        10,
        44.0,
        440,
    );
    let Some(p) = solve(&wall, &s) else {
        return;
    };
    let garden = AnalysisArea {
        name: "garden".into(),
        polygons: vec![vec![vec![
            DVec2::new(-10.0, 0.0),
            DVec2::new(10.0, 0.0),
            DVec2::new(10.0, 20.0),
            DVec2::new(-10.0, 20.0),
        ]]],
    };
    let sun = p.hours(HoursMetric::Sun);
    let gpu = pass_fraction(&p, &sun, 2.0, Some(&garden)).unwrap();
    // Analytic: a point (x, y) is shaded when the ray toward the sun meets the wall's
    // face y = 0 below its top and within its length; sampled every 2 cm.
    let suns = suns(&p);
    let hours = |x: f64, y: f64| -> f64 {
        suns.iter()
            .filter(|(d, _)| {
                if d.y >= 0.0 {
                    return true; // the sun is north of the wall's line: lit
                }
                let t = -y / d.y;
                let (hit_x, hit_z) = (x + t * d.x, t * d.z);
                !(hit_z <= H && hit_x.abs() <= 100.0)
            })
            .map(|(_, w)| w)
            .sum()
    };
    let (mut inside, mut pass) = (0usize, 0usize);
    for i in 0..200 {
        let x = -10.0 + (i as f64 + 0.5) * 0.1;
        for j in 0..1000 {
            let y = (j as f64 + 0.5) * 0.02;
            inside += 1;
            pass += (hours(x, y) >= 2.0 - 1e-9) as usize;
        }
    }
    let analytic = pass as f64 / inside as f64;
    eprintln!(
        "garden passing 2 h on 21 March: GPU {:.4}, analytic {:.4}",
        gpu, analytic
    );
    assert!(analytic > 0.2 && analytic < 0.8, "{analytic}");
    assert!(
        (gpu - analytic).abs() <= 0.01 * analytic,
        "{gpu} vs {analytic}"
    );
}

/// With the GPU: a temporary folder and the study's output folder in it.
fn study_dir() -> Option<(tempfile::TempDir, std::path::PathBuf)> {
    gpu_common::gpu()?;
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    Some((tmp, out))
}

fn read(dir: &Path, f: &str) -> String {
    std::fs::read_to_string(dir.join(f))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.join(f).display()))
}

fn asc_header(text: &str) -> Vec<(String, f64)> {
    text.lines()
        .take(6)
        .map(|l| {
            let (k, v) = l.split_once(' ').unwrap();
            (k.to_string(), v.trim().parse().unwrap())
        })
        .collect()
}

fn box_args(out: &Path, extra: &[&str]) -> Vec<String> {
    study_args(&root().join("assets/models/box.obj"), out, extra)
}

/// `profile MODEL` (Z-up) in Vienna, 08:00–16:00 hourly, hours of sun, then `extra`.
fn study_args(model: &Path, out: &Path, extra: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = [
        "profile",
        model.to_str().unwrap(),
        "--up",
        "z",
        "--lat",
        "48.21",
        "--lon",
        "16.37",
        "--tz",
        "Europe/Vienna",
        "--from",
        "08:00",
        "--to",
        "16:00",
        "--step",
        "60",
        "--metric",
        "sun",
        "--out",
        out.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    v.extend(extra.iter().map(|s| s.to_string()));
    v
}

fn cli(args: &[String]) -> (String, String) {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, out, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{args:?}\n{out}{err}");
    (out, err)
}

#[test]
fn model_view_writes_the_framed_image_and_the_hours_per_pixel() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("view");
    let (stdout, stderr) = cli(&box_args(
        &out,
        &[
            "--date",
            "2026-03-21",
            "--model-view",
            "--view-size",
            "320x240",
        ],
    ));
    let exr = image::open(out.join("model.exr")).unwrap().into_rgb32f();
    assert_eq!(exr.dimensions(), (320, 240), "{stdout}{stderr}");
    // 08:00–16:00 with the sun up throughout: open ground gets the whole 8 h, the box's
    // walls turned from the morning or afternoon sun less, the sky 0.
    let hours: Vec<f32> = exr.pixels().map(|p| p.0[0]).collect();
    let max = hours.iter().copied().fold(0.0, f32::max);
    assert!((max - 8.0).abs() < 1e-4, "{max}");
    assert!(hours.iter().any(|&h| h > 0.5 && h < 7.5));
    assert!(hours.contains(&0.0));
    let png = image::open(out.join("model.png")).unwrap();
    assert!(png.width() > 320 && png.height() > 240);
}

#[test]
fn several_dates_share_one_extent_and_equal_single_date_runs() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let multi = tmp.path().join("multi");
    cli(&box_args(
        &multi,
        &[
            "--dates",
            "2026-06-21,2026-12-21",
            "--threshold",
            "4",
            "--resolution",
            "96",
        ],
    ));
    let side = |dir: &Path| {
        let h = asc_header(&read(dir, "hours.asc"));
        h[0].1 * h[4].1
    };
    let (june, december) = (multi.join("2026-06-21"), multi.join("2026-12-21"));
    assert_eq!(side(&june), side(&december));
    let shared = side(&june);
    // Alone, June's default plan is smaller (its lowest sun is higher).
    let alone = tmp.path().join("alone");
    cli(&box_args(
        &alone,
        &["--date", "2026-06-21", "--resolution", "96"],
    ));
    assert!(side(&alone) < shared * 0.9, "{} vs {shared}", side(&alone));
    // With the shared extent given, a single-date run writes the same hours.
    let single = tmp.path().join("single");
    let extent = format!("{shared}");
    cli(&box_args(
        &single,
        &[
            "--date",
            "2026-12-21",
            "--extent",
            &extent,
            "--threshold",
            "4",
            "--resolution",
            "96",
        ],
    ));
    assert_eq!(read(&single, "hours.csv"), read(&december, "hours.csv"));
    assert_eq!(read(&single, "study.json"), read(&december, "study.json"));
    // The combined table: one row per date, with the same numbers as each study.json.
    let table = read(&multi, "dates.csv");
    let rows: Vec<&str> = table.lines().collect();
    assert_eq!(
        rows[0],
        "date,metric,period_h,sun_up_h,mean_h,threshold_h,pass_fraction"
    );
    assert_eq!(rows.len(), 3);
    for (row, dir) in rows[1..].iter().zip([&june, &december]) {
        let study: serde_json::Value = serde_json::from_str(&read(dir, "study.json")).unwrap();
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[0], study["date"].as_str().unwrap());
        let fraction: f64 = cells[6].parse().unwrap();
        assert!((fraction - study["pass_fraction"].as_f64().unwrap()).abs() < 1e-6);
    }
    // Presets name their dates.
    let preset = tmp.path().join("preset");
    cli(&box_args(
        &preset,
        &[
            "--preset",
            "equinox-solstices",
            "--year",
            "2026",
            "--resolution",
            "32",
        ],
    ));
    for d in ["2026-03-21", "2026-06-21", "2026-12-21"] {
        assert!(preset.join(d).join("study.json").is_file(), "{d}");
    }
}

#[test]
fn rasters_outlines_and_study_json_agree() {
    let Some((tmp, out)) = study_dir() else {
        return;
    };
    // The 2 × 1 × 3 m box on a 30 m plan. Two analysis areas: one south-west of the box
    // (always in the sun), one the whole plan (its fraction is the plan's).
    let areas = tmp.path().join("areas.geojson");
    std::fs::write(
        &areas,
        r#"{"type": "FeatureCollection", "features": [
  {"type": "Feature", "properties": {"name": "far corner"}, "geometry": {"type": "Polygon",
   "coordinates": [[[-14, -14], [-12, -14], [-12, -12], [-14, -12], [-14, -14]]]}},
  {"type": "Feature", "properties": {"name": "everything"}, "geometry": {"type": "MultiPolygon",
   "coordinates": [[[[-500, -500], [500, -500], [500, 500], [-500, 500]]]]}}]}"#,
    )
    .unwrap();
    let areas = areas.to_str().unwrap().to_string();
    cli(&box_args(
        &out,
        &[
            "--date",
            "2026-03-21",
            "--extent",
            "30",
            "--resolution",
            "240",
            "--threshold",
            "6",
            "--areas",
            &areas,
        ],
    ));
    // study.json: the contract's keys.
    let study: serde_json::Value = serde_json::from_str(&read(&out, "study.json")).unwrap();
    assert_eq!(study["metric"], "sun");
    assert_eq!(study["threshold_h"], 6.0);
    assert_eq!(study["period_h"], 8.0);
    let fraction = study["pass_fraction"].as_f64().unwrap();
    assert!(fraction > 0.5 && fraction < 1.0, "{fraction}");
    let areas = study["areas"].as_array().unwrap();
    assert_eq!(areas[0]["name"], "far corner");
    assert_eq!(areas[0]["pass_fraction"], 1.0);
    assert_eq!(areas[1]["pass_fraction"].as_f64().unwrap(), fraction);
    // hours.asc and hours.csv hold the same cells; the header places them.
    let asc = read(&out, "hours.asc");
    let h = asc_header(&asc);
    let keys: Vec<&str> = h.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(
        keys,
        [
            "ncols",
            "nrows",
            "xllcorner",
            "yllcorner",
            "cellsize",
            "NODATA_value"
        ]
    );
    let (n, x0, y0, cell) = (h[0].1 as usize, h[2].1, h[3].1, h[4].1);
    assert_eq!((n, cell), (240, 0.125));
    let grid: Vec<Vec<f64>> = asc
        .lines()
        .skip(6)
        .map(|l| l.split(' ').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(grid.len(), n);
    let csv = read(&out, "hours.csv");
    let mut passing = (0, 0);
    for line in csv.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let col = ((v[0] - x0) / cell).floor() as usize;
        let row = n - 1 - ((v[1] - y0) / cell).floor() as usize;
        assert!((grid[row][col] - v[2]).abs() < 1e-3, "{line}");
        passing.0 += 1;
        passing.1 += (v[2] >= 6.0 - 1e-4) as usize;
    }
    assert_eq!(passing.0, n * n, "every cell sees the ground or the box");
    assert!((passing.1 as f64 / passing.0 as f64 - fraction).abs() < 1e-9);
    let exr = image::open(out.join("hours.exr")).unwrap().to_rgb32f();
    assert_eq!(exr.dimensions(), (n as u32, n as u32));
    for (row, col) in [(0, 0), (90, 90), (120, 40)] {
        let v = exr.get_pixel(col as u32, row as u32)[0] as f64;
        assert!((v - grid[row][col]).abs() < 1e-3, "{row} {col}");
    }
    // The traced shadow outlines have the area profile.csv gives each step (within the
    // corners marching squares cuts off a pixel staircase).
    let outlines: serde_json::Value =
        serde_json::from_str(&read(&out, "outlines.geojson")).unwrap();
    let features = outlines["features"].as_array().unwrap();
    assert_eq!(features[0]["properties"]["kind"], "footprint");
    let footprint = features[0]["properties"]["area_m2"].as_f64().unwrap();
    assert!(
        (footprint - 2.0).abs() < 0.05,
        "the box is 2 × 1 m: {footprint}"
    );
    let profile = read(&out, "profile.csv");
    let rows: Vec<&str> = profile.lines().skip(1).collect();
    assert_eq!(rows.len(), features.len() - 1);
    for (row, f) in rows.iter().zip(&features[1..]) {
        let cells: Vec<&str> = row.split(',').collect();
        let area: f64 = cells[3].parse().unwrap();
        let traced = polygon_area(&f["geometry"]["coordinates"]);
        assert!(
            (traced - area).abs() <= 0.03 * area,
            "{}: traced {traced} vs {area}",
            cells[0]
        );
        assert_eq!(f["properties"]["time"], cells[0]);
    }
    let svg = read(&out, "outlines.svg");
    assert_eq!(
        svg.matches("<path").count(),
        rows.len() + 1 + 1,
        "steps, footprint, scale bar"
    );
    for f in ["pass.png", "hours.png", "profile.png", "sunpath.svg"] {
        assert!(out.join(f).is_file(), "{f}");
    }
}

/// Shoelace area of GeoJSON MultiPolygon coordinates (outer rings minus holes).
fn polygon_area(coords: &serde_json::Value) -> f64 {
    let ring = |r: &serde_json::Value| {
        let p: Vec<(f64, f64)> = r
            .as_array()
            .unwrap()
            .iter()
            .map(|c| (c[0].as_f64().unwrap(), c[1].as_f64().unwrap()))
            .collect();
        (0..p.len() - 1)
            .map(|i| p[i].0 * p[i + 1].1 - p[i + 1].0 * p[i].1)
            .sum::<f64>()
            .abs()
            / 2.0
    };
    coords
        .as_array()
        .unwrap()
        .iter()
        .map(|poly| {
            let rings = poly.as_array().unwrap();
            ring(&rings[0]) - rings[1..].iter().map(ring).sum::<f64>()
        })
        .sum()
}

/// The value of attribute `name` in an SVG tag's text.
fn svg_attr(tag: &str, name: &str) -> String {
    let start = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
    tag[start..].split('"').next().unwrap().to_string()
}

/// The suns a sun-path diagram plots: (time, azimuth, elevation) read back from their
/// positions through the frame the SVG itself draws (`unproject`: the frame tag and a
/// sun's x, y to azimuth and elevation).
fn plotted_suns(
    svg: &str,
    frame_tag: &str,
    frame_id: &str,
    unproject: impl Fn(&str, f64, f64) -> (f64, f64),
) -> Vec<(String, f64, f64)> {
    let frame = svg
        .split(&format!("<{frame_tag}"))
        .find(|t| t.contains(&format!("id=\"{frame_id}\"")))
        .unwrap_or_else(|| panic!("no {frame_tag} {frame_id}"));
    svg.split("<circle")
        .filter(|t| t.contains("class=\"sun\""))
        .map(|tag| {
            let (x, y): (f64, f64) = (
                svg_attr(tag, "cx").parse().unwrap(),
                svg_attr(tag, "cy").parse().unwrap(),
            );
            let (az, el) = unproject(frame, x, y);
            (svg_attr(tag, "data-time"), az, el)
        })
        .collect()
}

#[test]
fn sun_path_diagram_plots_the_suns_that_sun_json_gives() {
    let Some((_tmp, out)) = study_dir() else {
        return;
    };
    cli(&box_args(
        &out,
        &["--date", "2026-03-21", "--resolution", "64"],
    ));
    let num = |tag: &str, name: &str| -> f64 { svg_attr(tag, name).parse().unwrap() };
    let svg = read(&out, "sunpath.svg");
    // Invert the stereographic projection: r = R tan(zenith / 2), north up, east right.
    let stereographic = plotted_suns(&svg, "circle", "horizon", |horizon, x, y| {
        let (dx, dy) = (x - num(horizon, "cx"), num(horizon, "cy") - y);
        let azimuth = dx.atan2(dy).to_degrees().rem_euclid(360.0);
        let zenith = 2.0 * (dx.hypot(dy) / num(horizon, "r")).atan().to_degrees();
        (azimuth, 90.0 - zenith)
    });
    // The cylindrical chart: azimuth 0°–360° across its frame, elevation 0°–90° up it.
    let cylindrical_svg = read(&out, "sunpath-cylindrical.svg");
    assert!(cylindrical_svg.contains(r#"data-azimuth="0-360" data-elevation="0-90""#));
    let cylindrical = plotted_suns(&cylindrical_svg, "rect", "frame", |frame, x, y| {
        let (left, top) = (num(frame, "x"), num(frame, "y"));
        let (width, height) = (num(frame, "width"), num(frame, "height"));
        (
            360.0 * (x - left) / width,
            90.0 * (top + height - y) / height,
        )
    });
    assert_eq!(stereographic.len(), 9, "08:00 … 16:00");
    assert_eq!(cylindrical.len(), 9, "08:00 … 16:00");
    for (time, azimuth, elevation) in stereographic.iter().chain(&cylindrical) {
        let (code, json, err) = run_cli(
            &[
                "sun", "--lat", "48.21", "--lon", "16.37", "--time", time, "--json",
            ],
            "",
        );
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        let (az, el) = (
            v["azimuth_deg"].as_f64().unwrap(),
            v["elevation_deg"].as_f64().unwrap(),
        );
        assert!(
            (azimuth - az).abs() < 0.01 && (elevation - el).abs() < 0.01,
            "{time}: plotted {azimuth} {elevation}, sun {az} {el}"
        );
    }
    // Both diagrams have the date arcs and hour lines.
    for svg in [&svg, &cylindrical_svg] {
        assert_eq!(
            svg.matches("class=\"date\" data-date=\"2026-06-21\"")
                .count(),
            1
        );
        assert!(svg.matches("class=\"hour\"").count() >= 12);
    }
}

#[test]
fn missing_tz_and_a_wrong_up_axis_are_warned_about() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let model = root().join("assets/models/industrial_area.obj");
    let m = model.to_str().unwrap();
    let base = |out: &str, extra: &[&str]| -> Vec<String> {
        let mut v =
            common::profile_args(m, "10:00", "14:00", "120", &["--resolution", "32", "--out"]);
        v.push(tmp.path().join(out).to_str().unwrap().to_string());
        v.extend(extra.iter().map(|s| s.to_string()));
        v
    };
    // The industrial area is Z-up: read as Y-up (the default) it stands on its side.
    let (_, err) = cli(&base("a", &[]));
    assert!(err.contains("no --tz") && err.contains("UTC"), "{err}");
    assert!(err.contains("pass --up z"), "{err}");
    let (_, err) = cli(&base("b", &["--up", "z", "--tz", "Europe/Vienna"]));
    assert!(!err.contains("warning: "), "{err}");
    // `sun` gives the day's events in local time to the second.
    let (code, out, _) = run_cli(
        &[
            "sun",
            "--lat",
            "48.21",
            "--lon",
            "16.37",
            "--time",
            "2026-03-21T12:00",
            "--tz",
            "Europe/Vienna",
        ],
        "",
    );
    assert_eq!(code, 0);
    let sunrise = out.lines().find(|l| l.starts_with("sunrise")).unwrap();
    let value = sunrise.split_whitespace().nth(1).unwrap();
    assert!(
        value.starts_with("2026-03-21T05:5") && value.ends_with("+01:00") && value.len() == 25,
        "{sunrise}"
    );
}

#[test]
fn bad_study_options_are_refused_with_exit_2() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let bad_areas = tmp.path().join("bad.geojson");
    std::fs::write(&bad_areas, r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": {"type": "Point", "coordinates": [0, 0]}}]}"#).unwrap();
    let b = bad_areas.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![], "--date, --dates, --preset or --date-range"),
        (
            vec!["--date", "2026-03-21", "--threshold", "-1"],
            "--threshold",
        ),
        (
            vec!["--date", "2026-03-21", "--threshold", "2", "--areas", b],
            "bad.geojson",
        ),
        (vec!["--date-range", "2026-03-21..2026-03-01"], "is after"),
        (
            vec!["--date-range", "2026-01-01..2026-12-31", "--day-step", "1"],
            "at most 60",
        ),
        (
            vec!["--date", "2026-03-21", "--dates", "2026-06-21"],
            "cannot be used with",
        ),
        (
            vec!["--date", "2026-03-21", "--model-view", "--view-from", "1,2"],
            "expected three finite numbers",
        ),
        (
            vec![
                "--date",
                "2026-03-21",
                "--model-view",
                "--view-size",
                "10x900",
            ],
            "16 to",
        ),
        (
            vec!["--date", "2026-03-21", "--view-from", "1,2,3"],
            "--model-view",
        ),
        (
            vec![
                "--date",
                "2026-03-21",
                "--model-view",
                "--view-from",
                "0,0,6",
                "--view-at",
                "0,0,6",
            ],
            "different points",
        ),
    ];
    for (extra, expect) in cases {
        let args = box_args(&out, &extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, stdout, stderr) = run_cli(&args, "");
        assert_eq!(code, 2, "{extra:?}: {stdout}{stderr}");
        assert!(stderr.contains(expect), "{extra:?}: {stderr}");
        assert!(!out.exists(), "{extra:?} wrote files");
    }
}

/// A real model: its hours of sun at sampled cells against a CPU ray cast from the surface
/// seen from above (the Delft block is in the Dutch national grid: the study recentres it
/// and writes national-grid coordinates back).
fn real_model_matches_the_ray_cast(obj: &str, lat: &str, lon: &str, tz: &str, min_x: f64) {
    if gpu_common::gpu().is_none() {
        return;
    }
    let path = common::shared_dir().join("models").join(obj);
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let args: Vec<String> = [
        "profile",
        path.to_str().unwrap(),
        "--up",
        "z",
        "--lat",
        lat,
        "--lon",
        lon,
        "--tz",
        tz,
        "--date",
        "2026-03-21",
        "--from",
        "09:00",
        "--to",
        "16:00",
        "--step",
        "60",
        "--resolution",
        "384",
        "--metric",
        "sun",
        "--out",
        out.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    cli(&args);
    let asc = read(&out, "hours.asc");
    let h = asc_header(&asc);
    assert!(
        h[2].1 > min_x,
        "xllcorner {} in the file's coordinates",
        h[2].1
    );
    let mut mesh = goniolight::geometry::obj::read_obj(&path).unwrap();
    let origin = goniolight::study::model::recentre(&mut mesh);
    let bvh = TriangleBvh::new(&mesh);
    let ground = mesh.bounds().unwrap().0.z;
    let profile = read(&out, "profile.csv");
    let suns: Vec<(DVec3, f64)> = profile
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l
                .split(',')
                .skip(1)
                .map(|v| v.parse().unwrap_or(0.0))
                .collect();
            (direction_from_angles(c[0], c[1], 0.0), c[5])
        })
        .collect();
    let csv = read(&out, "hours.csv");
    let (mut compared, mut equal) = (0, 0);
    for line in csv.lines().skip(1).step_by(37) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let p = DVec2::new(v[0], v[1]) - origin;
        // The surface seen from above: the first hit of a ray down, else the ground.
        let top = DVec3::new(p.x, p.y, 1e4);
        let z = bvh
            .first_hit(top, DVec3::NEG_Z, 0.0)
            .map_or(ground, |(t, _)| top.z - t);
        let cpu = cpu_sun_hours(&bvh, &suns, DVec3::new(p.x, p.y, z + 1e-3));
        compared += 1;
        equal += ((cpu - v[2]).abs() < 1e-3) as usize;
    }
    let fraction = equal as f64 / compared as f64;
    eprintln!("{obj}: {equal} of {compared} sampled cells equal the ray cast");
    assert!(compared > 3000);
    assert!(fraction >= 0.98, "{fraction}");
}

#[test]
fn delft_city_block_in_national_grid_coordinates() {
    real_model_matches_the_ray_cast(
        "delft_3dfier/testarea.obj",
        "52.01",
        "4.36",
        "Europe/Amsterdam",
        84_000.0,
    );
}

#[test]
fn high_rises_without_a_ground_plane() {
    real_model_matches_the_ray_cast(
        "openfoam_buildings/buildings.obj",
        "48.21",
        "16.37",
        "Europe/Vienna",
        -1e9,
    );
}

/// A 20 m south facade under a 3 m deep overhang at 6 m (60 m long, so only its depth
/// matters): each facade cell's hours against the analytic shading of its centre.
#[test]
fn south_facade_under_an_overhang_matches_the_analytic_shading() {
    use goniolight::study::surfaces::{facade_hours, find_facades, Sun, SunRays};
    const DEPTH: f64 = 3.0;
    const UNDER: f64 = 6.0;
    let mut m = cuboid(DVec3::new(-10.0, 0.0, 0.0), DVec3::new(10.0, 10.0, 9.0));
    let slab = cuboid(
        DVec3::new(-30.0, -DEPTH, UNDER),
        DVec3::new(30.0, 0.0, UNDER + 0.2),
    );
    let base = m.positions.len() as u32;
    m.positions.extend(&slab.positions);
    m.triangles
        .extend(slab.triangles.iter().map(|t| t.map(|i| i + base)));
    // Vienna, 1 March (EN 17037's period), every 15 minutes of the day.
    let s = spec(
        (48.21, 16.37),
        "Europe/Vienna",
        "2026-03-01",
        "06:00",
        "18:00",
        15,
        1.0,
        16,
    );
    let (steps, _) = s.suns().unwrap();
    let suns: Vec<Sun> = steps
        .iter()
        .map(|(_, p, w)| Sun {
            direction: DVec3::from_array(p.direction),
            elevation_deg: p.elevation_deg,
            weight_h: *w,
        })
        .collect();
    let analytic = |x: f64, z: f64| -> f64 {
        suns.iter()
            .filter(|s| {
                let d = s.direction;
                if d.y >= 0.0 {
                    return false; // behind the facade
                }
                if z >= UNDER {
                    return true;
                }
                // The ray meets the overhang's underside before leaving its depth.
                let t = (UNDER - z) / d.z;
                let blocked = t * -d.y <= DEPTH && (x + t * d.x).abs() <= 30.0;
                !blocked
            })
            .map(|s| s.weight_h)
            .sum::<f64>()
    };
    let bvh = TriangleBvh::new(&m);
    let mut facades = find_facades(&m, 0.25, 1.0);
    let south = facades
        .iter()
        .position(|f| f.normal.y < -0.99 && (f.area_m2 - 180.0).abs() < 1e-6)
        .expect("the building's south facade");
    let none = IgnoredTriangles::default();
    let rays = SunRays {
        bvh: &bvh,
        suns: &suns,
        min_elevation_deg: 0.0,
        eps: 1e-4,
        non_casters: &none,
    };
    facade_hours(&rays, &mut facades);
    let f = &facades[south];
    assert_eq!(f.cells, (80, 36));
    let (mut compared, mut equal, mut shaded) = (0, 0, 0);
    for (k, h) in f.hours.iter().enumerate() {
        let p = f.cell_center(k % f.cells.0, k / f.cells.0);
        if (p.z - UNDER).abs() < 0.3 {
            continue; // where the overhang meets the wall
        }
        let want = analytic(p.x, p.z);
        compared += 1;
        shaded += (want < analytic(p.x, 8.9) - 1e-9) as usize;
        equal += ((h.unwrap() as f64 - want).abs() < 1e-4) as usize;
    }
    eprintln!("south facade: {equal} of {compared} cells equal the analytic hours ({shaded} shaded by the overhang)");
    assert!(shaded > 500, "{shaded}");
    assert!(
        equal as f64 >= 0.995 * compared as f64,
        "{equal} of {compared}"
    );
    // A window point under the overhang: the same hours, and its EN 17037 level.
    let window = DVec3::new(0.0, 0.0, 3.0);
    let hours = rays.hours_at(window, DVec3::NEG_Y);
    assert!((hours - analytic(0.0, 3.0)).abs() < 1e-9, "{hours}");
    // The facade seen from the south faces 180°.
    assert!((f.azimuth_deg(0.0) - 180.0).abs() < 1e-9);
}

#[test]
fn facades_and_window_points_are_written() {
    let Some((tmp, out)) = study_dir() else {
        return;
    };
    let points = tmp.path().join("points.toml");
    // box.obj is 2 × 1 × 3 m from the origin: one window on its south face, one on its
    // north face.
    std::fs::write(
        &points,
        "[[point]]\nname = \"south\"\nposition = [1.0, 0.0, 1.5]\nnormal = [0, -1, 0]\n\
         [[point]]\nname = \"north\"\nposition = [1.0, 1.0, 1.5]\nnormal = [0, 1, 0]\n",
    )
    .unwrap();
    let p = points.to_str().unwrap().to_string();
    cli(&box_args(
        &out,
        &[
            "--date",
            "2026-03-01",
            "--resolution",
            "64",
            "--facades",
            "--facade-cell",
            "0.25",
            "--points",
            &p,
        ],
    ));
    let study: serde_json::Value = serde_json::from_str(&read(&out, "study.json")).unwrap();
    let facades = study["facades"].as_array().unwrap();
    assert_eq!(facades.len(), 4);
    let mut faces: Vec<f64> = facades
        .iter()
        .map(|f| f["faces_deg"].as_f64().unwrap().round())
        .collect();
    faces.sort_by(f64::total_cmp);
    assert_eq!(faces, [0.0, 90.0, 180.0, 270.0]);
    for f in facades {
        assert!(out.join(f["image"].as_str().unwrap()).is_file());
    }
    // 08:00–16:00 on 1 March: the south face sees the sun all the time, the north face never.
    let south = facades
        .iter()
        .find(|f| f["faces_deg"].as_f64().unwrap().round() == 180.0)
        .unwrap();
    assert_eq!(south["min_h"], 8.0);
    let north = facades
        .iter()
        .find(|f| f["faces_deg"].as_f64().unwrap().round() == 0.0)
        .unwrap();
    assert_eq!(north["max_h"], 0.0);
    let csv = read(&out, "facades.csv");
    assert_eq!(csv.lines().next().unwrap(), "facade,faces_deg,x,y,z,hours");
    assert_eq!(
        csv.lines().count() - 1,
        2 * (8 * 12) + 2 * (4 * 12),
        "cells of 0.25 m"
    );
    let pts = study["points"].as_array().unwrap();
    assert_eq!(
        (pts[0]["name"].as_str(), pts[0]["hours"].as_f64()),
        (Some("south"), Some(8.0))
    );
    assert_eq!(pts[0]["en17037"], "high");
    assert_eq!(
        (pts[1]["hours"].as_f64(), pts[1]["en17037"].as_str()),
        (Some(0.0), Some("none"))
    );
    assert!(read(&out, "points.csv").starts_with("name,x,y,z,nx,ny,nz,hours,en17037\nsouth,"));
    // Each window's sun-path diagram with the sky the model hides from it: the south
    // window sees every step's sun (none drawn hollow), the north one none of them.
    assert!(!read(&out, "sunpath.svg").contains(r#"id="mask""#));
    for (name, hidden) in [("south", "false"), ("north", "true")] {
        let svg = read(&out, &format!("sunpath-{name}.svg"));
        assert!(
            svg.contains(r#"<g id="mask""#) && svg.contains("<polygon"),
            "{name}"
        );
        assert!(svg.contains(&format!("seen from {name}")), "{name}");
        let suns: Vec<&str> = svg
            .lines()
            .filter(|l| l.contains(r#"class="sun""#))
            .collect();
        assert_eq!(suns.len(), 9, "{name}: 08:00–16:00 hourly");
        for sun in suns {
            assert!(
                sun.contains(&format!(r#"data-hidden="{hidden}""#)),
                "{name}: {sun}"
            );
        }
    }
}

/// Two buildings in one OBJ, far enough apart that their shadows never meet: with
/// `--casters new` only the new one casts, and every cell outside the old one's footprint
/// has the hours of a study of the new building alone.
#[test]
fn only_the_chosen_components_cast_shadows() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let cube = |name: &str, x0: f64, first: usize| -> String {
        let m = cuboid(DVec3::new(x0, 0.0, 0.0), DVec3::new(x0 + 6.0, 6.0, 8.0));
        let mut s = format!("o {name}\n");
        for p in &m.positions {
            s += &format!("v {} {} {}\n", p.x, p.y, p.z);
        }
        for t in &m.triangles {
            s += &format!(
                "f {} {} {}\n",
                t[0] as usize + first,
                t[1] as usize + first,
                t[2] as usize + first
            );
        }
        s
    };
    let both = tmp.path().join("both.obj");
    std::fs::write(
        &both,
        cube("new_tower", -30.0, 1) + &cube("old_hall", 24.0, 9),
    )
    .unwrap();
    let alone = tmp.path().join("alone.obj");
    // The new building alone, plus a speck at the old one's far corner so both models
    // span the same plan.
    std::fs::write(
        &alone,
        cube("new_tower", -30.0, 1) + "o speck\nv 30 6 0\nv 29.99 6 0\nv 30 5.99 0\nf 9 10 11\n",
    )
    .unwrap();
    let run = |model: &Path, out: &str, extra: &[&str]| -> std::path::PathBuf {
        let dir = tmp.path().join(out);
        let plan = [
            "--date",
            "2026-03-21",
            "--extent",
            "90",
            "--resolution",
            "180",
        ];
        let extra: Vec<&str> = plan.iter().chain(extra).copied().collect();
        let (_, err) = cli(&study_args(model, &dir, &extra));
        assert!(!err.contains("panicked"), "{err}");
        dir
    };
    let chosen = run(&both, "chosen", &["--casters", "new*"]);
    let all = run(&both, "all", &[]);
    let single = run(&alone, "single", &[]);
    let cells = |dir: &Path| -> Vec<[f64; 3]> {
        read(dir, "hours.csv")
            .lines()
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                [v[0], v[1], v[2]]
            })
            .collect()
    };
    let (chosen, all, single) = (cells(&chosen), cells(&all), cells(&single));
    let in_old = |c: &[f64; 3]| c[0] > 23.5 && c[0] < 30.5 && c[1] > -0.5 && c[1] < 6.5;
    let (mut compared, mut differs_from_all) = (0, 0);
    for ((a, b), c) in chosen.iter().zip(&single).zip(&all) {
        assert_eq!((a[0], a[1]), (b[0], b[1]));
        if in_old(a) {
            continue;
        }
        compared += 1;
        assert!(
            (a[2] - b[2]).abs() < 1e-3,
            "{a:?} vs the new building alone {b:?}"
        );
        differs_from_all += ((a[2] - c[2]).abs() > 1e-3) as usize;
    }
    eprintln!(
        "{compared} cells compared; the old hall's shadow covered {differs_from_all} of them"
    );
    assert!(
        differs_from_all > 100,
        "the old hall's own shadow must be gone: {differs_from_all}"
    );
    // A pattern that matches nothing is refused, naming the objects.
    let args: Vec<String> = [
        "profile",
        both.to_str().unwrap(),
        "--up",
        "z",
        "--lat",
        "48",
        "--lon",
        "16",
        "--date",
        "2026-03-21",
        "--from",
        "10:00",
        "--to",
        "12:00",
        "--step",
        "60",
        "--casters",
        "nothing",
        "--out",
        tmp.path().join("x").to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (code, _, err) = run_cli(&args, "");
    assert_eq!(code, 2);
    assert!(
        err.contains("\"nothing\" matches no object") && err.contains("new_tower, old_hall"),
        "{err}"
    );
}

#[test]
fn model_coloured_by_hours_matches_a_cpu_ray_cast_per_pixel() {
    use goniolight::study::shadow_profile::{SURFACE_GROUND, SURFACE_MODEL};
    use goniolight::study::view_hours::{compute as view_hours, default_camera, pixel_ray};
    // The box and two one-sided walls (open meshes: the camera sees the front of one and
    // the back of the other), from the south-west above, Vienna at the equinox, hourly:
    // every pixel's hours of sun against a ray cast from the eye through its centre, then
    // toward each sun (the side seen gets the sun only when it faces it; the walls shadow
    // from either side, as the ray cast's triangles do).
    let mut model = box_model();
    for (centre, normal_azimuth) in [
        (DVec3::new(-22.0, -6.0, 0.0), 150.0),
        (DVec3::new(4.0, -24.0, 0.0), 330.0),
    ] {
        let n = direction_from_angles(normal_azimuth, 0.0, 0.0);
        let t = DVec3::Z.cross(n) * 4.0;
        let first = model.positions.len() as u32;
        let up = DVec3::new(0.0, 0.0, 6.0);
        model
            .positions
            .extend([centre - t, centre + t, centre + t + up, centre - t + up]);
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| first + i);
        let quad = if (t * 2.0).cross(up).dot(n) > 0.0 {
            [[a, b, c], [a, c, d]]
        } else {
            [[a, c, b], [a, d, c]]
        };
        model.triangles.extend(quad);
    }
    let s = spec(
        (48.21, 16.37),
        "Europe/Vienna",
        "2026-03-21",
        "08:00",
        "16:00",
        60,
        120.0,
        64,
    );
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let camera = default_camera(&model, 0.0).unwrap();
    let size = (240, 180);
    let geometry = goniolight::study::shadow_profile::prepare(&gpu, &model).unwrap();
    let v = view_hours(
        &gpu,
        &geometry,
        &s,
        &camera,
        size,
        |_, _| {},
        &AtomicBool::new(false),
    )
    .unwrap();
    assert_eq!((v.width, v.height, v.period_h), (240, 180, 8.0));
    let (sun_positions, _) = s.suns().unwrap();
    let suns: Vec<(DVec3, f64)> = sun_positions
        .iter()
        .map(|(_, p, w)| (DVec3::from(p.direction), *w))
        .collect();
    let bvh = TriangleBvh::new(&model);
    let normal = |t: usize| {
        let [a, b, c] = model.triangles[t].map(|i| model.positions[i as usize]);
        (b - a).cross(c - a).normalize()
    };
    let (mut compared, mut equal, mut partial, mut turned_from_some) = (0, 0, 0, 0);
    for py in 0..size.1 {
        for px in 0..size.0 {
            let k = (py * size.0 + px) as usize;
            let (eye, dir) = pixel_ray(&camera, size, px, py);
            let model_hit = bvh.first_hit(eye, dir, 0.0);
            let ground_t = (dir.z < 0.0).then(|| -eye.z / dir.z).filter(|&t| {
                let p = eye + dir * t;
                p.x.abs() <= 60.0 && p.y.abs() <= 60.0
            });
            let (surface, point, n) = match (model_hit, ground_t) {
                (Some((t, tri)), g) if g.is_none_or(|g| t < g) => {
                    let n = normal(tri);
                    let seen_side = if n.dot(dir) < 0.0 { n } else { -n };
                    (SURFACE_MODEL, eye + dir * t, seen_side)
                }
                (_, Some(g)) => (SURFACE_GROUND, eye + dir * g, DVec3::Z),
                _ => (SURFACE_NONE, eye, DVec3::Z),
            };
            if surface != v.surface[k] || surface == SURFACE_NONE {
                continue;
            }
            let lit: Vec<(DVec3, f64)> = suns
                .iter()
                .filter(|(d, _)| n.dot(*d) > 0.0)
                .copied()
                .collect();
            let cpu = cpu_sun_hours(&bvh, &lit, point + n * 1e-4);
            compared += 1;
            equal += ((v.sun_h[k] as f64 - cpu).abs() < 1e-4) as usize;
            if surface == SURFACE_MODEL {
                partial += (cpu > 0.0 && cpu < 8.0) as usize;
                turned_from_some += (lit.len() < suns.len()) as usize;
            }
        }
    }
    let fraction = equal as f64 / compared as f64;
    eprintln!(
        "view hours: {equal} of {compared} pixels equal the ray cast \
         ({partial} model pixels partly sunlit, {turned_from_some} on faces turned from a sun)"
    );
    assert!(compared > 20_000, "{compared}");
    assert!(
        partial > 1_000 && turned_from_some > 1_000,
        "{partial} {turned_from_some}"
    );
    assert!(fraction >= 0.998, "{fraction}");
    // Sun and shadow share the sun-up time on every surface seen.
    let shadow = v.hours(HoursMetric::Shadow);
    for ((&sun, &shade), &seen) in v.sun_h.iter().zip(&shadow).zip(&v.surface) {
        if seen != SURFACE_NONE {
            assert!((sun + shade - v.sun_up_h as f32).abs() < 1e-4);
        }
    }
}
