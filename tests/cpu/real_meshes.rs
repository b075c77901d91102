//! Real architectural models (`../shared/models/`, read in place): the conference room has
//! 53 627 zero-area triangles of 331 179, the high-rise block 673 of 400 020 plus many
//! slivers. Every command reads them, says how many triangles it dropped, and gives
//! finite numbers (no NaN, no panic).

use crate::common;

use std::path::Path;
use std::time::Duration;

struct Model {
    obj: &'static str,
    up: &'static str,
    scale: f64,
    dropped: usize,
    triangles: usize,
    /// A luminaire position and a point below it (model frame after up and scale).
    light: [f64; 3],
}

const MODELS: [Model; 2] = [
    Model {
        obj: "models/conference/conference.obj",
        up: "y",
        scale: 0.004,
        dropped: 53_627,
        triangles: 331_179,
        light: [1.0, 1.0, 2.0],
    },
    Model {
        obj: "models/openfoam_buildings/buildings.obj",
        up: "z",
        scale: 1.0,
        // SOURCES.md counts 687 with its own tolerance; the one test goniolight applies
        // everywhere (|n|² ≤ 1e-24 · L⁴) finds 673: 14 have a tiny but real area.
        dropped: 673,
        triangles: 400_020,
        light: [1.0, 1.0, 2.0],
    },
];

fn scene_for(m: &Model, dir: &Path) -> std::path::PathBuf {
    let obj = common::shared_dir().join(m.obj);
    let lum = common::luminaire("eulumdat-plot/sample_06_isym1.ldt");
    let [x, y, z] = m.light;
    let text = format!(
        "[[model]]\npath = {:?}\nup = {:?}\nscale = {}\n\n[[luminaire]]\nfile = {:?}\nposition = [{x}, {y}, {z}]\n\n[camera]\nposition = [0, 0, 3]\nlook_at = [2, 2, 0]\nfov_deg = 60\n",
        obj.to_str().unwrap(),
        m.up,
        m.scale,
        lum.to_str().unwrap()
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn run(dir: &Path, args: &[&str], stdin: &str) -> (String, String) {
    let (code, out, err, timed_out) =
        common::run_cli_in(dir, args, stdin, Duration::from_secs(600));
    assert!(!timed_out, "{args:?}");
    assert_eq!(code, 0, "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(!has_nan(&out), "{args:?}: {out}");
    (out, err)
}

/// A "NaN" (or "nan", "-nan") word in printed output.
fn has_nan(text: &str) -> bool {
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .any(|w| w.eq_ignore_ascii_case("nan"))
}

fn says_dropped(err: &str, m: &Model) {
    let note = format!(
        "{} of its {} triangles have no area",
        m.dropped, m.triangles
    );
    assert!(err.contains(&note), "{}: {note:?} in {err}", m.obj);
}

#[test]
fn scene_commands_drop_zero_area_triangles_with_a_count() {
    for m in &MODELS {
        let tmp = tempfile::tempdir().unwrap();
        let scene = scene_for(m, tmp.path());
        let s = scene.to_str().unwrap();
        // The library says so in the scene's warnings (printing them is the front end's).
        let warnings = goniolight::scene::Scene::load(&scene).unwrap().warnings;
        says_dropped(&warnings.join("\n"), m);
        let below = format!("{} {} 0.5 0 0 1\n", m.light[0], m.light[1]);
        for args in [vec!["illuminance", s, "--cpu"], vec!["illuminance", s]] {
            let (out, err) = run(tmp.path(), &args, &below);
            says_dropped(&err, m);
            let lux: f64 = out.trim().parse().unwrap();
            assert!(lux.is_finite() && lux >= 0.0, "{args:?}: {lux}");
        }
        let (out, err) = run(
            tmp.path(),
            &[
                "render", s, "--out", "x.png", "--width", "160", "--height", "120",
            ],
            "",
        );
        says_dropped(&err, m);
        assert!(out.contains("x.png"));
        image::open(tmp.path().join("x.png")).unwrap();
    }
}

#[test]
fn radiosity_reads_the_conference_room() {
    let m = &MODELS[0];
    let tmp = tempfile::tempdir().unwrap();
    let scene = scene_for(m, tmp.path());
    let args = [
        "radiosity",
        scene.to_str().unwrap(),
        "--max-shots",
        "1",
        "--texel-density",
        "1",
        "--width",
        "160",
        "--height",
        "120",
        "--out-dir",
        "r",
    ];
    let (_, err) = run(tmp.path(), &args, "");
    says_dropped(&err, m);
    // Its surfaces shoot as a whole: at most a tenth of its triangles are shooters.
    let shooters: usize = err
        .split(" shooters of ")
        .next()
        .and_then(|head| head.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no shooter count in {err}"));
    eprintln!("conference room: {shooters} shooters");
    assert!(shooters * 10 <= m.triangles, "{shooters} shooters");
    let csv = std::fs::read_to_string(tmp.path().join("r/convergence.csv")).unwrap();
    assert!(!has_nan(&csv), "{csv}");
}

#[test]
fn model_commands_drop_zero_area_triangles_with_a_count() {
    for m in &MODELS {
        let obj = common::shared_dir().join(m.obj);
        let o = obj.to_str().unwrap();
        let tmp = tempfile::tempdir().unwrap();
        let (out, err) = run(
            tmp.path(),
            &["silhouette", o, "--light", "1,2,30,1", "--json"],
            "",
        );
        says_dropped(&err, m);
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert!(v["count"].as_u64().unwrap() > 0);
        let args = common::profile_args(
            o,
            "10:00",
            "14:00",
            "240",
            &["--up", m.up, "--resolution", "64", "--out", "p"],
        );
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (_, err) = run(tmp.path(), &args, "");
        says_dropped(&err, m);
        let csv = std::fs::read_to_string(tmp.path().join("p/profile.csv")).unwrap();
        assert!(!has_nan(&csv), "{csv}");
    }
}

#[test]
fn the_viewer_opens_the_conference_room() {
    let m = &MODELS[0];
    let tmp = tempfile::tempdir().unwrap();
    let scene = scene_for(m, tmp.path());
    let shot = tmp.path().join("window.png");
    let out = std::process::Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_goniolight"))
        .args([
            "view",
            scene.to_str().unwrap(),
            "--frames",
            "2",
            "--screenshot",
        ])
        .arg(&shot)
        .env("GONIOLIGHT_CONFIG_DIR", tmp.path().join("config"))
        .output()
        .expect("xvfb-run is needed (scripts/install-deps.sh installs it)");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    says_dropped(&err, m);
    assert!(!err.contains("panicked"), "{err}");
    image::open(&shot).unwrap();
}

#[test]
fn charts_tile_the_conference_room_exactly_with_fewer_elements() {
    use goniolight::radiosity::scene::RadiosityScene;
    use goniolight::radiosity::Hierarchy;
    let m = &MODELS[0];
    let tmp = tempfile::tempdir().unwrap();
    let scene = goniolight::scene::Scene::load(&scene_for(m, tmp.path())).unwrap();
    let charted = RadiosityScene::with_hierarchy(&scene, 2.0, 2, Hierarchy::Clusters).unwrap();
    let flat = RadiosityScene::new(&scene, 2.0, 2).unwrap();
    let el = &charted.elements;
    let mesh = &charted.casters;
    let area = |t: usize| {
        let [a, b, c] = mesh.triangles[t].map(|i| mesh.positions[i as usize]);
        0.5 * (b - a).cross(c - a).length()
    };
    let mut seen = vec![0u32; mesh.triangles.len()];
    for chart in &el.charts {
        let want: f64 = chart.triangles.iter().map(|&t| area(t as usize)).sum();
        let got: f64 = el.area[chart.first as usize..][..chart.count as usize]
            .iter()
            .sum();
        assert!(
            (got - want).abs() <= 1e-9 * want.max(1e-6),
            "{got} vs {want}"
        );
        for &t in &chart.triangles {
            seen[t as usize] += 1;
        }
    }
    assert!(seen.iter().all(|&n| n == 1), "every triangle in one chart");
    eprintln!(
        "conference room at 2 texels/m: {} elements in {} charts, {} per triangle",
        el.len(),
        el.charts.len(),
        flat.elements.len()
    );
    assert!(el.charts.len() * 2 < mesh.triangles.len());
    assert!(el.len() < flat.elements.len());
}

#[test]
fn the_real_model_scene_files_read_the_shared_models_in_place() {
    // assets/real_models/*.toml point at ../shared next to the repository.
    assert!(common::shared_dir().join("models").is_dir());
    for (file, triangles, luminaires) in [
        ("sibenik.toml", 73_553, 5),
        ("conference.toml", 331_179 - 53_627, 4),
    ] {
        let path = common::root().join("assets/real_models").join(file);
        let scene = goniolight::scene::Scene::load(&path).unwrap();
        assert_eq!(scene.triangle_count(), triangles, "{file}");
        assert_eq!(scene.luminaires.len(), luminaires, "{file}");
        // Every luminaire hangs inside the model's bounds.
        let mesh = scene.caster_mesh();
        let lo = mesh
            .positions
            .iter()
            .fold(glam::DVec3::MAX, |a, &p| a.min(p));
        let hi = mesh
            .positions
            .iter()
            .fold(glam::DVec3::MIN, |a, &p| a.max(p));
        for l in &scene.luminaires {
            assert!(
                (l.position.cmpgt(lo) & l.position.cmplt(hi)).all(),
                "{file}: {} outside {lo} … {hi}",
                l.position
            );
        }
    }
}
