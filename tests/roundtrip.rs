//! Writers round-trip: LDT → LDT exactly, LDT → IES → LDT within print precision.

mod common;

use common::all_luminaire_files;
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
