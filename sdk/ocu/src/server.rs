//! The local web server: the page (embedded in the binary), the full view with trails
//! (`GET /api/view`), commands (`POST /api/command`, one page message as the body), the
//! server's counters (`GET /api/stats`), a WebSocket (`/ws`) that pushes the view and
//! the new log entries as they are published and takes the page's commands, and the
//! map's optional layers ([`crate::map`]): what they are (`GET /api/map`), the background
//! image (`GET /map/background`) and tiles (`GET /map/tiles/Z/X/Y.png`). Every route but
//! the static files passes the [`Guard`]; `GET /?key=KEY` (the address printed at
//! start-up) sets the key's cookie and sends the browser on to `/`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message as WsMessage, WebSocket, WebSocketUpgrade};
use axum::extract::{Path, RawQuery, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::serve::ListenerExt;
use axum::Router;

use crate::guard::{Access, Guard, Refusal};
use crate::map::{tiles, MapLayers};
use crate::shared::Shared;

/// What every route sees.
#[derive(Debug, Clone)]
struct App {
    shared: Arc<Shared>,
    guard: Arc<Guard>,
    map: Arc<MapLayers>,
}

/// Log entries sent in one push at most.
const LOG_PUSH_MAX: usize = 200;

const INDEX: &str = include_str!("../assets/index.html");
const APP: &str = include_str!("../assets/app.js");
const STYLE: &str = include_str!("../assets/style.css");

/// The page's routes over `shared` and the map's layers `map`, behind `guard`.
pub fn router(shared: Arc<Shared>, guard: Arc<Guard>, map: Arc<MapLayers>) -> Router {
    Router::new()
        .route("/", get(index))
        .route(
            "/app.js",
            get(|State(app): State<App>, h: HeaderMap| async move {
                gate(&app, Access::Asset, &h, "/app.js")
                    .unwrap_or_else(|| asset("text/javascript; charset=utf-8", APP))
            }),
        )
        .route(
            "/style.css",
            get(|State(app): State<App>, h: HeaderMap| async move {
                gate(&app, Access::Asset, &h, "/style.css")
                    .unwrap_or_else(|| asset("text/css; charset=utf-8", STYLE))
            }),
        )
        .route("/api/view", get(view))
        .route("/api/stats", get(stats))
        .route("/api/command", post(command))
        .route("/ws", get(ws))
        .route("/api/map", get(map_layers))
        .route("/map/background", get(background))
        .route("/map/tiles/{z}/{x}/{y}", get(tile))
        .with_state(App { shared, guard, map })
}

/// `None` when the request passes the guard's checks for `access`; else the refusal
/// as a response (logged and counted).
fn gate(app: &App, access: Access, headers: &HeaderMap, route: &str) -> Option<Response> {
    app.guard
        .check(access, headers)
        .err()
        .map(|why| refuse(app, headers, route, &why))
}

fn refuse(app: &App, headers: &HeaderMap, route: &str, why: &Refusal) -> Response {
    app.shared.refused.fetch_add(1, Ordering::Relaxed);
    let text = |h| {
        headers
            .get(h)
            .and_then(|v: &header::HeaderValue| v.to_str().ok())
            .unwrap_or("-")
            .to_string()
    };
    tracing::warn!(
        route,
        host = %text(header::HOST),
        origin = %text(header::ORIGIN),
        status = why.status().as_u16(),
        "console request refused: {why}"
    );
    (
        why.status(),
        [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
        format!("refused: {why}\n"),
    )
        .into_response()
}

/// `/`: with the right `?key=`, the cookie and a redirect to `/` (so the key leaves the
/// address bar); with the cookie, the page; else a refusal that says what to open.
async fn index(State(app): State<App>, RawQuery(query): RawQuery, headers: HeaderMap) -> Response {
    if let Some(r) = gate(&app, Access::Asset, &headers, "/") {
        return r;
    }
    let given = query.as_deref().and_then(|q| {
        q.split('&')
            .filter_map(|p| p.split_once('='))
            .find(|(k, _)| *k == "key")
            .map(|(_, v)| v)
    });
    match given {
        Some(k) if app.guard.is_key(k) => (
            StatusCode::SEE_OTHER,
            [
                (header::SET_COOKIE, app.guard.set_cookie()),
                (header::LOCATION, "/".to_string()),
                (header::CACHE_CONTROL, "no-store".to_string()),
            ],
        )
            .into_response(),
        Some(_) => refuse(&app, &headers, "/", &Refusal::Key),
        None => gate(&app, Access::Read, &headers, "/")
            .unwrap_or_else(|| asset("text/html; charset=utf-8", INDEX)),
    }
}

fn asset(kind: &'static str, body: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, kind),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
        .into_response()
}

async fn view(State(app): State<App>, headers: HeaderMap) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/api/view") {
        return r;
    }
    let json = app.shared.trails();
    (
        [(header::CONTENT_TYPE, "application/json")],
        json.as_str().to_owned(),
    )
        .into_response()
}

async fn stats(State(app): State<App>, headers: HeaderMap) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/api/stats") {
        return r;
    }
    (
        [(header::CONTENT_TYPE, "application/json")],
        app.shared.stats_json(),
    )
        .into_response()
}

async fn command(State(app): State<App>, headers: HeaderMap, body: String) -> Response {
    if let Some(r) = gate(&app, Access::Command, &headers, "/api/command") {
        return r;
    }
    if app.shared.submit(body) {
        StatusCode::ACCEPTED.into_response()
    } else {
        StatusCode::SERVICE_UNAVAILABLE.into_response()
    }
}

async fn ws(State(app): State<App>, headers: HeaderMap, upgrade: WebSocketUpgrade) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/ws") {
        return r;
    }
    let shared = app.shared.clone();
    upgrade.on_upgrade(move |socket| session(socket, shared))
}

/// `/api/map`: the layers the page may draw under the vehicles (JSON; nulls when none).
async fn map_layers(State(app): State<App>, headers: HeaderMap) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/api/map") {
        return r;
    }
    ([(header::CONTENT_TYPE, "application/json")], app.map.json()).into_response()
}

/// `/map/background`: the background image given at start-up (read then), or 404.
async fn background(State(app): State<App>, headers: HeaderMap) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/map/background") {
        return r;
    }
    match &app.map.background {
        Some(b) => (
            [
                (header::CONTENT_TYPE, b.format.mime()),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            axum::body::Bytes::from_owner(b.bytes.clone()),
        )
            .into_response(),
        None => not_found("no background image (jaus ocu --background)"),
    }
}

/// `/map/tiles/Z/X/Y.EXT`: one tile of the tile directory ([`tiles::Tiles::read`]),
/// 400 for an address that is not three integers in range, 404 for anything else.
async fn tile(
    State(app): State<App>,
    headers: HeaderMap,
    Path((z, x, y)): Path<(String, String, String)>,
) -> Response {
    if let Some(r) = gate(&app, Access::Read, &headers, "/map/tiles") {
        return r;
    }
    let Some(tiles) = app.map.tiles.clone() else {
        return not_found("no tile directory (jaus ocu --tiles)");
    };
    let read = tokio::task::spawn_blocking(move || tiles.read(&z, &x, &y)).await;
    match read {
        Ok(Ok((bytes, mime))) => (
            [
                (header::CONTENT_TYPE, mime),
                (header::CACHE_CONTROL, "private, max-age=300"),
            ],
            bytes,
        )
            .into_response(),
        Ok(Err(tiles::Miss::BadAddress)) => (
            StatusCode::BAD_REQUEST,
            [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
            "a tile is /map/tiles/Z/X/Y.EXT: integers in range, the directory's extension\n",
        )
            .into_response(),
        Ok(Err(tiles::Miss::NotFound(why))) => {
            tracing::debug!("tile not served: {why}");
            not_found("no such tile")
        }
        Err(e) => {
            tracing::warn!("tile: {e}");
            StatusCode::INTERNAL_SERVER_ERROR.into_response()
        }
    }
}

fn not_found(what: &'static str) -> Response {
    (
        StatusCode::NOT_FOUND,
        [(header::CONTENT_TYPE, "text/plain; charset=utf-8")],
        what,
    )
        .into_response()
}

/// One page's WebSocket: the full view first, then every published view with the log
/// entries new since the last push; page messages go to the node thread.
async fn session(mut socket: WebSocket, shared: Arc<Shared>) {
    let mut views = shared.view.subscribe();
    let hello = format!("{{\"type\":\"hello\",\"view\":{}}}", shared.trails());
    if socket.send(WsMessage::Text(hello.into())).await.is_err() {
        return;
    }
    let mut log_seen = 0u64;
    loop {
        tokio::select! {
            changed = views.changed() => {
                if changed.is_err() {
                    return;
                }
                let published = views.borrow_and_update().clone();
                let (log, last) = if published.log_seq > log_seen {
                    shared.log_since(log_seen, LOG_PUSH_MAX)
                } else {
                    ("[]".to_string(), log_seen)
                };
                log_seen = last;
                let msg = format!(
                    "{{\"type\":\"view\",\"published_unix_ms\":{},\"view\":{},\"log\":{log}}}",
                    published.unix_ms, published.view
                );
                if socket.send(WsMessage::Text(msg.into())).await.is_err() {
                    return;
                }
            }
            incoming = socket.recv() => {
                match incoming {
                    Some(Ok(WsMessage::Text(text))) => {
                        if !shared.submit(text.as_str().to_owned()) {
                            let busy = r#"{"type":"error","text":"the console is busy: command dropped"}"#;
                            if socket.send(WsMessage::Text(busy.into())).await.is_err() {
                                return;
                            }
                        }
                    }
                    Some(Ok(WsMessage::Close(_))) | None | Some(Err(_)) => return,
                    Some(Ok(_)) => {}
                }
            }
        }
    }
}

/// Serves the page and the map's layers `map` on `listener` behind `guard` until `stop`
/// is set.
pub fn serve(
    listener: std::net::TcpListener,
    shared: Arc<Shared>,
    guard: Arc<Guard>,
    map: Arc<MapLayers>,
    stop: &AtomicBool,
) {
    let runtime = match tokio::runtime::Builder::new_multi_thread()
        .worker_threads(1)
        .thread_name("ocu-http")
        .enable_all()
        .build()
    {
        Ok(r) => r,
        Err(e) => {
            tracing::error!("web server: no runtime: {e}");
            return;
        }
    };
    runtime.block_on(async {
        if let Err(e) = listener.set_nonblocking(true) {
            tracing::error!("web server: {e}");
            return;
        }
        let listener = match tokio::net::TcpListener::from_std(listener) {
            Ok(l) => l,
            Err(e) => {
                tracing::error!("web server: {e}");
                return;
            }
        };
        let stopped = async {
            while !stop.load(Ordering::Relaxed) {
                tokio::time::sleep(Duration::from_millis(100)).await;
            }
        };
        tokio::select! {
            // No Nagle: a view is one small frame, and waiting for the browser's delayed
            // ACK would hold it back by up to 40 ms.
            r = axum::serve(
                listener.tap_io(|tcp| {
                    let _ = tcp.set_nodelay(true);
                }),
                router(shared, guard, map),
            ) => {
                if let Err(e) = r {
                    tracing::error!("web server: {e}");
                }
            }
            () = stopped => {}
        }
    });
    // Open WebSockets end with the runtime.
    runtime.shutdown_background();
}
