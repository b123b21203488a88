//! The local web server: the page (embedded in the binary), the full view with trails
//! (`GET /api/view`), commands (`POST /api/command`, one page message as the body) and a
//! WebSocket (`/ws`) that pushes the view and the new log entries as they are published
//! and takes the page's commands.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Duration;

use axum::extract::ws::{Message as WsMessage, WebSocket, WebSocketUpgrade};
use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::serve::ListenerExt;
use axum::Router;

use crate::shared::Shared;

/// Log entries sent in one push at most.
const LOG_PUSH_MAX: usize = 200;

const INDEX: &str = include_str!("../assets/index.html");
const APP: &str = include_str!("../assets/app.js");
const STYLE: &str = include_str!("../assets/style.css");

/// The page's routes over `shared`.
pub fn router(shared: Arc<Shared>) -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", INDEX) }),
        )
        .route(
            "/app.js",
            get(|| async { asset("text/javascript; charset=utf-8", APP) }),
        )
        .route(
            "/style.css",
            get(|| async { asset("text/css; charset=utf-8", STYLE) }),
        )
        .route("/api/view", get(view))
        .route("/api/command", post(command))
        .route("/ws", get(ws))
        .with_state(shared)
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

async fn view(State(shared): State<Arc<Shared>>) -> Response {
    let json = shared.trails();
    (
        [(header::CONTENT_TYPE, "application/json")],
        json.as_str().to_owned(),
    )
        .into_response()
}

async fn command(State(shared): State<Arc<Shared>>, body: String) -> StatusCode {
    if shared.submit(body) {
        StatusCode::ACCEPTED
    } else {
        StatusCode::SERVICE_UNAVAILABLE
    }
}

async fn ws(State(shared): State<Arc<Shared>>, upgrade: WebSocketUpgrade) -> Response {
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

/// Serves the page on `listener` until `stop` is set.
pub fn serve(listener: std::net::TcpListener, shared: Arc<Shared>, stop: &AtomicBool) {
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
                router(shared),
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
