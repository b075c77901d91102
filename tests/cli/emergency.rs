//! `calc --emergency` (EN 1838): a corridor under two emergency downlights whose
//! centre-line illuminance is the point-source sum, evaluated here from the luminaire file
//! (the luminaire without an emergency output stays dark); Emin, Emax and Emax/Emin and
//! the glare limit judged; a route too long for its luminaires fails 40:1; open and
//! high-risk areas and a point of safety equipment; bad input refused.

use crate::calc::s;
use crate::common::{calc_csv_rows, luminaire, run_cli};
use goniolight::photometry::{Interp, Luminaire};
use serde_json::Value;
use std::path::{Path, PathBuf};

const EMERGENCY_LM: f64 = 200.0;
const HEIGHT: f64 = 2.8;
const AT: [f64; 2] = [2.5, 7.5];

/// Two emergency downlights over a corridor along y = 1 and one normal luminaire between
/// them; no model, so no shadows: the light is the point-source sum.
fn corridor(dir: &Path, route_end: f64, extra: &str) -> PathBuf {
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    let path = dir.join("corridor.toml");
    let mut text = String::new();
    for x in AT {
        text.push_str(&format!(
            "[[luminaire]]\nfile = {lum:?}\nposition = [{x}, 1.0, {HEIGHT}]\nemergency_flux_lm = {EMERGENCY_LM}\n\n"
        ));
    }
    text.push_str(&format!(
        "[[luminaire]]\nfile = {lum:?}\nposition = [5.0, 1.0, {HEIGHT}]\n\n[[emergency]]\nname = \"corridor\"\nkind = \"route\"\nline = [[0.0, 1.0], [{route_end}, 1.0]]\nwidth = 2.0\n\n{extra}"
    ));
    std::fs::write(&path, text).unwrap();
    path
}

fn run(scene: &Path, out: &Path) -> Value {
    let report = out.with_extension("html");
    let (code, _, err) = run_cli(
        &[
            "calc",
            s(scene),
            "--out",
            s(out),
            "--emergency",
            "--cpu",
            "--report",
            s(&report),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    serde_json::from_slice(&std::fs::read(out.join("calc.json")).unwrap()).unwrap()
}

fn verdict<'d>(doc: &'d Value, area: &str, part: &str, quantity: &str) -> &'d Value {
    doc["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["area"] == area && r["part"] == part && r["quantity"] == quantity)
        .unwrap_or_else(|| panic!("no {area} {part} {quantity} in {}", doc["requirements"]))
}

/// The two emergency downlights' direct illuminance at `p` on a surface facing `n`.
fn point_source_sum(lum: &Luminaire, p: [f64; 3], n: [f64; 3]) -> f64 {
    let dimming = EMERGENCY_LM / lum.summary().flux_lm;
    AT.iter()
        .map(|&x| {
            let d = [x - p[0], 1.0 - p[1], HEIGHT - p[2]];
            let r = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let gamma = (d[2] / r).acos().to_degrees();
            let cos = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / r;
            lum.distribution
                .candela(0.0, gamma, Interp::CatmullRom, dimming)
                * cos.max(0.0)
                / (r * r)
        })
        .sum()
}

#[test]
fn a_corridors_centre_line_is_the_point_source_sum_and_judged_by_en1838() {
    let tmp = tempfile::tempdir().unwrap();
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let doc = run(&corridor(tmp.path(), 10.0, ""), &tmp.path().join("out"));
    let rows = calc_csv_rows(&tmp.path().join("out/corridor-centre-line.csv"));
    assert_eq!(rows.len(), 50); // 10 m at 0.2 m
    let want: Vec<f64> = rows
        .iter()
        .map(|r| point_source_sum(&lum, [r[0], r[1], r[2]], [0.0, 0.0, 1.0]))
        .collect();
    for (r, w) in rows.iter().zip(&want) {
        assert!((r[3] - w).abs() <= 1e-3 * w, "{r:?} vs {w}");
    }
    let (emin, emax) = want
        .iter()
        .fold((f64::MAX, 0.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let close = |v: &Value, w: f64| (v.as_f64().unwrap() - w).abs() <= 1e-3 * w;
    let line_min = verdict(&doc, "corridor", "centre line", "Emin");
    assert!(close(&line_min["achieved"], emin), "{line_min} vs {emin}");
    assert_eq!(line_min["required"], 1.0);
    assert_eq!(line_min["pass"], emin >= 1.0);
    assert_eq!(line_min["standard"], "EN 1838:2013");
    let ratio = verdict(&doc, "corridor", "centre line", "Emax/Emin");
    assert!(
        close(&ratio["achieved"], emax / emin),
        "{ratio} vs {}",
        emax / emin
    );
    assert_eq!(ratio["required"], 40.0);
    assert_eq!(ratio["pass"], true);
    let band = verdict(&doc, "corridor", "central band", "Emin");
    assert_eq!(band["required"], 0.5);
    let band_rows = calc_csv_rows(&tmp.path().join("out/corridor-central-band.csv"));
    assert!(band_rows.iter().all(|r| (r[1] - 1.0).abs() <= 0.5));

    // Glare: each emergency luminaire's highest intensity 60–90° against 900 cd (mounted
    // 2.5–3 m above the floor); only the two emergency luminaires are judged.
    let dimming = EMERGENCY_LM / lum.summary().flux_lm;
    let peak = (60..=90)
        .map(|g| {
            lum.distribution
                .candela(0.0, g as f64, Interp::CatmullRom, dimming)
        })
        .fold(0.0, f64::max);
    for k in 1..=2 {
        let g = verdict(&doc, &format!("L{k}"), "luminaire", "I 60-90°");
        assert_eq!(g["required"], 900.0);
        assert!(close(&g["achieved"], peak), "L{k}: {g} vs {peak}");
    }
    assert_eq!(
        doc["requirements"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["part"] == "luminaire")
            .count(),
        2
    );
    assert_eq!(doc["method"]["emergency"], true);
    assert_eq!(doc["method"]["light"], "direct light only");

    // Thirty metres: the far end is too dark for 40:1.
    let long = run(&corridor(tmp.path(), 30.0, ""), &tmp.path().join("long"));
    let ratio = verdict(&long, "corridor", "centre line", "Emax/Emin");
    assert_eq!(ratio["pass"], false, "{ratio}");
    let html = std::fs::read_to_string(tmp.path().join("long.html")).unwrap();
    assert!(html.contains("Verification (EN 1838:2013)"));
    assert!(
        html.contains("<tr class=\"fail\"><td>corridor</td><td>centre line</td><td>Emax/Emin</td>")
    );
}

#[test]
fn open_and_high_risk_areas_and_safety_points() {
    let tmp = tempfile::tempdir().unwrap();
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_06_isym1.ldt")).unwrap();
    let extra = "[[emergency]]\nname = \"hall\"\nkind = \"open-area\"\ncorner = [0.0, 0.0]\nsize = [10.0, 2.0]\nspacing = 0.5\n\n[[emergency]]\nname = \"saw\"\nkind = \"high-risk\"\ncorner = [2.0, 0.5]\nsize = [1.0, 1.0]\nheight = 0.9\nem = 500\n\n[[emergency]]\nname = \"extinguisher\"\nkind = \"point\"\nposition = [5.0, 0.0, 1.2]\nnormal = [0.0, 1.0, 0.0]\n\n[sky]\nmodel = \"uniform\"\ndiffuse_horizontal_lux = 10000\n";
    // A sky of 10 000 lx, which EN 1838 leaves out (the mains fail at night too): the
    // values below are the emergency luminaires' alone.
    let doc = run(&corridor(tmp.path(), 10.0, extra), &tmp.path().join("out"));
    // The open area less its 0.5 m border: 0.5 m cells, centres 0.75 … 9.25 by 0.75, 1.25.
    let hall = calc_csv_rows(&tmp.path().join("out/hall.csv"));
    assert_eq!(hall.len(), 18 * 2);
    let emin = verdict(&doc, "hall", "task", "Emin");
    let lowest = hall.iter().map(|r| r[3]).fold(f64::MAX, f64::min);
    let achieved = emin["achieved"].as_f64().unwrap();
    assert!((achieved - lowest).abs() < 1e-6, "{achieved} vs {lowest}");
    assert_eq!(emin["pass"], lowest >= 0.5);
    // High risk: at least 10 % of 500 lx and 15 lx → 50 lx; Emin/Emax at least 0.1.
    assert_eq!(verdict(&doc, "saw", "task", "Emin")["required"], 50.0);
    assert_eq!(verdict(&doc, "saw", "task", "g2")["required"], 0.1);
    // The extinguisher: the vertical illuminance on its front, 5 lx.
    let point = verdict(&doc, "extinguisher", "task", "Emin");
    let want = point_source_sum(&lum, [5.0, 0.0, 1.2], [0.0, 1.0, 0.0]);
    let got = point["achieved"].as_f64().unwrap();
    assert!((got - want).abs() <= 1e-3 * want, "{got} vs {want}");
    assert_eq!(point["required"], 5.0);
    assert_eq!(point["pass"], want >= 5.0);
}

#[test]
fn emergency_input_is_refused_by_key() {
    let tmp = tempfile::tempdir().unwrap();
    let lum = luminaire("eulumdat-plot/sample_06_isym1.ldt");
    let dark = tmp.path().join("dark.toml");
    std::fs::write(
        &dark,
        format!("[[luminaire]]\nfile = {lum:?}\nposition = [1.0, 1.0, 2.8]\n\n[[emergency]]\nname = \"c\"\nkind = \"route\"\nline = [[0, 1], [5, 1]]\nwidth = 1\n"),
    )
    .unwrap();
    let out = tmp.path().join("out");
    let (code, _, err) = run_cli(
        &["calc", s(&dark), "--out", s(&out), "--emergency", "--cpu"],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("emergency_flux_lm"), "{err}");
    let (code, _, err) = run_cli(
        &[
            "calc",
            s(&dark),
            "--out",
            s(&out),
            "--emergency",
            "--indirect",
            "radiosity",
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    for (extra, key) in [
        ("[[emergency]]\nname = \"w\"\nkind = \"route\"\nline = [[0, 1], [5, 1]]\nwidth = 3\n", "emergency[0].width"),
        ("[[emergency]]\nname = \"w\"\nkind = \"route\"\nline = [[0, 1]]\nwidth = 1\n", "emergency[0].line"),
        ("[[emergency]]\nname = \"h\"\nkind = \"high-risk\"\ncorner = [0, 0]\nsize = [1, 1]\n", "emergency[0].em"),
        ("[[emergency]]\nname = \"p\"\nkind = \"point\"\nposition = [1, 1, 1]\nnormal = [0, 0, 1]\n", "emergency[0].normal"),
        ("[[emergency]]\nname = \"p\"\nkind = \"open-area\"\ncorner = [0, 0]\nsize = [1, 1]\nwidth = 2\n", "emergency[0].width"),
        ("[[luminaire]]\nfile = \"LUM\"\nposition = [1, 1, 2]\nemergency_flux_lm = 100\nballast_lumen_factor = 0.1\n", "luminaire[0].ballast_lumen_factor"),
        ("[[luminaire]]\nfile = \"LUM\"\nposition = [1, 1, 2]\nballast_lumen_factor = 1.5\n", "luminaire[0].ballast_lumen_factor"),
        ("[[luminaire]]\nfile = \"LUM\"\nposition = [1, 1, 2]\nemergency_flux_lm = 100000\n", "luminaire[0].emergency_flux_lm"),
    ] {
        let scene = tmp.path().join("bad.toml");
        std::fs::write(&scene, extra.replace("LUM", s(&lum))).unwrap();
        let (code, _, err) = run_cli(&["calc", s(&scene), "--out", s(&out), "--emergency", "--cpu"], "");
        assert_eq!(code, 2, "{extra}: {err}");
        assert!(err.contains("bad.toml") && err.contains(key), "{key}: {err}");
        assert!(!out.exists());
    }
}
