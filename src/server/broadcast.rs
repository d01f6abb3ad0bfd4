//! Streaming to viewers: the hub that fans each accepted edit out to every
//! connected WebSocket (the per-viewer loop and the protocol are
//! `super::viewer`'s).
//!
//! Where it sits: the edit route takes a [`Ticket`] from the [`Hub`] while it
//! holds the session lock, then writes the delta GLB after letting the lock go
//! and publishes it with the ticket: the hub lets updates out in ticket order,
//! so viewers get them in revision order while the next edit is already being
//! staged (the GLB is written once per update, whatever the number of
//! viewers). Each viewer has
//! its own task reading the hub through a bounded queue ([`VIEWER_QUEUE`] updates,
//! a `tokio::sync::broadcast` ring): sending never waits for a viewer, so a slow
//! viewer never blocks the editor or the other viewers. A viewer whose queue
//! overflows is told so and sent a full resync; one whose socket accepts nothing
//! for [`VIEWER_SEND_TIMEOUT`] is dropped.
//!
//! **Compact deltas.** A viewer that connects to `/ws?compress=meshopt` (the
//! viewer page does) gets each delta's GLB written with the hub's
//! [`GlbOptions`] ([`Hub::new`]; by default `EXT_meshopt_compression`, and
//! `KHR_mesh_quantization` when `serve --quantize` meshed the model for it):
//! the update carries that GLB beside the plain one, written only while such
//! a viewer is connected ([`Hub::compact_viewer`]). Other viewers get the
//! plain GLB, as before.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::body::Bytes;
use tokio::sync::broadcast;

use super::session::Accepted;
use crate::export::{Compression, GlbOptions, Scene, write_glb_with};

/// Updates a viewer may fall behind by before it is sent a full resync.
pub const VIEWER_QUEUE: usize = 64;

/// How long a viewer's socket may take to accept one message before the viewer
/// is dropped, unless the server is told otherwise
/// ([`ServeOptions::viewer_timeout`](super::ServeOptions::viewer_timeout)).
pub const VIEWER_SEND_TIMEOUT: Duration = Duration::from_secs(10);

/// Largest message a viewer may send, bytes.
pub const MAX_VIEWER_MESSAGE: usize = 64 * 1024;

/// The read buffer of a viewer's socket, bytes. A viewer sends nothing but
/// pongs and a close frame, and the WebSocket reader zeroes its whole read
/// buffer on every read attempt — after every message sent to the viewer:
/// with the default 128 KiB that zeroing was the largest single cost of
/// streaming deltas (9 % of the load test's CPU, `perf`), 32 times this one's.
pub const VIEWER_READ_BUFFER: usize = 4 * 1024;

/// One accepted edit as viewers receive it.
#[derive(Debug)]
pub struct Update {
    /// Its revision.
    pub revision: u64,
    /// The delta header (JSON text).
    pub header: String,
    /// The GLB of the changed parts (plain: `f32`, no extension).
    pub glb: Bytes,
    /// The same parts in the hub's compact form, for viewers that asked for
    /// it; `None` when none was connected as it was written (they then get
    /// the plain GLB, which they read too).
    pub compact: Option<Bytes>,
}

impl Update {
    /// The update of an accepted edit: writes its delta GLB, and the compact
    /// one with `compact` (call it without the session lock).
    pub fn of(accepted: &Accepted, compact: Option<&GlbOptions>) -> Update {
        Update {
            revision: accepted.revision,
            header: accepted.to_json("delta").to_string(),
            glb: accepted.delta_glb(),
            compact: compact.map(|options| compact_glb(&accepted.delta, options)),
        }
    }

    /// The GLB a viewer gets: the compact one if it asked for it and it was
    /// written, else the plain one.
    pub fn glb_for(&self, compact: bool) -> &Bytes {
        match (&self.compact, compact) {
            (Some(c), true) => c,
            _ => &self.glb,
        }
    }
}

/// `delta` written with `options`, or the plain GLB if it cannot be (the
/// error is printed).
fn compact_glb(delta: &Scene, options: &GlbOptions) -> Bytes {
    match write_glb_with(delta, options) {
        Ok(glb) => Bytes::from(glb),
        Err(e) => {
            eprintln!("vesselcad serve: cannot write a compact delta GLB: {e}");
            Bytes::from(write_glb_with(delta, &GlbOptions::default()).unwrap_or_default())
        }
    }
}

/// The compact form of deltas a viewer may ask for: `EXT_meshopt_compression`
/// of the plain GLB's `f32` data (lossless: the same vertices, so the same
/// chordal bound).
pub const COMPACT_DELTAS: GlbOptions = GlbOptions {
    reuse: true,
    quantize: None,
    compress: Compression::Meshopt,
    instancing: false,
    normals: crate::export::Normals::Smooth,
};

/// Fans updates out to every viewer, in the order their tickets were taken.
#[derive(Clone, Debug)]
pub struct Hub {
    sender: broadcast::Sender<Arc<Update>>,
    order: Arc<Mutex<Order>>,
    compact: Arc<CompactDeltas>,
}

/// How compact deltas are written, and how many viewers want them.
#[derive(Debug)]
struct CompactDeltas {
    options: GlbOptions,
    viewers: AtomicUsize,
}

/// A viewer's claim on compact deltas: while it lives, each update carries
/// them.
#[derive(Debug)]
pub struct CompactViewer(Arc<CompactDeltas>);

impl Drop for CompactViewer {
    fn drop(&mut self) {
        self.0.viewers.fetch_sub(1, Ordering::Relaxed);
    }
}

/// Tickets taken and updates waiting for an earlier ticket.
#[derive(Debug, Default)]
struct Order {
    /// The next ticket to take.
    issued: u64,
    /// The next ticket to let out.
    next: u64,
    /// Settled tickets after `next`: their update, or `None` for a ticket
    /// dropped without one.
    waiting: BTreeMap<u64, Option<Update>>,
}

/// A place in the viewers' order, taken under the session lock: publishing
/// with it later (after the GLB is written without the lock) keeps revision
/// order. A ticket dropped unused lets the later ones out.
#[derive(Debug)]
#[must_use = "a ticket holds back every later update until it is published or dropped"]
pub struct Ticket {
    hub: Hub,
    number: u64,
    settled: bool,
}

impl Ticket {
    /// Writes the update of `accepted` (its compact GLB too while a viewer
    /// wants it) and publishes it.
    pub fn publish_accepted(self, accepted: &Accepted) {
        let compact = self.hub.compact_options();
        self.publish(Update::of(accepted, compact.as_ref()));
    }

    /// Sends `update` to every viewer once every earlier ticket is settled;
    /// never waits.
    pub fn publish(mut self, update: Update) {
        self.settled = true;
        self.hub.settle(self.number, Some(update));
    }
}

impl Drop for Ticket {
    fn drop(&mut self) {
        if !self.settled {
            self.hub.settle(self.number, None);
        }
    }
}

impl Default for Hub {
    fn default() -> Self {
        Hub::new(COMPACT_DELTAS)
    }
}

impl Hub {
    /// A hub whose compact deltas are written with `compact`.
    pub fn new(compact: GlbOptions) -> Hub {
        Hub {
            sender: broadcast::channel(VIEWER_QUEUE).0,
            order: Arc::default(),
            compact: Arc::new(CompactDeltas {
                options: compact,
                viewers: AtomicUsize::new(0),
            }),
        }
    }

    /// Registers a viewer that wants compact deltas (before it subscribes:
    /// an update written before that is older than its snapshot).
    pub fn compact_viewer(&self) -> CompactViewer {
        self.compact.viewers.fetch_add(1, Ordering::Relaxed);
        CompactViewer(self.compact.clone())
    }

    /// The compact deltas' options while a viewer wants them.
    fn compact_options(&self) -> Option<GlbOptions> {
        (self.compact.viewers.load(Ordering::Relaxed) > 0).then_some(self.compact.options)
    }

    /// Sends an update to every viewer after those of the tickets already
    /// taken; never waits.
    pub fn publish(&self, update: Update) {
        self.ticket().publish(update);
    }

    /// The next place in the viewers' order (take it under the session lock).
    pub fn ticket(&self) -> Ticket {
        let mut order = self.order.lock().unwrap_or_else(|p| p.into_inner());
        let number = order.issued;
        order.issued += 1;
        Ticket {
            hub: self.clone(),
            number,
            settled: false,
        }
    }

    /// Settles ticket `number` and sends every update whose turn has come.
    fn settle(&self, number: u64, update: Option<Update>) {
        let mut order = self.order.lock().unwrap_or_else(|p| p.into_inner());
        order.waiting.insert(number, update);
        loop {
            let next = order.next;
            let Some(ready) = order.waiting.remove(&next) else {
                break;
            };
            order.next += 1;
            if let Some(update) = ready {
                // An error only means that no viewer is connected.
                let _ = self.sender.send(Arc::new(update));
            }
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn update(revision: u64) -> Update {
        Update {
            revision,
            header: String::new(),
            glb: Bytes::new(),
            compact: None,
        }
    }

    fn received(queue: &mut broadcast::Receiver<Arc<Update>>) -> Vec<u64> {
        std::iter::from_fn(|| queue.try_recv().ok().map(|u| u.revision)).collect()
    }

    #[test]
    fn updates_go_out_in_ticket_order_whatever_order_they_are_written_in() {
        let hub = Hub::default();
        let mut queue = hub.subscribe();
        let (first, second, third) = (hub.ticket(), hub.ticket(), hub.ticket());
        third.publish(update(3));
        second.publish(update(2));
        assert_eq!(
            received(&mut queue),
            Vec::<u64>::new(),
            "held for the first"
        );
        first.publish(update(1));
        assert_eq!(received(&mut queue), [1, 2, 3]);
        hub.publish(update(4));
        assert_eq!(received(&mut queue), [4]);
    }

    #[test]
    fn a_ticket_dropped_unused_lets_the_later_ones_out() {
        let hub = Hub::default();
        let mut queue = hub.subscribe();
        let (lost, kept) = (hub.ticket(), hub.ticket());
        kept.publish(update(2));
        drop(lost);
        assert_eq!(received(&mut queue), [2]);
    }

    #[test]
    fn concurrent_writers_publish_each_update_once_in_order() {
        let hub = Hub::default();
        let mut queue = hub.subscribe();
        let tickets: Vec<_> = (1..=48).map(|r| (r, hub.ticket())).collect();
        let threads: Vec<_> = tickets
            .into_iter()
            .rev()
            .map(|(r, t)| std::thread::spawn(move || t.publish(update(r))))
            .collect();
        for t in threads {
            t.join().unwrap();
        }
        assert_eq!(received(&mut queue), (1..=48).collect::<Vec<_>>());
    }
}
