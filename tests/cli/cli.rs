//! The command-line contract of `goniolight ldt …` and `demo`.

use crate::common;

use common::{luminaire, run_cli};
use goniolight::photometry::{Interp, Luminaire};

#[test]
fn help_works_for_every_command() {
    for args in [
        vec!["--help"],
        vec!["ldt", "--help"],
        vec!["ldt", "info", "--help"],
        vec!["ldt", "sample", "--help"],
        vec!["ldt", "check", "--help"],
        vec!["ldt", "plot", "--help"],
        vec!["ldt", "convert", "--help"],
        vec!["demo", "--help"],
    ] {
        let (code, out, _) = run_cli(&args, "");
        assert_eq!(code, 0, "{args:?}");
        assert!(out.contains("Usage"), "{args:?}");
    }
}

#[test]
fn info_json_has_the_contract_keys() {
    let f = luminaire("eulumdat-plot/sample_16_isym3.ldt");
    let (code, out, err) = run_cli(&["ldt", "info", f.to_str().unwrap(), "--json"], "");
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in [
        "format",
        "symmetry",
        "c_angles",
        "gamma_angles",
        "intensities",
        "max_intensity",
        "lamp_flux_lm",
        "flux_lm",
        "lorl_declared",
        "lorl_computed",
        "dff_declared",
        "dff_computed",
        "beam_angle_deg",
        "field_angle_deg",
        "warnings",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["format"], "eulumdat");
    assert_eq!(v["symmetry"], 3);
    let c = v["c_angles"].as_array().unwrap();
    assert_eq!(c[0], 0.0);
    assert_eq!(c.len(), v["intensities"].as_array().unwrap().len());
    assert!(v["beam_angle_deg"]["c0_c180"].is_number());
    assert!(v["field_angle_deg"]["c90_c270"].is_number());
    let ies = luminaire("photometric-viewer/ies95/metric_units.ies");
    let (_, out, _) = run_cli(&["ldt", "info", ies.to_str().unwrap(), "--json"], "");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["format"], "ies");
}

#[test]
fn sample_prints_the_library_values() {
    let f = luminaire("eulumdat-luminance/sample_07.ldt");
    let lum = Luminaire::load(&f).unwrap();
    let queries = [(0.0, 0.0), (33.3, 41.7), (271.0, 89.9), (359.9, 12.0)];
    let stdin: String = queries.iter().map(|(c, g)| format!("{c} {g}\n")).collect();
    for interp in Interp::ALL {
        let (code, out, err) = run_cli(
            &[
                "ldt",
                "sample",
                f.to_str().unwrap(),
                "--interp",
                interp.name(),
            ],
            &stdin,
        );
        assert_eq!(code, 0, "{err}");
        let got: Vec<f64> = out.lines().map(|l| l.parse().unwrap()).collect();
        assert_eq!(got.len(), queries.len());
        for ((c, g), v) in queries.iter().zip(got) {
            assert_eq!(v, lum.distribution.sample(*c, *g, interp));
        }
    }
}

#[test]
fn check_json_has_every_method() {
    let f = luminaire("eulumdat-luminance/sample_06.ldt");
    let (code, out, err) = run_cli(&["ldt", "check", f.to_str().unwrap(), "--json"], "");
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["held_out"].as_u64().unwrap() > 0);
    for m in ["bilinear", "catmull_rom", "monotone"] {
        for k in [
            "rms",
            "max_abs",
            "max_rel",
            "overshoot_count",
            "flux_error_percent",
            "hausdorff",
        ] {
            assert!(v["methods"][m][k].is_number(), "{m}.{k}");
        }
    }
    // --reference: the 15° file checked against itself is exact.
    let (code, out, _) = run_cli(
        &[
            "ldt",
            "check",
            f.to_str().unwrap(),
            "--reference",
            f.to_str().unwrap(),
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v["methods"]["catmull_rom"]["max_abs"].as_f64().unwrap() < 1e-9);
}

#[test]
fn plot_and_convert_write_files() {
    let dir = tempfile::tempdir().unwrap();
    let f = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let png = dir.path().join("polar.png");
    let (code, _, err) = run_cli(
        &[
            "ldt",
            "plot",
            f.to_str().unwrap(),
            "--out",
            png.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1100, 860));
    // The datasheet diagram: the red C0–C180 and blue C90–C270 curves are drawn.
    assert!(img.pixels().any(|p| p[0] > 180 && p[1] < 60 && p[2] < 60));
    assert!(img.pixels().any(|p| p[2] > 180 && p[0] < 60));
    for ext in ["ies", "ldt"] {
        let out = dir.path().join(format!("x.{ext}"));
        let (code, _, err) = run_cli(
            &[
                "ldt",
                "convert",
                f.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 0, "{err}");
        let back = Luminaire::load(&out).unwrap();
        assert_eq!(back.data.symmetry.isym(), 3);
    }
    // An unknown extension writes nothing.
    let bad = dir.path().join("x.txt");
    let (code, _, _) = run_cli(
        &[
            "ldt",
            "convert",
            f.to_str().unwrap(),
            "--out",
            bad.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 2);
    assert!(!bad.exists());
}

#[test]
fn demo_writes_the_check_and_the_plot() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out, err) = run_cli(&["demo", "--out-dir", dir.path().to_str().unwrap()], "");
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("lowest RMS error"), "{out}");
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("check.json")).unwrap()).unwrap();
    assert_eq!(v["held_out"], 64272);
    assert!(dir.path().join("polar.png").exists());
}

#[test]
fn headless_gpu_commands_print_no_wayland_noise() {
    let scene = common::root().join("assets/scenes/box_room.toml");
    let (code, _, err) = common::run_cli_without(
        &["illuminance", scene.to_str().unwrap()],
        "1 1 0.8 0 0 1\n",
        &["XDG_RUNTIME_DIR", "WAYLAND_DISPLAY"],
    );
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("XDG_RUNTIME_DIR"), "{err}");
}

/// wgpu's OpenGL backend (what wgpu picks without a Vulkan driver) computed nothing into
/// the float targets: `illuminance` printed 0 lux with exit 0. Every GPU command now
/// refuses it (or finds no adapter) with exit 1 and the fix, and writes nothing.
#[test]
fn the_opengl_backend_is_refused_with_the_fix_never_a_wrong_number() {
    let scene = common::root().join("assets/scenes/box_room.toml");
    let scene = scene.to_str().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_string_lossy().into_owned();
    let (png, solved) = (out("room.png"), out("solved"));
    let commands: [(&[&str], &str); 4] = [
        (&["illuminance", scene], "1 1 0.8 0 0 1\n"),
        (&["render", scene, "--out", &png], ""),
        (
            &["radiosity", scene, "--max-shots", "2", "--out-dir", &solved],
            "",
        ),
        (&["demo", "--out-dir", &solved], ""),
    ];
    for (args, stdin) in commands {
        let (code, stdout, err) = common::run_cli_env(args, stdin, &[("WGPU_BACKEND", "gl")], &[]);
        assert_eq!(code, 1, "{args:?}: {err}");
        assert!(err.contains("mesa-vulkan-drivers"), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(stdout.trim().is_empty(), "{args:?} printed {stdout:?}");
    }
    assert!(
        common::files_in(dir.path()).is_empty(),
        "nothing is written"
    );
}

#[test]
fn info_text_is_for_people() {
    // The example: an IES downlight printed "(Ies, Isym 1)", "903.4996780611565 lm"
    // and "emits Full hemisphere".
    let f = luminaire("photometric-viewer/ies95/absolute_photometry.ies");
    let (code, out, err) = run_cli(&["ldt", "info", f.to_str().unwrap()], "");
    assert_eq!(code, 0, "{err}");
    for needle in [
        "IES, Isym 1 (rotationally symmetric)",
        "903 lm, 15 W",
        "flux           903 lm from 903 lm of lamps",
        "efficacy       60.2 lm/W",
        "DFF            100.0 % (declared 100.0 %): downward only",
        "dimensions     luminaire Ø 120 mm",
        "CIE flux code  94 99 100 100 100",
    ] {
        assert!(out.contains(needle), "{needle:?} missing in\n{out}");
    }
    assert!(
        !out.contains("903.49") && !out.contains("Ies") && !out.contains("hemisphere"),
        "{out}"
    );
    // The lamp set's flux for the text's figures; the JSON carries the same flux code.
    let f = luminaire("eulumdat-luminance/sample_06.ldt");
    let (code, out, _) = run_cli(&["ldt", "info", f.to_str().unwrap(), "--lamp-set", "2"], "");
    assert_eq!(code, 0);
    assert!(
        out.contains("flux           2643 lm from 2643 lm of lamps"),
        "{out}"
    );
    assert!(out.contains("efficacy       106.1 lm/W"), "{out}");
    let (_, json, _) = run_cli(&["ldt", "info", f.to_str().unwrap(), "--json"], "");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["cie_flux_code"], serde_json::json!([51, 80, 94, 87, 100]));
    assert!(out.contains("CIE flux code  51 80 94 87 100"), "{out}");
    let (code, _, err) = run_cli(&["ldt", "info", f.to_str().unwrap(), "--lamp-set", "3"], "");
    assert_eq!(code, 2);
    assert!(
        err.contains("sample_06.ldt")
            && err.contains("--lamp-set 3 is not in the file: it has 2 lamp set"),
        "{err}"
    );
}
