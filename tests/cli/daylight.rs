//! `illuminance` with daylight: the bundled side-lit room's `[sky]` and `[site]`, the
//! `--sky` and `--time` overrides, and the commands that refuse a sky they cannot compute
//! yet (so that no lux leaves out the daylight the scene asks for).

use glam::DVec3;
use goniolight::daylight::points::scene_daylight;
use goniolight::lighting::SurfacePoint;
use goniolight::scene::Scene;

use crate::common::{root, run_cli};

const POINTS: &str = "3 1 0.85 0 0 1\n3 2.5 0.85 0 0 1\n1 3.5 0.85 0 0 1\n3 0.5 1.2 0 -1 0\n";

fn side_lit() -> std::path::PathBuf {
    root().join("assets/scenes/side_lit_room.toml")
}

fn points() -> Vec<SurfacePoint> {
    POINTS
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            SurfacePoint {
                position: DVec3::new(v[0], v[1], v[2]),
                normal: DVec3::new(v[3], v[4], v[5]),
            }
        })
        .collect()
}

fn values(out: &str) -> Vec<f64> {
    out.lines().map(|l| l.trim().parse().unwrap()).collect()
}

/// The library's daylight for `scene` (the reference the command must print).
fn expected(scene: &Scene) -> Vec<f64> {
    scene_daylight(scene, &points())
        .unwrap()
        .iter()
        .map(|d| d.total())
        .collect()
}

fn assert_same(got: &[f64], want: &[f64], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (g, w) in got.iter().zip(want) {
        assert!(
            (g - w).abs() <= 1e-6 * (1.0 + w.abs()),
            "{what}: {g} vs {w}"
        );
    }
}

/// The scene's sky through its glazed window, on the CPU and with the GPU path (daylight
/// is computed on the CPU either way), equal to the library's values; falling with the
/// distance from the window; `--sky` and `--time` replace the scene's model and time.
#[test]
fn illuminance_adds_the_scene_s_daylight() {
    let path = side_lit();
    let scene = Scene::load(&path).unwrap();
    let want = expected(&scene);
    let p = path.to_str().unwrap();
    for extra in [&["--cpu"][..], &[][..]] {
        let mut args = vec!["illuminance", p];
        args.extend_from_slice(extra);
        let (code, out, err) = run_cli(&args, POINTS);
        assert_eq!(code, 0, "{err}");
        assert_same(&values(&out), &want, &format!("{extra:?}"));
    }
    assert!(want[0] > 2.0 * want[1] && want[1] > want[2], "{want:?}");
    // A daylight factor of 10.4 % a metre from the window (sky and ground, 70 % glass):
    // between the unglazed opening's and nothing.
    assert!(want[0] > 500.0 && want[0] < 2000.0, "{want:?}");
    let (code, out, err) = run_cli(
        &[
            "illuminance",
            p,
            "--cpu",
            "--sky",
            "cie:12",
            "--time",
            "2026-06-21T13:00",
        ],
        POINTS,
    );
    assert_eq!(code, 0, "{err}");
    let clear = scene
        .with_sky(Some("cie:12"), Some("2026-06-21T13:00"))
        .unwrap();
    assert_same(&values(&out), &expected(&clear), "clear sky at 13:00");
    // A number for --time is still the animation's seconds (no sky time).
    let (code, out, err) = run_cli(&["illuminance", p, "--cpu", "--time", "12.5"], POINTS);
    assert_eq!(code, 0, "{err}");
    assert_same(&values(&out), &want, "--time 12.5");
}

/// The sun through the window: a scene with 60 klx of direct normal illuminance at noon;
/// the sunlit patch of floor moves with `--time`.
#[test]
fn the_sun_moves_with_the_time() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(side_lit())
        .unwrap()
        .replace(
            "path = \"side_lit_room.obj\"",
            &format!(
                "path = {:?}",
                root().join("assets/scenes/side_lit_room.obj")
            ),
        )
        .replace(
            "model = \"cie-overcast\"",
            "model = \"cie-clear\"\ndirect_normal_lux = 60000",
        );
    let path = dir.path().join("sunny.toml");
    std::fs::write(&path, text).unwrap();
    let scene = Scene::load(&path).unwrap();
    let sun = scene.daylight.as_ref().unwrap().sky.sun.unwrap();
    // The floor point the sun reaches through the window's middle at noon.
    let lit = DVec3::new(3.0, 0.0, 1.65) - sun.direction * (1.65 / sun.direction.z);
    let stdin = format!("{} {} 0 0 0 1\n", lit.x, lit.y);
    let p = path.to_str().unwrap();
    let (code, noon, err) = run_cli(&["illuminance", p, "--cpu", "--format", "json"], &stdin);
    assert_eq!(code, 0, "{err}");
    let noon: serde_json::Value = serde_json::from_str(&noon).unwrap();
    let noon = noon[0]["lux"].as_f64().unwrap();
    assert!(
        noon > 0.7 * 60_000.0 * sun.direction.z * 0.6,
        "sunlit: {noon}"
    );
    let (code, late, err) = run_cli(
        &["illuminance", p, "--cpu", "--time", "2026-03-21T16:30"],
        &stdin,
    );
    assert_eq!(code, 0, "{err}");
    let late = values(&late)[0];
    assert!(
        late < 0.1 * noon,
        "the sun has moved west: {late} vs {noon}"
    );
}

/// What cannot draw daylight yet refuses a scene with a sky, naming it; a bad sky is
/// refused by flag or key.
#[test]
fn commands_refuse_what_they_would_get_wrong() {
    let p = side_lit();
    let p = p.to_str().unwrap();
    let (code, _, err) = run_cli(&["illuminance", p, "--cpu", "--sky", "cie:16"], POINTS);
    assert_ne!(code, 0);
    assert!(err.contains("--sky") && err.contains("cie:16"), "{err}");
    let (code, _, err) = run_cli(
        &[
            "illuminance",
            p,
            "--cpu",
            "--sky",
            "cie:9",
            "--time",
            "2026-03-21T23:00",
        ],
        POINTS,
    );
    assert_ne!(code, 0);
    assert!(
        err.contains("above the horizon") && err.contains("below"),
        "{err}"
    );
    let out = tempfile::tempdir().unwrap();
    let png = out.path().join("lux.png");
    let (code, _, err) = run_cli(
        &[
            "render",
            p,
            "--mode",
            "illuminance",
            "--out",
            png.to_str().unwrap(),
        ],
        "",
    );
    assert_ne!(code, 0);
    assert!(err.contains("[sky]") && !png.exists(), "{err}");
}

/// The side-lit room's `[[grid]]` copied beside it, its model found by absolute path, with
/// `replace` applied to the text and `extra` appended.
fn side_lit_copy(
    dir: &std::path::Path,
    name: &str,
    replace: &[(&str, &str)],
    extra: &str,
) -> std::path::PathBuf {
    let mut text = std::fs::read_to_string(side_lit()).unwrap().replace(
        "path = \"side_lit_room.obj\"",
        &format!(
            "path = {:?}",
            root().join("assets/scenes/side_lit_room.obj")
        ),
    );
    for (from, to) in replace {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text + extra).unwrap();
    path
}

fn csv_rows(path: &std::path::Path) -> (String, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// `calc` on the side-lit room (daylight alone, with interreflections): every CSV value
/// is what `radiosity --points` gives at that point, the `df` column is lux / 10 000 lx ×
/// 100, `calc.json`'s `daylight_factor` holds the column's statistics, the plans and the
/// report show it. The interreflected part (calc − `illuminance`) is positive everywhere
/// and its mean within a factor of two of the BRE split-flux estimate of the average
/// internally reflected component (BRE 209 / BR 288: IRC = τ W / (A (1 − R)) · (C R_fw +
/// 5 R_cw), here 0.72 % of 10 000 lx: 72 lx; Radiance gives 74.6 lx, see
/// docs/src/measurements/daylight.md).
#[test]
fn calc_gives_the_daylight_factor_of_its_grids() {
    let out = tempfile::tempdir().unwrap();
    let p = side_lit();
    let dir = out.path().join("calc");
    let report = out.path().join("report.html");
    let solver = ["--converge", "0.97", "--texel-density", "4"];
    let mut args = vec!["calc", p.to_str().unwrap(), "--out", dir.to_str().unwrap()];
    args.extend(["--report", report.to_str().unwrap()]);
    args.extend(solver);
    let (code, stdout, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    assert!(stdout.contains("daylight factor: mean"), "{stdout}");
    let (header, rows) = csv_rows(&dir.join("work-plane.csv"));
    assert_eq!(header, "x,y,z,lux,df");
    for r in &rows {
        assert!((r[4] - r[3] / 100.0).abs() < 2e-6, "{r:?}");
    }
    let stdin: String = rows
        .iter()
        .map(|r| format!("{} {} {} 0 0 1\n", r[0], r[1], r[2]))
        .collect();
    let mut args = vec!["radiosity", p.to_str().unwrap(), "--points"];
    args.extend(solver);
    let (code, solved, err) = run_cli(&args, &stdin);
    assert_eq!(code, 0, "{err}");
    for (r, v) in rows.iter().zip(values(&solved)) {
        assert!(
            (r[3] - v).abs() <= 1e-3 * (1.0 + v),
            "calc {} vs radiosity --points {v}",
            r[3]
        );
    }
    let (code, direct, err) = run_cli(&["illuminance", p.to_str().unwrap(), "--cpu"], &stdin);
    assert_eq!(code, 0, "{err}");
    let inter: Vec<f64> = rows
        .iter()
        .zip(values(&direct))
        .map(|(r, d)| r[3] - d)
        .collect();
    assert!(inter.iter().all(|&v| v > 10.0), "{inter:?}");
    let mean = inter.iter().sum::<f64>() / inter.len() as f64;
    // Window 3.6 m², room surfaces 108 m², mean reflectance 0.461, below the window's
    // mid-height 0.347, above it 0.612, unobstructed (C = 39), glass 0.70.
    let (w, a, r, r_fw, r_cw) = (3.6, 108.0, 0.461, 0.347, 0.612);
    let bre = 0.7 * w / (a * (1.0 - r)) * (39.0 * r_fw + 5.0 * r_cw) / 100.0 * 10_000.0;
    assert!((71.0..73.0).contains(&bre), "{bre}");
    assert!(
        mean > bre / 2.0 && mean < 2.0 * bre,
        "interreflected {mean:.1} lx vs BRE {bre:.1} lx"
    );
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("calc.json")).unwrap()).unwrap();
    let grid = &doc["grids"][0];
    let df: Vec<f64> = rows.iter().map(|r| r[4]).collect();
    let stats = goniolight::calc::daylight::factor_stats(&df);
    for (key, want) in [
        ("mean", stats.mean),
        ("median", stats.median),
        ("min", stats.min),
        ("max", stats.max),
        ("u0", stats.u0),
    ] {
        let got = grid["daylight_factor"][key].as_f64().unwrap();
        assert!(
            (got - want).abs() < 1e-5 * (1.0 + want),
            "{key}: {got} vs {want}"
        );
    }
    // A metre from the window a few per cent, at the back under one.
    assert!(stats.max > 10.0 && stats.min < 1.0, "{stats:?}");
    assert!(doc["method"]["daylight"]["sky"]
        .as_str()
        .unwrap()
        .contains("overcast"));
    for plan in ["work-plane-df.png", "work-plane-df.svg", "work-plane.png"] {
        assert!(dir.join(plan).is_file(), "{plan}");
    }
    let svg = std::fs::read_to_string(dir.join("work-plane-df.svg")).unwrap();
    assert!(
        svg.contains("daylight factor") && svg.contains("2 %"),
        "DF plan with its lines"
    );
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(html.contains("Daylight factor (CIE standard overcast sky)"));
}

/// The maintenance factor is the luminaires': with a luminaire and the sky, each value is
/// MF × the luminaire's alone plus the daylight alone (direct light, on the CPU).
#[test]
fn calc_adds_daylight_to_the_maintained_light_of_the_luminaires() {
    let out = tempfile::tempdir().unwrap();
    let luminaire = format!(
        "\n[[luminaire]]\nfile = {:?}\nposition = [3.0, 2.0, 2.9]\n",
        root().join("luminaires/eulumdat-plot/sample_06_isym1.ldt")
    );
    let direct = [("indirect = \"radiosity\"", "indirect = \"none\"")];
    let both = side_lit_copy(out.path(), "both", &direct, &luminaire);
    let no_sky = [
        direct[0],
        ("[sky]\nmodel = \"cie-overcast\"\ndiffuse_horizontal_lux = 10000\ntime = \"2026-03-21T12:00\"\nground_reflectance = 0.2\n", ""),
    ];
    let electric = side_lit_copy(out.path(), "electric", &no_sky, &luminaire);
    let sky_only = side_lit_copy(out.path(), "sky", &direct, "");
    let run = |scene: &std::path::Path, mf: &str| {
        let dir = out.path().join(format!(
            "{}-{mf}",
            scene.file_stem().unwrap().to_string_lossy()
        ));
        let (code, _, err) = run_cli(
            &[
                "calc",
                scene.to_str().unwrap(),
                "--cpu",
                "--maintenance-factor",
                mf,
                "--out",
                dir.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{err}");
        csv_rows(&dir.join("work-plane.csv")).1
    };
    let (both, electric, sky) = (
        run(&both, "0.8"),
        run(&electric, "1"),
        run(&sky_only, "0.5"),
    );
    assert_eq!(both.len(), electric.len());
    for ((b, e), d) in both.iter().zip(&electric).zip(&sky) {
        let want = 0.8 * e[3] + d[3];
        assert!(
            (b[3] - want).abs() < 2e-5 * (1.0 + want),
            "{} vs 0.8 × {} + {}",
            b[3],
            e[3],
            d[3]
        );
        // The daylight factor is the sky's alone, whatever the luminaires add.
        assert!((b[4] - d[4]).abs() < 1e-6, "{} vs {}", b[4], d[4]);
    }
}

/// `[sky] weather` with a `time`: the sky's and the sun's illuminances are those of the
/// weather file's hour that holds the time (read here from the file's fields 17 and 18,
/// local standard time, the hour ending at its number); the daylight at points equals that
/// of the same sky given by its numbers; the sun is left out while it is down.
#[test]
fn a_weather_file_gives_the_sky_its_hour_s_illuminances() {
    let tmp = tempfile::tempdir().unwrap();
    let epw = root().join("assets/weather/USA_IL_Chicago.OHare.Intl.AP.725300_TMY3.epw");
    let write = |name: &str, sky: &str| {
        let path = tmp.path().join(name);
        std::fs::write(
            &path,
            format!(
                "[[model]]\npath = {:?}\nup = \"z\"\n[site]\nlatitude = 41.98\nlongitude = -87.92\ntimezone = \"-06:00\"\n[sky]\nmodel = \"cie:12\"\ntime = \"2026-06-21T13:30\"\n{sky}",
                root().join("assets/scenes/side_lit_room.obj").display().to_string()
            ),
        )
        .unwrap();
        path
    };
    // 13:30 standard time is in the record of 21 June, hour 14 (13:00–14:00).
    let text = std::fs::read_to_string(&epw).unwrap();
    let row: Vec<f64> = text
        .lines()
        .skip(8)
        .map(|l| {
            l.split(',')
                .map(|f| f.parse::<f64>().unwrap_or(f64::NAN))
                .collect::<Vec<_>>()
        })
        .find(|f| (f[1], f[2], f[3]) == (6.0, 21.0, 14.0))
        .unwrap();
    let (direct_normal, diffuse) = (row[17], row[18]);
    assert!(
        direct_normal > 0.0 && diffuse > 0.0,
        "{direct_normal} {diffuse}"
    );
    let from_file = Scene::load(&write(
        "weather.toml",
        &format!("weather = {:?}\n", epw.display().to_string()),
    ))
    .unwrap();
    let sky = &from_file.daylight.as_ref().unwrap().sky;
    assert_eq!(sky.diffuse_horizontal_lux, diffuse);
    assert_eq!(sky.sun.unwrap().normal_lux, direct_normal);
    let given = Scene::load(&write(
        "given.toml",
        &format!("diffuse_horizontal_lux = {diffuse}\ndirect_normal_lux = {direct_normal}\n"),
    ))
    .unwrap();
    assert_same(&expected(&from_file), &expected(&given), "weather vs given");
    // Saved elsewhere, the scene keeps finding its weather file.
    let elsewhere = tmp.path().join("sub");
    std::fs::create_dir(&elsewhere).unwrap();
    from_file.save(&elsewhere.join("copy.toml")).unwrap();
    let copy = Scene::load(&elsewhere.join("copy.toml")).unwrap();
    assert_eq!(copy.daylight.unwrap().sky.diffuse_horizontal_lux, diffuse);
    // At night: no sun (and the file's night sky).
    let night = write(
        "night.toml",
        &format!("weather = {:?}\n", epw.display().to_string()),
    )
    .to_str()
    .unwrap()
    .to_string();
    let text = std::fs::read_to_string(&night)
        .unwrap()
        .replace("13:30", "23:30");
    std::fs::write(&night, text).unwrap();
    // A cie:12 sky needs the sun above the horizon: the night is refused by key.
    let e = Scene::load(std::path::Path::new(&night))
        .unwrap_err()
        .to_string();
    assert!(e.contains("sky."), "{e}");
}
