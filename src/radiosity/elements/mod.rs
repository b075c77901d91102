//! Radiosity elements: every chart gets a rectangle of texels in a light-map atlas
//! (Wallner §2.3, §4.2). A chart is one triangle, or a set of coplanar triangles (with face
//! clusters: each planar cluster, Edström ch. 5) laid in one plane frame and one rectangle,
//! so the light map runs on across their shared edges without a seam. Texel size per object
//! comes from the user's texel density; every texel whose square touches a triangle of the
//! chart is an element (conservative coverage, §2.3.1), with the exact area and centroid of
//! the part of the chart's triangles inside it, so the elements of a chart tile it exactly.
//! Elements are grouped into shooting patches of 2^level × 2^level texels (substructuring:
//! a coarser mip level shoots, the fine elements receive). Texels around the covered ones
//! get a display source (gutter fill) so bilinear filtering never reads an empty texel.
//! With adaptive subdivision ([`Subdivision`]) an element is a block of 2^k × 2^k texels,
//! split where it straddles a shadow boundary.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

mod display;
mod plan;
mod subdivide;

pub use plan::InputTriangle;
use plan::{group, pack, ChartPlan};
use subdivide::{lay_out, LaidPatch};
pub use subdivide::{NeverSplit, SplitTest, Subdivision};

/// A shooting patch: a block of a chart's texels (one texel of a coarser mip level).
#[derive(Debug, Clone)]
pub struct Patch {
    /// First element (the patch's elements are contiguous).
    pub first: u32,
    /// Number of elements.
    pub count: u32,
    /// The block clipped to the chart, counter-clockwise from the front: exact for a
    /// chart of one triangle, the convex hull of the clipped triangles (at most 8
    /// corners) for a chart of several.
    pub polygon: Vec<DVec3>,
    /// Area-weighted centre, metres.
    pub centroid: DVec3,
    /// Its elements' area, m².
    pub area: f64,
}

/// A chart: triangles sharing one plane frame and one rectangle of the atlas.
#[derive(Debug, Clone)]
pub struct Chart {
    /// First element (a chart's elements are contiguous, patch after patch).
    pub first: u32,
    /// Number of elements.
    pub count: u32,
    /// First patch.
    pub first_patch: u32,
    /// Number of patches.
    pub patch_count: u32,
    /// Unit normal of its plane.
    pub normal: DVec3,
    /// Material index.
    pub material: usize,
    /// Area, m² (its triangles' exact area).
    pub area: f64,
    /// Atlas rectangle: x, y, width, height in texels (one gutter texel on each side).
    pub rect: [u32; 4],
    /// Texel side, metres.
    pub texel_m: f64,
    /// Its triangles (those with an area).
    pub triangles: Vec<u32>,
    /// Plane frame: a point of the plane …
    pub origin: DVec3,
    /// … and two unit axes in it (`u × v` is the normal).
    pub axes: [DVec3; 2],
    /// Plane coordinates of the texel grid's corner (column 0, row 0), metres.
    pub lo: DVec2,
}

impl Chart {
    /// The point of the chart's plane at atlas coordinates `p` (texels from the atlas's
    /// top-left corner).
    pub fn atlas_to_world(&self, p: DVec2) -> DVec3 {
        let rows = self.rect[3].saturating_sub(2) as f64;
        let x = self.lo.x + (p.x - self.rect[0] as f64 - 1.0) * self.texel_m;
        let y = self.lo.y + (self.rect[1] as f64 + 1.0 + rows - p.y) * self.texel_m;
        self.origin + self.axes[0] * x + self.axes[1] * y
    }
}

/// Where one triangle lies in the atlas.
#[derive(Debug, Clone)]
pub struct TriangleElements {
    /// Its chart; `u32::MAX` for a triangle without area (it has no elements).
    pub chart: u32,
    /// Unit face normal.
    pub normal: DVec3,
    /// Material index.
    pub material: usize,
    /// Area, m² (0 for a triangle without area).
    pub area: f64,
    /// Atlas coordinates (texels, from the atlas's top-left corner) of the corners.
    pub atlas_uv: [DVec2; 3],
}

/// All elements of a scene, chart after chart.
#[derive(Debug, Clone, Default)]
pub struct Elements {
    /// Atlas width, texels.
    pub atlas_width: u32,
    /// Atlas height, texels.
    pub atlas_height: u32,
    /// Element centroids, metres.
    pub position: Vec<DVec3>,
    /// Element areas, m².
    pub area: Vec<f64>,
    /// Element atlas texels: the top-left texel of its block of [`Self::span`] texels.
    pub texel: Vec<[u32; 2]>,
    /// Side of each element's block of texels (1 without adaptive subdivision).
    pub span: Vec<u32>,
    /// Element → chart.
    pub chart: Vec<u32>,
    /// The charts, in the order of their first triangle.
    pub charts: Vec<Chart>,
    /// Per input triangle.
    pub triangles: Vec<TriangleElements>,
    /// Shooting patches, in chart order.
    pub patches: Vec<Patch>,
    /// Substructuring level: patches are 2^level texels square (with adaptive
    /// subdivision, the levels of [`Self::subdivision`] included).
    pub level: u32,
    /// How elements were subdivided ([`Subdivision::NONE`]: one per texel).
    pub subdivision: Subdivision,
    /// Per atlas texel (row-major): the element whose value it shows, `u32::MAX` for none.
    pub display_source: Vec<u32>,
}

/// Largest atlas side.
pub const MAX_ATLAS: u32 = 8192;

/// Most levels of adaptive subdivision (an unsplit element of 2^6 × 2^6 texels).
pub const MAX_SUBDIVISION: u32 = 6;

/// Why elements cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ElementError {
    /// The texel size is not a positive number.
    #[error("texel size {0} m is not a positive number (is the texel density positive?)")]
    TexelSize(f64),
    /// Too many texels for the largest atlas.
    #[error(
        "{} texels do not fit in an {MAX_ATLAS} × {MAX_ATLAS} atlas: lower the texel density (or the adaptive subdivision's levels: each quadruples the texels)",
        texel_count(*.0)
    )]
    TooLarge(u64),
    /// No surface absorbs: every one gives back all the light it receives, so a closed
    /// room has no finite solution.
    #[error(
        "no surface absorbs light: material {name:?} (like every other) reflects and transmits {sum:.4} of the light it receives (at most {MAX_SENT_BACK} absorbs): a room whose surfaces absorb nothing has no finite radiosity solution; lower a reflectance (Kd, diffuse_reflectance) or transmittance"
    )]
    Lossless {
        /// The material's name.
        name: String,
        /// Reflectance plus transmittance, its largest channel.
        sum: f32,
    },
    /// No triangle with an area.
    #[error("the scene has no triangle with an area")]
    Empty,
    /// More subdivision levels than [`MAX_SUBDIVISION`].
    #[error("{0} adaptive subdivision levels: at most {MAX_SUBDIVISION}")]
    Subdivision(u32),
    /// A chart id list of the wrong length.
    #[error("{given} chart ids for {triangles} triangles")]
    ChartIds {
        /// Ids given.
        given: usize,
        /// Triangles.
        triangles: usize,
    },
}

/// The most a surface may send back out of the light it receives (reflectance plus
/// transmittance, any channel): the whitest real surfaces reach about 0.99.
pub const MAX_SENT_BACK: f32 = 0.999;

/// A texel count as people read it: digits up to a trillion, then "about 1.4e19".
fn texel_count(n: u64) -> String {
    if n < 1_000_000_000_000 {
        n.to_string()
    } else {
        format!("about {:.1e}", n as f64)
    }
}

impl Elements {
    /// How many elements there are of each side (index k: 2^k × 2^k texels, up to the
    /// subdivision's levels), and the texels they cover together.
    pub fn sizes(&self) -> (Vec<usize>, u64) {
        let mut by_side = vec![0usize; self.subdivision.levels as usize + 1];
        for &s in &self.span {
            by_side[s.trailing_zeros() as usize] += 1;
        }
        let texels = self.span.iter().map(|&s| u64::from(s) * u64::from(s)).sum();
        (by_side, texels)
    }

    /// Splits `triangles` into elements with shooting patches of 2^`level` texels, each
    /// triangle its own chart.
    pub fn build(triangles: &[InputTriangle], level: u32) -> Result<Elements, ElementError> {
        let ids: Vec<u32> = (0..triangles.len() as u32).collect();
        Elements::build_charts(triangles, &ids, level)
    }

    /// [`Elements::build`] with the triangles of equal `chart_of` (and equal material and
    /// texel size) sharing one chart, laid in their summed normal's plane: give only
    /// triangles that are coplanar (within a small fraction of a texel) and connected.
    pub fn build_charts(
        triangles: &[InputTriangle],
        chart_of: &[u32],
        level: u32,
    ) -> Result<Elements, ElementError> {
        Elements::build_subdivided(triangles, chart_of, level, Subdivision::NONE, &NeverSplit)
    }

    /// [`Elements::build_charts`] with adaptive subdivision: the triangles' texels are the
    /// finest elements, an element is a block of 2^`subdivision.levels` of them unless
    /// `test` splits it (recursively), and patches are 2^`level` unsplit elements square.
    pub fn build_subdivided(
        triangles: &[InputTriangle],
        chart_of: &[u32],
        level: u32,
        subdivision: Subdivision,
        test: &dyn SplitTest,
    ) -> Result<Elements, ElementError> {
        if chart_of.len() != triangles.len() {
            return Err(ElementError::ChartIds {
                given: chart_of.len(),
                triangles: triangles.len(),
            });
        }
        if subdivision.levels > MAX_SUBDIVISION {
            return Err(ElementError::Subdivision(subdivision.levels));
        }
        for t in triangles {
            if !(t.texel_m.is_finite() && t.texel_m > 0.0) {
                return Err(ElementError::TexelSize(t.texel_m));
            }
        }
        let plans: Vec<ChartPlan> = group(triangles, chart_of)
            .iter()
            .map(|members| ChartPlan::new(triangles, members, subdivision.block()))
            .collect();
        // Count the texels (with gutters) before laying any out: a density that cannot
        // fit is refused in milliseconds, not after gigabytes of elements. Shelf packing
        // needs about 10 % more than the sum (the atlas width below allows for that).
        let total: u64 = plans.iter().map(ChartPlan::texels).sum();
        if total == 0 {
            return Err(ElementError::Empty);
        }
        let widest = plans
            .iter()
            .map(|p| p.cols.saturating_add(2))
            .max()
            .unwrap_or(1);
        if total as f64 * 1.1 > (MAX_ATLAS as f64).powi(2) || widest > MAX_ATLAS {
            return Err(ElementError::TooLarge(total));
        }
        let sizes: Vec<(u32, u32)> = plans
            .iter()
            .map(|p| match p.cols {
                0 => (0, 0),
                _ => (p.cols + 2, p.rows + 2),
            })
            .collect();
        let width = (((total as f64 * 1.1).sqrt().ceil() as u32).max(widest))
            .next_multiple_of(64)
            .min(MAX_ATLAS);
        let (origins, height) = pack(&sizes, width);
        if height > MAX_ATLAS {
            return Err(ElementError::TooLarge(total));
        }
        let level = level + subdivision.levels;
        let patch = 1u32 << level;
        let laid: Vec<Vec<LaidPatch>> = plans
            .par_iter()
            .map(|plan| lay_out(plan, patch, subdivision.block(), test))
            .collect();
        let mut out = Elements {
            atlas_width: width,
            atlas_height: height.max(1),
            level,
            subdivision,
            display_source: vec![u32::MAX; width as usize * height.max(1) as usize],
            triangles: triangles
                .iter()
                .map(|t| TriangleElements {
                    chart: u32::MAX,
                    normal: DVec3::Z,
                    material: t.material,
                    area: 0.0,
                    atlas_uv: [DVec2::ZERO; 3],
                })
                .collect(),
            ..Default::default()
        };
        for ((plan, origin), patches) in plans.iter().zip(origins).zip(laid) {
            out.push_chart(triangles, plan, origin, patch, patches);
        }
        out.fill_gutters();
        Ok(out)
    }

    fn push_chart(
        &mut self,
        triangles: &[InputTriangle],
        plan: &ChartPlan,
        origin: [u32; 2],
        block: u32,
        patches: Vec<LaidPatch>,
    ) {
        let s = plan.texel_m;
        let first = self.position.len() as u32;
        let first_patch = self.patches.len() as u32;
        let chart = self.charts.len() as u32;
        let bins = plan.triangles_by_block(block);
        for laid in patches {
            let key = laid.key;
            let lo = plan.lo + DVec2::new(key.0 as f64, key.1 as f64) * s * block as f64;
            let touching = bins.get(&key).map_or(&[][..], Vec::as_slice);
            let poly = plan.block_polygon(lo, s * block as f64, touching);
            let mut patch = Patch {
                first: self.position.len() as u32,
                count: laid.elements.len() as u32,
                polygon: poly.iter().map(|&p| plan.to_world(p)).collect(),
                centroid: DVec3::ZERO,
                area: 0.0,
            };
            for b in &laid.elements {
                patch.area += b.area;
                patch.centroid += plan.to_world(b.centroid) * b.area;
                // Atlas rows run down, plane rows up: the block's top-left texel.
                let texel = [
                    origin[0] + 1 + b.column,
                    origin[1] + 1 + plan.rows - b.row - b.side,
                ];
                let element = self.position.len() as u32;
                for y in texel[1]..texel[1] + b.side {
                    for x in texel[0]..texel[0] + b.side {
                        self.display_source[(y * self.atlas_width + x) as usize] = element;
                    }
                }
                self.position.push(plan.to_world(b.centroid));
                self.area.push(b.area);
                self.texel.push(texel);
                self.span.push(b.side);
                self.chart.push(chart);
            }
            patch.centroid /= patch.area.max(1e-300);
            self.patches.push(patch);
        }
        // Atlas coordinates of the corners: x right with u, y down against v.
        for &(t, c, _) in &plan.triangles {
            let te = &mut self.triangles[t as usize];
            te.chart = chart;
            te.atlas_uv = c.map(|p| {
                let q = (p - plan.lo) / s;
                DVec2::new(
                    origin[0] as f64 + 1.0 + q.x,
                    origin[1] as f64 + 1.0 + plan.rows as f64 - q.y,
                )
            });
            let [a, b, d] = triangles[t as usize].corners;
            let n = (b - a).cross(d - a);
            te.normal = n.normalize();
            te.area = 0.5 * n.length();
        }
        let rect = match plan.cols {
            0 => [origin[0], origin[1], 0, 0],
            _ => [origin[0], origin[1], plan.cols + 2, plan.rows + 2],
        };
        self.charts.push(Chart {
            first,
            count: self.position.len() as u32 - first,
            first_patch,
            patch_count: self.patches.len() as u32 - first_patch,
            normal: plan.normal,
            material: plan.material,
            area: self.area[first as usize..].iter().sum(),
            rect,
            texel_m: s,
            triangles: plan.triangles.iter().map(|t| t.0).collect(),
            origin: plan.origin,
            axes: plan.axes,
            lo: plan.lo,
        });
    }

    /// Gives every empty texel of a chart's rectangle next to a filled one (two rings)
    /// the value of a filled neighbour of the same chart.
    fn fill_gutters(&mut self) {
        let w = self.atlas_width as i64;
        for _ring in 0..2 {
            let mut fills = Vec::new();
            for c in &self.charts {
                let [x0, y0, rw, rh] = c.rect.map(|v| v as i64);
                for y in y0..y0 + rh {
                    for x in x0..x0 + rw {
                        if self.display_source[(y * w + x) as usize] != u32::MAX {
                            continue;
                        }
                        let source = (-1..=1i64)
                            .flat_map(|dy| (-1..=1i64).map(move |dx| (x + dx, y + dy)))
                            .filter(|&(u, v)| u >= x0 && v >= y0 && u < x0 + rw && v < y0 + rh)
                            .map(|(u, v)| self.display_source[(v * w + u) as usize])
                            .find(|&s| s != u32::MAX);
                        if let Some(s) = source {
                            fills.push(((y * w + x) as usize, s));
                        }
                    }
                }
            }
            for (slot, s) in fills {
                self.display_source[slot] = s;
            }
        }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.position.len()
    }

    /// Whether there are no elements.
    pub fn is_empty(&self) -> bool {
        self.position.is_empty()
    }

    /// Unit normal of element `e` (its chart's).
    pub fn normal(&self, e: usize) -> DVec3 {
        self.charts[self.chart[e] as usize].normal
    }

    /// Element `e`'s square in the atlas: its top-left corner and side, texels.
    pub fn atlas_square(&self, e: usize) -> (DVec2, f64) {
        let [tx, ty] = self.texel[e];
        (DVec2::new(tx as f64, ty as f64), self.span[e] as f64)
    }

    /// Element `e`'s side, metres.
    pub fn side_m(&self, e: usize) -> f64 {
        self.charts[self.chart[e] as usize].texel_m * self.span[e] as f64
    }

    /// Points of an `n` × `n` grid over element `e`'s texels that lie on its chart's
    /// triangles; the element's centroid when `n` ≤ 1 or no grid point does. Averages over
    /// these integrate steep gradients (a luminaire close to a surface) that one sample at
    /// the centroid would miss.
    pub fn texel_samples(&self, e: usize, n: u32) -> Vec<DVec3> {
        if n <= 1 {
            return vec![self.position[e]];
        }
        let chart = &self.charts[self.chart[e] as usize];
        let (lo, side) = self.atlas_square(e);
        let hi = lo + DVec2::splat(side);
        let touching: Vec<[DVec2; 3]> = chart
            .triangles
            .iter()
            .map(|&t| self.triangles[t as usize].atlas_uv)
            .filter(|c| {
                let (a, b) = (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]));
                a.x <= hi.x && a.y <= hi.y && b.x >= lo.x && b.y >= lo.y
            })
            .collect();
        let inside = |p: DVec2, [a, b, c]: &[DVec2; 3]| {
            let (v0, v1) = (*b - *a, *c - *a);
            let det = v0.perp_dot(v1);
            let d = p - *a;
            let (u, v) = (d.perp_dot(v1) / det, v0.perp_dot(d) / det);
            det.abs() >= 1e-12 && u >= 0.0 && v >= 0.0 && u + v <= 1.0
        };
        let step = side / n as f64;
        let mut out = Vec::with_capacity((n * n) as usize);
        for j in 0..n {
            for i in 0..n {
                let p = lo + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * step;
                if touching.iter().any(|t| inside(p, t)) {
                    out.push(chart.atlas_to_world(p));
                }
            }
        }
        if out.is_empty() {
            out.push(self.position[e]);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(corners: [DVec3; 3], texel_m: f64) -> InputTriangle {
        InputTriangle {
            corners,
            material: 0,
            texel_m,
        }
    }

    #[test]
    fn texel_samples_lie_on_the_element_around_its_centroid() {
        let corners = [
            DVec3::new(0.1, 0.0, 0.3),
            DVec3::new(1.3, 0.2, 0.0),
            DVec3::new(0.4, 0.9, 0.5),
        ];
        let s = 0.07;
        let el = Elements::build(&[tri(corners, s)], 0).unwrap();
        let n = el.normal(0);
        let mut full = 0;
        for e in 0..el.len() {
            let samples = el.texel_samples(e, 8);
            let mean = samples.iter().sum::<DVec3>() / samples.len() as f64;
            for p in &samples {
                // On the triangle's plane, within the texel around the centroid.
                assert!((*p - corners[0]).dot(n).abs() < 1e-9);
                assert!(p.distance(el.position[e]) <= s * 1.5);
            }
            if el.area[e] > s * s * (1.0 - 1e-9) {
                full += 1;
                // A whole texel: the grid's mean is its centre.
                assert_eq!(samples.len(), 64);
                assert!(mean.distance(el.position[e]) < 1e-9, "{e}");
            } else {
                assert!(mean.distance(el.position[e]) < s / 4.0, "{e}");
            }
        }
        assert!(full > 50, "{full}");
        assert_eq!(el.texel_samples(3, 1), vec![el.position[3]]);
    }

    #[test]
    fn elements_tile_each_triangle_exactly() {
        let t = [
            tri(
                [
                    DVec3::ZERO,
                    DVec3::new(1.3, 0.2, 0.0),
                    DVec3::new(0.4, 0.9, 0.5),
                ],
                0.07,
            ),
            tri(
                [
                    DVec3::new(2.0, 0.0, 0.0),
                    DVec3::new(2.0, 3.0, 0.0),
                    DVec3::new(2.0, 0.0, 1.0),
                ],
                0.25,
            ),
        ];
        for level in 0..4 {
            let e = Elements::build(&t, level).unwrap();
            for (k, te) in e.charts.iter().enumerate() {
                let [a, b, c] = t[k].corners;
                let want = 0.5 * (b - a).cross(c - a).length();
                let range = te.first as usize..(te.first + te.count) as usize;
                let sum: f64 = e.area[range.clone()].iter().sum();
                assert!(
                    (sum - want).abs() < 1e-12 * want.max(1.0),
                    "{sum} vs {want}"
                );
                let patches = &e.patches[te.first_patch as usize..][..te.patch_count as usize];
                let patch_sum: f64 = patches.iter().map(|p| p.area).sum();
                assert!((patch_sum - want).abs() < 1e-12);
                // Each patch's area is its elements' area; its polygon lies in the plane.
                for p in patches {
                    let s: f64 = e.area[p.first as usize..][..p.count as usize].iter().sum();
                    assert!((s - p.area).abs() < 1e-12);
                    for v in &p.polygon {
                        assert!((*v - a).dot(te.normal).abs() < 1e-12);
                    }
                }
                // Centroids lie inside the triangle: barycentric coordinates ≥ 0.
                for &p in &e.position[range] {
                    let n = te.normal;
                    for (q, r) in [(a, b), (b, c), (c, a)] {
                        assert!((r - q).cross(p - q).dot(n) >= -1e-12);
                    }
                }
            }
        }
    }

    #[test]
    fn texels_are_unique_and_every_element_shows_in_the_atlas() {
        let t: Vec<InputTriangle> = (0..50)
            .map(|k| {
                let o = DVec3::new(k as f64, 0.0, 0.0);
                tri(
                    [
                        o,
                        o + DVec3::new(0.8, 0.1, 0.0),
                        o + DVec3::new(0.2, 0.7, 0.0),
                    ],
                    0.1,
                )
            })
            .collect();
        let e = Elements::build(&t, 2).unwrap();
        let mut seen = std::collections::HashSet::new();
        for (k, &[x, y]) in e.texel.iter().enumerate() {
            assert!(seen.insert((x, y)));
            let slot = (y * e.atlas_width + x) as usize;
            assert_eq!(e.display_source[slot], k as u32);
        }
        // The gutter: more texels show a value than there are elements.
        let shown = e.display_source.iter().filter(|&&s| s != u32::MAX).count();
        assert!(shown > e.len() + 50 * 8, "{shown} vs {}", e.len());
    }

    #[test]
    fn a_chart_of_several_triangles_tiles_them_in_one_rectangle() {
        // A hexagon fan of six triangles in a tilted plane, plus one degenerate triangle.
        let (u, v) = (
            DVec3::new(1.0, 0.2, 0.3).normalize(),
            DVec3::new(-0.1, 1.0, 0.4).normalize(),
        );
        let v = (v - u * u.dot(v)).normalize();
        let centre = DVec3::new(0.5, -1.0, 2.0);
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 6.0;
                centre + (u * a.cos() + v * a.sin()) * 1.3
            })
            .collect();
        let mut t: Vec<InputTriangle> = (0..6)
            .map(|k| tri([centre, ring[k], ring[(k + 1) % 6]], 0.09))
            .collect();
        t.push(tri([centre, ring[0], ring[0]], 0.09));
        let e = Elements::build_charts(&t, &[7; 7], 1).unwrap();
        assert_eq!(e.charts.len(), 1);
        let chart = &e.charts[0];
        assert_eq!(chart.triangles, (0..6).collect::<Vec<u32>>());
        assert_eq!(e.triangles[6].chart, u32::MAX, "no area, no chart");
        let want = 6.0 * 0.25 * 3f64.sqrt() * 1.3 * 1.3;
        let sum: f64 = e.area.iter().sum();
        assert!((sum - want).abs() < 1e-12 * want, "{sum} vs {want}");
        assert!((chart.area - want).abs() < 1e-12 * want);
        assert!((chart.normal - u.cross(v)).length() < 1e-12);
        for p in &e.patches {
            let s: f64 = e.area[p.first as usize..][..p.count as usize].iter().sum();
            assert!((s - p.area).abs() < 1e-12);
            assert!((3..=8).contains(&p.polygon.len()));
        }
        // One texel grid: every element in its own texel, on the plane, and the texel's
        // samples around it; the corners shared by two triangles meet in the atlas.
        let mut seen = std::collections::HashSet::new();
        for k in 0..e.len() {
            assert!(seen.insert(e.texel[k]));
            assert!((e.position[k] - centre).dot(chart.normal).abs() < 1e-12);
            for p in e.texel_samples(k, 4) {
                assert!((p - centre).dot(chart.normal).abs() < 1e-12);
                assert!(p.distance(e.position[k]) <= 0.09 * 1.5);
            }
        }
        for k in 0..6 {
            let next = (k + 1) % 6;
            let (a, b) = (e.triangles[k].atlas_uv, e.triangles[next].atlas_uv);
            assert!(a[0].distance(b[0]) < 1e-9 && a[2].distance(b[1]) < 1e-9);
        }
        // The atlas maps back onto the plane where the corners are.
        for (k, c) in ring.iter().enumerate() {
            let back = chart.atlas_to_world(e.triangles[k].atlas_uv[1]);
            assert!(back.distance(*c) < 1e-9, "{back} vs {c}");
        }
        assert!(matches!(
            Elements::build_charts(&t, &[0; 3], 0),
            Err(ElementError::ChartIds { .. })
        ));
    }

    /// Splits blocks with points on both sides of x = 0.37.
    struct SplitAtX;

    impl SplitTest for SplitAtX {
        fn split(&self, points: &[DVec3], _: DVec3) -> bool {
            points.iter().any(|p| p.x < 0.37) && points.iter().any(|p| p.x >= 0.37)
        }
    }

    #[test]
    fn adaptive_blocks_split_only_at_the_edge_and_still_tile_the_triangle() {
        let t = [tri(
            [
                DVec3::ZERO,
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.1, 0.9, 0.0),
            ],
            0.025,
        )];
        let sub = Subdivision::levels(2);
        let el = Elements::build_subdivided(&t, &[0], 1, sub, &SplitAtX).unwrap();
        let uniform = Elements::build_subdivided(&t, &[0], 1, sub, &NeverSplit).unwrap();
        let fine = Elements::build(&t, 0).unwrap();
        assert_eq!((el.level, el.subdivision), (3, sub));
        let area: f64 = el.area.iter().sum();
        assert!((area - 0.45).abs() < 1e-12, "{area}");
        // Unsplit: 4 × 4 texels everywhere; split: single texels along x = 0.37 only.
        assert!(uniform.span.iter().all(|&s| s == 4));
        assert!(el.span.contains(&1) && el.span.contains(&2) && el.span.contains(&4));
        assert!(el.len() < fine.len() / 3, "{} of {}", el.len(), fine.len());
        let mut texels = std::collections::HashSet::new();
        for e in 0..el.len() {
            let (lo, side) = el.atlas_square(e);
            let points = el.texel_samples(e, 4 * el.span[e]);
            let straddles = points.iter().any(|p| p.x < 0.37) && points.iter().any(|p| p.x >= 0.37);
            if el.span[e] > 1 {
                // A block left whole holds no edge among its finest elements' centroids.
                assert!(!straddles || (el.position[e].x - 0.37).abs() < 0.05, "{e}");
            }
            // Every texel of the block shows it, and no texel belongs to two elements.
            for y in 0..el.span[e] {
                for x in 0..el.span[e] {
                    let (tx, ty) = (lo.x as u32 + x, lo.y as u32 + y);
                    assert!(texels.insert((tx, ty)));
                    let slot = (ty * el.atlas_width + tx) as usize;
                    assert_eq!(el.display_source[slot], e as u32);
                }
            }
            assert_eq!(side, el.span[e] as f64);
            // The centroid lies within its block, on the triangle.
            for p in &points {
                assert!(p.distance(el.position[e]) <= 0.025 * side * 1.5);
            }
        }
        // The patches still tile the chart and hold their elements contiguously.
        let patch_area: f64 = el.patches.iter().map(|p| p.area).sum();
        assert!((patch_area - 0.45).abs() < 1e-12);
        let mut next = 0;
        for p in &el.patches {
            assert_eq!(p.first, next);
            next += p.count;
        }
        assert_eq!(next as usize, el.len());
    }

    #[test]
    fn a_whole_blocks_texels_follow_a_smooth_field_and_stop_at_an_edge() {
        let t = [tri(
            [
                DVec3::ZERO,
                DVec3::new(1.0, 0.0, 0.0),
                DVec3::new(0.0, 1.0, 0.0),
            ],
            0.05,
        )];
        let el =
            Elements::build_subdivided(&t, &[0], 0, Subdivision::levels(1), &SplitAtX).unwrap();
        // A linear field shown through blocks: blended texels follow it within a block's
        // slope, where flat blocks would be off by half a block's.
        let shown = el.display_texels(|e| [1.0 + el.position[e].y as f32; 4]);
        let chart = &el.charts[0];
        let mut worst: f64 = 0.0;
        for e in 0..el.len() {
            if el.span[e] != 2 || el.area[e] < 0.01 || el.position[e].x > 0.3 {
                continue;
            }
            let (lo, _) = el.atlas_square(e);
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let (x, y) = (lo.x as u32 + dx, lo.y as u32 + dy);
                let centre = chart.atlas_to_world(DVec2::new(x as f64 + 0.5, y as f64 + 0.5));
                if centre.x + centre.y > 0.85 || centre.x < 0.1 || centre.y < 0.1 {
                    continue;
                }
                let got = shown[(y * el.atlas_width + x) as usize][0] as f64;
                worst = worst.max((got - 1.0 - centre.y).abs());
            }
        }
        assert!(
            worst < 0.01,
            "{worst} m off a linear field (flat blocks: 0.025)"
        );
        // A step at x = 0.37, where the blocks were split: whole blocks on either side
        // show their own side's value, not a blend across the step.
        let step = |e: usize| if el.position[e].x < 0.37 { 0.1 } else { 1.0 };
        let shown = el.display_texels(|e| [step(e); 4]);
        for e in 0..el.len() {
            if el.span[e] != 2 {
                continue;
            }
            let (lo, _) = el.atlas_square(e);
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let slot = ((lo.y as u32 + dy) * el.atlas_width + lo.x as u32 + dx) as usize;
                assert_eq!(shown[slot][0], step(e), "element {e}");
            }
        }
    }

    #[test]
    fn bad_texel_sizes_and_degenerate_scenes_are_refused() {
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X * 2.0];
        assert_eq!(
            Elements::build(&[tri(flat, 0.1)], 0).unwrap_err(),
            ElementError::Empty
        );
        let ok = [DVec3::ZERO, DVec3::X, DVec3::Y];
        assert!(matches!(
            Elements::build(&[tri(ok, 0.0)], 0),
            Err(ElementError::TexelSize(_))
        ));
        assert!(matches!(
            Elements::build(
                &[tri([DVec3::ZERO, DVec3::X * 1e4, DVec3::Y * 1e4], 0.1)],
                0
            ),
            Err(ElementError::TooLarge(_))
        ));
        assert_eq!(
            Elements::build_subdivided(
                &[tri(ok, 0.1)],
                &[0],
                0,
                Subdivision::levels(40),
                &NeverSplit
            )
            .unwrap_err(),
            ElementError::Subdivision(40)
        );
    }
}
