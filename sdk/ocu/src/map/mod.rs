//! What the map may draw under the vehicles, from local files only (nothing by default,
//! no network): a georeferenced image ([`image`]) and a directory of slippy-map tiles
//! ([`tiles`]).
//!
//! The map's frame is metres east (x) and north (y) of the console's origin (its
//! `--origin`, else the first position received). An image is placed in that frame by a
//! world file or by its bounds; tiles are placed by latitude and longitude, so the page
//! draws them once the origin is known.

pub mod image;
pub mod tiles;

use std::path::{Path, PathBuf};
use std::sync::Arc;

pub use image::{Affine, Format};
pub use tiles::Tiles;

/// How a background image is placed on the map.
#[derive(Debug, Clone, PartialEq)]
pub enum Placement {
    /// Its outer edges: west, south, east, north, metres in the map's frame.
    Bounds([f64; 4]),
    /// A world file (six lines: a, d, b, e, c, f) in the map's frame, metres.
    WorldFile(PathBuf),
}

/// A background image to load.
#[derive(Debug, Clone, PartialEq)]
pub struct BackgroundSource {
    /// The image (PNG or JPEG).
    pub image: PathBuf,
    /// Where it lies.
    pub placement: Placement,
}

impl BackgroundSource {
    /// `image` placed by `bounds` when given, else by the world file beside it
    /// ([`image::sidecar`]); an error saying both ways when there is neither.
    pub fn new(image: PathBuf, bounds: Option<[f64; 4]>) -> Result<Self, MapError> {
        let placement = match bounds {
            Some(b) => Placement::Bounds(b),
            None => Placement::WorldFile(image::sidecar(&image).ok_or_else(|| {
                MapError::Image {
                    path: image.clone(),
                    what: "no world file beside it (e.g. a .pgw for a .png, a .jgw for a .jpg, or .wld) and no --background-bounds".into(),
                }
            })?),
        };
        Ok(Self { image, placement })
    }
}

/// The map's optional layers, as given.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapOptions {
    /// A georeferenced image.
    pub background: Option<BackgroundSource>,
    /// A directory of tiles, `z/x/y.png`.
    pub tiles: Option<PathBuf>,
}

/// Why a layer could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MapError {
    /// The background image.
    #[error("background image {}: {what}", path.display())]
    Image {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
    /// A world file line.
    #[error("{}:{line}: {what}", path.display())]
    WorldFile {
        /// The file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// The tile directory.
    #[error("tile directory {}: {what}", path.display())]
    Tiles {
        /// The directory.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
}

/// A loaded background image.
#[derive(Debug, Clone)]
pub struct Background {
    /// The file's bytes.
    pub bytes: Arc<[u8]>,
    /// Its format.
    pub format: Format,
    /// Its size in pixels.
    pub width: u32,
    /// Its height in pixels.
    pub height: u32,
    /// Where it lies.
    pub affine: Affine,
}

impl Background {
    /// Reads and places `source`'s image.
    pub fn load(source: &BackgroundSource) -> Result<Self, MapError> {
        let path = &source.image;
        let err = |what: String| MapError::Image {
            path: path.clone(),
            what,
        };
        let bytes = read_bounded(path, image::IMAGE_MAX).map_err(err)?;
        let (format, width, height) = image::probe(&bytes)
            .ok_or_else(|| err("not a PNG or JPEG image (or cut short)".into()))?;
        if width == 0 || height == 0 {
            return Err(err(format!("{width} × {height} pixels")));
        }
        let affine = match &source.placement {
            Placement::Bounds(b) => Affine::from_bounds(*b, width, height).map_err(err)?,
            Placement::WorldFile(w) => {
                let text = String::from_utf8(read_bounded(w, 4096).map_err(|what| {
                    MapError::WorldFile {
                        path: w.clone(),
                        line: 0,
                        what,
                    }
                })?)
                .map_err(|_| MapError::WorldFile {
                    path: w.clone(),
                    line: 0,
                    what: "not text".into(),
                })?;
                Affine::parse_world_file(&text, w)?
            }
        };
        Ok(Self {
            bytes: bytes.into(),
            format,
            width,
            height,
            affine,
        })
    }
}

/// The layers the server serves.
#[derive(Debug, Clone, Default)]
pub struct MapLayers {
    /// The background image, if any.
    pub background: Option<Background>,
    /// The tile directory, if any.
    pub tiles: Option<Tiles>,
}

impl MapLayers {
    /// Loads what `options` name (checking every file now, so a mistake stops the
    /// console at start-up with the file and the reason).
    pub fn load(options: &MapOptions) -> Result<Self, MapError> {
        Ok(Self {
            background: options
                .background
                .as_ref()
                .map(Background::load)
                .transpose()?,
            tiles: options.tiles.as_deref().map(Tiles::open).transpose()?,
        })
    }

    /// What the page needs to draw the layers (`GET /api/map`), as JSON.
    pub fn json(&self) -> String {
        let background = self.background.as_ref().map(|b| {
            serde_json::json!({
                "url": "/map/background",
                "width": b.width,
                "height": b.height,
                "matrix": b.affine.svg_matrix(),
                "extent": b.affine.extent(b.width, b.height),
            })
        });
        let tiles = self.tiles.as_ref().map(|t| {
            serde_json::json!({
                "url": format!("/map/tiles/{{z}}/{{x}}/{{y}}.{}", t.ext()),
                "zooms": t.zooms(),
            })
        });
        serde_json::json!({ "background": background, "tiles": tiles }).to_string()
    }
}

/// The bytes of `path`, at most `max` of them.
fn read_bounded(path: &Path, max: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let len = file.metadata().map_err(|e| e.to_string())?.len();
    if len > max {
        return Err(format!("{len} bytes: larger than {max}"));
    }
    let mut bytes = Vec::new();
    file.take(max + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max {
        return Err(format!("larger than {max} bytes"));
    }
    Ok(bytes)
}
