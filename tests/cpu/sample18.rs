//! The raw 1° × 1° lab measurement: integrated flux against the declared lamp flux, and
//! the downsampling check that answers "which interpolation reconstructs it best".

use crate::common;

use goniolight::photometry::{check, Luminaire};

fn sample18() -> Luminaire {
    Luminaire::load(&common::luminaire("eulumdat-analysis/sample_18.ldt")).unwrap()
}

#[test]
fn integrated_flux_matches_declared_lamp_flux() {
    let lum = sample18();
    let s = lum.summary();
    assert_eq!(s.lamp_flux_lm, 2445.4);
    assert!((s.flux_lm / 2445.4 - 1.0).abs() < 0.01, "{}", s.flux_lm);
    assert!((s.lorl_computed - s.lorl_declared).abs() < 1.0);
    assert_eq!(lum.distribution.grid().c_angles().len(), 360);
    assert_eq!(lum.distribution.grid().gamma_angles().len(), 181);
}

#[test]
fn downsample_15_5_ranks_the_methods() {
    let lum = sample18();
    let r = check::downsample(&lum.distribution, 15.0, 5.0).unwrap();
    // 360 × 181 measured values, 24 × 37 kept.
    assert_eq!(r.held_out, 360 * 181 - 24 * 37);
    let m = |k: &str| r.methods.get(k).unwrap_or_else(|| panic!("method {k}"));
    let (bl, cr, mono, near) = (m("bilinear"), m("catmull_rom"), m("monotone"), m("nearest"));
    // Cubic reconstruction beats linear, which beats nearest, on RMS error.
    assert!(
        cr.rms < bl.rms && mono.rms < bl.rms && bl.rms < near.rms,
        "{r:#?}"
    );
    // Bilinear and monotone never leave their cell's range; Catmull-Rom does.
    assert_eq!(bl.overshoot_count, 0);
    assert_eq!(mono.overshoot_count, 0);
    assert!(cr.overshoot_count > 0);
    // Flux is preserved to well under 1 % by every interpolating method.
    for x in [bl, cr, mono] {
        assert!(x.flux_error_percent.abs() < 0.5, "{r:#?}");
        assert!(x.hausdorff <= x.max_abs + 1e-9 && x.hausdorff > 0.0);
    }
}

#[test]
fn leave_out_modes_hide_the_right_counts() {
    let lum = sample18();
    let g = check::leave_out(&lum.distribution, check::LeaveOut::Gamma).unwrap();
    assert_eq!(g.held_out, 360 * 90);
    let c = check::leave_out(&lum.distribution, check::LeaveOut::C).unwrap();
    assert_eq!(c.held_out, 180 * 181);
    let both = check::leave_out(&lum.distribution, check::LeaveOut::Both).unwrap();
    assert_eq!(both.held_out, 360 * 181 - 180 * 91);
}

#[test]
fn reference_check_against_a_finer_measurement() {
    // Coarse: the file itself downsampled and written out; fine: the 1° file.
    let lum = sample18();
    let coarse_grid = check::downsampled_grid(&lum.distribution, 15.0, 5.0).unwrap();
    let coarse = goniolight::photometry::Distribution::from_grid(
        coarse_grid,
        lum.distribution.lamp_flux_lm(),
        lum.distribution.symmetry(),
    );
    let r = check::against_reference(&coarse, &lum.distribution).unwrap();
    assert_eq!(r.held_out, 360 * 181);
    let down = check::downsample(&lum.distribution, 15.0, 5.0).unwrap();
    // Same reconstructions, same worst error (the extra points are exact).
    for (k, m) in &r.methods {
        assert!((m.max_abs - down.methods[k].max_abs).abs() < 1e-9, "{k}");
    }
}
