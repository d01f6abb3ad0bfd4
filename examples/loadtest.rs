//! Load test of live sessions (a benchmark, not a unit test): starts
//! `vesselcad serve` in-process on loopback, connects N WebSocket viewers and M
//! editors for a bounded time, and prints the edits per second, the edit → delta
//! latency at the viewers (p50, p99, max), and the revisions each viewer lost or
//! got twice (both must be zero; a viewer that falls behind is resynced, which
//! counts as receiving the revisions it skipped).
//!
//! ```sh
//! cargo run --release --example loadtest -- --viewers 50 --editors 5 --seconds 20
//! #   [--design examples/designs/small-plant.json | --plant 1000] [--tolerance 0.5]
//! #   [--full]
//! ```
//!
//! Viewers connect as the viewer page does, to `/ws?progressive=1` (a hello of
//! every vessel's box, no GLB; they fetch no vessel GLB themselves); `--full`
//! connects them to `/ws`, whose hello and resyncs carry the whole model's GLB
//! or, past the server's `--whole-glb-limit` (16 MiB), a GLB of boxes followed
//! by each vessel's GLB (at 1,000 vessels every viewer receives the whole
//! plant, one vessel a message).
//!
//! `--plant N` serves the generated plant of `vesselcad plant generate --vessels
//! N --seed 1` instead of a design file.
//!
//! Each editor changes one nozzle's projection back and forth (editor e: vessel
//! e mod V, nozzle e div V) with JSON Patches over HTTP, one request after the
//! other. Latency is measured from the moment an editor sends its edit to the
//! moment a viewer has the whole delta (header and GLB); the revision links the
//! two. The server works on a copy of the design in a temporary folder.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::StreamExt;
use serde_json::{Value, json};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio::sync::Mutex;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::tungstenite::protocol::WebSocketConfig;
use vesselcad::mesh::TessellationOptions;
use vesselcad::server::{ServeOptions, start};

/// The binary's allocator (`src/cli/alloc.rs`), so that the server's times
/// are those of `vesselcad serve`.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

struct Args {
    viewers: usize,
    editors: usize,
    seconds: f64,
    design: String,
    tolerance: f64,
    /// Viewers connect to `/ws?progressive=1` (hello without the whole GLB),
    /// as the viewer page does; `--full`: to `/ws`.
    progressive: bool,
    /// Serve a generated plant of this many vessels instead of `design`.
    plant: Option<usize>,
}

fn args() -> Args {
    let mut a = Args {
        viewers: 50,
        editors: 5,
        seconds: 20.0,
        design: concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/designs/small-plant.json"
        )
        .into(),
        tolerance: TessellationOptions::DEFAULT.tolerance,
        progressive: true,
        plant: None,
    };
    let mut list: Vec<String> = std::env::args().skip(1).collect();
    if let Some(k) = list.iter().position(|a| a == "--progressive") {
        list.remove(k);
    }
    if let Some(k) = list.iter().position(|a| a == "--full") {
        list.remove(k);
        a.progressive = false;
    }
    for pair in list.chunks(2) {
        let value = pair.get(1).map(String::as_str).unwrap_or("");
        let bad = || -> ! {
            eprintln!("bad value {value:?} for {}", pair[0]);
            std::process::exit(2)
        };
        match pair[0].as_str() {
            "--viewers" => a.viewers = value.parse().unwrap_or_else(|_| bad()),
            "--editors" => a.editors = value.parse().unwrap_or_else(|_| bad()),
            "--seconds" => a.seconds = value.parse().unwrap_or_else(|_| bad()),
            "--design" => a.design = value.into(),
            "--tolerance" => a.tolerance = value.parse().unwrap_or_else(|_| bad()),
            "--plant" => a.plant = Some(value.parse().unwrap_or_else(|_| bad())),
            other => {
                eprintln!("unknown argument {other}");
                std::process::exit(2)
            }
        }
    }
    a
}

/// What one viewer saw: revision → arrival time, resyncs, duplicates, gaps.
#[derive(Default)]
struct Seen {
    arrivals: HashMap<u64, Instant>,
    resyncs: usize,
    duplicates: usize,
    covered_by_resync: Vec<(u64, u64)>,
    last: u64,
    bytes: usize,
    error: Option<String>,
}

/// One POST /edit over a fresh loopback connection; the revision it got.
async fn post(address: std::net::SocketAddr, body: &str) -> Result<u64, String> {
    let mut stream = TcpStream::connect(address)
        .await
        .map_err(|e| e.to_string())?;
    let request = format!(
        "POST /edit HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\nContent-Type: application/json-patch+json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    );
    stream
        .write_all(request.as_bytes())
        .await
        .map_err(|e| e.to_string())?;
    let mut raw = Vec::new();
    stream
        .read_to_end(&mut raw)
        .await
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&raw);
    let (head, body) = text.split_once("\r\n\r\n").ok_or("no HTTP head")?;
    if !head.starts_with("HTTP/1.1 200") {
        return Err(format!("{head}\n{body}"));
    }
    let answer: Value = serde_json::from_str(body).map_err(|e| e.to_string())?;
    answer["revision"]
        .as_u64()
        .ok_or_else(|| "no revision".into())
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let k = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
    sorted[k.min(sorted.len() - 1)]
}

#[tokio::main(flavor = "multi_thread")]
async fn main() {
    let args = args();
    let dir = std::env::temp_dir().join(format!("vesselcad-loadtest-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let design_path = dir.join("design.json");
    match args.plant {
        Some(n) => {
            let plant = vesselcad::plant::generate_plant(n, 1).expect("a generated plant");
            std::fs::write(&design_path, vesselcad::design::to_canonical_json(&plant))
                .expect("cannot write the plant");
        }
        None => {
            std::fs::copy(&args.design, &design_path).expect("cannot copy the design");
        }
    }
    let design: Value =
        serde_json::from_str(&std::fs::read_to_string(&design_path).unwrap()).expect("design JSON");
    let vessels = design["vessels"].as_array().map_or(0, Vec::len).max(1);

    let mut options = ServeOptions::new(&design_path);
    options.port = 0;
    options.tessellation = TessellationOptions::chord(args.tolerance);
    let server = start(options).await.expect("cannot start the server");
    let address = server.address();
    println!(
        "loadtest: {} viewers{}, {} editors, {} s, {} ({} vessels), tolerance {} mm, http://{address}/",
        args.viewers,
        if args.progressive {
            " (progressive)"
        } else {
            " (whole GLB in each hello)"
        },
        args.editors,
        args.seconds,
        args.plant
            .map_or(args.design.clone(), |n| format!("generated plant of {n}")),
        vessels,
        args.tolerance
    );

    // Viewers: connect all, wait for every hello.
    let mut viewer_tasks = Vec::new();
    let stop_at = Arc::new(Mutex::new(None::<u64>));
    let (ready_tx, mut ready_rx) = tokio::sync::mpsc::channel::<()>(args.viewers.max(1));
    for _ in 0..args.viewers {
        let url = if args.progressive {
            format!("ws://{address}/ws?progressive=1")
        } else {
            format!("ws://{address}/ws")
        };
        let ready = ready_tx.clone();
        let stop_at = stop_at.clone();
        viewer_tasks.push(tokio::spawn(async move {
            // Whole-plant GLBs can pass tungstenite's default 16 MiB message limit.
            // A smaller read buffer than the default 128 KiB: tungstenite zeroes
            // it on every read, which took a sixth of the run's CPU (the
            // viewers share the machine with the server they measure).
            let config = WebSocketConfig::default()
                .max_message_size(None)
                .max_frame_size(None)
                .read_buffer_size(16 * 1024);
            let mut seen = Seen::default();
            let mut ws =
                match tokio_tungstenite::connect_async_with_config(url, Some(config), true).await {
                    Ok((ws, _)) => ws,
                    Err(e) => {
                        seen.error = Some(format!("cannot connect: {e}"));
                        let _ = ready.send(()).await;
                        return seen;
                    }
                };
            let mut greeted = false;
            let mut header: Option<Value> = None;
            loop {
                let next = tokio::time::timeout(Duration::from_secs(1), ws.next()).await;
                let message = match next {
                    Ok(Some(Ok(m))) => m,
                    Ok(Some(Err(e))) => {
                        seen.error = Some(e.to_string());
                        break;
                    }
                    Ok(None) => {
                        seen.error = Some("the server closed the socket".into());
                        break;
                    }
                    Err(_) => {
                        // Idle: finished once the editors are done and we are at the end.
                        if let Some(last) = *stop_at.lock().await
                            && seen.last >= last
                        {
                            break;
                        }
                        continue;
                    }
                };
                // A progressive hello or resync comes without a GLB.
                let message = match message {
                    Message::Text(t) => {
                        header = serde_json::from_str(&t).ok();
                        if header.as_ref().is_some_and(|h| h["progressive"] == true) {
                            Message::Binary(Default::default())
                        } else {
                            continue;
                        }
                    }
                    other => other,
                };
                if let Message::Binary(glb) = message {
                    let now = Instant::now();
                    seen.bytes += glb.len();
                    let Some(h) = header.take() else { continue };
                    let revision = h["revision"].as_u64().unwrap_or(0);
                    match h["type"].as_str() {
                        Some("hello") => {
                            seen.last = revision;
                            greeted = true;
                            let _ = ready.send(()).await;
                        }
                        Some("resync") => {
                            seen.resyncs += 1;
                            seen.covered_by_resync.push((seen.last + 1, revision));
                            seen.last = revision;
                        }
                        Some("delta") => {
                            if seen.arrivals.insert(revision, now).is_some() {
                                seen.duplicates += 1;
                            }
                            seen.last = seen.last.max(revision);
                        }
                        _ => {}
                    }
                    if let Some(last) = *stop_at.lock().await
                        && seen.last >= last
                    {
                        break;
                    }
                }
            }
            if !greeted {
                // Dropped before its hello (e.g. the server's send timeout on a
                // whole-plant GLB): counted as failed, not waited for.
                let _ = ready.send(()).await;
            }
            seen
        }));
    }
    drop(ready_tx);
    let connecting = Instant::now();
    for _ in 0..args.viewers {
        ready_rx.recv().await;
    }
    println!(
        "every viewer's hello in: {:.2} s",
        connecting.elapsed().as_secs_f64()
    );

    // Editors: edit back and forth until the time is up.
    let deadline = Instant::now() + Duration::from_secs_f64(args.seconds);
    let started = Instant::now();
    let mut editor_tasks = Vec::new();
    for e in 0..args.editors {
        let vessel = e % vessels;
        let nozzle = e / vessels;
        let original = design["vessels"][vessel]["nozzles"][nozzle]["projection"]
            .as_f64()
            .expect("the editor's nozzle");
        let path = format!("/vessels/{vessel}/nozzles/{nozzle}/projection");
        editor_tasks.push(tokio::spawn(async move {
            let mut sent: Vec<(u64, Instant)> = Vec::new();
            let mut k = 0u64;
            while Instant::now() < deadline {
                k += 1;
                let value = original + if k % 2 == 1 { 20.0 } else { 0.0 };
                let body = json!([{ "op": "replace", "path": path, "value": value }]).to_string();
                let t0 = Instant::now();
                match post(address, &body).await {
                    Ok(revision) => sent.push((revision, t0)),
                    Err(e) => panic!("edit refused: {e}"),
                }
            }
            sent
        }));
    }
    let mut sent: BTreeMap<u64, Instant> = BTreeMap::new();
    let mut duplicate_acks = 0;
    for t in editor_tasks {
        for (revision, t0) in t.await.expect("editor") {
            if sent.insert(revision, t0).is_some() {
                duplicate_acks += 1;
            }
        }
    }
    let elapsed = started.elapsed().as_secs_f64();
    let last = sent.keys().next_back().copied().unwrap_or(0);
    *stop_at.lock().await = Some(last);

    let mut latencies = Vec::new();
    let mut lost = 0usize;
    let mut duplicated = 0usize;
    let mut resyncs = 0usize;
    let mut bytes = 0usize;
    let mut worst_viewer_p99: f64 = 0.0;
    let mut failed = 0usize;
    for task in viewer_tasks {
        let seen = tokio::time::timeout(Duration::from_secs(60), task)
            .await
            .expect("a viewer did not finish")
            .expect("viewer");
        if let Some(e) = &seen.error {
            eprintln!("a viewer failed: {e}");
            failed += 1;
        }
        resyncs += seen.resyncs;
        duplicated += seen.duplicates;
        bytes += seen.bytes;
        let mut mine = Vec::new();
        for (&revision, &t0) in &sent {
            match seen.arrivals.get(&revision) {
                Some(&t1) => mine.push(t1.saturating_duration_since(t0).as_secs_f64() * 1e3),
                None => {
                    let covered = seen
                        .covered_by_resync
                        .iter()
                        .any(|&(a, b)| (a..=b).contains(&revision));
                    if !covered {
                        lost += 1;
                    }
                }
            }
        }
        mine.sort_by(f64::total_cmp);
        worst_viewer_p99 = worst_viewer_p99.max(percentile(&mine, 99.0));
        latencies.extend(mine);
    }
    latencies.sort_by(f64::total_cmp);
    let gaps = (1..=last).filter(|r| !sent.contains_key(r)).count();
    println!(
        "edits acknowledged:      {} (revisions 1..={last}, {gaps} missing, {duplicate_acks} acknowledged twice)",
        sent.len()
    );
    println!(
        "edits per second:        {:.1}",
        sent.len() as f64 / elapsed
    );
    println!(
        "edit → delta latency:    p50 {:.1} ms, p99 {:.1} ms, max {:.1} ms over {} deliveries (worst viewer p99 {:.1} ms)",
        percentile(&latencies, 50.0),
        percentile(&latencies, 99.0),
        latencies.last().copied().unwrap_or(f64::NAN),
        latencies.len(),
        worst_viewer_p99
    );
    println!("viewers failed:          {failed} of {}", args.viewers);
    println!("lost revisions:          {lost}");
    println!("duplicated revisions:    {duplicated}");
    println!("resyncs:                 {resyncs}");
    println!("bytes streamed:          {:.1} MB", bytes as f64 / 1e6);
    server.shutdown().await.expect("shutdown");
    let _ = std::fs::remove_dir_all(&dir);
    if lost + duplicated + gaps + duplicate_acks > 0 {
        std::process::exit(1);
    }
}
