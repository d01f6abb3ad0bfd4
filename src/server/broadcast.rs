//! Streaming to viewers: the hub that fans each accepted edit out to every
//! connected WebSocket, and the per-viewer loop.
//!
//! Where it sits: the edit route sends an [`Update`] to the [`Hub`] while it holds
//! the session lock, so updates enter the hub in revision order. Each viewer has
//! its own task reading the hub through a bounded queue ([`VIEWER_QUEUE`] updates,
//! a `tokio::sync::broadcast` ring): sending never waits for a viewer, so a slow
//! viewer never blocks the editor or the other viewers. A viewer whose queue
//! overflows is told so and sent a full resync; one whose socket accepts nothing
//! for [`VIEWER_SEND_TIMEOUT`] is dropped.
//!
//! The protocol, server → viewer, is pairs of a JSON text message and a binary GLB:
//!
//! ```text
//! {"type":"hello","revision":R,"ids":[...]}                 + full GLB (on connect)
//! {"type":"delta","revision":R,"changed":[...],"removed":[...],"work":{...}}
//!                                                           + GLB of the changed parts
//! {"type":"resync","revision":R,"ids":[...],"reason":"..."} + full GLB (fell behind)
//! ```
//!
//! A viewer connecting to `/ws?progressive=1` gets its hello and resyncs as one
//! text message each, `"progressive":true` and each vessel's box in
//! `"vessels":[{"tag","min","max"}]` (glTF frame, m) instead of the GLB, and
//! fetches the vessels' GLBs itself ([`super::progressive`]).
//!
//! Revisions of deltas follow each other by one from the hello's; a viewer
//! ignores nothing and applies them in order. Viewers send nothing but pings and
//! close frames (text they send is ignored; messages above
//! [`MAX_VIEWER_MESSAGE`] bytes close the socket).

use std::sync::Arc;
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::ws::{Message, WebSocket};
use futures_util::{SinkExt, StreamExt};
use serde_json::json;
use tokio::sync::{broadcast, watch};

use super::session::{Accepted, Snapshot};

/// Updates a viewer may fall behind by before it is sent a full resync.
pub const VIEWER_QUEUE: usize = 64;

/// How long a viewer's socket may take to accept one message before the viewer
/// is dropped, unless the server is told otherwise
/// ([`ServeOptions::viewer_timeout`](super::ServeOptions::viewer_timeout)).
pub const VIEWER_SEND_TIMEOUT: Duration = Duration::from_secs(10);

/// Largest message a viewer may send, bytes.
pub const MAX_VIEWER_MESSAGE: usize = 64 * 1024;

/// One accepted edit as viewers receive it.
#[derive(Debug)]
pub struct Update {
    /// Its revision.
    pub revision: u64,
    /// The delta header (JSON text).
    pub header: String,
    /// The GLB of the changed parts.
    pub glb: Bytes,
}

impl Update {
    /// The update of an accepted edit.
    pub fn of(accepted: &Accepted) -> Update {
        Update {
            revision: accepted.revision,
            header: accepted.to_json("delta").to_string(),
            glb: accepted.delta_glb.clone(),
        }
    }
}

/// Fans updates out to every viewer.
#[derive(Clone, Debug)]
pub struct Hub {
    sender: broadcast::Sender<Arc<Update>>,
}

impl Default for Hub {
    fn default() -> Self {
        Hub {
            sender: broadcast::channel(VIEWER_QUEUE).0,
        }
    }
}

impl Hub {
    /// Sends an update to every viewer; never waits.
    pub fn publish(&self, update: Update) {
        // An error only means that no viewer is connected.
        let _ = self.sender.send(Arc::new(update));
    }

    /// A new viewer's queue. Subscribe before taking the snapshot: updates already
    /// in the snapshot are then skipped by revision, and none is missed.
    pub fn subscribe(&self) -> broadcast::Receiver<Arc<Update>> {
        self.sender.subscribe()
    }

    /// Viewers connected.
    pub fn viewers(&self) -> usize {
        self.sender.receiver_count()
    }
}

/// Why a viewer loop ended.
enum Ended {
    /// The viewer closed, failed or was too slow; nothing more to send.
    Gone,
}

/// Serves one viewer until it goes, the server shuts down, or it stops reading
/// (its socket accepts nothing for `timeout`); pings it every `ping`, so a quiet
/// viewer is never an idle connection. `snapshot` gives the current full
/// model (it locks the session).
pub async fn run_viewer<F, Fut>(
    socket: WebSocket,
    mut queue: broadcast::Receiver<Arc<Update>>,
    snapshot: F,
    mut shutdown: watch::Receiver<bool>,
    timeout: Duration,
    ping: Duration,
) where
    F: Fn() -> Fut,
    Fut: std::future::Future<Output = Option<Snapshot>>,
{
    let (mut sink, mut stream) = socket.split();
    let Some(first) = snapshot().await else {
        return;
    };
    let mut at = first.revision;
    if send_full(&mut sink, "hello", &first, None, timeout)
        .await
        .is_err()
    {
        return;
    }
    let mut pings = tokio::time::interval_at(tokio::time::Instant::now() + ping, ping);
    pings.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    loop {
        tokio::select! {
            _ = pings.tick() => {
                let sent = tokio::time::timeout(timeout, sink.send(Message::Ping(Bytes::new()))).await;
                if !matches!(sent, Ok(Ok(()))) {
                    break;
                }
            }
            update = queue.recv() => {
                let sent = match update {
                    Ok(update) if update.revision <= at => Ok(()),
                    Ok(update) => {
                        at = update.revision;
                        send_pair(&mut sink, update.header.clone(), &update.glb, timeout).await
                    }
                    Err(broadcast::error::RecvError::Lagged(missed)) => {
                        let Some(full) = snapshot().await else { break };
                        at = full.revision;
                        let reason = format!(
                            "fell behind by {missed} updates (queue of {VIEWER_QUEUE})"
                        );
                        send_full(&mut sink, "resync", &full, Some(reason), timeout).await
                    }
                    Err(broadcast::error::RecvError::Closed) => break,
                };
                if sent.is_err() {
                    break;
                }
            }
            incoming = stream.next() => match incoming {
                Some(Ok(Message::Close(_))) | Some(Err(_)) | None => break,
                Some(Ok(_)) => {}
            },
            _ = shutdown.changed() => {
                let _ = sink.send(Message::Close(None)).await;
                break;
            }
        }
    }
}

/// Sends a full model: header with every id, then the GLB.
async fn send_full<S>(
    sink: &mut S,
    kind: &str,
    snapshot: &Snapshot,
    reason: Option<String>,
    timeout: Duration,
) -> Result<(), Ended>
where
    S: SinkExt<Message> + Unpin,
{
    let mut header = json!({ "type": kind, "revision": snapshot.revision, "ids": snapshot.ids });
    if let Some(reason) = reason {
        header["reason"] = json!(reason);
    }
    let Some(outline) = &snapshot.outline else {
        return send_pair(sink, header.to_string(), &snapshot.glb, timeout).await;
    };
    // Progressive: the boxes, and no GLB (the viewer fetches each vessel's).
    header["progressive"] = json!(true);
    header["vessels"] = outline.clone();
    match tokio::time::timeout(timeout, sink.send(Message::Text(header.to_string().into()))).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(Ended::Gone),
    }
}

/// Sends a JSON header then its GLB, each within `timeout`.
async fn send_pair<S>(
    sink: &mut S,
    header: String,
    glb: &Bytes,
    timeout: Duration,
) -> Result<(), Ended>
where
    S: SinkExt<Message> + Unpin,
{
    for message in [Message::Text(header.into()), Message::Binary(glb.clone())] {
        match tokio::time::timeout(timeout, sink.send(message)).await {
            Ok(Ok(())) => {}
            _ => return Err(Ended::Gone),
        }
    }
    Ok(())
}
