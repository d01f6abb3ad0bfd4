//! What every handler of a live session shares ([`AppState`]): the session
//! behind its lock, the viewers' hub, the token and the shutdown signal; read by
//! the [`guard`](super::guard) and the [`routes`](super::routes).

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use axum::http::{HeaderMap, header};
use tokio::sync::watch;

use super::broadcast::Hub;
use super::error::ApiError;
use super::session::Session;

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
    /// Above this many bytes of whole-model GLB (estimated), a plain viewer's
    /// hello is pushed vessel by vessel (see [`super::viewer`]).
    pub whole_glb_limit: u64,
}

impl AppState {
    /// Runs `work` on the locked session on a blocking thread.
    pub(super) async fn with_session<T, F>(&self, work: F) -> T
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

    /// Runs `work` on a blocking thread without the session lock (writing a
    /// GLB from what was read under it).
    pub(super) async fn unlocked<T, F>(work: F) -> T
    where
        T: Send + 'static,
        F: FnOnce() -> T + Send + 'static,
    {
        match tokio::task::spawn_blocking(work).await {
            Ok(value) => value,
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

/// Compares two byte strings in time independent of where they differ.
fn constant_time_eq(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}
