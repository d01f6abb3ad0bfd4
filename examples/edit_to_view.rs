//! Edit → view latency of the viewer page (a benchmark, not a unit test):
//! starts `vesselcad serve` in-process on loopback with a copy of the example
//! plant, and drives the page in headless Chromium
//! (`tests/support/edit-to-view.js`): a part's parameter typed and entered
//! again and again, each edit timed from the Enter key to the first animation
//! frame in which the page holds the edit's revision.
//!
//! ```sh
//! cargo run --profile test --example edit_to_view -- [--edits 40] [--tolerance 0.5]
//! #   [--part V-101/N1 --field projection --values 1500,1520]
//! ```
//!
//! Needs Debian's `/usr/bin/chromium` and `npm ci --prefix tests/support`.

use std::path::Path;
use std::process::Command;

use serde_json::Value;
use vesselcad::mesh::TessellationOptions;
use vesselcad::server::{ServeOptions, start};

/// The binary's allocator, so that the server's figures are those of
/// `vesselcad serve`.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

#[tokio::main(flavor = "multi_thread")]
async fn main() {
    let mut edits = 40usize;
    let mut tolerance = 0.5f64;
    let mut part = "V-101/N1".to_string();
    let mut field = "projection".to_string();
    let mut values = ("1520".to_string(), "1500".to_string());
    let list: Vec<String> = std::env::args().skip(1).collect();
    for pair in list.chunks(2) {
        let value = pair.get(1).map(String::as_str).unwrap_or("");
        let bad = || -> ! {
            eprintln!("bad value {value:?} for {}", pair[0]);
            std::process::exit(2)
        };
        match pair[0].as_str() {
            "--edits" => edits = value.parse().unwrap_or_else(|_| bad()),
            "--tolerance" => tolerance = value.parse().unwrap_or_else(|_| bad()),
            "--part" => part = value.to_string(),
            "--field" => field = value.to_string(),
            "--values" => {
                let (a, b) = value.split_once(',').unwrap_or_else(|| bad());
                values = (a.to_string(), b.to_string());
            }
            other => {
                eprintln!("unknown argument {other}");
                std::process::exit(2)
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("vesselcad-edit-to-view-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp folder");
    let design_path = dir.join("design.json");
    std::fs::copy(root.join("examples/designs/small-plant.json"), &design_path)
        .expect("cannot copy the example plant");
    let mut options = ServeOptions::new(&design_path);
    options.port = 0;
    options.tessellation = TessellationOptions::chord(tolerance);
    let server = start(options).await.expect("cannot start the server");
    let url = format!("http://{}/", server.address());
    let script = root.join("tests/support/edit-to-view.js");
    let (a, b) = values;
    let count = edits.to_string();
    let output = tokio::task::spawn_blocking(move || {
        Command::new("node")
            .arg(script)
            .args([url.as_str(), &part, &field, &a, &b, &count])
            .output()
            .expect("cannot run node")
    })
    .await
    .expect("node");
    server.shutdown().await.expect("shutdown");
    let _ = std::fs::remove_dir_all(&dir);
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        eprintln!(
            "edit-to-view.js failed: {stdout}\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
        std::process::exit(1);
    }
    let report: Value = serde_json::from_str(&stdout).expect("a JSON report");
    println!(
        "edit_to_view: example plant at {tolerance} mm, {} edits typed in the page",
        report["edits"]
    );
    println!(
        "Enter → frame showing the edit: p50 {:.1} ms, p99 {:.1} ms, max {:.1} ms",
        report["p50"].as_f64().unwrap_or(f64::NAN),
        report["p99"].as_f64().unwrap_or(f64::NAN),
        report["max"].as_f64().unwrap_or(f64::NAN)
    );
}
