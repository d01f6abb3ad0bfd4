//! Streaming to viewers over `/ws`: a hello with every id and the full GLB, then
//! per accepted edit a JSON delta and a GLB holding exactly the changed parts —
//! applying it to the old model (replace those nodes, drop the removed ones) gives
//! the new model node for node. Many viewers get every revision in order, and a
//! viewer that stops reading never blocks the editor or the others.

mod server_support;

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use futures_util::StreamExt;
use gltf::Gltf;
use serde_json::{Value, json};
use server_support::{ServerProcess, TIMEOUT, design_copy};
use tokio::net::TcpStream;
use tokio_tungstenite::tungstenite::Message;
use tokio_tungstenite::{MaybeTlsStream, WebSocketStream};

type Socket = WebSocketStream<MaybeTlsStream<TcpStream>>;

/// A part or nozzle node as a viewer sees it: transform, extras and, per patch,
/// vertex count and bounds.
type NodeView = (String, Vec<(String, usize, Vec<f64>)>);

/// Stable id → node view, and the vessel tags with their transforms.
#[derive(Debug, PartialEq, Default, Clone)]
struct ModelView {
    vessels: BTreeMap<String, String>,
    nodes: BTreeMap<String, NodeView>,
}

fn transform_of(node: &gltf::Node) -> String {
    format!(
        "{:?} {:?}",
        node.transform().decomposed(),
        node.extras().as_ref().map(|e| e.get())
    )
}

/// The view of a GLB (full or delta).
fn view(glb: &[u8]) -> ModelView {
    let gltf = Gltf::from_slice(glb).expect("a valid GLB");
    let mut out = ModelView::default();
    let scene = gltf.default_scene().unwrap();
    let plant = scene.nodes().next().unwrap();
    for vessel in plant.children() {
        let tag = vessel.name().unwrap().to_string();
        out.vessels.insert(tag.clone(), transform_of(&vessel));
        for part in vessel.children() {
            let patches = part
                .children()
                .map(|patch| {
                    let prim = patch.mesh().unwrap().primitives().next().unwrap();
                    let pos = prim.get(&gltf::Semantic::Positions).unwrap();
                    let bounds = [pos.min().unwrap(), pos.max().unwrap()]
                        .iter()
                        .flat_map(|v| v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
                        .collect();
                    (patch.name().unwrap().to_string(), pos.count(), bounds)
                })
                .collect();
            out.nodes.insert(
                format!("{tag}/{}", part.name().unwrap()),
                (transform_of(&part), patches),
            );
        }
    }
    out
}

/// Asserts two views are equal, naming the first id that differs.
fn same(applied: &ModelView, full: &ModelView, revision: usize) {
    assert_eq!(
        applied.vessels.keys().collect::<Vec<_>>(),
        full.vessels.keys().collect::<Vec<_>>(),
        "revision {revision}: vessels"
    );
    assert_eq!(
        applied.nodes.keys().collect::<Vec<_>>(),
        full.nodes.keys().collect::<Vec<_>>(),
        "revision {revision}: nodes"
    );
    for (tag, t) in &applied.vessels {
        assert!(
            t == &full.vessels[tag],
            "revision {revision}: vessel {tag} differs from the full model"
        );
    }
    for (id, n) in &applied.nodes {
        assert!(
            n == &full.nodes[id],
            "revision {revision}: {id} differs from the full model"
        );
    }
}

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

async fn connect(server: &ServerProcess) -> Socket {
    let url = format!("ws://{}/ws", server.address);
    tokio_tungstenite::connect_async(url).await.unwrap().0
}

/// POSTs an edit from a blocking thread (the HTTP helper is synchronous).
async fn post_edit(server: &ServerProcess, patch: Value) -> Value {
    let address = server.address;
    tokio::task::spawn_blocking(move || {
        let r =
            server_support::request(address, "POST", "/edit", &[], patch.to_string().as_bytes());
        assert_eq!(r.status, 200, "{}", r.text());
        r.json()
    })
    .await
    .unwrap()
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap()
}

#[test]
fn a_delta_replaces_exactly_the_changed_nodes() {
    let design = design_copy("horizontal-drum.json", "stream-delta");
    let server = ServerProcess::start(&design, &[]);
    runtime().block_on(async {
        let mut ws = connect(&server).await;
        let (hello, glb) = next_pair(&mut ws).await;
        assert_eq!(hello["type"], "hello");
        assert_eq!(hello["revision"], 0);
        let mut model = view(&glb);
        let ids: Vec<String> = serde_json::from_value(hello["ids"].clone()).unwrap();
        let mut expected_ids: Vec<String> =
            model.vessels.keys().cloned().chain(model.nodes.keys().cloned()).collect();
        expected_ids.sort();
        let mut sorted = ids.clone();
        sorted.sort();
        assert_eq!(sorted, expected_ids);

        let edits = [
            // A nozzle's projection: its neck, and the host patch it is cut into.
            json!([{ "op": "replace", "path": "/vessels/0/nozzles/0/projection", "value": 1700 }]),
            // The shell gets longer: H2, the supports and nozzles move or re-cut.
            json!([{ "op": "replace", "path": "/vessels/0/parts/1/shell/length", "value": 7600 }]),
            // A nozzle's service text: metadata only, no geometry.
            json!([{ "op": "replace", "path": "/vessels/0/nozzles/1/service", "value": "outlet to P-101" }]),
            // A nozzle is removed.
            json!([{ "op": "remove", "path": "/vessels/0/nozzles/6" }]),
            // The vessel moves: a frame change only.
            json!([{ "op": "replace", "path": "/vessels/0/placement/position", "value": [1000, 0, 2000] }]),
        ];
        for (k, patch) in edits.into_iter().enumerate() {
            let answer = post_edit(&server, patch).await;
            let (delta, glb) = next_pair(&mut ws).await;
            assert_eq!(delta["type"], "delta");
            assert_eq!(delta["revision"], k + 1);
            assert_eq!(delta["changed"], answer["changed"]);
            assert_eq!(delta["removed"], answer["removed"]);
            let changed: Vec<String> = serde_json::from_value(delta["changed"].clone()).unwrap();
            let removed: Vec<String> = serde_json::from_value(delta["removed"].clone()).unwrap();
            let part = view(&glb);
            // The delta holds exactly the changed parts and nozzles.
            let part_ids: Vec<&String> = part.nodes.keys().collect();
            let changed_parts: Vec<&String> = changed.iter().filter(|id| id.contains('/')).collect();
            assert_eq!(part_ids, changed_parts, "revision {}", k + 1);
            assert!(glb.len() < 400_000 || k == 1, "delta {} is {} bytes", k + 1, glb.len());
            // Apply it as the viewer does.
            for id in &removed {
                model.nodes.remove(id);
                model.vessels.remove(id);
            }
            for (tag, transform) in part.vessels {
                if changed.contains(&tag) || !model.vessels.contains_key(&tag) {
                    model.vessels.insert(tag, transform);
                }
            }
            assert!(
                changed.iter().all(|id| part.nodes.contains_key(id) || model.vessels.contains_key(id)),
                "every changed id is in the delta"
            );
            model.nodes.extend(part.nodes);
            let full = server.request("GET", "/model.glb", &[], b"");
            assert_eq!(full.header("x-vesselcad-revision"), Some(&*(k + 1).to_string()));
            same(&model, &view(&full.body), k + 1);
        }
        let _ = ws.close(None).await;
    });
}

#[test]
fn many_viewers_get_every_revision_and_a_stalled_one_blocks_nobody() {
    let design = design_copy("horizontal-drum.json", "stream-many");
    // The stalled viewer must outlast the whole editing phase (resynced, not
    // dropped), however slow the machine: a long socket timeout.
    let server = ServerProcess::start(&design, &["--viewer-timeout", "600"]);
    runtime().block_on(async {
        // A viewer that never reads, with a tiny receive window.
        let socket = tokio::net::TcpSocket::new_v4().unwrap();
        socket.set_recv_buffer_size(4096).unwrap();
        let stream = socket.connect(server.address).await.unwrap();
        let (mut stalled, _) = tokio_tungstenite::client_async(
            format!("ws://{}/ws", server.address),
            MaybeTlsStream::Plain(stream),
        )
        .await
        .unwrap();
        let mut viewers = Vec::new();
        for _ in 0..4 {
            let mut ws = connect(&server).await;
            let (hello, _) = next_pair(&mut ws).await;
            assert_eq!(hello["revision"], 0);
            viewers.push(ws);
        }
        let readers: Vec<_> = viewers
            .into_iter()
            .map(|mut ws| {
                tokio::spawn(async move {
                    let mut revisions = Vec::new();
                    while revisions.last() != Some(&EDITS) {
                        let (delta, _) = next_pair(&mut ws).await;
                        assert_eq!(delta["type"], "delta");
                        revisions.push(delta["revision"].as_u64().unwrap());
                    }
                    revisions
                })
            })
            .collect();
        const EDITS: u64 = 80;
        let start = Instant::now();
        for k in 1..=EDITS {
            // Alternate the shell thickness: every part is meshed again, so each
            // delta is large and the stalled viewer's socket fills up.
            let od = if k % 2 == 0 { 2400 } else { 2450 };
            let answer = post_edit(
                &server,
                json!([{ "op": "replace", "path": "/vessels/0/parts/1/shell/od", "value": od }]),
            )
            .await;
            assert_eq!(answer["revision"], k);
        }
        let editing = start.elapsed();
        for reader in readers {
            let revisions = tokio::time::timeout(TIMEOUT, reader)
                .await
                .unwrap()
                .unwrap();
            assert_eq!(
                revisions,
                (1..=EDITS).collect::<Vec<_>>(),
                "lost, duplicated or reordered"
            );
        }
        // The stalled viewer now reads: it is consistent (each delta follows the
        // previous revision, or a resync restarts it) and reaches the last one.
        let mut at = 0;
        let mut resyncs = 0;
        let deadline = Instant::now() + Duration::from_secs(60);
        let (hello, _) = next_pair(&mut stalled).await;
        assert_eq!(hello["type"], "hello");
        while at < EDITS && Instant::now() < deadline {
            let (header, _) = next_pair(&mut stalled).await;
            let revision = header["revision"].as_u64().unwrap();
            match header["type"].as_str() {
                Some("delta") => assert_eq!(revision, at + 1, "gap without a resync"),
                Some("resync") => {
                    resyncs += 1;
                    assert!(header["reason"].as_str().unwrap().contains("fell behind"));
                }
                other => panic!("unexpected {other:?}"),
            }
            at = revision;
        }
        assert_eq!(at, EDITS);
        // 80 deltas of the whole drum (~0.3 MB each) overflow the stalled
        // viewer's socket buffers and then its queue of VIEWER_QUEUE updates.
        assert!(resyncs >= 1, "the stalled viewer was never resynced");
        eprintln!(
            "{EDITS} edits in {editing:?}; the stalled viewer was resynced {resyncs} time(s)"
        );
    });
}

#[test]
fn a_viewer_message_over_the_limit_closes_only_that_viewer() {
    let design = design_copy("storage-tank.json", "stream-oversized");
    let server = ServerProcess::start(&design, &[]);
    runtime().block_on(async {
        use futures_util::SinkExt;
        let mut loud = connect(&server).await;
        let mut quiet = connect(&server).await;
        next_pair(&mut loud).await;
        next_pair(&mut quiet).await;
        let big = "x".repeat(vesselcad::server::MAX_VIEWER_MESSAGE + 1);
        loud.send(Message::Text(big.into())).await.unwrap();
        // The server drops that viewer: its stream ends (close frame or error).
        let ended = tokio::time::timeout(TIMEOUT, async {
            loop {
                match loud.next().await {
                    None | Some(Err(_)) | Some(Ok(Message::Close(_))) => break,
                    Some(Ok(_)) => {}
                }
            }
        })
        .await;
        assert!(ended.is_ok(), "the oversized viewer was not closed");
        // The other viewer and the editor carry on.
        let answer = post_edit(
            &server,
            json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 15 }]),
        )
        .await;
        let (delta, _) = next_pair(&mut quiet).await;
        assert_eq!(delta["revision"], answer["revision"]);
    });
}

#[test]
fn a_quiet_viewer_outlives_the_idle_timeout() {
    let design = design_copy("horizontal-drum.json", "stream-quiet");
    let server = ServerProcess::start(&design, &["--idle-timeout", "1"]);
    runtime().block_on(async {
        let mut ws = connect(&server).await;
        let (hello, _) = next_pair(&mut ws).await;
        assert_eq!(hello["type"], "hello");
        // Three idle timeouts with no edit: the server's pings keep it alive
        // (the client answers them while it waits for the next message).
        let quiet = tokio::time::timeout(Duration::from_secs(3), ws.next()).await;
        if let Ok(Some(message)) = quiet {
            assert!(
                message.unwrap().is_ping(),
                "only pings while nothing changes"
            );
        }
        let answer = post_edit(
            &server,
            json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 5 }]),
        )
        .await;
        let (delta, _) = next_pair(&mut ws).await;
        assert_eq!(delta["revision"], answer["revision"]);
    });
}

/// Applies a delta to a viewer's model as the viewer does.
fn apply_delta(model: &mut ModelView, delta: &Value, glb: &[u8]) {
    let changed: Vec<String> = serde_json::from_value(delta["changed"].clone()).unwrap();
    let removed: Vec<String> = serde_json::from_value(delta["removed"].clone()).unwrap();
    let part = view(glb);
    for id in &removed {
        model.nodes.remove(id);
        model.vessels.remove(id);
    }
    for (tag, transform) in part.vessels {
        if changed.contains(&tag) || !model.vessels.contains_key(&tag) {
            model.vessels.insert(tag, transform);
        }
    }
    model.nodes.extend(part.nodes);
}

/// Editors working at once: each delta is written after the session lock is
/// let go, yet every viewer gets each revision once, in order, and the deltas
/// applied give the server's final model.
#[test]
fn concurrent_editors_reach_every_viewer_once_in_revision_order() {
    const EDITORS: usize = 4;
    const EACH: usize = 8;
    let total = (EDITORS * EACH) as u64;
    let design = design_copy("small-plant.json", "stream-concurrent");
    let server = ServerProcess::start(&design, &[]);
    runtime().block_on(async {
        let mut readers = Vec::new();
        for _ in 0..3 {
            let mut ws = connect(&server).await;
            let (hello, glb) = next_pair(&mut ws).await;
            assert_eq!(hello["revision"], 0);
            readers.push(tokio::spawn(async move {
                let mut model = view(&glb);
                let mut revisions = Vec::new();
                while revisions.len() < total as usize {
                    let (delta, glb) = next_pair(&mut ws).await;
                    assert_eq!(delta["type"], "delta");
                    revisions.push(delta["revision"].as_u64().unwrap());
                    apply_delta(&mut model, &delta, &glb);
                }
                (revisions, model)
            }));
        }
        let editors: Vec<_> = (0..EDITORS)
            .map(|e| {
                let address = server.address;
                tokio::task::spawn_blocking(move || {
                    (0..EACH)
                        .map(|k| {
                            // Each vessel's first nozzle, from its projection in the
                            // example plant outwards.
                            let value = [1500, 1500, 1400, 4300][e] + 20 * (k % 3);
                            let path = format!("/vessels/{e}/nozzles/0/projection");
                            let patch = json!([{ "op": "replace", "path": path, "value": value }]);
                            let r = server_support::request(
                                address,
                                "POST",
                                "/edit",
                                &[],
                                patch.to_string().as_bytes(),
                            );
                            assert_eq!(r.status, 200, "{}", r.text());
                            r.json()["revision"].as_u64().unwrap()
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        let mut acknowledged = Vec::new();
        for editor in editors {
            acknowledged.extend(editor.await.unwrap());
        }
        acknowledged.sort_unstable();
        assert_eq!(acknowledged, (1..=total).collect::<Vec<_>>());
        let full = server.request("GET", "/model.glb", &[], b"");
        assert_eq!(
            full.header("x-vesselcad-revision"),
            Some(&*total.to_string())
        );
        let full = view(&full.body);
        for reader in readers {
            let (revisions, model) = tokio::time::timeout(TIMEOUT, reader)
                .await
                .unwrap()
                .unwrap();
            assert_eq!(
                revisions,
                (1..=total).collect::<Vec<_>>(),
                "lost, duplicated or reordered"
            );
            same(&model, &full, total as usize);
        }
    });
}
