//! How a chart is laid out before packing: its plane frame, its triangles in plane
//! coordinates, its texel grid and the elements the triangles cover.

use glam::{DVec2, DVec3};

use crate::geometry::simplify::merge_strips;
use crate::geometry::Mesh;
use crate::radiosity::clusters::obb::{convex_hull, Obb};
use crate::radiosity::polygon::{area_centroid, clip_square, outline};

/// One triangle to be split into elements.
#[derive(Debug, Clone, Copy)]
pub struct InputTriangle {
    /// Corners, metres, counter-clockwise seen from the front.
    pub corners: [DVec3; 3],
    /// Index of its material.
    pub material: usize,
    /// Texel side, metres (1 / the object's texel density).
    pub texel_m: f64,
}

/// One chart before packing: its triangles, plane frame and texel grid.
pub(super) struct ChartPlan {
    pub(super) material: usize,
    pub(super) texel_m: f64,
    /// Triangles with an area, with their corners in plane coordinates (as given) and
    /// the factor from plane area to their true area (1 for a chart of one triangle).
    pub(super) triangles: Vec<(u32, [DVec2; 3], f64)>,
    /// The surface the elements cover: the triangles with CAD fans merged back into the
    /// triangles they fill (the same points, within a millionth of the chart's size),
    /// counter-clockwise in plane coordinates with their true/plane area factor.
    /// Clipping texels against a face's 350 slivers one by one was most of the layout's
    /// time on CAD models.
    coverage: Vec<([DVec2; 3], f64)>,
    /// The triangles' true area over the coverage's (1 up to rounding and the merge's
    /// tolerance): element areas are scaled by it, so they sum to the triangles' area.
    coverage_scale: f64,
    pub(super) origin: DVec3,
    pub(super) axes: [DVec3; 2],
    pub(super) normal: DVec3,
    pub(super) lo: DVec2,
    pub(super) cols: u32,
    pub(super) rows: u32,
}

/// One element before packing: column, row, area (m²) and centroid (plane coordinates).
pub(super) type Laid = (u32, u32, f64, DVec2);

fn has_area(t: &InputTriangle) -> Option<DVec3> {
    let [a, b, c] = t.corners;
    let n = (b - a).cross(c - a);
    (n.length() > 1e-14 && n.is_finite()).then_some(n)
}

/// `corners` counter-clockwise in the plane (clipping needs that orientation).
fn counter_clockwise(mut corners: [DVec2; 3]) -> [DVec2; 3] {
    if (corners[1] - corners[0]).perp_dot(corners[2] - corners[0]) < 0.0 {
        corners.swap(1, 2);
    }
    corners
}

impl ChartPlan {
    /// The plan of the triangles `members` (one material, one texel size), its grid's
    /// columns and rows a multiple of `multiple` (the side of an unsplit element).
    pub(super) fn new(triangles: &[InputTriangle], members: &[u32], multiple: u32) -> ChartPlan {
        let first = &triangles[members[0] as usize];
        let with_area: Vec<(u32, DVec3)> = members
            .iter()
            .filter_map(|&t| has_area(&triangles[t as usize]).map(|n| (t, n)))
            .collect();
        let area_normal: DVec3 = with_area.iter().map(|(_, n)| *n).sum();
        let (origin, axes, normal) = match with_area.as_slice() {
            [] => (DVec3::ZERO, [DVec3::X, DVec3::Y], DVec3::Z),
            // One triangle: its own frame, u along its first edge.
            [(t, n)] => {
                let [a, b, _] = triangles[*t as usize].corners;
                let n = n.normalize();
                let u = (b - a).normalize();
                (a, [u, n.cross(u)], n)
            }
            // Several: the plane through their corners' mean along their summed normal,
            // axes along the minimum-area rectangle (a tight rectangle in the atlas).
            many => {
                let corners: Vec<DVec3> = many
                    .iter()
                    .flat_map(|(t, _)| triangles[*t as usize].corners)
                    .collect();
                let n = area_normal.normalize_or(DVec3::Z);
                let u = Obb::around(&corners, n).axes[0];
                let mean = corners.iter().sum::<DVec3>() / corners.len() as f64;
                (mean, [u, n.cross(u)], n)
            }
        };
        let single = with_area.len() == 1;
        let to_2d = |p: DVec3| DVec2::new((p - origin).dot(axes[0]), (p - origin).dot(axes[1]));
        let laid: Vec<(u32, [DVec2; 3], f64)> = with_area
            .iter()
            .map(|&(t, n)| {
                let c = triangles[t as usize].corners.map(to_2d);
                let plane = (c[1] - c[0]).perp_dot(c[2] - c[0]).abs();
                let scale = if single || plane <= 0.0 {
                    1.0
                } else {
                    n.length() / plane
                };
                (t, c, scale)
            })
            .collect();
        let (coverage, coverage_scale) = coverage(triangles, &with_area, &laid, to_2d, single);
        let lo = laid
            .iter()
            .flat_map(|l| l.1)
            .fold(DVec2::splat(f64::INFINITY), DVec2::min);
        let hi = laid
            .iter()
            .flat_map(|l| l.1)
            .fold(DVec2::splat(f64::NEG_INFINITY), DVec2::max);
        let s = first.texel_m;
        // Saturating casts: a huge grid is refused by the caller, never allocated.
        let (cols, rows) = if laid.is_empty() {
            (0, 0)
        } else {
            let side = |extent: f64| {
                ((extent / s).ceil() as u32)
                    .max(1)
                    .saturating_add(multiple.max(1) - 1)
                    / multiple.max(1)
                    * multiple.max(1)
            };
            (side(hi.x - lo.x), side(hi.y - lo.y))
        };
        ChartPlan {
            material: first.material,
            texel_m: s,
            triangles: laid,
            coverage,
            coverage_scale,
            origin,
            axes,
            normal,
            lo: if cols == 0 { DVec2::ZERO } else { lo },
            cols,
            rows,
        }
    }

    pub(super) fn to_world(&self, p: DVec2) -> DVec3 {
        self.origin + self.axes[0] * p.x + self.axes[1] * p.y
    }

    /// Texels (with a one-texel gutter on each side) of its atlas rectangle.
    pub(super) fn texels(&self) -> u64 {
        if self.cols == 0 {
            return 0;
        }
        (self.cols as u64 + 2) * (self.rows as u64 + 2)
    }

    /// The texel columns and rows a triangle's bounding box touches.
    fn span(&self, c: &[DVec2; 3]) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
        let s = self.texel_m;
        let lo = (c[0].min(c[1]).min(c[2]) - self.lo) / s;
        let hi = (c[0].max(c[1]).max(c[2]) - self.lo) / s;
        // At least one texel, inside the grid, whatever rounding did to a sliver's box.
        let range = |lo: f64, hi: f64, n: u32| {
            let last = n.max(1) - 1;
            let start = (lo.floor().max(0.0) as u32).min(last);
            start..(hi.ceil().max(0.0) as u32).clamp(start + 1, last + 1)
        };
        (range(lo.x, hi.x, self.cols), range(lo.y, hi.y, self.rows))
    }

    /// The elements: every texel the chart's triangles touch, with the area and centroid
    /// of the triangles' parts inside it.
    pub(super) fn elements(&self) -> Vec<Laid> {
        let s = self.texel_m;
        let cells = self.cols as usize * self.rows as usize;
        let mut area = vec![0.0f64; cells];
        let mut moment = vec![DVec2::ZERO; cells];
        for (ccw, scale) in &self.coverage {
            let scale = scale * self.coverage_scale;
            let (columns, rows) = self.span(ccw);
            for j in rows {
                for i in columns.clone() {
                    let sq_lo = self.lo + DVec2::new(i as f64, j as f64) * s;
                    let poly = clip_square(sq_lo, sq_lo + DVec2::splat(s), ccw);
                    if poly.len() < 3 {
                        continue;
                    }
                    let (a, centroid) = area_centroid(&poly);
                    let k = j as usize * self.cols as usize + i as usize;
                    area[k] += a * scale;
                    moment[k] += centroid * (a * scale);
                }
            }
        }
        let mut out = Vec::new();
        for j in 0..self.rows {
            for i in 0..self.cols {
                let k = j as usize * self.cols as usize + i as usize;
                if area[k] > 1e-12 * s * s {
                    out.push((i, j, area[k], moment[k] / area[k]));
                }
            }
        }
        out
    }

    /// Per block of `block` texels, the chart's coverage triangles (indices) whose
    /// bounding boxes touch it.
    pub(super) fn triangles_by_block(
        &self,
        block: u32,
    ) -> std::collections::HashMap<(u32, u32), Vec<usize>> {
        let mut bins: std::collections::HashMap<(u32, u32), Vec<usize>> = Default::default();
        for (k, (c, _)) in self.coverage.iter().enumerate() {
            let (columns, rows) = self.span(c);
            for j in rows.start / block..=(rows.end - 1) / block {
                for i in columns.start / block..=(columns.end - 1) / block {
                    bins.entry((i, j)).or_default().push(k);
                }
            }
        }
        bins
    }

    /// The polygon of the block of `side` metres at `lo` clipped to the chart's
    /// coverage triangles `touching`.
    pub(super) fn block_polygon(&self, lo: DVec2, side: f64, touching: &[usize]) -> Vec<DVec2> {
        let hi = lo + DVec2::splat(side);
        let pieces = touching.iter().filter_map(|&k| {
            let piece = clip_square(lo, hi, &self.coverage[k].0);
            (piece.len() >= 3).then_some(piece)
        });
        if self.coverage.len() == 1 {
            return pieces.into_iter().next().unwrap_or_default();
        }
        let points: Vec<DVec2> = pieces.flatten().collect();
        outline(&convex_hull(&points), lo, hi)
    }
}

/// A chart's coverage ([`ChartPlan`]): its triangles `with_area` (and their normals),
/// laid in the plane as `laid`, with CAD fans merged; and the true-area scale.
fn coverage(
    triangles: &[InputTriangle],
    with_area: &[(u32, DVec3)],
    laid: &[(u32, [DVec2; 3], f64)],
    to_2d: impl Fn(DVec3) -> DVec2,
    single: bool,
) -> (Vec<([DVec2; 3], f64)>, f64) {
    let as_laid = || {
        let cover = laid.iter().map(|l| (counter_clockwise(l.1), l.2)).collect();
        (cover, 1.0)
    };
    if with_area.len() < 2 {
        return as_laid();
    }
    let mut mesh = Mesh::default();
    for (t, _) in with_area {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(triangles[*t as usize].corners);
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    let size = mesh.bounds().map_or(1.0, |(lo, hi)| (hi - lo).length());
    let merged = merge_strips(&mesh, 1e-6 * size.max(1.0));
    if merged.triangles.len() == with_area.len() {
        return as_laid();
    }
    let true_area = |a: DVec3, b: DVec3, c: DVec3| 0.5 * (b - a).cross(c - a).length();
    let mut cover = Vec::with_capacity(merged.triangles.len());
    let mut merged_area = 0.0;
    for t in &merged.triangles {
        let [a, b, c] = t.map(|i| merged.positions[i as usize]);
        let p = [a, b, c].map(&to_2d);
        let plane = (p[1] - p[0]).perp_dot(p[2] - p[0]).abs();
        let area = true_area(a, b, c);
        merged_area += area;
        let scale = if single || plane <= 0.0 {
            1.0
        } else {
            2.0 * area / plane
        };
        cover.push((counter_clockwise(p), scale));
    }
    let source: f64 = with_area.iter().map(|(_, n)| 0.5 * n.length()).sum();
    (
        cover,
        if merged_area > 0.0 {
            source / merged_area
        } else {
            1.0
        },
    )
}

/// Shelf packing of rectangles (w, h) into an atlas of `width`: positions and height.
pub(super) fn pack(sizes: &[(u32, u32)], width: u32) -> (Vec<[u32; 2]>, u32) {
    let mut order: Vec<usize> = (0..sizes.len()).collect();
    order.sort_by_key(|&k| (std::cmp::Reverse(sizes[k].1), std::cmp::Reverse(sizes[k].0)));
    let mut at = vec![[0u32; 2]; sizes.len()];
    let (mut x, mut y, mut shelf) = (0u32, 0u32, 0u32);
    for k in order {
        let (w, h) = sizes[k];
        if x + w > width {
            x = 0;
            y += shelf;
            shelf = 0;
        }
        at[k] = [x, y];
        x += w;
        shelf = shelf.max(h);
    }
    (at, y + shelf)
}

/// Groups triangles by chart id, material and texel size, in the order of their first
/// triangle.
pub(super) fn group(triangles: &[InputTriangle], chart_of: &[u32]) -> Vec<Vec<u32>> {
    let mut index = std::collections::HashMap::new();
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for (t, (tri, &id)) in triangles.iter().zip(chart_of).enumerate() {
        let key = (id, tri.material, tri.texel_m.to_bits());
        let g = *index.entry(key).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(t as u32);
    }
    groups
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_triangle_box_at_the_grid_edge_spans_one_texel_inside_the_grid() {
        // One triangle: its own frame, u along its first edge (+x), v along +y.
        let t = InputTriangle {
            corners: [
                DVec3::ZERO,
                DVec3::new(2.5, 0.0, 0.0),
                DVec3::new(0.0, 2.5, 0.0),
            ],
            material: 0,
            texel_m: 1.0,
        };
        let plan = ChartPlan::new(&[t], &[0], 1);
        assert_eq!((plan.cols, plan.rows), (3, 3));
        // A box starting on the grid's far edge (rounding in a sliver's corners) and one
        // past it: both clamp to the last texel instead of an empty or inverted range.
        for x in [3.0, 3.5] {
            let c = [
                DVec2::new(x, 0.0),
                DVec2::new(x + 1e-3, 0.0),
                DVec2::new(x, 1.0),
            ];
            let (columns, rows) = plan.span(&c);
            assert_eq!(columns, 2..3, "{x}");
            assert_eq!(rows, 0..1);
        }
        let whole = [DVec2::ZERO, DVec2::new(3.0, 0.0), DVec2::new(0.0, 3.0)];
        assert_eq!(plan.span(&whole), (0..3, 0..3));
    }

    #[test]
    fn merged_fans_lay_the_same_elements_as_their_strips() {
        // A 1.6 × 0.8 m desk top at 0.72 m as two triangles fanned into 350 strips each,
        // corners rounded to micrometres as an OBJ stores them.
        let quad = crate::geometry::Mesh {
            positions: vec![
                DVec3::new(0.3, 0.2, 0.72),
                DVec3::new(1.9, 0.2, 0.72),
                DVec3::new(1.9, 1.0, 0.72),
                DVec3::new(0.3, 1.0, 0.72),
            ],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        };
        let fine = crate::geometry::generate::fan_split(&quad, 350);
        let round = |p: DVec3| (p * 1e6).round() / 1e6;
        let input: Vec<InputTriangle> = fine
            .triangles
            .iter()
            .map(|t| InputTriangle {
                corners: t.map(|i| round(fine.positions[i as usize])),
                material: 0,
                texel_m: 0.1,
            })
            .collect();
        let members: Vec<u32> = (0..input.len() as u32).collect();
        let plan = ChartPlan::new(&input, &members, 1);
        assert_eq!(
            plan.coverage.len(),
            2,
            "each fan merges back into its triangle"
        );
        // The oracle: every strip clipped against every texel it touches.
        let s = plan.texel_m;
        let cells = (plan.cols * plan.rows) as usize;
        let (mut area, mut moment) = (vec![0.0; cells], vec![DVec2::ZERO; cells]);
        for (_, c, scale) in &plan.triangles {
            let (columns, rows) = plan.span(c);
            for j in rows {
                for i in columns.clone() {
                    let lo = plan.lo + DVec2::new(i as f64, j as f64) * s;
                    let poly = clip_square(lo, lo + DVec2::splat(s), &counter_clockwise(*c));
                    if poly.len() >= 3 {
                        let (a, centroid) = area_centroid(&poly);
                        let k = (j * plan.cols + i) as usize;
                        area[k] += a * scale;
                        moment[k] += centroid * (a * scale);
                    }
                }
            }
        }
        let laid = plan.elements();
        let expected: Vec<usize> = (0..cells).filter(|&k| area[k] > 1e-12 * s * s).collect();
        assert_eq!(laid.len(), expected.len());
        for ((i, j, a, centroid), &k) in laid.iter().zip(&expected) {
            assert_eq!((j * plan.cols + i) as usize, k);
            assert!(
                (a / area[k] - 1.0).abs() < 1e-6,
                "texel {k}: {a} vs {}",
                area[k]
            );
            assert!(centroid.distance(moment[k] / area[k]) < 1e-6 * s);
        }
        let total: f64 = laid.iter().map(|l| l.2).sum();
        assert!((total - 1.28).abs() < 1e-9, "{total} m²");
    }
}
