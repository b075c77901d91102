//! `calc`: calculation surfaces, their statistics and CSVs against `illuminance` at the
//! same points, vertical and cylindrical illuminance against the point-source formula,
//! grids that are virtual, and bad grids refused by key.

use crate::common;
use crate::gpu_common;
use crate::svg_common as svg;

use std::path::Path;

use common::{calc_csv_rows, luminaire, root, run_cli};
use glam::DVec3;
use goniolight::photometry::{Interp, Luminaire};
use serde_json::Value;

pub(crate) fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A scene file in `dir` with the box room, its luminaire and `extra` TOML.
pub(crate) fn room_scene(dir: &Path, extra: &str) -> std::path::PathBuf {
    let path = dir.join("room.toml");
    let model = root().join("assets/scenes/box_room.obj");
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    std::fs::write(
        &path,
        format!(
            "[[model]]\npath = {:?}\nup = \"z\"\n\n[[luminaire]]\nfile = {:?}\nposition = [3.0, 2.0, 2.95]\n\n{extra}",
            s(&model),
            s(&lum)
        ),
    )
    .unwrap();
    path
}

fn stats_of(values: &[f64]) -> [f64; 5] {
    let em = values.iter().sum::<f64>() / values.len() as f64;
    let emin = values.iter().copied().fold(f64::MAX, f64::min);
    let emax = values.iter().copied().fold(0.0, f64::max);
    [em, emin, emax, emin / em, emin / emax]
}

fn check_against_illuminance(cpu: bool) {
    let tmp = tempfile::tempdir().unwrap();
    let scene = room_scene(
        tmp.path(),
        "[calc]\nmaintenance_factor = 0.8\n\n[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [6.0, 4.0]\nborder = 0.5\n",
    );
    let out = tmp.path().join("out");
    let report = tmp.path().join("report.html");
    let mut args = vec!["calc", s(&scene), "--out", s(&out), "--report", s(&report)];
    if cpu {
        args.push("--cpu");
    }
    let (code, stdout, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("work plane"), "{stdout}");
    let doc: Value =
        serde_json::from_slice(&std::fs::read(out.join("calc.json")).unwrap()).unwrap();
    let grid = &doc["grids"][0];
    assert_eq!(grid["name"], "work plane");
    assert_eq!(grid["maintenance_factor"], 0.8);
    let rows = calc_csv_rows(&out.join("work-plane.csv"));
    // The plan as PNG and SVG: both show the false colours (the SVG is a picture).
    assert_eq!(
        grid["plans"],
        serde_json::json!(["work-plane.png", "work-plane.svg"])
    );
    let picture = svg::render(&out.join("work-plane.svg"));
    let raster = svg::load_png(&out.join("work-plane.png"));
    assert_eq!(picture.width, raster.width);
    let coloured = |p: &svg::Picture| {
        p.rgb
            .iter()
            .filter(|c| c.iter().max().unwrap() - c.iter().min().unwrap() > 80)
            .count()
    };
    assert!(coloured(&picture) > 50_000 && coloured(&raster) > 50_000);
    // EN 12464-1 on 6 m: p = 0.2 · 5^log10 6 → 9 × 6 cells of 0.667 m; the 0.5 m border
    // leaves 7 × 4.
    assert_eq!(rows.len(), 28);
    assert_eq!(grid["points"], 28);
    // The same points through `illuminance` (exact shadows), times the maintenance factor.
    let stdin: String = rows
        .iter()
        .map(|r| format!("{} {} {} 0 0 1\n", r[0], r[1], r[2]))
        .collect();
    let mut args = vec!["illuminance", s(&scene), "--shadows", "volumes"];
    if cpu {
        args.push("--cpu");
    }
    let (code, lux, err) = run_cli(&args, &stdin);
    assert_eq!(code, 0, "{err}");
    let lux: Vec<f64> = lux
        .lines()
        .map(|l| l.parse::<f64>().unwrap() * 0.8)
        .collect();
    for (row, v) in rows.iter().zip(&lux) {
        assert!((row[3] - v).abs() < 1e-5, "{row:?} vs {v}");
    }
    let want = stats_of(&lux);
    for (key, w) in ["em", "emin", "emax", "u0", "g2"].iter().zip(want) {
        let got = grid[key].as_f64().unwrap();
        assert!((got - w).abs() <= 1e-5 * w.max(1.0), "{key}: {got} vs {w}");
    }
    // The report: self-contained, the same statistics, the plan inline and drawable.
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(
        html.starts_with("<!doctype html>") && !html.contains("src=") && !html.contains("href=")
    );
    let em = format!(
        "<td class=\"n\">{:.1}</td><td class=\"n\">{:.1}</td>",
        want[0], want[1]
    );
    assert!(html.contains(&em), "Em, Emin in the report");
    assert!(html.contains("sample_06_isym1.ldt") && html.contains("<td>0.8</td>"));
    let body = html.split("<svg").nth(1).unwrap();
    let plan = tmp.path().join("plan.svg");
    std::fs::write(
        &plan,
        format!("<svg{}</svg>", &body[..body.find("</svg>").unwrap()]),
    )
    .unwrap();
    assert!(svg::render(&plan).width > 1000);
}

#[test]
fn grid_statistics_equal_illuminance_at_the_same_points_on_the_cpu() {
    check_against_illuminance(true);
}

#[test]
fn grid_statistics_equal_illuminance_at_the_same_points_on_the_gpu() {
    if gpu_common::gpu().is_none() {
        return;
    }
    check_against_illuminance(false);
}

#[test]
fn vertical_and_cylindrical_illuminance_follow_the_point_source_formula() {
    // One luminaire 3 m up at the origin, no geometry: E_v = I cos(angle to the normal) / d²,
    // E_z = I sin θ / (π d²) (θ from the vertical), E_sc = I sin θ (1 + cos α) / (π d²).
    let tmp = tempfile::tempdir().unwrap();
    let file = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let scene = tmp.path().join("point.toml");
    let grid = |name: &str, kind: &str, normal: &str| {
        format!("[[grid]]\nname = \"{name}\"\ncorner = [0.5, -1.5]\nsize = [2.0, 3.0]\nspacing = 0.5\nheight = 1.2\nkind = \"{kind}\"\n{normal}\n")
    };
    std::fs::write(
        &scene,
        format!(
            "[[luminaire]]\nfile = {:?}\nposition = [0.0, 0.0, 3.0]\n\n{}{}{}",
            s(&file),
            grid("cyl", "cylindrical", ""),
            grid("semi", "semicylindrical", "normal = [-1.0, 0.0, 0.0]"),
            "[[grid]]\nname = \"wall\"\ncorner = [2.0, -1.0]\nsize = [2.0, 2.0]\nspacing = 0.5\nheight = 0.5\nkind = \"vertical\"\nnormal = [-1.0, 0.0, 0.0]\n",
        ),
    )
    .unwrap();
    let out = tmp.path().join("out");
    let (code, _, err) = run_cli(&["calc", s(&scene), "--out", s(&out), "--cpu"], "");
    assert_eq!(code, 0, "{err}");
    let lum = Luminaire::load(&file).unwrap();
    let source = DVec3::new(0.0, 0.0, 3.0);
    // Intensity toward `p` (luminaire unrotated: C0 along +x, γ from straight down).
    let toward = |p: DVec3| -> (f64, DVec3, f64) {
        let d = p - source;
        let gamma = (-d.z / d.length()).acos().to_degrees();
        let c = d.y.atan2(d.x).to_degrees().rem_euclid(360.0);
        let i = lum.distribution.candela(c, gamma, Interp::CatmullRom, 1.0);
        (i, -d.normalize(), d.length_squared())
    };
    let pi = std::f64::consts::PI;
    for (name, formula) in [
        (
            "cyl",
            &(|i: f64, l: DVec3, d2: f64| i * l.truncate().length() / (pi * d2))
                as &dyn Fn(f64, DVec3, f64) -> f64,
        ),
        ("semi", &|i: f64, l: DVec3, d2: f64| {
            let h = l.truncate();
            let cos_a = if h.length() > 0.0 {
                -h.x / h.length()
            } else {
                0.0
            };
            i * h.length() * (1.0 + cos_a) / (pi * d2)
        }),
        ("wall", &|i: f64, l: DVec3, d2: f64| {
            i * l.dot(DVec3::NEG_X).max(0.0) / d2
        }),
    ] {
        let rows = calc_csv_rows(&out.join(format!("{name}.csv")));
        assert!(rows.len() >= 16, "{name}: {} points", rows.len());
        for r in rows {
            let (i, l, d2) = toward(DVec3::new(r[0], r[1], r[2]));
            let want = formula(i, l, d2);
            assert!(
                (r[3] - want).abs() <= 1e-3 * want + 1e-6,
                "{name} at {r:?}: {} vs {want}",
                r[3]
            );
        }
    }
}

#[test]
fn grids_are_virtual_and_bad_grids_are_refused_by_key() {
    let tmp = tempfile::tempdir().unwrap();
    let points = "1 1 0.8 0 0 1\n3 2 0.0 0 0 1\n5 3 1.5 -1 0 0\n";
    let plain = room_scene(tmp.path(), "");
    let (_, without, _) = run_cli(
        &["illuminance", s(&plain), "--cpu", "--shadows", "volumes"],
        points,
    );
    // A grid right through the points and across the room changes nothing.
    let with_grid = room_scene(
        tmp.path(),
        "[[grid]]\nname = \"g\"\ncorner = [0.0, 0.0]\nsize = [6.0, 4.0]\nheight = 0.8\nspacing = 0.25\n",
    );
    let (code, with, err) = run_cli(
        &[
            "illuminance",
            s(&with_grid),
            "--cpu",
            "--shadows",
            "volumes",
        ],
        points,
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(with, without);
    for (extra, key) in [
        ("[[grid]]\nname = \"w\"\ncorner = [0.0, 0.0]\nsize = [2.0, 2.0]\nkind = \"vertical\"\n", "grid[0].normal"),
        ("[[grid]]\nname = \"w\"\ncorner = [0.0, 0.0]\nsize = [-2.0, 2.0]\n", "grid[0].size"),
        ("[[grid]]\nname = \"w\"\ncorner = [0.0, 0.0]\nsize = [2.0, 2.0]\nspacing = \"dense\"\n", "grid[0].spacing"),
        ("[[grid]]\nname = \"w\"\ncorner = [0.0, 0.0]\nsize = [2.0, 2.0]\n\n[[grid]]\nname = \"W\"\ncorner = [0.0, 0.0]\nsize = [2.0, 2.0]\n", "grid[1].name"),
        ("[calc]\nmaintenance_factor = 1.5\n", "calc.maintenance_factor"),
        ("[calc]\nindirect = \"some\"\n", "indirect"),
        ("[[observer]]\nname = \"o\"\nposition = [1.0, 1.0, 1.2]\ndirection = [0.0, 0.0, 1.0]\n", "observer[0].direction"),
        ("[[observer]]\nname = \"o\"\nposition = [1.0, 1.0, 1.2]\ndirection = [1.0, 0.0, 0.0]\n\n[[observer]]\nname = \" O\"\nposition = [2.0, 1.0, 1.2]\ndirection = [1.0, 0.0, 0.0]\n", "observer[1].name"),
        ("[[observer]]\nname = \"o\"\nposition = [1.0, 1.0]\ndirection = [1.0, 0.0, 0.0]\n", "position"),
    ] {
        let scene = room_scene(tmp.path(), extra);
        let out = tmp.path().join("refused");
        let (code, _, err) = run_cli(&["calc", s(&scene), "--out", s(&out), "--cpu"], "");
        assert_eq!(code, 2, "{extra}: {err}");
        assert!(err.contains("room.toml") && err.contains(key), "{key}: {err}");
        assert!(!out.join("calc.json").exists());
    }
    let plain = room_scene(tmp.path(), "");
    let (code, _, err) = run_cli(
        &[
            "calc",
            s(&plain),
            "--out",
            s(&tmp.path().join("o")),
            "--cpu",
        ],
        "",
    );
    assert_eq!(code, 2);
    assert!(err.contains("no [[grid]]"), "{err}");
}

#[test]
fn illuminance_echoes_the_points_as_csv_and_json() {
    let scene = root().join("assets/scenes/box_room.toml");
    let points = "1 1 0.8 0 0 1\n2 2 0.8 0 0 1\n";
    let (_, plain, _) = run_cli(&["illuminance", s(&scene), "--cpu"], points);
    let (code, csv, err) = run_cli(
        &["illuminance", s(&scene), "--cpu", "--format", "csv"],
        points,
    );
    assert_eq!(code, 0, "{err}");
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("x,y,z,nx,ny,nz,lux"));
    let rows: Vec<&str> = lines.collect();
    assert!(rows[0].starts_with("1,1,0.8,0,0,1,"), "{}", rows[0]);
    let values: Vec<&str> = rows.iter().map(|r| r.rsplit(',').next().unwrap()).collect();
    assert_eq!(values, plain.lines().collect::<Vec<_>>());
    let (_, json, _) = run_cli(
        &["illuminance", s(&scene), "--cpu", "--format", "json"],
        points,
    );
    let v: Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v[1]["position"], serde_json::json!([2.0, 2.0, 0.8]));
    let lux: f64 = plain.lines().nth(1).unwrap().parse().unwrap();
    assert!((v[1]["lux"].as_f64().unwrap() - lux).abs() < 1e-6);
}

#[test]
fn isolux_lines_lie_within_one_spacing_of_the_analytic_radius() {
    use goniolight::calc::grid_stats;
    use goniolight::calc::plan::Plan;
    use goniolight::scene::grid::{GridEntry, GridKind, Spacing};
    // A rotationally symmetric downlight 2 m above a 6 × 6 m plane: E(r) = I(γ) cos γ / d²
    // falls with r, so each level L is a circle of the radius where E(r) = L.
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let e = |r: f64| {
        let g = r.atan2(2.0);
        lum.distribution
            .candela(0.0, g.to_degrees(), Interp::CatmullRom, 1.0)
            * g.cos()
            / (r * r + 4.0)
    };
    let entry = GridEntry {
        name: "plane".into(),
        corner: Some([-3.0, -3.0]),
        size: Some([6.0, 6.0]),
        outline: None,
        exclude: None,
        height: 0.0,
        spacing: Spacing::Metres(0.25),
        border: 0.0,
        kind: GridKind::Horizontal,
        normal: None,
    };
    let grid = entry.resolve().unwrap();
    let values: Vec<f64> = grid
        .points
        .iter()
        .map(|p| e(p.truncate().length()))
        .collect();
    let plan = Plan {
        grid: &grid,
        values: &values,
        stats: grid_stats(&values),
        maintenance_factor: 1.0,
        luminaires: Vec::new(),
        observers: Vec::new(),
        areas: Vec::new(),
        light: vec!["direct light only".into()],
        palette: (Default::default(), 0),
        values_at_points: false,
        north_offset_deg: None,
        daylight_factor: None,
    };
    let lines = plan.isolux().unwrap();
    assert!(lines.len() >= 4, "{} levels", lines.len());
    let mut checked = 0;
    for (level, pieces) in &lines {
        // The analytic radius by bisection (E falls monotonically over the plane).
        let (mut lo, mut hi) = (0.0, 5.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if e(mid) > *level {
                lo = mid
            } else {
                hi = mid
            }
        }
        for p in pieces.iter().flatten() {
            let r = p[0].hypot(p[1]);
            if r > 2.9 {
                continue; // the lattice ends at the plane's edge
            }
            assert!((r - lo).abs() <= 0.25, "level {level}: r {r:.3} vs {lo:.3}");
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked} points checked");
    // PNG and SVG render; the SVG's statistics are the grid's.
    let svg = plan.svg().unwrap();
    assert!(
        svg.contains(&format!("Em    {:.1} lx", plan.stats.em)),
        "statistics box"
    );
    let png = plan.png().unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

/// `calc` with the interreflected light (the scene's `calc.indirect = "radiosity"`): every
/// grid value is `radiosity --points` at that point (same shadows and interpolation), the
/// observers' background luminance is the interreflected light at the eye over π, and
/// their UGR is the CIE 117 formula evaluated here from the luminaire file and the
/// geometry.
#[test]
fn total_light_and_glare_at_observers() {
    if gpu_common::gpu().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let observers = "[[observer]]\nname = \"door\"\nposition = [0.5, 2.0, 1.2]\ndirection = [1.0, 0.0, 0.0]\n\n[[observer]]\nname = \"window\"\nposition = [5.5, 2.0, 1.2]\ndirection = [1.0, 0.0, 0.0]\n";
    let grid =
        "[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [6.0, 4.0]\nspacing = 1.0\n";
    // Observers need the background luminance: refused without the interreflected light.
    let direct_only = room_scene(tmp.path(), &format!("{grid}\n{observers}"));
    let out = tmp.path().join("refused");
    let (code, _, err) = run_cli(&["calc", s(&direct_only), "--out", s(&out)], "");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--indirect radiosity"), "{err}");
    assert!(!out.exists(), "nothing written");

    // Two areas judged on UGR: one at "door" only, and the room at every observer (with
    // its walls and ceiling).
    let areas = "[[area]]\nname = \"desk\"\nkind = \"area\"\ncorner = [2.0, 1.0]\nsize = [2.0, 2.0]\nspacing = 1.0\nugr_l = 19\nobservers = [\"door\"]\n\n[[area]]\nname = \"room\"\nkind = \"room\"\ncorner = [0.0, 0.0]\nsize = [6.0, 4.0]\nspacing = 1.0\nugr_l = 10\n";
    let scene = room_scene(
        tmp.path(),
        &format!("[calc]\nindirect = \"radiosity\"\n\n{grid}\n{observers}\n{areas}"),
    );
    let out = tmp.path().join("out");
    let (code, stdout, err) = run_cli(&["calc", s(&scene), "--out", s(&out)], "");
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("observer door"), "{stdout}");
    let doc: Value =
        serde_json::from_slice(&std::fs::read(out.join("calc.json")).unwrap()).unwrap();
    assert_eq!(doc["indirect"], "radiosity");
    assert_eq!(doc["grids"][0]["indirect"], true);

    // The grid against `radiosity --points` at the same points; the eye of "door"
    // (facing its line of sight) next; then the room's first wall and its ceiling, facing
    // into the room (one solve for all).
    let rows = calc_csv_rows(&out.join("work-plane.csv"));
    assert_eq!(rows.len(), 24);
    let at = |rows: &[[f64; 4]], normal: &str| -> String {
        rows.iter()
            .map(|r| format!("{} {} {} {normal}\n", r[0], r[1], r[2]))
            .collect()
    };
    let surfaces = [
        (
            "room-wall-1",
            calc_csv_rows(&out.join("room-wall-1.csv")),
            "0 1 0",
        ),
        (
            "room-ceiling",
            calc_csv_rows(&out.join("room-ceiling.csv")),
            "0 0 -1",
        ),
    ];
    let mut stdin = at(&rows, "0 0 1");
    stdin.push_str("0.5 2.0 1.2 1 0 0\n");
    for (_, surface, normal) in &surfaces {
        stdin.push_str(&at(surface, normal));
    }
    let (code, total, err) = run_cli(
        &["radiosity", s(&scene), "--points", "--shadows", "volumes"],
        &stdin,
    );
    assert_eq!(code, 0, "{err}");
    let total: Vec<f64> = total.lines().map(|l| l.parse().unwrap()).collect();
    // The solver adds on the GPU with atomics, so the order of additions (and the last
    // bits) may differ between two solves.
    for (row, t) in rows.iter().zip(&total) {
        assert!((row[3] - t).abs() <= 1e-4 * t.max(1.0), "{row:?} vs {t}");
    }
    let (code, direct, err) = run_cli(&["illuminance", s(&scene), "--shadows", "volumes"], &stdin);
    assert_eq!(code, 0, "{err}");
    let direct: Vec<f64> = direct.lines().map(|l| l.parse().unwrap()).collect();
    for (d, t) in direct.iter().zip(&total) {
        assert!(t > d, "interreflected light adds to the direct: {t} vs {d}");
    }
    let pi = std::f64::consts::PI;
    let lb_want = (total[24] - direct[24]) / pi;
    let door = &doc["observers"][0];
    let lb = door["background_cd_m2"].as_f64().unwrap();
    assert!(
        (lb - lb_want).abs() <= 1e-3 * lb_want,
        "L_b {lb} vs {lb_want}"
    );

    // CIE 117 by hand: the downlight (Ø 450 mm, luminous sides 95 mm) 2.5 m ahead of and
    // 1.75 m above the eye, straight on (T = 0).
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let (t, h, r): (f64, f64, f64) = (0.0, 2.95 - 1.2, 2.5);
    let gamma = r.atan2(h).to_degrees();
    let cd = lum
        .distribution
        .candela(180.0, gamma, Interp::CatmullRom, 1.0);
    let (radius, side) = (0.225, 0.095);
    let a_p = pi * radius * radius * gamma.to_radians().cos()
        + 2.0 * radius * side * gamma.to_radians().sin();
    let l = cd / a_p;
    let omega = a_p / (t * t + h * h + r * r);
    let beta = h.atan2(r).to_degrees();
    let p = ((35.2 - 1.22) * 1e-3 * beta + 21e-5 * beta * beta).exp();
    let ugr = 8.0 * (0.25 / lb * l * l * omega / (p * p)).log10();
    let got = door["ugr"].as_f64().unwrap();
    assert!((got - ugr).abs() < 0.05, "UGR {got} vs {ugr} by hand");
    // The room's walls and ceiling: their values are `radiosity --points` at their points
    // facing into the room, and their verdicts judge their statistics.
    let mut next = 25;
    for (name, surface, _) in &surfaces {
        for (row, l) in surface.iter().zip(&total[next..]) {
            assert!(
                (row[3] - l).abs() <= 1e-4 * l.max(1.0),
                "{name}: {row:?} vs {l}"
            );
        }
        next += surface.len();
    }
    assert_eq!(next, total.len());
    let wall = doc["grids"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["name"] == "room wall 1")
        .unwrap();
    assert_eq!(wall["kind"], "vertical");
    let verdicts = doc["requirements"].as_array().unwrap();
    let wall_em = verdicts
        .iter()
        .find(|v| v["grid"] == "room wall 1" && v["quantity"] == "Em")
        .unwrap();
    assert_eq!(wall_em["required"], 50.0);
    assert_eq!(wall_em["achieved"], wall["em"]);
    assert_eq!(wall_em["pass"], wall["em"].as_f64().unwrap() >= 50.0);
    // UGR, 4 walls and the ceiling (Em and U0 each) of the room; UGR of the desk.
    assert_eq!(verdicts.len(), 1 + 1 + 2 * 5);
    // The areas' UGR_L: the highest UGR of their observers ("window" sees nothing).
    for (k, limit) in [(0, 19.0), (1, 10.0)] {
        let v = &doc["requirements"][k];
        assert_eq!(v["quantity"], "UGR");
        assert_eq!(v["achieved"].as_f64().unwrap(), got, "{v}");
        assert_eq!(v["required"].as_f64().unwrap(), limit);
        assert_eq!(v["pass"].as_bool().unwrap(), got <= limit, "{v}");
    }
    assert_eq!(door["luminaires"].as_array().unwrap().len(), 1);
    // UGR is rated on the initial light: a maintenance factor changes the lux, not UGR.
    let maintained = tmp.path().join("maintained");
    let (code, _, err) = run_cli(
        &[
            "calc",
            s(&scene),
            "--out",
            s(&maintained),
            "--maintenance-factor",
            "0.5",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let again: Value =
        serde_json::from_slice(&std::fs::read(maintained.join("calc.json")).unwrap()).unwrap();
    let ugr_again = again["observers"][0]["ugr"].as_f64().unwrap();
    assert!(
        (ugr_again - got).abs() < 0.01,
        "UGR {ugr_again} with MF 0.5 vs {got}"
    );
    let em = |d: &Value| d["grids"][0]["em"].as_f64().unwrap();
    assert!((em(&again) / em(&doc) - 0.5).abs() < 1e-3);
    // The other observer has the luminaire behind the eye: nothing glares.
    let window = &doc["observers"][1];
    assert!(window["ugr"].is_null(), "{window}");
    assert_eq!(window["luminaires"].as_array().unwrap().len(), 0);
}

/// The report in a real browser: headless Chromium (installed by the test command)
/// renders it to a PNG with the statistics table and the plan in false colour on it.
/// The picture is kept as `target/tmp/calc-report-chromium.png` to look at.
#[test]
fn report_opens_in_a_real_browser() {
    if std::env::var("GONIOLIGHT_SKIP_BROWSER_TESTS").as_deref() == Ok("1") {
        eprintln!("browser test skipped: GONIOLIGHT_SKIP_BROWSER_TESTS=1");
        return;
    }
    let chromium = ["chromium", "chromium-browser"]
        .into_iter()
        .find(|c| {
            std::process::Command::new(c)
                .arg("--version")
                .output()
                .is_ok_and(|o| o.status.success())
        })
        .expect("the report test needs Chromium: scripts/install-deps.sh installs it (apt-get install chromium), or set GONIOLIGHT_SKIP_BROWSER_TESTS=1 to skip");
    let tmp = tempfile::tempdir().unwrap();
    let scene = room_scene(
        tmp.path(),
        "[[grid]]\nname = \"work plane\"\ncorner = [0.0, 0.0]\nsize = [6.0, 4.0]\nspacing = 0.25\n",
    );
    let out = tmp.path().join("out");
    let report = tmp.path().join("report.html");
    let (code, _, err) = run_cli(
        &[
            "calc",
            s(&scene),
            "--out",
            s(&out),
            "--cpu",
            "--report",
            s(&report),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let shot = tmp.path().join("shot.png");
    let run = std::process::Command::new(chromium)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--window-size=1280,1600",
        ])
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", report.display()))
        .output()
        .unwrap();
    assert!(
        shot.exists(),
        "Chromium wrote no screenshot: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let keep = Path::new(env!("CARGO_TARGET_TMPDIR")).join("calc-report-chromium.png");
    std::fs::copy(&shot, &keep).unwrap();
    let page = svg::load_png(&shot);
    assert_eq!(page.width, 1280);
    let rows = page.rgb.len() / page.width as usize;
    let at = |x: usize, y: usize| page.rgb[y * page.width as usize + x];
    // Text of the title and the tables: dark pixels in the top third.
    let dark = (0..rows / 3)
        .flat_map(|y| (0..page.width as usize).map(move |x| (x, y)))
        .filter(|&(x, y)| at(x, y).iter().all(|&c| c < 90))
        .count();
    // The plan: saturated false colour below the tables.
    let coloured = page
        .rgb
        .iter()
        .filter(|c| c.iter().max().unwrap() - c.iter().min().unwrap() > 80)
        .count();
    assert!(
        dark > 3_000,
        "{dark} dark pixels of text (see {})",
        keep.display()
    );
    assert!(
        coloured > 100_000,
        "{coloured} false-colour pixels of the plan (see {})",
        keep.display()
    );
}

/// `--dxf` writes each plan as DXF R12 beside its SVG: one value text per CSV row (to
/// 0.1 lx), the outline, the isolux lines with their values in extended data, the
/// luminaire inserted; without the flag there is none. (ezdxf reads it back in
/// `python/tests/test_dxf.py`.)
#[test]
fn calc_dxf_writes_the_plan_for_cad() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = common::box_room_scene(
        tmp.path(),
        "room",
        "eulumdat-plot/sample_06_isym1.ldt",
        "position = [3.0, 2.0, 2.95]\n[[grid]]\nname = \"work plane\"\ncorner = [0.5, 0.5]\nsize = [5.0, 3.0]\nheight = 0.8\nspacing = 0.5\n",
    );
    let out = tmp.path().join("out");
    let args = [
        "calc",
        scene.to_str().unwrap(),
        "--cpu",
        "--dxf",
        "--out",
        out.to_str().unwrap(),
    ];
    let (code, stdout, stderr) = run_cli(&args, "");
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("PNG, SVG, DXF"), "{stdout}");
    let dxf = std::fs::read_to_string(out.join("work-plane.dxf")).unwrap();
    let rows = calc_csv_rows(&out.join("work-plane.csv"));
    assert!(dxf.starts_with("  0\nSECTION\n  2\nHEADER\n  9\n$ACADVER\n  1\nAC1009\n"));
    assert!(dxf.ends_with("  0\nEOF\n"));
    let pairs: Vec<(&str, &str)> = dxf
        .lines()
        .collect::<Vec<_>>()
        .chunks(2)
        .map(|c| (c[0].trim(), c[1]))
        .collect();
    // Each VALUES text's string follows its layer; collect them in order.
    let mut values = Vec::new();
    for w in pairs.windows(8) {
        if w[0] == ("0", "TEXT") && w[1] == ("8", "VALUES") {
            let text = w.iter().find(|p| p.0 == "1").unwrap().1;
            values.push(text.parse::<f64>().unwrap());
        }
    }
    assert_eq!(values.len(), rows.len());
    for (v, r) in values.iter().zip(&rows) {
        assert!((v - r[3]).abs() <= 0.051, "{v} vs {}", r[3]);
    }
    assert_eq!(
        pairs.iter().filter(|p| **p == ("2", "LUMINAIRE")).count(),
        2
    ); // block + insert
    assert!(pairs.iter().filter(|p| **p == ("8", "ISOLUX")).count() > 2);
    // Without the flag: no DXF.
    let again = tmp.path().join("again");
    let (code, _, _) = run_cli(
        &[
            "calc",
            scene.to_str().unwrap(),
            "--cpu",
            "--out",
            again.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0);
    assert!(!again.join("work-plane.dxf").exists());
}
