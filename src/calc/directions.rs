//! The surface normals each grid point is evaluated with, and how their illuminances make
//! the grid's value: one normal for planar kinds; for cylindrical illuminance the mean of
//! the vertical illuminance over 72 horizontal directions (5° apart), for semi-cylindrical
//! the mean over 36 directions across the half facing the grid's direction. The mean of
//! the vertical illuminance over directions is the cylinder's (resp. half cylinder's)
//! illuminance exactly; sampling it every 5° is within 0.07 % for any light.

use glam::DVec3;

use crate::lighting::SurfacePoint;
use crate::scene::grid::{CalcGrid, GridKind};

/// Directions sampled around the full circle (cylindrical).
pub const CYLINDER_DIRECTIONS: usize = 72;

fn horizontal(angle_rad: f64) -> DVec3 {
    DVec3::new(angle_rad.cos(), angle_rad.sin(), 0.0)
}

/// The normals evaluated at every point of `grid`.
pub fn normals(grid: &CalcGrid) -> Vec<DVec3> {
    let step = std::f64::consts::TAU / CYLINDER_DIRECTIONS as f64;
    match (grid.entry.kind, grid.facing) {
        (GridKind::Horizontal, _) => vec![DVec3::Z],
        (GridKind::Ceiling, _) => vec![DVec3::NEG_Z],
        (GridKind::Vertical, Some(f)) => vec![f],
        (GridKind::Cylindrical, _) => (0..CYLINDER_DIRECTIONS)
            .map(|k| horizontal((k as f64 + 0.5) * step))
            .collect(),
        (GridKind::Semicylindrical, Some(f)) => {
            let facing = f.y.atan2(f.x);
            (0..CYLINDER_DIRECTIONS / 2)
                .map(|k| horizontal(facing - std::f64::consts::FRAC_PI_2 + (k as f64 + 0.5) * step))
                .collect()
        }
        (kind, None) => unreachable!("a {kind:?} grid is resolved with its facing direction"),
    }
}

/// Every (point, normal) to evaluate, point by point.
pub fn surface_points(grid: &CalcGrid) -> Vec<SurfacePoint> {
    let normals = normals(grid);
    grid.points
        .iter()
        .flat_map(|&position| {
            normals
                .iter()
                .map(move |&normal| SurfacePoint { position, normal })
        })
        .collect()
}

/// The grid's values from the illuminances of [`surface_points`]: the mean over each
/// point's normals.
pub fn combine(grid: &CalcGrid, lux: &[f64]) -> Vec<f64> {
    let n = normals(grid).len();
    lux.chunks(n)
        .map(|c| c.iter().sum::<f64>() / n as f64)
        .collect()
}
