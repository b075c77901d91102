//! `goniolight view` in a real window under Xvfb on the GPU (lavapipe in CI):
//! `--frames N --screenshot out.png` for every bundled scene, the viewport's pixels
//! against `goniolight render` of the same view, bad input and a missing display.
//! `view --headless` draws the same frames offscreen with no display.
//! Needs `xvfb-run` (scripts/install-deps.sh installs it); fails, never skips, without
//! it, unless GPU tests are opted out with GONIOLIGHT_SKIP_GPU_TESTS=1.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{luminaire, root};

fn skip() -> bool {
    let skip = std::env::var("GONIOLIGHT_SKIP_GPU_TESTS").as_deref() == Ok("1");
    if skip {
        eprintln!("viewer window test skipped: GONIOLIGHT_SKIP_GPU_TESTS=1");
    }
    skip
}

/// Runs `goniolight view ARGS` under a fresh Xvfb server; returns (code, stdout, stderr).
fn view_under_xvfb(args: &[&str]) -> (i32, String, String) {
    view_under_xvfb_with(args, &[])
}

/// [`view_under_xvfb`] with environment variables `env` set.
fn view_under_xvfb_with(args: &[&str], env: &[(&str, &Path)]) -> (i32, String, String) {
    let out = Command::new("xvfb-run")
        .envs(env.iter().map(|&(k, v)| (k, v)))
        .args(["-a", "-s", "-screen 0 1600x1000x24"])
        .arg(env!("CARGO_BIN_EXE_goniolight"))
        .arg("view")
        .args(args)
        .env("GONIOLIGHT_CONFIG_DIR", std::env::temp_dir().join("goniolight-test-config"))
        .output()
        .unwrap_or_else(|e| {
            panic!("xvfb-run is needed for the viewer tests ({e}): apt-get install xvfb xauth (scripts/install-deps.sh does)")
        });
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The viewport rectangle `[x, y, width, height]` of a `view --screenshot` summary.
fn viewport_px(summary: &serde_json::Value) -> Vec<u32> {
    summary["viewport_px"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap() as u32)
        .collect()
}

fn render(scene: &Path, w: u32, h: u32, out: &Path) {
    let (code, _, err) = common::run_cli(
        &[
            "render",
            &scene.display().to_string(),
            "--mode",
            "shaded",
            // The viewer draws one sample per pixel.
            "--supersample",
            "1",
            "--width",
            &w.to_string(),
            "--height",
            &h.to_string(),
            "--out",
            &out.display().to_string(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
}

/// How many of the viewport `v`'s pixels in `window` differ from `reference` by more than
/// 2 levels in a channel, and the largest difference.
fn differing_pixels(
    window: &image::RgbaImage,
    v: &[u32],
    reference: &image::RgbaImage,
) -> (usize, i32) {
    let mut off = 0usize;
    let mut worst = 0i32;
    for y in 0..v[3] {
        for x in 0..v[2] {
            let a = window.get_pixel(v[0] + x, v[1] + y);
            let b = reference.get_pixel(x, y);
            let d = (0..3)
                .map(|c| (a[c] as i32 - b[c] as i32).abs())
                .max()
                .unwrap();
            worst = worst.max(d);
            off += usize::from(d > 2);
        }
    }
    (off, worst)
}

/// Asserts that the viewport of `window` (a `view --screenshot` of `scene`) shows what
/// `render` makes of the same view (at most 0.1 % of its pixels off by more than 2
/// levels); returns the viewport rectangle.
fn viewport_is_the_render(
    name: &str,
    window: &image::RgbaImage,
    summary: &serde_json::Value,
    scene: &Path,
    dir: &Path,
) -> Vec<u32> {
    let v = viewport_px(summary);
    // The side panel, menu and status bar take their share; the view the rest.
    assert!(v[0] > 100 && v[2] > 300 && v[3] > 300, "{v:?}");
    let reference = dir.join(format!("{name}-render.png"));
    render(scene, v[2], v[3], &reference);
    let reference = image::open(&reference).unwrap().to_rgba8();
    let (off, worst) = differing_pixels(window, &v, &reference);
    let total = (v[2] * v[3]) as usize;
    eprintln!(
        "{name}: viewport {v:?}, {off} of {total} pixels differ by > 2 levels (worst {worst})"
    );
    assert!(
        off * 1000 <= total,
        "{name}: {off} of {total} pixels differ (worst {worst})"
    );
    v
}

/// `view` arguments for 4 frames of `scene`, shaded, 900 × 600, saved to `shot`.
fn screenshot_args(scene: &Path, shot: &Path) -> Vec<String> {
    let (scene, shot) = (scene.display().to_string(), shot.display().to_string());
    [
        scene.as_str(),
        "--mode",
        "shaded",
        "--width",
        "900",
        "--height",
        "600",
        "--frames",
        "4",
        // Effect lights held where `render` draws them (they turn otherwise).
        "--time",
        "0",
        "--screenshot",
        shot.as_str(),
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn every_bundled_scene_renders_in_the_window_like_the_render_command() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    for name in ["box_room", "cornell_box", "effect_stage", "furnished_room"] {
        let scene = root().join(format!("assets/scenes/{name}.toml"));
        let shot = dir.path().join(format!("{name}-window.png"));
        let args = screenshot_args(&scene, &shot);
        let (code, out, err) =
            view_under_xvfb(&args.iter().map(|a| a.as_str()).collect::<Vec<_>>());
        assert_eq!(code, 0, "{name}: {err}");
        let summary: serde_json::Value =
            serde_json::from_str(out.trim()).unwrap_or_else(|e| panic!("{e}: {out}"));
        assert_eq!(summary["frames"], 4, "{summary}");
        let window = image::open(&shot).unwrap().to_rgba8();
        assert_eq!([window.width(), window.height()], [900, 600]);
        assert_eq!(summary["window_px"], serde_json::json!([900, 600]));
        let v = viewport_is_the_render(name, &window, &summary, &scene, dir.path());
        // The UI is there: the side panel is egui's panel grey with text on it.
        let panel: Vec<u8> = (40..v[3])
            .flat_map(|y| (2..v[0] - 2).map(move |x| (x, y)))
            .map(|(x, y)| window.get_pixel(x, y)[0])
            .collect();
        let grey = panel.iter().filter(|&&p| (20..=40).contains(&p)).count();
        let bright = panel.iter().filter(|&&p| p > 150).count();
        assert!(grey * 10 > panel.len() * 7, "{name}: side panel not drawn");
        assert!(bright > 200, "{name}: no text in the side panel");
    }
}

#[test]
fn a_malformed_luminaire_at_start_is_refused_and_nothing_is_written() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("broken.ldt");
    std::fs::write(&bad, "not a luminaire\n").unwrap();
    let shot = dir.path().join("never.png");
    let scene = root().join("assets/scenes/box_room.toml");
    let (code, _, err) = view_under_xvfb(&[
        &scene.display().to_string(),
        "--add",
        &bad.display().to_string(),
        "--screenshot",
        &shot.display().to_string(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("broken.ldt"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!shot.exists());
    // A good one is added (and lights the view).
    let good = luminaire("eulumdat-luminance/sample_07.ldt");
    let shot = dir.path().join("added.png");
    let (code, _, err) = view_under_xvfb(&[
        &scene.display().to_string(),
        "--add",
        &good.display().to_string(),
        "--frames",
        "2",
        "--screenshot",
        &shot.display().to_string(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(shot.exists());
}

#[test]
fn bad_flags_and_a_missing_display_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("x.jpg");
    let (code, _, err) =
        common::run_cli(&["view", "--screenshot", &shot.display().to_string()], "");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(".png"), "{err}");
    let (code, _, err) = common::run_cli(&["view", "--frames", "0"], "");
    assert_eq!(code, 2, "{err}");
    for ms in ["-1", "NaN", "5000"] {
        let flag = format!("--solver-ms-per-frame={ms}");
        let (code, _, err) = common::run_cli(&["view", &flag, "--frames", "1"], "");
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("--solver-ms-per-frame"), "{err}");
    }
    let (code, _, err) = common::run_cli(&["view", "--drive", "sideways"], "");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("perspective"), "{err}");
    let (code, _, err) = common::run_cli(&["view", "no/such/scene.toml", "--frames", "1"], "");
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("no/such/scene.toml"), "{err}");
    // No display at all: a message that says what to do, no panic.
    let (code, _, err) = view_without_a_display(&["--frames", "1"], dir.path());
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("xvfb-run") && err.contains("--headless"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

/// The window's screenshot of `scene` (900 × 600, 3 frames), its viewport rectangle, and
/// `render`'s image of the same view at the viewport's size.
fn window_and_render(
    dir: &Path,
    scene: &Path,
    name: &str,
) -> (image::RgbaImage, Vec<u32>, image::RgbaImage) {
    window_and_render_with(dir, Some(scene), scene, &[], name)
}

/// [`window_and_render`] of `scene` (`None`: `view` without a scene) with environment
/// variables `env`, against `render` of `reference`.
fn window_and_render_with(
    dir: &Path,
    scene: Option<&Path>,
    reference: &Path,
    env: &[(&str, &Path)],
    name: &str,
) -> (image::RgbaImage, Vec<u32>, image::RgbaImage) {
    let shot = dir.join(format!("{name}.png"));
    let shot_arg = shot.display().to_string();
    let mut args = vec![
        "--width",
        "900",
        "--height",
        "600",
        "--frames",
        "3",
        "--screenshot",
        &shot_arg,
    ];
    let scene_arg = scene.map(|s| s.display().to_string());
    if let Some(s) = &scene_arg {
        args.insert(0, s);
    }
    let (code, out, err) = view_under_xvfb_with(&args, env);
    assert_eq!(code, 0, "{err}");
    let summary: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    let v = viewport_px(&summary);
    let rendered = dir.join(format!("{name}-render.png"));
    render(reference, v[2], v[3], &rendered);
    (
        image::open(&shot).unwrap().to_rgba8(),
        v,
        image::open(&rendered).unwrap().to_rgba8(),
    )
}

/// A scene camera looking straight down (a plan view) showed an empty viewport: the
/// orbit camera's pitch came out at −90° with no defined view. Its window now shows the
/// room's floor like `render` does.
#[test]
fn a_straight_down_camera_shows_the_room() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = common::box_room_scene(
        dir.path(),
        "down",
        "eulumdat-plot/sample_06_isym1.ldt",
        "position = [3, 2, 2.9]\n[camera]\nposition = [3, 2, 2.8]\nlook_at = [3, 2, 0]\nup = [0, 1, 0]\nfov_deg = 90\n",
    );
    let (window, v, reference) = window_and_render(dir.path(), &scene, "down");
    // The lit floor fills the view in both (the background is a dark grey, ≤ 40).
    let lit = |img: &image::RgbaImage, x0: u32, y0: u32| {
        (0..v[3])
            .flat_map(|y| (0..v[2]).map(move |x| (x, y)))
            .filter(|&(x, y)| img.get_pixel(x0 + x, y0 + y).0[..3].iter().any(|&c| c > 60))
            .count() as f64
            / (v[2] * v[3]) as f64
    };
    let (in_window, in_render) = (lit(&window, v[0], v[1]), lit(&reference, 0, 0));
    eprintln!("lit: window {in_window:.3}, render {in_render:.3}");
    assert!(in_render > 0.9, "render: {in_render}");
    assert!(in_window > 0.9, "the window's view is empty: {in_window}");
}

/// An orthographic scene camera stays orthographic in the viewer: a scene without
/// `[camera]` gets the plan view (orthographic, from above, cut under the ceiling), and
/// the window shows what `render` makes of it.
#[test]
fn a_plan_view_stays_orthographic_in_the_window() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = common::box_room_scene(
        dir.path(),
        "plan",
        "eulumdat-plot/sample_06_isym1.ldt",
        "position = [2, 2, 2.9]\n",
    );
    let (window, v, reference) = window_and_render(dir.path(), &scene, "plan");
    let mut off = 0usize;
    for y in 0..v[3] {
        for x in 0..v[2] {
            let (a, b) = (
                window.get_pixel(v[0] + x, v[1] + y),
                reference.get_pixel(x, y),
            );
            off += usize::from((0..3).any(|c| (a[c] as i32 - b[c] as i32).abs() > 8));
        }
    }
    let total = (v[2] * v[3]) as usize;
    eprintln!("plan view: {off} of {total} pixels differ by more than 8 levels");
    // A perspective view of the same camera would differ almost everywhere.
    assert!(off * 100 <= total, "{off} of {total} pixels differ");
}

/// `view` with no argument outside any checkout (an installed binary): the furnished room
/// bundled in the binary is extracted to the cache folder and shown, exactly as the
/// checkout's scene renders.
#[test]
fn view_without_a_scene_works_outside_the_checkout() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (nowhere, cache) = (dir.path().join("no-data"), dir.path().join("cache"));
    std::fs::create_dir_all(&nowhere).unwrap();
    let env = [
        ("GONIOLIGHT_DATA_DIR", nowhere.as_path()),
        ("GONIOLIGHT_CACHE_DIR", cache.as_path()),
    ];
    let checkout = root().join("assets/scenes/furnished_room.toml");
    let (window, v, reference) =
        window_and_render_with(dir.path(), None, &checkout, &env, "default");
    let extracted: Vec<_> = std::fs::read_dir(&cache).unwrap().flatten().collect();
    assert_eq!(extracted.len(), 1, "one folder per version");
    let scene = extracted[0]
        .path()
        .join("assets/scenes/furnished_room.toml");
    assert!(scene.is_file(), "{} not extracted", scene.display());
    let (off, worst) = differing_pixels(&window, &v, &reference);
    let total = (v[2] * v[3]) as usize;
    assert!(
        off * 1000 <= total,
        "{off} of {total} pixels differ (worst {worst})"
    );
}

/// The JSON summary `view ARGS` prints under Xvfb (it must succeed).
fn summary(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = view_under_xvfb(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(out.lines().last().unwrap()).unwrap()
}

/// `view --indirect ambient|radiosity` starts the solver with the window: the ambient
/// estimate is shown without a shot, radiosity shoots while the frames are drawn.
#[test]
fn the_viewer_starts_with_the_indirect_light_asked_for() {
    if skip() {
        return;
    }
    let scene = root().join("assets/scenes/box_room.toml");
    let scene = scene.to_str().unwrap();
    let none = summary(&[scene, "--frames", "3"]);
    assert_eq!(none["indirect_shown"], false, "{none}");
    let ambient = summary(&[scene, "--indirect", "ambient", "--frames", "20"]);
    assert_eq!(ambient["indirect_shown"], true, "{ambient}");
    assert_eq!(ambient["indirect_shots"], 0, "{ambient}");
    // A shot a frame at most on lavapipe, each taking longer than the frame's budget: 9
    // shots in 10 frames there (the solver is set up during the first).
    let solved = summary(&[scene, "--indirect", "radiosity", "--frames", "10"]);
    assert_eq!(solved["indirect_shown"], true, "{solved}");
    assert!(solved["indirect_shots"].as_u64().unwrap() > 0, "{solved}");
}

/// The live solve in the window: the lux read at the viewport's centre starts at the
/// direct light and, after the frames, is the batch solve's (`render --indirect
/// radiosity` of the same view, read from its EXR) within 2 %.
#[test]
fn the_live_solve_converges_to_the_batch_solve_under_the_centre_pixel() {
    if skip() {
        return;
    }
    let scene = root().join("assets/scenes/box_room.toml");
    let scene = scene.to_str().unwrap();
    let lux = |s: &serde_json::Value| s["centre_lux"].as_f64().expect("a surface at the centre");
    let direct = summary(&[scene, "--mode", "illuminance", "--frames", "3"]);
    // Converged after 20-24 solving frames on lavapipe (a shot per frame at most there); a
    // faster GPU takes fewer.
    let live = summary(&[
        scene,
        "--mode",
        "illuminance",
        "--indirect",
        "radiosity",
        "--frames",
        "200",
    ]);
    assert!(
        live["indirect_status"]
            .as_str()
            .unwrap()
            .starts_with("done: converged"),
        "{live}"
    );
    let v = viewport_px(&live);
    let dir = tempfile::tempdir().unwrap();
    let exr = dir.path().join("batch.exr");
    let (code, _, err) = common::run_cli(
        &[
            "render",
            scene,
            "--mode",
            "illuminance",
            "--indirect",
            "radiosity",
            "--indirect-time",
            "300",
            "--width",
            &v[2].to_string(),
            "--height",
            &v[3].to_string(),
            "--out",
            dir.path().join("batch.png").to_str().unwrap(),
            "--exr",
            exr.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let image = image::open(&exr).unwrap().to_rgb32f();
    let batch = image.get_pixel(v[2] / 2, v[3] / 2)[0] as f64;
    let (d, l) = (lux(&direct), lux(&live));
    eprintln!("centre: direct {d:.2} lx, live {l:.2} lx, batch {batch:.2} lx");
    assert!(
        (d - batch).abs() > 0.2 * batch,
        "no indirect light to converge to"
    );
    assert!(
        (l - batch).abs() <= 0.02 * batch,
        "live {l} lx, batch {batch} lx"
    );
}

/// `goniolight view ARGS` with no display at all; returns (code, stdout, stderr).
fn view_without_a_display(args: &[&str], config: &Path) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_goniolight"))
        .arg("view")
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("GONIOLIGHT_CONFIG_DIR", config)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `view --headless` draws the window's frames offscreen with no display: the viewport is
/// what `render` makes of the same view, the UI is drawn around it, the live solve shoots
/// while the frames are drawn and their times are reported (how frame rates are measured
/// on a GPU server); without a frame count it is refused.
#[test]
fn headless_frames_are_the_windows_without_a_display() {
    if skip() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = root().join("assets/scenes/furnished_room.toml");
    let shot = dir.path().join("headless.png");
    let mut args = screenshot_args(&scene, &shot);
    args.push("--headless".into());
    let args: Vec<&str> = args.iter().map(|a| a.as_str()).collect();
    let (code, out, err) = view_without_a_display(&args, dir.path());
    assert_eq!(code, 0, "{err}");
    let summary: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(summary["headless"], true, "{summary}");
    assert_eq!(summary["frames"], 4, "{summary}");
    assert_eq!(summary["window_px"], serde_json::json!([900, 600]));
    let window = image::open(&shot).unwrap().to_rgba8();
    assert_eq!([window.width(), window.height()], [900, 600]);
    let v = viewport_is_the_render("headless", &window, &summary, &scene, dir.path());
    let panel_text = (40..v[3])
        .flat_map(|y| (2..v[0] - 2).map(move |x| (x, y)))
        .filter(|&(x, y)| window.get_pixel(x, y)[0] > 150)
        .count();
    assert!(panel_text > 200, "no text in the side panel");

    let box_room = root().join("assets/scenes/box_room.toml");
    let (code, out, err) = view_without_a_display(
        &[
            box_room.to_str().unwrap(),
            "--headless",
            "--indirect",
            "radiosity",
            "--frames",
            "60",
        ],
        dir.path(),
    );
    assert_eq!(code, 0, "{err}");
    let live: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(live["indirect_shown"], true, "{live}");
    assert!(live["indirect_shots"].as_u64().unwrap() > 0, "{live}");
    let ms = |k: &str| live[k].as_f64().unwrap();
    let solving = live["solving_frames"].as_u64().unwrap();
    assert!((1..=59).contains(&solving), "{live}");
    assert!(ms("solving_mean_frame_ms") > 0.0, "{live}");
    assert!(ms("solving_p95_frame_ms") <= ms("max_frame_ms"), "{live}");
    assert!(ms("mean_frame_ms") <= ms("max_frame_ms"), "{live}");

    let (code, _, err) = view_without_a_display(&["--headless"], dir.path());
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--frames"), "{err}");
}
