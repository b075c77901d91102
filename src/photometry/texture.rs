//! Light distribution texture (LDT) data: the normalised (÷ I_max) intensity grid on a
//! uniform C × γ grid, one row per C plane, as the GPU renderer and the radiosity solver
//! upload it. Its CPU sampler is the reference the WGSL code must match.

use serde::Serialize;

use super::distribution::Distribution;
use super::grid::{Grid, Interp};

/// Most C planes a resampled texture gets (0.5° steps).
pub const MAX_C_PLANES: usize = 720;
/// Most γ rows a resampled texture gets (0.1° steps).
pub const MAX_GAMMA_ROWS: usize = 1801;

/// Which part of the sphere receives light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Hemisphere {
    /// Only directions below the horizontal (γ < 90°).
    Lower,
    /// Only directions above the horizontal (γ > 90°).
    Upper,
    /// Both.
    Full,
}

/// Normalised intensities on a uniform grid.
#[derive(Debug, Clone)]
pub struct LdtTexture {
    /// Number of C planes (rows); 1 for a rotationally symmetric luminaire.
    pub c_count: usize,
    /// Number of γ samples per row.
    pub gamma_count: usize,
    /// γ of the first column, degrees.
    pub gamma_start_deg: f64,
    /// γ step, degrees.
    pub gamma_step_deg: f64,
    /// Peak intensity, cd/klm: texel × `i_max` = cd/klm.
    pub i_max: f64,
    /// The lit part of the sphere.
    pub hemisphere: Hemisphere,
    /// Row-major texels (`data[c * gamma_count + g]`), each in `[0, 1]`.
    pub data: Vec<f32>,
    grid: Grid,
}

impl LdtTexture {
    /// Builds the texture data of `dist`. A non-uniform grid is resampled with
    /// Catmull-Rom onto a uniform one whose step is the smallest spacing of the file.
    pub fn from_distribution(dist: &Distribution) -> LdtTexture {
        let src = dist.grid();
        let i_max = dist.max_intensity().0.max(f64::MIN_POSITIVE);
        let (c_angles, gammas, mut rows) = uniform_rows(src);
        // Rotationally symmetric data needs one row.
        let rotational = rows.iter().all(|r| r == &rows[0]);
        if rotational {
            rows.truncate(1);
        }
        let c_angles = if rotational { vec![0.0] } else { c_angles };
        // Trim γ to the lit range plus one zero column on each side that has one.
        let lit = |gi: usize| rows.iter().any(|r| r[gi] > 0.0);
        let ng = gammas.len();
        let first_lit = (0..ng).find(|&g| lit(g)).unwrap_or(0);
        let last_lit = (0..ng).rev().find(|&g| lit(g)).unwrap_or(ng - 1);
        let lo = first_lit.saturating_sub(1);
        let hi = (last_lit + 1).min(ng - 1).max(lo + 1);
        let hemisphere = if gammas[last_lit] <= 90.0 {
            Hemisphere::Lower
        } else if gammas[first_lit] >= 90.0 {
            Hemisphere::Upper
        } else {
            Hemisphere::Full
        };
        let gammas = gammas[lo..=hi].to_vec();
        let rows: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| {
                r[lo..=hi]
                    .iter()
                    .map(|v| ((v / i_max) as f32) as f64)
                    .collect()
            })
            .collect();
        let data: Vec<f32> = rows.iter().flatten().map(|&v| v as f32).collect();
        let gamma_step_deg = gammas[1] - gammas[0];
        LdtTexture {
            c_count: rows.len(),
            gamma_count: gammas.len(),
            gamma_start_deg: gammas[0],
            gamma_step_deg,
            i_max,
            hemisphere,
            data,
            grid: Grid::new(c_angles, gammas, &rows),
        }
    }

    /// C step between rows, degrees (360 for a single row).
    pub fn c_step_deg(&self) -> f64 {
        360.0 / self.c_count as f64
    }

    /// Whether the first γ column is exactly 0° (knots below it mirror across the pole).
    pub fn starts_at_pole(&self) -> bool {
        self.grid.gamma_angles()[0] == 0.0
    }

    /// Whether the last γ column is exactly 180°.
    pub fn ends_at_pole(&self) -> bool {
        self.grid.gamma_angles()[self.gamma_count - 1] == 180.0
    }

    /// Whether one row serves every C plane.
    pub fn is_rotational(&self) -> bool {
        self.c_count == 1
    }

    /// The normalised intensity at (C, γ) degrees: the CPU reference of the GPU sampler.
    pub fn sample(&self, c_deg: f64, gamma_deg: f64, interp: Interp) -> f64 {
        self.grid.sample(c_deg, gamma_deg, interp)
    }
}

/// The grid's planes on uniform C (starting at 0°) and γ axes, resampled if needed.
fn uniform_rows(src: &Grid) -> (Vec<f64>, Vec<f64>, Vec<Vec<f64>>) {
    let c = src.c_angles();
    let g = src.gamma_angles();
    let c_uniform = c.len() == 1
        || (c[0] == 0.0 && {
            let step = 360.0 / c.len() as f64;
            c.iter()
                .enumerate()
                .all(|(i, a)| (a - step * i as f64).abs() < 1e-6)
        });
    let g_step = (g[g.len() - 1] - g[0]) / (g.len() - 1) as f64;
    let g_uniform = g
        .iter()
        .enumerate()
        .all(|(i, a)| (a - (g[0] + g_step * i as f64)).abs() < 1e-6);
    if c_uniform && g_uniform {
        let rows = (0..c.len()).map(|i| src.plane(i).to_vec()).collect();
        return (c.to_vec(), g.to_vec(), rows);
    }
    let min_gap = |a: &[f64], wrap: bool| {
        let mut m = a
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        if wrap && a.len() > 1 {
            m = m.min(a[0] + 360.0 - a[a.len() - 1]);
        }
        m
    };
    let nc = if c.len() == 1 {
        1
    } else {
        ((360.0 / min_gap(c, true)).ceil() as usize).clamp(1, MAX_C_PLANES)
    };
    let span = g[g.len() - 1] - g[0];
    let ngam = ((span / min_gap(g, false)).ceil() as usize + 1).clamp(2, MAX_GAMMA_ROWS);
    let new_c: Vec<f64> = (0..nc).map(|i| i as f64 * 360.0 / nc as f64).collect();
    let new_g: Vec<f64> = (0..ngam)
        .map(|i| g[0] + span * i as f64 / (ngam - 1) as f64)
        .collect();
    let rows = new_c
        .iter()
        .map(|&cc| {
            new_g
                .iter()
                .map(|&gg| src.sample(cc, gg, Interp::CatmullRom))
                .collect()
        })
        .collect();
    (new_c, new_g, rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::photometry::Luminaire;

    fn load(rel: &str) -> Luminaire {
        let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("luminaires")
            .join(rel);
        Luminaire::load(&p).unwrap()
    }

    #[test]
    fn uniform_file_texture_samples_like_the_distribution() {
        for rel in [
            "eulumdat-plot/sample_01_isym3.ldt",
            "eulumdat-luminance/sample_06.ldt",
            "eulumdat-plot/sample_13_isym1.ldt",
        ] {
            let lum = load(rel);
            let tex = LdtTexture::from_distribution(&lum.distribution);
            for interp in Interp::ALL {
                for k in 0..500 {
                    let c = (k as f64 * 71.123) % 360.0;
                    let g = (k as f64 * 17.377) % 180.0;
                    let want = lum.distribution.sample(c, g, interp) / tex.i_max;
                    let got = tex.sample(c, g, interp);
                    // Texels are f32.
                    assert!((want - got).abs() < 1e-6, "{rel} {interp:?} C{c} γ{g}");
                }
            }
            assert!(tex.data.iter().all(|v| (0.0..=1.0).contains(v)));
            assert_eq!(tex.data.iter().cloned().fold(0.0, f32::max), 1.0);
        }
    }

    #[test]
    fn rotational_and_hemisphere_detection() {
        let rot =
            LdtTexture::from_distribution(&load("eulumdat-plot/sample_13_isym1.ldt").distribution);
        assert!(rot.is_rotational());
        let lower = LdtTexture::from_distribution(
            &load("photometric-viewer/ldt/relative.ldt").distribution,
        );
        assert_eq!(lower.hemisphere, Hemisphere::Lower);
        // 0…90° data plus one zero column beyond the last lit angle at most.
        assert!(lower.gamma_start_deg == 0.0 && lower.gamma_count <= 38);
        let asym =
            LdtTexture::from_distribution(&load("eulumdat-plot/sample_01_isym3.ldt").distribution);
        assert_eq!(asym.c_count, 24);
        assert!((asym.c_step_deg() - 15.0).abs() < 1e-12);
    }

    #[test]
    fn non_uniform_grids_are_resampled_through_the_measured_values() {
        // γ at 0, 5, 10, 20, 40, 90 (non-uniform); the texture grid is 5° uniform.
        let g = vec![0.0, 5.0, 10.0, 20.0, 40.0, 90.0];
        let row = vec![100.0, 98.0, 90.0, 60.0, 20.0, 0.0];
        let grid = Grid::new(vec![0.0], g.clone(), std::slice::from_ref(&row));
        let dist = Distribution::from_grid(grid, 1000.0, crate::photometry::Symmetry::Rotational);
        let tex = LdtTexture::from_distribution(&dist);
        assert!((tex.gamma_step_deg - 5.0).abs() < 1e-12);
        for (a, v) in g.iter().zip(row) {
            assert!((tex.sample(0.0, *a, Interp::Nearest) * tex.i_max - v).abs() < 1e-4);
        }
    }
}
