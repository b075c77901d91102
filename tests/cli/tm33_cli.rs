//! TM-33 / ATLA files on the command line: `ldt convert` between the four formats (with
//! what each loses), `ldt info` (spectral figures), `check`, `plot`, `report` and
//! catalogue walks on TM-33 files, a TM-33 luminaire in a scene lighting as its EULUMDAT
//! twin, and a bad file refused with the element and line.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{luminaire, run_cli, shared_dir};

fn tm33(name: &str) -> PathBuf {
    shared_dir().join("luminaires/tm33").join(name)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn info_json(path: &Path) -> Value {
    let (code, out, err) = run_cli(&["ldt", "info", "--json", s(path)], "");
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn convert_goes_between_all_four_formats_and_says_what_is_lost() {
    let dir = tempfile::tempdir().unwrap();
    let ldt = luminaire("eulumdat-plot/sample_01_isym3.ldt");
    let want = info_json(&ldt);
    let mut last = ldt.clone();
    // LDT → TM-33 → ATLA → IES → LDT, each read back with the same peak and flux.
    for (ext, to) in [
        ("xml", "tm33"),
        ("json", "atla"),
        ("ies", "ies"),
        ("ldt", "ldt"),
    ] {
        let out = dir.path().join(format!("step.{ext}"));
        let (code, _, err) = run_cli(&["ldt", "convert", s(&last), "--out", s(&out)], "");
        assert_eq!(code, 0, "{to}: {err}");
        let got = info_json(&out);
        for key in ["max_intensity", "flux_lm", "lamp_flux_lm"] {
            let (a, b) = (want[key].as_f64().unwrap(), got[key].as_f64().unwrap());
            assert!((a - b).abs() < 1e-4 * a, "{to} {key}: {a} vs {b}");
        }
        assert_eq!(got["symmetry"], want["symmetry"], "{to}");
        if ext == "xml" {
            // The luminous area's side heights are what TM-33 cannot hold of this file.
            assert!(
                err.contains("TM-33-23 XML cannot hold the luminous area's heights"),
                "{err}"
            );
            assert_eq!(got["format"], "tm33");
            assert_eq!(got["source"], "TM-33-23 XML");
        }
        last = out;
    }
    // --to writes next to the input, named after it.
    let copy = dir.path().join("grow.xml");
    std::fs::copy(tm33("grow_light.xml"), &copy).unwrap();
    let (code, _, err) = run_cli(&["ldt", "convert", s(&copy), "--to", "ldt"], "");
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("EULUMDAT cannot hold the spectral distribution"),
        "{err}"
    );
    assert!(dir.path().join("grow.ldt").is_file());
    let (code, _, err) = run_cli(&["ldt", "convert", s(&copy), "--to", "atla"], "");
    assert_eq!(code, 0, "{err}");
    let atla = info_json(&dir.path().join("grow.json"));
    assert_eq!(atla["tm33"]["dialect"], "atla-json");
    // The spectrum went along to ATLA.
    assert_eq!(
        atla["tm33"]["spectral"]["melanopic_der"],
        info_json(&copy)["tm33"]["spectral"]["melanopic_der"]
    );
}

#[test]
fn info_shows_the_spectral_figures() {
    let (code, out, err) = run_cli(
        &["ldt", "info", s(&tm33("tm33-23_horticultural_led.xml"))],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("data           TM-33-23 XML"), "{out}");
    assert!(out.contains("melanopic DER"), "{out}");
    assert!(out.contains("PPF"), "{out}");
    assert!(out.contains("µmol/J"), "{out}");
    // Spectra that do not span 400–700 nm give no PPF.
    let (_, out, _) = run_cli(
        &["ldt", "info", s(&tm33("tm33-23_far_red_supplemental.xml"))],
        "",
    );
    assert!(
        out.contains("melanopic DER") && !out.contains("PPF"),
        "{out}"
    );
    // The ATLA sample's two openings.
    let (_, out, _) = run_cli(&["ldt", "info", s(&tm33("sample-luminaire.xml"))], "");
    assert!(
        out.contains("openings       500 × 600 mm at (-100, 0) mm; 500 × 600 mm at (100, 0) mm"),
        "{out}"
    );
}

#[test]
fn check_plot_report_and_catalogues_take_tm33_files() {
    let dir = tempfile::tempdir().unwrap();
    let file = tm33("tm33-23_horticultural_led.xml");
    let (code, out, err) = run_cli(&["ldt", "check", s(&file), "--json"], "");
    assert_eq!(code, 0, "{err}");
    assert!(serde_json::from_str::<Value>(&out).is_ok(), "{out}");
    let svg = dir.path().join("polar.svg");
    let (code, _, err) = run_cli(&["ldt", "plot", s(&file), "--out", s(&svg)], "");
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let html = dir.path().join("sheet.html");
    let (code, _, err) = run_cli(&["ldt", "report", s(&file), "--out", s(&html)], "");
    assert_eq!(code, 0, "{err}");
    let sheet = std::fs::read_to_string(&html).unwrap();
    assert!(sheet.contains("Full Spectrum Horticultural LED Panel"));
    // The datasheet's summary carries the spectral figures.
    assert!(
        sheet.contains("melanopic DER") && sheet.contains("PPF"),
        "no spectral rows"
    );
    // A folder walk finds the 13 TM-33 documents beside the LDT (not the licence texts).
    let (code, out, err) = run_cli(
        &[
            "ldt",
            "info",
            "--csv",
            s(&shared_dir().join("luminaires/tm33")),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.lines().count(), 1 + 14, "{out}");
}

#[test]
fn a_tm33_luminaire_lights_a_scene_as_its_eulumdat_twin() {
    let dir = tempfile::tempdir().unwrap();
    let lux = |file: PathBuf| -> Vec<f64> {
        let scene = dir.path().join("s.toml");
        std::fs::write(
            &scene,
            format!(
                "[[luminaire]]\nfile = {:?}\nposition = [0.0, 0.0, 3.0]\n",
                file.display().to_string()
            ),
        )
        .unwrap();
        // Points in the C0 and C90 planes (the planes both files hold) on the floor.
        let points = "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1.5 0 0 0 1\n-2 0 0 0 0 1\n";
        let (code, out, err) = run_cli(
            &[
                "illuminance",
                s(&scene),
                "--cpu",
                "--shadows",
                "none",
                "--interp",
                "bilinear",
            ],
            points,
        );
        assert_eq!(code, 0, "{err}");
        out.lines().map(|l| l.parse().unwrap()).collect()
    };
    let ldt = lux(tm33("fluorescent_luminaire.ldt"));
    let xml = lux(tm33("fluorescent.xml"));
    assert_eq!(ldt.len(), 4);
    for (a, b) in ldt.iter().zip(&xml) {
        assert!(*a > 1.0 && (a - b).abs() < 1e-4 * a, "{ldt:?} vs {xml:?}");
    }
}

#[test]
fn a_bad_tm33_file_is_refused_with_element_and_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.xml");
    let text = std::fs::read_to_string(tm33("tm33-23_minimal.xml"))
        .unwrap()
        .replace("vert=\"30\">275<", "vert=\"30\">2,75<");
    std::fs::write(&bad, text).unwrap();
    let (code, _, err) = run_cli(&["ldt", "info", s(&bad)], "");
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("bad.xml: line 48: IntensityData: expected a number, found \"2,75\""),
        "{err}"
    );
    // Converting it writes nothing.
    let out = dir.path().join("out.ldt");
    let (code, _, _) = run_cli(&["ldt", "convert", s(&bad), "--out", s(&out)], "");
    assert_eq!(code, 2);
    assert!(!out.exists());
}
