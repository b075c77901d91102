//! Mipmaps of material textures, made on the CPU at upload: each level halves the one
//! above with a 2 × 2 box filter. Colour maps are averaged in linear light (sRGB decoded
//! and encoded again, so a fine black-and-white pattern fades to the right mid-grey, not a
//! dark one). Normal maps average their normals as vectors n · a (a = alpha / 255, 1 on
//! the finest level) and store the direction in rgb and the mean vector's length in
//! alpha: diffuse light is linear in the normal, so shading with the shortened normal
//! gives the mean of the shaded relief (a renormalised mean would brighten a bumpy wall
//! seen from afar; the shortening also widens highlights, as Toksvig's factor does).
//! With trilinear, anisotropic sampling this removes the moiré of fine textures seen at a
//! distance.

use crate::scene::palette::srgb_to_linear;

/// What a texture's texels are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexelKind {
    /// sRGB-encoded colour (alpha linear).
    SrgbColour,
    /// A tangent-space normal map: xyz = n · 0.5 + 0.5.
    Normal,
}

/// The full mip chain of `img` (level 0 first, down to 1 × 1).
/// A normal map's own alpha (some carry a height there) is replaced by 1 on level 0.
pub fn mip_chain(img: &image::RgbaImage, kind: TexelKind) -> Vec<image::RgbaImage> {
    let mut first = img.clone();
    if kind == TexelKind::Normal {
        first.pixels_mut().for_each(|p| p[3] = 255);
    }
    let mut levels = vec![first];
    while let Some(last) = levels.last() {
        if last.width() == 1 && last.height() == 1 {
            break;
        }
        let next = half(last, kind);
        levels.push(next);
    }
    levels
}

/// The number of levels [`mip_chain`] makes of a `width` × `height` texture.
pub fn level_count(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

fn half(img: &image::RgbaImage, kind: TexelKind) -> image::RgbaImage {
    let (w, h) = img.dimensions();
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    image::RgbaImage::from_fn(nw, nh, |x, y| {
        let texels = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| {
            img.get_pixel((2 * x + dx).min(w - 1), (2 * y + dy).min(h - 1))
                .0
        });
        image::Rgba(average(&texels, kind))
    })
}

fn average(texels: &[[u8; 4]; 4], kind: TexelKind) -> [u8; 4] {
    let mut alpha = texels.iter().map(|t| t[3] as f32).sum::<f32>() / 4.0;
    let rgb: [f32; 3] = match kind {
        TexelKind::SrgbColour => [0, 1, 2].map(|c| {
            let mean = texels.iter().map(|t| srgb_to_linear(t[c])).sum::<f32>() / 4.0;
            crate::render::tonemap::linear_to_srgb(mean) as f32
        }),
        TexelKind::Normal => {
            let mean = texels
                .iter()
                .map(|t| {
                    let n = glam::Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 127.5 - 1.0;
                    n.normalize_or(glam::Vec3::Z) * (t[3] as f32 / 255.0)
                })
                .sum::<glam::Vec3>()
                / 4.0;
            alpha = mean.length().min(1.0) * 255.0;
            let n = mean.normalize_or(glam::Vec3::Z);
            [n.x, n.y, n.z].map(|v| (v + 1.0) * 127.5)
        }
    };
    [
        rgb[0].round().clamp(0.0, 255.0) as u8,
        rgb[1].round().clamp(0.0, 255.0) as u8,
        rgb[2].round().clamp(0.0, 255.0) as u8,
        alpha.round() as u8,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_checkerboard_fades_to_linear_mid_grey_down_to_one_texel() {
        let img = image::RgbaImage::from_fn(8, 4, |x, y| {
            let v = if (x + y) % 2 == 0 { 255 } else { 0 };
            image::Rgba([v, v, v, 255])
        });
        let chain = mip_chain(&img, TexelKind::SrgbColour);
        let sizes: Vec<_> = chain.iter().map(|l| l.dimensions()).collect();
        assert_eq!(sizes, [(8, 4), (4, 2), (2, 1), (1, 1)]);
        assert_eq!(chain.len() as u32, level_count(8, 4));
        // Linear 0.5 is sRGB 188, not 128.
        for level in &chain[1..] {
            for p in level.pixels() {
                assert_eq!(p.0, [188, 188, 188, 255]);
            }
        }
    }

    #[test]
    fn normal_maps_average_directions_and_keep_the_mean_length_in_alpha() {
        // Two normals tilted ±x (0.6, 0, 0.8) average to straight up, 0.8 long.
        let img = image::RgbaImage::from_fn(2, 2, |x, _| {
            let nx = if x == 0 { 0.6f32 } else { -0.6 };
            let enc = |v: f32| ((v + 1.0) * 127.5).round() as u8;
            image::Rgba([enc(nx), enc(0.0), enc(0.8), 255])
        });
        let top = &mip_chain(&img, TexelKind::Normal)[1];
        let p = top.get_pixel(0, 0).0;
        assert!((p[0] as i32 - 128).abs() <= 1 && (p[1] as i32 - 128).abs() <= 1);
        assert_eq!(p[2], 255);
        assert!((p[3] as i32 - 204).abs() <= 1, "{p:?}");
    }
}
