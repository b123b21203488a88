//! A background image and where it lies: its size (read from a PNG or JPEG header), and
//! its georeference, a world file or bounds, as one affine map from pixels to the map's
//! metres.

use std::path::Path;

use super::MapError;

/// The largest background image the console loads, bytes.
pub const IMAGE_MAX: u64 = 64 << 20;

/// An image format the page can draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// PNG.
    Png,
    /// JPEG.
    Jpeg,
}

impl Format {
    /// The HTTP Content-Type.
    pub fn mime(self) -> &'static str {
        match self {
            Format::Png => "image/png",
            Format::Jpeg => "image/jpeg",
        }
    }
}

/// An image's format and size in pixels, from its header; `None` when it is neither a
/// PNG nor a baseline or progressive JPEG, or is cut short.
pub fn probe(bytes: &[u8]) -> Option<(Format, u32, u32)> {
    const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
    if bytes.starts_with(PNG) {
        if bytes.get(12..16)? != b"IHDR" {
            return None;
        }
        let be = |at: usize| Some(u32::from_be_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
        return Some((Format::Png, be(16)?, be(20)?));
    }
    if !bytes.starts_with(&[0xFF, 0xD8]) {
        return None;
    }
    // JPEG: walk the marker segments to the first start of frame.
    let mut at = 2;
    loop {
        while *bytes.get(at)? != 0xFF {
            at += 1;
        }
        while *bytes.get(at)? == 0xFF {
            at += 1;
        }
        let marker = *bytes.get(at)?;
        at += 1;
        if matches!(marker, 0x01 | 0xD0..=0xD9) {
            continue;
        }
        let len = usize::from(u16::from_be_bytes([*bytes.get(at)?, *bytes.get(at + 1)?]));
        let start_of_frame = matches!(marker, 0xC0..=0xCF) && !matches!(marker, 0xC4 | 0xC8 | 0xCC);
        if start_of_frame {
            let h = u16::from_be_bytes([*bytes.get(at + 3)?, *bytes.get(at + 4)?]);
            let w = u16::from_be_bytes([*bytes.get(at + 5)?, *bytes.get(at + 6)?]);
            return Some((Format::Jpeg, u32::from(w), u32::from(h)));
        }
        if len < 2 {
            return None;
        }
        at += len;
    }
}

/// Where an image lies on the map: a world file's six numbers. A pixel (column, row),
/// counted from the upper-left pixel's centre, lies at x = a·col + b·row + c (metres
/// east of the origin), y = d·col + e·row + f (metres north).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// x metres per column (the pixel's width).
    pub a: f64,
    /// y metres per column (rotation; 0 for a north-up image).
    pub d: f64,
    /// x metres per row (rotation; 0 for a north-up image).
    pub b: f64,
    /// y metres per row (negative: rows go south).
    pub e: f64,
    /// x of the upper-left pixel's centre.
    pub c: f64,
    /// y of the upper-left pixel's centre.
    pub f: f64,
}

impl Affine {
    /// The placement of a `width` × `height` image whose outer edges are `x0` (west),
    /// `y0` (south), `x1` (east), `y1` (north), metres.
    pub fn from_bounds(
        [x0, y0, x1, y1]: [f64; 4],
        width: u32,
        height: u32,
    ) -> Result<Self, String> {
        if ![x0, y0, x1, y1].iter().all(|v| v.is_finite()) || x1 <= x0 || y1 <= y0 {
            return Err(format!(
                "bounds {x0},{y0},{x1},{y1}: need x0 < x1 and y0 < y1 (west, south, east, north, metres)"
            ));
        }
        let a = (x1 - x0) / f64::from(width);
        let e = -(y1 - y0) / f64::from(height);
        Ok(Self {
            a,
            d: 0.0,
            b: 0.0,
            e,
            c: x0 + a / 2.0,
            f: y1 + e / 2.0,
        })
    }

    /// A world file's text (six numbers, one a line: a, d, b, e, c, f); errors name the
    /// file (`path`) and line.
    pub fn parse_world_file(text: &str, path: &Path) -> Result<Self, MapError> {
        let at = |line: usize, what: String| MapError::WorldFile {
            path: path.to_path_buf(),
            line,
            what,
        };
        let mut v = [0.0f64; 6];
        let mut n = 0;
        for (i, raw) in text.lines().enumerate() {
            let t = raw.trim();
            if t.is_empty() {
                continue;
            }
            if n == 6 {
                return Err(at(
                    i + 1,
                    format!("a seventh value `{t}`: a world file has six"),
                ));
            }
            v[n] = t
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| at(i + 1, format!("`{t}` is not a number")))?;
            n += 1;
        }
        if n < 6 {
            return Err(at(
                text.lines().count(),
                format!("{n} values: a world file has six (a, d, b, e, c, f)"),
            ));
        }
        let [a, d, b, e, c, f] = v;
        if (a * e - b * d).abs() < f64::MIN_POSITIVE {
            return Err(at(
                1,
                "the pixel size is zero (a·e − b·d = 0): the image would have no area".into(),
            ));
        }
        Ok(Self { a, d, b, e, c, f })
    }

    /// The SVG `matrix(…)` that places an image drawn at (0, 0) with its size in pixels
    /// on the page's map, whose SVG y is minus the map's y (north up).
    pub fn svg_matrix(&self) -> [f64; 6] {
        // Pixel edges: the upper-left pixel's centre is at (0.5, 0.5) of the image.
        let c = self.c - (self.a + self.b) / 2.0;
        let f = self.f - (self.d + self.e) / 2.0;
        [self.a, -self.d, self.b, -self.e, c, -f]
    }

    /// The map position of the image point (`u`, `v`) in pixels from its upper-left
    /// corner.
    pub fn at(&self, u: f64, v: f64) -> (f64, f64) {
        let (col, row) = (u - 0.5, v - 0.5);
        (
            self.a * col + self.b * row + self.c,
            self.d * col + self.e * row + self.f,
        )
    }

    /// The smallest rectangle (west, south, east, north) holding a `width` × `height`
    /// image.
    pub fn extent(&self, width: u32, height: u32) -> [f64; 4] {
        let (w, h) = (f64::from(width), f64::from(height));
        let corners = [
            self.at(0.0, 0.0),
            self.at(w, 0.0),
            self.at(0.0, h),
            self.at(w, h),
        ];
        corners.iter().fold(
            [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            |r, &(x, y)| [r[0].min(x), r[1].min(y), r[2].max(x), r[3].max(y)],
        )
    }
}

/// The world file beside `image`, if there is one: the image's name with the extension's
/// first and last letters and `w` (`map.png` → `map.pgw`), its extension and `w`
/// (`map.pngw`), or `.wld`.
pub fn sidecar(image: &Path) -> Option<std::path::PathBuf> {
    let ext = image.extension()?.to_str()?.to_ascii_lowercase();
    let mut names = Vec::new();
    if let (Some(first), Some(last)) = (ext.chars().next(), ext.chars().last()) {
        names.push(format!("{first}{last}w"));
    }
    names.push(format!("{ext}w"));
    names.push("wld".into());
    names
        .iter()
        .flat_map(|n| [n.clone(), n.to_ascii_uppercase()])
        .map(|n| image.with_extension(n))
        .find(|p| p.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_and_jpeg_sizes_come_from_their_headers() {
        let mut png = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
        png.extend_from_slice(&640u32.to_be_bytes());
        png.extend_from_slice(&480u32.to_be_bytes());
        assert_eq!(probe(&png), Some((Format::Png, 640, 480)));
        assert_eq!(probe(&png[..18]), None, "cut short");
        // SOI, an APP0 of 16 bytes, then SOF0: length 17, precision 8, height 300, width 200.
        let mut jpeg = vec![0xFF, 0xD8, 0xFF, 0xE0, 0, 16];
        jpeg.extend_from_slice(&[0; 14]);
        jpeg.extend_from_slice(&[0xFF, 0xC0, 0, 17, 8, 0x01, 0x2C, 0, 0xC8, 3]);
        assert_eq!(probe(&jpeg), Some((Format::Jpeg, 200, 300)));
        assert_eq!(probe(b"GIF89a....."), None);
        assert_eq!(probe(&[0xFF, 0xD8, 0xFF, 0xE0, 0, 1]), None, "a bad length");
    }

    #[test]
    fn bounds_and_world_files_are_the_same_placement() {
        let from_bounds = Affine::from_bounds([-50.0, -20.0, 50.0, 30.0], 200, 100).unwrap();
        let text = "0.5\n0\n0\n-0.5\n-49.75\n29.75\n";
        let world = Affine::parse_world_file(text, Path::new("map.pgw")).unwrap();
        assert_eq!(from_bounds, world);
        assert_eq!(world.extent(200, 100), [-50.0, -20.0, 50.0, 30.0]);
        // The image's upper-left corner lands on (west, -north) in SVG coordinates.
        let m = world.svg_matrix();
        assert_eq!((m[4], m[5]), (-50.0, -30.0));
        assert_eq!((m[0], m[3]), (0.5, 0.5));
        assert!(Affine::from_bounds([1.0, 0.0, 0.0, 1.0], 10, 10).is_err());
    }

    #[test]
    fn world_file_errors_name_the_file_and_line() {
        let p = Path::new("bg.pgw");
        let e = Affine::parse_world_file("1\n0\nzero\n-1\n0\n0\n", p).unwrap_err();
        assert_eq!(e.to_string(), "bg.pgw:3: `zero` is not a number");
        let e = Affine::parse_world_file("1\n0\n0\n-1\n", p).unwrap_err();
        assert!(e.to_string().contains("4 values"), "{e}");
        let e = Affine::parse_world_file("1\n0\n0\n-1\n0\n0\n7\n", p).unwrap_err();
        assert!(e.to_string().starts_with("bg.pgw:7:"), "{e}");
        let e = Affine::parse_world_file("0\n0\n0\n0\n0\n0\n", p).unwrap_err();
        assert!(e.to_string().contains("zero"), "{e}");
        let e = Affine::parse_world_file("1\n0\n0\n-1\ninf\n0\n", p).unwrap_err();
        assert!(e.to_string().starts_with("bg.pgw:5:"), "{e}");
    }
}
