//! Errors of the live-session server, in two domains: [`ServeError`] stops the
//! server from starting (bad design, corrupt journal, port in use); [`ApiError`] is
//! one refused request, answered with a 4xx/5xx status and a JSON body that says
//! what was wrong — the session is unchanged.
//!
//! Every response error body has the shape
//! `{"error": "<message>", "kind": "<kind>", "violations": [...]?, "failures": [...]?}`
//! where `violations` lists the broken design rules (path, entity, field, value,
//! rule) and `failures` the parts and nozzles whose geometry cannot be built
//! (kind `geometry`: path, entity, stage, patch, cause; see
//! [`BuildFailure::to_json`]).

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use serde_json::json;
use thiserror::Error;

use crate::design::{DesignError, RuleViolation};
use crate::drawing::{LISTED_TAGS, list_tags};
use crate::model::{BuildFailure, ModelError};

/// Why `vesselcad serve` could not start or stopped.
#[derive(Debug, Error)]
pub enum ServeError {
    /// The design file could not be loaded or built.
    #[error("{path}: {source}")]
    Design {
        /// The design file.
        path: String,
        /// What was wrong.
        source: ModelError,
    },
    /// The journal beside the design could not be read, written or replayed.
    #[error("journal {path}: {message}")]
    Journal {
        /// The journal file.
        path: String,
        /// What was wrong.
        message: String,
    },
    /// The listening socket could not be opened or the server failed.
    #[error("cannot listen on {address}: {source}")]
    Listen {
        /// The address asked for.
        address: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Saving the design at shutdown failed (the journal still holds every edit).
    #[error("cannot save {path}: {source}")]
    Save {
        /// The design file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// One refused request. The session, its model and its journal are unchanged.
#[derive(Debug, Error)]
pub enum ApiError {
    /// The body is not JSON, or not a JSON Patch document (RFC 6902). 400.
    #[error("malformed edit: {0}")]
    Malformed(String),
    /// The body is larger than the stated limit. 413.
    #[error("request body too large: the limit is {limit} bytes")]
    TooLarge {
        /// The limit, bytes.
        limit: usize,
    },
    /// An operation's path does not exist in the design, or an operation cannot be
    /// applied to what it names. 422.
    #[error("patch cannot be applied: {0}")]
    Unappliable(String),
    /// A `test` operation failed: the design is not what the editor expected
    /// (typically another editor changed it first). 409.
    #[error("patch test failed: {0}")]
    TestFailed(String),
    /// The patched document is not a valid design: a wrong type, an unknown field,
    /// or values breaking design rules (all listed). 422.
    #[error("the edited design is invalid: {0}")]
    Invalid(DesignError),
    /// The model refused the edit. 422.
    #[error("the model refused the edit: {0}")]
    Refused(ModelError),
    /// Editing needs `Authorization: Bearer <token>` and it was missing or wrong. 401.
    #[error(
        "this session needs its token: the header `Authorization: Bearer <token>` (or \
         `?token=<token>` on a GET) with the server's --token"
    )]
    Unauthorized,
    /// Refused by the session's origin rules: a Host that is not served, or a
    /// request from another origin. 403.
    #[error("forbidden: {0}")]
    Forbidden(String),
    /// A POST whose body is not declared JSON. 415.
    #[error("unsupported content type: {0}")]
    UnsupportedType(String),
    /// No such vessel (e.g. in `/drawing.svg?vessel=`); the design's tags are
    /// listed (the first 20, then how many more). 404.
    #[error("no vessel has the tag {tag:?}; the design's vessels are: {}", list_tags(.known))]
    UnknownVessel {
        /// The tag asked for.
        tag: String,
        /// Every tag of the design, in design order.
        known: Vec<String>,
    },
    /// No such file or route. 404.
    #[error("not found: {0}")]
    NotFound(String),
    /// A query parameter is missing or malformed. 400.
    #[error("bad query: {0}")]
    BadQuery(String),
    /// The drawing sheet of a vessel could not be made. 422.
    #[error("no drawing: {0}")]
    Drawing(String),
    /// The process plan (traveler) of a vessel could not be made. 422.
    #[error("no process plan: {0}")]
    Plan(String),
    /// The edit was valid but could not be made durable (journal write failed);
    /// the model was put back as it was. 500.
    #[error("edit not saved, nothing changed: {0}")]
    Storage(String),
    /// The design store cannot be reached (the connection was lost or the
    /// database is down): the edit was not acknowledged and the model is as it
    /// was; the next request reconnects. 503.
    #[error(
        "edit not saved, nothing changed: the design store cannot be reached (the server \
         reconnects on the next request): {0}"
    )]
    StoreUnavailable(String),
    /// The design file could not be saved; it is as it was and the journal
    /// still holds every edit. 500.
    #[error("design not saved (the file is as it was, the journal keeps every edit): {0}")]
    SaveFailed(String),
    /// Another server committed to the shared store first; nothing changed
    /// here. 409, with the current revision.
    #[error("edit refused: {message}")]
    Conflict {
        /// The design's newest revision.
        current: u64,
        /// What happened.
        message: String,
    },
    /// `POST /undo` or `/redo` with nothing to undo or redo. 409.
    #[error("nothing to {0}")]
    NothingTo(&'static str),
    /// History asked of a session without a store (`serve --store`). 404.
    #[error("this session keeps no history: start `vesselcad serve` with --store")]
    NoHistory,
}

impl ApiError {
    /// The HTTP status of this error.
    pub fn status(&self) -> StatusCode {
        match self {
            ApiError::Malformed(_) | ApiError::BadQuery(_) => StatusCode::BAD_REQUEST,
            ApiError::TooLarge { .. } => StatusCode::PAYLOAD_TOO_LARGE,
            ApiError::Unappliable(_) | ApiError::Invalid(_) | ApiError::Refused(_) => {
                StatusCode::UNPROCESSABLE_ENTITY
            }
            ApiError::TestFailed(_) | ApiError::Conflict { .. } | ApiError::NothingTo(_) => {
                StatusCode::CONFLICT
            }
            ApiError::NoHistory => StatusCode::NOT_FOUND,
            ApiError::Unauthorized => StatusCode::UNAUTHORIZED,
            ApiError::Forbidden(_) => StatusCode::FORBIDDEN,
            ApiError::UnsupportedType(_) => StatusCode::UNSUPPORTED_MEDIA_TYPE,
            ApiError::UnknownVessel { .. } | ApiError::NotFound(_) => StatusCode::NOT_FOUND,
            ApiError::Drawing(_) | ApiError::Plan(_) => StatusCode::UNPROCESSABLE_ENTITY,
            ApiError::Storage(_) | ApiError::SaveFailed(_) => StatusCode::INTERNAL_SERVER_ERROR,
            ApiError::StoreUnavailable(_) => StatusCode::SERVICE_UNAVAILABLE,
        }
    }

    /// A short machine-readable name of the error kind.
    pub fn kind(&self) -> &'static str {
        match self {
            ApiError::Malformed(_) => "malformed",
            ApiError::TooLarge { .. } => "too_large",
            ApiError::Unappliable(_) => "unappliable",
            ApiError::TestFailed(_) => "test_failed",
            ApiError::Invalid(_) => "invalid",
            ApiError::Refused(ModelError::Geometry(_)) => "geometry",
            ApiError::Refused(_) => "refused",
            ApiError::Unauthorized => "unauthorized",
            ApiError::Forbidden(_) => "forbidden",
            ApiError::UnsupportedType(_) => "unsupported_type",
            ApiError::UnknownVessel { .. } => "unknown_vessel",
            ApiError::NotFound(_) => "not_found",
            ApiError::BadQuery(_) => "bad_query",
            ApiError::Drawing(_) => "drawing",
            ApiError::Plan(_) => "plan",
            ApiError::Storage(_) => "storage",
            ApiError::StoreUnavailable(_) => "store_unavailable",
            ApiError::SaveFailed(_) => "save_failed",
            ApiError::Conflict { .. } => "conflict",
            ApiError::NothingTo(_) => "nothing_to_do",
            ApiError::NoHistory => "no_history",
        }
    }

    /// The broken design rules, if any.
    fn violations(&self) -> &[RuleViolation] {
        match self {
            ApiError::Invalid(e) | ApiError::Refused(ModelError::Design(e)) => e.violations(),
            _ => &[],
        }
    }

    /// The parts and nozzles whose geometry cannot be built, if any.
    fn failures(&self) -> &[BuildFailure] {
        match self {
            ApiError::Refused(ModelError::Geometry(f)) => f,
            _ => &[],
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let mut body = json!({ "error": self.to_string(), "kind": self.kind() });
        let violations = self.violations();
        if !violations.is_empty() {
            body["violations"] = violations
                .iter()
                .map(|v| {
                    json!({
                        "path": v.path, "entity": v.entity, "field": v.field,
                        "value": v.value, "rule": v.rule,
                    })
                })
                .collect();
        }
        let failures = self.failures();
        if !failures.is_empty() {
            body["failures"] = failures.iter().map(BuildFailure::to_json).collect();
        }
        if let ApiError::UnknownVessel { known, .. } = &self {
            body["vessels"] = json!(known.iter().take(LISTED_TAGS).collect::<Vec<_>>());
        }
        if let ApiError::Conflict { current, .. } = &self {
            body["revision"] = json!(current);
        }
        if let ApiError::TooLarge { limit } = self {
            body["limit"] = json!(limit);
        }
        let retry = matches!(self, ApiError::StoreUnavailable(_));
        let mut response = (self.status(), Json(body)).into_response();
        if retry {
            response.headers_mut().insert(
                axum::http::header::RETRY_AFTER,
                axum::http::HeaderValue::from_static("1"),
            );
        }
        response
    }
}
