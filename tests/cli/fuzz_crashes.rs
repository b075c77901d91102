//! Every reproducer of `tests/data/fuzz-crashes/` (mutations of the bundled files found by
//! black-box fuzzing; its README lists command and symptom) ends cleanly: exit 0, 1 or 2,
//! no panic, abort or hang, no null, negative or non-finite flux or intensity with exit 0,
//! no silhouette edge outside the OBJ, converted files that goniolight reads back with the
//! same table, and errors that name the file.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use serde_json::Value;

/// Generous for a debug build on two cores; the slowest reproducer takes a few seconds.
const LIMIT: Duration = Duration::from_secs(120);

fn data() -> PathBuf {
    common::root().join("tests/data/fuzz-crashes")
}

/// Files (or folders) directly under `rel`'s subfolders: `check/panic/A-2364.ldt`, …
fn cases(rel: &str) -> Vec<String> {
    let mut out = Vec::new();
    for class in std::fs::read_dir(data().join(rel)).unwrap() {
        let class = class.unwrap().path();
        if !class.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&class).unwrap() {
            let p = f.unwrap().path();
            out.push(p.strip_prefix(data()).unwrap().display().to_string());
        }
    }
    out.sort();
    assert!(!out.is_empty(), "{rel}: no reproducers");
    out
}

/// Runs in the reproducer folder and checks the universal promises: finished in time,
/// exit 0/1/2, no panic, and an error that names `names` (the input as given).
fn run(args: &[&str], stdin: &str, names: &str) -> (i32, String, String) {
    run_in(&data(), args, stdin, names)
}

fn run_in(dir: &Path, args: &[&str], stdin: &str, names: &str) -> (i32, String, String) {
    let (code, out, err, timed_out) = common::run_cli_in(dir, args, stdin, LIMIT);
    assert!(!timed_out, "{args:?}: still running after {LIMIT:?}");
    assert!(
        matches!(code, 0..=2),
        "{args:?}: exit {code} (a signal is -1)\n{err}"
    );
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    if code != 0 {
        assert!(
            err.contains(names),
            "{args:?}: error names {names:?}: {err}"
        );
        assert!(out.is_empty(), "{args:?}: no output on failure, got {out}");
    }
    (code, out, err)
}

/// A null anywhere but in the beam and field angles and the CIE flux code (null there
/// means the 50 % or 10 % level is never crossed, or no light goes downward, as the reference (docs/src/reference/commands.md)
/// documents).
fn has_null(v: &Value) -> bool {
    match v {
        Value::Null => true,
        Value::Array(a) => a.iter().any(has_null),
        Value::Object(o) => o
            .iter()
            .filter(|(k, _)| !k.ends_with("_angle_deg") && *k != "cie_flux_code")
            .any(|(_, v)| has_null(v)),
        _ => false,
    }
}

fn number(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} in {v}"))
}

/// `ldt info --json` output checked for usable numbers; returns it.
fn checked_info(file: &str, out: &str, err: &str) -> Value {
    let v: Value = serde_json::from_str(out).unwrap();
    assert!(!has_null(&v), "{file}: null in {out}");
    for key in ["flux_lm", "max_intensity", "lamp_flux_lm"] {
        let x = number(&v, key);
        assert!(x.is_finite() && x > 0.0, "{file}: {key} = {x}");
    }
    for row in v["intensities"].as_array().unwrap() {
        for x in row.as_array().unwrap() {
            assert!(x.as_f64().unwrap() >= 0.0, "{file}: negative intensity");
        }
    }
    if number(&v, "lorl_computed") > 100.5 {
        assert!(err.contains("LORL above 100 %"), "{file}: {err}");
    }
    v
}

#[test]
fn ldt_info_gives_usable_numbers_or_refuses() {
    let mut files = cases("info");
    files.extend(
        std::fs::read_dir(data().join("08-wrong-data-exit0"))
            .unwrap()
            .map(|e| {
                format!(
                    "08-wrong-data-exit0/{}",
                    e.unwrap().file_name().to_string_lossy()
                )
            }),
    );
    let mut refused = 0;
    for f in &files {
        let (code, out, err) = run(&["ldt", "info", f, "--json"], "", f);
        if code == 0 {
            checked_info(f, &out, &err);
        } else {
            refused += 1;
        }
    }
    // Negative, null or zero flux and overflowing factors are refused; LORL above 100 %
    // and the duplicate-angle file are read (with a warning for the LORL).
    assert!(refused >= 12, "{refused} of {} refused", files.len());
}

#[test]
fn ldt_check_never_panics_nor_stalls_and_gives_numbers() {
    let mut files = cases("check");
    for dir in ["02-ldt-check-kiddo-panic", "07-ldt-check-perf-cliff"] {
        files.extend(
            std::fs::read_dir(data().join(dir))
                .unwrap()
                .map(|e| format!("{dir}/{}", e.unwrap().file_name().to_string_lossy())),
        );
    }
    for f in &files {
        for extra in [None, Some("gamma")] {
            let mut args = vec!["ldt", "check", f.as_str(), "--json"];
            if let Some(mode) = extra {
                args.extend(["--leave-out", mode]);
            }
            let (code, out, _) = run(&args, "", f);
            if code == 0 {
                let v: Value = serde_json::from_str(&out).unwrap();
                assert!(!has_null(&v), "{f}: null in {out}");
            }
        }
    }
}

#[test]
fn converted_files_read_back_with_the_same_table() {
    let mut files = cases("convert");
    files.push("08-wrong-data-exit0/convert_gamma_1e-7_dup_angle.ldt".into());
    let tmp = tempfile::tempdir().unwrap();
    let mut converted = 0;
    for f in &files {
        let (code, out, err) = run(&["ldt", "info", f, "--json"], "", f);
        if code != 0 {
            continue;
        }
        let source = checked_info(f, &out, &err);
        // `--exact`: the table itself, every digit. (Without it, numbers are rounded to
        // EULUMDAT's widths: see below.)
        for ext in ["ldt", "ies"] {
            let target = tmp.path().join(format!("out.{ext}"));
            let t = target.to_str().unwrap();
            let (code, _, err) = run(&["ldt", "convert", f, "--out", t, "--exact"], "", f);
            assert_eq!(code, 0, "{f} → {ext}: {err}");
            let (code, out, err) = run(&["ldt", "info", t, "--json"], "", t);
            assert_eq!(code, 0, "{f} → {ext} is unreadable: {err}");
            let back = checked_info(t, &out, &err);
            assert_eq!(back["c_angles"], source["c_angles"], "{f} → {ext}");
            assert_eq!(back["gamma_angles"], source["gamma_angles"], "{f} → {ext}");
            let cd = |v: &Value| -> Vec<f64> {
                let k = number(v, "lamp_flux_lm") / 1000.0;
                v["intensities"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .flat_map(|r| {
                        r.as_array()
                            .unwrap()
                            .iter()
                            .map(move |x| x.as_f64().unwrap() * k)
                    })
                    .collect()
            };
            let (a, b) = (cd(&source), cd(&back));
            let peak = a.iter().cloned().fold(0.0, f64::max);
            for (x, y) in a.iter().zip(&b) {
                assert!((x - y).abs() <= 1e-9 * peak, "{f} → {ext}: {x} cd → {y} cd");
            }
            converted += 1;
        }
        // To EULUMDAT's widths: a file that reads back, or a refusal and no file.
        let target = tmp.path().join("standard.ldt");
        let t = target.to_str().unwrap();
        let (code, _, err) = run(&["ldt", "convert", f, "--out", t], "", f);
        if code == 0 {
            let (code, _, err) = run(&["ldt", "info", t, "--json"], "", t);
            assert_eq!(code, 0, "{f} → standard ldt is unreadable: {err}");
        } else {
            assert_eq!(code, 2, "{f}: {err}");
            assert!(err.contains("--exact"), "{f}: {err}");
            assert!(!target.exists(), "{f}: a refused conversion wrote {t}");
        }
        let _ = std::fs::remove_file(&target);
    }
    assert!(converted >= 16, "{converted} conversions");
}

/// Vertices of an OBJ as the format counts them: lines whose first word is `v`.
fn obj_vertex_count(path: &Path) -> usize {
    let bytes = std::fs::read(path).unwrap();
    String::from_utf8_lossy(&bytes)
        .lines()
        .filter(|l| l.split_whitespace().next() == Some("v"))
        .count()
}

#[test]
fn silhouette_edges_stay_inside_the_obj_and_errors_name_file_and_line() {
    for f in cases("silhouette") {
        let vertices = obj_vertex_count(&data().join(&f));
        for method in ["brute", "hextree"] {
            let args = [
                "silhouette",
                &f,
                "--light",
                "1,2,3,1",
                "--json",
                "--method",
                method,
            ];
            let (code, out, err) = run(&args, "", &f);
            if code == 0 {
                let v: Value = serde_json::from_str(&out).unwrap();
                for e in v["edges"].as_array().unwrap() {
                    for i in e.as_array().unwrap() {
                        let i = i.as_u64().unwrap() as usize;
                        assert!(i < vertices, "{f}: edge vertex {i} of {vertices}");
                    }
                }
            } else if f.ends_with("A-0.obj") {
                assert!(err.contains("line 1: not OBJ text"), "{err}");
            }
        }
    }
}

/// A reproducer scene folder copied beside the bundled textures (the reproducers name
/// `textures/…` of the furnished room but do not carry them).
fn scene_copy(rel: &str) -> tempfile::TempDir {
    let tmp = tempfile::tempdir().unwrap();
    for e in std::fs::read_dir(data().join(rel)).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, tmp.path().join(p.file_name().unwrap())).unwrap();
    }
    let textures = common::root().join("assets/scenes/textures");
    std::fs::create_dir(tmp.path().join("textures")).unwrap();
    for e in std::fs::read_dir(textures).unwrap() {
        let p = e.unwrap().path();
        std::fs::copy(&p, tmp.path().join("textures").join(p.file_name().unwrap())).unwrap();
    }
    tmp
}

fn check_lux(out: &str, what: &str) {
    for line in out.lines() {
        let v: f64 = line
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("{what}: {line:?}"));
        assert!(v.is_finite() && v >= 0.0, "{what}: {v} lx");
    }
}

#[test]
fn malformed_scenes_end_cleanly_on_cpu_and_gpu() {
    let mut dirs = cases("illum");
    for d in std::fs::read_dir(data().join("01-mtl-short-vector-panic/fuzz")).unwrap() {
        dirs.push(format!(
            "01-mtl-short-vector-panic/fuzz/{}",
            d.unwrap().file_name().to_string_lossy()
        ));
    }
    dirs.push("01-mtl-short-vector-panic/minimal".into());
    for rel in &dirs {
        let copy = scene_copy(rel);
        for cpu in [true, false] {
            let mut args = vec!["illuminance", "scene.toml"];
            if cpu {
                args.push("--cpu");
            }
            let (code, out, err) = run_in(copy.path(), &args, "1 1 0.8 0 0 1\n", "scene.toml");
            if code == 0 {
                check_lux(&out, rel);
            }
            if rel.starts_with("01-") || rel.contains("/panic/") {
                assert!(err.contains("needs 3 number(s)"), "{rel}: {err}");
            }
        }
    }
}

/// `render SCENE` at 160 × 120 with `extra` flags into a temporary folder: (exit code,
/// stderr, whether the image exists).
fn render_small(scene: &str, extra: &[&str]) -> (i32, String, bool) {
    let tmp = tempfile::tempdir().unwrap();
    let png = tmp.path().join("x.png");
    let mut args = vec![
        "render",
        scene,
        "--out",
        png.to_str().unwrap(),
        "--width",
        "160",
        "--height",
        "120",
    ];
    args.extend_from_slice(extra);
    let (code, _, err) = run(&args, "", scene);
    (code, err, png.exists())
}

#[test]
fn scenes_beyond_the_gpu_are_refused_before_upload() {
    for (scene, shadows, says) in [
        (
            "03-too-many-luminaires-panic/lum_129.toml",
            "paraboloid",
            "258 texture layers",
        ),
        (
            "03-too-many-luminaires-panic/lum_257.toml",
            "volumes",
            "257 texture layers",
        ),
    ] {
        let (code, err, image) = render_small(scene, &["--shadows", shadows]);
        assert_eq!(code, 2, "{scene}: {err}");
        assert!(err.contains(says), "{scene}: {err}");
        // The library names the option; the command, its flag.
        assert!(
            err.contains("--shadows none") && !err.contains('`'),
            "{scene}: {err}"
        );
        assert!(!image, "{scene}: no image on refusal");
    }
    // Ground planes of 300 m and 1 km: the paraboloid casters are tessellated more
    // coarsely (with a warning) instead of exhausting memory.
    for scene in [
        "04-large-triangle-paraboloid/g300.toml",
        "04-large-triangle-paraboloid/g1000.toml",
    ] {
        let (code, err, image) = render_small(scene, &[]);
        assert_eq!(code, 0, "{scene}: {err}");
        assert!(err.contains("casters tessellated to"), "{scene}: {err}");
        assert!(err.contains("--shadows volumes is exact"), "{scene}: {err}");
        assert_eq!(err.matches("casters tessellated to").count(), 1, "{err}");
        assert!(image);
    }
    // The same 257 luminaires without shadows render.
    let scene = "03-too-many-luminaires-panic/lum_257.toml";
    let (code, err, image) = render_small(scene, &["--shadows", "none"]);
    assert_eq!(code, 0, "{err}");
    assert!(image);
}

#[test]
fn a_two_million_triangle_mesh_is_refused_with_its_size() {
    // 05-big-mesh-buffer-panic/make_big2m.py, in Rust: a 1000 × 1000 quad grid.
    let tmp = tempfile::tempdir().unwrap();
    let mut obj = String::with_capacity(70 << 20);
    let n = 1000;
    for j in 0..=n {
        for i in 0..=n {
            obj.push_str(&format!("v {} {} 0\n", i as f64 * 0.05, j as f64 * 0.05));
        }
    }
    for j in 0..n {
        let b = j * (n + 1) + 1;
        for i in 0..n {
            obj.push_str(&format!("f {} {} {}\n", b + i, b + i + 1, b + i + n + 2));
            obj.push_str(&format!(
                "f {} {} {}\n",
                b + i,
                b + i + n + 2,
                b + i + n + 1
            ));
        }
    }
    std::fs::write(tmp.path().join("big2m.obj"), obj).unwrap();
    let lum = common::luminaire("eulumdat-plot/sample_06_isym1.ldt");
    std::fs::write(
        tmp.path().join("big2m.toml"),
        format!(
            "[[model]]\npath = \"big2m.obj\"\nup = \"z\"\n[[luminaire]]\nfile = {:?}\nposition = [25, 25, 5]\n[camera]\nposition = [-5, -5, 20]\nlook_at = [25, 25, 0]\nfov_deg = 60.0\n",
            lum.to_str().unwrap()
        ),
    )
    .unwrap();
    let args = [
        "render",
        "big2m.toml",
        "--out",
        "x.png",
        "--width",
        "160",
        "--height",
        "120",
    ];
    let (code, _, err) = run_in(tmp.path(), &args, "", "triangles");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("2000000 triangles need"), "{err}");
    assert!(!tmp.path().join("x.png").exists());
}

#[test]
fn devices_and_endless_inputs_are_refused_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let png = tmp.path().join("x.png");
    let png = png.to_str().unwrap();
    for args in [
        vec!["ldt", "info", "/dev/zero"],
        vec!["render", "/dev/zero", "--out", png],
        vec!["silhouette", "/dev/zero", "--light", "1,2,3,1"],
    ] {
        let (code, _, err) = run(&args, "", "/dev/zero");
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("a device, not a file"), "{err}");
    }
    let dir = "06-device-file-unbounded-read/mtllib_devzero";
    let (code, _, err) = run_in(
        &data().join(dir),
        &["illuminance", "--cpu", "scene.toml"],
        "1 1 0.8 0 0 1\n",
        "/dev/zero",
    );
    assert_eq!(code, 2, "{err}");
    // A texel density whose atlas cannot exist is refused before any element is made.
    let scene = common::root().join("assets/scenes/cornell_box.toml");
    let args = [
        "radiosity",
        scene.to_str().unwrap(),
        "--texel-density",
        "1200",
        "--max-shots",
        "1",
        "--out-dir",
        tmp.path().to_str().unwrap(),
    ];
    let started = std::time::Instant::now();
    let (code, _, err) = run(&args, "", "cornell_box.toml");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("do not fit"), "{err}");
    assert!(started.elapsed() < Duration::from_secs(30));
}

#[test]
fn plot_and_convert_never_replace_their_input() {
    let tmp = tempfile::tempdir().unwrap();
    let a = tmp.path().join("a.ldt");
    std::fs::copy(common::luminaire("eulumdat-plot/sample_14_isym1.ldt"), &a).unwrap();
    let before = std::fs::read(&a).unwrap();
    let a_s = a.to_str().unwrap();
    for args in [
        vec!["ldt", "plot", a_s, "--out", a_s],
        vec!["ldt", "convert", a_s, "--out", a_s],
        vec!["ldt", "plot", a_s, "--out", "a.ies"],
    ] {
        let (code, _, err) = run(&args, "", "--out");
        assert_eq!(code, 2, "{args:?}: {err}");
    }
    assert_eq!(
        std::fs::read(&a).unwrap(),
        before,
        "the luminaire is untouched"
    );
}

#[test]
fn scene_and_silhouette_read_the_same_latin1_obj() {
    let dir = data().join("10-obj-latin1-scene-vs-silhouette");
    let (code, _, err) = run_in(
        &dir,
        &["silhouette", "m.obj", "--light", "0.3,0.3,1,1", "--json"],
        "",
        "m.obj",
    );
    assert_eq!(code, 0, "{err}");
    let (code, out, err) = run_in(
        &dir,
        &["illuminance", "--cpu", "scene.toml"],
        "0.3 0.3 0 0 0 1\n",
        "scene.toml",
    );
    assert_eq!(code, 0, "{err}");
    check_lux(&out, "latin-1 scene");
}

/// A bundled file with 1-based line `n` replaced.
fn with_line(rel: &str, n: usize, value: &str) -> Vec<u8> {
    let text = std::fs::read_to_string(common::luminaire(rel)).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    lines[n - 1] = value;
    lines.join("\n").into_bytes()
}

#[test]
fn inputs_found_by_the_stable_fuzzer() {
    use goniolight::photometry::Luminaire;
    let refused = |name: &str, bytes: &[u8], says: &str| {
        let e = Luminaire::from_bytes(name, bytes).unwrap_err().to_string();
        assert!(e.contains(says), "{name}: {e}");
    };
    // Luminaire dimensions that overflow once converted (LDT mm, IES units).
    let ldt = "eulumdat-plot/sample_06_isym1.ldt";
    refused(
        "big.ldt",
        &with_line(ldt, 13, "1e305"),
        "line 13: 1e305 mm is not the size",
    );
    let ies = "photometric-viewer/ies95/metric_units.ies";
    let text = std::fs::read_to_string(common::luminaire(ies)).unwrap();
    let tilt = text.lines().position(|l| l.starts_with("TILT")).unwrap() + 2;
    let first: Vec<&str> = text
        .lines()
        .nth(tilt - 1)
        .unwrap()
        .split_whitespace()
        .collect();
    let mut bad = first.clone();
    bad[7] = "1e305";
    refused(
        "big.ies",
        &with_line(ies, tilt, &bad.join(" ")),
        "opening width 1e305",
    );
    let mut bad = first.clone();
    bad[0] = "1e9";
    refused(
        "lamps.ies",
        &with_line(ies, tilt, &bad.join(" ")),
        "exceeds 1 000 000",
    );
    // A denormal lamp flux leaves no light in candela: refused, not written as an IES
    // file nobody can read.
    refused(
        "dark.ldt",
        &with_line(ldt, 29, "4.9e-324"),
        "emits no light",
    );
    // Non-finite material values would reach the reflectances (and radiosity).
    for mtl in [
        "newmtl a\nKd inf 0.5 0.5\n",
        "newmtl a\nKd 0.5 0.5 0.5\nNs NaN\n",
    ] {
        let e = goniolight::geometry::obj::parse_mtl("m.mtl", mtl.as_bytes()).unwrap_err();
        assert!(e.to_string().contains("is not a finite number"), "{e}");
    }
    // A normal with a component near f64::MAX is still a unit normal.
    let points =
        goniolight::lighting::read_points(std::io::Cursor::new("1 1 0.8 0 0 1e308\n"), "<stdin>")
            .unwrap();
    assert!((points[0].normal.z - 1.0).abs() < 1e-12);
}
