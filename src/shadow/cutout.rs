//! Holes in shadow casters: the triangles of alpha-masked materials
//! ([`crate::scene::alpha`]) let a ray through where it crosses a hole. Ray casts (the
//! brute-force oracle and [`super::TriangleBvh`]) ask [`Cutouts::passes`] after every hit.
//! [`AlphaMask`] holds the rule that decides a point, for the CPU and the shaders alike:
//! the texel under `floor(fract(uv) · size)` (row 0 the image's top row, as the renderer
//! samples) is solid when its alpha is at least [`ALPHA_CUTOFF`]; no filtering.

use std::sync::Arc;

use glam::{DVec3, Vec2};

/// Alpha values (0–255) at or above this are solid; below, a hole.
pub const ALPHA_CUTOFF: u8 = 128;

/// Which texels of a texture are solid.
#[derive(Debug, Clone, PartialEq)]
pub struct AlphaMask {
    width: u32,
    height: u32,
    solid: Vec<bool>,
    solid_fraction: f64,
}

impl AlphaMask {
    /// The mask of `img`'s alpha channel; `None` when every texel is solid (no holes).
    pub fn from_alpha(img: &image::RgbaImage) -> Option<AlphaMask> {
        let solid: Vec<bool> = img.pixels().map(|p| p.0[3] >= ALPHA_CUTOFF).collect();
        if solid.iter().all(|&s| s) {
            return None;
        }
        let solid_fraction = solid.iter().filter(|&&s| s).count() as f64 / solid.len() as f64;
        Some(AlphaMask {
            width: img.width(),
            height: img.height(),
            solid,
            solid_fraction,
        })
    }

    /// Whether texture coordinate `uv` (wrapped, as the renderer's repeat sampler does)
    /// falls on a solid texel.
    pub fn solid_at(&self, uv: Vec2) -> bool {
        let texel = |t: f32, size: u32| {
            let f = t - t.floor();
            ((f * size as f32) as u32).min(size - 1)
        };
        self.solid_texel(texel(uv.x, self.width), texel(uv.y, self.height))
    }

    /// Width and height, texels.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Whether texel (`x`, `y`) (row 0 the image's top) is solid.
    pub fn solid_texel(&self, x: u32, y: u32) -> bool {
        self.solid[(y * self.width + x) as usize]
    }

    /// The share of texels that are solid (0..1).
    pub fn solid_fraction(&self) -> f64 {
        self.solid_fraction
    }
}

/// The masked triangles of a caster mesh: per triangle, its mask and its corners' texture
/// coordinates.
#[derive(Debug, Clone, Default)]
pub struct Cutouts {
    /// Per caster triangle: (index into `masks`, corner uvs); `None` where it is solid.
    triangles: Vec<Option<(u32, [Vec2; 3])>>,
    /// The masks.
    masks: Vec<Arc<AlphaMask>>,
}

impl Cutouts {
    /// Cut-outs from each triangle's mask (an index into `masks`) and corner uvs.
    pub fn new(triangles: Vec<Option<(u32, [Vec2; 3])>>, masks: Vec<Arc<AlphaMask>>) -> Cutouts {
        debug_assert!(triangles
            .iter()
            .flatten()
            .all(|(m, _)| (*m as usize) < masks.len()));
        Cutouts { triangles, masks }
    }

    /// Whether no triangle has holes.
    pub fn is_empty(&self) -> bool {
        self.triangles.iter().all(Option::is_none)
    }

    /// How many triangles have a mask.
    pub fn masked_count(&self) -> usize {
        self.triangles.iter().flatten().count()
    }

    /// The masks (indexed by the triangles' mask numbers).
    pub fn masks(&self) -> &[Arc<AlphaMask>] {
        &self.masks
    }

    /// The mask number of triangle `k`, `None` where it is solid.
    pub fn mask_of(&self, k: usize) -> Option<u32> {
        self.triangles.get(k).copied().flatten().map(|(m, _)| m)
    }

    /// Cut-outs for another mesh whose triangle j is triangle `source[j]` of this one
    /// (corners in the same order), or solid where `source[j]` is `None`.
    pub fn remapped(&self, source: impl IntoIterator<Item = Option<usize>>) -> Cutouts {
        let triangles = source
            .into_iter()
            .map(|k| k.and_then(|k| self.triangles.get(k).copied().flatten()))
            .collect();
        Cutouts::new(triangles, self.masks.clone())
    }

    /// The mask and corner uvs of triangle `k`, `None` where it is solid.
    pub fn triangle(&self, k: usize) -> Option<(&AlphaMask, [Vec2; 3])> {
        let (m, uv) = (*self.triangles.get(k)?)?;
        Some((&self.masks[m as usize], uv))
    }

    /// The texture coordinate at `p` of triangle `k` (corners `corners`), `None` where
    /// it is solid.
    pub fn uv_at(&self, k: usize, corners: [DVec3; 3], p: DVec3) -> Option<Vec2> {
        let (_, uv) = self.triangle(k)?;
        let [b0, b1, b2] = barycentric(corners, p);
        Some(uv[0] * b0 as f32 + uv[1] * b1 as f32 + uv[2] * b2 as f32)
    }

    /// Whether a ray that hits triangle `k` (corners `corners`) at `p` passes through a
    /// hole there.
    pub fn passes(&self, k: usize, corners: [DVec3; 3], p: DVec3) -> bool {
        let (Some((mask, _)), Some(at)) = (self.triangle(k), self.uv_at(k, corners, p)) else {
            return false;
        };
        !mask.solid_at(at)
    }
}

/// Barycentric coordinates of `p` (in the triangle's plane) in triangle `[a, b, c]`.
pub fn barycentric([a, b, c]: [DVec3; 3], p: DVec3) -> [f64; 3] {
    let (e1, e2, d) = (b - a, c - a, p - a);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d1, d2) = (d.dot(e1), d.dot(e2));
    let det = d11 * d22 - d12 * d12;
    if det.abs() < 1e-300 {
        return [1.0, 0.0, 0.0];
    }
    let v = (d22 * d1 - d12 * d2) / det;
    let w = (d11 * d2 - d12 * d1) / det;
    [1.0 - v - w, v, w]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holes_pass_where_the_mask_is_open() {
        // 2 × 2 cells of 2 texels: solid where (x + y) / 2 is even.
        let img = image::RgbaImage::from_fn(4, 4, |x, y| {
            image::Rgba([0, 0, 0, if (x / 2 + y / 2) % 2 == 0 { 255 } else { 0 }])
        });
        let mask = AlphaMask::from_alpha(&img);
        let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        let cut = Cutouts::new(vec![Some((0, uv)), None], vec![Arc::new(mask.unwrap())]);
        assert_eq!(cut.masked_count(), 1);
        // uv (0.1, 0.1): solid; (0.6, 0.1): a hole.
        assert!(!cut.passes(0, corners, DVec3::new(0.1, 0.1, 0.0)));
        assert!(cut.passes(0, corners, DVec3::new(0.6, 0.1, 0.0)));
        assert!(!cut.passes(1, corners, DVec3::new(0.6, 0.1, 0.0)), "solid");
        let b = barycentric(corners, DVec3::new(0.25, 0.5, 0.0));
        assert!((b[0] - 0.25).abs() < 1e-12 && (b[1] - 0.25).abs() < 1e-12);
    }
}
