//! Garland's fit quadric (Edström Eq. 4.2–4.7): the ten numbers that give the least-squares
//! plane of a cluster's points and its fit error, summed when clusters merge.

use glam::{DMat3, DVec3};

/// Σ (v vᵀ, v, 1) over a set of points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitQuadric {
    /// Σ v vᵀ.
    pub a: DMat3,
    /// Σ v.
    pub b: DVec3,
    /// Number of points.
    pub c: f64,
}

impl Default for FitQuadric {
    /// The quadric of no points (glam's default matrix is the identity, not zero).
    fn default() -> Self {
        FitQuadric {
            a: DMat3::ZERO,
            b: DVec3::ZERO,
            c: 0.0,
        }
    }
}

impl FitQuadric {
    /// The quadric of the points `points`.
    pub fn of_points(points: &[DVec3]) -> FitQuadric {
        points.iter().fold(FitQuadric::default(), |q, &v| {
            q + FitQuadric {
                a: outer(v, v),
                b: v,
                c: 1.0,
            }
        })
    }

    /// The covariance matrix Z = A − b bᵀ / c (Eq. 4.7), about the points' mean.
    pub fn covariance(&self) -> DMat3 {
        if self.c <= 0.0 {
            return DMat3::ZERO;
        }
        self.a - outer(self.b, self.b) * (1.0 / self.c)
    }

    /// The fit error of the least-squares plane: the mean squared distance of the points
    /// to it (Eq. 4.1), the smallest eigenvalue of Z divided by the point count.
    pub fn fit_error(&self) -> f64 {
        if self.c <= 0.0 {
            return 0.0;
        }
        (smallest_eigenvalue(&self.covariance()) / self.c).max(0.0)
    }
}

impl std::ops::Add for FitQuadric {
    type Output = FitQuadric;
    fn add(self, o: FitQuadric) -> FitQuadric {
        FitQuadric {
            a: self.a + o.a,
            b: self.b + o.b,
            c: self.c + o.c,
        }
    }
}

fn outer(u: DVec3, v: DVec3) -> DMat3 {
    DMat3::from_cols(u * v.x, u * v.y, u * v.z)
}

/// The smallest eigenvalue of the symmetric 3 × 3 matrix `m`, in closed form (the
/// trigonometric solution of the characteristic cubic; Smith 1961).
pub fn smallest_eigenvalue(m: &DMat3) -> f64 {
    let (a00, a11, a22) = (m.x_axis.x, m.y_axis.y, m.z_axis.z);
    let (a01, a02, a12) = (
        0.5 * (m.y_axis.x + m.x_axis.y),
        0.5 * (m.z_axis.x + m.x_axis.z),
        0.5 * (m.z_axis.y + m.y_axis.z),
    );
    let off = a01 * a01 + a02 * a02 + a12 * a12;
    let q = (a00 + a11 + a22) / 3.0;
    if off <= 1e-30 * (q * q).max(f64::MIN_POSITIVE) {
        return a00.min(a11).min(a22);
    }
    let p2 = (a00 - q).powi(2) + (a11 - q).powi(2) + (a22 - q).powi(2) + 2.0 * off;
    let p = (p2 / 6.0).sqrt();
    // B = (M − q I) / p; r = det(B) / 2, clamped against rounding.
    let (b00, b11, b22) = ((a00 - q) / p, (a11 - q) / p, (a22 - q) / p);
    let (b01, b02, b12) = (a01 / p, a02 / p, a12 / p);
    let det = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02)
        + b02 * (b01 * b12 - b11 * b02);
    let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    // The eigenvalues are q + 2p cos(φ + 2πk/3); k = 1 gives the smallest.
    q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_of_known_matrices() {
        let d = DMat3::from_diagonal(DVec3::new(3.0, 1.0, 2.0));
        assert_eq!(smallest_eigenvalue(&d), 1.0);
        // Rotated diag(5, 2, 0.5): the smallest stays 0.5.
        let r = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let m = r * DMat3::from_diagonal(DVec3::new(5.0, 2.0, 0.5)) * r.transpose();
        assert!((smallest_eigenvalue(&m) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn fit_error_is_the_mean_squared_distance_to_the_plane() {
        // Points on z = 0 plus two at z = ±1 → the best plane is z = 0 (the x–y spread is
        // wider than 1), mean squared distance 2 / 6.
        let mut pts: Vec<DVec3> = [(-3.0, -3.0), (3.0, -3.0), (3.0, 3.0), (-3.0, 3.0)]
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .to_vec();
        assert!(FitQuadric::of_points(&pts).fit_error() < 1e-12);
        pts.push(DVec3::new(0.0, 0.0, 1.0));
        pts.push(DVec3::new(0.0, 0.0, -1.0));
        let e = FitQuadric::of_points(&pts).fit_error();
        assert!((e - 2.0 / 6.0).abs() < 1e-12, "{e}");
    }
}
