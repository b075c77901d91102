//! Writing rendered images: PNG (display) and OpenEXR (linear values), each through a
//! temporary file so a failure leaves nothing half-written.

use std::path::Path;

use super::RenderedFrame;
use crate::io::{write_atomic, WriteError};
use crate::scene::Mode;

/// Encodes an image in the format `path`'s extension names and writes it atomically.
pub fn write_image<P>(
    path: &Path,
    image: &image::ImageBuffer<P, Vec<P::Subpixel>>,
) -> Result<(), WriteError>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let format = image::ImageFormat::from_path(path).map_err(|_| WriteError::UnknownExtension {
        path: path.to_path_buf(),
    })?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, format)
        .map_err(|e| WriteError::encode(path, e))?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_path_without_a_known_format_is_refused_and_nothing_written() {
        let dir = std::env::temp_dir().join(format!("goniolight-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("room.txt");
        let image = image::RgbImage::new(2, 2);
        let e = write_image(&path, &image).unwrap_err();
        assert!(matches!(e, WriteError::UnknownExtension { .. }), "{e:?}");
        assert!(
            e.to_string().contains("room.txt: unknown image extension"),
            "{e}"
        );
        assert!(!path.exists());
        let png = dir.join("room.png");
        write_image(&png, &image).unwrap();
        assert_eq!(image::open(&png).unwrap().width(), 2);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
