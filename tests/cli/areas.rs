//! `calc` with EN 12464-1 areas (`[[area]]`): the generated grids, the requirements
//! (given and derived by the standard's relations) judged against the grids' values and
//! against `illuminance` at the same points, the verdict flipping at the limit, the
//! method recorded, the report's verification table, and bad areas refused by key.

use crate::calc::{room_scene, s};
use crate::common::{calc_csv_rows, run_cli};
use serde_json::Value;
use std::path::Path;

const DESK: &str = "[[area]]\nname = \"desk\"\ncorner = [2.2, 1.6]\nsize = [1.6, 0.8]\nheight = 0.75\nu0 = 0.6\nra = 80\n";

fn calc(scene: &Path, out: &Path, report: Option<&Path>) -> (Value, String) {
    let mut args = vec!["calc", s(scene), "--out", s(out), "--cpu"];
    if let Some(r) = report {
        args.extend(["--report", s(r)]);
    }
    let (code, stdout, err) = run_cli(&args, "");
    assert_eq!(code, 0, "{err}");
    let doc = serde_json::from_slice(&std::fs::read(out.join("calc.json")).unwrap()).unwrap();
    (doc, stdout)
}

fn grid_names(doc: &Value) -> Vec<&str> {
    doc["grids"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["name"].as_str().unwrap())
        .collect()
}

fn grid<'d>(doc: &'d Value, name: &str) -> &'d Value {
    doc["grids"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["name"] == name)
        .unwrap_or_else(|| panic!("no grid {name:?} in {}", doc["grids"]))
}

fn verdict<'d>(doc: &'d Value, part: &str, quantity: &str) -> &'d Value {
    doc["requirements"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["part"] == part && r["quantity"] == quantity)
        .unwrap_or_else(|| panic!("no {part} {quantity} in {}", doc["requirements"]))
}

#[test]
fn task_area_requirements_are_judged_on_its_grids_and_flip_at_the_limit() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = room_scene(
        tmp.path(),
        &format!("[calc]\nmaintenance_factor = 0.8\n\n{DESK}em = 500\n"),
    );
    let out = tmp.path().join("out");
    let report = tmp.path().join("out/report.html");
    let (doc, stdout) = calc(&scene, &out, Some(&report));
    assert_eq!(
        grid_names(&doc),
        ["desk", "desk surrounding", "desk background"]
    );

    // The task's values against `illuminance` at the same points, times the MF.
    let rows = calc_csv_rows(&out.join("desk.csv"));
    let stdin: String = rows
        .iter()
        .map(|r| format!("{} {} {} 0 0 1\n", r[0], r[1], r[2]))
        .collect();
    let (code, lux, err) = run_cli(
        &["illuminance", s(&scene), "--cpu", "--shadows", "volumes"],
        &stdin,
    );
    assert_eq!(code, 0, "{err}");
    let lux: Vec<f64> = lux
        .lines()
        .map(|l| 0.8 * l.parse::<f64>().unwrap())
        .collect();
    let em = lux.iter().sum::<f64>() / lux.len() as f64;
    let u0 = lux.iter().copied().fold(f64::MAX, f64::min) / em;
    let task_em = verdict(&doc, "task", "Em");
    assert!((task_em["achieved"].as_f64().unwrap() - em).abs() < 1e-6 * em);
    assert!((verdict(&doc, "task", "U0")["achieved"].as_f64().unwrap() - u0).abs() < 1e-6);

    // Every verdict: the grid's statistic, the limit given or derived, pass = the test.
    let want = [
        ("task", "Em", 500.0, "given"),
        ("task", "U0", 0.6, "given"),
        ("surrounding", "Em", 300.0, "EN 12464-1"),
        ("surrounding", "U0", 0.4, "EN 12464-1"),
        ("background", "Em", 100.0, "EN 12464-1"),
        ("background", "U0", 0.1, "EN 12464-1"),
    ];
    for (part, quantity, required, basis) in want {
        let v = verdict(&doc, part, quantity);
        assert_eq!(v["required"].as_f64().unwrap(), required, "{v}");
        assert!(v["basis"].as_str().unwrap().starts_with(basis), "{v}");
        let g = grid(&doc, v["grid"].as_str().unwrap());
        let stat = g[quantity.to_lowercase().as_str()].as_f64().unwrap();
        assert_eq!(v["achieved"].as_f64().unwrap(), stat, "{v}");
        assert_eq!(v["pass"].as_bool().unwrap(), stat >= required, "{v}");
    }
    // The sample file states no colour rendering index: unknown, not passed.
    let ra = verdict(&doc, "task", "Ra");
    assert!(ra["achieved"].is_null() && ra["pass"].is_null(), "{ra}");
    assert!(
        ra["note"].as_str().unwrap().contains("sample_06_isym1.ldt"),
        "{ra}"
    );
    assert_eq!(doc["requirements"].as_array().unwrap().len(), 7);

    // The method a reviewer needs.
    let method = &doc["method"];
    assert!(method["standards"][0]
        .as_str()
        .unwrap()
        .starts_with("EN 12464-1:2021"));
    assert_eq!(method["maintenance_factor"], 0.8);
    assert_eq!(method["light"], "direct light only");
    assert!(method["software"]
        .as_str()
        .unwrap()
        .ends_with(env!("CARGO_PKG_VERSION")));
    assert!(method["grid_rule"].as_str().unwrap().contains("5^log10(d)"));

    // Printed, and in the report's verification table, coloured by outcome.
    assert!(
        stdout.contains("desk") && stdout.contains("surrounding"),
        "{stdout}"
    );
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(html.contains("Verification (EN 12464-1:2021)"));
    assert!(html.contains("<tr class=\"unknown\">"));

    // The task's Em a hundredth of a lux above and below what it achieves.
    let achieved = task_em["achieved"].as_f64().unwrap();
    for (em, pass) in [(achieved + 0.01, false), (achieved - 0.01, true)] {
        let scene = room_scene(
            tmp.path(),
            &format!("[calc]\nmaintenance_factor = 0.8\n\n{DESK}em = {em}\n"),
        );
        let out = tmp.path().join(format!("out-{pass}"));
        let report = tmp.path().join(format!("report-{pass}.html"));
        let (doc, _) = calc(&scene, &out, Some(&report));
        assert_eq!(verdict(&doc, "task", "Em")["pass"], pass, "em {em}");
        let row = if pass { "pass" } else { "fail" };
        let html = std::fs::read_to_string(&report).unwrap();
        assert!(html.contains(&format!(
            "<tr class=\"{row}\"><td>desk</td><td>task</td><td>Em</td>"
        )));
    }
}

#[test]
fn a_plain_area_has_its_own_grid_and_a_cylindrical_one() {
    let tmp = tempfile::tempdir().unwrap();
    let scene = room_scene(
        tmp.path(),
        "[[area]]\nname = \"hall\"\nkind = \"area\"\noutline = [[0.5, 0.5], [5.5, 0.5], [5.5, 3.5], [0.5, 3.5]]\nheight = 0.0\nem = 50\nez = 30\nez_height = 1.6\n",
    );
    let (doc, _) = calc(&scene, &tmp.path().join("out"), None);
    assert_eq!(grid_names(&doc), ["hall", "hall Ez"]);
    assert_eq!(grid(&doc, "hall Ez")["kind"], "cylindrical");
    let rows = calc_csv_rows(&tmp.path().join("out/hall-Ez.csv"));
    assert!(rows.iter().all(|r| r[2] == 1.6));
    let ez = verdict(&doc, "cylindrical", "Ez");
    assert_eq!(ez["achieved"], grid(&doc, "hall Ez")["em"]);
    assert_eq!(doc["requirements"].as_array().unwrap().len(), 2);
}

#[test]
fn bad_areas_are_refused_by_key() {
    let tmp = tempfile::tempdir().unwrap();
    let rect = "corner = [2.0, 1.0]\nsize = [1.0, 1.0]\n";
    for (extra, key) in [
        (format!("[[area]]\nname = \"a\"\n{rect}"), "area[0].em"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nsurrounding_width = 0.3\n"), "area[0].surrounding_width"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nbackground_width = 2\n"), "area[0].background_width"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nu0 = 1.5\n"), "area[0].u0"),
        ("[[area]]\nname = \"a\"\nem = 500\noutline = [[1, 1], [3, 1], [3, 2], [2, 2], [2, 3], [1, 3]]\n".into(), "area[0].outline"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nugr_l = 19\n"), "area[0].ugr_l"),
        (format!("[[area]]\nname = \"a\"\nkind = \"area\"\n{rect}em = 500\nsurrounding_em = 100\n"), "area[0].surrounding_em"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nroom = [[10, 10], [12, 10], [12, 12]]\n"), "area[0].corner"),
        (format!("[[grid]]\nname = \"a surrounding\"\n{rect}\n[[area]]\nname = \"a\"\n{rect}em = 500\n"), "area[0].name"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\n\n[[area]]\nname = \"A\"\n{rect}em = 500\n"), "area[1].name"),
        (format!("[[area]]\nname = \"a\"\n{rect}em = 500\nlevel = 3\n"), "level"),
    ] {
        let scene = room_scene(tmp.path(), &extra);
        let out = tmp.path().join("refused");
        let (code, _, err) = run_cli(&["calc", s(&scene), "--out", s(&out), "--cpu"], "");
        assert_eq!(code, 2, "{extra}: {err}");
        assert!(err.contains("room.toml") && err.contains(key), "{key}: {err}");
        assert!(!out.exists());
    }
}
