//! Radiosity elements: every triangle gets a rectangle of texels in a light-map atlas
//! (Wallner §2.3, §4.2). Texel size per object comes from the user's texel density; every
//! texel whose square touches the triangle is an element (conservative coverage, §2.3.1),
//! with the exact area, centroid and normal of the part of the triangle inside it, so
//! edge texels exist and the elements of a triangle tile it exactly. Elements are grouped
//! into shooting patches of 2^level × 2^level texels (substructuring: a coarser mip level
//! shoots, the fine elements receive), each patch a convex polygon. Texels around the
//! covered ones get a display source (gutter fill) so bilinear filtering never reads
//! an empty texel.

use glam::{DVec2, DVec3};

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

/// A shooting patch: a block of a triangle's texels (one texel of a coarser mip level).
#[derive(Debug, Clone)]
pub struct Patch {
    /// First element (the patch's elements are contiguous).
    pub first: u32,
    /// Number of elements.
    pub count: u32,
    /// The block clipped to the triangle: a convex polygon, counter-clockwise from the front.
    pub polygon: Vec<DVec3>,
    /// Area-weighted centre, metres.
    pub centroid: DVec3,
    /// Area, m².
    pub area: f64,
}

/// The elements and patches of one triangle and where it sits in the atlas.
#[derive(Debug, Clone)]
pub struct TriangleElements {
    /// First element.
    pub first: u32,
    /// Number of elements.
    pub count: u32,
    /// First patch.
    pub first_patch: u32,
    /// Number of patches.
    pub patch_count: u32,
    /// Unit face normal.
    pub normal: DVec3,
    /// Material index.
    pub material: usize,
    /// Area, m².
    pub area: f64,
    /// Atlas rectangle: x, y, width, height in texels (one gutter texel on each side).
    pub rect: [u32; 4],
    /// Texel side, metres.
    pub texel_m: f64,
    /// Atlas coordinates (texels, from the atlas's top-left corner) of the corners.
    pub atlas_uv: [DVec2; 3],
}

/// All elements of a scene, in triangle order.
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
    /// Element atlas texels.
    pub texel: Vec<[u32; 2]>,
    /// Element → triangle.
    pub triangle: Vec<u32>,
    /// Per input triangle (degenerate ones have no elements).
    pub triangles: Vec<TriangleElements>,
    /// Shooting patches, in triangle order.
    pub patches: Vec<Patch>,
    /// Substructuring level: patches are 2^level texels square.
    pub level: u32,
    /// Per atlas texel (row-major): the element whose value it shows, `u32::MAX` for none.
    pub display_source: Vec<u32>,
}

/// Largest atlas side.
pub const MAX_ATLAS: u32 = 8192;

/// Why elements cannot be built.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ElementError {
    /// The texel size is not a positive number.
    #[error("texel size {0} m is not a positive number (is the texel density positive?)")]
    TexelSize(f64),
    /// Too many texels for the largest atlas.
    #[error(
        "{0} texels do not fit in an {MAX_ATLAS} × {MAX_ATLAS} atlas: lower the texel density"
    )]
    TooLarge(u64),
    /// No triangle with an area.
    #[error("the scene has no triangle with an area")]
    Empty,
}

/// Local 2D frame of a triangle: origin at corner 0, u along edge 0→1, v in the plane.
struct Frame {
    origin: DVec3,
    u: DVec3,
    v: DVec3,
}

impl Frame {
    fn to_world(&self, p: DVec2) -> DVec3 {
        self.origin + self.u * p.x + self.v * p.y
    }
}

/// Clips a convex polygon to the half-plane left of the directed edge a → b.
fn clip_left(poly: &[DVec2], a: DVec2, b: DVec2) -> Vec<DVec2> {
    let side = |p: DVec2| (b - a).perp_dot(p - a);
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(p + (q - p) * (sp / (sp - sq)));
        }
    }
    out
}

/// The axis-aligned square [lo, hi] clipped to the triangle `t` (counter-clockwise).
pub(crate) fn clip_square(lo: DVec2, hi: DVec2, t: &[DVec2; 3]) -> Vec<DVec2> {
    let mut poly = vec![lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
    for k in 0..3 {
        if poly.is_empty() {
            break;
        }
        poly = clip_left(&poly, t[k], t[(k + 1) % 3]);
    }
    poly
}

/// Area and centroid of a simple polygon (shoelace).
pub(crate) fn area_centroid(poly: &[DVec2]) -> (f64, DVec2) {
    let mut a = 0.0;
    let mut c = DVec2::ZERO;
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let cross = p.perp_dot(q);
        a += cross;
        c += (p + q) * cross;
    }
    if a.abs() < 1e-300 {
        let mean = poly.iter().copied().sum::<DVec2>() / poly.len().max(1) as f64;
        return (0.0, mean);
    }
    (a / 2.0, c / (3.0 * a))
}

/// One triangle's elements before packing: texel (i, j) within its grid, area, centroid.
struct Laid {
    frame: Frame,
    corners_2d: [DVec2; 3],
    lo: DVec2,
    cols: u32,
    rows: u32,
    elements: Vec<(u32, u32, f64, DVec2)>,
}

/// Where a triangle's texel grid lies: its plane frame, corners in it, and grid size.
struct Footprint {
    frame: Frame,
    corners_2d: [DVec2; 3],
    lo: DVec2,
    cols: u32,
    rows: u32,
}

/// The texel grid of `t`, or `None` for a triangle without area.
fn footprint(t: &InputTriangle) -> Option<Footprint> {
    let [a, b, c] = t.corners;
    let n = (b - a).cross(c - a);
    if n.length() <= 1e-14 || !n.is_finite() {
        return None;
    }
    let n = n.normalize();
    let u = (b - a).normalize();
    let frame = Frame {
        origin: a,
        u,
        v: n.cross(u),
    };
    let to_2d = |p: DVec3| DVec2::new((p - a).dot(frame.u), (p - a).dot(frame.v));
    let corners_2d = [DVec2::ZERO, to_2d(b), to_2d(c)];
    let lo = corners_2d[0].min(corners_2d[1]).min(corners_2d[2]);
    let hi = corners_2d[0].max(corners_2d[1]).max(corners_2d[2]);
    let s = t.texel_m;
    // Saturating casts: a huge grid is refused by the caller, never allocated.
    let cols = (((hi.x - lo.x) / s).ceil() as u32).max(1);
    let rows = (((hi.y - lo.y) / s).ceil() as u32).max(1);
    Some(Footprint {
        frame,
        corners_2d,
        lo,
        cols,
        rows,
    })
}

fn lay_out(t: &InputTriangle) -> Result<Option<Laid>, ElementError> {
    let Some(Footprint {
        frame,
        corners_2d,
        lo,
        cols,
        rows,
    }) = footprint(t)
    else {
        return Ok(None);
    };
    let s = t.texel_m;
    let texels = cols as u64 * rows as u64;
    if texels > (MAX_ATLAS as u64).pow(2) {
        return Err(ElementError::TooLarge(texels));
    }
    let mut elements = Vec::new();
    for j in 0..rows {
        for i in 0..cols {
            let sq_lo = lo + DVec2::new(i as f64, j as f64) * s;
            let poly = clip_square(sq_lo, sq_lo + DVec2::splat(s), &corners_2d);
            if poly.len() < 3 {
                continue;
            }
            let (area, centroid) = area_centroid(&poly);
            if area > 1e-12 * s * s {
                elements.push((i, j, area, centroid));
            }
        }
    }
    Ok(Some(Laid {
        frame,
        corners_2d,
        lo,
        cols,
        rows,
        elements,
    }))
}

/// Shelf packing of rectangles (w, h) into an atlas of `width`: positions and height.
fn pack(sizes: &[(u32, u32)], width: u32) -> (Vec<[u32; 2]>, u32) {
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

impl Elements {
    /// Splits `triangles` into elements with shooting patches of 2^`level` texels.
    pub fn build(triangles: &[InputTriangle], level: u32) -> Result<Elements, ElementError> {
        let mut laid = Vec::with_capacity(triangles.len());
        for t in triangles {
            if !(t.texel_m.is_finite() && t.texel_m > 0.0) {
                return Err(ElementError::TexelSize(t.texel_m));
            }
        }
        // Count the texels (with gutters) before laying any out: a density that cannot
        // fit is refused in milliseconds, not after gigabytes of elements. Shelf packing
        // needs about 10 % more than the sum (the atlas width below allows for that).
        let needed: u64 = triangles
            .iter()
            .filter_map(footprint)
            .map(|f| (f.cols as u64 + 2) * (f.rows as u64 + 2))
            .sum();
        if needed as f64 * 1.1 > (MAX_ATLAS as f64).powi(2) {
            return Err(ElementError::TooLarge(needed));
        }
        for t in triangles {
            laid.push(lay_out(t)?);
        }
        // Rectangles with one gutter texel on each side.
        let sizes: Vec<(u32, u32)> = laid
            .iter()
            .map(|l| l.as_ref().map_or((0, 0), |l| (l.cols + 2, l.rows + 2)))
            .collect();
        let total: u64 = sizes.iter().map(|&(w, h)| w as u64 * h as u64).sum();
        if total == 0 {
            return Err(ElementError::Empty);
        }
        let widest = sizes.iter().map(|s| s.0).max().unwrap_or(1);
        if total > (MAX_ATLAS as u64).pow(2) || widest > MAX_ATLAS {
            return Err(ElementError::TooLarge(total));
        }
        let width = (((total as f64 * 1.1).sqrt().ceil() as u32).max(widest))
            .next_multiple_of(64)
            .min(MAX_ATLAS);
        let (origins, height) = pack(&sizes, width);
        if height > MAX_ATLAS {
            return Err(ElementError::TooLarge(total));
        }
        let mut out = Elements {
            atlas_width: width,
            atlas_height: height.max(1),
            level,
            display_source: vec![u32::MAX; width as usize * height.max(1) as usize],
            ..Default::default()
        };
        let block = 1u32 << level;
        for (k, (t, l)) in triangles.iter().zip(&laid).enumerate() {
            let [x0, y0] = origins[k];
            let Some(l) = l else {
                out.triangles.push(TriangleElements {
                    first: out.position.len() as u32,
                    count: 0,
                    first_patch: out.patches.len() as u32,
                    patch_count: 0,
                    normal: DVec3::Z,
                    material: t.material,
                    area: 0.0,
                    rect: [x0, y0, 0, 0],
                    texel_m: t.texel_m,
                    atlas_uv: [DVec2::ZERO; 3],
                });
                continue;
            };
            out.push_triangle(t, l, [x0, y0], block);
        }
        out.fill_gutters();
        Ok(out)
    }

    fn push_triangle(&mut self, t: &InputTriangle, l: &Laid, origin: [u32; 2], block: u32) {
        let s = t.texel_m;
        let first = self.position.len() as u32;
        let first_patch = self.patches.len() as u32;
        let tri_index = self.triangles.len() as u32;
        // Patch by patch, so each patch's elements are contiguous.
        let mut order: Vec<&(u32, u32, f64, DVec2)> = l.elements.iter().collect();
        order.sort_by_key(|e| (e.1 / block, e.0 / block, e.1, e.0));
        let mut area_sum = 0.0;
        let mut current: Option<(u32, u32)> = None;
        for &&(i, j, area, centroid) in &order {
            let key = (i / block, j / block);
            if current != Some(key) {
                current = Some(key);
                let lo = l.lo + DVec2::new(key.0 as f64, key.1 as f64) * s * block as f64;
                let poly = clip_square(lo, lo + DVec2::splat(s * block as f64), &l.corners_2d);
                let (a, c) = area_centroid(&poly);
                self.patches.push(Patch {
                    first: self.position.len() as u32,
                    count: 0,
                    polygon: poly.iter().map(|&p| l.frame.to_world(p)).collect(),
                    centroid: l.frame.to_world(c),
                    area: a,
                });
            }
            if let Some(p) = self.patches.last_mut() {
                p.count += 1;
            }
            let texel = [origin[0] + 1 + i, origin[1] + 1 + l.rows - 1 - j];
            let slot = (texel[1] * self.atlas_width + texel[0]) as usize;
            self.display_source[slot] = self.position.len() as u32;
            self.position.push(l.frame.to_world(centroid));
            self.area.push(area);
            self.texel.push(texel);
            self.triangle.push(tri_index);
            area_sum += area;
        }
        // Atlas coordinates of the corners: x right with u, y down against v.
        let atlas_uv = l.corners_2d.map(|p| {
            let q = (p - l.lo) / s;
            DVec2::new(
                origin[0] as f64 + 1.0 + q.x,
                origin[1] as f64 + 1.0 + l.rows as f64 - q.y,
            )
        });
        self.triangles.push(TriangleElements {
            first,
            count: self.position.len() as u32 - first,
            first_patch,
            patch_count: self.patches.len() as u32 - first_patch,
            normal: l.frame.u.cross(l.frame.v),
            material: t.material,
            area: area_sum,
            rect: [origin[0], origin[1], l.cols + 2, l.rows + 2],
            texel_m: s,
            atlas_uv,
        });
    }

    /// Gives every empty texel of a triangle's rectangle next to a filled one (two
    /// rings) the value of a filled neighbour of the same triangle.
    fn fill_gutters(&mut self) {
        let w = self.atlas_width as i64;
        for _ring in 0..2 {
            let mut fills = Vec::new();
            for t in &self.triangles {
                let [x0, y0, rw, rh] = t.rect.map(|v| v as i64);
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

    /// Unit normal of element `e` (its triangle's).
    pub fn normal(&self, e: usize) -> DVec3 {
        self.triangles[self.triangle[e] as usize].normal
    }

    /// Points of an `n` × `n` grid over element `e`'s texel that lie on its triangle, whose
    /// `corners` are as given to [`Elements::build`]; the element's centroid when `n` ≤ 1
    /// or no grid point does. Averages over these integrate steep gradients (a luminaire
    /// close to a surface) that one sample at the centroid would miss.
    pub fn texel_samples(&self, e: usize, corners: &[DVec3; 3], n: u32) -> Vec<DVec3> {
        let [a, b, c] = self.triangles[self.triangle[e] as usize].atlas_uv;
        let (v0, v1) = (b - a, c - a);
        let det = v0.perp_dot(v1);
        if n <= 1 || det.abs() < 1e-12 {
            return vec![self.position[e]];
        }
        let [tx, ty] = self.texel[e];
        let step = 1.0 / n as f64;
        let mut out = Vec::with_capacity((n * n) as usize);
        for j in 0..n {
            for i in 0..n {
                let p = DVec2::new(
                    tx as f64 + (i as f64 + 0.5) * step,
                    ty as f64 + (j as f64 + 0.5) * step,
                );
                let d = p - a;
                let (u, v) = (d.perp_dot(v1) / det, v0.perp_dot(d) / det);
                if u >= 0.0 && v >= 0.0 && u + v <= 1.0 {
                    out.push(
                        corners[0] + (corners[1] - corners[0]) * u + (corners[2] - corners[0]) * v,
                    );
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
            let samples = el.texel_samples(e, &corners, 8);
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
        assert_eq!(el.texel_samples(3, &corners, 1), vec![el.position[3]]);
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
            for (k, te) in e.triangles.iter().enumerate() {
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
    }
}
