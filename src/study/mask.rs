//! The obstruction mask of a point: which parts of its sky the model hides, on a grid of
//! [`MASK_STEP_DEG`] of azimuth by as much elevation, each cell hidden when the ray
//! through its centre meets the model or leaves behind the point's own surface. Drawn on
//! the sun-path diagram, it shows when the point is in shade: wherever a sun path crosses
//! the grey.

use std::fmt::Write as _;

use glam::DVec3;

use crate::shadow::bvh::TriangleBvh;
use crate::shadow::IgnoredTriangles;
use crate::sun::direction_from_angles;

/// Side of a mask cell, degrees of azimuth and of elevation.
pub const MASK_STEP_DEG: f64 = 2.0;
/// Cells along the azimuth (a full turn).
const COLUMNS: usize = (360.0 / MASK_STEP_DEG) as usize;
/// Cells along the elevation (horizon to zenith).
const ROWS: usize = (90.0 / MASK_STEP_DEG) as usize;

/// What a point's sky hides.
#[derive(Debug, Clone)]
pub struct ObstructionMask {
    /// The point's name.
    pub name: String,
    /// Per elevation row (from the horizon up), per azimuth column (from north, clockwise):
    /// whether the cell is hidden.
    hidden: Vec<[bool; COLUMNS]>,
}

/// What a mask is cast against: the model, the offset off the surface, the triangles that
/// cast no shadow and the azimuth of the model's +y axis east of true north.
pub struct MaskRays<'a> {
    /// The model.
    pub bvh: &'a TriangleBvh,
    /// How far the point is moved off its surface along its normal, metres.
    pub eps: f64,
    /// Triangles that cast no shadow.
    pub non_casters: &'a IgnoredTriangles,
    /// `--north-offset`, degrees.
    pub north_offset_deg: f64,
}

impl ObstructionMask {
    /// Casts the mask of the point `name` at `point` on a surface facing `normal` (unit).
    pub fn cast(rays: &MaskRays, name: &str, point: DVec3, normal: DVec3) -> ObstructionMask {
        let origin = point + normal * rays.eps;
        let hidden = (0..ROWS)
            .map(|i| {
                let mut row = [false; COLUMNS];
                for (j, cell) in row.iter_mut().enumerate() {
                    let (az, el) = centre(i, j);
                    let dir = direction_from_angles(az, el, rays.north_offset_deg);
                    *cell = dir.dot(normal) <= 0.0
                        || rays
                            .bvh
                            .blocked(origin, dir, 0.0, f64::INFINITY, rays.non_casters);
                }
                row
            })
            .collect();
        ObstructionMask {
            name: name.to_string(),
            hidden,
        }
    }

    /// Whether the sky at `azimuth_deg` (true north) and `elevation_deg` is hidden (the
    /// cell holding it; below the horizon: hidden).
    pub fn hides(&self, azimuth_deg: f64, elevation_deg: f64) -> bool {
        if elevation_deg < 0.0 {
            return true;
        }
        let i = ((elevation_deg / MASK_STEP_DEG) as usize).min(ROWS - 1);
        let j = ((azimuth_deg.rem_euclid(360.0) / MASK_STEP_DEG) as usize).min(COLUMNS - 1);
        self.hidden[i][j]
    }

    /// The share of the sky hemisphere's cells hidden, weighted by solid angle.
    pub fn hidden_sky_fraction(&self) -> f64 {
        let (mut hidden, mut all) = (0.0, 0.0);
        for (i, row) in self.hidden.iter().enumerate() {
            let (_, el) = centre(i, 0);
            let w = el.to_radians().cos();
            all += w * COLUMNS as f64;
            hidden += w * row.iter().filter(|&&h| h).count() as f64;
        }
        hidden / all
    }

    /// SVG polygons of the hidden cells, each row's runs merged, in the diagram's
    /// projection (`project(azimuth, elevation)` → SVG point).
    pub fn svg(&self, project: impl Fn(f64, f64) -> (f64, f64)) -> String {
        let mut s = String::from(r#"<g id="mask" fill="rgb(110,110,110)" fill-opacity="0.35">"#);
        s.push('\n');
        for (i, row) in self.hidden.iter().enumerate() {
            let (lo, hi) = (i as f64 * MASK_STEP_DEG, (i + 1) as f64 * MASK_STEP_DEG);
            let mut j = 0;
            while j < COLUMNS {
                if !row[j] {
                    j += 1;
                    continue;
                }
                let start = j;
                while j < COLUMNS && row[j] {
                    j += 1;
                }
                let (a0, a1) = (start as f64 * MASK_STEP_DEG, j as f64 * MASK_STEP_DEG);
                let project = &project;
                let arc = |el: f64, forward: bool| -> Vec<(f64, f64)> {
                    (0..=(j - start))
                        .map(|k| {
                            let k = if forward { k } else { j - start - k };
                            project(a0 + k as f64 * MASK_STEP_DEG, el)
                        })
                        .collect()
                };
                let outline: Vec<String> = arc(lo, true)
                    .into_iter()
                    .chain(arc(hi, false))
                    .map(|(x, y)| format!("{x:.1},{y:.1}"))
                    .collect();
                let _ = writeln!(
                    s,
                    r#"<polygon points="{}" data-azimuth="{a0}-{a1}" data-elevation="{lo}-{hi}"/>"#,
                    outline.join(" ")
                );
            }
        }
        s.push_str("</g>\n");
        s
    }
}

/// Azimuth and elevation of the centre of cell (row `i`, column `j`), degrees.
fn centre(i: usize, j: usize) -> (f64, f64) {
    (
        (j as f64 + 0.5) * MASK_STEP_DEG,
        (i as f64 + 0.5) * MASK_STEP_DEG,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::generate::cuboid;

    /// A wall 200 m wide and 10 m high (its top 10 m above the point), 10 m south of the
    /// point at the origin: from the point it hides the sky up to 45° due south.
    fn wall_mask(normal: DVec3) -> ObstructionMask {
        let wall = cuboid(
            DVec3::new(-100.0, -10.5, 0.0),
            DVec3::new(100.0, -10.0, 10.0),
        );
        let bvh = TriangleBvh::new(&wall);
        let rays = MaskRays {
            bvh: &bvh,
            eps: 1e-6,
            non_casters: &IgnoredTriangles::default(),
            north_offset_deg: 0.0,
        };
        ObstructionMask::cast(&rays, "yard", DVec3::ZERO, normal)
    }

    #[test]
    fn a_wall_to_the_south_hides_the_sky_up_to_its_angle() {
        let mask = wall_mask(DVec3::Z);
        for el in [1.0, 20.0, 43.0] {
            assert!(mask.hides(181.0, el), "south at {el}°");
        }
        for el in [47.0, 60.0, 89.0] {
            assert!(!mask.hides(181.0, el), "south at {el}°");
        }
        // Along the wall, its angle falls as 1/√(1 + (x/10)²): at azimuth 135° (x = 10 m
        // across, 14.1 m away) the wall's top stands at atan(10 / 14.1) = 35.3°.
        assert!(mask.hides(135.0, 33.0) && !mask.hides(135.0, 37.0));
        for az in [1.0, 45.0, 91.0, 269.0, 315.0] {
            assert!(!mask.hides(az, 1.0), "azimuth {az}");
        }
        let f = mask.hidden_sky_fraction();
        assert!(f > 0.1 && f < 0.5, "{f}");
    }

    #[test]
    fn a_window_facing_north_sees_no_southern_sky() {
        let mask = wall_mask(DVec3::Y);
        assert!(mask.hides(181.0, 60.0) && mask.hides(95.0, 10.0));
        assert!(!mask.hides(1.0, 30.0) && !mask.hides(85.0, 10.0));
        assert!(mask.svg(|a, e| (a, e)).contains("<polygon"));
    }
}
