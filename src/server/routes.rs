//! The HTTP surface of a live session: the router and its handlers.
//!
//! ```text
//! GET  /                      the viewer page
//! GET  /static/<file>         its script, style and three.js bundle (embedded)
//! GET  /model.glb             the current model (header x-vesselcad-revision)
//! GET  /design.json           the current design, canonical JSON (mm)
//! POST /edit                  a JSON Patch (RFC 6902) → {"revision", "changed", ...}
//! POST /save                  write the design file (again, if it was deleted),
//!                              start a fresh journal
//! GET  /drawing.svg?vessel=T  the vessel's drawing sheet
//! GET  /ws                    the viewer stream (see `broadcast`)
//! ```
//!
//! Every request first passes [`guard`] (loopback `Host` names, same-origin
//! `Origin`, JSON content types, and with `--token` the token on every route but
//! the page shell; security headers on every answer). Request bodies are limited to [`MAX_BODY`] bytes. Every refusal
//! is an [`ApiError`] with a 4xx status and a JSON body; the session is unchanged.
//! Session work (model updates, GLB writing) runs on blocking threads, one edit at
//! a time under the session lock; updates are published inside that lock so
//! viewers get them in revision order.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use axum::Router;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::ws::WebSocketUpgrade;
use axum::extract::{DefaultBodyLimit, Path, Query, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, Uri, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use serde::Deserialize;
use serde_json::json;
use tokio::sync::watch;

use super::assets::{self, Asset};
use super::broadcast::{Hub, MAX_VIEWER_MESSAGE, Update, run_viewer};
use super::error::ApiError;
use super::guard::guard;
use super::session::Session;
use crate::drawing::{SheetOptions, sheet_svg};

/// Largest request body (an edit), bytes: 1 MiB.
pub const MAX_BODY: usize = 1 << 20;

/// What every handler shares.
#[derive(Clone)]
pub struct AppState {
    /// The session, one request at a time.
    pub session: Arc<Mutex<Session>>,
    /// Viewers' updates.
    pub hub: Hub,
    /// The token every route but the page shell needs, if any.
    pub token: Option<String>,
    /// Whether only loopback `Host` names are answered (the server is bound to
    /// a loopback address).
    pub loopback_only: bool,
    /// Turns true when the server shuts down (viewers close).
    pub shutdown: watch::Receiver<bool>,
    /// How long a viewer's socket may accept nothing before it is dropped.
    pub viewer_timeout: Duration,
    /// How often viewers are pinged (so a quiet viewer is not idle).
    pub viewer_ping: Duration,
}

impl AppState {
    /// Runs `work` on the locked session on a blocking thread.
    async fn with_session<T, F>(&self, work: F) -> T
    where
        T: Send + 'static,
        F: FnOnce(&mut Session, &Hub) -> T + Send + 'static,
    {
        let session = self.session.clone();
        let hub = self.hub.clone();
        let joined = tokio::task::spawn_blocking(move || work(&mut lock(&session), &hub)).await;
        match joined {
            Ok(value) => value,
            // The closure panicked: that is a bug, and the panic carries on here.
            Err(e) => std::panic::resume_unwind(e.into_panic()),
        }
    }

    /// Refuses a request without the right token (in the `Authorization`
    /// header, or `from_query`).
    pub(super) fn authorize(
        &self,
        headers: &HeaderMap,
        from_query: Option<&str>,
    ) -> Result<(), ApiError> {
        let Some(token) = &self.token else {
            return Ok(());
        };
        let given = headers
            .get(header::AUTHORIZATION)
            .and_then(|v| v.to_str().ok())
            .and_then(|v| v.strip_prefix("Bearer "))
            .or(from_query);
        match given {
            Some(g) if constant_time_eq(g.as_bytes(), token.as_bytes()) => Ok(()),
            _ => Err(ApiError::Unauthorized),
        }
    }
}

/// Locks the session; a poisoned lock (a panic while editing) still holds a
/// consistent session, because edits are staged before anything is written.
fn lock(session: &Mutex<Session>) -> MutexGuard<'_, Session> {
    session.lock().unwrap_or_else(|p| p.into_inner())
}

/// The router of a live session.
pub fn router(state: AppState) -> Router {
    Router::new()
        .route("/", get(index))
        .route("/static/{*file}", get(static_file))
        .route("/model.glb", get(model_glb))
        .route("/design.json", get(design_json))
        .route("/edit", post(edit))
        .route("/save", post(save))
        .route("/drawing.svg", get(drawing_svg))
        .route("/ws", get(viewer_socket))
        .fallback(not_found)
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .layer(axum::middleware::from_fn_with_state(state.clone(), guard))
        .with_state(state)
}

fn asset_response(asset: Asset) -> Response {
    ([(header::CONTENT_TYPE, asset.content_type)], asset.bytes).into_response()
}

async fn index() -> Response {
    asset_response(assets::INDEX)
}

async fn static_file(Path(file): Path<String>) -> Result<Response, ApiError> {
    assets::lookup(&file)
        .map(asset_response)
        .ok_or_else(|| ApiError::NotFound(format!("/static/{file}")))
}

async fn not_found(uri: Uri) -> ApiError {
    ApiError::NotFound(uri.path().to_string())
}

/// The revision header.
fn revision_header(revision: u64) -> (header::HeaderName, HeaderValue) {
    (
        header::HeaderName::from_static("x-vesselcad-revision"),
        HeaderValue::from(revision),
    )
}

async fn model_glb(State(state): State<AppState>) -> Response {
    let snapshot = state.with_session(|s, _| s.snapshot()).await;
    (
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("model/gltf-binary"),
            ),
            revision_header(snapshot.revision),
        ],
        snapshot.glb,
    )
        .into_response()
}

async fn design_json(State(state): State<AppState>) -> Response {
    let (revision, text) = state
        .with_session(|s, _| (s.revision(), s.design_text()))
        .await;
    (
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            ),
            revision_header(revision),
        ],
        text,
    )
        .into_response()
}

/// The body, or the error for one over the limit.
fn body_or_error(body: Result<Bytes, BytesRejection>) -> Result<Bytes, ApiError> {
    body.map_err(|e| {
        if e.status() == StatusCode::PAYLOAD_TOO_LARGE {
            ApiError::TooLarge { limit: MAX_BODY }
        } else {
            ApiError::Malformed(e.body_text())
        }
    })
}

async fn edit(
    State(state): State<AppState>,
    body: Result<Bytes, BytesRejection>,
) -> Result<Response, ApiError> {
    let body = body_or_error(body)?;
    let answer = state
        .with_session(move |session, hub| {
            let accepted = session.apply_patch(&body)?;
            hub.publish(Update::of(&accepted));
            Ok::<_, ApiError>(accepted.to_json("accepted"))
        })
        .await?;
    Ok(axum::Json(answer).into_response())
}

async fn save(State(state): State<AppState>) -> Result<Response, ApiError> {
    let (saved, path) = state
        .with_session(|s, _| Ok::<_, ApiError>((s.save()?, s.path().display().to_string())))
        .await?;
    let mut answer = json!({
        "saved": path, "revision": saved.revision, "written": saved.written,
        "recreated": saved.recreated,
    });
    if saved.recreated {
        answer["message"] = json!(format!(
            "{path} had been deleted while serving; it was written again"
        ));
    }
    Ok(axum::Json(answer).into_response())
}

/// The `vessel` query parameter.
#[derive(Deserialize)]
struct DrawingQuery {
    vessel: Option<String>,
}

/// `GET /drawing.svg?vessel=TAG`: the vessel's drawing sheet (ANSI D, hidden lines
/// dashed) from the current model, as SVG.
async fn drawing_svg(
    State(state): State<AppState>,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let Ok(Query(DrawingQuery { vessel: Some(tag) })) = query else {
        return Err(ApiError::BadQuery(
            "expected /drawing.svg?vessel=<tag>".into(),
        ));
    };
    let known = state.with_session(|s, _| s.vessel_tags()).await;
    if !known.contains(&tag) {
        return Err(ApiError::UnknownVessel { tag, known });
    }
    let svg = state
        .with_session(move |s, _| {
            sheet_svg(s.model(), &tag, &SheetOptions::default())
                .map_err(|e| ApiError::Drawing(e.to_string()))
        })
        .await?;
    Ok((
        [(
            header::CONTENT_TYPE,
            HeaderValue::from_static("image/svg+xml"),
        )],
        svg,
    )
        .into_response())
}

async fn viewer_socket(State(state): State<AppState>, ws: WebSocketUpgrade) -> Response {
    ws.max_message_size(MAX_VIEWER_MESSAGE)
        .on_upgrade(move |socket| async move {
            let queue = state.hub.subscribe();
            let shutdown = state.shutdown.clone();
            let snapshot = || {
                let state = state.clone();
                async move { Some(state.with_session(|s, _| s.snapshot()).await) }
            };
            let timeout = state.viewer_timeout;
            let ping = state.viewer_ping;
            run_viewer::<_, _>(socket, queue, snapshot, shutdown, timeout, ping).await;
        })
}

/// Compares two byte strings in time independent of where they differ.
fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}
