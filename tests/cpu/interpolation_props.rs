//! Property tests of the sampler: interpolation through the measured values, C wrap,
//! pole continuity, no overshoot for the monotone cubic, symmetry invariants, and parsers
//! that never panic on arbitrary bytes.

use crate::common;

use goniolight::photometry::{Eulumdat, Grid, IesFile, Interp, Luminaire};
use proptest::prelude::*;

/// A random grid: `nc` planes (uniform or jittered), γ from 0 to 90 or 180 (uniform or
/// jittered), values in [0, 1000] with one value per pole shared by all planes.
fn arb_grid() -> impl Strategy<Value = Grid> {
    (
        prop_oneof![Just(1usize), 2usize..24],
        4usize..30,
        any::<bool>(),
        any::<bool>(),
        any::<u64>(),
    )
        .prop_map(|(nc, ng, full, jitter, seed)| {
            let mut rng = goniolight::geometry::generate::XorShift::new(seed);
            let mut next = move || rng.next_f64();
            let top = if full { 180.0 } else { 90.0 };
            let mut c: Vec<f64> = (0..nc).map(|i| i as f64 * 360.0 / nc as f64).collect();
            let mut g: Vec<f64> = (0..ng).map(|i| i as f64 * top / (ng - 1) as f64).collect();
            if jitter {
                let dc = 360.0 / nc as f64;
                for x in c.iter_mut().skip(1) {
                    *x += (next() - 0.5) * 0.6 * dc;
                }
                let dg = top / (ng - 1) as f64;
                for x in g.iter_mut().skip(1).take(ng - 2) {
                    *x += (next() - 0.5) * 0.6 * dg;
                }
            }
            let south = next() * 1000.0;
            let north = next() * 1000.0;
            let planes: Vec<Vec<f64>> = (0..nc)
                .map(|_| {
                    (0..ng)
                        .map(|gi| match gi {
                            0 => south,
                            _ if gi == ng - 1 && full => north,
                            _ => next() * 1000.0,
                        })
                        .collect()
                })
                .collect();
            Grid::new(c, g, &planes)
        })
}

fn arb_interp() -> impl Strategy<Value = Interp> {
    prop_oneof![
        Just(Interp::Nearest),
        Just(Interp::Bilinear),
        Just(Interp::CatmullRom),
        Just(Interp::Monotone)
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn passes_through_measured_values(grid in arb_grid(), interp in arb_interp()) {
        for (ci, &c) in grid.c_angles().iter().enumerate() {
            for (gi, &g) in grid.gamma_angles().iter().enumerate() {
                let v = grid.sample(c, g, interp);
                prop_assert!((v - grid.value(ci, gi)).abs() < 1e-9 * 1000.0,
                    "C{c} γ{g}: {v} vs {}", grid.value(ci, gi));
            }
        }
    }

    #[test]
    fn c_wraps(grid in arb_grid(), interp in arb_interp(), c in 0.0f64..360.0, g in 0.0f64..180.0) {
        let a = grid.sample(c, g, interp);
        prop_assert!((a - grid.sample(c + 360.0, g, interp)).abs() < 1e-7);
        prop_assert!((a - grid.sample(c - 360.0, g, interp)).abs() < 1e-7);
        // Across the 0°/360° seam the sampler is continuous.
        let below = grid.sample(360.0 - 1e-9, g, interp);
        let above = grid.sample(1e-9, g, interp);
        if interp != Interp::Nearest {
            prop_assert!((below - above).abs() < 1e-4, "{below} vs {above}");
        }
    }

    #[test]
    fn no_seam_at_the_poles(grid in arb_grid(), interp in arb_interp(), c1 in 0.0f64..360.0, c2 in 0.0f64..360.0) {
        prop_assume!(interp != Interp::Nearest);
        let eps = 1e-7;
        let a = grid.sample(c1, eps, interp);
        let b = grid.sample(c2, eps, interp);
        prop_assert!((a - b).abs() < 1e-2, "γ→0: C{c1} {a} vs C{c2} {b}");
        if *grid.gamma_angles().last().unwrap() == 180.0 {
            let a = grid.sample(c1, 180.0 - eps, interp);
            let b = grid.sample(c2, 180.0 - eps, interp);
            prop_assert!((a - b).abs() < 1e-2, "γ→180: {a} vs {b}");
        }
    }

    #[test]
    fn monotone_and_bilinear_never_overshoot(grid in arb_grid(), c in 0.0f64..360.0, g in 0.0f64..180.0) {
        for interp in [Interp::Bilinear, Interp::Monotone] {
            let v = grid.sample(c, g, interp);
            let (lo, hi) = grid.cell_range(c, g);
            prop_assert!(v >= lo - 1e-9 && v <= hi + 1e-9, "{interp:?}: {v} outside [{lo}, {hi}]");
        }
        prop_assert!(grid.sample(c, g, Interp::CatmullRom) >= 0.0);
    }

    #[test]
    fn parsers_never_panic_on_arbitrary_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
        let _ = Eulumdat::parse("fuzz.ldt", &bytes);
        let _ = IesFile::parse("fuzz.ies", &bytes);
        let _ = Luminaire::from_bytes("fuzz.ldt", &bytes);
    }

    #[test]
    fn parsers_never_panic_on_mutated_files(pos in 0usize..3000, byte in any::<u8>(), cut in 0usize..3000) {
        for rel in ["eulumdat-plot/sample_01_isym3.ldt", "photometric-viewer/ies95/metric_units.ies"] {
            let mut bytes = std::fs::read(common::luminaire(rel)).unwrap();
            let n = bytes.len();
            bytes[pos % n] = byte;
            bytes.truncate(cut.max(1) % (n + 1));
            let _ = Luminaire::from_bytes(rel, &bytes);
        }
    }
}

#[test]
fn symmetry_invariants_hold_for_every_file_and_method() {
    for path in common::all_luminaire_files() {
        let lum = Luminaire::load(&path).unwrap();
        let d = &lum.distribution;
        let peak = d.max_intensity().0;
        let mirrors: &[fn(f64) -> f64] = match lum.data.symmetry.isym() {
            1 => &[|c| c + 37.0, |c| 360.0 - c],
            2 => &[|c| 360.0 - c],
            3 => &[|c| 180.0 - c],
            4 => &[|c| 360.0 - c, |c| 180.0 - c],
            _ => &[],
        };
        for interp in Interp::ALL {
            for k in 0..200 {
                let c = (k as f64 * 47.318_71) % 360.0;
                let g = (k as f64 * 13.771_3) % 180.0;
                let v = d.sample(c, g, interp);
                for m in mirrors {
                    let w = d.sample(m(c), g, interp);
                    assert!(
                        (v - w).abs() <= 1e-9 * peak,
                        "{} {interp:?} C{c} γ{g}: {v} vs {w}",
                        path.display()
                    );
                }
            }
        }
    }
}
