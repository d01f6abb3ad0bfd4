//! The HTTP surface of a live session: the router and its handlers.
//!
//! ```text
//! GET  /                      the viewer page
//! GET  /static/<file>         its script, style and three.js bundle (embedded)
//! GET  /model.glb             the current model (header x-vesselcad-revision)
//! GET  /vessel.glb?tag=T      one vessel's GLB (ETag; see `progressive`)
//! GET  /design.json           the current design, canonical JSON (mm)
//! POST /edit                  a JSON Patch (RFC 6902) → {"revision", "changed", ...}
//! POST /save                  write the design file (again, if it was deleted),
//!                              start a fresh journal
//! POST /undo, POST /redo      a new revision that undoes / redoes this server's
//!                              last edit (409 when there is none)
//! GET  /revisions             the store's revisions (`serve --store`)
//! GET  /design.json?rev=N     the design at revision N (`serve --store`)
//! GET  /vessel.json?vessel=T  one vessel's design and index {"revision","index","vessel"}
//! GET  /drawing.svg?vessel=T  the vessel's drawing sheet
//! GET  /drawing.dxf?vessel=T  the same sheet as DXF (a download)
//! GET  /calc.json            the calculation's deficiencies by part (`deficiencies`)
//! GET  /traveler.html?vessel=T the vessel's shop traveler (`traveler`), also .csv
//! GET  /plates.json?vessel=T    its plates, boot plates and head blanks; /plates/<file>?vessel=T one's DXF
//! GET  /ws                    the viewer stream (see `viewer`)
//! ```
//!
//! Every request first passes [`guard`] (loopback `Host` names, same-origin
//! `Origin`, JSON content types, and with `--token` the token on every route but
//! the page shell; security headers on every answer). Request bodies are limited to [`MAX_BODY`] bytes. Every refusal
//! is an [`ApiError`] with a 4xx status and a JSON body; the session is unchanged.
//! Session work runs on blocking threads: model updates one edit at a time
//! under the session lock, which reads what a GLB needs (meshes are shared);
//! GLBs are written after the lock is let go. An update takes its place in the
//! viewers' order (a [`Ticket`]) under the lock, so viewers get updates in
//! revision order.

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

use super::assets::{self, Asset};
use super::broadcast::{MAX_VIEWER_MESSAGE, Ticket, VIEWER_READ_BUFFER};
use super::error::ApiError;
use super::guard::guard;
use super::session::{Accepted, SheetFormat};
use super::state::AppState;
use super::viewer::run_viewer;

/// Largest request body (an edit), bytes: 1 MiB.
pub const MAX_BODY: usize = 1 << 20;

/// The router of a live session.
pub fn router(state: AppState) -> Router {
    Router::new()
        .route("/", get(index))
        .route("/static/{*file}", get(static_file))
        .route("/model.glb", get(model_glb))
        .route("/vessel.glb", get(vessel_glb))
        .route("/design.json", get(design_json))
        .route("/edit", post(edit))
        .route("/save", post(save))
        .route("/undo", post(undo))
        .route("/redo", post(redo))
        .route("/revisions", get(revisions))
        .route("/drawing.svg", get(drawing_svg))
        .route("/drawing.dxf", get(drawing_dxf))
        .route("/vessel.json", get(vessel_json))
        .route("/calc.json", get(super::deficiencies::calc_json))
        .route("/traveler.html", get(super::traveler::traveler_page))
        .route("/traveler.csv", get(super::traveler::traveler_table))
        .route("/plates.json", get(super::traveler::plate_list))
        .route("/plates/{file}", get(super::traveler::plate_dxf))
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
    let full = state.with_session(|s, _| s.full_model()).await;
    let snapshot = AppState::unlocked(move || full.snapshot()).await;
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

/// The `rev` query parameter.
#[derive(Deserialize)]
struct RevisionQuery {
    rev: Option<u64>,
}

async fn design_json(
    State(state): State<AppState>,
    query: Result<Query<RevisionQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let Ok(Query(RevisionQuery { rev })) = query else {
        return Err(ApiError::BadQuery(
            "expected /design.json or /design.json?rev=<revision number>".into(),
        ));
    };
    let (revision, text) = state
        .with_session(move |s, _| {
            let revision = rev.unwrap_or(s.revision());
            s.design_text_at(revision).map(|t| (revision, t))
        })
        .await?;
    Ok((
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("application/json"),
            ),
            revision_header(revision),
        ],
        text,
    )
        .into_response())
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
    let staged = state
        .with_session(move |session, hub| match session.apply_unflushed(&body) {
            Ok(accepted) => Ok((accepted, hub.ticket())),
            Err(e @ ApiError::Conflict { .. }) => {
                // Another server was first: take its revision, then refuse.
                let caught = session.catch_up().ok().flatten();
                Err((e, caught.map(|c| Box::new((c, hub.ticket())))))
            }
            Err(e) => Err((e, None)),
        })
        .await;
    match staged {
        Ok((accepted, ticket)) => {
            let answer = stream(accepted, ticket, "accepted").await?;
            Ok(axum::Json(answer).into_response())
        }
        Err((e, caught)) => {
            if let Some(caught) = caught {
                // Committed by the other server: nothing to wait for.
                let (caught, ticket) = *caught;
                let _ = stream(caught, ticket, "delta").await;
            }
            Err(e)
        }
    }
}

/// After the session lock is let go: waits until an accepted change is
/// durable (the journal's group commit), writes its delta GLB and publishes
/// it with the ticket taken under the lock; returns the answer to the editor
/// (kind `kind`), once viewers have been handed the delta.
///
/// # Errors
///
/// [`ApiError::Storage`] when the journal could not be flushed: the change
/// is neither acknowledged nor streamed.
async fn stream(
    accepted: Accepted,
    ticket: Ticket,
    kind: &str,
) -> Result<serde_json::Value, ApiError> {
    let answer = accepted.to_json(kind);
    // A panic writing the GLB drops the ticket, which lets later updates out.
    AppState::unlocked(move || {
        accepted.wait_durable()?;
        ticket.publish_accepted(&accepted);
        Ok(answer)
    })
    .await
}

/// `POST /undo` and `POST /redo`: a new revision, streamed like an edit.
async fn undo(State(state): State<AppState>) -> Result<Response, ApiError> {
    let (accepted, ticket) = state
        .with_session(|session, hub| Ok::<_, ApiError>((session.undo()?, hub.ticket())))
        .await?;
    Ok(axum::Json(stream(accepted, ticket, "undone").await?).into_response())
}

async fn redo(State(state): State<AppState>) -> Result<Response, ApiError> {
    let (accepted, ticket) = state
        .with_session(|session, hub| Ok::<_, ApiError>((session.redo()?, hub.ticket())))
        .await?;
    Ok(axum::Json(stream(accepted, ticket, "redone").await?).into_response())
}

/// `GET /revisions`: the store's revisions, oldest first (404 without a store).
async fn revisions(State(state): State<AppState>) -> Result<Response, ApiError> {
    let list = state.with_session(|s, _| s.revisions()).await?;
    Ok(axum::Json(json!({ "revisions": list })).into_response())
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

/// `GET /vessel.glb?tag=T`: one vessel's node tree as in `/model.glb`, with
/// the session's revision (`x-vesselcad-revision`), the last revision that
/// changed the vessel (`x-vesselcad-vessel-revision`) and an `ETag` of both
/// tag and that revision (`If-None-Match` answers 304).
async fn vessel_glb(
    State(state): State<AppState>,
    headers: HeaderMap,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let Ok(Query(DrawingQuery {
        tag: Some(tag),
        vessel: None,
    })) = query
    else {
        return Err(ApiError::BadQuery("expected /vessel.glb?tag=<tag>".into()));
    };
    let found = state
        .with_session({
            let tag = tag.clone();
            move |s, _| s.vessel_scene(&tag).ok_or_else(|| s.vessel_tags())
        })
        .await;
    let glb = match found {
        Ok(scene) => AppState::unlocked(move || scene.glb()).await,
        Err(known) => return Err(ApiError::UnknownVessel { tag, known }),
    };
    let etag = format!(
        "\"{}-{}\"",
        super::journal::fingerprint(tag.as_bytes()),
        glb.vessel_revision
    );
    let etag = HeaderValue::from_str(&etag).unwrap_or(HeaderValue::from_static("\"0\""));
    let vessel_revision = (
        header::HeaderName::from_static("x-vesselcad-vessel-revision"),
        HeaderValue::from(glb.vessel_revision),
    );
    if headers.get(header::IF_NONE_MATCH) == Some(&etag) {
        return Ok((
            StatusCode::NOT_MODIFIED,
            [
                (header::ETAG, etag),
                revision_header(glb.revision),
                vessel_revision,
            ],
        )
            .into_response());
    }
    Ok((
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("model/gltf-binary"),
            ),
            (header::ETAG, etag),
            revision_header(glb.revision),
            vessel_revision,
        ],
        glb.glb,
    )
        .into_response())
}

/// The `vessel` query parameter.
#[derive(Deserialize)]
struct DrawingQuery {
    vessel: Option<String>,
    /// `/vessel.glb`'s name for it.
    tag: Option<String>,
}

/// The tag of a `?vessel=T` query on `route`, if it names a vessel.
async fn queried_vessel(
    state: &AppState,
    route: &str,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<String, ApiError> {
    let Ok(Query(DrawingQuery {
        vessel: Some(tag),
        tag: None,
    })) = query
    else {
        return Err(ApiError::BadQuery(format!("expected {route}?vessel=<tag>")));
    };
    let known = state.with_session(|s, _| s.vessel_tags()).await;
    if !known.contains(&tag) {
        return Err(ApiError::UnknownVessel { tag, known });
    }
    Ok(tag)
}

/// `GET /drawing.svg?vessel=TAG`: the vessel's drawing sheet (ANSI D, hidden lines
/// dashed) from the current model, as SVG.
async fn drawing_svg(
    State(state): State<AppState>,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let tag = queried_vessel(&state, "/drawing.svg", query).await?;
    let svg = state
        .with_session(move |s, _| s.drawing(&tag, SheetFormat::Svg))
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

/// `GET /drawing.dxf?vessel=TAG`: the same sheet as DXF (R2000), as a download.
async fn drawing_dxf(
    State(state): State<AppState>,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let tag = queried_vessel(&state, "/drawing.dxf", query).await?;
    let file = format!(
        "attachment; filename=\"{}.dxf\"",
        tag.replace(
            |c: char| !c.is_ascii_alphanumeric() && c != '-' && c != '_',
            "_"
        )
    );
    let dxf = state
        .with_session(move |s, _| s.drawing(&tag, SheetFormat::Dxf))
        .await?;
    Ok((
        [
            (
                header::CONTENT_TYPE,
                HeaderValue::from_static("image/vnd.dxf"),
            ),
            (
                header::CONTENT_DISPOSITION,
                HeaderValue::from_str(&file).unwrap_or(HeaderValue::from_static("attachment")),
            ),
        ],
        dxf,
    )
        .into_response())
}

/// `GET /vessel.json?vessel=TAG`: one vessel's design (canonical JSON, mm) and
/// its index in the design: `{"revision", "index", "vessel"}` — what a viewer
/// reads after a delta instead of the whole design.
async fn vessel_json(
    State(state): State<AppState>,
    query: Result<Query<DrawingQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Response, ApiError> {
    let tag = queried_vessel(&state, "/vessel.json", query).await?;
    let answer = state
        .with_session(move |s, _| s.vessel_entry(&tag))
        .await
        .ok_or_else(|| ApiError::NotFound("/vessel.json".into()))?;
    Ok(axum::Json(answer).into_response())
}

/// The query parameters of `/ws`: `progressive` and `compress` (`meshopt`
/// for compact deltas, `none` or absent for plain ones).
#[derive(Deserialize)]
struct SocketQuery {
    progressive: Option<String>,
    compress: Option<String>,
}

async fn viewer_socket(
    State(state): State<AppState>,
    query: Result<Query<SocketQuery>, axum::extract::rejection::QueryRejection>,
    ws: WebSocketUpgrade,
) -> Response {
    let (progressive, compress) = match query {
        Ok(Query(q)) => (q.progressive, q.compress),
        Err(_) => (None, None),
    };
    let progressive = progressive.is_some_and(|p| p != "0" && p != "false");
    let compact = match compress.as_deref() {
        None | Some("none") => false,
        Some("meshopt") => true,
        Some(other) => {
            return ApiError::BadQuery(format!(
                "/ws: compress = {other:?}: must be \"meshopt\" or \"none\""
            ))
            .into_response();
        }
    };
    ws.max_message_size(MAX_VIEWER_MESSAGE)
        .read_buffer_size(VIEWER_READ_BUFFER)
        .on_upgrade(move |socket| async move {
            // Before subscribing: every update after its snapshot carries
            // the compact GLB.
            let claim = compact.then(|| state.hub.compact_viewer());
            let queue = state.hub.subscribe();
            let shutdown = state.shutdown.clone();
            let snapshot = || {
                let state = state.clone();
                async move {
                    if progressive {
                        return Some(state.with_session(|s, _| s.outline()).await);
                    }
                    let full = state.with_session(|s, _| s.full_model()).await;
                    let limit = state.whole_glb_limit;
                    Some(
                        AppState::unlocked(move || {
                            if full.estimated_glb_bytes() > limit {
                                full.pushed()
                            } else {
                                full.snapshot()
                            }
                        })
                        .await,
                    )
                }
            };
            let timeout = state.viewer_timeout;
            let ping = state.viewer_ping;
            run_viewer::<_, _>(socket, queue, snapshot, shutdown, timeout, ping, compact).await;
            drop(claim);
        })
}
