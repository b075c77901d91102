//! Every bundled luminaire parses, and each symmetry expands to the full circle exactly as
//! the format says — checked against an independent reading of the files' own numbers.

use crate::common;

use common::{all_luminaire_files, luminaire, raw_ldt};
use goniolight::photometry::{Luminaire, Symmetry};

/// The full-circle plane at C for the stored planes of a file, written out per Isym from
/// the format description (independently of the library's symmetry code).
fn expected_plane(isym: u8, c_angles: &[f64], stored: &[Vec<f64>], c: f64) -> Vec<f64> {
    let mc = c_angles.len();
    let index_of = |a: f64| {
        c_angles
            .iter()
            .position(|&x| ((x - a).rem_euclid(360.0)).min((a - x).rem_euclid(360.0)) < 1e-6)
            .unwrap()
    };
    match isym {
        0 => stored[index_of(c)].clone(),
        1 => stored[0].clone(),
        2 => {
            let m = if c <= 180.0 { c } else { 360.0 - c };
            stored[index_of(m)].clone()
        }
        3 => {
            // Stored: C270, …, C350, C0, …, C90 (Mc/2 + 1 planes).
            let m = if c >= 270.0 || c <= 90.0 {
                c
            } else {
                (180.0 - c).rem_euclid(360.0)
            };
            let k = (index_of(m) + mc - 3 * mc / 4) % mc;
            stored[k].clone()
        }
        4 => {
            let h = if c <= 180.0 { c } else { 360.0 - c };
            let q = if h <= 90.0 { h } else { 180.0 - h };
            stored[index_of(q)].clone()
        }
        _ => unreachable!(),
    }
}

#[test]
fn every_bundled_file_parses_with_a_plausible_summary() {
    for path in all_luminaire_files() {
        let lum = Luminaire::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let s = lum.summary();
        assert!(s.max_intensity > 0.0, "{}", path.display());
        assert!(
            s.flux_lm.is_finite() && s.flux_lm > 0.0,
            "{}",
            path.display()
        );
        assert!(
            (0.0..=100.0 + 1e-9).contains(&s.dff_computed),
            "{}",
            path.display()
        );
    }
}

#[test]
fn expansion_matches_the_format_for_every_ldt_file() {
    let mut seen = [0usize; 5];
    for path in all_luminaire_files() {
        if path.extension().unwrap() != "ldt" {
            continue;
        }
        let (isym, c, _g, stored) = raw_ldt(&path);
        let lum = Luminaire::load(&path).unwrap();
        seen[isym as usize] += 1;
        let grid = lum.distribution.grid();
        let n = grid.gamma_angles().len();
        for (ci, &angle) in grid.c_angles().iter().enumerate() {
            let want = expected_plane(isym, &c, &stored, angle);
            // Poles may be unified (warned); compare the interior angles exactly.
            for (gi, w) in want.iter().enumerate().take(n - 1).skip(1) {
                assert_eq!(
                    grid.value(ci, gi),
                    *w,
                    "{} C{angle} γ index {gi}",
                    path.display()
                );
            }
        }
    }
    assert!(seen.iter().all(|&n| n >= 2), "each Isym covered: {seen:?}");
}

#[test]
fn isym3_stores_c270_to_c90_and_is_not_mirrored() {
    // Synthetic file: every stored plane distinct, 10° steps, Mc = 36.
    let path = luminaire("photometric-viewer/ldt/symmetry_to_c90c270.ldt");
    let (_, _, _, stored) = raw_ldt(&path);
    assert_eq!(stored.len(), 19);
    let lum = Luminaire::load(&path).unwrap();
    assert_eq!(lum.data.symmetry, Symmetry::C90C270);
    let grid = lum.distribution.grid();
    let plane = |c: f64| grid.plane(grid.c_angles().iter().position(|&a| a == c).unwrap());
    // (The grid may close a lit γ edge with one more zero column: compare the file's span.)
    let n = stored[0].len();
    let interior = |p: &[f64]| p[1..n - 1].to_vec();
    // First stored plane is C270, the tenth C0, the last C90.
    assert_eq!(interior(plane(270.0)), interior(&stored[0]));
    assert_eq!(interior(plane(0.0)), interior(&stored[9]));
    assert_eq!(interior(plane(90.0)), interior(&stored[18]));
    // Reading it as C0 → C180 would put stored[0] at C0: it must not be there.
    assert_ne!(interior(plane(0.0)), interior(&stored[0]));
    // Mirror about the C90–C270 plane.
    for (a, b) in [(100.0, 80.0), (180.0, 0.0), (200.0, 340.0), (250.0, 290.0)] {
        assert_eq!(plane(a), plane(b), "C{a} mirrors C{b}");
    }
    // A real Isym 3 file: C0 and C180 coincide, C90 and C270 differ.
    let lum = Luminaire::load(&luminaire("eulumdat-plot/sample_01_isym3.ldt")).unwrap();
    let d = &lum.distribution;
    use goniolight::photometry::Interp::Bilinear;
    assert_eq!(
        d.sample(0.0, 40.0, Bilinear),
        d.sample(180.0, 40.0, Bilinear)
    );
    assert!((d.sample(90.0, 40.0, Bilinear) - d.sample(270.0, 40.0, Bilinear)).abs() > 1.0);
}

#[test]
fn multiple_lamp_sets_are_read_set_by_set() {
    let lum = Luminaire::load(&luminaire("photometric-viewer/ldt/multiple_lamp_sets.ldt")).unwrap();
    let sets = &lum.data.lamp_sets;
    assert_eq!(sets.len(), 3);
    assert_eq!(
        sets.iter()
            .map(|s| (s.count, s.flux_lm, s.watts))
            .collect::<Vec<_>>(),
        vec![(1, 500.0, 15.0), (2, 1200.0, 30.0), (1, 500.0, 15.0)]
    );
    assert_eq!(sets[1].lamp_type, "Double Lamp");
    assert_eq!(sets[2].color, "5000");
    assert_eq!(lum.data.lamp_flux_lm(), 2200.0);
    assert_eq!(lum.summary().lamp_flux_lm, 2200.0);
    // Two lamp sets in a real lab file.
    let lum = Luminaire::load(&luminaire("eulumdat-luminance/sample_06.ldt")).unwrap();
    assert_eq!(lum.data.lamp_sets.len(), 2);
}

#[test]
fn absolute_photometry_ldt_and_ies() {
    let abs = Luminaire::load(&luminaire("photometric-viewer/ldt/absolute.ldt")).unwrap();
    let rel = Luminaire::load(&luminaire("photometric-viewer/ldt/relative.ldt")).unwrap();
    assert!(abs.data.is_absolute() && !rel.data.is_absolute());
    assert_eq!(abs.data.lamp_sets[0].count, -2);
    // Same numbers, so the same candela: absolute photometry only marks the data.
    assert_eq!(
        abs.distribution.grid().values(),
        rel.distribution.grid().values()
    );
    let ies_abs = Luminaire::load(&luminaire(
        "photometric-viewer/ies95/absolute_photometry.ies",
    ))
    .unwrap();
    assert!(ies_abs.data.is_absolute());
    // Lamp flux := integrated flux, so LORL is 100 % and candela are preserved.
    let s = ies_abs.summary();
    assert!(
        (s.lorl_computed - 100.0).abs() < 1e-9,
        "{}",
        s.lorl_computed
    );
    let cd = ies_abs
        .distribution
        .candela(0.0, 0.0, goniolight::photometry::Interp::Bilinear, 1.0);
    assert!((cd - 2200.0).abs() < 1e-9, "{cd}");
}

#[test]
fn ies_multiplier_units_and_openings() {
    use goniolight::photometry::ies::OpeningShape::*;
    let rel = Luminaire::load(&luminaire(
        "photometric-viewer/ies95/relative_photometry.ies",
    ))
    .unwrap();
    let mul = Luminaire::load(&luminaire(
        "photometric-viewer/ies95/relative_photometry_with_multiplier.ies",
    ))
    .unwrap();
    let b = goniolight::photometry::Interp::Bilinear;
    let (a, m) = (
        rel.distribution.candela(0.0, 10.0, b, 1.0),
        mul.distribution.candela(0.0, 10.0, b, 1.0),
    );
    assert!((m / a - 1.5).abs() < 1e-12, "multiplier 1.5: {a} → {m}");
    // 2200 cd at nadir, 1 lamp of 500 lm → 4400 cd/klm.
    assert!((rel.distribution.sample(0.0, 0.0, b) - 4400.0).abs() < 1e-9);
    let cases = [
        (
            "imperial_units.ies",
            RectangularWithSides,
            [0.12 * 0.3048, 0.34 * 0.3048],
        ),
        ("metric_units.ies", RectangularWithSides, [0.12, 0.34]),
        ("point_opening.ies", Point, [0.0, 0.0]),
        ("rectangular_opening.ies", Rectangular, [f64::NAN; 2]),
        (
            "rectangular_opening_with_height.ies",
            RectangularWithSides,
            [f64::NAN; 2],
        ),
        ("round_opening.ies", Circular, [0.12, 0.0]),
        (
            "round_opening_with_height.ies",
            VerticalCylinder,
            [f64::NAN; 2],
        ),
        ("sphere_opening.ies", Sphere, [f64::NAN; 2]),
        (
            "horizontal_cylinder_opening_along_length.ies",
            HorizontalCylinderAlongLength,
            [f64::NAN; 2],
        ),
        (
            "horizontal_cylinder_opening_along_width.ies",
            HorizontalCylinderAlongWidth,
            [f64::NAN; 2],
        ),
    ];
    for (file, shape, size) in cases {
        let lum = Luminaire::load(&luminaire(&format!("photometric-viewer/ies95/{file}"))).unwrap();
        let o = lum.ies.as_ref().unwrap().opening();
        assert_eq!(o.shape, shape, "{file}");
        if !size[0].is_nan() {
            assert!(
                (o.width_m - size[0]).abs() < 1e-12 && (o.length_m - size[1]).abs() < 1e-12,
                "{file}: {o:?}"
            );
        }
    }
    let labels = Luminaire::load(&luminaire("photometric-viewer/ies95/label_lines.ies")).unwrap();
    let more = labels
        .ies
        .unwrap()
        .keyword("MULTILINE")
        .unwrap()
        .lines()
        .count();
    assert_eq!(more, 3, "[MORE] lines folded into the keyword before them");
}

#[test]
fn tolerated_quirks_parse_to_the_same_data_with_warnings() {
    let path = luminaire("eulumdat-plot/sample_03_isym2.ldt");
    let clean_bytes = std::fs::read(&path).unwrap();
    let clean = Luminaire::from_bytes("clean.ldt", &clean_bytes).unwrap();
    let text = String::from_utf8(clean_bytes.clone()).unwrap();
    // Comma decimals, CRLF, BOM, Windows-1252 company name, trailing blank lines.
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    lines[0] = "Leuchten f\u{fc}r R\u{e4}ume".to_string();
    let commas: Vec<String> = lines.iter().map(|l| l.replace('.', ",")).collect();
    let mut bytes = b"\xEF\xBB\xBF".to_vec();
    bytes.extend(commas.join("\r\n").into_bytes());
    bytes.extend(b"\r\n\r\n\r\n");
    let quirky = Luminaire::from_bytes("quirky.ldt", &bytes).unwrap();
    assert_eq!(quirky.distribution, clean.distribution);
    assert!(quirky.warnings.iter().any(|w| w.contains("decimal commas")));
    assert!(quirky
        .warnings
        .iter()
        .any(|w| w.contains("byte-order mark")));
    assert!(quirky.warnings.iter().any(|w| w.contains("trailing blank")));
    // Windows-1252 bytes for ü and ä.
    let mut cp = b"Leuchten f\xfcr R\xe4ume\r\n".to_vec();
    cp.extend(lines[1..].join("\r\n").into_bytes());
    let l = Luminaire::from_bytes("cp1252.ldt", &cp).unwrap();
    assert_eq!(l.data.company, "Leuchten für Räume");
    assert!(l.warnings.iter().any(|w| w.contains("Windows-1252")));
    // Missing optional values (dimensions, DFF) become 0 with a warning.
    let mut missing = lines.clone();
    for n in [13, 14, 22] {
        missing[n - 1] = String::new();
    }
    let l = Luminaire::from_bytes("missing.ldt", missing.join("\n").as_bytes()).unwrap();
    assert_eq!(l.data.dimensions.length, 0.0);
    assert_eq!(l.distribution, clean.distribution);
    assert_eq!(
        l.warnings.iter().filter(|w| w.contains("missing")).count(),
        3
    );
}
