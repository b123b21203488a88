//! Raster images as cameras deliver them ([`RgbImage`]) and their encodings for Report
//! Image: PNG (through the `png` crate) and binary PPM.

use crate::messages::ImageFormat;

/// An 8-bit RGB image, rows top to bottom, pixels left to right.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbImage {
    /// Width, pixels.
    pub width: u16,
    /// Height, pixels.
    pub height: u16,
    /// `width × height × 3` bytes.
    pub pixels: Vec<u8>,
}

impl RgbImage {
    /// A `width × height` image of one colour.
    pub fn filled(width: u16, height: u16, rgb: [u8; 3]) -> Self {
        let n = usize::from(width) * usize::from(height);
        Self {
            width,
            height,
            pixels: rgb.iter().copied().cycle().take(n * 3).collect(),
        }
    }

    /// Sets pixel (`x`, `y`) (outside the image: nothing).
    pub fn put(&mut self, x: usize, y: usize, rgb: [u8; 3]) {
        if x < usize::from(self.width) && y < usize::from(self.height) {
            let at = (y * usize::from(self.width) + x) * 3;
            self.pixels[at..at + 3].copy_from_slice(&rgb);
        }
    }

    /// Pixel (`x`, `y`), if inside.
    pub fn get(&self, x: usize, y: usize) -> Option<[u8; 3]> {
        (x < usize::from(self.width) && y < usize::from(self.height)).then(|| {
            let at = (y * usize::from(self.width) + x) * 3;
            [self.pixels[at], self.pixels[at + 1], self.pixels[at + 2]]
        })
    }
}

/// Why an image could not be encoded.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ImageError {
    /// The format is not one this encoder writes.
    #[error("image format {0:?} is not encoded here (PNG and PPM are)")]
    Format(ImageFormat),
    /// The pixel buffer does not match the size.
    #[error("{len} bytes of pixels for a {width}×{height} RGB image ({} expected)", usize::from(*width) * usize::from(*height) * 3)]
    Size {
        /// Width.
        width: u16,
        /// Height.
        height: u16,
        /// Bytes given.
        len: usize,
    },
    /// The PNG encoder failed.
    #[error("PNG encoding: {0}")]
    Png(String),
}

/// The formats [`encode`] writes.
pub const FORMATS: [ImageFormat; 2] = [ImageFormat::Png, ImageFormat::Ppm];

/// `image` in `format` (PNG or PPM).
pub fn encode(image: &RgbImage, format: ImageFormat) -> Result<Vec<u8>, ImageError> {
    let expected = usize::from(image.width) * usize::from(image.height) * 3;
    if image.pixels.len() != expected {
        return Err(ImageError::Size {
            width: image.width,
            height: image.height,
            len: image.pixels.len(),
        });
    }
    match format {
        ImageFormat::Png => {
            let mut out = Vec::new();
            let mut e = png::Encoder::new(&mut out, image.width.into(), image.height.into());
            e.set_color(png::ColorType::Rgb);
            e.set_depth(png::BitDepth::Eight);
            let mut w = e
                .write_header()
                .map_err(|e| ImageError::Png(e.to_string()))?;
            w.write_image_data(&image.pixels)
                .map_err(|e| ImageError::Png(e.to_string()))?;
            w.finish().map_err(|e| ImageError::Png(e.to_string()))?;
            Ok(out)
        }
        ImageFormat::Ppm => {
            let mut out = format!("P6\n{} {}\n255\n", image.width, image.height).into_bytes();
            out.extend_from_slice(&image.pixels);
            Ok(out)
        }
        other => Err(ImageError::Format(other)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_and_ppm_carry_the_size_and_the_pixels() {
        let mut img = RgbImage::filled(4, 3, [10, 20, 30]);
        img.put(1, 2, [255, 0, 0]);
        assert_eq!(img.get(1, 2), Some([255, 0, 0]));
        assert_eq!(img.get(4, 0), None);
        let png = encode(&img, ImageFormat::Png).unwrap();
        let mut d = png::Decoder::new(png.as_slice()).read_info().unwrap();
        let mut buf = vec![0; d.output_buffer_size()];
        let info = d.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (4, 3));
        assert_eq!(&buf[..info.buffer_size()], img.pixels.as_slice());
        let ppm = encode(&img, ImageFormat::Ppm).unwrap();
        assert!(ppm.starts_with(b"P6\n4 3\n255\n"));
        assert_eq!(ppm.len(), 11 + 36);
        assert_eq!(
            encode(&img, ImageFormat::Jpeg),
            Err(ImageError::Format(ImageFormat::Jpeg))
        );
        img.pixels.pop();
        assert!(matches!(
            encode(&img, ImageFormat::Png),
            Err(ImageError::Size { len: 35, .. })
        ));
    }
}
