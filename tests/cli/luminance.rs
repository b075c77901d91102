//! `ldt luminance` against Relux's luminance tables of the ten lab files in
//! `luminaires/eulumdat-luminance` (`relux_luminance_reference.json`, exported from Relux
//! Desktop): every value within the file's stated tolerance (3 % above 10 cd/m², 10 cd/m²
//! absolute below, for Relux rounds to whole cd/m²).

use crate::common;

use common::{luminaire, run_cli};
use serde_json::Value;

fn reference() -> Value {
    let text = std::fs::read_to_string(luminaire(
        "eulumdat-luminance/relux_luminance_reference.json",
    ))
    .unwrap();
    serde_json::from_str(&text).unwrap()
}

#[test]
fn luminance_tables_agree_with_relux() {
    let reference = reference();
    let rel = reference["tolerance"]["relative_percent"].as_f64().unwrap() / 100.0;
    let abs = reference["tolerance"]["absolute_cd_m2"].as_f64().unwrap();
    assert_eq!((rel, abs), (0.03, 10.0));
    let samples = reference["samples"].as_object().unwrap();
    assert_eq!(samples.len(), 10);
    let mut worst = 0.0f64;
    for (name, sample) in samples {
        let file = luminaire(&format!("eulumdat-luminance/{name}.ldt"));
        let (code, out, err) = run_cli(&["ldt", "luminance", file.to_str().unwrap(), "--json"], "");
        assert_eq!(code, 0, "{name}: {err}");
        let ours: Value = serde_json::from_str(&out).unwrap();
        let cs = ours["c_angles"].as_array().unwrap();
        let gs = ours["gamma_angles"].as_array().unwrap();
        assert_eq!(cs.len(), 24);
        assert_eq!(gs.len(), 5);
        assert_eq!(
            ours["cd_m2"].as_array().unwrap().len(),
            24,
            "one array per C angle"
        );
        for (gi, g) in gs.iter().enumerate() {
            let key = format!("{}", g.as_f64().unwrap());
            let row = sample["table"][&key].as_array().unwrap();
            for (ci, c) in cs.iter().enumerate() {
                let want = row[ci].as_f64().unwrap();
                let got = ours["cd_m2"][ci][gi].as_f64().unwrap();
                let ok = if want > abs {
                    (got - want).abs() <= rel * want
                } else {
                    (got - want).abs() <= abs
                };
                assert!(ok, "{name} C{c} γ{g}: {got:.1} cd/m², Relux {want}");
                if want > abs {
                    worst = worst.max((got - want).abs() / want);
                }
            }
        }
        let max = ours["cd_m2"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()))
            .fold(0.0, f64::max);
        let want = sample["maximum"].as_f64().unwrap();
        assert!(
            (max - want).abs() <= rel * want,
            "{name}: max {max} vs {want}"
        );
    }
    // Most values agree far better than the tolerance: the small ones carry Relux's
    // rounding to whole cd/m².
    assert!(worst < 0.025, "worst relative difference {worst}");
}

#[test]
fn lamp_set_choice_scales_the_table_and_bad_choices_are_refused() {
    // sample_06 has two lamp sets: 1983 lm and 2643 lm.
    let file = luminaire("eulumdat-luminance/sample_06.ldt");
    let f = file.to_str().unwrap();
    let table = |extra: &[&str]| -> Value {
        let mut args = vec!["ldt", "luminance", f, "--json"];
        args.extend(extra);
        let (code, out, err) = run_cli(&args, "");
        assert_eq!(code, 0, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    let first = table(&[]);
    let second = table(&["--lamp-set", "2"]);
    assert_eq!(first["flux_lm"], 1983.0);
    assert_eq!(second["flux_lm"], 2643.0);
    let a = first["cd_m2"][3][2].as_f64().unwrap();
    let b = second["cd_m2"][3][2].as_f64().unwrap();
    assert!((b / a - 2643.0 / 1983.0).abs() < 1e-12);
    let (code, _, err) = run_cli(&["ldt", "luminance", f, "--lamp-set", "3"], "");
    assert_eq!(code, 2);
    assert!(
        err.contains("sample_06.ldt")
            && err.contains("--lamp-set 3 is not in the file: it has 2 lamp set"),
        "{err}"
    );
    // Lower rows for datasheets: γ 45–85°.
    let wide = table(&["--gamma-from", "45"]);
    assert_eq!(wide["gamma_angles"].as_array().unwrap().len(), 9);
    assert_eq!(
        wide["cd_m2"][0][4], first["cd_m2"][0][0],
        "γ65 is the same value"
    );
    let (code, _, err) = run_cli(&["ldt", "luminance", f, "--gamma-from", "47"], "");
    assert_eq!(code, 2, "{err}");
}

#[test]
fn a_file_without_luminous_area_is_refused_by_name() {
    // An IES point opening (width = length = height = 0) has no area to divide by.
    let file = luminaire("photometric-viewer/ies95/point_opening.ies");
    let (code, out, err) = run_cli(&["ldt", "luminance", file.to_str().unwrap()], "");
    assert_eq!(code, 2, "{out}");
    assert!(
        err.contains("point_opening.ies") && err.contains("no luminous area"),
        "{err}"
    );
}
