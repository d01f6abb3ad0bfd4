//! Progressive loading and per-vessel edits in `vesselcad serve`: a viewer on
//! `/ws?progressive=1` gets every id and each vessel's box without a GLB, then
//! fetches `/vessel.glb?tag=T` (the vessel's nodes exactly as in `/model.glb`,
//! with an `ETag` that changes only when the vessel does); edits confined to
//! vessels, edits that rename or add vessels, and the per-vessel design and
//! drawing routes keep the session's design equal to the model's.

mod server_support;

use std::collections::BTreeMap;

use futures_util::StreamExt;
use gltf::Gltf;
use serde_json::{Value, json};
use server_support::{ServerProcess, TIMEOUT, design_copy};
use tokio_tungstenite::tungstenite::Message;

/// Each node of a GLB by stable id: its transform, extras and patch bounds.
fn nodes(glb: &[u8]) -> BTreeMap<String, String> {
    let gltf = Gltf::from_slice(glb).expect("a valid GLB");
    let scene = gltf.default_scene().unwrap();
    let plant = scene.nodes().next().unwrap();
    let mut out = BTreeMap::new();
    for vessel in plant.children() {
        let tag = vessel.name().unwrap().to_string();
        let describe = |node: &gltf::Node| {
            let patches: Vec<String> = node
                .children()
                .filter_map(|p| {
                    let prim = p.mesh()?.primitives().next().unwrap();
                    let pos = prim.get(&gltf::Semantic::Positions).unwrap();
                    Some(format!(
                        "{} {} {:?} {:?}",
                        p.name().unwrap(),
                        pos.count(),
                        pos.min(),
                        pos.max()
                    ))
                })
                .collect();
            format!(
                "{:?} {:?} {patches:?}",
                node.transform().decomposed(),
                node.extras().as_ref().map(|e| e.get())
            )
        };
        out.insert(tag.clone(), describe(&vessel));
        for part in vessel.children() {
            out.insert(format!("{tag}/{}", part.name().unwrap()), describe(&part));
        }
    }
    out
}

fn vessel_glb(server: &ServerProcess, tag: &str) -> server_support::Response {
    let r = server.request("GET", &format!("/vessel.glb?tag={tag}"), &[], b"");
    assert_eq!(r.status, 200, "{}", r.text());
    r
}

#[test]
fn a_progressive_viewer_gets_boxes_then_each_vessel_as_in_the_whole_model() {
    let design = design_copy("small-plant.json", "progressive");
    let server = ServerProcess::start(&design, &[]);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    let whole = server.request("GET", "/model.glb", &[], b"");
    assert_eq!(whole.status, 200);
    let whole = nodes(&whole.body);
    runtime.block_on(async {
        let url = format!("ws://{}/ws?progressive=1", server.address);
        let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
        let hello = match tokio::time::timeout(TIMEOUT, ws.next()).await {
            Ok(Some(Ok(Message::Text(t)))) => serde_json::from_str::<Value>(&t).unwrap(),
            other => panic!("expected a text hello, got {other:?}"),
        };
        assert_eq!(hello["type"], "hello");
        assert_eq!(hello["progressive"], true);
        let mut ids: Vec<String> = serde_json::from_value(hello["ids"].clone()).unwrap();
        ids.sort();
        assert_eq!(ids, whole.keys().cloned().collect::<Vec<_>>());
        let boxes = hello["vessels"].as_array().unwrap();
        let tags: Vec<&str> = boxes.iter().map(|b| b["tag"].as_str().unwrap()).collect();
        assert_eq!(tags, ["V-101", "V-102", "C-201", "TK-301"]);
        for b in boxes {
            let (min, max) = (&b["min"], &b["max"]);
            for k in 0..3 {
                assert!(min[k].as_f64().unwrap() < max[k].as_f64().unwrap(), "{b}");
            }
        }
        // No GLB follows the hello: the next message is the first delta's header.
        let answer = server.edit(&json!([
            { "op": "replace", "path": "/vessels/2/nozzles/0/service", "value": "feed from E-1" }
        ]));
        assert_eq!(answer.status, 200, "{}", answer.text());
        match tokio::time::timeout(TIMEOUT, ws.next()).await {
            Ok(Some(Ok(Message::Text(t)))) => {
                let delta: Value = serde_json::from_str(&t).unwrap();
                assert_eq!(delta["type"], "delta");
                assert_eq!(delta["revision"], 1);
                assert_eq!(delta["changed"], json!(["C-201/N1"]));
            }
            other => panic!("expected the delta's header, got {other:?}"),
        }
    });

    // Each vessel's GLB holds its nodes exactly as the whole model did (C-201's
    // nozzle N1 aside: its service changed since).
    let mut etags = BTreeMap::new();
    for tag in ["V-101", "V-102", "C-201", "TK-301"] {
        let r = vessel_glb(&server, tag);
        assert_eq!(r.header("content-type"), Some("model/gltf-binary"));
        assert_eq!(r.header("x-vesselcad-revision"), Some("1"));
        let one = nodes(&r.body);
        assert!(
            one.keys()
                .all(|id| id == tag || id.starts_with(&format!("{tag}/")))
        );
        for (id, node) in &one {
            if id != "C-201/N1" {
                assert_eq!(node, &whole[id], "{id}");
            }
        }
        let expected = whole
            .keys()
            .filter(|id| *id == tag || id.starts_with(&format!("{tag}/")));
        assert_eq!(one.keys().collect::<Vec<_>>(), expected.collect::<Vec<_>>());
        let vessel_revision = if tag == "C-201" { "1" } else { "0" };
        assert_eq!(
            r.header("x-vesselcad-vessel-revision"),
            Some(vessel_revision),
            "{tag}"
        );
        etags.insert(tag, r.header("etag").unwrap().to_string());
    }
    // The ETag: 304 while the vessel is unchanged, a new one after its edit.
    let etag = etags["V-101"].clone();
    let r = server.request(
        "GET",
        "/vessel.glb?tag=V-101",
        &[("If-None-Match", &etag)],
        b"",
    );
    assert_eq!(r.status, 304);
    assert!(r.body.is_empty());
    let moved = server.edit(&json!([
        { "op": "replace", "path": "/vessels/0/placement/position", "value": [1000, 0, 2000] }
    ]));
    assert_eq!(moved.status, 200, "{}", moved.text());
    let r = server.request(
        "GET",
        "/vessel.glb?tag=V-101",
        &[("If-None-Match", &etag)],
        b"",
    );
    assert_eq!(r.status, 200);
    assert_ne!(r.header("etag"), Some(etag.as_str()));
    assert_eq!(r.header("x-vesselcad-vessel-revision"), Some("2"));
    let r = server.request(
        "GET",
        "/vessel.glb?tag=V-102",
        &[("If-None-Match", &etags["V-102"])],
        b"",
    );
    assert_eq!(r.status, 304, "an edit of V-101 leaves V-102's ETag");

    let r = server.request("GET", "/vessel.glb?tag=NOPE", &[], b"");
    assert_eq!(r.status, 404, "{}", r.text());
    assert!(r.text().contains("V-101"), "{}", r.text());
}

#[test]
fn edits_in_vessels_renames_and_new_vessels_keep_the_design_in_step() {
    let design = design_copy("small-plant.json", "scoped-edits");
    let server = ServerProcess::start(&design, &[]);
    let model_design = || server.get_json("/design.json");
    let base = model_design();

    // Inside two vessels at once (a move between them included): one edit.
    let r = server.edit(&json!([
        { "op": "test", "path": "/vessels/1/nozzles/0/projection", "value": 1500 },
        { "op": "replace", "path": "/vessels/1/nozzles/0/projection", "value": 1550 },
        { "op": "replace", "path": "/vessels/3/nozzles/2/service", "value": "breather" },
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let changed: Vec<String> = serde_json::from_value(r.json()["changed"].clone()).unwrap();
    assert!(changed.contains(&"V-102/N1".to_string()), "{changed:?}");
    assert!(changed.contains(&"TK-301/N3".to_string()), "{changed:?}");
    assert!(
        changed
            .iter()
            .all(|id| id.starts_with("V-102") || id.starts_with("TK-301")),
        "{changed:?}"
    );
    let after = model_design();
    assert_eq!(after["vessels"][1]["nozzles"][0]["projection"], 1550.0);
    assert_eq!(after["vessels"][3]["nozzles"][2]["service"], "breather");
    assert_eq!(after["vessels"][0], base["vessels"][0]);
    let one = server.get_json("/vessel.json?vessel=V-102");
    assert_eq!(one["index"], 1);
    assert_eq!(one["revision"], 1);
    assert_eq!(one["vessel"], after["vessels"][1]);

    // A failed `test` inside a vessel: refused as in the whole document.
    let r = server.edit(&json!([
        { "op": "test", "path": "/vessels/1/nozzles/0/projection", "value": 1500 },
        { "op": "replace", "path": "/vessels/1/nozzles/0/projection", "value": 1600 },
    ]));
    assert_eq!(r.status, 409, "{}", r.text());
    assert!(
        r.text().contains("/vessels/1/nozzles/0/projection"),
        "{}",
        r.text()
    );
    // A broken rule inside a vessel names its path.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/1/parts/1/shell/length", "value": -5 },
    ]));
    assert_eq!(r.status, 422, "{}", r.text());
    assert!(r.text().contains("vessels[1].parts[1]"), "{}", r.text());
    // A wrong type inside a vessel: the whole document's syntax error and path.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/1/parts/1/shell/length", "value": "long" },
    ]));
    assert_eq!(r.status, 422, "{}", r.text());
    assert!(
        r.text().contains("vessels[1].parts[1].shell.length"),
        "{}",
        r.text()
    );

    // A rename goes through the whole design: the old id is removed.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/0/tag", "value": "V-100" },
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let answer = r.json();
    assert!(
        answer["removed"]
            .as_array()
            .unwrap()
            .contains(&json!("V-101")),
        "{answer}"
    );
    assert!(
        answer["changed"]
            .as_array()
            .unwrap()
            .contains(&json!("V-100/S1")),
        "{answer}"
    );
    // A new vessel, copied from another.
    let mut copy = model_design()["vessels"][1].clone();
    copy["tag"] = json!("V-103");
    copy["placement"]["position"] = json!([40000, 40000, 0]);
    let r = server.edit(&json!([{ "op": "add", "path": "/vessels/-", "value": copy }]));
    assert_eq!(r.status, 200, "{}", r.text());
    let now = model_design();
    let tags: Vec<&str> = now["vessels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["tag"].as_str().unwrap())
        .collect();
    assert_eq!(tags, ["V-100", "V-102", "C-201", "TK-301", "V-103"]);
    assert_eq!(
        vessel_glb(&server, "V-103").header("x-vesselcad-vessel-revision"),
        Some("3")
    );
    let glb = server.request("GET", "/model.glb", &[], b"");
    let ids = nodes(&glb.body);
    assert!(
        ids.contains_key("V-103/N1") && ids.contains_key("V-100") && !ids.contains_key("V-101")
    );
}

#[test]
fn drawings_come_from_the_vessel_alone_as_svg_and_dxf() {
    let design = design_copy("small-plant.json", "drawings");
    let server = ServerProcess::start(&design, &[]);
    let svg = server.request("GET", "/drawing.svg?vessel=C-201", &[], b"");
    assert_eq!(svg.status, 200, "{}", svg.text());
    assert!(svg.text().contains("<svg") && svg.text().contains("C-201"));
    let dxf = server.request("GET", "/drawing.dxf?vessel=C-201", &[], b"");
    assert_eq!(dxf.status, 200, "{}", dxf.text());
    assert!(
        dxf.header("content-disposition")
            .unwrap()
            .contains("C-201.dxf")
    );
    assert!(dxf.text().contains("SECTION") && dxf.text().contains("C-201"));
    // After an edit of the vessel the sheet follows it.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/2/nozzles/0/service", "value": "feed from E-17" }
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let svg = server.request("GET", "/drawing.svg?vessel=C-201", &[], b"");
    assert!(
        svg.text().contains("E-17"),
        "the sheet shows the edited service"
    );
    let r = server.request("GET", "/drawing.dxf?vessel=NOPE", &[], b"");
    assert_eq!(r.status, 404, "{}", r.text());
}

#[test]
fn the_session_model_keeps_no_drawing_views() {
    let design = design_copy("small-plant.json", "no-views");
    let session = vesselcad::server::session::Session::open(
        &design,
        vesselcad::mesh::TessellationOptions::DEFAULT,
    )
    .unwrap();
    let world = session.model().world();
    let views = world
        .iter_entities()
        .filter(|e| e.contains::<vesselcad::components::VesselViews>())
        .count();
    assert_eq!(views, 0, "serve projects no drawing views of the plant");
    // Every vessel is still in the model, meshed.
    assert_eq!(session.vessel_tags().len(), 4);
    assert!(session.model().mesh_bytes() > 0);
}

/// A plain `/ws` viewer of a plant whose whole GLB passes the server's limit
/// (`--whole-glb-limit`, 16 MiB by default; 100 kB here for a 12-vessel plant
/// at 2 mm): a coarse whole of boxes first, then each vessel in its own
/// message — none near the whole plant's size — then deltas; what it puts
/// together is the whole model of `/model.glb`. Before, its hello carried the
/// whole plant in one message (at 1,000 vessels, longer than the send timeout:
/// dropped).
#[test]
fn a_plain_viewer_of_a_large_plant_gets_boxes_then_each_vessel() {
    let dir = tempfile::Builder::new()
        .prefix("vesselcad-pushed-")
        .tempdir()
        .unwrap();
    let path = dir.path().join("plant.json");
    let plant = vesselcad::plant::generate_plant(12, 1).unwrap();
    vesselcad::design::save(&plant, &path).unwrap();
    let tags: Vec<String> = plant.vessels.iter().map(|v| v.tag.clone()).collect();
    let server = ServerProcess::start(&path, &["--whole-glb-limit", "100000"]);
    let whole = server.request("GET", "/model.glb", &[], b"");
    assert_eq!(whole.status, 200);
    let whole_bytes = whole.body.len();
    assert!(whole_bytes > 1_000_000, "the plant is {whole_bytes} bytes");
    let whole = nodes(&whole.body);
    let runtime = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    runtime.block_on(async {
        let url = format!("ws://{}/ws", server.address);
        let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
        let mut next_pair = async || -> (Value, Vec<u8>) {
            let mut header = None;
            loop {
                match tokio::time::timeout(TIMEOUT, ws.next()).await {
                    Ok(Some(Ok(Message::Text(t)))) => {
                        header = Some(serde_json::from_str::<Value>(&t).unwrap());
                    }
                    Ok(Some(Ok(Message::Binary(b)))) => {
                        return (header.expect("a GLB without its header"), b.to_vec());
                    }
                    Ok(Some(Ok(_))) => {}
                    other => panic!("expected a message, got {other:?}"),
                }
            }
        };
        let (hello, coarse) = next_pair().await;
        assert_eq!(hello["type"], "hello");
        assert_eq!(hello["revision"], 0);
        assert_eq!(hello["pushed"], tags.len(), "{}", hello["pushed"]);
        let mut ids: Vec<String> = serde_json::from_value(hello["ids"].clone()).unwrap();
        ids.sort();
        assert_eq!(ids, whole.keys().cloned().collect::<Vec<_>>());
        // The coarse whole: a box under each vessel's node, nothing else.
        let mut model = nodes(&coarse);
        let boxes: Vec<String> = tags.iter().map(|t| format!("{t}/box")).collect();
        assert_eq!(
            model
                .keys()
                .filter(|id| id.contains('/'))
                .cloned()
                .collect::<Vec<_>>(),
            {
                let mut b = boxes.clone();
                b.sort();
                b
            }
        );
        assert!(coarse.len() < 50_000, "boxes in {} bytes", coarse.len());
        outward_boxes(&coarse, tags.len());
        let mut largest = 0;
        for (k, tag) in tags.iter().enumerate() {
            let (header, glb) = next_pair().await;
            assert_eq!(header["type"], "vessel", "{header}");
            assert_eq!(header["revision"], 0);
            assert_eq!(header["tag"], tag.as_str());
            assert_eq!(header["index"], k);
            largest = largest.max(glb.len());
            model.retain(|id, _| id != tag && !id.starts_with(&format!("{tag}/")));
            model.extend(nodes(&glb));
        }
        assert_eq!(model, whole, "the vessels put together are the whole model");
        assert!(
            largest * 4 < whole_bytes,
            "largest message {largest} of {whole_bytes} bytes"
        );
        // Then the deltas, as before.
        let path = "/vessels/3/nozzles/0/projection";
        let projection = server
            .get_json("/design.json")
            .pointer(path)
            .unwrap()
            .as_f64()
            .unwrap();
        let answer = server.edit(&json!([
            { "op": "replace", "path": path, "value": projection + 20.0 }
        ]));
        assert_eq!(answer.status, 200, "{}", answer.text());
        let (delta, _) = next_pair().await;
        assert_eq!(delta["type"], "delta");
        assert_eq!(delta["revision"], 1);
        assert_eq!(delta["changed"], answer.json()["changed"]);
    });
    // The default limit keeps the whole GLB in a plain hello of this plant (the
    // journal replays the edit).
    drop(server);
    let server = ServerProcess::start(&path, &[]);
    let whole_bytes = server.request("GET", "/model.glb", &[], b"").body.len();
    runtime.block_on(async {
        let url = format!("ws://{}/ws", server.address);
        let (mut ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
        let hello = match tokio::time::timeout(TIMEOUT, ws.next()).await {
            Ok(Some(Ok(Message::Text(t)))) => serde_json::from_str::<Value>(&t).unwrap(),
            other => panic!("expected a text hello, got {other:?}"),
        };
        assert!(hello.get("pushed").is_none(), "{}", hello["pushed"]);
        match tokio::time::timeout(TIMEOUT, ws.next()).await {
            Ok(Some(Ok(Message::Binary(b)))) => assert_eq!(b.len(), whole_bytes),
            other => panic!("expected the whole GLB, got {other:?}"),
        }
    });
}

/// Each box of a coarse GLB is 12 triangles wound counter-clockwise about
/// their vertices' outward normals.
fn outward_boxes(glb: &[u8], count: usize) {
    let gltf = Gltf::from_slice(glb).expect("a valid GLB");
    let mut boxes = 0;
    for mesh in gltf.meshes() {
        for primitive in mesh.primitives() {
            let reader = primitive.reader(|_| gltf.blob.as_deref());
            let p: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            let n: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
            let i: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            assert_eq!(i.len(), 36);
            let v = |k: u32| glam::Vec3::from(p[k as usize]);
            for t in i.chunks(3) {
                let face = (v(t[1]) - v(t[0])).cross(v(t[2]) - v(t[0]));
                for &k in t {
                    assert!(face.dot(glam::Vec3::from(n[k as usize])) > 0.0, "{t:?}");
                }
            }
            boxes += 1;
        }
    }
    assert_eq!(boxes, count);
}

/// The estimate that decides whether a hello is pushed is near the GLB
/// written.
#[test]
fn the_whole_glb_estimate_is_near_its_size() {
    let design = design_copy("small-plant.json", "estimate");
    let mut session = vesselcad::server::session::Session::open(
        &design,
        vesselcad::mesh::TessellationOptions::chord(1.0),
    )
    .unwrap();
    let estimate = session.full_model().estimated_glb_bytes() as f64;
    let written = session.snapshot().glb.len() as f64;
    assert!(
        (0.8..1.25).contains(&(estimate / written)),
        "estimated {estimate} bytes, written {written}"
    );
}
