//! Live redesign sessions: `vesselcad serve` — an HTTP and WebSocket server that
//! applies edits to one design, journals them, and streams glTF deltas to browser
//! viewers.
//!
//! Where it sits in the data flow: edits arrive as JSON Patch documents
//! (`POST /edit`), become one transactional [`crate::model::Edit`] on the
//! incremental model ([`session`]), are made durable in the journal before they are
//! acknowledged ([`journal`]), and the ids the model reports as changed go out to
//! every viewer as a small JSON delta plus a GLB of only the changed parts
//! ([`broadcast`], [`crate::export::write_delta_glb`]). The viewer page and its
//! three.js bundle are embedded ([`assets`]); the routes are in [`routes`].
//!
//! Limits: [`limits::MAX_CONNECTIONS`] connections at once, each closed after
//! [`limits::IDLE_TIMEOUT`] without a byte moving; request bodies [`MAX_BODY`] bytes; a viewer's queue [`VIEWER_QUEUE`]
//! updates (beyond: full resync); a viewer's socket [`VIEWER_SEND_TIMEOUT`] per
//! message (beyond: dropped); viewer messages [`MAX_VIEWER_MESSAGE`] bytes.

pub mod assets;
pub mod broadcast;
pub mod deficiencies;
pub mod error;
pub mod flush;
pub mod follow;
pub mod guard;
pub mod journal;
pub mod limits;
pub mod persist;
pub mod progressive;
pub mod routes;
pub mod scoped;
pub mod session;
pub mod state;
pub mod store_link;
pub mod traveler;
pub mod undo;
pub mod viewer;

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Duration;

pub use broadcast::{COMPACT_DELTAS, MAX_VIEWER_MESSAGE, VIEWER_QUEUE, VIEWER_SEND_TIMEOUT};
pub use error::{ApiError, ServeError};
pub use routes::MAX_BODY;
pub use viewer::WHOLE_GLB_LIMIT;

use crate::mesh::TessellationOptions;
use broadcast::Hub;
use routes::router;
use session::Session;
use state::AppState;
use tokio::sync::watch;
use tokio::task::JoinHandle;

/// How to serve a design.
#[derive(Clone, Debug)]
pub struct ServeOptions {
    /// The design file; its journal is `<design>.journal` beside it.
    pub design: PathBuf,
    /// The address to listen on (loopback by default).
    pub bind: IpAddr,
    /// The port (0: any free port).
    pub port: u16,
    /// The token every route but the page shell needs, if any.
    pub token: Option<String>,
    /// Meshing options of the model.
    pub tessellation: TessellationOptions,
    /// How long a viewer's socket may take to accept one message before the
    /// viewer is dropped ([`VIEWER_SEND_TIMEOUT`] by default).
    pub viewer_timeout: Duration,
    /// The largest whole-model GLB, bytes (estimated), a plain `/ws` viewer
    /// gets in its hello; above it the plant is pushed to it vessel by vessel
    /// after a coarse whole ([`viewer`]; [`WHOLE_GLB_LIMIT`] by default).
    pub whole_glb_limit: u64,
    /// Connections served at once ([`limits::MAX_CONNECTIONS`] by default).
    pub max_connections: usize,
    /// How long a connection may move no byte before it is closed
    /// ([`limits::IDLE_TIMEOUT`] by default).
    pub idle_timeout: Duration,
    /// Whether a clean shutdown saves unsaved edits into the design file. Off by
    /// default: the file is written only by `POST /save`; unsaved edits stay in
    /// the journal and are replayed on the next start.
    pub save_on_exit: bool,
    /// The design store edits are committed to (a SQLite path or a PostgreSQL
    /// URL); without one, the journal beside the design.
    pub store: Option<String>,
    /// How the deltas of viewers that connect with `compress=meshopt` are
    /// written ([`broadcast::COMPACT_DELTAS`] by default: meshopt-compressed,
    /// not quantized; a quantizing caller meshes to
    /// [`GlbOptions::meshing_tolerance`](crate::export::GlbOptions::meshing_tolerance)).
    pub compact_deltas: crate::export::GlbOptions,
}

impl ServeOptions {
    /// Serve `design` on 127.0.0.1:8080, no token, default meshing.
    pub fn new(design: impl Into<PathBuf>) -> ServeOptions {
        ServeOptions {
            design: design.into(),
            bind: IpAddr::V4(Ipv4Addr::LOCALHOST),
            port: 8080,
            token: None,
            tessellation: TessellationOptions::DEFAULT,
            viewer_timeout: VIEWER_SEND_TIMEOUT,
            whole_glb_limit: WHOLE_GLB_LIMIT,
            save_on_exit: false,
            max_connections: limits::MAX_CONNECTIONS,
            idle_timeout: limits::IDLE_TIMEOUT,
            store: None,
            compact_deltas: broadcast::COMPACT_DELTAS,
        }
    }
}

/// A running server.
pub struct Server {
    address: SocketAddr,
    session: Arc<Mutex<Session>>,
    shutdown: watch::Sender<bool>,
    task: JoinHandle<std::io::Result<()>>,
    save_on_exit: bool,
}

/// Opens the session (design + journal replay) and starts serving it on the
/// current tokio runtime.
///
/// # Errors
///
/// [`ServeError`] when the design or journal cannot be opened or the address
/// cannot be bound.
pub async fn start(options: ServeOptions) -> Result<Server, ServeError> {
    let design = options.design.clone();
    let tessellation = options.tessellation;
    let store = options.store.clone();
    let session = tokio::task::spawn_blocking(move || {
        Session::open_with(&design, tessellation, store.as_deref())
    })
    .await
    .map_err(|e| ServeError::Journal {
        path: options.design.display().to_string(),
        message: format!("opening the session panicked: {e}"),
    })??;
    let session = Arc::new(Mutex::new(session));
    let address = SocketAddr::new(options.bind, options.port);
    let listener = tokio::net::TcpListener::bind(address)
        .await
        .map_err(|source| ServeError::Listen {
            address: address.to_string(),
            source,
        })?;
    let address = listener.local_addr().map_err(|source| ServeError::Listen {
        address: address.to_string(),
        source,
    })?;
    let (shutdown, watching) = watch::channel(false);
    let state = AppState {
        session: session.clone(),
        hub: Hub::new(options.compact_deltas),
        token: options.token,
        loopback_only: options.bind.is_loopback(),
        shutdown: watching.clone(),
        viewer_timeout: options.viewer_timeout,
        viewer_ping: limits::ping_interval(options.idle_timeout),
        whole_glb_limit: options.whole_glb_limit,
    };
    if let Some(url) = options
        .store
        .as_deref()
        .filter(|s| crate::store::is_postgres_url(s))
    {
        // Detached: it looks at the shutdown signal every quarter second.
        drop(follow::follow(
            url.to_string(),
            store_link::design_name(&options.design),
            session.clone(),
            state.hub.clone(),
            watching.clone(),
        ));
    }
    let app = router(state);
    let listener =
        limits::LimitedListener::new(listener, options.max_connections, options.idle_timeout);
    let mut stop = watching;
    let task = tokio::spawn(async move {
        axum::serve(listener, app)
            .with_graceful_shutdown(async move {
                let _ = stop.wait_for(|s| *s).await;
            })
            .await
    });
    Ok(Server {
        address,
        session,
        shutdown,
        task,
        save_on_exit: options.save_on_exit,
    })
}

impl Server {
    /// The address it listens on.
    pub fn address(&self) -> SocketAddr {
        self.address
    }

    /// Stops serving (viewers are closed) and waits for requests in flight; with
    /// [`ServeOptions::save_on_exit`], then saves unsaved edits into the design
    /// file and starts a fresh journal. Otherwise the file is left as it is and
    /// unsaved edits stay in the journal.
    ///
    /// # Errors
    ///
    /// [`ServeError::Save`] if the design cannot be saved (the journal still
    /// holds every edit), [`ServeError::Listen`] if the server had failed.
    pub async fn shutdown(self) -> Result<(), ServeError> {
        let _ = self.shutdown.send(true);
        let served = self.task.await;
        let address = self.address.to_string();
        let session = self.session;
        let save_on_exit = self.save_on_exit;
        let saved = tokio::task::spawn_blocking(move || {
            let mut s = session.lock().unwrap_or_else(|p| p.into_inner());
            let path = s.path().display().to_string();
            // Only edits are saved on exit (a file deleted with nothing to save
            // stays deleted).
            if !save_on_exit || !s.has_unsaved_edits() {
                if s.has_unsaved_edits() && !save_on_exit {
                    println!(
                        "vesselcad serve: {path} not written: its unsaved edits are kept in \
                         the journal and replayed on the next start (POST /save or \
                         --save-on-exit writes them)"
                    );
                }
                return Ok(());
            }
            s.save().map(|_| ()).map_err(|e| ServeError::Save {
                path,
                source: std::io::Error::other(e.to_string()),
            })
        })
        .await;
        match served {
            Ok(Ok(())) => {}
            Ok(Err(source)) => return Err(ServeError::Listen { address, source }),
            Err(e) => {
                return Err(ServeError::Listen {
                    address,
                    source: std::io::Error::other(e.to_string()),
                });
            }
        }
        match saved {
            Ok(result) => result,
            Err(e) => Err(ServeError::Save {
                path: String::new(),
                source: std::io::Error::other(e.to_string()),
            }),
        }
    }
}

/// `vesselcad serve`: serves until Ctrl-C or SIGTERM, then saves. Prints the URL
/// on its first line of output.
///
/// # Errors
///
/// As [`start`] and [`Server::shutdown`].
pub fn run(options: ServeOptions) -> Result<(), ServeError> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|source| ServeError::Listen {
            address: format!("{}:{}", options.bind, options.port),
            source,
        })?;
    runtime.block_on(async move {
        let server = start(options).await?;
        println!("vesselcad serve: http://{}/", server.address());
        // Flush so a parent process reading our output sees the address now.
        use std::io::Write;
        let _ = std::io::stdout().flush();
        stop_signal().await;
        println!("vesselcad serve: shutting down");
        server.shutdown().await
    })
}

/// Waits for Ctrl-C or (on Unix) SIGTERM.
async fn stop_signal() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        () = ctrl_c => {}
        () = term => {}
    }
}
