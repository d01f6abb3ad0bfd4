//! Compact deltas on `/ws`: a viewer that connects with `compress=meshopt`
//! (as the viewer page does) gets each edit's delta GLB
//! `EXT_meshopt_compression`-compressed. It holds the same nodes and the same
//! triangles as the plain delta a plain viewer gets at the same revision
//! (decoded here with the meshopt crate, independently of the writer), passes
//! the Khronos validator, and is smaller. Under `serve --quantize` it is also
//! quantized, every vertex within the quarter of the tolerance given to
//! quantization. An unknown `compress` value is refused.

mod common;
mod server_support;

use std::collections::BTreeMap;
use std::time::Duration;

use futures_util::StreamExt;
use glam::{DMat4, DVec3};
use serde_json::{Value, json};
use server_support::{ServerProcess, design_copy};
use tokio_tungstenite::tungstenite::Message;

use common::glb::{Glb, validate};

type Socket =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

const TIMEOUT: Duration = Duration::from_secs(60);

/// The next (header, GLB) pair from a viewer socket.
async fn next_pair(ws: &mut Socket) -> (Value, Vec<u8>) {
    let mut header = None;
    loop {
        let message = tokio::time::timeout(TIMEOUT, ws.next())
            .await
            .expect("no message within the timeout")
            .expect("socket closed")
            .expect("socket error");
        match message {
            Message::Text(text) => header = Some(serde_json::from_str(&text).unwrap()),
            Message::Binary(bytes) => {
                return (header.expect("GLB without a header"), bytes.to_vec());
            }
            _ => {}
        }
    }
}

/// Each patch node's triangles by its path (`vessel/part/patch`), corners in
/// the part's frame (the patch node's transform applied: a quantized mesh's
/// dequantization), m.
fn triangles(glb: &Glb) -> BTreeMap<String, Vec<[DVec3; 3]>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![(glb.root(), String::new())];
    while let Some((node, path)) = stack.pop() {
        let name = glb.node(node)["name"].as_str().unwrap_or("").to_string();
        let path = if path.is_empty() {
            name
        } else {
            format!("{path}/{name}")
        };
        if let Some(mesh) = glb.node(node)["mesh"].as_u64() {
            let matrix: DMat4 = glb.local_matrix(node);
            let p = glb.primitive(mesh as usize);
            let at: Vec<DVec3> = p
                .positions
                .iter()
                .map(|&v| matrix.transform_point3(v))
                .collect();
            let tris = p
                .indices
                .chunks(3)
                .map(|t| [at[t[0] as usize], at[t[1] as usize], at[t[2] as usize]])
                .collect();
            assert!(out.insert(path.clone(), tris).is_none(), "{path} twice");
        }
        for child in glb.children(node) {
            stack.push((child, path.clone()));
        }
    }
    out
}

/// A triangle as a sorted list of its corners (compression may reorder
/// triangles and rotate their corners).
fn key(t: &[DVec3; 3]) -> [[f64; 3]; 3] {
    let mut c = t.map(|p| p.to_array());
    c.sort_by(|x, y| x.partial_cmp(y).unwrap());
    c
}

/// Edits the drum (a nozzle's projection, then the shell's length) with a
/// plain and a compact viewer connected; returns each delta's (plain,
/// compact) GLB.
fn deltas(extra: &[&str], test: &str) -> Vec<(Vec<u8>, Vec<u8>)> {
    let design = design_copy("horizontal-drum.json", test);
    let server = ServerProcess::start(&design, extra);
    let address = server.address;
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async {
        let connect = |query: &'static str| async move {
            let url = format!("ws://{address}/ws{query}");
            tokio_tungstenite::connect_async(url).await.unwrap().0
        };
        let mut plain = connect("").await;
        let mut compact = connect("?compress=meshopt").await;
        let (hello, _) = next_pair(&mut plain).await;
        assert_eq!(hello["type"], "hello");
        let (hello, _) = next_pair(&mut compact).await;
        assert_eq!(hello["type"], "hello");
        let edits = [
            json!([{ "op": "replace", "path": "/vessels/0/nozzles/0/projection", "value": 1700 }]),
            json!([{ "op": "replace", "path": "/vessels/0/parts/1/shell/length", "value": 7600 }]),
        ];
        let mut out = Vec::new();
        for (k, patch) in edits.into_iter().enumerate() {
            let r = tokio::task::spawn_blocking(move || {
                server_support::request(address, "POST", "/edit", &[], patch.to_string().as_bytes())
            })
            .await
            .unwrap();
            assert_eq!(r.status, 200, "{}", r.text());
            let (a, plain_glb) = next_pair(&mut plain).await;
            let (b, compact_glb) = next_pair(&mut compact).await;
            assert_eq!(a["type"], "delta");
            assert_eq!(a, b, "both viewers get the same delta header");
            assert_eq!(a["revision"], k + 1);
            out.push((plain_glb, compact_glb));
        }
        out
    })
}

#[test]
fn a_compact_viewer_gets_the_same_triangles_meshopt_compressed() {
    for (k, (plain, compact)) in deltas(&[], "compact-deltas").into_iter().enumerate() {
        let (p, c) = (Glb::parse(&plain), Glb::parse(&compact));
        println!(
            "delta {}: plain {} bytes, meshopt {} bytes ({:.1} %)",
            k + 1,
            plain.len(),
            compact.len(),
            100.0 * compact.len() as f64 / plain.len() as f64
        );
        assert!(
            !p.json["extensionsUsed"].to_string().contains("meshopt"),
            "the plain delta is not compressed"
        );
        assert_eq!(
            c.json["extensionsRequired"],
            json!(["EXT_meshopt_compression"])
        );
        assert!(compact.len() < plain.len(), "delta {}", k + 1);
        let (tp, tc) = (triangles(&p), triangles(&c));
        assert_eq!(
            tp.keys().collect::<Vec<_>>(),
            tc.keys().collect::<Vec<_>>(),
            "the same patch nodes"
        );
        assert!(!tp.is_empty());
        for (path, expected) in &tp {
            // Lossless: the same corners, bit for bit.
            let sorted = |t: &[[DVec3; 3]]| {
                let mut keys: Vec<_> = t.iter().map(key).collect();
                keys.sort_by(|x, y| x.partial_cmp(y).unwrap());
                keys
            };
            assert!(
                sorted(expected) == sorted(&tc[path]),
                "{path}: triangles differ"
            );
        }
        if let Some(report) = validate(&format!("compact-delta-{k}"), &compact) {
            assert_eq!(report["numErrors"], 0, "{report}");
            assert_eq!(report["numWarnings"], 0, "{report}");
        }
    }
}

#[test]
fn quantized_deltas_hold_the_quantization_budget() {
    // The drum at 1 mm: meshed to 0.75 mm, a quarter of a millimetre for
    // quantization.
    let budget_m = 0.25e-3;
    for (k, (plain, compact)) in deltas(&["--tolerance", "1", "--quantize"], "quantized-deltas")
        .into_iter()
        .enumerate()
    {
        let (p, c) = (Glb::parse(&plain), Glb::parse(&compact));
        println!(
            "delta {}: plain {} bytes, quantized + meshopt {} bytes ({:.1} %)",
            k + 1,
            plain.len(),
            compact.len(),
            100.0 * compact.len() as f64 / plain.len() as f64
        );
        let used = c.json["extensionsUsed"].to_string();
        assert!(
            used.contains("KHR_mesh_quantization") && used.contains("EXT_meshopt_compression"),
            "{used}"
        );
        let (tp, tc) = (triangles(&p), triangles(&c));
        assert_eq!(tp.keys().collect::<Vec<_>>(), tc.keys().collect::<Vec<_>>());
        let mut worst = 0.0f64;
        for (path, expected) in &tp {
            let got = &tc[path];
            assert_eq!(got.len(), expected.len(), "{path}");
            // Each drawn corner within the budget of a plain corner (+ f32
            // rounding of the plain positions, m).
            let mut plain_points: Vec<DVec3> = expected.iter().flatten().copied().collect();
            plain_points.sort_by(|a, b| a.x.total_cmp(&b.x));
            for point in got.iter().flatten() {
                let from = plain_points.partition_point(|q| q.x < point.x - budget_m);
                let nearest = plain_points[from..]
                    .iter()
                    .take_while(|q| q.x <= point.x + budget_m)
                    .map(|q| q.distance(*point))
                    .fold(f64::INFINITY, f64::min);
                worst = worst.max(nearest);
                assert!(
                    nearest <= budget_m + 1e-6,
                    "{path}: a corner {nearest} m away"
                );
            }
        }
        println!("delta {}: farthest corner {:.4} mm", k + 1, worst * 1e3);
        if let Some(report) = validate(&format!("quantized-delta-{k}"), &compact) {
            assert_eq!(report["numErrors"], 0, "{report}");
            assert_eq!(report["numWarnings"], 0, "{report}");
        }
    }
}

#[test]
fn an_unknown_compression_is_refused() {
    let design = design_copy("horizontal-drum.json", "compact-refused");
    let server = ServerProcess::start(&design, &[]);
    let url = format!("ws://{}/ws?compress=draco", server.address);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    match runtime.block_on(tokio_tungstenite::connect_async(url)) {
        Err(tokio_tungstenite::tungstenite::Error::Http(response)) => {
            assert_eq!(response.status(), 400);
            let body = String::from_utf8_lossy(response.body().as_deref().unwrap_or_default());
            assert!(
                body.contains("compress") && body.contains("draco"),
                "{body}"
            );
        }
        other => panic!("not refused: {:?}", other.map(|_| ())),
    }
}
