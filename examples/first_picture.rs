//! Time to the first picture and to full detail of a plant in `vesselcad serve`
//! (a benchmark, not a unit test): starts the server in-process on loopback
//! with a generated plant, connects one client as the viewer page does and
//! prints how long each step takes, and the process's memory.
//!
//! ```sh
//! cargo run --profile test --example first_picture -- [--plant 1000] [--tolerance 1] [--runs 3]
//! ```
//!
//! The client does what the page does: it opens `/ws?progressive=1`, whose hello
//! names every stable id and gives each vessel's box (the page draws the boxes:
//! the first picture), then fetches every vessel's `/vessel.glb` with six
//! requests in flight, in the hello's order (the page orders them by distance
//! to the camera, which does not change the total), replacing the boxes: full
//! detail. Times are from the moment the client connects. The page's own work
//! (parsing the hello, drawing boxes, parsing GLBs) is not in these figures.
//!
//! Memory: the resident set after the model is built and served (no client
//! yet), again 3 s later (mimalloc returns memory unused for a second), after
//! the pages and the peak of the whole run (`VmHWM`), from `/proc/self/status`.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use futures_util::StreamExt;
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use vesselcad::mesh::TessellationOptions;
use vesselcad::server::{ServeOptions, start};

/// The binary's allocator, so that the server's figures are those of
/// `vesselcad serve`.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Requests in flight while fetching vessels, as the viewer page.
const IN_FLIGHT: usize = 6;

/// A figure of `/proc/self/status` (e.g. `VmRSS`), MB.
fn status_mb(key: &str) -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix(key)?.strip_prefix(':'))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// One GET over a fresh loopback connection; the body's length.
async fn get(address: std::net::SocketAddr, path: &str) -> Result<usize, String> {
    let mut stream = TcpStream::connect(address)
        .await
        .map_err(|e| e.to_string())?;
    let request = format!("GET {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\n\r\n");
    stream
        .write_all(request.as_bytes())
        .await
        .map_err(|e| e.to_string())?;
    let mut raw = Vec::new();
    stream
        .read_to_end(&mut raw)
        .await
        .map_err(|e| e.to_string())?;
    let end = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .ok_or("no HTTP head")?;
    let head = String::from_utf8_lossy(&raw[..end]);
    if !head.starts_with("HTTP/1.1 200") {
        return Err(format!("{path}: {head}"));
    }
    Ok(raw.len() - end - 4)
}

/// One page's load: (seconds to the hello, seconds to every vessel, bytes).
async fn page(address: std::net::SocketAddr) -> (f64, f64, usize) {
    let t0 = Instant::now();
    let (mut ws, _) = tokio_tungstenite::connect_async(format!("ws://{address}/ws?progressive=1"))
        .await
        .expect("cannot connect");
    let hello: Value = loop {
        match ws.next().await {
            Some(Ok(Message::Text(t))) => break serde_json::from_str(&t).expect("hello JSON"),
            Some(Ok(_)) => continue,
            other => panic!("no hello: {other:?}"),
        }
    };
    assert_eq!(hello["type"], "hello", "{hello}");
    let first = t0.elapsed().as_secs_f64();
    let mut bytes = serde_json::to_vec(&hello).map_or(0, |v| v.len());
    let tags: Vec<String> = hello["vessels"]
        .as_array()
        .expect("a progressive hello lists the vessels")
        .iter()
        .filter_map(|v| v["tag"].as_str().map(String::from))
        .collect();
    let tags = Arc::new(tags);
    let next = Arc::new(AtomicUsize::new(0));
    let mut workers = Vec::new();
    for _ in 0..IN_FLIGHT {
        let (tags, next) = (tags.clone(), next.clone());
        workers.push(tokio::spawn(async move {
            let mut bytes = 0;
            loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(tag) = tags.get(k) else { break bytes };
                bytes += get(address, &format!("/vessel.glb?tag={tag}"))
                    .await
                    .unwrap_or_else(|e| panic!("{tag}: {e}"));
            }
        }));
    }
    for w in workers {
        bytes += w.await.expect("worker");
    }
    let full = t0.elapsed().as_secs_f64();
    drop(ws);
    (first, full, bytes)
}

#[tokio::main(flavor = "multi_thread")]
async fn main() {
    let mut plant = 1000usize;
    let mut tolerance = 1.0f64;
    let mut runs = 3usize;
    let list: Vec<String> = std::env::args().skip(1).collect();
    for pair in list.chunks(2) {
        let value = pair.get(1).map(String::as_str).unwrap_or("");
        let bad = || -> ! {
            eprintln!("bad value {value:?} for {}", pair[0]);
            std::process::exit(2)
        };
        match pair[0].as_str() {
            "--plant" => plant = value.parse().unwrap_or_else(|_| bad()),
            "--tolerance" => tolerance = value.parse().unwrap_or_else(|_| bad()),
            "--runs" => runs = value.parse().unwrap_or_else(|_| bad()),
            other => {
                eprintln!("unknown argument {other}");
                std::process::exit(2)
            }
        }
    }
    let dir = std::env::temp_dir().join(format!("vesselcad-first-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let design_path = dir.join("design.json");
    let design = vesselcad::plant::generate_plant(plant, 1).expect("a generated plant");
    std::fs::write(&design_path, vesselcad::design::to_canonical_json(&design))
        .expect("cannot write the plant");
    drop(design);
    let before = status_mb("VmRSS");
    let mut options = ServeOptions::new(&design_path);
    options.port = 0;
    options.tessellation = TessellationOptions::chord(tolerance);
    let started = Instant::now();
    let server = start(options).await.expect("cannot start the server");
    let ready = started.elapsed().as_secs_f64();
    let served = status_mb("VmRSS");
    // mimalloc hands memory unused for a second back to the system: the
    // resident set a long session settles at.
    tokio::time::sleep(std::time::Duration::from_secs(3)).await;
    let settled = status_mb("VmRSS");
    let address = server.address();
    println!(
        "first_picture: generated plant of {plant} vessels at {tolerance} mm, http://{address}/"
    );
    println!("server ready in:         {ready:.2} s");
    println!(
        "resident set:            {before:.0} MB before the server, {served:.0} MB with the model served, \
         {settled:.0} MB 3 s later, peak {:.0} MB",
        status_mb("VmHWM")
    );
    for run in 1..=runs {
        let (first, full, bytes) = page(address).await;
        println!(
            "page {run}: first picture (hello with every box) {:.0} ms, full detail {:.2} s, {:.1} MB",
            first * 1e3,
            full,
            bytes as f64 / 1e6
        );
    }
    let end = status_mb("VmRSS");
    tokio::time::sleep(std::time::Duration::from_secs(3)).await;
    println!(
        "resident set:            {end:.0} MB at the end, {:.0} MB 3 s later, peak {:.0} MB",
        status_mb("VmRSS"),
        status_mb("VmHWM")
    );
    server.shutdown().await.expect("shutdown");
    let _ = std::fs::remove_dir_all(&dir);
}
