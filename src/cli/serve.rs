//! The `vesselcad serve` command line: its arguments and the few lines that turn
//! them into [`ServeOptions`] and run the server, so `main.rs` only names it.

use std::net::IpAddr;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::Args;

use vesselcad::design::DesignError;
use vesselcad::export::quantization_budget;
use vesselcad::mesh::{
    DEFAULT_VERTEX_BUDGET, MAX_VERTEX_BUDGET, MIN_VERTEX_BUDGET, TessellationOptions,
};
use vesselcad::model::ModelError;
use vesselcad::server::{
    self, ServeError, ServeOptions, VIEWER_SEND_TIMEOUT, WHOLE_GLB_LIMIT, limits,
};

/// Arguments of `vesselcad serve`.
#[derive(Args, Debug)]
pub struct ServeArgs {
    /// The design file (JSON, vesselcad/1). Edits are journaled beside it in
    /// `<design>.journal` and replayed on restart.
    pub design: PathBuf,
    /// Port to listen on (0: any free port; the URL is printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// Address to listen on. Loopback by default, and then only loopback Host
    /// names are answered (no DNS rebinding); anything else exposes the session
    /// to the network and answers any Host name.
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: IpAddr,
    /// Require this token on every route but the page shell: `Authorization:
    /// Bearer <token>`, or `?token=<token>` on a GET (the page asks for it once).
    #[arg(long)]
    pub token: Option<String>,
    /// Chordal tolerance of the meshes, mm.
    #[arg(long, default_value_t = TessellationOptions::DEFAULT.tolerance, allow_negative_numbers = true)]
    pub tolerance: f64,
    /// Most vertices the mesher may give one patch (1000 to 4294967295): a
    /// patch that needs more is refused, naming it, instead of taking the
    /// memory and time it would need.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_VERTEX_BUDGET as u64,
          value_parser = clap::value_parser!(u64).range(MIN_VERTEX_BUDGET as u64..=MAX_VERTEX_BUDGET as u64))]
    pub max_vertices: u64,
    /// Seconds a viewer's socket may accept nothing before the viewer is
    /// dropped (a viewer that only falls behind is resynced, not dropped).
    #[arg(long, default_value_t = VIEWER_SEND_TIMEOUT.as_secs_f64(), value_parser = parse_timeout, allow_negative_numbers = true)]
    pub viewer_timeout: f64,
    /// Largest whole-model GLB (bytes, estimated) a plain `/ws` viewer gets in
    /// its hello; above it the viewer gets each vessel's box first, then the
    /// vessels one message each.
    #[arg(long, value_name = "BYTES", default_value_t = WHOLE_GLB_LIMIT)]
    pub whole_glb_limit: u64,
    /// Connections served at once; more wait until one closes.
    #[arg(long, default_value_t = limits::MAX_CONNECTIONS as u16, value_parser = clap::value_parser!(u16).range(1..))]
    pub max_connections: u16,
    /// Seconds a connection may move no byte (idle keep-alive, unfinished
    /// headers, a silent viewer) before it is closed.
    #[arg(long, default_value_t = limits::IDLE_TIMEOUT.as_secs_f64(), value_parser = parse_timeout, allow_negative_numbers = true)]
    pub idle_timeout: f64,
    /// On a clean shutdown (Ctrl-C, SIGTERM), write unsaved edits into the design
    /// file. Without it the file is written only by `POST /save`; unsaved edits
    /// stay in the journal and are replayed on the next start.
    #[arg(long)]
    pub save_on_exit: bool,
    /// Commit every edit as a revision in this design store (a SQLite file or
    /// a `postgres://` URL shared by several servers) instead of the journal;
    /// adds undo, redo and history. The design is the file's name without
    /// `.json`; an old journal is migrated on first start.
    #[arg(long)]
    pub store: Option<String>,
    /// Quantize the compact deltas viewers get (`KHR_mesh_quantization`,
    /// 16-bit positions, byte normals, as `build --quantize`): the model is
    /// meshed to 0.75 × the tolerance and a quarter of it is given to
    /// quantization, so what viewers draw holds the tolerance. Deltas are
    /// meshopt-compressed for the viewer page either way.
    #[arg(long)]
    pub quantize: bool,
}

/// A positive, finite number of seconds (at most a day).
fn parse_timeout(text: &str) -> Result<f64, String> {
    let seconds: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number of seconds"))?;
    if seconds.is_finite() && seconds > 0.0 && seconds <= 86_400.0 {
        Ok(seconds)
    } else {
        Err("must be more than 0 and at most 86400 seconds".to_string())
    }
}

/// Runs `vesselcad serve`; exit 1 for an invalid design or a journal that cannot
/// be replayed, 2 for a file that cannot be read or written or a socket failure.
pub fn run(args: ServeArgs) -> ExitCode {
    if !args.bind.is_loopback() && args.token.is_none() {
        eprintln!(
            "warning: listening on {} without --token: anyone who can reach it can edit",
            args.bind
        );
    }
    let mut compact_deltas = server::COMPACT_DELTAS;
    if args.quantize {
        compact_deltas.quantize = Some(quantization_budget(args.tolerance));
    }
    let options = ServeOptions {
        design: args.design,
        bind: args.bind,
        port: args.port,
        token: args.token,
        tessellation: TessellationOptions::chord(compact_deltas.meshing_tolerance(args.tolerance))
            .with_max_vertices(args.max_vertices as usize),
        viewer_timeout: Duration::from_secs_f64(args.viewer_timeout),
        whole_glb_limit: args.whole_glb_limit,
        save_on_exit: args.save_on_exit,
        max_connections: usize::from(args.max_connections),
        idle_timeout: Duration::from_secs_f64(args.idle_timeout),
        store: args.store,
        compact_deltas,
    };
    match server::run(options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            match &e {
                // Bad options named by their flag.
                ServeError::Design {
                    path,
                    source: source @ ModelError::Options(_),
                } => eprintln!("error: {path}: {}", super::model_error(source)),
                e => eprintln!("error: {e}"),
            }
            match e {
                ServeError::Design {
                    source: ModelError::Design(DesignError::Io { .. }),
                    ..
                } => ExitCode::from(2),
                ServeError::Design { .. } | ServeError::Journal { .. } => ExitCode::from(1),
                ServeError::Listen { .. } | ServeError::Save { .. } => ExitCode::from(2),
            }
        }
    }
}
