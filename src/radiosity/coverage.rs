//! Alpha-masked elements (Wallner ch. 4): a hole neither receives nor sends light, so an
//! element of a masked material counts only the solid part of its area. Its radiosity
//! stays that of the solid surface (what a pixel of it shows); its power, what it receives
//! and what it shoots, scale with the solid share. The share is measured on a grid of
//! [`SAMPLES`]² points over the element's texel, each looked up in the mask through the
//! texture coordinates of the chart triangle it falls in.

use glam::DVec2;
use rustc_hash::FxHashMap;

use super::elements::Elements;
use crate::shadow::Cutouts;

/// Sample points per texel side.
pub const SAMPLES: u32 = 8;

/// The least share an element keeps, so a texel wholly in a hole still has an area to
/// divide by (it then neither receives nor sends anything that matters).
const MIN_SHARE: f64 = 1e-4;

/// Scales the area of every element of a masked triangle (`cutouts`, indexed like
/// `elements.triangles`) by its solid share, and each patch's area to its elements' sum.
/// Returns how many elements changed.
pub fn apply(elements: &mut Elements, cutouts: &Cutouts) -> usize {
    let masked_chart: Vec<bool> = elements
        .charts
        .iter()
        .map(|c| {
            c.triangles
                .iter()
                .any(|&t| cutouts.mask_of(t as usize).is_some())
        })
        .collect();
    if !masked_chart.iter().any(|&m| m) {
        return 0;
    }
    // Per masked chart, the triangles whose atlas box touches each texel: an element
    // tests only those (a CAD panel of thousands of triangles stays linear).
    let mut by_texel: FxHashMap<[u32; 2], Vec<u32>> = FxHashMap::default();
    for (c, chart) in elements.charts.iter().enumerate() {
        if !masked_chart[c] {
            continue;
        }
        for &t in &chart.triangles {
            let uv = elements.triangles[t as usize].atlas_uv;
            let lo = uv[0].min(uv[1]).min(uv[2]).floor().max(DVec2::ZERO);
            let hi = uv[0].max(uv[1]).max(uv[2]).ceil();
            for y in lo.y as u32..(hi.y as u32).max(lo.y as u32 + 1) {
                for x in lo.x as u32..(hi.x as u32).max(lo.x as u32 + 1) {
                    by_texel.entry([x, y]).or_default().push(t);
                }
            }
        }
    }
    let mut changed = 0;
    for e in 0..elements.len() {
        if !masked_chart[elements.chart[e] as usize] {
            continue;
        }
        let (lo, side) = elements.atlas_square(e);
        let [tx, ty] = elements.texel[e];
        let span = elements.span[e];
        // A one-texel element borrows its texel's list; a block gathers its texels'.
        let near: std::borrow::Cow<[u32]> = if span == 1 {
            by_texel
                .get(&[tx, ty])
                .map_or(&[][..], Vec::as_slice)
                .into()
        } else {
            let mut all: Vec<u32> = (ty..ty + span)
                .flat_map(|y| (tx..tx + span).map(move |x| [x, y]))
                .filter_map(|texel| by_texel.get(&texel))
                .flatten()
                .copied()
                .collect();
            all.sort_unstable();
            all.dedup();
            all.into()
        };
        let share = solid_share(elements, cutouts, &near, lo, side);
        if share < 1.0 {
            elements.area[e] *= share.max(MIN_SHARE);
            changed += 1;
        }
    }
    for p in &mut elements.patches {
        p.area = elements.area[p.first as usize..][..p.count as usize]
            .iter()
            .sum();
    }
    changed
}

/// The solid share of the samples over an element's square (top-left corner `lo`, side
/// `side` texels) that fall in one of `triangles` (those of its chart near it; 1 when
/// none does).
fn solid_share(
    elements: &Elements,
    cutouts: &Cutouts,
    triangles: &[u32],
    lo: DVec2,
    side: f64,
) -> f64 {
    let (mut inside, mut solid) = (0u32, 0u32);
    let n = SAMPLES * side as u32;
    for j in 0..n {
        for i in 0..n {
            let p = lo + DVec2::new(i as f64 + 0.5, j as f64 + 0.5) * (side / n as f64);
            let hit = triangles.iter().find_map(|&t| {
                let b = barycentric_2d(elements.triangles[t as usize].atlas_uv, p)?;
                Some((t as usize, b))
            });
            let Some((t, b)) = hit else { continue };
            inside += 1;
            let solid_here = match cutouts.triangle(t) {
                Some((mask, uv)) => {
                    let at = uv[0] * b[0] as f32 + uv[1] * b[1] as f32 + uv[2] * b[2] as f32;
                    mask.solid_at(at)
                }
                None => true,
            };
            solid += u32::from(solid_here);
        }
    }
    if inside == 0 {
        1.0
    } else {
        solid as f64 / inside as f64
    }
}

/// Barycentric coordinates of `p` in the 2D triangle `[a, b, c]`, `None` outside it (or
/// for a degenerate triangle).
fn barycentric_2d([a, b, c]: [DVec2; 3], p: DVec2) -> Option<[f64; 3]> {
    let (e1, e2, d) = (b - a, c - a, p - a);
    let det = e1.perp_dot(e2);
    if det.abs() < 1e-300 {
        return None;
    }
    let v = d.perp_dot(e2) / det;
    let w = e1.perp_dot(d) / det;
    let u = 1.0 - v - w;
    const EDGE: f64 = -1e-9;
    (u >= EDGE && v >= EDGE && w >= EDGE).then_some([u, v, w])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentric_2d_finds_points_inside_only() {
        let t = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let b = barycentric_2d(t, DVec2::new(0.25, 0.5)).unwrap();
        assert!((b[0] - 0.25).abs() < 1e-12 && (b[1] - 0.25).abs() < 1e-12);
        assert!(barycentric_2d(t, DVec2::new(0.6, 0.6)).is_none());
        assert!(barycentric_2d([DVec2::ZERO; 3], DVec2::ZERO).is_none());
    }
}
