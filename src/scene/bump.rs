//! MTL `bump` / `map_Bump` textures that are height maps (greyscale, as the OBJ format
//! defines them), turned into the tangent-space normal maps the renderer and the radiosity
//! solver read. A map whose texels are coloured is taken as a normal map already (many
//! exporters write one under `map_Bump`).

/// Whether `img` is a height map: every texel grey (channels within 3 of each other,
/// room for JPEG noise).
pub fn is_height_map(img: &image::RgbaImage) -> bool {
    img.pixels().all(|p| {
        let [r, g, b, _] = p.0.map(i16::from);
        (r - g).abs() <= 3 && (g - b).abs() <= 3
    })
}

/// The `-bm` multiplier of an MTL map statement ("-bm 0.5 bricks.png"), 1 without one.
pub fn bump_multiplier(statement: &str) -> f32 {
    let mut words = statement.split_whitespace();
    while let Some(w) = words.next() {
        if w == "-bm" {
            return words
                .next()
                .and_then(|v| v.parse::<f32>().ok())
                .filter(|v| v.is_finite())
                .unwrap_or(1.0);
        }
    }
    1.0
}

/// The tangent-space normal map of height map `img` (height = red / 255, repeating):
/// n = normalise(−s ∂h/∂x, −s ∂h/∂y, 1) with central differences per texel, x along +u
/// and y along +v (image rows, as the renderer samples them), encoded n · 0.5 + 0.5.
pub fn height_to_normal(img: &image::RgbaImage, scale: f32) -> image::RgbaImage {
    let (w, h) = (img.width() as i64, img.height() as i64);
    let height = |x: i64, y: i64| {
        img.get_pixel(x.rem_euclid(w) as u32, y.rem_euclid(h) as u32)
            .0[0] as f32
            / 255.0
    };
    image::RgbaImage::from_fn(img.width(), img.height(), |x, y| {
        let (x, y) = (x as i64, y as i64);
        let dx = 0.5 * (height(x + 1, y) - height(x - 1, y));
        let dy = 0.5 * (height(x, y + 1) - height(x, y - 1));
        let n = glam::Vec3::new(-scale * dx, -scale * dy, 1.0).normalize();
        let c = (n * 0.5 + glam::Vec3::splat(0.5)) * 255.0;
        image::Rgba([c.x.round() as u8, c.y.round() as u8, c.z.round() as u8, 255])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ramp_tilts_the_normal_against_its_slope_and_a_flat_height_points_straight_up() {
        // Height rising 0.1 per texel along x (repeating sawtooth: look away from the wrap).
        let ramp = image::RgbaImage::from_fn(16, 4, |x, _| {
            let v = (x as f32 * 0.1 * 255.0).round() as u8;
            image::Rgba([v, v, v, 255])
        });
        assert!(is_height_map(&ramp));
        let n = height_to_normal(&ramp, 2.0);
        let texel = n.get_pixel(5, 1).0;
        let decode = |c: u8| c as f32 / 255.0 * 2.0 - 1.0;
        let got = glam::Vec3::new(decode(texel[0]), decode(texel[1]), decode(texel[2]));
        let want = glam::Vec3::new(-0.2, 0.0, 1.0).normalize();
        assert!((got - want).length() < 0.01, "{got}");
        let flat = image::RgbaImage::from_pixel(4, 4, image::Rgba([90, 90, 90, 255]));
        assert_eq!(
            height_to_normal(&flat, 1.0).get_pixel(2, 2).0,
            [128, 128, 255, 255]
        );
        // A normal map is not grey.
        let normal = image::RgbaImage::from_pixel(2, 2, image::Rgba([128, 128, 255, 255]));
        assert!(!is_height_map(&normal));
    }

    #[test]
    fn the_bump_multiplier_is_read_from_the_statement() {
        assert_eq!(bump_multiplier("-bm 0.5 bricks.png"), 0.5);
        assert_eq!(bump_multiplier("bricks.png"), 1.0);
        assert_eq!(bump_multiplier("-bm nan bricks.png"), 1.0);
    }
}
