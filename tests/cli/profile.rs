//! Sun-path shadow profiles (lavapipe in CI): a box building's shadow area against the
//! analytic value (footprint swept along the sun direction by the roof's projection),
//! hours in shadow against a CPU ray cast, and the command's files and bad input.

use crate::common;

use crate::gpu_common;

use std::sync::atomic::AtomicBool;

use chrono::{NaiveDate, NaiveTime};
use common::{root, run_cli};
use glam::DVec3;
use goniolight::geometry::generate::cuboid;
use goniolight::shadow::raycast::in_shadow;
use goniolight::shadow::{Light, SilhouetteMethod};
use goniolight::study::output::{hours_colour, hours_image, hours_scale};
use goniolight::study::shadow_profile::{
    compute, HoursMetric, Profile, ProfileSpec, VolumeEnds, SURFACE_GROUND,
};
use goniolight::sun::{direction_from_angles, Site, SunOptions, Zone};

/// A 20 × 10 × 12 m box on the ground, turned 30° about the vertical so no edge runs
/// along the pixel grid (an edge along it makes the pixel count jump by whole rows).
const BOX: (f64, f64, f64) = (20.0, 10.0, 12.0);
const TURN_DEG: f64 = 30.0;

fn box_model() -> goniolight::geometry::Mesh {
    let mut m = cuboid(
        DVec3::new(-BOX.0 / 2.0, -BOX.1 / 2.0, 0.0),
        DVec3::new(BOX.0 / 2.0, BOX.1 / 2.0, BOX.2),
    );
    let turn = glam::DMat3::from_rotation_z(TURN_DEG.to_radians());
    for p in &mut m.positions {
        *p = turn * *p;
    }
    m
}

fn spec(from: &str, to: &str, step: u32, extent: f64, resolution: u32) -> ProfileSpec {
    let hm = |s: &str| NaiveTime::parse_from_str(s, "%H:%M").unwrap();
    ProfileSpec {
        site: Site::new(48.21, 16.37, 0.0).unwrap(),
        zone: Zone::parse("Europe/Vienna").unwrap(),
        date: NaiveDate::from_ymd_opt(2026, 6, 21).unwrap(),
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

fn profile(spec: &ProfileSpec) -> Option<Profile> {
    let gpu = gpu_common::gpu()?;
    Some(compute(&gpu, &box_model(), spec, |_, _| {}, &AtomicBool::new(false)).unwrap())
}

#[test]
fn box_shadow_area_matches_the_analytic_sweep_at_every_step() {
    let Some(p) = profile(&spec("08:30", "16:30", 40, 100.0, 2048)) else {
        return;
    };
    assert!(p.steps.len() >= 10, "{} steps", p.steps.len());
    let (w, d, h) = BOX;
    let footprint = p.footprint_area_m2();
    assert!(
        (footprint - w * d).abs() <= 0.005 * w * d,
        "footprint {footprint}"
    );
    for s in &p.steps {
        assert!(!s.reaches_edge);
        // The roof's shadow is the footprint moved by −h · (dx, dy) / dz; the shadow is
        // the footprint swept along that offset: w · |oy| + d · |ox| beyond the footprint.
        // In the box's own frame (turned back by TURN_DEG).
        let world = direction_from_angles(s.azimuth_deg, s.elevation_deg, 0.0);
        let dir = glam::DMat3::from_rotation_z(-TURN_DEG.to_radians()) * world;
        let (ox, oy) = (-h * dir.x / dir.z, -h * dir.y / dir.z);
        let analytic = w * oy.abs() + d * ox.abs();
        let rel = (s.shadow_area_m2 - analytic).abs() / analytic;
        eprintln!(
            "{} az {:6.1}° el {:5.1}°: {:8.2} m² vs analytic {:8.2} m² ({:.3} %)",
            s.time.format("%H:%M"),
            s.azimuth_deg,
            s.elevation_deg,
            s.shadow_area_m2,
            analytic,
            100.0 * rel
        );
        assert!(rel <= 0.005, "{}: {rel}", s.time);
        let with = s.shadow_area_with_footprint_m2 - s.shadow_area_m2;
        assert!((with - footprint).abs() < 1e-9);
    }
}

#[test]
fn volumes_ending_at_the_ground_shadow_what_volumes_of_one_length_do() {
    // The benchmark's two ways to end the plan's volumes must give the same shadows: the
    // same pixels at every step (ending at the ground only draws less).
    let mut s = spec("07:30", "17:30", 60, 120.0, 512);
    let Some(ground) = profile(&s) else {
        return;
    };
    s.volume_ends = VolumeEnds::OneLength;
    let one_length = profile(&s).unwrap();
    assert_eq!(ground.steps.len(), one_length.steps.len());
    let n = (ground.resolution * ground.resolution) as usize;
    for (a, b) in ground.steps.iter().zip(&one_length.steps) {
        let differ = (0..n).filter(|&k| a.in_shadow(k) != b.in_shadow(k)).count();
        let shadowed = (0..n).filter(|&k| a.in_shadow(k)).count();
        assert!(shadowed > 1_000, "{}", a.time);
        eprintln!("{}: {differ} of {shadowed} shadowed pixels differ", a.time);
        assert!(differ <= 2, "{}: {differ} pixels differ", a.time);
    }
}

#[test]
fn hours_in_shadow_match_a_cpu_ray_cast() {
    let Some(p) = profile(&spec("06:00", "19:00", 60, 120.0, 192)) else {
        return;
    };
    let mesh = box_model();
    let hours = p.hours_in_shadow();
    let lights: Vec<(Light, f64)> = p
        .steps
        .iter()
        .map(|s| {
            let d = direction_from_angles(s.azimuth_deg, s.elevation_deg, 0.0);
            (Light::new([d.x, d.y, d.z, 0.0]).unwrap(), s.weight_h)
        })
        .collect();
    let n = p.resolution;
    let (mut compared, mut equal, mut shaded) = (0, 0, 0);
    for py in 0..n {
        for px in 0..n {
            let k = (py * n + px) as usize;
            if p.surface[k] != SURFACE_GROUND {
                continue;
            }
            let c = p.pixel_center(px, py);
            let point = DVec3::new(c.x, c.y, 0.0);
            let cpu: f64 = lights
                .iter()
                .filter(|(l, _)| in_shadow(&mesh, l, point, 1e-9))
                .map(|(_, w)| w)
                .sum();
            compared += 1;
            shaded += (cpu > 0.0) as usize;
            equal += ((hours[k] as f64 - cpu).abs() < 1e-4) as usize;
        }
    }
    let fraction = equal as f64 / compared as f64;
    eprintln!("hours: {equal} of {compared} ground cells equal ({shaded} ever in shadow)");
    assert!(shaded > 500);
    // Cells cut by a shadow edge may differ by one step.
    assert!(fraction >= 0.99, "{fraction}");
    // The image shows those hours on its colour scale.
    let image = hours_image(&p, HoursMetric::Shadow);
    let scale = hours_scale(&p);
    for k in (0..(n * n) as usize).step_by(97) {
        if p.surface[k] == SURFACE_GROUND {
            let px = image.get_pixel(k as u32 % n, k as u32 / n);
            assert_eq!(
                [px[0], px[1], px[2]],
                hours_colour(hours[k], scale),
                "cell {k}"
            );
        }
    }
}

#[test]
fn profile_command_writes_the_plan_hours_and_csv() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("profile");
    let model = root().join("assets/models/box.obj");
    let (code, stdout, stderr) = run_cli(
        &[
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
            "--date",
            "2026-12-21",
            "--from",
            "06:00",
            "--to",
            "18:00",
            "--step",
            "60",
            "--resolution",
            "128",
            "--step-images",
            "--out",
            out.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{stdout}{stderr}");
    // Vienna at the winter solstice: sunrise ~07:43, sunset ~16:03 local time.
    assert!(stderr.contains("below the horizon"), "{stderr}");
    assert!(
        stderr.contains("06:00 07:00") && stderr.contains("17:00 18:00"),
        "{stderr}"
    );
    let csv = std::fs::read_to_string(out.join("profile.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time,azimuth_deg,elevation_deg,shadow_area_m2,shadow_area_with_footprint_m2,reaches_edge,weight_h"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 9, "08:00 … 16:00");
    assert!(
        rows[0].starts_with("2026-12-21T08:00:00+01:00,"),
        "{}",
        rows[0]
    );
    for f in [
        "profile.png",
        "hours.png",
        "steps/0800.png",
        "steps/1600.png",
    ] {
        let img = image::open(out.join(f)).unwrap();
        assert!(img.width() >= 128, "{f}");
    }
}

#[test]
fn bad_profile_input_is_refused_with_exit_2_and_no_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p");
    let model = root().join("assets/models/box.obj");
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "# nothing\nv 0 0 0\n").unwrap();
    let base = |model: &str, from: &str, to: &str, step: &str, date: &str| -> Vec<String> {
        [
            "profile",
            model,
            "--lat",
            "48.21",
            "--lon",
            "16.37",
            "--tz",
            "Europe/Vienna",
            "--date",
            date,
            "--from",
            from,
            "--to",
            to,
            "--step",
            step,
            "--out",
            out.to_str().unwrap(),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect()
    };
    let m = model.to_str().unwrap();
    let cases = [
        (
            base(m, "21:00", "23:30", "30", "2026-06-21"),
            "below the horizon at every step",
        ),
        (base(m, "14:00", "10:00", "30", "2026-06-21"), "after --to"),
        (
            base(m, "10:00", "14:00", "0", "2026-06-21"),
            "at least 1 minute",
        ),
        (
            base(
                empty.to_str().unwrap(),
                "10:00",
                "14:00",
                "30",
                "2026-06-21",
            ),
            "empty.obj",
        ),
        (base(m, "10:00", "14:00", "30", "2026-02-30"), "--date"),
        (base(m, "10:61", "14:00", "30", "2026-06-21"), "not a time"),
    ];
    for (args, expect) in cases {
        let args: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let (code, stdout, stderr) = run_cli(&args, "");
        assert_eq!(code, 2, "{args:?}: {stdout}{stderr}");
        assert!(stderr.contains(expect), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!out.join("profile.csv").exists());
    }
}

#[test]
fn bench_profile_reports_both_methods_as_json() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let (code, stdout, stderr) = run_cli(
        &[
            "bench",
            "profile",
            "--json",
            "--floors",
            "1",
            "--resolution",
            "64",
            "--step",
            "120",
        ],
        "",
    );
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    let kinds = [
        ("brute force", "ground"),
        ("hextree", "ground"),
        ("hextree", "one length"),
    ];
    for (row, (method, ends)) in rows.iter().zip(kinds) {
        assert_eq!(
            (&row["method"], &row["volume_ends"]),
            (&method.into(), &ends.into())
        );
        assert_eq!(row["triangles"], 30000);
        assert_eq!(row["steps"], 5, "08:00 … 16:00 every 2 h");
        for key in [
            "total_s",
            "per_step_ms",
            "silhouette_ms_per_step",
            "render_ms_per_step",
        ] {
            assert!(row[key].as_f64().unwrap() > 0.0, "{key}");
        }
    }
}

#[test]
fn a_one_sided_wall_casts_its_shadow_from_either_side() {
    // A free-standing wall modelled as one quad (an open surface, common in architects'
    // files), 20 m long and 8 m high, facing north and then south: the June sun from the
    // south lights its back in the first case. Both cast the same shadow, and it is the
    // analytic one: length × height × |cos Δ| / tan e (Δ the sun's azimuth from the
    // wall's normal).
    let wall = |normal_y: f64| {
        let (l, h) = (10.0, 8.0);
        let mut m = goniolight::geometry::Mesh {
            positions: vec![
                DVec3::new(-l, 0.0, 0.0),
                DVec3::new(l, 0.0, 0.0),
                DVec3::new(l, 0.0, h),
                DVec3::new(-l, 0.0, h),
            ],
            triangles: vec![[0, 2, 1], [0, 3, 2]],
        };
        if normal_y < 0.0 {
            m.triangles = vec![[0, 1, 2], [0, 2, 3]];
        }
        // Winding (b − a) × (c − a) along normal_y.
        let [a, b, c] = m.triangles[0].map(|i| m.positions[i as usize]);
        assert!((b - a).cross(c - a).y * normal_y > 0.0);
        m
    };
    let s = spec("10:00", "14:00", 60, 60.0, 2048);
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let run = |m: &goniolight::geometry::Mesh| {
        compute(&gpu, m, &s, |_, _| {}, &AtomicBool::new(false)).unwrap()
    };
    let (north, south) = (run(&wall(1.0)), run(&wall(-1.0)));
    let n = (north.resolution * north.resolution) as usize;
    for (a, b) in north.steps.iter().zip(&south.steps) {
        let differ = (0..n).filter(|&k| a.in_shadow(k) != b.in_shadow(k)).count();
        assert!(differ <= 4, "{}: {differ} pixels differ", a.time);
        let e = a.elevation_deg.to_radians();
        let delta = (a.azimuth_deg - 180.0).to_radians();
        let analytic = 20.0 * 8.0 * delta.cos().abs() / e.tan();
        let got = a.shadow_area_m2;
        assert!(
            (got - analytic).abs() <= 0.02 * analytic,
            "{}: {got:.2} m² vs {analytic:.2} m²",
            a.time
        );
    }
}
