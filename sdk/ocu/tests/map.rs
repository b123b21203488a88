//! The map's background layers over plain HTTP: `/api/map`, `/map/background` and
//! `/map/tiles/Z/X/Y.EXT` pass the guard like every other route (no key, a rebinding
//! name, another origin: refused and counted), serve the right bytes with the right
//! Content-Type, and never serve a file outside the given image or tile directory
//! (`..`, encoded slashes, absolute paths, symbolic links out of the directory, a
//! directory, an oversized file, out-of-range or non-integer addresses); a mistake in
//! the command line's files stops the console at start-up naming the file.

mod common;

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use common::{console, request, Answer, Console};
use jaus_ocu::map::tiles::TILE_MAX;
use jaus_ocu::{BackgroundSource, ConsoleOptions, MapOptions, Placement};
use serde_json::{json, Value};

const FIELD_PNG: &[u8] = include_bytes!("fixtures/field.png");

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jaus-ocu-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A tile directory (`DIR/tiles`) with a secret beside it and every way out of it that
/// a file system allows: a link to the secret, a linked directory outside, a directory
/// named like a tile, an oversized tile; and a link that stays inside.
fn tile_dir() -> (PathBuf, PathBuf) {
    let base = scratch("tiles");
    let root = base.join("tiles");
    let outside = base.join("outside");
    std::fs::create_dir_all(root.join("3/2")).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    std::fs::write(root.join("3/2/5.png"), FIELD_PNG).unwrap();
    std::fs::write(base.join("secret.png"), b"SECRET: not a tile").unwrap();
    std::fs::write(outside.join("1.png"), b"SECRET: not a tile either").unwrap();
    std::os::unix::fs::symlink(base.join("secret.png"), root.join("3/2/6.png")).unwrap();
    std::os::unix::fs::symlink(root.join("3/2/5.png"), root.join("3/2/7.png")).unwrap();
    std::os::unix::fs::symlink(&outside, root.join("3/4")).unwrap();
    std::fs::create_dir_all(root.join("3/2/0.png")).unwrap();
    let big = std::fs::File::create(root.join("3/2/1.png")).unwrap();
    big.set_len(TILE_MAX + 1).unwrap();
    (base, root)
}

fn options(map: MapOptions) -> ConsoleOptions {
    ConsoleOptions {
        http: SocketAddr::from(([127, 0, 0, 1], 0)),
        map,
        ..ConsoleOptions::default()
    }
}

fn keyed(c: &Console, path: &str) -> Answer {
    let host = c.bound.http.to_string();
    request(
        c.bound.http,
        "GET",
        path,
        &[("Host", &host), ("X-Jaus-Key", &c.bound.key)],
        "",
    )
}

fn refused(c: &Console) -> u64 {
    let a = keyed(c, "/api/stats");
    serde_json::from_str::<Value>(&a.body).unwrap()["refused"]
        .as_u64()
        .unwrap()
}

#[test]
fn the_layers_are_served_only_to_the_page_and_only_from_their_files() {
    let (base, root) = tile_dir();
    let c = console(options(MapOptions {
        background: Some(BackgroundSource {
            image: fixture("field.png"),
            placement: Placement::Bounds([-24.0, -16.0, 24.0, 16.0]),
        }),
        tiles: Some(root.clone()),
    }));
    let (host, to) = (c.bound.http.to_string(), c.bound.http);
    let origin = format!("http://{host}");
    let cookie = format!("jaus_ocu_{}={}", to.port(), c.bound.key);

    // What the page is told.
    let layers: Value = serde_json::from_str(&keyed(&c, "/api/map").body).unwrap();
    assert_eq!(layers["background"]["width"], json!(96), "{layers}");
    assert_eq!(layers["background"]["height"], json!(64));
    assert_eq!(
        layers["background"]["extent"],
        json!([-24.0, -16.0, 24.0, 16.0])
    );
    assert_eq!(
        layers["background"]["matrix"],
        json!([0.5, -0.0, 0.0, 0.5, -24.0, -16.0])
    );
    assert_eq!(
        layers["tiles"],
        json!({"url": "/map/tiles/{z}/{x}/{y}.png", "zooms": [3]})
    );

    // The page's own requests (the cookie; an image request carries no Origin, a fetch
    // may carry the page's).
    let bg = request(
        to,
        "GET",
        "/map/background",
        &[("Host", &host), ("Cookie", &cookie)],
        "",
    );
    assert_eq!(bg.status, 200, "{bg:?}");
    assert_eq!(bg.header("content-type"), Some("image/png"));
    assert_eq!(bg.bytes, FIELD_PNG);
    for path in ["/map/tiles/3/2/5.png", "/map/tiles/3/2/7.png"] {
        let t = request(
            to,
            "GET",
            path,
            &[("Host", &host), ("Cookie", &cookie), ("Origin", &origin)],
            "",
        );
        assert_eq!(t.status, 200, "{path}: {t:?}");
        assert_eq!(t.header("content-type"), Some("image/png"), "{path}");
        assert_eq!(t.bytes, FIELD_PNG, "{path}");
    }

    // The guard, on every new route.
    let before = refused(&c);
    let mut n = 0;
    for path in ["/api/map", "/map/background", "/map/tiles/3/2/5.png"] {
        let cases: [(&[(&str, &str)], u16); 4] = [
            (&[("Host", &host)], 401),
            (&[("Host", &host), ("X-Jaus-Key", "0123456789abcdef")], 401),
            (
                &[("Host", "rebind.evil.example:80"), ("Cookie", &cookie)],
                403,
            ),
            (
                &[
                    ("Host", &host),
                    ("Cookie", &cookie),
                    ("Origin", "http://evil.example"),
                ],
                403,
            ),
        ];
        for (headers, status) in cases {
            let a = request(to, "GET", path, headers, "");
            assert_eq!(a.status, status, "{path} {headers:?}: {a:?}");
            assert!(a.body.starts_with("refused: "), "{path}: {}", a.body);
            assert!(!a.bytes.starts_with(b"\x89PNG"), "{path}: an image leaked");
            n += 1;
        }
    }
    assert_eq!(refused(&c), before + n, "refusals counted");

    // Addresses that are not three integers in range: 400, nothing read.
    for path in [
        "/map/tiles/../../secret.png",
        "/map/tiles/3/2/..%2F..%2F..%2Fsecret.png",
        "/map/tiles/3/..%2F..%2F..%2Fsecret/x.png",
        "/map/tiles/%2Fetc/passwd/0.png",
        "/map/tiles/3/2/5.png%00.png",
        "/map/tiles/3/2/-1.png",
        "/map/tiles/3/2/+5.png",
        "/map/tiles/3/02/5.png",
        "/map/tiles/3/8/5.png",
        "/map/tiles/3/2/8.png",
        "/map/tiles/31/0/0.png",
        "/map/tiles/3/2/5.jpg",
        "/map/tiles/3/2/5",
        "/map/tiles/3/2/5.png.png",
        "/map/tiles/x/y/z.png",
    ] {
        let a = keyed(&c, path);
        assert_eq!(a.status, 400, "{path}: {a:?}");
        assert!(!a.body.contains("SECRET"), "{path}");
    }
    // Well-formed addresses whose file is missing, a link out of the directory, a
    // directory, or too large: 404, nothing read.
    for path in [
        "/map/tiles/3/2/4.png",
        "/map/tiles/3/2/6.png",
        "/map/tiles/3/4/1.png",
        "/map/tiles/3/2/0.png",
        "/map/tiles/3/2/1.png",
        "/map/tiles/2/0/0.png",
    ] {
        let a = keyed(&c, path);
        assert_eq!(a.status, 404, "{path}: {a:?}");
        assert!(!a.body.contains("SECRET"), "{path}: {}", a.body);
    }
    // An absolute path, a fourth segment, another name: nothing either.
    for path in [
        "/map/tiles//etc/passwd",
        "/map/tiles/3/2/5/6.png",
        "/map/x.png",
    ] {
        let a = keyed(&c, path);
        assert!(matches!(a.status, 400 | 404), "{path}: {a:?}");
        assert!(!a.body.contains("SECRET") && !a.body.contains("root:"));
    }
    drop(c);
    let _ = std::fs::remove_dir_all(base);
}

#[test]
fn without_layers_the_routes_answer_404_and_the_page_is_told_none() {
    let c = console(options(MapOptions::default()));
    let layers: Value = serde_json::from_str(&keyed(&c, "/api/map").body).unwrap();
    assert_eq!(layers, json!({"background": null, "tiles": null}));
    assert_eq!(keyed(&c, "/map/background").status, 404);
    assert_eq!(keyed(&c, "/map/tiles/0/0/0.png").status, 404);
}

#[test]
fn a_world_file_beside_the_image_places_it() {
    let source = BackgroundSource::new(fixture("field.png"), None).unwrap();
    assert_eq!(
        source.placement,
        Placement::WorldFile(fixture("field.pgw")),
        "the sidecar"
    );
    let c = console(options(MapOptions {
        background: Some(source),
        tiles: None,
    }));
    let layers: Value = serde_json::from_str(&keyed(&c, "/api/map").body).unwrap();
    assert_eq!(
        layers["background"]["extent"],
        json!([-24.0, -16.0, 24.0, 16.0])
    );
}

#[test]
fn mistakes_in_the_files_stop_the_console_naming_the_file() {
    let dir = scratch("bad");
    let not_png = dir.join("map.png");
    std::fs::write(&not_png, b"<html>not an image</html>").unwrap();
    let png = dir.join("field.png");
    std::fs::write(&png, FIELD_PNG).unwrap();
    std::fs::write(dir.join("field.pgw"), "0.5\n0\n0\n-0.5\n-23.75\nnorth\n").unwrap();
    let empty = dir.join("empty");
    std::fs::create_dir_all(empty.join("not-a-zoom")).unwrap();
    let bounds = |image: &Path| {
        Some(BackgroundSource {
            image: image.to_path_buf(),
            placement: Placement::Bounds([0.0, 0.0, 10.0, 10.0]),
        })
    };
    let cases = [
        (
            MapOptions {
                background: bounds(&dir.join("missing.png")),
                tiles: None,
            },
            format!("background image {}", dir.join("missing.png").display()),
        ),
        (
            MapOptions {
                background: bounds(&not_png),
                tiles: None,
            },
            "not a PNG or JPEG".into(),
        ),
        (
            MapOptions {
                background: Some(BackgroundSource::new(png.clone(), None).unwrap()),
                tiles: None,
            },
            format!(
                "{}:6: `north` is not a number",
                dir.join("field.pgw").display()
            ),
        ),
        (
            MapOptions {
                background: None,
                tiles: Some(empty.clone()),
            },
            format!("tile directory {}: no zoom level", empty.display()),
        ),
        (
            MapOptions {
                background: None,
                tiles: Some(dir.join("nowhere")),
            },
            format!("tile directory {}", dir.join("nowhere").display()),
        ),
    ];
    for (map, expected) in cases {
        let stop = AtomicBool::new(true);
        let e = jaus_ocu::run(&options(map), &stop, |_| {}).unwrap_err();
        assert!(
            e.to_string().contains(&expected),
            "{e} (expected {expected})"
        );
    }
    let e = BackgroundSource::new(not_png, None).unwrap_err();
    assert!(e.to_string().contains("no world file"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}
