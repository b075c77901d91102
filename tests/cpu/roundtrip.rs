//! Writers round-trip: LDT → LDT exactly, LDT → IES → LDT within print precision.

use crate::common;

use common::{all_luminaire_files, files_with};
use goniolight::photometry::ies::write_ies;
use goniolight::photometry::{Eulumdat, Interp, Luminaire};

#[test]
fn ldt_to_ldt_is_exact_for_every_file() {
    for path in all_luminaire_files() {
        let lum = Luminaire::load(&path).unwrap();
        let text = lum.data.to_ldt_string();
        let back = Eulumdat::parse("written.ldt", text.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(back.data, lum.data, "{}", path.display());
    }
}

#[test]
fn ldt_to_ies_to_ldt_keeps_the_candela() {
    for path in all_luminaire_files() {
        let lum = Luminaire::load(&path).unwrap();
        let ies = write_ies(&lum.data, "EULUMDAT");
        let back = Luminaire::from_bytes("written.ies", ies.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e}\n{ies}", path.display()));
        assert_eq!(back.data.symmetry, lum.data.symmetry, "{}", path.display());
        assert_eq!(back.data.gamma_angles, lum.data.gamma_angles);
        let (a, b) = (&lum.distribution, &back.distribution);
        if lum.data.symmetry != goniolight::photometry::Symmetry::Rotational {
            // (IES stores a rotational luminaire as one plane however many the LDT lists.)
            assert_eq!(
                a.grid().c_angles(),
                b.grid().c_angles(),
                "{}",
                path.display()
            );
        }
        let peak = a.candela(0.0, 0.0, Interp::Nearest, 1.0).max(1.0);
        for (ci, &c) in a.grid().c_angles().iter().enumerate() {
            for (gi, &g) in a.grid().gamma_angles().iter().enumerate() {
                let want = a.grid().value(ci, gi) * a.lamp_flux_lm() / 1000.0;
                let got = b.candela(c, g, Interp::Nearest, 1.0);
                // IES values are printed with six decimals.
                assert!(
                    (got - want).abs() <= 1e-6 + 1e-9 * peak,
                    "{} C{c} γ{g}: {want} → {got}",
                    path.display()
                );
            }
        }
        // Relative files keep their lamp flux and so their cd/klm.
        if !lum.data.is_absolute() {
            assert!((back.data.lamp_flux_lm() - lum.data.lamp_flux_lm()).abs() < 1e-6);
        }
    }
}

#[test]
fn ies_to_ldt_to_ies_keeps_the_candela() {
    for path in all_luminaire_files() {
        if path.extension().unwrap() != "ies" {
            continue;
        }
        let lum = Luminaire::load(&path).unwrap();
        let ldt = lum.data.to_ldt_string();
        let back = Luminaire::from_bytes("written.ldt", ldt.as_bytes()).unwrap();
        for c in [0.0, 45.0, 90.0, 200.0] {
            for g in [0.0, 12.5, 47.5, 90.0] {
                let (x, y) = (
                    lum.distribution.candela(c, g, Interp::CatmullRom, 1.0),
                    back.distribution.candela(c, g, Interp::CatmullRom, 1.0),
                );
                assert!(
                    (x - y).abs() < 1e-9 * x.max(1.0),
                    "{} C{c} γ{g}",
                    path.display()
                );
            }
        }
    }
}

/// EULUMDAT's field widths in file order, from the format description (not from the
/// writer): lines 1–26, six lines per lamp set, ten direct ratios, then every angle and
/// intensity with 6 characters.
fn ldt_widths(sets: usize, mc: usize, ng: usize, values: usize) -> Vec<usize> {
    let mut w = vec![78, 1, 1, 2, 5, 2, 5, 78, 78, 78, 8, 78];
    w.extend([4; 11]); // lines 13–23: dimensions, DFF, LORL
    w.extend([6, 6, 4]); // conversion factor, tilt, number of lamp sets
    for _ in 0..sets {
        w.extend([4, 24, 12, 16, 6, 8]);
    }
    w.extend([7; 10]);
    w.extend(std::iter::repeat_n(6, mc + ng + values));
    w
}

/// Half a unit in the last decimal the text shows.
fn half_unit(text: &str) -> f64 {
    let decimals = text.split_once('.').map_or(0, |(_, f)| f.len());
    0.5 * 10f64.powi(-(decimals as i32))
}

#[test]
fn ies_to_standard_ldt_fits_the_widths_and_keeps_intensities_within_the_written_precision() {
    let wild = files_with(&common::shared_dir().join("luminaires/wild"), &["ies"]);
    let files: Vec<_> = all_luminaire_files()
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ies")))
        .chain(wild)
        .collect();
    assert!(files.len() > 100, "{} IES files", files.len());
    let mut cut_names = 0;
    for path in &files {
        let Ok(lum) = Luminaire::load(path) else {
            continue; // the wild corpus test covers what is refused and why
        };
        let std_ldt = lum
            .data
            .to_ldt_standard()
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let lines: Vec<&str> = std_ldt.text.split("\r\n").collect();
        assert_eq!(
            lines.last(),
            Some(&""),
            "{}: ends with CRLF",
            path.display()
        );
        let lines = &lines[..lines.len() - 1];
        let d = &lum.data;
        let values: usize = d.intensities.iter().map(Vec::len).sum();
        let widths = ldt_widths(d.lamp_sets.len(), d.mc(), d.ng(), values);
        assert_eq!(lines.len(), widths.len(), "{}", path.display());
        for (i, (line, w)) in lines.iter().zip(&widths).enumerate() {
            let counted = matches!(i + 1, 4 | 6); // Mc, Ng: a count is written in full…
            let noted = std_ldt
                .notes
                .iter()
                .any(|n| n.starts_with(&format!("line {} (", i + 1)));
            assert!(
                line.chars().count() <= *w || (counted && noted),
                "{} line {}: {line:?} is wider than {w}",
                path.display(),
                i + 1
            );
        }
        cut_names += std_ldt
            .notes
            .iter()
            .filter(|n| n.contains(" cut to "))
            .count();
        // Back in: every intensity within half a unit of the decimals written.
        let back = Eulumdat::parse("written.ldt", std_ldt.text.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .data;
        let first_value = lines.len() - values;
        let written = &lines[first_value..];
        let stored = d.intensities.iter().flatten();
        let read = back.intensities.iter().flatten();
        let mut worst_cd = 0.0f64;
        for ((text, want), got) in written.iter().zip(stored).zip(read) {
            let tol = half_unit(text) * (1.0 + 1e-9);
            assert!(
                (got - want).abs() <= tol,
                "{}: {want} cd/klm written as {text:?}, read {got}",
                path.display()
            );
            worst_cd = worst_cd.max(tol);
        }
        // …and out to IES again: the candela of the original within that precision.
        let ies = write_ies(&back, "EULUMDAT");
        let again = Luminaire::from_bytes("again.ies", ies.as_bytes())
            .unwrap_or_else(|e| panic!("{}: {e}\n{ies}", path.display()));
        let (a, b) = (&lum.distribution, &again.distribution);
        let cd_per_cdklm = a.lamp_flux_lm() / 1000.0;
        let angle_tol = 0.5e-4;
        for (ci, &c) in a.grid().c_angles().iter().enumerate() {
            for (gi, &g) in a.grid().gamma_angles().iter().enumerate() {
                let want = a.grid().value(ci, gi) * cd_per_cdklm;
                let got = b.candela(c, g, Interp::Nearest, 1.0);
                assert!(
                    (got - want).abs() <= worst_cd * cd_per_cdklm * (1.0 + 1e-6) + 1e-9,
                    "{} C{c} γ{g}: {want} cd → {got} cd",
                    path.display()
                );
            }
        }
        for (x, y) in d.gamma_angles.iter().zip(&back.gamma_angles) {
            assert!(
                (x - y).abs() <= angle_tol,
                "{}: γ {x} → {y}",
                path.display()
            );
        }
    }
    // The bundled IES files carry long names: cutting them is what is being checked.
    assert!(cut_names > 0);
}

#[test]
fn convert_writes_standard_widths_by_default_and_exact_numbers_with_exact() {
    let dir = tempfile::tempdir().unwrap();
    let src = common::luminaire("photometric-viewer/ies95/imperial_units.ies");
    let lum = Luminaire::load(&src).unwrap();
    let s = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let (std_out, exact_out) = (dir.path().join("a.ldt"), dir.path().join("b.ldt"));
    let (code, _, err) = common::run_cli(&["ldt", "convert", &s(&src), "--out", &s(&std_out)], "");
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&std_out).unwrap();
    assert_eq!(text, lum.data.to_ldt_standard().unwrap().text);
    assert!(text.split("\r\n").all(|l| l.chars().count() <= 78));
    let (code, _, err) = common::run_cli(
        &[
            "ldt",
            "convert",
            &s(&src),
            "--out",
            &s(&exact_out),
            "--exact",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let back = Eulumdat::parse("b.ldt", &std::fs::read(&exact_out).unwrap()).unwrap();
    assert_eq!(back.data, lum.data);
    // The two differ: the IES → cd/klm conversion leaves digits that 6 characters cannot hold.
    assert_ne!(std::fs::read(&exact_out).unwrap(), text.as_bytes());
}

#[test]
fn standard_ldt_refuses_a_number_no_rounding_fits() {
    let path = all_luminaire_files()
        .into_iter()
        .find(|p| p.extension().unwrap() == "ldt")
        .unwrap();
    let mut data = Luminaire::load(&path).unwrap().data;
    data.intensities[0][1] = 2.5e6;
    let err = data.to_ldt_standard().unwrap_err();
    let g = goniolight::photometry::text::exact(data.gamma_angles[1]);
    assert!(err.field.starts_with("line 30 (intensity C"), "{err}");
    assert!(err.field.ends_with(&format!("γ{g})")), "{err}");
    assert!(
        err.reason.contains("2500000 does not fit EULUMDAT's 6"),
        "{err}"
    );
    assert!(err.to_string().contains("`exact`"), "{err}");
    // The exact writer keeps it.
    assert!(data.to_ldt_string().contains("2500000\r\n"));
}

#[test]
fn standard_ldt_refuses_angles_closer_than_its_precision() {
    let path = all_luminaire_files()
        .into_iter()
        .find(|p| p.extension().unwrap() == "ldt")
        .unwrap();
    let mut data = Luminaire::load(&path).unwrap().data;
    data.gamma_angles[1] = data.gamma_angles[0] + 1e-7;
    data.dg = 0.0;
    let err = data.to_ldt_standard().unwrap_err();
    assert!(err.reason.contains("would not read back"), "{err}");
    let back = Eulumdat::parse("x.ldt", data.to_ldt_string().as_bytes()).unwrap();
    assert_eq!(back.data, data);
}
