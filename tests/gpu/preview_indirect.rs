//! `render --indirect none|ambient|radiosity` and the scene key `display.indirect`: the
//! preview's interreflected light, and the label saying which lux an image shows.

use crate::common;
use crate::gpu_common;

use goniolight::radiosity::initial::{InitialState, LuminaireLight};
use goniolight::radiosity::scene::{luminance, RadiosityScene};
use goniolight::radiosity::shooters::Hierarchy;
use goniolight::radiosity::solve::ambient_term;
use goniolight::scene::Scene;

/// `render SCENE --mode illuminance` with `extra`: (exit code, stdout, stderr).
fn render(scene: &std::path::Path, extra: &[&str]) -> (i32, String, String) {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("room.png");
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
        "--mode",
        "illuminance",
        "--width",
        "320",
        "--height",
        "180",
    ];
    args.extend_from_slice(extra);
    common::run_cli(&args, "")
}

/// The mean lux the render printed.
fn mean_lux(out: &str) -> f64 {
    let at = out.find("mean ").expect(out) + 5;
    out[at..].split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn the_ambient_preview_adds_the_ambient_term_of_the_luminaires_first_bounce() {
    let Some(gpu) = gpu_common::gpu() else {
        return;
    };
    let path = common::root().join("assets/scenes/box_room.toml");
    let (code, direct, err) = render(&path, &[]);
    assert_eq!(code, 0, "{err}");
    assert!(direct.contains("illuminance (direct)"), "{direct}");
    let (code, ambient, err) = render(&path, &["--indirect", "ambient"]);
    assert_eq!(code, 0, "{err}");
    assert!(
        ambient.contains("illuminance (direct + ambient estimate)"),
        "{ambient}"
    );
    assert!(
        ambient.contains("indirect light: ambient estimate"),
        "{ambient}"
    );

    // The ambient term, as the radiosity solver's defaults make it (10 texels/m, level 2,
    // face clusters): every surface in view gains its lux.
    let scene = Scene::load(&path).unwrap();
    let r = RadiosityScene::with_hierarchy(&scene, 10.0, 2, Hierarchy::Clusters).unwrap();
    let light = LuminaireLight::new(&gpu, &scene, goniolight::photometry::Interp::CatmullRom);
    let shadows = goniolight::render::ShadowSettings::default();
    let initial = InitialState::from_luminaires_gpu(&gpu, &light, &r, &shadows).unwrap();
    let a = luminance(ambient_term(&r, &initial.radiosity));
    let (d, m) = (mean_lux(&direct), mean_lux(&ambient));
    eprintln!("direct mean {d} lx, with ambient {m} lx, ambient term {a:.1} lx");
    assert!(a > 0.2 * d, "a box room reflects: {a} vs {d}");
    assert!(
        (m - (d + a)).abs() < 0.05 * (d + a),
        "{m} vs {d} + {a} (the light map's mean is the pixels' within a few %)"
    );
}

#[test]
fn the_radiosity_preview_and_the_scene_key() {
    let Some(_gpu) = gpu_common::gpu() else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    // The scene key asks for radiosity; the flag overrides it.
    let scene = common::box_room_scene(
        dir.path(),
        "room",
        "eulumdat-plot/sample_06_isym1.ldt",
        "position = [3.0, 2.0, 2.95]\n[camera]\nposition = [0.3, 0.3, 1.6]\nlook_at = [4.5, 3.2, 1.0]\n[display]\nindirect = \"radiosity\"\n",
    );
    let (code, solved, err) = render(&scene, &["--indirect-time", "3"]);
    assert_eq!(code, 0, "{err}");
    assert!(solved.contains("illuminance (total)"), "{solved}");
    assert!(solved.contains("indirect light: radiosity"), "{solved}");
    let (code, direct, err) = render(&scene, &["--indirect", "none"]);
    assert_eq!(code, 0, "{err}");
    assert!(direct.contains("illuminance (direct)"), "{direct}");
    // A white-ish room: the interreflected light adds a good share.
    let (t, d) = (mean_lux(&solved), mean_lux(&direct));
    assert!(t > 1.2 * d, "{t} vs {d}");

    // Bad input is refused before anything is written.
    let (code, _, err) = render(&scene, &["--indirect-time", "0"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("'0' for '--indirect-time") && err.contains("positive"),
        "{err}"
    );
    let bad = dir.path().join("bad.toml");
    let text = std::fs::read_to_string(&scene)
        .unwrap()
        .replace("indirect = \"radiosity\"", "indirect = \"bounce\"");
    std::fs::write(&bad, text).unwrap();
    let (code, _, err) = render(&bad, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("indirect"), "{err}");
}
