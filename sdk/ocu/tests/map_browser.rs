//! The console's map in a real headless browser (as `browser.rs`): with a background
//! image placed by its world file and a local tile directory around the demo's origin,
//! the page draws the image where the world file puts it (on top of everything under the
//! vehicles at a point clear of them) and the tiles where their latitude and longitude
//! put them through the console's origin; the automatic view keeps the whole trail in
//! view while the vehicle drives; a real mouse wheel zooms about the cursor and a drag
//! pans (without adding a waypoint), after which the view stays put while the vehicle
//! moves; the scale bar matches the map's scale at every zoom; Fit returns to the
//! automatic view. A screenshot is saved as `target/ocu/map.png`.
//!
//! Without `chromedriver` the test is skipped with a message, unless
//! `JAUS_REQUIRE_BROWSER` is set.

mod common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use common::browser::{get, js, vehicle_xy, wait_for, Browser, Rig};
use common::request;
use fantoccini::actions::{
    InputSource, MouseActions, PointerAction, WheelAction, WheelActions, MOUSE_BUTTON_LEFT,
};
use fantoccini::Client;
use jaus::stock::geo::LocalFrame;
use jaus_ocu::{BackgroundSource, ConsoleOptions, MapOptions};
use serde_json::{json, Value};

const ZOOM: u32 = 18;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// The tile (x, y) holding (`lat`, `lon`) at `zoom` (Web Mercator).
fn tile_of(lat: f64, lon: f64, zoom: u32) -> (u32, u32) {
    let n = f64::from(1u32 << zoom);
    let r = lat.to_radians();
    let x = ((lon + 180.0) / 360.0 * n).floor();
    let y = ((1.0 - (r.tan() + 1.0 / r.cos()).ln() / std::f64::consts::PI) / 2.0 * n).floor();
    (x as u32, y as u32)
}

/// The latitude of a tile row's north edge.
fn row_lat(y: u32, zoom: u32) -> f64 {
    let n = f64::from(1u32 << zoom);
    (std::f64::consts::PI * (1.0 - 2.0 * f64::from(y) / n))
        .sinh()
        .atan()
        .to_degrees()
}

/// 5 × 5 tiles round the demo's origin (the fixture image each).
fn tiles() -> PathBuf {
    let root = std::env::temp_dir().join(format!("jaus-ocu-map-tiles-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let (lat, lon, _) = jaus_sim::demo::ORIGIN;
    let (cx, cy) = tile_of(lat, lon, ZOOM);
    for x in cx - 2..=cx + 2 {
        let dir = root.join(format!("{ZOOM}/{x}"));
        std::fs::create_dir_all(&dir).unwrap();
        for y in cy - 2..=cy + 2 {
            std::fs::copy(fixture("field.png"), dir.join(format!("{y}.png"))).unwrap();
        }
    }
    root
}

fn command(rig: &Rig, body: &str) {
    let host = rig.bound.http.to_string();
    let a = request(
        rig.bound.http,
        "POST",
        "/api/command",
        &[
            ("Host", &host),
            ("X-Jaus-Key", &rig.bound.key),
            ("Content-Type", "application/json"),
        ],
        body,
    );
    assert_eq!(a.status, 202, "{body}: {a:?}");
}

/// The map's viewBox, as the page last drew it.
async fn view_box(c: &Client) -> Vec<f64> {
    js(
        c,
        "return document.getElementById('map').getAttribute('viewBox');",
    )
    .await
    .as_str()
    .unwrap()
    .split(' ')
    .map(|v| v.parse().unwrap())
    .collect()
}

/// The scale bar's metres, its length on the screen, and the map's pixels per metre.
async fn scale(c: &Client) -> (f64, f64, f64) {
    let v = js(
        c,
        "const b = document.getElementById('scale-bar'); const r = b.getBoundingClientRect(); \
         const a = ocu.worldToClient(0, 0), e = ocu.worldToClient(100, 0); \
         return [Number(b.dataset.metres), r.width, (e.x - a.x) / 100, document.getElementById('scale-text').textContent];",
    )
    .await;
    let (m, px, ppm) = (
        v[0].as_f64().unwrap(),
        v[1].as_f64().unwrap(),
        v[2].as_f64().unwrap(),
    );
    let text = v[3].as_str().unwrap();
    let shown: f64 = if let Some(km) = text.strip_suffix(" km") {
        km.parse::<f64>().unwrap() * 1000.0
    } else {
        text.strip_suffix(" m").unwrap().parse().unwrap()
    };
    assert_eq!(shown, m, "the scale bar says {text}");
    // The bar's line (its ticks' stroke adds a pixel or two).
    assert!(
        (px - m * ppm).abs() < 3.0,
        "the scale bar: {m} m drawn {px:.1} px, but the map has {ppm:.3} px/m"
    );
    (m, px, ppm)
}

/// Trail points drawn outside the map (none, in the automatic view), and the trail's
/// length.
async fn trail_outside(c: &Client) -> (u64, u64) {
    let v = js(
        c,
        "const r = document.getElementById('map').getBoundingClientRect(); \
         const t = ocu.trails.get(1) || []; \
         const out = t.filter(p => { const q = ocu.worldToClient(p[0], p[1]); \
           return q.x < r.left - 1 || q.x > r.right + 1 || q.y < r.top - 1 || q.y > r.bottom + 1; }); \
         return [t.length, out.length];",
    )
    .await;
    (v[0].as_u64().unwrap(), v[1].as_u64().unwrap())
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_map_draws_its_background_and_keeps_or_leaves_the_view() {
    let Some(browser) = Browser::start().await else {
        return;
    };
    let c = browser.client.clone();
    let tile_root = tiles();
    let rig = Rig::start(ConsoleOptions {
        map: MapOptions {
            // Placed by the world file beside it: 48 m × 32 m round the origin.
            background: Some(BackgroundSource::new(fixture("field.png"), None).unwrap()),
            tiles: Some(tile_root.clone()),
        },
        ..ConsoleOptions::default()
    });
    c.goto(&rig.bound.url()).await.expect("the page");
    wait_for("the vehicle", Duration::from_secs(20), async || {
        vehicle_xy(&c).await
    })
    .await;

    // The image, where its world file puts it, and drawn (topmost at a point clear of
    // the vehicle, its trail and the grid).
    wait_for(
        "the background loaded",
        Duration::from_secs(10),
        async || {
            (js(&c, "return ocu.layers.backgroundLoaded === true;").await == json!(true))
                .then_some(())
        },
    )
    .await;
    let placed = js(
        &c,
        "const r = document.getElementById('bg-image').getBoundingClientRect(); \
         const nw = ocu.worldToClient(-24, 16), se = ocu.worldToClient(24, -16); \
         const p = ocu.worldToClient(-13.3, 8.7); \
         const top = document.elementFromPoint(p.x, p.y); \
         return [r.left - nw.x, r.top - nw.y, r.right - se.x, r.bottom - se.y, top && top.id];",
    )
    .await;
    for i in 0..4 {
        assert!(placed[i].as_f64().unwrap().abs() < 1.5, "{placed}");
    }
    assert_eq!(placed[4], json!("bg-image"), "{placed}");

    // A tile where its latitude and longitude put it through the console's origin.
    // (The view with trails is refreshed once a second: the first may predate the origin.)
    let (lat0, lon0) = wait_for("the origin", Duration::from_secs(10), async || {
        let view = get(&rig.bound, "/api/view");
        Some((view["origin"][0].as_f64()?, view["origin"][1].as_f64()?))
    })
    .await;
    let (tx, ty) = tile_of(lat0, lon0, ZOOM);
    let id = format!("tile-{ZOOM}-{tx}-{ty}");
    let tile = wait_for("the origin's tile", Duration::from_secs(10), async || {
        let t = js(
            &c,
            &format!(
                "const t = document.getElementById('{id}'); \
                 return t && t.classList.contains('loaded') ? ['x', 'y', 'width', 'height'].map(a => Number(t.getAttribute(a))) : null;"
            ),
        )
        .await;
        t.as_array().map(|a| a.iter().map(|v| v.as_f64().unwrap()).collect::<Vec<_>>())
    })
    .await;
    let frame = LocalFrame::new(lat0, lon0, 0.0);
    let n = f64::from(1u32 << ZOOM);
    let west = frame.to_local(lat0, f64::from(tx) / n * 360.0 - 180.0).y;
    let east = frame
        .to_local(lat0, f64::from(tx + 1) / n * 360.0 - 180.0)
        .y;
    let north = frame.to_local(row_lat(ty, ZOOM), lon0).x;
    let south = frame.to_local(row_lat(ty + 1, ZOOM), lon0).x;
    let expected = [west, -north, east - west, north - south];
    for (got, want) in tile.iter().zip(expected) {
        assert!(
            (got - want).abs() < 0.01,
            "tile {id}: {tile:?}, expected {expected:?}"
        );
    }
    assert!(
        west < 0.0 && east > 0.0 && south < 0.0 && north > 0.0,
        "{expected:?}"
    );

    // Driving: the automatic view keeps the whole trail in view.
    command(&rig, r#"{"op":"take","target":"1.1.45.1","authority":5}"#);
    wait_for("control", Duration::from_secs(10), async || {
        (js(
            &c,
            "return document.getElementById('driver-control').textContent;",
        )
        .await
            == json!("held"))
        .then_some(())
    })
    .await;
    command(
        &rig,
        r#"{"op":"waypoints","driver":"1.1.45.1","speed":2,"points":[{"x":14,"y":-8},{"x":22,"y":12},{"x":2,"y":-4}]}"#,
    );
    wait_for("the vehicle moving", Duration::from_secs(20), async || {
        vehicle_xy(&c)
            .await
            .filter(|(x, y)| x.hypot(*y) > 4.0)
            .map(|_| ())
    })
    .await;
    let (points, outside) = trail_outside(&c).await;
    assert_eq!(outside, 0, "trail points off the map ({points} points)");
    let (m0, _, ppm0) = scale(&c).await;

    // A real wheel zooms in about the cursor; the view is then the operator's.
    let rect = js(
        &c,
        "const r = document.getElementById('map').getBoundingClientRect(); return [r.left, r.top, r.width, r.height];",
    )
    .await;
    let (cx, cy) = (
        rect[0].as_f64().unwrap() + rect[2].as_f64().unwrap() * 0.3,
        rect[1].as_f64().unwrap() + rect[3].as_f64().unwrap() * 0.6,
    );
    let under = |c: Client| async move {
        let w = js(
            &c,
            &format!(
                "const m = document.getElementById('map'); const p = m.createSVGPoint(); p.x = {cx}; p.y = {cy}; \
                 const q = p.matrixTransform(m.getScreenCTM().inverse()); return [q.x, -q.y];"
            ),
        )
        .await;
        (w[0].as_f64().unwrap(), w[1].as_f64().unwrap())
    };
    let before = under(c.clone()).await;
    let mut wheel = WheelActions::new("wheel".into());
    wheel.push(WheelAction::Scroll {
        duration: None,
        x: cx.round() as i64,
        y: cy.round() as i64,
        delta_x: 0,
        delta_y: -500,
    });
    c.perform_actions(wheel).await.expect("the wheel");
    let after = under(c.clone()).await;
    let (m1, _, ppm1) = scale(&c).await;
    assert!(ppm1 > ppm0 * 1.5, "zoomed in: {ppm0:.2} -> {ppm1:.2} px/m");
    assert!(m1 < m0, "the scale bar follows the zoom: {m0} m -> {m1} m");
    // The point under the cursor stays there (within a pixel's worth of metres).
    assert!(
        (after.0 - before.0).hypot(after.1 - before.1) < 1.5 / ppm1,
        "{before:?} -> {after:?}"
    );
    assert_eq!(
        js(
            &c,
            "return document.getElementById('view-mode').textContent;"
        )
        .await,
        json!("your view (Fit: automatic)")
    );

    // A drag pans by as much as the pointer moved, and adds no waypoint.
    let vb = view_box(&c).await;
    let drag = MouseActions::new("mouse".into())
        .then(PointerAction::MoveTo {
            duration: None,
            x: cx.round(),
            y: cy.round(),
        })
        .then(PointerAction::Down {
            button: MOUSE_BUTTON_LEFT,
        })
        .then(PointerAction::MoveTo {
            duration: Some(Duration::from_millis(200)),
            x: cx.round() + 120.0,
            y: cy.round() + 60.0,
        })
        .then(PointerAction::Up {
            button: MOUSE_BUTTON_LEFT,
        });
    c.perform_actions(drag).await.expect("the drag");
    let panned = view_box(&c).await;
    assert!(
        (vb[0] - panned[0] - 120.0 / ppm1).abs() < 2.0 / ppm1
            && (vb[1] - panned[1] - 60.0 / ppm1).abs() < 2.0 / ppm1,
        "dragged 120, 60 px at {ppm1:.2} px/m: {vb:?} -> {panned:?}"
    );
    assert_eq!(
        js(&c, "return ocu.draft.length;").await,
        json!(0),
        "a drag is no click"
    );
    // While the vehicle drives on and views keep coming, the view stays put.
    let frames = js(&c, "return ocu.stats.frames;").await.as_u64().unwrap();
    let moved_from = vehicle_xy(&c).await.unwrap();
    tokio::time::sleep(Duration::from_millis(1500)).await;
    let moved_to = vehicle_xy(&c).await.unwrap();
    assert!(
        js(&c, "return ocu.stats.frames;").await.as_u64().unwrap() > frames + 5
            && (moved_to.0 - moved_from.0).hypot(moved_to.1 - moved_from.1) > 0.5,
        "the vehicle should still be driving: {moved_from:?} -> {moved_to:?}"
    );
    assert_eq!(
        view_box(&c).await,
        panned,
        "the operator's view moved by itself"
    );

    // Fit: the automatic view again, the whole trail in it, the scale bar right.
    c.find(fantoccini::Locator::Id("fit"))
        .await
        .unwrap()
        .click()
        .await
        .unwrap();
    assert_eq!(
        js(
            &c,
            "return document.getElementById('view-mode').textContent;"
        )
        .await,
        json!("automatic view")
    );
    let (points, outside) = trail_outside(&c).await;
    assert!(points > 20, "a trail: {points} points");
    assert_eq!(outside, 0, "after Fit, trail points off the map");
    scale(&c).await;

    let png = c.screenshot().await.expect("a screenshot");
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/ocu");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("map.png"), &png).unwrap();
    let tiles_drawn: Value = js(
        &c,
        "return document.querySelectorAll('#tiles image.loaded').length;",
    )
    .await;
    eprintln!(
        "map browser test: {points} trail points in the automatic view; {tiles_drawn} tiles drawn; scale {m0} m -> {m1} m after the wheel; screenshot {}",
        dir.join("map.png").display()
    );
    let _ = c.close().await;
    rig.finish();
    let _ = std::fs::remove_dir_all(tile_root);
}
