//! A C × γ grid of intensities over the sphere and its interpolation.
//!
//! C wraps around (360° periodic). Along γ, the neighbours beyond a pole (γ = 0° or 180°)
//! are taken from the opposite half-plane (C + 180°) at the mirrored angle, so the
//! reconstruction has no seam at the poles; beyond a γ range that stops short of a pole the
//! intensity falls to zero over one grid step. Cubic methods are separable Hermite cubics
//! on the (possibly non-uniform) knots: Catmull-Rom uses central-difference slopes,
//! the monotone method the Fritsch–Butland limited slopes (no overshoot).

use serde::Serialize;

/// Interpolation between the measured angles.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all(serialize = "snake_case", deserialize = "kebab-case"))]
pub enum Interp {
    /// The nearest measured value.
    Nearest,
    /// Linear in C and in γ.
    Bilinear,
    /// Bicubic Catmull-Rom (interpolating, may overshoot; clamped at 0).
    #[cfg_attr(feature = "cli", value(name = "catmull-rom"))]
    CatmullRom,
    /// Shape-preserving bicubic (monotone piecewise cubic, never overshoots the cell).
    Monotone,
}

impl Interp {
    /// All methods, cheapest first.
    pub const ALL: [Interp; 4] = [
        Interp::Nearest,
        Interp::Bilinear,
        Interp::CatmullRom,
        Interp::Monotone,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Interp::Nearest => "nearest",
            Interp::Bilinear => "bilinear",
            Interp::CatmullRom => "catmull-rom",
            Interp::Monotone => "monotone",
        }
    }
}

/// Angle equality within the precision files are printed with (mod 360°).
/// Both angles must lie within (−360°, 720°), as all angles here do.
pub(crate) fn angle_eq(a: f64, b: f64) -> bool {
    const EPS: f64 = 1e-6;
    let d = (a - b).abs();
    d < EPS || (d - 360.0).abs() < EPS || (d - 720.0).abs() < EPS
}

/// An ascending list of angles with a fast path for uniform spacing.
#[derive(Debug, Clone, PartialEq)]
struct Axis {
    angles: Vec<f64>,
    /// `(first, 1 / step)` when the spacing is uniform.
    uniform: Option<(f64, f64)>,
}

impl Axis {
    fn new(angles: Vec<f64>) -> Axis {
        let uniform = if angles.len() >= 2 {
            let step = (angles[angles.len() - 1] - angles[0]) / (angles.len() - 1) as f64;
            let ok = angles
                .iter()
                .enumerate()
                .all(|(i, a)| (a - (angles[0] + step * i as f64)).abs() < 1e-9 * 360.0);
            ok.then_some((angles[0], 1.0 / step))
        } else {
            None
        };
        Axis { angles, uniform }
    }

    fn len(&self) -> usize {
        self.angles.len()
    }

    /// Index `i` with `angles[i] <= x < angles[i + 1]`, for `angles[0] <= x < last`.
    fn locate_inside(&self, x: f64) -> usize {
        let n = self.angles.len();
        let i = match self.uniform {
            Some((first, inv_step)) => ((x - first) * inv_step) as usize,
            None => self.angles.partition_point(|&a| a <= x).saturating_sub(1),
        };
        i.min(n - 2)
    }
}

/// Where a direction falls in the grid: the four C planes around it and its γ cell.
#[derive(Debug, Clone, Copy)]
struct Cell {
    /// Plane indices j−1, j, j+1, j+2 (all equal when there is one plane).
    planes: [usize; 4],
    /// Their C angles, unwrapped around the query.
    c_knots: [f64; 4],
    /// The query's C angle, unwrapped like the knots.
    c: f64,
    /// γ cell: knots `gi` and `gi + 1` bracket the query (`-1` and `ng − 1` are the
    /// virtual zero cells beyond a γ range that stops short of a pole).
    gi: isize,
    /// The query's γ angle.
    g: f64,
}

/// Intensities on a C × γ grid covering the sphere.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    c: Axis,
    g: Axis,
    /// C-major: `values[ci * ng + gi]`.
    values: Vec<f64>,
    /// For each plane, the plane at C + 180° (itself when the grid has none there).
    opposite: Vec<usize>,
}

impl Grid {
    /// A grid from C angles in `[0, 360)` (ascending), γ angles in `[0, 180]` (ascending,
    /// at least two) and one row of values per C angle.
    ///
    /// # Panics
    /// When the shapes disagree; callers validate their input first.
    pub fn new(c_angles: Vec<f64>, gamma_angles: Vec<f64>, planes: &[Vec<f64>]) -> Grid {
        assert!(!c_angles.is_empty() && gamma_angles.len() >= 2);
        assert_eq!(c_angles.len(), planes.len());
        let ng = gamma_angles.len();
        let mut values = Vec::with_capacity(planes.len() * ng);
        for p in planes {
            assert_eq!(p.len(), ng);
            values.extend_from_slice(p);
        }
        let opposite = (0..c_angles.len())
            .map(|j| {
                let target = c_angles[j] + 180.0;
                c_angles
                    .iter()
                    .position(|&a| angle_eq(a, target))
                    .unwrap_or(j)
            })
            .collect();
        Grid {
            c: Axis::new(c_angles),
            g: Axis::new(gamma_angles),
            values,
            opposite,
        }
    }

    /// The C angles (degrees).
    pub fn c_angles(&self) -> &[f64] {
        &self.c.angles
    }

    /// The γ angles (degrees).
    pub fn gamma_angles(&self) -> &[f64] {
        &self.g.angles
    }

    /// The intensities of plane `ci` over the γ angles.
    pub fn plane(&self, ci: usize) -> &[f64] {
        let ng = self.g.len();
        &self.values[ci * ng..(ci + 1) * ng]
    }

    /// The value at grid point (`ci`, `gi`).
    pub fn value(&self, ci: usize, gi: usize) -> f64 {
        self.values[ci * self.g.len() + gi]
    }

    /// All values, C-major.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Mutable access to all values, C-major.
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Whether the C angles are evenly spaced (and the γ angles too).
    pub fn is_uniform(&self) -> bool {
        (self.c.len() == 1 || self.c.uniform.is_some()) && self.g.uniform.is_some()
    }

    /// Angle of γ knot `k`: a grid angle, its mirror across a pole, or a step beyond the
    /// end of a γ range that stops short of a pole.
    #[inline(always)]
    fn knot_angle(&self, k: isize) -> f64 {
        let g = &self.g.angles;
        let ng = g.len() as isize;
        if (0..ng).contains(&k) {
            return g[k as usize];
        }
        if k < 0 {
            let m = -k;
            if g[0] == 0.0 && m < ng {
                return -g[m as usize];
            }
            return g[0] - (g[1] - g[0]) * m as f64;
        }
        let last = ng - 1;
        let m = 2 * last - k;
        if g[last as usize] == 180.0 && m >= 0 {
            return 360.0 - g[m as usize];
        }
        let gl = g[last as usize];
        gl + (gl - g[last as usize - 1]) * (k - last) as f64
    }

    /// Value of γ knot `k` of plane `plane` (see `knot_angle`): across a pole it comes
    /// from the opposite plane, beyond a γ range it is zero.
    #[inline(always)]
    fn knot_value(&self, plane: usize, k: isize) -> f64 {
        let g = &self.g.angles;
        let ng = g.len() as isize;
        if (0..ng).contains(&k) {
            return self.values[plane * ng as usize + k as usize];
        }
        let last = ng - 1;
        let m = if k < 0 { -k } else { 2 * last - k };
        let pole = if k < 0 {
            g[0] == 0.0
        } else {
            g[last as usize] == 180.0
        };
        if pole && (0..ng).contains(&m) {
            self.values[self.opposite[plane] * ng as usize + m as usize]
        } else {
            0.0
        }
    }

    /// The four γ knot values `gi − 1 … gi + 2` of `plane`.
    #[inline(always)]
    fn row(&self, plane: usize, gi: isize) -> [f64; 4] {
        let ng = self.g.len() as isize;
        if gi >= 1 && gi + 2 < ng {
            let base = plane * ng as usize + gi as usize - 1;
            let v = &self.values[base..base + 4];
            [v[0], v[1], v[2], v[3]]
        } else {
            [-1, 0, 1, 2].map(|d| self.knot_value(plane, gi + d))
        }
    }

    /// The cell of the query, or `None` where the intensity is zero by definition
    /// (more than a grid step beyond a γ range that stops short of a pole).
    #[inline(always)]
    fn cell(&self, c: f64, g: f64) -> Option<Cell> {
        let ga = &self.g.angles;
        let ng = ga.len();
        let g = g.clamp(0.0, 180.0);
        let gi: isize = if g < ga[0] {
            if g < ga[0] - (ga[1] - ga[0]) {
                return None;
            }
            -1
        } else if g >= ga[ng - 1] {
            if g == ga[ng - 1] {
                ng as isize - 2
            } else if g > ga[ng - 1] + (ga[ng - 1] - ga[ng - 2]) {
                return None;
            } else {
                ng as isize - 1
            }
        } else {
            self.g.locate_inside(g) as isize
        };
        let nc = self.c.len();
        let ca = &self.c.angles;
        let mut c = if (0.0..360.0).contains(&c) {
            c
        } else {
            c.rem_euclid(360.0)
        };
        if nc == 1 {
            return Some(Cell {
                planes: [0; 4],
                c_knots: [c - 2.0, c - 1.0, c, c + 1.0],
                c,
                gi,
                g,
            });
        }
        // j: plane at or below c (wrapping); unwrap c so that ca[j] <= c.
        let j = if c < ca[0] {
            c += 360.0;
            nc - 1
        } else if c >= ca[nc - 1] {
            nc - 1
        } else {
            self.c.locate_inside(c)
        };
        let mut planes = [0; 4];
        let mut c_knots = [0.0; 4];
        for d in 0..4 {
            // k ∈ [−1, nc + 1]: wrap with compares (integer division is slow here).
            let k = j as isize + d as isize - 1;
            let (idx, offset) = if k < 0 {
                (k + nc as isize, -360.0)
            } else if k >= nc as isize {
                (k - nc as isize, 360.0)
            } else {
                (k, 0.0)
            };
            planes[d] = idx as usize;
            c_knots[d] = ca[idx as usize] + offset;
        }
        Some(Cell {
            planes,
            c_knots,
            c,
            gi,
            g,
        })
    }

    /// The intensity at (`c`, `g`) degrees, interpolated with `interp`, never negative.
    pub fn sample(&self, c: f64, g: f64, interp: Interp) -> f64 {
        let Some(cell) = self.cell(c, g) else {
            return 0.0;
        };
        let single = self.c.len() == 1;
        let gi = cell.gi;
        let v = match interp {
            Interp::Nearest => {
                let (t1, t2) = (self.knot_angle(gi), self.knot_angle(gi + 1));
                let k = if cell.g - t1 <= t2 - cell.g {
                    gi
                } else {
                    gi + 1
                };
                let plane = if single || cell.c - cell.c_knots[1] <= cell.c_knots[2] - cell.c {
                    cell.planes[1]
                } else {
                    cell.planes[2]
                };
                self.knot_value(plane, k)
            }
            Interp::Bilinear => {
                let (t1, t2) = (self.knot_angle(gi), self.knot_angle(gi + 1));
                let along = |plane| {
                    let (p1, p2) = (self.knot_value(plane, gi), self.knot_value(plane, gi + 1));
                    lerp(t1, p1, t2, p2, cell.g)
                };
                let a = along(cell.planes[1]);
                if single {
                    a
                } else {
                    lerp(
                        cell.c_knots[1],
                        a,
                        cell.c_knots[2],
                        along(cell.planes[2]),
                        cell.c,
                    )
                }
            }
            Interp::CatmullRom => {
                // Catmull-Rom is linear in the data: weights once per axis.
                let t = [-1, 0, 1, 2].map(|d| self.knot_angle(gi + d));
                let wg = catmull_rom_weights(t, cell.g);
                let along = |plane| dot(wg, self.row(plane, gi));
                if single {
                    along(0)
                } else {
                    let wc = catmull_rom_weights(cell.c_knots, cell.c);
                    dot(wc, cell.planes.map(along))
                }
            }
            Interp::Monotone => {
                let t = [-1, 0, 1, 2].map(|d| self.knot_angle(gi + d));
                let along = |plane| monotone_cubic(t, self.row(plane, gi), cell.g);
                if single {
                    along(0)
                } else {
                    monotone_cubic(cell.c_knots, cell.planes.map(along), cell.c)
                }
            }
        };
        v.max(0.0)
    }

    /// The smallest and largest of the measured values at the corners of the cell holding
    /// (`c`, `g`): a reconstruction outside this range overshoots.
    pub fn cell_range(&self, c: f64, g: f64) -> (f64, f64) {
        let Some(cell) = self.cell(c, g) else {
            return (0.0, 0.0);
        };
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let planes: &[usize] = if self.c.len() == 1 {
            &cell.planes[1..2]
        } else {
            &cell.planes[1..3]
        };
        for &p in planes {
            for k in [cell.gi, cell.gi + 1] {
                let v = self.knot_value(p, k);
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        (lo, hi)
    }
}

#[inline]
fn lerp(t1: f64, p1: f64, t2: f64, p2: f64, x: f64) -> f64 {
    let s = (x - t1) / (t2 - t1);
    p1 + (p2 - p1) * s
}

/// Fritsch–Butland slope at a knot between secants `da` (interval width `ha`, left) and
/// `db` (width `hb`, right): zero at extrema, a weighted harmonic mean otherwise.
#[inline]
fn limited_slope(da: f64, db: f64, ha: f64, hb: f64) -> f64 {
    if da * db <= 0.0 {
        return 0.0;
    }
    let w1 = 2.0 * hb + ha;
    let w2 = hb + 2.0 * ha;
    (w1 + w2) / (w1 / da + w2 / db)
}

#[inline]
fn dot(a: [f64; 4], b: [f64; 4]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3]
}

/// Hermite basis on `[t[1], t[2]]` at `x`: (h00, h10·h, h01, h11·h).
#[inline]
fn hermite_basis(t: [f64; 4], x: f64) -> [f64; 4] {
    let h = t[2] - t[1];
    let s = (x - t[1]) / h;
    let s2 = s * s;
    let s3 = s2 * s;
    [
        2.0 * s3 - 3.0 * s2 + 1.0,
        (s3 - 2.0 * s2 + s) * h,
        -2.0 * s3 + 3.0 * s2,
        (s3 - s2) * h,
    ]
}

/// Weights of the four knot values in the Catmull-Rom cubic on `[t[1], t[2]]` (slopes by
/// central differences over the possibly non-uniform knots).
#[inline]
fn catmull_rom_weights(t: [f64; 4], x: f64) -> [f64; 4] {
    // One division for the three reciprocals (1/h, 1/(t2 − t0), 1/(t3 − t1)).
    let h = t[2] - t[1];
    let (w0, w1) = (t[2] - t[0], t[3] - t[1]);
    let r = 1.0 / (h * w0 * w1);
    let s = (x - t[1]) * (r * w0 * w1);
    let s2 = s * s;
    let s3 = s2 * s;
    let (h00, h01) = (2.0 * s3 - 3.0 * s2 + 1.0, -2.0 * s3 + 3.0 * s2);
    // h10·h / (t2 − t0) and h11·h / (t3 − t1).
    let a = (s3 - 2.0 * s2 + s) * h * (r * h * w1);
    let b = (s3 - s2) * h * (r * h * w0);
    [-a, h00 - b, h01 + a, b]
}

/// Monotone (Fritsch–Butland) cubic on `[t[1], t[2]]` through `p[1]` and `p[2]`.
#[inline]
fn monotone_cubic(t: [f64; 4], p: [f64; 4], x: f64) -> f64 {
    let h = t[2] - t[1];
    let d0 = (p[1] - p[0]) / (t[1] - t[0]);
    let d1 = (p[2] - p[1]) / h;
    let d2 = (p[3] - p[2]) / (t[3] - t[2]);
    let m1 = limited_slope(d0, d1, t[1] - t[0], h);
    let m2 = limited_slope(d1, d2, h, t[3] - t[2]);
    let [h00, h10, h01, h11] = hermite_basis(t, x);
    h00 * p[1] + h10 * m1 + h01 * p[2] + h11 * m2
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp_grid() -> Grid {
        // I = γ in every plane, 0..90 by 10°, 4 planes.
        let g: Vec<f64> = (0..=9).map(|i| i as f64 * 10.0).collect();
        let planes = vec![g.clone(); 4];
        Grid::new(vec![0.0, 90.0, 180.0, 270.0], g, &planes)
    }

    #[test]
    fn linear_data_is_reproduced_by_every_cubic() {
        let grid = ramp_grid();
        for interp in [Interp::Bilinear, Interp::CatmullRom, Interp::Monotone] {
            // Away from the pole (where the data is |γ|) and the zero margin past 90°.
            for g in [12.5, 33.3, 55.0, 69.0] {
                let v = grid.sample(17.0, g, interp);
                assert!((v - g).abs() < 1e-9, "{interp:?} at {g}: {v}");
            }
        }
    }

    #[test]
    fn beyond_range_falls_to_zero_in_one_step() {
        let grid = ramp_grid();
        assert_eq!(grid.sample(0.0, 100.0 + 1e-9, Interp::Bilinear), 0.0);
        let half = grid.sample(0.0, 95.0, Interp::Bilinear);
        assert!((half - 45.0).abs() < 1e-9);
    }

    #[test]
    fn catmull_rom_uniform_matches_textbook_weights() {
        let g: Vec<f64> = (0..=18).map(|i| i as f64 * 10.0).collect();
        let row: Vec<f64> = g.iter().map(|x| (x / 30.0).sin() + 2.0).collect();
        let grid = Grid::new(vec![0.0], g, std::slice::from_ref(&row));
        // Between knots 3 and 4 at s = 0.25.
        let s: f64 = 0.25;
        let w = [
            -0.5 * s * s * s + s * s - 0.5 * s,
            1.5 * s * s * s - 2.5 * s * s + 1.0,
            -1.5 * s * s * s + 2.0 * s * s + 0.5 * s,
            0.5 * s * s * s - 0.5 * s * s,
        ];
        let expect: f64 = (0..4).map(|k| w[k] * row[2 + k]).sum();
        let v = grid.sample(123.0, 32.5, Interp::CatmullRom);
        assert!((v - expect).abs() < 1e-12, "{v} vs {expect}");
    }
}
