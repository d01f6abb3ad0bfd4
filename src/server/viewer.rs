//! One viewer's WebSocket: the hello, the deltas in revision order, resyncs,
//! pings — and, on a large plant, the plant pushed vessel by vessel.
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
//! **A large plant is pushed.** When the whole model's GLB would pass the
//! server's limit ([`ServeOptions::whole_glb_limit`](super::ServeOptions::whole_glb_limit),
//! estimated without writing it), a plain `/ws` viewer's hello and resyncs
//! carry `"pushed":N` and, instead of the whole GLB, the coarse whole: a GLB of
//! each vessel's box (node `box` under the vessel's node). The N vessels then
//! follow at the hello's revision, in design order, one pair each:
//!
//! ```text
//! {"type":"vessel","revision":R,"tag":T,"index":k}          + the vessel's GLB
//! ```
//!
//! which replaces every node of vessel T (its box included), as `/vessel.glb`
//! would at revision R; deltas come after the last vessel. So no message is
//! larger than the largest vessel: a whole-plant message took every viewer's
//! socket its own copy of the plant and longer than the send timeout (at 1,000
//! vessels, 49 of 50 viewers were dropped before their hello). Below the limit
//! the hello is as it always was, so existing clients of small plants see no
//! change. Updates that come while the vessels are pushed are kept (at most
//! [`PUSH_PENDING`]; more is falling behind: a resync) and sent after them.
//!
//! A viewer connecting to `/ws?progressive=1` gets its hello and resyncs as one
//! text message each, `"progressive":true` and each vessel's box in
//! `"vessels":[{"tag","min","max"}]` (glTF frame, m) instead of the GLB, and
//! fetches the vessels' GLBs itself, nearest its camera first
//! ([`super::progressive`]).
//!
//! A viewer connecting with `compress=meshopt` (`/ws?progressive=1&compress=meshopt`,
//! as the viewer page does) gets the deltas' GLBs `EXT_meshopt_compression`-compressed
//! (and quantized under `serve --quantize`; see [`super::broadcast`]); it needs a
//! meshopt decoder (three.js's `MeshoptDecoder`, exported by the page's bundle).
//!
//! Revisions of deltas follow each other by one from the hello's; a viewer
//! ignores nothing and applies them in order. Viewers send nothing but pings and
//! close frames (text they send is ignored; messages above
//! [`MAX_VIEWER_MESSAGE`](super::broadcast::MAX_VIEWER_MESSAGE) bytes close the socket).

use std::collections::VecDeque;
use std::sync::Arc;
use std::time::Duration;

use axum::body::Bytes;
use axum::extract::ws::{Message, WebSocket};
use futures_util::{SinkExt, StreamExt};
use serde_json::json;
use tokio::sync::{broadcast, watch};

use super::broadcast::{Update, VIEWER_QUEUE};
use super::session::Snapshot;

/// The largest whole-model GLB a plain viewer gets in its hello by default,
/// bytes (estimated): 16 MiB, the example plant at 0.5 mm and then some; a
/// larger plant is pushed.
pub const WHOLE_GLB_LIMIT: u64 = 16 << 20;

/// Updates kept for a viewer while a plant is pushed to it; more and it is
/// resynced, as one that fell behind.
pub const PUSH_PENDING: usize = 16 * VIEWER_QUEUE;

/// Why a viewer loop ended.
enum Ended {
    /// The viewer closed, failed or was too slow; nothing more to send.
    Gone,
    /// It fell behind by this many updates while a snapshot was pushed.
    Behind(u64),
}

/// Serves one viewer until it goes, the server shuts down, or it stops reading
/// (its socket accepts nothing for `timeout`); pings it every `ping`, so a quiet
/// viewer is never an idle connection. `snapshot` gives the current full
/// model (it locks the session). A `compact` viewer gets each delta's compact
/// GLB where the update has one ([`Update::glb_for`]).
pub async fn run_viewer<F, Fut>(
    socket: WebSocket,
    mut queue: broadcast::Receiver<Arc<Update>>,
    snapshot: F,
    mut shutdown: watch::Receiver<bool>,
    timeout: Duration,
    ping: Duration,
    compact: bool,
) where
    F: Fn() -> Fut,
    Fut: std::future::Future<Output = Option<Snapshot>>,
{
    let (mut sink, mut stream) = socket.split();
    let mut pending = VecDeque::new();
    let Some(first) = snapshot().await else {
        return;
    };
    let Some(mut at) = send_snapshot(
        &mut sink,
        ("hello", None),
        first,
        &snapshot,
        &mut queue,
        &mut pending,
        timeout,
    )
    .await
    else {
        return;
    };
    let mut pings = tokio::time::interval_at(tokio::time::Instant::now() + ping, ping);
    pings.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
    loop {
        // Updates that came while a plant was pushed go first, in order.
        while let Some(update) = pending.pop_front() {
            if update.revision > at {
                at = update.revision;
                let header = update.header.clone();
                if send_pair(&mut sink, header, update.glb_for(compact), timeout)
                    .await
                    .is_err()
                {
                    return;
                }
            }
        }
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
                        send_pair(&mut sink, update.header.clone(), update.glb_for(compact), timeout)
                            .await
                    }
                    Err(broadcast::error::RecvError::Lagged(missed)) => {
                        let Some(full) = snapshot().await else { break };
                        let resent = send_snapshot(
                            &mut sink,
                            ("resync", Some(missed)),
                            full,
                            &snapshot,
                            &mut queue,
                            &mut pending,
                            timeout,
                        )
                        .await;
                        match resent {
                            Some(revision) => {
                                at = revision;
                                Ok(())
                            }
                            None => Err(Ended::Gone),
                        }
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

/// Sends a snapshot as `kind` (`hello`, or `resync` after missing some
/// updates) and, for a pushed one, its vessels; a viewer that falls behind
/// meanwhile is sent a fresh one as a resync. Returns the revision the viewer
/// is at, or `None` once it is gone.
async fn send_snapshot<S, F, Fut>(
    sink: &mut S,
    (mut kind, mut missed): (&'static str, Option<u64>),
    mut snapshot: Snapshot,
    fresh: &F,
    queue: &mut broadcast::Receiver<Arc<Update>>,
    pending: &mut VecDeque<Arc<Update>>,
    timeout: Duration,
) -> Option<u64>
where
    S: SinkExt<Message> + Unpin,
    F: Fn() -> Fut,
    Fut: std::future::Future<Output = Option<Snapshot>>,
{
    loop {
        let reason =
            missed.map(|n| format!("fell behind by {n} updates (queue of {VIEWER_QUEUE})"));
        pending.clear();
        let sent = match send_full(sink, kind, &snapshot, reason, timeout).await {
            Ok(()) => push_vessels(sink, &snapshot, queue, pending, timeout).await,
            Err(e) => Err(e),
        };
        match sent {
            Ok(()) => return Some(snapshot.revision),
            Err(Ended::Gone) => return None,
            Err(Ended::Behind(n)) => {
                snapshot = fresh().await?;
                (kind, missed) = ("resync", Some(n));
            }
        }
    }
}

/// Sends a full model: header with every id, then the GLB (the coarse whole
/// of a pushed snapshot, with `"pushed"`: its number of vessels).
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
    if let Some(full) = &snapshot.pushed {
        header["pushed"] = json!(full.vessel_tags().len());
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

/// Sends a pushed snapshot's vessels, one pair each (nothing for another
/// snapshot), each GLB written off the async threads; keeps the updates that
/// come meanwhile in `pending`.
async fn push_vessels<S>(
    sink: &mut S,
    snapshot: &Snapshot,
    queue: &mut broadcast::Receiver<Arc<Update>>,
    pending: &mut VecDeque<Arc<Update>>,
    timeout: Duration,
) -> Result<(), Ended>
where
    S: SinkExt<Message> + Unpin,
{
    let Some(full) = &snapshot.pushed else {
        return Ok(());
    };
    let tags: Vec<String> = full.vessel_tags().map(str::to_string).collect();
    for (k, tag) in tags.into_iter().enumerate() {
        loop {
            match queue.try_recv() {
                Ok(update) => pending.push_back(update),
                Err(broadcast::error::TryRecvError::Empty) => break,
                Err(broadcast::error::TryRecvError::Lagged(n)) => return Err(Ended::Behind(n)),
                Err(broadcast::error::TryRecvError::Closed) => return Err(Ended::Gone),
            }
        }
        if pending.len() > PUSH_PENDING {
            return Err(Ended::Behind(pending.len() as u64));
        }
        let writer = full.clone();
        let glb = tokio::task::spawn_blocking(move || writer.vessel_glb(k))
            .await
            .map_err(|_| Ended::Gone)?;
        let header = json!({
            "type": "vessel", "revision": full.revision(), "tag": tag, "index": k,
        });
        send_pair(sink, header.to_string(), &glb, timeout).await?;
    }
    Ok(())
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
