//! What each atlas texel shows. A texel of a one-texel element shows that element (the
//! GPU's bilinear filter interpolates between them); a texel of a block that adaptive
//! subdivision left whole ([`super::Subdivision`]) is interpolated bilinearly between the
//! block's value at its centre and its neighbours' at theirs, as the texels of uniform
//! elements of the block's size would be, so an unsplit block does not show as a flat
//! square. A split neighbour gives its element nearest the texel. A neighbour outside the
//! chart gives nothing (the weights of the rest are renormalised), and so does one more
//! than twice as bright or dark as the block: blending across a shadow's edge would smear
//! the shadow into the block, while along a steep but smooth gradient (the rim of a
//! ceiling's light spot) the blend keeps unsplit blocks from showing as steps.

use glam::DVec2;
use rayon::prelude::*;

use super::Elements;

impl Elements {
    /// Every atlas texel's value (row-major), from each element's `value`: black where
    /// no element shows.
    pub fn display_texels(&self, value: impl Fn(usize) -> [f32; 4] + Sync) -> Vec<[f32; 4]> {
        let w = self.atlas_width as usize;
        let mut out = vec![[0.0f32; 4]; self.display_source.len()];
        out.par_chunks_mut(w.max(1))
            .enumerate()
            .for_each(|(y, row)| {
                for (x, texel) in row.iter_mut().enumerate() {
                    *texel = match self.display_source[y * w + x] {
                        u32::MAX => [0.0; 4],
                        e => self.blend(e as usize, x as u32, y as u32, &value),
                    };
                }
            });
        out
    }

    /// The value texel (`x`, `y`) shows of element `e` and, when `e` is a block the texel
    /// lies in, of its neighbours.
    fn blend(&self, e: usize, x: u32, y: u32, value: &impl Fn(usize) -> [f32; 4]) -> [f32; 4] {
        let (lo, side) = self.atlas_square(e);
        let q = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
        let inside = q.cmpge(lo).all() && q.cmplt(lo + DVec2::splat(side)).all();
        if side <= 1.0 || !inside {
            return value(e);
        }
        // Offset from the block's centre, in blocks: the neighbours on that side.
        let d = (q - (lo + DVec2::splat(0.5 * side))) / side;
        let step = DVec2::new(d.x.signum(), d.y.signum());
        let chart = self.chart[e];
        let own = value(e);
        let mut sum = [0.0f64; 4];
        let mut weight = 0.0;
        for (ox, oy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
            let wx = if ox == 0.0 {
                1.0 - d.x.abs()
            } else {
                d.x.abs()
            };
            let wy = if oy == 0.0 {
                1.0 - d.y.abs()
            } else {
                d.y.abs()
            };
            let w = wx * wy;
            if w <= 0.0 {
                continue;
            }
            let cell = lo + DVec2::new(step.x * ox, step.y * oy) * side;
            let Some(n) = self.source_near(cell, side, q, chart) else {
                continue;
            };
            let theirs = value(n);
            // The neighbour's element next to this block is taken only where the light
            // runs on smoothly (within a factor of two), not across a shadow's edge.
            if !smooth(&own, &theirs) {
                continue;
            }
            for (s, v) in sum.iter_mut().zip(theirs) {
                *s += w * f64::from(v);
            }
            weight += w;
        }
        sum.map(|s| (s / weight) as f32)
    }

    /// The element of `chart` shown at the texel of the cell (top-left `cell`, side
    /// `side` texels) nearest `q`, if there is one.
    fn source_near(&self, cell: DVec2, side: f64, q: DVec2, chart: u32) -> Option<usize> {
        let p = q.clamp(cell + DVec2::splat(0.5), cell + DVec2::splat(side - 0.5));
        if p.x < 0.0 || p.y < 0.0 {
            return None;
        }
        let (tx, ty) = (p.x as u32, p.y as u32);
        if tx >= self.atlas_width || ty >= self.atlas_height {
            return None;
        }
        let s = self.display_source[(ty * self.atlas_width + tx) as usize];
        (s != u32::MAX && self.chart[s as usize] == chart).then_some(s as usize)
    }
}

/// Whether two texel values differ by at most a factor of two in every channel.
fn smooth(a: &[f32; 4], b: &[f32; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(&x, &y)| x.max(y) <= 2.0 * x.min(y) || x.max(y) <= f32::MIN_POSITIVE)
}
