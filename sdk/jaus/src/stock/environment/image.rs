//! Raster images as cameras deliver them ([`RgbImage`]) and their encodings for Report
//! Image: PNG (through the `png` crate) and binary PPM; baseline JPEG (through the
//! `jpeg-encoder` crate) for video frames; and the way back ([`decode`]) from PNG and
//! PPM, bounded before any pixel is decoded.

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
    /// The JPEG encoder failed.
    #[error("JPEG encoding: {0}")]
    Jpeg(String),
    /// The bytes are not an image of the format they were said to be.
    #[error("{format:?} decoding: {why}")]
    Decode {
        /// The format expected.
        format: ImageFormat,
        /// What is wrong.
        why: String,
    },
    /// The image would be larger than allowed (checked before its pixels are decoded).
    #[error("a {width}×{height} image ({bytes} bytes as RGB) is over the {limit}-byte limit")]
    TooLarge {
        /// Width, pixels.
        width: u32,
        /// Height, pixels.
        height: u32,
        /// Its size as RGB (or as given, if larger), bytes.
        bytes: usize,
        /// The limit, bytes.
        limit: usize,
    },
}

/// The formats the stock camera offers (Report Image); [`encode`] writes JPEG too.
pub const FORMATS: [ImageFormat; 2] = [ImageFormat::Png, ImageFormat::Ppm];

/// The quality [`encode`] gives JPEG (1–100).
pub const JPEG_QUALITY: u8 = 80;

/// `image` in `format` (PNG, PPM or JPEG).
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
        ImageFormat::Jpeg => {
            let mut out = Vec::new();
            jpeg_encoder::Encoder::new(&mut out, JPEG_QUALITY)
                .encode(
                    &image.pixels,
                    image.width,
                    image.height,
                    jpeg_encoder::ColorType::Rgb,
                )
                .map_err(|e| ImageError::Jpeg(e.to_string()))?;
            Ok(out)
        }
        other => Err(ImageError::Format(other)),
    }
}

/// `data`, an image in `format` (PNG or PPM), as RGB: PNG palettes and low bit depths
/// expanded, 16 bits to 8, grey replicated, alpha dropped. Refused, before its pixels
/// are decoded, when it would take more than `max_bytes` as RGB (or as decoded).
pub fn decode(format: ImageFormat, data: &[u8], max_bytes: usize) -> Result<RgbImage, ImageError> {
    match format {
        ImageFormat::Png => decode_png(data, max_bytes),
        ImageFormat::Ppm => decode_ppm(data, max_bytes),
        other => Err(ImageError::Format(other)),
    }
}

/// Checks a `width` × `height` image of `given` bytes against `limit` (and `u16` sides).
fn check_size(width: u32, height: u32, given: usize, limit: usize) -> Result<(), ImageError> {
    let rgb = (width as usize)
        .saturating_mul(height as usize)
        .saturating_mul(3);
    let bytes = rgb.max(given);
    if width > u32::from(u16::MAX) || height > u32::from(u16::MAX) || bytes > limit {
        return Err(ImageError::TooLarge {
            width,
            height,
            bytes,
            limit,
        });
    }
    Ok(())
}

fn decode_png(data: &[u8], max_bytes: usize) -> Result<RgbImage, ImageError> {
    let bad = |e: png::DecodingError| ImageError::Decode {
        format: ImageFormat::Png,
        why: e.to_string(),
    };
    let mut d = png::Decoder::new_with_limits(data, png::Limits { bytes: max_bytes });
    d.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut r = d.read_info().map_err(bad)?;
    let (w, h) = (r.info().width, r.info().height);
    check_size(w, h, 0, max_bytes)?;
    let mut buf = vec![0; r.output_buffer_size()];
    let f = r.next_frame(&mut buf).map_err(bad)?;
    let bpp = match f.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => {
            return Err(ImageError::Decode {
                format: ImageFormat::Png,
                why: "a palette left unexpanded".into(),
            })
        }
    };
    let (w, h) = (w as usize, h as usize);
    let mut pixels = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        let start = y.saturating_mul(f.line_size);
        let row = buf
            .get(start..start.saturating_add(w * bpp))
            .ok_or_else(|| ImageError::Decode {
                format: ImageFormat::Png,
                why: format!("row {y} is short"),
            })?;
        for p in row.chunks_exact(bpp) {
            pixels.extend_from_slice(&if bpp < 3 {
                [p[0]; 3]
            } else {
                [p[0], p[1], p[2]]
            });
        }
    }
    // check_size bounded both sides to u16.
    Ok(RgbImage {
        width: w as u16,
        height: h as u16,
        pixels,
    })
}

/// Binary PPM (`P6`, maxval 255, `#` comments in the header).
fn decode_ppm(data: &[u8], max_bytes: usize) -> Result<RgbImage, ImageError> {
    let bad = |why: &str| ImageError::Decode {
        format: ImageFormat::Ppm,
        why: why.into(),
    };
    let mut at = 0;
    let mut token = || -> Option<&[u8]> {
        loop {
            match data.get(at)? {
                b'#' => {
                    while *data.get(at)? != b'\n' {
                        at += 1;
                    }
                }
                c if c.is_ascii_whitespace() => at += 1,
                _ => break,
            }
        }
        let start = at;
        while data.get(at).is_some_and(|c| !c.is_ascii_whitespace()) {
            at += 1;
        }
        Some(&data[start..at])
    };
    let number = |t: Option<&[u8]>| -> Option<u32> { std::str::from_utf8(t?).ok()?.parse().ok() };
    if token() != Some(b"P6".as_slice()) {
        return Err(bad("not a binary PPM (P6)"));
    }
    let (w, h, max) = (number(token()), number(token()), number(token()));
    let (Some(w), Some(h), Some(255)) = (w, h, max) else {
        return Err(bad("a header of width, height and maxval 255 expected"));
    };
    check_size(w, h, 0, max_bytes)?;
    // One whitespace byte ends the header.
    let pixels = data
        .get(at + 1..)
        .and_then(|p| p.get(..w as usize * h as usize * 3))
        .ok_or_else(|| bad("fewer pixel bytes than the header says"))?;
    Ok(RgbImage {
        width: w as u16,
        height: h as u16,
        pixels: pixels.to_vec(),
    })
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
        assert_eq!(decode(ImageFormat::Png, &png, 1 << 20).unwrap(), img);
        assert_eq!(decode(ImageFormat::Ppm, &ppm, 1 << 20).unwrap(), img);
        let jpeg = encode(&img, ImageFormat::Jpeg).unwrap();
        assert!(jpeg.starts_with(&[0xFF, 0xD8]) && jpeg.ends_with(&[0xFF, 0xD9]));
        assert_eq!(
            encode(&img, ImageFormat::Gif),
            Err(ImageError::Format(ImageFormat::Gif))
        );
        // Bounded before decoding; bad bytes are typed errors.
        assert!(matches!(
            decode(ImageFormat::Png, &png, 30),
            Err(ImageError::TooLarge {
                width: 4,
                height: 3,
                bytes: 36,
                limit: 30
            })
        ));
        assert!(matches!(
            decode(ImageFormat::Ppm, b"P6\n4000 4000\n255\n", 1 << 20),
            Err(ImageError::TooLarge { .. })
        ));
        for short in [
            &png[..png.len() - 20],
            b"P6\n4 3\n255\nabc".as_slice(),
            b"P3\n1 1\n255\n",
        ] {
            let format = if short.starts_with(b"P") {
                ImageFormat::Ppm
            } else {
                ImageFormat::Png
            };
            assert!(
                matches!(
                    decode(format, short, 1 << 20),
                    Err(ImageError::Decode { .. })
                ),
                "{short:?}"
            );
        }
        img.pixels.pop();
        assert!(matches!(
            encode(&img, ImageFormat::Png),
            Err(ImageError::Size { len: 35, .. })
        ));
    }
}
