//! Following other servers on a shared PostgreSQL store: a thread that
//! `LISTEN`s on [`CHANNEL`] and, when another server commits a revision of this
//! session's design, has the session adopt it ([`Session::catch_up`]) and sends
//! the change to this server's viewers like a local edit. On a lost connection
//! it reconnects every second and catches up once connected (notifications sent
//! while away are not replayed, so it asks the store).

use std::sync::{Arc, Mutex};
use std::time::Duration;

use postgres::fallible_iterator::FallibleIterator;
use tokio::sync::watch;

use super::broadcast::Hub;
use super::session::Session;
use crate::store::CHANNEL;
use crate::store::pg::{full_message, redact};

/// How long the thread waits for a notification before looking at the stop
/// signal again.
const POLL: Duration = Duration::from_millis(250);

/// Starts following `design` in the PostgreSQL store at `url`.
pub fn follow(
    url: String,
    design: String,
    session: Arc<Mutex<Session>>,
    hub: Hub,
    stop: watch::Receiver<bool>,
) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut warned = false;
        while !*stop.borrow() {
            let mut client = match postgres::Client::connect(&url, postgres::NoTls) {
                Ok(c) => c,
                Err(e) => {
                    if !warned {
                        eprintln!(
                            "vesselcad serve: cannot listen to {} for other servers' edits \
                             (retrying every second): {}",
                            redact(&url),
                            full_message(&e)
                        );
                        warned = true;
                    }
                    std::thread::sleep(Duration::from_secs(1));
                    continue;
                }
            };
            if let Err(e) = client.batch_execute(&format!("LISTEN {CHANNEL}")) {
                eprintln!("vesselcad serve: LISTEN {CHANNEL}: {}", full_message(&e));
                std::thread::sleep(Duration::from_secs(1));
                continue;
            }
            warned = false;
            adopt(&session, &hub);
            while !*stop.borrow() && !client.is_closed() {
                let mut ours = false;
                let mut notifications = client.notifications();
                let mut waiting = notifications.timeout_iter(POLL);
                while let Ok(Some(n)) = waiting.next() {
                    ours |= n.payload().split_once(' ').map(|(_, d)| d) == Some(design.as_str());
                }
                if ours {
                    adopt(&session, &hub);
                }
            }
        }
    })
}

/// Has the session adopt the newest revision and tells the viewers (the delta
/// GLB written after the session lock is let go).
fn adopt(session: &Mutex<Session>, hub: &Hub) {
    let caught = {
        let mut s = session.lock().unwrap_or_else(|p| p.into_inner());
        s.catch_up().map(|c| c.map(|c| (c, hub.ticket())))
    };
    match caught {
        Ok(Some((accepted, ticket))) => ticket.publish_accepted(&accepted),
        Ok(None) => {}
        Err(e) => eprintln!("vesselcad serve: cannot adopt another server's revision: {e}"),
    }
}
