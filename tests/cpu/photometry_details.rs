//! Details of the photometry contract checked against analytic values: beam and field
//! angles, dimming, direction sampling, IES editions and TILT=INCLUDE.

use crate::common;

use glam::DVec3;
use goniolight::photometry::ies::Tilt;
use goniolight::photometry::{Distribution, Grid, Interp, Luminaire, Summary, Symmetry};

/// I(γ) = 1000·cos γ below the horizon on a 1° grid (a Lambertian downlight).
fn lambertian() -> Distribution {
    let g: Vec<f64> = (0..=180).map(f64::from).collect();
    let row: Vec<f64> = g
        .iter()
        .map(|a| 1000.0 * a.to_radians().cos().max(0.0))
        .collect();
    Distribution::from_grid(
        Grid::new(vec![0.0], g, &[row]),
        1000.0,
        Symmetry::Rotational,
    )
}

#[test]
fn beam_and_field_angles_of_a_lambertian_source() {
    let s = Summary::of(&lambertian(), 100.0, 100.0);
    // 50 % at γ = 60°, 10 % at γ = acos(0.1) = 84.26°, on both sides of the nadir.
    let beam = s.beam_angle_deg.c0_c180.unwrap();
    let field = s.field_angle_deg.c90_c270.unwrap();
    assert!((beam - 120.0).abs() < 0.05, "{beam}");
    assert!(
        (field - 2.0 * 0.1f64.acos().to_degrees()).abs() < 0.05,
        "{field}"
    );
    // Φ = π · I(0) = 3141.6 lm per 1000 lm of lamp: LORL 314 %, all of it downward.
    assert!((s.flux_lm / (std::f64::consts::PI * 1000.0) - 1.0).abs() < 1e-4);
    assert!((s.dff_computed - 100.0).abs() < 1e-9);
    assert_eq!(s.max_direction_deg, [0.0, 0.0]);
}

#[test]
fn dimming_and_direction_sampling() {
    let d = lambertian();
    // 1000 cd/klm × 1000 lm / 1000 × 0.25 dimming at the nadir.
    assert!((d.candela(0.0, 0.0, Interp::CatmullRom, 0.25) - 250.0).abs() < 1e-9);
    // Luminaire frame: γ = 0 along −Z. A direction 30° off the nadir toward +Y.
    let dir = DVec3::new(0.0, 30f64.to_radians().sin(), -30f64.to_radians().cos());
    let v = d.sample_dir(dir * 7.0, Interp::CatmullRom);
    assert!((v - 1000.0 * 30f64.to_radians().cos()).abs() < 1e-3, "{v}");
    assert_eq!(d.sample_dir(DVec3::Z, Interp::CatmullRom), 0.0);
    // An asymmetric file: the direction toward +Y is the C90 plane.
    let lum = Luminaire::load(&common::luminaire("eulumdat-plot/sample_01_isym3.ldt")).unwrap();
    let (c90, g40) = (90.0, 40.0f64);
    let dir = DVec3::new(0.0, g40.to_radians().sin(), -g40.to_radians().cos());
    let a = lum.distribution.sample_dir(dir, Interp::Bilinear);
    assert!((a - lum.distribution.sample(c90, g40, Interp::Bilinear)).abs() < 1e-9);
}

fn ies_variant(header: &str, tilt: &str) -> Vec<u8> {
    let path = common::luminaire("photometric-viewer/ies95/metric_units.ies");
    let text = std::fs::read_to_string(path).unwrap();
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if i == 0 {
            out.push_str(header);
        } else if line.starts_with("TILT") {
            out.push_str(tilt);
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out.into_bytes()
}

#[test]
fn ies_editions_and_tilt_include() {
    let base =
        Luminaire::from_bytes("base.ies", &ies_variant("IESNA:LM-63-1995", "TILT=NONE")).unwrap();
    for header in ["IESNA:LM-63-2002", "IES:LM-63-2019", "IESNA91"] {
        let l = Luminaire::from_bytes("x.ies", &ies_variant(header, "TILT=NONE")).unwrap();
        assert_eq!(l.distribution, base.distribution, "{header}");
    }
    let tilt = "TILT=INCLUDE\n1\n3\n0 45 90\n1.0 0.95 0.9";
    let l = Luminaire::from_bytes("tilt.ies", &ies_variant("IESNA:LM-63-2002", tilt)).unwrap();
    assert_eq!(
        l.ies.as_ref().unwrap().tilt,
        Tilt::Include {
            geometry: 1,
            angles: vec![0.0, 45.0, 90.0],
            factors: vec![1.0, 0.95, 0.9]
        }
    );
    assert_eq!(l.distribution, base.distribution);
    assert!(l.warnings.iter().any(|w| w.contains("TILT=INCLUDE")));
}

#[test]
fn cie_flux_codes_of_lambertian_and_uniform_downlights() {
    use goniolight::photometry::summary::cie_flux_code;
    // Lambertian: the cone of half-angle θ holds sin²θ of the downward flux; LOR π × 100 %
    // of a 1000 lm lamp for I = 1000 cd/klm · cos γ.
    assert_eq!(cie_flux_code(&lambertian()), Some([44, 75, 94, 100, 314]));
    // Uniform below the horizon (cut off within 0.01° above it): 1 − cos θ.
    let mut g: Vec<f64> = (0..=90).map(f64::from).collect();
    g.extend([90.01, 180.0]);
    let row: Vec<f64> = g
        .iter()
        .map(|a| if *a <= 90.0 { 100.0 } else { 0.0 })
        .collect();
    let uniform = Distribution::from_grid(
        Grid::new(vec![0.0], g, &[row]),
        1000.0,
        Symmetry::Rotational,
    );
    let code = cie_flux_code(&uniform).unwrap();
    assert_eq!(code[..4], [25, 50, 75, 100]);
    // 100 cd/klm over 2π sr: 62.8 %.
    assert_eq!(code[4], 63);
}
