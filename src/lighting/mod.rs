//! The CPU twin of the renderer's lighting: direct illuminance at surface points from
//! placed luminaires, exact hard shadows by ray casting, and the reader of point lists
//! ("x y z nx ny nz" lines). The GPU code in `render` is checked against it, and the CPU
//! radiosity solver uses it without touching the GPU.

pub mod specular;
pub mod sun;

use std::io::{BufRead, Read};

use glam::DVec3;
use rayon::prelude::*;

use crate::geometry::Mesh;
use crate::photometry::Interp;
use crate::scene::PlacedLuminaire;
use std::sync::Arc;

use crate::shadow::{raycast, Cutouts, IgnoredTriangles, Light, TriangleBvh};

/// A malformed line in a list of points.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{source_name}: line {line}: {message}")]
pub struct PointsError {
    /// The file (or "stdin") the points came from.
    pub source_name: String,
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

/// A computed illuminance that is not a usable number (not finite, or below zero by more
/// than rounding): a bug, refused rather than reported.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("point {point}: the computed illuminance {value} lx is not a usable number")]
pub struct UnusableLux {
    /// The point, counted from 1.
    pub point: usize,
    /// The value, lux.
    pub value: f64,
}

/// How far below zero a computed illuminance may fall by rounding, lux.
pub const LUX_ROUNDING: f64 = 1e-6;

/// Checks computed illuminances before anyone is told them: refuses the first that is not
/// finite or lies below zero by more than [`LUX_ROUNDING`]; the others below zero (−0,
/// rounding) become 0, so no −0 is ever printed.
pub fn usable_lux(lux: &mut [f64]) -> Result<(), UnusableLux> {
    for (i, v) in lux.iter_mut().enumerate() {
        if !v.is_finite() || *v < -LUX_ROUNDING {
            return Err(UnusableLux {
                point: i + 1,
                value: *v,
            });
        }
        if *v <= 0.0 {
            *v = 0.0;
        }
    }
    Ok(())
}

/// A point on a surface: position (metres) and normal (need not be unit length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position.
    pub position: DVec3,
    /// Normal.
    pub normal: DVec3,
}

/// The CPU reference without shadows: Σ over luminaires of I · cos θ / d², lux.
pub fn illuminance_cpu(luminaires: &[PlacedLuminaire], p: &SurfacePoint, interp: Interp) -> f64 {
    let n = p.normal.normalize_or_zero();
    luminaires
        .iter()
        .map(|l| l.illuminance_at(p.position, n, interp))
        .sum()
}

/// What casts shadows on points: a mesh, the holes of its alpha-masked triangles, and per
/// luminaire the triangles it ignores (its housing; none where the slice is shorter).
#[derive(Debug, Clone, Copy)]
pub struct Occluders<'a> {
    /// Every caster triangle.
    pub mesh: &'a Mesh,
    /// Holes in its masked triangles (light passes them).
    pub cutouts: Option<&'a Arc<Cutouts>>,
    /// Per luminaire, the triangles it ignores.
    pub ignored: &'a [IgnoredTriangles],
}

impl<'a> Occluders<'a> {
    /// `mesh` without holes, every triangle casting.
    pub fn solid(mesh: &'a Mesh) -> Occluders<'a> {
        Occluders {
            mesh,
            cutouts: None,
            ignored: &[],
        }
    }
}

/// Which lights reach which points: `visible[light][point]`, by casting a ray from each
/// point toward each light position against `casters`, through a BVH built for the call.
/// These are exact hard shadows: the CPU reference of every shadow technique, and what
/// `volumes` means for point queries.
pub fn point_visibility(
    casters: &Occluders,
    light_positions: &[DVec3],
    points: &[SurfacePoint],
) -> Vec<Vec<bool>> {
    let eps = raycast::self_hit_epsilon(casters.mesh);
    let bvh = TriangleBvh::new(casters.mesh).with_cutouts(casters.cutouts.cloned());
    let none = IgnoredTriangles::default();
    light_positions
        .iter()
        .enumerate()
        .map(|(k, &at)| {
            let light = Light(at.extend(1.0));
            let ignored = casters.ignored.get(k).unwrap_or(&none);
            points
                .par_iter()
                .map(|p| !bvh.in_shadow(&light, p.position, eps, ignored))
                .collect()
        })
        .collect()
}

/// The CPU reference with shadows cast by `casters` (none when `None`; the luminaires in
/// order of `casters.ignored`): lux at `points`.
pub fn illuminance_cpu_in_scene(
    luminaires: &[PlacedLuminaire],
    casters: Option<&Occluders>,
    points: &[SurfacePoint],
    interp: Interp,
) -> Vec<f64> {
    let visible = casters.map(|casters| {
        let positions: Vec<DVec3> = luminaires.iter().map(|l| l.position).collect();
        point_visibility(casters, &positions, points)
    });
    points
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let n = p.normal.normalize_or_zero();
            luminaires
                .iter()
                .enumerate()
                .filter(|(k, _)| visible.as_ref().is_none_or(|v| v[*k][i]))
                .map(|(_, l)| l.illuminance_at(p.position, n, interp))
                .sum()
        })
        .collect()
}

/// Reads lines of `count` finite numbers separated by spaces or commas (blank lines and
/// `#` comments skipped); `what` describes a line in errors. Returns (line, numbers).
fn read_number_lines(
    mut input: impl BufRead,
    name: &str,
    count: usize,
    what: &str,
) -> Result<Vec<(usize, Vec<f64>)>, PointsError> {
    let mut rows = Vec::new();
    let mut total = 0u64;
    let mut buf = Vec::new();
    for i in 0.. {
        let err = |message: String| PointsError {
            source_name: name.to_string(),
            line: i + 1,
            message,
        };
        buf.clear();
        let n = (&mut input)
            .take(MAX_LINE_BYTES + 1)
            .read_until(b'\n', &mut buf)
            .map_err(|e| err(e.to_string()))?;
        if n == 0 {
            break;
        }
        total += n as u64;
        if buf.len() as u64 > MAX_LINE_BYTES {
            return Err(err(format!(
                "a line longer than {MAX_LINE_BYTES} bytes (is this a text file of points?)"
            )));
        }
        if total > crate::io::MAX_MODEL_BYTES {
            return Err(err(format!(
                "more than the {} bytes goniolight reads as points",
                crate::io::MAX_MODEL_BYTES
            )));
        }
        let line = std::str::from_utf8(&buf).map_err(|e| err(format!("not text: {e}")))?;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let v: Option<Vec<f64>> = t
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty())
            .map(|w| w.parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        match v {
            Some(v) if v.len() == count => rows.push((i + 1, v)),
            _ => return Err(err(format!("expected {what}, found {t:?}"))),
        }
    }
    Ok(rows)
}

/// The longest line of a points input, bytes.
const MAX_LINE_BYTES: u64 = 4096;

/// Parses lines `x y z nx ny nz` (spaces or commas; blank lines and `#` comments
/// skipped); normals are returned with unit length.
pub fn read_points(input: impl BufRead, name: &str) -> Result<Vec<SurfacePoint>, PointsError> {
    let rows = read_number_lines(input, name, 6, "six finite numbers \"x y z nx ny nz\"")?;
    let mut points = Vec::with_capacity(rows.len());
    for (line, v) in rows {
        let normal = DVec3::new(v[3], v[4], v[5]);
        if normal.length() < 1e-12 {
            return Err(PointsError {
                source_name: name.to_string(),
                line,
                message: "the normal has zero length".into(),
            });
        }
        points.push(SurfacePoint {
            position: DVec3::new(v[0], v[1], v[2]),
            // Scaled first: a component near f64::MAX must not overflow the length.
            normal: (normal / normal.abs().max_element()).normalize(),
        });
    }
    Ok(points)
}

/// Parses lines `C GAMMA` in degrees (what `ldt sample` reads): γ must lie in [0°, 180°],
/// C may be any finite angle (it wraps).
pub fn read_angles(input: impl BufRead, name: &str) -> Result<Vec<(f64, f64)>, PointsError> {
    let rows = read_number_lines(input, name, 2, "\"C GAMMA\" in degrees")?;
    rows.into_iter()
        .map(|(line, v)| {
            if (0.0..=180.0).contains(&v[1]) {
                Ok((v[0], v[1]))
            } else {
                Err(PointsError {
                    source_name: name.to_string(),
                    line,
                    message: format!("γ {} outside [0°, 180°]", v[1]),
                })
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn usable_lux_refuses_what_is_not_a_number_and_zeroes_rounding() {
        let mut lux = [1.5, -0.0, -1e-9, 0.0];
        assert_eq!(usable_lux(&mut lux), Ok(()));
        assert_eq!(lux, [1.5, 0.0, 0.0, 0.0]);
        assert!(lux.iter().all(|v| v.is_sign_positive()));
        for bad in [f64::NAN, f64::INFINITY, -0.01] {
            let mut lux = [3.0, bad, 4.0];
            let e = usable_lux(&mut lux).unwrap_err();
            assert_eq!(e.point, 2);
            assert!(e
                .to_string()
                .starts_with("point 2: the computed illuminance"));
        }
    }
}
