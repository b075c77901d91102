//! Writing rendered images: PNG (display) and OpenEXR (linear values), each through a
//! temporary file so a failure leaves nothing half-written.

use std::path::Path;

use anyhow::Context;

use super::RenderedFrame;
use crate::io::write_atomic;
use crate::scene::Mode;

/// Encodes an image in the format `path`'s extension names and writes it atomically.
pub fn write_image<P>(
    path: &Path,
    image: &image::ImageBuffer<P, Vec<P::Subpixel>>,
) -> anyhow::Result<()>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let format = image::ImageFormat::from_path(path)
        .with_context(|| format!("{}: unknown image extension", path.display()))?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, format)
        .with_context(|| format!("encoding {}", path.display()))?;
    write_atomic(path, bytes.get_ref())
}

/// The linear image of a frame (needs `hdr`): luminance RGB in cd/m² in shaded mode, the
/// illuminance in lux in every channel in illuminance mode; 0 where no surface is seen.
pub fn linear_image(frame: &RenderedFrame, width: u32, height: u32) -> Option<image::Rgb32FImage> {
    let hdr = frame.hdr.as_ref()?;
    let mut data = Vec::with_capacity(hdr.len() * 3);
    for px in hdr {
        let v = match (px[3] < 0.0, frame.tone.mode) {
            (true, _) => [0.0; 3],
            (false, Mode::Shaded) => [px[0], px[1], px[2]],
            (false, Mode::Illuminance) => [px[3]; 3],
        };
        data.extend(v);
    }
    image::Rgb32FImage::from_raw(width, height, data)
}
