//! "Checking LDT interpolation against measurements": reconstruct measured values that
//! the interpolation did not see, and measure the error of each method.
//!
//! Three ways to get hidden values:
//! - **leave-out**: hide every other measured angle (in γ, in C, or both; the last γ angle
//!   is always kept so the range does not shrink) and reconstruct the hidden ones;
//! - **reference**: reconstruct a coarse file at every angle of a finer measurement of the
//!   same luminaire;
//! - **downsample**: keep only the angles on a coarser step (e.g. 15° × 5°) and reconstruct
//!   all the others.

use std::collections::BTreeMap;

use kiddo::{KdTree, SquaredEuclidean};
use serde::Serialize;

use super::distribution::{angles_to_direction, Distribution};
use super::error::PhotometryError;
use super::flux::integrate_flux;
use super::grid::{angle_eq, Grid, Interp};

/// Which angles leave-out hides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum LeaveOut {
    /// Every other γ angle.
    Gamma,
    /// Every other C plane.
    C,
    /// Every other angle in both.
    Both,
}

/// Error figures of one interpolation method.
#[derive(Debug, Clone, Serialize)]
pub struct MethodResult {
    /// Root mean square error over the hidden values, cd/klm.
    pub rms: f64,
    /// Largest absolute error, cd/klm.
    pub max_abs: f64,
    /// Largest relative error over hidden values above 1 % of I_max.
    pub max_rel: f64,
    /// Reconstructed values outside the range of their cell's measured corners.
    pub overshoot_count: usize,
    /// The largest such excursion, cd/klm.
    pub overshoot_max: f64,
    /// Flux of the reconstruction relative to the measured flux, percent.
    pub flux_error_percent: f64,
    /// Symmetric Hausdorff distance between the measured and reconstructed photometric
    /// solids (surfaces r = I(dir)·dir sampled on the measured grid), cd/klm.
    pub hausdorff: f64,
}

/// The result of a check.
#[derive(Debug, Clone, Serialize)]
pub struct CheckReport {
    /// How the hidden values were chosen.
    pub mode: String,
    /// Number of values reconstructed and compared.
    pub held_out: usize,
    /// Peak measured intensity of the reference, cd/klm.
    pub i_max: f64,
    /// Per method (`nearest`, `bilinear`, `catmull_rom`, `monotone`).
    pub methods: BTreeMap<String, MethodResult>,
    /// Every reconstructed value, hidden point by hidden point (not in the JSON: `ldt
    /// check --residuals` writes them as CSV).
    #[serde(skip)]
    pub residuals: Vec<Residual>,
}

/// One hidden measured value and each method's reconstruction of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// C angle, degrees.
    pub c_deg: f64,
    /// γ angle, degrees.
    pub gamma_deg: f64,
    /// The measured value, cd/klm.
    pub measured: f64,
    /// Reconstructed minus measured, cd/klm, in the order of [`Interp::ALL`].
    pub error: [f64; 4],
}

impl CheckReport {
    /// The residuals as CSV: a header, then per hidden angle C, γ, the measured value and each
    /// method's reconstructed − measured (cd/klm).
    pub fn residuals_csv(&self) -> String {
        let mut out = String::from("c_deg,gamma_deg,measured_cd_klm");
        for interp in Interp::ALL {
            out.push(',');
            out.push_str(method_key(interp));
        }
        out.push('\n');
        for r in &self.residuals {
            out.push_str(&format!("{},{},{}", r.c_deg, r.gamma_deg, r.measured));
            for e in r.error {
                out.push_str(&format!(",{e}"));
            }
            out.push('\n');
        }
        out
    }

    /// The method with the smallest RMS error (ties: smallest max error).
    pub fn best_by_rms(&self) -> Option<&str> {
        self.methods
            .iter()
            .min_by(|a, b| {
                a.1.rms
                    .total_cmp(&b.1.rms)
                    .then(a.1.max_abs.total_cmp(&b.1.max_abs))
            })
            .map(|(k, _)| k.as_str())
    }
}

/// Key of a method in reports.
pub fn method_key(interp: Interp) -> &'static str {
    match interp {
        Interp::Nearest => "nearest",
        Interp::Bilinear => "bilinear",
        Interp::CatmullRom => "catmull_rom",
        Interp::Monotone => "monotone",
    }
}

/// Leave-out check of `dist`.
pub fn leave_out(dist: &Distribution, which: LeaveOut) -> Result<CheckReport, PhotometryError> {
    let grid = dist.grid();
    let nc = grid.c_angles().len();
    let ng = grid.gamma_angles().len();
    let keep_c: Vec<bool> = (0..nc)
        .map(|i| matches!(which, LeaveOut::Gamma) || nc == 1 || i % 2 == 0)
        .collect();
    let keep_g: Vec<bool> = (0..ng)
        .map(|i| matches!(which, LeaveOut::C) || i % 2 == 0 || i + 1 == ng)
        .collect();
    let mode = match which {
        LeaveOut::Gamma => "leave-out γ",
        LeaveOut::C => "leave-out C",
        LeaveOut::Both => "leave-out C and γ",
    };
    subset_check(dist, &keep_c, &keep_g, mode)
}

/// Downsample `dist` to the angles on multiples of `dc` and `dg` degrees (the last γ angle
/// is kept as well) and reconstruct every other measured value.
pub fn downsample(dist: &Distribution, dc: f64, dg: f64) -> Result<CheckReport, PhotometryError> {
    let (keep_c, keep_g) = downsample_masks(dist, dc, dg)?;
    subset_check(
        dist,
        &keep_c,
        &keep_g,
        &format!("downsample to {dc}° × {dg}°"),
    )
}

/// The grid of `dist` reduced to the angles on multiples of `dc` and `dg` degrees.
pub fn downsampled_grid(dist: &Distribution, dc: f64, dg: f64) -> Result<Grid, PhotometryError> {
    let (keep_c, keep_g) = downsample_masks(dist, dc, dg)?;
    coarse_grid(
        dist.grid(),
        &keep_c,
        &keep_g,
        &format!("downsample to {dc}° × {dg}°"),
    )
}

fn downsample_masks(
    dist: &Distribution,
    dc: f64,
    dg: f64,
) -> Result<(Vec<bool>, Vec<bool>), PhotometryError> {
    if !(dc > 0.0 && dg > 0.0 && dc.is_finite() && dg.is_finite()) {
        return Err(PhotometryError::Field {
            field: "downsample",
            value: format!("{dc},{dg}"),
            problem: "must be two positive steps (ΔC,Δγ in degrees)".into(),
        });
    }
    let grid = dist.grid();
    let on_step = |a: f64, step: f64| {
        let k = (a / step).round();
        (a - k * step).abs() < 1e-6
    };
    let nc = grid.c_angles().len();
    let keep_c = grid
        .c_angles()
        .iter()
        .map(|&c| nc == 1 || on_step(c, dc))
        .collect();
    let ng = grid.gamma_angles().len();
    let keep_g = grid
        .gamma_angles()
        .iter()
        .enumerate()
        .map(|(i, &g)| on_step(g, dg) || i + 1 == ng)
        .collect();
    Ok((keep_c, keep_g))
}

/// Reconstruct `coarse` at every grid angle of `fine` (another measurement of the same
/// luminaire, both in cd/klm).
pub fn against_reference(
    coarse: &Distribution,
    fine: &Distribution,
) -> Result<CheckReport, PhotometryError> {
    let fg = fine.grid();
    let points: Vec<(usize, usize)> = (0..fg.c_angles().len())
        .flat_map(|ci| (0..fg.gamma_angles().len()).map(move |gi| (ci, gi)))
        .collect();
    Ok(evaluate(coarse.grid(), fg, &points, "reference"))
}

fn coarse_grid(
    grid: &Grid,
    keep_c: &[bool],
    keep_g: &[bool],
    mode: &str,
) -> Result<Grid, PhotometryError> {
    let kc: Vec<usize> = (0..keep_c.len()).filter(|&i| keep_c[i]).collect();
    let kg: Vec<usize> = (0..keep_g.len()).filter(|&i| keep_g[i]).collect();
    if kg.len() < 2 {
        return Err(PhotometryError::Invalid(format!(
            "{mode}: fewer than two γ angles would remain"
        )));
    }
    if kc.is_empty() {
        return Err(PhotometryError::Invalid(format!(
            "{mode}: no C plane lies on the requested step"
        )));
    }
    let coarse_c: Vec<f64> = kc.iter().map(|&i| grid.c_angles()[i]).collect();
    let coarse_g: Vec<f64> = kg.iter().map(|&i| grid.gamma_angles()[i]).collect();
    let planes: Vec<Vec<f64>> = kc
        .iter()
        .map(|&ci| kg.iter().map(|&gi| grid.value(ci, gi)).collect())
        .collect();
    Ok(Grid::new(coarse_c, coarse_g, &planes))
}

fn subset_check(
    dist: &Distribution,
    keep_c: &[bool],
    keep_g: &[bool],
    mode: &str,
) -> Result<CheckReport, PhotometryError> {
    let grid = dist.grid();
    let coarse = coarse_grid(grid, keep_c, keep_g, mode)?;
    let hidden: Vec<(usize, usize)> = (0..keep_c.len())
        .flat_map(|ci| (0..keep_g.len()).map(move |gi| (ci, gi)))
        .filter(|&(ci, gi)| !(keep_c[ci] && keep_g[gi]))
        .collect();
    if hidden.is_empty() {
        return Err(PhotometryError::Invalid(format!(
            "{mode}: no measured value is hidden (the file is already on that grid)"
        )));
    }
    Ok(evaluate(&coarse, grid, &hidden, mode))
}

/// Compares reconstructions from `coarse` with `reference` at the `hidden` grid points;
/// the other points keep their measured values in the reconstructed solid.
fn evaluate(coarse: &Grid, reference: &Grid, hidden: &[(usize, usize)], mode: &str) -> CheckReport {
    let rc = reference.c_angles();
    let rg = reference.gamma_angles();
    let i_max = reference.values().iter().cloned().fold(0.0, f64::max);
    let ref_planes = planes_of(reference, |ci, gi| reference.value(ci, gi));
    let ref_flux = integrate_flux(&ref_planes, rg).0;
    // Squares and k-d tree splits work on values scaled to I_max = 1: intensities near
    // the ends of the f64 range (1e-300 or 1e150 cd/klm) neither underflow nor overflow.
    let unit = if i_max > 0.0 { 1.0 / i_max } else { 1.0 };
    let ref_solid = solid(reference, &|ci, gi| reference.value(ci, gi) * unit);
    let ref_tree = tree_of(&ref_solid);
    let mut methods = BTreeMap::new();
    let mut residuals: Vec<Residual> = hidden
        .iter()
        .map(|&(ci, gi)| Residual {
            c_deg: rc[ci],
            gamma_deg: rg[gi],
            measured: reference.value(ci, gi),
            error: [0.0; 4],
        })
        .collect();
    for (m, interp) in Interp::ALL.into_iter().enumerate() {
        // Kept points keep their measured values; hidden ones are overwritten below.
        let mut recon = reference.values().to_vec();
        let ng = rg.len();
        let (mut sq, mut max_abs, mut max_rel) = (0.0, 0.0f64, 0.0f64);
        let (mut over_n, mut over_max) = (0usize, 0.0f64);
        for (&(ci, gi), residual) in hidden.iter().zip(&mut residuals) {
            let (c, g) = (rc[ci], rg[gi]);
            let v = coarse.sample(c, g, interp);
            recon[ci * ng + gi] = v;
            let truth = residual.measured;
            let err = v - truth;
            residual.error[m] = err;
            sq += (err * unit).powi(2);
            max_abs = max_abs.max(err.abs());
            if truth > 0.01 * i_max {
                max_rel = max_rel.max(err.abs() / truth);
            }
            let (lo, hi) = coarse.cell_range(c, g);
            let excursion = (v - hi).max(lo - v);
            if excursion > 1e-9 * i_max.max(1.0) {
                over_n += 1;
                over_max = over_max.max(excursion);
            }
        }
        let planes = planes_of(reference, |ci, gi| recon[ci * ng + gi]);
        let flux = integrate_flux(&planes, rg).0;
        let solid_r = solid(reference, &|ci, gi| recon[ci * ng + gi] * unit);
        let hausdorff = directed_hausdorff(&solid_r, &ref_tree)
            .max(directed_hausdorff(&ref_solid, &tree_of(&solid_r)))
            / unit;
        methods.insert(
            method_key(interp).to_string(),
            MethodResult {
                rms: (sq / hidden.len() as f64).sqrt() / unit,
                max_abs,
                max_rel,
                overshoot_count: over_n,
                overshoot_max: over_max,
                flux_error_percent: if ref_flux > 0.0 {
                    (flux - ref_flux) / ref_flux * 100.0
                } else {
                    0.0
                },
                hausdorff,
            },
        );
    }
    CheckReport {
        mode: mode.to_string(),
        held_out: hidden.len(),
        i_max,
        methods,
        residuals,
    }
}

fn planes_of(grid: &Grid, value: impl Fn(usize, usize) -> f64) -> Vec<(f64, Vec<f64>)> {
    grid.c_angles()
        .iter()
        .enumerate()
        .map(|(ci, &c)| {
            (
                c,
                (0..grid.gamma_angles().len())
                    .map(|gi| value(ci, gi))
                    .collect(),
            )
        })
        .collect()
}

/// Points r = I(dir)·dir of the photometric solid at the grid's directions.
fn solid(grid: &Grid, value: &dyn Fn(usize, usize) -> f64) -> Vec<[f64; 3]> {
    let mut pts = Vec::with_capacity(grid.values().len());
    for (ci, &c) in grid.c_angles().iter().enumerate() {
        for (gi, &g) in grid.gamma_angles().iter().enumerate() {
            // Both poles are one point however many planes meet there.
            if ci > 0 && (angle_eq(g, 0.0) || g == 180.0) {
                continue;
            }
            pts.push((angles_to_direction(c, g) * value(ci, gi)).to_array());
        }
    }
    pts
}

fn tree_of(points: &[[f64; 3]]) -> KdTree<f64, 3> {
    // Points are in units of I_max. Coordinates are snapped to 2⁻⁴⁰ (1e-12 of I_max, far
    // below any measurement) so that values like 1e-298 next to ordinary ones cannot make
    // the tree split ever thinner slabs; zero intensities all sit at the origin, and a
    // k-d tree needs distinct points.
    const QUANTUM: f64 = 1.0 / (1u64 << 40) as f64;
    let mut unique: Vec<[f64; 3]> = points
        .iter()
        .map(|p| p.map(|x| (x / QUANTUM).round() * QUANTUM))
        .collect();
    unique.sort_by(|a, b| {
        a[0].total_cmp(&b[0])
            .then(a[1].total_cmp(&b[1]))
            .then(a[2].total_cmp(&b[2]))
    });
    unique.dedup();
    let mut tree: KdTree<f64, 3> = KdTree::with_capacity(unique.len());
    for (i, p) in unique.iter().enumerate() {
        tree.add(p, i as u64);
    }
    tree
}

fn directed_hausdorff(from: &[[f64; 3]], to: &KdTree<f64, 3>) -> f64 {
    from.iter()
        .map(|p| to.nearest_one::<SquaredEuclidean>(p).distance)
        .fold(0.0, f64::max)
        .sqrt()
}
