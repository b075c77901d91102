//! (Included by `#[path]` where needed.) SVG outputs checked as pictures: rendered with resvg (the bundled font loaded), so a
//! file that is not SVG, or draws nothing, fails.

use std::path::Path;

/// An RGBA picture.
pub struct Picture {
    /// Width, pixels.
    pub width: u32,
    /// Row-major RGB(A-demultiplied) pixels.
    pub rgb: Vec<[u8; 3]>,
}

/// Renders the SVG file at its own size on white.
pub fn render(path: &Path) -> Picture {
    let data = std::fs::read(path).unwrap();
    assert!(
        data.starts_with(b"<svg") || data.starts_with(b"<?xml"),
        "{}: not SVG (starts {:?})",
        path.display(),
        &data[..data.len().min(8)]
    );
    let mut options = resvg::usvg::Options::default();
    options.fontdb_mut().load_font_data(
        std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/fonts/DejaVuSans.ttf"))
            .unwrap(),
    );
    // The diagrams ask for "sans-serif": that is the bundled DejaVu Sans here.
    options.fontdb_mut().set_sans_serif_family("DejaVu Sans");
    let tree = resvg::usvg::Tree::from_data(&data, &options)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height()).unwrap();
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(&tree, Default::default(), &mut pixmap.as_mut());
    Picture {
        width: size.width(),
        rgb: pixmap
            .pixels()
            .iter()
            .map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue()]
            })
            .collect(),
    }
}

/// The PNG file as a picture.
pub fn load_png(path: &Path) -> Picture {
    let img = image::open(path).unwrap().to_rgb8();
    Picture {
        width: img.width(),
        rgb: img.pixels().map(|p| p.0).collect(),
    }
}

/// The (x, y) of every pixel within 12 levels of `rgb` in each channel.
pub fn pixels_of(p: &Picture, rgb: [u8; 3]) -> Vec<(u32, u32)> {
    p.rgb
        .iter()
        .enumerate()
        .filter(|(_, c)| c.iter().zip(rgb).all(|(a, b)| a.abs_diff(b) <= 12))
        .map(|(i, _)| (i as u32 % p.width, i as u32 / p.width))
        .collect()
}

/// Writes the picture as PNG (to look at a rendered SVG while developing a test).
pub fn save_png(p: &Picture, path: &Path) {
    let height = p.rgb.len() as u32 / p.width;
    let bytes: Vec<u8> = p.rgb.iter().flatten().copied().collect();
    image::RgbImage::from_raw(p.width, height, bytes)
        .unwrap()
        .save(path)
        .unwrap();
}
