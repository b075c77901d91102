//! The full-sphere light distribution every other part of goniolight samples.

use glam::DVec3;

use super::eulumdat::Eulumdat;
use super::flux::integrate_flux;
use super::grid::{Grid, Interp};
use super::symmetry::Symmetry;
use super::text::show_rounded;

/// Intensities over the whole sphere: C ∈ [0°, 360°), γ ∈ [0°, 180°], in cd/klm, plus
/// the lamp flux that turns them into candela.
#[derive(Debug, Clone, PartialEq)]
pub struct Distribution {
    grid: Grid,
    lamp_flux_lm: f64,
    symmetry: Symmetry,
}

impl Distribution {
    /// Expands an EULUMDAT data set to the full sphere. Planes that disagree at a pole
    /// (γ = 0° or 180°, where all planes meet) are set to their mean: returned as a warning.
    pub fn from_eulumdat(ldt: &Eulumdat) -> (Distribution, Vec<String>) {
        let planes = ldt.expanded();
        let c: Vec<f64> = planes.iter().map(|p| p.0).collect();
        let mut rows: Vec<Vec<f64>> = planes.into_iter().map(|p| p.1).collect();
        let gamma = close_lit_edges(ldt.gamma_angles.clone(), &mut rows);
        let mut dist = Distribution {
            grid: Grid::new(c, gamma, &rows),
            lamp_flux_lm: ldt.lamp_flux_lm(),
            symmetry: ldt.symmetry,
        };
        let warnings = dist.unify_poles();
        (dist, warnings)
    }

    /// A distribution from a grid in cd/klm and a lamp flux.
    pub fn from_grid(grid: Grid, lamp_flux_lm: f64, symmetry: Symmetry) -> Distribution {
        Distribution {
            grid,
            lamp_flux_lm,
            symmetry,
        }
    }

    fn unify_poles(&mut self) -> Vec<String> {
        let mut warnings = Vec::new();
        let g = self.grid.gamma_angles().to_vec();
        let nc = self.grid.c_angles().len();
        let ng = g.len();
        let i_max = self.max_intensity().0.max(f64::MIN_POSITIVE);
        for (gi, pole) in [(0, 0.0), (ng - 1, 180.0)] {
            if g[gi] != pole || nc == 1 {
                continue;
            }
            let vals: Vec<f64> = (0..nc).map(|ci| self.grid.value(ci, gi)).collect();
            let (lo, hi) = vals
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            if hi - lo > 1e-9 * i_max {
                let mean = vals.iter().sum::<f64>() / nc as f64;
                for ci in 0..nc {
                    self.grid.values_mut()[ci * ng + gi] = mean;
                }
                warnings.push(format!(
                    "C planes disagree at γ = {pole}° ({} to {} cd/klm) although all meet there: their mean {} is used for sampling (the stored values are kept)",
                    show_rounded(lo),
                    show_rounded(hi),
                    show_rounded(mean)
                ));
            }
        }
        warnings
    }

    /// The grid (cd/klm).
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Declared lamp flux, lm (cd/klm × lamp flux / 1000 = cd).
    pub fn lamp_flux_lm(&self) -> f64 {
        self.lamp_flux_lm
    }

    /// The symmetry the data came with.
    pub fn symmetry(&self) -> Symmetry {
        self.symmetry
    }

    /// Intensity in cd/klm at C, γ (degrees).
    pub fn sample(&self, c_deg: f64, gamma_deg: f64, interp: Interp) -> f64 {
        self.grid.sample(c_deg, gamma_deg, interp)
    }

    /// Intensity in cd/klm toward `dir` in the luminaire frame (γ = 0 along −Z, C0 along
    /// +X, C90 along +Y). `dir` need not be normalised.
    pub fn sample_dir(&self, dir: DVec3, interp: Interp) -> f64 {
        let (c, g) = direction_to_angles(dir);
        self.grid.sample(c, g, interp)
    }

    /// Intensity in candela for the declared lamp flux times `dimming`.
    pub fn candela(&self, c_deg: f64, gamma_deg: f64, interp: Interp, dimming: f64) -> f64 {
        self.sample(c_deg, gamma_deg, interp) * self.lamp_flux_lm / 1000.0 * dimming
    }

    /// Peak measured intensity (cd/klm) and its direction (C, γ degrees).
    pub fn max_intensity(&self) -> (f64, f64, f64) {
        let ng = self.grid.gamma_angles().len();
        let (i, v) =
            self.grid
                .values()
                .iter()
                .enumerate()
                .fold((0, f64::NEG_INFINITY), |best, (i, &v)| {
                    if v > best.1 {
                        (i, v)
                    } else {
                        best
                    }
                });
        (
            v,
            self.grid.c_angles()[i / ng],
            self.grid.gamma_angles()[i % ng],
        )
    }

    /// Integrated flux per 1000 lm of lamp flux (lm/klm) and its downward part.
    pub fn relative_flux(&self) -> (f64, f64) {
        let planes: Vec<(f64, Vec<f64>)> = self
            .grid
            .c_angles()
            .iter()
            .enumerate()
            .map(|(ci, &c)| (c, self.grid.plane(ci).to_vec()))
            .collect();
        integrate_flux(&planes, self.grid.gamma_angles())
    }

    /// Integrated luminaire flux in lm for the declared lamp flux.
    pub fn flux_lm(&self) -> f64 {
        self.relative_flux().0 * self.lamp_flux_lm / 1000.0
    }
}

/// Width over which a lit edge of a γ range that stops short of a pole falls to zero.
pub const EDGE_FALL_DEG: f64 = 0.5;

/// A γ range that stops short of a pole means no light beyond it (LM-63: a file listing
/// 0°…90° lights the lower hemisphere only). The samplers fall to zero over one grid step
/// past the range, so where the edge value is not zero a zero column is added
/// [`EDGE_FALL_DEG`] (or one step, if finer) beyond it: the light beyond the range, and so
/// the difference between the flux of the file and the flux the renderer emits, stays
/// below a fraction of a percent.
fn close_lit_edges(mut gamma: Vec<f64>, rows: &mut [Vec<f64>]) -> Vec<f64> {
    let n = gamma.len();
    let lit = |k: usize, rows: &[Vec<f64>]| rows.iter().any(|r| r[k] > 0.0);
    if gamma[n - 1] < 180.0 && lit(n - 1, rows) {
        let step = (gamma[n - 1] - gamma[n - 2]).min(EDGE_FALL_DEG);
        gamma.push((gamma[n - 1] + step).min(180.0));
        rows.iter_mut().for_each(|r| r.push(0.0));
    }
    if gamma[0] > 0.0 && lit(0, rows) {
        let step = (gamma[1] - gamma[0]).min(EDGE_FALL_DEG);
        gamma.insert(0, (gamma[0] - step).max(0.0));
        rows.iter_mut().for_each(|r| r.insert(0, 0.0));
    }
    gamma
}

/// (C, γ) in degrees of a direction in the luminaire frame.
pub fn direction_to_angles(dir: DVec3) -> (f64, f64) {
    if dir.length_squared() == 0.0 {
        return (0.0, 0.0);
    }
    // atan2 is well conditioned everywhere (acos is not near the poles).
    let g = dir.x.hypot(dir.y).atan2(-dir.z).to_degrees();
    let c = dir.y.atan2(dir.x).to_degrees().rem_euclid(360.0);
    (c, g)
}

/// Unit direction in the luminaire frame of (C, γ) in degrees.
pub fn angles_to_direction(c_deg: f64, gamma_deg: f64) -> DVec3 {
    let (sc, cc) = c_deg.to_radians().sin_cos();
    let (sg, cg) = gamma_deg.to_radians().sin_cos();
    DVec3::new(sg * cc, sg * sc, -cg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_conventions() {
        let (c, g) = direction_to_angles(DVec3::new(0.0, 0.0, -1.0));
        assert_eq!(g, 0.0);
        assert!(c.is_finite());
        let (c, g) = direction_to_angles(DVec3::new(0.0, 1.0, 0.0));
        assert!((c - 90.0).abs() < 1e-12 && (g - 90.0).abs() < 1e-12);
        let (c, g) = direction_to_angles(DVec3::new(1.0, 0.0, 1.0));
        assert!(c.abs() < 1e-12 && (g - 135.0).abs() < 1e-12);
        let d = angles_to_direction(250.0, 33.0);
        let (c, g) = direction_to_angles(d);
        assert!((c - 250.0).abs() < 1e-9 && (g - 33.0).abs() < 1e-9);
    }
}
