//! A local directory of map tiles in the usual `z/x/y.png` ("slippy map") layout, served
//! one tile at a time. A request names a tile by three integers only; the file it reads
//! is the canonical path of `DIR/z/x/y.ext`, which must still lie inside the directory's
//! own canonical path (so no `..`, no absolute path and no symbolic link leads out), be a
//! regular file and be no larger than [`TILE_MAX`].

use std::io::Read;
use std::path::{Path, PathBuf};

use super::MapError;

/// The largest tile served, bytes.
pub const TILE_MAX: u64 = 4 << 20;

/// The deepest zoom level a tile may have (2^30 tiles across).
pub const ZOOM_MAX: u8 = 30;

/// Tile file extensions, with their Content-Type.
const KINDS: [(&str, &str); 4] = [
    ("png", "image/png"),
    ("jpg", "image/jpeg"),
    ("jpeg", "image/jpeg"),
    ("webp", "image/webp"),
];

/// A tile directory.
#[derive(Debug, Clone)]
pub struct Tiles {
    root: PathBuf,
    zooms: Vec<u8>,
    ext: &'static str,
}

/// Why a tile is not served.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Miss {
    /// The request is not `z/x/y.ext` with integers in range and the directory's
    /// extension.
    BadAddress,
    /// No such tile, or not a regular file inside the directory, or too large (the
    /// reason, for the log).
    NotFound(String),
}

impl Tiles {
    /// The directory `dir`: canonicalized, with the zoom levels it holds (its
    /// subdirectories named 0 to [`ZOOM_MAX`]) and the tiles' extension (that of the
    /// first tile found).
    pub fn open(dir: &Path) -> Result<Self, MapError> {
        let err = |what: String| MapError::Tiles {
            path: dir.to_path_buf(),
            what,
        };
        let root = dir.canonicalize().map_err(|e| err(e.to_string()))?;
        if !root.is_dir() {
            return Err(err("not a directory".into()));
        }
        let mut zooms: Vec<u8> = std::fs::read_dir(&root)
            .map_err(|e| err(e.to_string()))?
            .filter_map(Result::ok)
            .filter(|e| e.path().is_dir())
            .filter_map(|e| integer(e.file_name().to_str()?, u64::from(ZOOM_MAX)))
            .filter_map(|z| u8::try_from(z).ok())
            .collect();
        zooms.sort_unstable();
        if zooms.is_empty() {
            return Err(err(format!(
                "no zoom level directories (0 to {ZOOM_MAX}): expected the z/x/y.png layout"
            )));
        }
        let ext = zooms
            .iter()
            .find_map(|z| first_tile_ext(&root.join(z.to_string())))
            .ok_or_else(|| err("no tiles (z/x/y.png, .jpg or .webp) found".into()))?;
        Ok(Self { root, zooms, ext })
    }

    /// The zoom levels, ascending.
    pub fn zooms(&self) -> &[u8] {
        &self.zooms
    }

    /// The tiles' file extension (`png`, `jpg`, `jpeg` or `webp`).
    pub fn ext(&self) -> &'static str {
        self.ext
    }

    /// The tile named by the request's path segments `z`, `x` and `name` (`y.ext`): its
    /// bytes and Content-Type.
    pub fn read(&self, z: &str, x: &str, name: &str) -> Result<(Vec<u8>, &'static str), Miss> {
        let z = integer(z, u64::from(ZOOM_MAX)).ok_or(Miss::BadAddress)?;
        let last = (1u64 << z) - 1;
        let x = integer(x, last).ok_or(Miss::BadAddress)?;
        let (y, ext) = name.split_once('.').ok_or(Miss::BadAddress)?;
        let y = integer(y, last).ok_or(Miss::BadAddress)?;
        if ext != self.ext {
            return Err(Miss::BadAddress);
        }
        let mime = KINDS
            .iter()
            .find(|(e, _)| *e == ext)
            .map(|(_, m)| *m)
            .ok_or(Miss::BadAddress)?;
        // Built from the integers, never from the request's text.
        let path = self
            .root
            .join(z.to_string())
            .join(x.to_string())
            .join(format!("{y}.{ext}"));
        let miss = |why: String| Miss::NotFound(format!("{}: {why}", path.display()));
        let real = path.canonicalize().map_err(|e| miss(e.to_string()))?;
        if !real.starts_with(&self.root) {
            return Err(miss(format!(
                "leads out of the tile directory (to {})",
                real.display()
            )));
        }
        let file = std::fs::File::open(&real).map_err(|e| miss(e.to_string()))?;
        let meta = file.metadata().map_err(|e| miss(e.to_string()))?;
        if !meta.is_file() {
            return Err(miss("not a regular file".into()));
        }
        if meta.len() > TILE_MAX {
            return Err(miss(format!(
                "{} bytes: larger than {TILE_MAX}",
                meta.len()
            )));
        }
        let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
        file.take(TILE_MAX + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| miss(e.to_string()))?;
        if bytes.len() as u64 > TILE_MAX {
            return Err(miss(format!("grew larger than {TILE_MAX} bytes")));
        }
        Ok((bytes, mime))
    }
}

/// A decimal integer of at most 10 ASCII digits, no sign, no leading zero (so each tile
/// has one name), at most `max`.
fn integer(text: &str, max: u64) -> Option<u64> {
    let plain = !text.is_empty()
        && text.len() <= 10
        && text.bytes().all(|b| b.is_ascii_digit())
        && (text == "0" || !text.starts_with('0'));
    plain
        .then(|| text.parse::<u64>().ok())
        .flatten()
        .filter(|v| *v <= max)
}

/// The extension of the first tile under a zoom level's directory `zdir`.
fn first_tile_ext(zdir: &Path) -> Option<&'static str> {
    std::fs::read_dir(zdir)
        .ok()?
        .filter_map(Result::ok)
        .filter(|e| e.path().is_dir())
        .take(64)
        .find_map(|xdir| {
            std::fs::read_dir(xdir.path())
                .ok()?
                .filter_map(Result::ok)
                .take(64)
                .find_map(|f| {
                    let name = f.file_name();
                    let (_, ext) = name.to_str()?.rsplit_once('.')?;
                    KINDS.iter().find(|(e, _)| *e == ext).map(|(e, _)| *e)
                })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_addresses_are_plain_integers_in_range() {
        assert_eq!(integer("0", 5), Some(0));
        assert_eq!(integer("17", 30), Some(17));
        for bad in [
            "",
            "-1",
            "+1",
            "01",
            "1.0",
            "31",
            " 1",
            "..",
            "%2e",
            "99999999999",
        ] {
            assert_eq!(integer(bad, 30), None, "{bad:?}");
        }
    }
}
