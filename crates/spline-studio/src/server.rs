//! The HTTP side: axum routes for the page, its assets and the endpoints of [`crate::api`].

use crate::api::{self, ApiError};
use axum::Router;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{DefaultBodyLimit, Path};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use std::net::SocketAddr;

/// The largest request body accepted, in bytes (a 100,000-point file fits; a larger one is
/// refused with status 413 before it is read whole).
pub const MAX_BODY: usize = 8 << 20;

const PAGE: &str = include_str!("../assets/index.html");
const SCRIPT: &str = include_str!("../assets/studio.js");
const STYLE: &str = include_str!("../assets/studio.css");

fn asset(content_type: &'static str, text: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, content_type),
            (header::CACHE_CONTROL, "no-store"),
        ],
        text,
    )
        .into_response()
}

fn json_response(status: u16, body: String) -> Response {
    let status = StatusCode::from_u16(status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    (
        status,
        [(header::CONTENT_TYPE, "application/json; charset=utf-8")],
        body,
    )
        .into_response()
}

fn error_response(error: &ApiError) -> Response {
    json_response(error.status, error.body())
}

async fn endpoint(Path(name): Path<String>, body: Result<Bytes, BytesRejection>) -> Response {
    let body = match body {
        Ok(body) => body,
        Err(rejection) => {
            return error_response(&ApiError {
                status: rejection.status().as_u16(),
                message: format!("request body refused: {rejection} (at most {MAX_BODY} bytes)"),
            });
        }
    };
    // The computation runs on the blocking pool, so that a long one (the eraser) does not
    // hold up the other tabs; a panic there becomes a JSON error, not a dropped connection.
    match tokio::task::spawn_blocking(move || api::handle(&name, &body)).await {
        Ok(Ok(value)) => json_response(200, value.to_string()),
        Ok(Err(error)) => error_response(&error),
        Err(join) => error_response(&ApiError {
            status: 500,
            message: format!("internal error: {join}"),
        }),
    }
}

async fn not_found() -> Response {
    error_response(&ApiError {
        status: 404,
        message: "not found: the page is GET /, the endpoints POST /api/<name>".into(),
    })
}

async fn method_not_allowed() -> Response {
    error_response(&ApiError {
        status: 405,
        message: "the endpoints take POST with a JSON body".into(),
    })
}

/// The routes: `GET /` (the page), `GET /studio.js`, `GET /studio.css`, `POST /api/<name>`.
pub fn router() -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", PAGE) }),
        )
        .route(
            "/studio.js",
            get(|| async { asset("text/javascript; charset=utf-8", SCRIPT) }),
        )
        .route(
            "/studio.css",
            get(|| async { asset("text/css; charset=utf-8", STYLE) }),
        )
        .route("/api/{name}", post(endpoint).fallback(method_not_allowed))
        .fallback(not_found)
        .layer(DefaultBodyLimit::max(MAX_BODY))
}

/// Binds `host:port` (port 0: any free port), calls `ready` with the address bound, then
/// serves until the process ends. One I/O thread; the computations run on tokio's blocking
/// pool.
///
/// # Errors
/// The I/O error of building the runtime, binding or serving.
pub fn run(host: &str, port: u16, ready: impl FnOnce(SocketAddr)) -> std::io::Result<()> {
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .build()?;
    runtime.block_on(async {
        let listener = tokio::net::TcpListener::bind((host, port)).await?;
        ready(listener.local_addr()?);
        axum::serve(listener, router()).await
    })
}
