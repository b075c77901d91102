//! Alpha masks (cut-outs, Wallner ch. 4): a material whose diffuse texture has texels with
//! alpha below one half — from the texture's own alpha channel or from MTL `map_d` — has
//! holes there. A hole neither blocks light nor receives it, in every path: the CPU ray
//! casts, the renderer's depth and shading passes, the paraboloid shadow maps, and the
//! radiosity elements (whose area counts only their solid part).
//!
//! One rule decides a point everywhere, on the CPU and in the shaders: the texel under
//! `floor(fract(uv) · size)` (row 0 the image's top row, as the renderer samples) is solid
//! when its alpha is at least [`ALPHA_CUTOFF`]. No filtering: the CPU reference and the GPU
//! agree texel for texel.

pub use crate::shadow::cutout::{AlphaMask, ALPHA_CUTOFF};

/// `diffuse` (or a white texture when there is none) with `map_d`'s values as its alpha:
/// `map_d`'s own alpha channel when it has one, else its first channel (a grey mask).
/// A `map_d` of another size is read at the nearest texel.
pub fn with_dissolve_map(
    diffuse: Option<&image::RgbaImage>,
    map_d: &image::RgbaImage,
) -> image::RgbaImage {
    let channel = if map_d.pixels().any(|p| p.0[3] < 255) {
        3
    } else {
        0
    };
    let mut out = diffuse.cloned().unwrap_or_else(|| {
        image::RgbaImage::from_pixel(map_d.width(), map_d.height(), image::Rgba([255; 4]))
    });
    let (w, h) = out.dimensions();
    for (x, y, p) in out.enumerate_pixels_mut() {
        let sx = ((x as u64 * map_d.width() as u64) / w as u64) as u32;
        let sy = ((y as u64 * map_d.height() as u64) / h as u64) as u32;
        p.0[3] = map_d.get_pixel(sx, sy).0[channel];
    }
    out
}

/// A checkerboard of `cells` × `cells` squares on a `size` × `size` texture, solid where
/// `(x + y)` is even and a hole elsewhere (half open): the perforated panel of the tests
/// and examples.
pub fn checker_texture(size: u32, cells: u32, colour: [u8; 3]) -> image::RgbaImage {
    let cell = (size / cells.max(1)).max(1);
    image::RgbaImage::from_fn(size, size, |x, y| {
        let solid = (x / cell + y / cell).is_multiple_of(2);
        let [r, g, b] = colour;
        image::Rgba([r, g, b, if solid { 255 } else { 0 }])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn a_checker_is_half_solid_and_wraps_like_the_sampler() {
        let img = checker_texture(8, 2, [200, 100, 50]);
        let mask = AlphaMask::from_alpha(&img).unwrap();
        assert_eq!(mask.solid_fraction(), 0.5);
        // Cell (0, 0) is solid, (1, 0) and (0, 1) are holes; row 0 is the image's top.
        assert!(mask.solid_at(Vec2::new(0.1, 0.1)));
        assert!(!mask.solid_at(Vec2::new(0.6, 0.1)));
        assert!(!mask.solid_at(Vec2::new(0.1, 0.6)));
        assert!(mask.solid_at(Vec2::new(0.6, 0.6)));
        // Repeat addressing: 1.1 and −0.9 are 0.1.
        assert!(mask.solid_at(Vec2::new(1.1, -0.9)));
        assert!(!mask.solid_at(Vec2::new(-0.4, 0.1)));
        // The upper edge stays inside.
        assert!(mask.solid_at(Vec2::new(0.999_999, 0.999_999)));
    }

    #[test]
    fn opaque_textures_have_no_mask_and_map_d_becomes_alpha() {
        let opaque = image::RgbaImage::from_pixel(4, 4, image::Rgba([9, 9, 9, 255]));
        assert!(AlphaMask::from_alpha(&opaque).is_none());
        // A grey map_d of another size: its first channel, nearest texel.
        let grey = image::RgbaImage::from_fn(2, 1, |x, _| {
            let v = if x == 0 { 0 } else { 255 };
            image::Rgba([v, v, v, 255])
        });
        let combined = with_dissolve_map(Some(&opaque), &grey);
        assert_eq!(combined.get_pixel(0, 0).0, [9, 9, 9, 0]);
        assert_eq!(combined.get_pixel(1, 3).0[3], 0);
        assert_eq!(combined.get_pixel(2, 0).0[3], 255);
        assert_eq!(
            AlphaMask::from_alpha(&combined).unwrap().solid_fraction(),
            0.5
        );
        // Without a diffuse map: white with the mask.
        let white = with_dissolve_map(None, &grey);
        assert_eq!(white.dimensions(), (2, 1));
        assert_eq!(white.get_pixel(0, 0).0, [255, 255, 255, 0]);
    }
}
