//! Every reproducer of `../shared/fuzz-crashes/outputs-and-limits/` (one folder per defect
//! class, its `cmd.txt` the command and what happened) ends as the reliability rules say:
//! an output never replaces an input, another output or a FIFO; a run writes a complete
//! set or nothing and leaves no temporary file; every number and size is bounded; bad
//! input exits 2 with an error naming the file and field. Each test runs in a copy of its
//! reproducer folder.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Generous for a debug build on two cores.
const LIMIT: Duration = Duration::from_secs(240);

/// The reproducers' folder.
fn reproducers() -> PathBuf {
    common::shared_dir().join("fuzz-crashes/outputs-and-limits")
}

/// A copy of reproducer `name` (a folder name's prefix, e.g. "OVERWRITE-01") in a new
/// temporary folder; returns (the guard, the copy).
fn copy_of(name: &str) -> (tempfile::TempDir, PathBuf) {
    let src = std::fs::read_dir(reproducers())
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.file_name().unwrap().to_string_lossy().starts_with(name))
        .unwrap_or_else(|| panic!("no reproducer {name}"));
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("case");
    std::fs::create_dir(&dir).unwrap();
    for f in common::files_in(&src) {
        std::fs::copy(src.join(&f), dir.join(&f)).unwrap();
    }
    (tmp, dir)
}

/// Runs the CLI in `dir`; checks it ended in time, without a panic or signal.
fn run(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let (code, out, err, timed_out) = common::run_cli_in(dir, args, "", LIMIT);
    assert!(!timed_out, "{args:?}: still running after {LIMIT:?}");
    assert!(matches!(code, 0..=2), "{args:?}: exit {code}\n{err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (code, out, err)
}

/// Runs and expects a refusal: exit 2, an error containing every one of `names`.
fn refused(dir: &Path, args: &[&str], names: &[&str]) -> String {
    let (code, _, err) = run(dir, args);
    assert_eq!(code, 2, "{args:?}: expected a refusal\n{err}");
    for n in names {
        assert!(err.contains(n), "{args:?}: the error names {n:?}: {err}");
    }
    err
}

/// Every file under `dir` with its bytes, in order.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files: Vec<_> = walk(dir)
        .into_iter()
        .filter(|p| p.is_file())
        .map(|p| (p.clone(), std::fs::read(&p).unwrap()))
        .collect();
    files.sort();
    files
}

/// Everything under `dir` (files and folders), depth first.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(walk(&p));
        }
        out.push(p);
    }
    out
}

/// No temporary file or staging folder (names starting with a dot) under `dir`.
fn no_temporaries(dir: &Path) {
    let left: Vec<_> = walk(dir)
        .into_iter()
        .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with('.'))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

const PROFILE: [&str; 14] = [
    "--up",
    "z",
    "--lat",
    "48.2",
    "--lon",
    "16.4",
    "--tz",
    "Europe/Vienna",
    "--from",
    "09:00",
    "--to",
    "15:00",
    "--step",
    "60",
];

/// `profile box.obj` at 128 px in Vienna, 09:00–15:00 hourly, then `extra`.
fn profile<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    profile_at("128", extra)
}

/// [`profile`] at `resolution` pixels.
fn profile_at<'a>(resolution: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["profile", "box.obj", "--resolution", resolution];
    v.extend(PROFILE);
    v.extend(extra);
    v
}

#[test]
fn every_reproducer_has_its_test_here() {
    let source = include_str!("outputs_and_limits.rs");
    for e in std::fs::read_dir(reproducers()).unwrap() {
        let p = e.unwrap().path();
        if !p.is_dir() {
            continue;
        }
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        // The class and number: "OVERWRITE-01", "WRONG-EXIT0-08".
        let parts: Vec<&str> = name.split('-').collect();
        let number = parts
            .iter()
            .position(|p| p.chars().all(|c| c.is_ascii_digit()))
            .unwrap_or_else(|| panic!("{name}: no number"));
        let class = parts[..=number].join("-");
        assert!(
            source.contains(&format!("\"{class}\"")),
            "{name}: no test copies it (add one to tests/cli/outputs_and_limits.rs)"
        );
    }
}

#[test]
fn calc_report_never_replaces_an_input_and_names_both() {
    let (_t, dir) = copy_of("OVERWRITE-01");
    let before = snapshot(&dir);
    for input in ["scene.toml", "lum.ldt", "box_room.obj", "box_room.mtl"] {
        refused(
            &dir,
            &["calc", "scene.toml", "--out", "out", "--report", input],
            &[&format!("--report {input}"), "is the input"],
        );
    }
    // An output of the same run: the plan of grid g.
    std::fs::create_dir(dir.join("out")).unwrap();
    refused(
        &dir,
        &[
            "calc",
            "scene.toml",
            "--out",
            "out",
            "--report",
            "out/g.svg",
        ],
        &["--report out/g.svg", "another output"],
    );
    std::fs::remove_dir(dir.join("out")).unwrap();
    assert_eq!(snapshot(&dir), before, "nothing changed");
}

#[test]
fn batch_outputs_are_checked_together_before_any_job() {
    let (_t, dir) = copy_of("OVERWRITE-02");
    let before = snapshot(&dir);
    refused(
        &dir,
        &["batch", "jobs.toml", "--summary", "s.json"],
        &["jobs.toml", "job[0].stdout", "is the input"],
    );
    refused(
        &dir,
        &[
            "batch",
            "jobs_summary.toml",
            "--summary",
            "jobs_summary.toml",
        ],
        &["--summary jobs_summary.toml", "is the input"],
    );
    assert_eq!(snapshot(&dir), before, "no job ran, nothing written");

    let (_t, dir) = copy_of("OVERWRITE-03");
    refused(
        &dir,
        &["batch", "jobs.toml", "--summary", "s.json"],
        &["job[1].stdout out/same.txt", "job[0].stdout out/same.txt"],
    );
    assert!(!dir.join("out").exists() && !dir.join("s.json").exists());
}

#[test]
fn radiosity_export_never_replaces_an_input_or_its_own_output() {
    let (_t, dir) = copy_of("OVERWRITE-04");
    let before = snapshot(&dir);
    let args = |export: &'static str| {
        [
            "radiosity",
            "box_room.toml",
            "--max-shots",
            "1",
            "--width",
            "64",
            "--height",
            "48",
            "--out-dir",
            "rd",
            "--export",
            export,
        ]
    };
    for input in ["box_room.toml", "box_room.obj", "lum.ldt"] {
        refused(&dir, &args(input), &["--export", input, "is the input"]);
    }
    refused(
        &dir,
        &args("rd/render.png"),
        &["rd/render.png", "another output"],
    );
    assert_eq!(snapshot(&dir), before);
}

#[test]
fn fifos_are_not_replaced_by_outputs() {
    let (_t, dir) = copy_of("OVERWRITE-05");
    assert!(Command::new("mkfifo")
        .arg(dir.join("fifo"))
        .status()
        .unwrap()
        .success());
    let is_fifo = || {
        use std::os::unix::fs::FileTypeExt;
        std::fs::metadata(dir.join("fifo"))
            .unwrap()
            .file_type()
            .is_fifo()
    };
    refused(
        &dir,
        &profile(&["--date", "2026-03-21", "--gif", "fifo", "--out", "po"]),
        &["--gif fifo", "a FIFO"],
    );
    refused(
        &dir,
        &["calc", "r.toml", "--out", "oc", "--report", "fifo"],
        &["--report fifo", "a FIFO"],
    );
    assert!(is_fifo(), "the FIFO is still a FIFO");
    assert!(!dir.join("po").exists() && !dir.join("oc").exists());
}

#[test]
fn profile_gif_never_replaces_the_model_or_the_study() {
    let (_t, dir) = copy_of("OVERWRITE-06");
    let model = std::fs::read(dir.join("box.obj")).unwrap();
    refused(
        &dir,
        &profile(&["--date", "2026-03-21", "--gif", "box.obj", "--out", "po"]),
        &["--gif box.obj", "is the input box.obj"],
    );
    assert_eq!(std::fs::read(dir.join("box.obj")).unwrap(), model);
    // Into the study's own plan: caught when the outputs are moved in, nothing written.
    std::fs::create_dir(dir.join("po")).unwrap();
    let (code, _, err) = run(
        &dir,
        &profile(&[
            "--date",
            "2026-03-21",
            "--gif",
            "po/profile.png",
            "--out",
            "po",
        ]),
    );
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("another output"), "{err}");
    assert!(
        common::files_in(&dir.join("po")).is_empty(),
        "nothing written"
    );
    no_temporaries(&dir);
}

#[test]
fn huge_time_limits_are_refused_not_panics() {
    let (_t, dir) = copy_of("PANIC-01");
    let cases: [&[&str]; 5] = [
        &[
            "radiosity",
            "box_room.toml",
            "--out-dir",
            "rd",
            "--time-limit",
            "2e19",
        ],
        &[
            "calc",
            "box_room.toml",
            "--out",
            "o",
            "--indirect",
            "radiosity",
            "--time-limit",
            "1e20",
        ],
        &[
            "render",
            "box_room.toml",
            "--out",
            "r.png",
            "--indirect",
            "radiosity",
            "--indirect-time",
            "1e20",
        ],
        &["bench", "radiosity", "--time-limit", "1e20"],
        &["bench", "adaptive", "--time-limit", "1e20"],
    ];
    for args in cases {
        refused(&dir, args, &["1e7 s", "accepted"]);
    }
    for bad in ["0", "-1", "NaN", "inf"] {
        refused(
            &dir,
            &["radiosity", "box_room.toml", &format!("--time-limit={bad}")],
            &["--time-limit"],
        );
    }
    assert!(!dir.join("rd").exists());
}

#[test]
fn a_huge_day_step_gives_the_first_date_only() {
    let (_t, dir) = copy_of("PANIC-02");
    let mut args = profile_at("64", &[]);
    args.extend([
        "--date-range",
        "2026-03-01..2026-03-31",
        "--day-step",
        "4294967295",
        "--out",
        "po",
    ]);
    let (code, _, err) = run(&dir, &args);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("on 1 date(s)"), "{err}");
    assert!(dir.join("po/study.json").is_file());
}

#[test]
fn a_room_that_absorbs_nothing_is_refused_naming_the_material() {
    let (_t, dir) = copy_of("HANG-01");
    refused(
        &dir,
        &[
            "calc",
            "scene.toml",
            "--out",
            "out",
            "--indirect",
            "radiosity",
        ],
        &["scene.toml", "material", "no surface absorbs"],
    );
    assert!(!dir.join("out").exists());
}

#[test]
fn grid_errors_name_the_right_key_and_names_print_escaped() {
    let (_t, dir) = copy_of("MSG-01");
    refused(&dir, &calc("scene.toml"), &["grid[0].corner"]);
    let (_t, dir) = copy_of("MSG-02");
    let (code, out, err) = run(&dir, &calc("scene.toml"));
    assert_eq!(code, 0, "{err}");
    assert!(
        !out.chars().any(|c| c.is_control() && c != '\n'),
        "control characters printed raw: {out:?}"
    );
    assert!(out.contains(r"a\nb\u{7}c\u{1b}[31m"), "{out}");
}

#[test]
fn profile_bad_dates_or_paths_write_nothing() {
    let (_t, dir) = copy_of("HALF-WRITTEN-01");
    let (code, _, err) = run(&dir, &profile(&["--date=-0500-03-21", "--out", "po"]));
    assert_ne!(code, 0, "{err}");
    assert!(err.contains("-500"), "{err}");
    assert!(!dir.join("po").exists(), "nothing written");
    no_temporaries(&dir);
    let (_t, dir) = copy_of("HALF-WRITTEN-02");
    refused(
        &dir,
        &profile(&[
            "--date",
            "2026-03-21",
            "--gif",
            "nodir/x/d.gif",
            "--out",
            "po",
        ]),
        &["--gif nodir/x/d.gif", "does not exist"],
    );
    assert!(!dir.join("po").exists());
}

/// Starts the CLI in `dir`, sends it SIGINT after each of `after` (from the start), and
/// returns its exit code and standard error.
fn interrupted(dir: &Path, args: &[&str], after: &[Duration]) -> (i32, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .args(args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    for &t in after {
        while started.elapsed() < t {
            std::thread::sleep(Duration::from_millis(10));
        }
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
    }
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn ctrl_c_in_calc_leaves_a_complete_set_or_nothing() {
    let (_t, dir) = copy_of("HALF-WRITTEN-03");
    // Once (finish the step, write nothing) and twice (at once); at any moment.
    for after in [
        vec![Duration::from_millis(1500)],
        vec![Duration::from_millis(1500), Duration::from_millis(1800)],
    ] {
        let (code, err) = interrupted(&dir, &["calc", "four.toml", "--out", "o4"], &after);
        assert!(!err.contains("panicked"), "{err}");
        no_temporaries(&dir);
        if code == 0 {
            let n = common::files_in(&dir.join("o4")).len();
            assert_eq!(n, 13, "a complete set: calc.json and 4 × (CSV, PNG, SVG)");
            std::fs::remove_dir_all(dir.join("o4")).unwrap();
        } else {
            assert!(matches!(code, 1 | 130), "exit {code}: {err}");
            assert!(!dir.join("o4").exists(), "{err}");
        }
    }
}

#[test]
fn ctrl_c_in_a_command_that_does_not_poll_ends_it_at_once_and_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::root().join("assets/scenes/box_room.toml");
    let scene = scene.to_str().unwrap();
    let (code, err) = interrupted(
        dir.path(),
        &[
            "render", scene, "--out", "r.png", "--exr", "r.exr", "--width", "4096", "--height",
            "4096",
        ],
        &[Duration::from_millis(1500)],
    );
    assert!(!err.contains("panicked"), "{err}");
    no_temporaries(dir.path());
    match code {
        0 => assert!(dir.path().join("r.png").is_file() && dir.path().join("r.exr").is_file()),
        130 => {}
        _ => panic!("exit {code}: {err}"),
    }
    // An image the device cannot read back is refused before the work (it panicked in
    // wgpu: a 1 GB read-back buffer against lavapipe's 256 MB).
    let err = refused(
        dir.path(),
        &[
            "render", scene, "--out", "r8.png", "--width", "8192", "--height", "8192",
        ],
        &["8192×8192", "use a smaller image"],
    );
    assert!(!dir.path().join("r8.png").exists(), "{err}");
}

#[test]
fn ctrl_c_in_profile_writes_nothing_at_any_moment() {
    let (_t, dir) = copy_of("HALF-WRITTEN-04");
    let args = [
        "profile",
        "box.obj",
        "--up",
        "z",
        "--lat",
        "48.2",
        "--lon",
        "16.4",
        "--tz",
        "Europe/Vienna",
        "--date-range",
        "2026-01-01..2026-02-28",
        "--from",
        "00:00",
        "--to",
        "23:59",
        "--step",
        "1",
        "--resolution",
        "128",
        "--out",
        "pj",
    ];
    for after in [
        vec![Duration::from_millis(2000)],
        vec![Duration::from_millis(2000), Duration::from_millis(2300)],
    ] {
        let (code, err) = interrupted(&dir, &args, &after);
        assert!(matches!(code, 1 | 130), "exit {code}: {err}");
        assert!(err.contains("nothing written") || code == 130, "{err}");
        assert!(!dir.join("pj").exists(), "{err}");
        no_temporaries(&dir);
    }
    // WRONG-EXIT0-08: a Ctrl-C after the steps no longer gives exit 0 and all files.
    let (_t, dir) = copy_of("WRONG-EXIT0-08");
    let (code, err) = interrupted(&dir, &args, &[Duration::from_millis(2500)]);
    assert_eq!(code, 1, "{err}");
    assert!(!dir.join("pj").exists());
}

#[test]
fn extra_coordinates_are_refused_with_the_line() {
    let (_t, dir) = copy_of("WRONG-EXIT0-01");
    refused(
        &dir,
        &calc("scene.toml"),
        &["scene.toml", "line", "invalid length 3", "2 numbers"],
    );
    refused(
        &dir,
        &calc("scene_outline.toml"),
        &["scene_outline.toml", "outline", "invalid length"],
    );
    refused(
        &dir,
        &profile(&[
            "--date",
            "2026-03-21",
            "--points",
            "q10_pos4.toml",
            "--out",
            "po",
        ]),
        &["q10_pos4.toml", "invalid length 4"],
    );
}

/// `calc SCENE --out out`.
fn calc(scene: &str) -> [&str; 4] {
    ["calc", scene, "--out", "out"]
}

/// `calc SCENE --out out --indirect radiosity --max-shots SHOTS`.
fn calc_radiosity<'a>(scene: &'a str, shots: &'a str) -> [&'a str; 8] {
    [
        "calc",
        scene,
        "--out",
        "out",
        "--indirect",
        "radiosity",
        "--max-shots",
        shots,
    ]
}

/// `calc.json`'s first observer.
fn first_observer(dir: &Path, out: &str) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join(out).join("calc.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["observers"][0].clone()
}

#[test]
fn huge_vectors_keep_their_direction() {
    let (_t, dir) = copy_of("WRONG-EXIT0-02");
    let radiosity = ["--indirect", "radiosity", "--max-shots", "1"];
    for (scene, out) in [
        ("scene.toml", "out"),
        ("scene_same_direction_small.toml", "out2"),
    ] {
        let mut args = vec!["calc", scene, "--out", out];
        args.extend(radiosity);
        let (code, _, err) = run(&dir, &args);
        assert_eq!(code, 0, "{err}");
    }
    let (huge, small) = (first_observer(&dir, "out"), first_observer(&dir, "out2"));
    let ugr = |v: &serde_json::Value| v["ugr"].as_f64().unwrap_or(f64::NAN);
    assert!(ugr(&small) > 10.0, "{small}");
    assert!((ugr(&huge) - ugr(&small)).abs() < 1e-9, "{huge} vs {small}");
    for (points, out) in [
        ("q11_normal_huge.toml", "p1"),
        ("q12_normal_small.toml", "p2"),
    ] {
        let (code, _, err) = run(
            &dir,
            &profile(&["--date", "2026-03-21", "--points", points, "--out", out]),
        );
        assert_eq!(code, 0, "{err}");
    }
    let last = |out: &str| {
        let text = std::fs::read_to_string(dir.join(out).join("points.csv")).unwrap();
        let line = text.lines().last().unwrap().to_string();
        line.rsplit(',')
            .take(2)
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    assert_eq!(last("p1"), last("p2"));
    assert_eq!(last("p2"), ["high", "6.0000"]);
}

#[test]
fn an_eye_inside_a_luminaire_is_refused_before_the_solve() {
    let (_t, dir) = copy_of("WRONG-EXIT0-03");
    for scene in ["scene_0.11m.toml", "scene_at_centre.toml"] {
        let err = refused(
            &dir,
            &calc_radiosity(scene, "1"),
            &[scene, "observer \"a\"", "inside the luminaire"],
        );
        assert!(!err.contains("shots"), "refused before solving: {err}");
    }
    assert!(!dir.join("out").exists());
}

#[test]
fn ugr_without_a_background_is_refused_not_called_no_glare() {
    let (_t, dir) = copy_of("WRONG-EXIT0-04");
    refused(
        &dir,
        &calc_radiosity("scene.toml", "3"),
        &[
            "observer",
            "background luminance L_b is 0",
            "no finite value",
        ],
    );
    assert!(!dir.join("out").exists());
}

#[test]
fn a_material_overridden_twice_is_refused() {
    let (_t, dir) = copy_of("WRONG-EXIT0-05");
    refused(
        &dir,
        &calc_radiosity("scene.toml", "2"),
        &["scene.toml", "material[1].name", "\"wall\"", "material[0]"],
    );
}

#[test]
fn an_emission_brighter_than_the_sun_is_refused() {
    let (_t, dir) = copy_of("WRONG-EXIT0-06");
    refused(
        &dir,
        &calc_radiosity("scene.toml", "2"),
        &["Ke", "brighter than the sun"],
    );
}

#[test]
fn absurd_luminous_areas_are_refused_naming_the_line() {
    let (_t, dir) = copy_of("WRONG-EXIT0-07");
    for cmd in ["ugr", "luminance"] {
        refused(
            &dir,
            &["ldt", cmd, "tiny.ldt"],
            &["tiny.ldt", "lines 16–21", "1 mm²"],
        );
        let (code, _, err) = run(&dir, &["ldt", cmd, "a.ldt"]);
        assert_eq!(code, 0, "{err}");
    }
    refused(
        &dir,
        &["ldt", "luminance", "neg.ldt"],
        &["neg.ldt", "line 16", "-450 mm is negative"],
    );
}

#[test]
fn budgets_over_the_whole_run_are_refused_with_the_option_that_raises_them() {
    let (_t, dir) = copy_of("RESOURCE-01");
    refused(
        &dir,
        &calc("scene.toml"),
        &["20000000 points", "--max-points"],
    );
    assert!(!dir.join("out").exists());
    let (_t, dir) = copy_of("RESOURCE-02");
    refused(
        &dir,
        &profile_at(
            "8192",
            &["--date", "2026-03-21", "--step-images", "--out", "po"],
        ),
        &["--resolution 8192", "GB", "--output-limit"],
    );
    assert!(!dir.join("po").exists());
    let (_t, dir) = copy_of("RESOURCE-03");
    refused(
        &dir,
        &["batch", "jobs.toml", "--summary", "s.json"],
        &["job[0].stdin /dev/zero", "not a regular file"],
    );
}
