//! The local web server: the page (embedded in the binary), the full view with trails
//! (`GET /api/view`), commands (`POST /api/command`, one page message as the body), the
//! server's counters (`GET /api/stats`) and a WebSocket (`/ws`) that pushes the view and
//! the new log entries as they are published and takes the page's commands. Every route
//! but the static files passes the [`Guard`]; `GET /?key=KEY` (the address printed at
//! start-up) sets the key's cookie and sends the browser on to `/`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message as WsMessage, WebSocket, WebSocketUpgrade};
use axum::extract::{RawQuery, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::serve::ListenerExt;
use axum::Router;

use crate::guard::{Access, Guard, Refusal};
use crate::shared::Shared;

/// What every route sees.
#[derive(Debug, Clone)]
struct App {
    shared: Arc<Shared>,
    guard: Arc<Guard>,
}

/// Log entries sent in one push at most.
const LOG_PUSH_MAX: usize = 200;

const INDEX: &str = include_str!("../assets/index.html");
const APP: &str = include_str!("../assets/app.js");
const STYLE: &str = include_str!("../assets/style.css");

/// The page's routes over `shared`, behind `guard`.
pub fn router(shared: Arc<Shared>, guard: Arc<Guard>) -> Router {
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
        .with_state(App { shared, guard })
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

/// Serves the page on `listener` behind `guard` until `stop` is set.
pub fn serve(
    listener: std::net::TcpListener,
    shared: Arc<Shared>,
    guard: Arc<Guard>,
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
                router(shared, guard),
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
