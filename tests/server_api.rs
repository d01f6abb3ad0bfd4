//! `vesselcad serve` over HTTP: JSON Patch edits answered with revisions and the
//! work they caused (proportional to the change), every kind of bad request
//! answered with its 4xx status and a clear error while changing nothing, the
//! editing token, the body limit, and static files that cannot escape their folder.

mod server_support;

use serde_json::{Value, json};
use server_support::{ServerProcess, design_copy};
use vesselcad::server::MAX_BODY;

/// The design and revision the server reports.
fn state(server: &ServerProcess) -> (Value, String) {
    let r = server.request("GET", "/design.json", &[], b"");
    assert_eq!(r.status, 200);
    let revision = r.header("x-vesselcad-revision").unwrap().to_string();
    (r.json(), revision)
}

#[test]
fn an_edit_gets_a_revision_and_rebuilds_only_what_it_changes() {
    let design = design_copy("horizontal-drum.json", "api-edit");
    let server = ServerProcess::start(&design, &[]);
    let (before, revision) = state(&server);
    assert_eq!(revision, "0");
    // N3 (a vent on S1) gets a longer projection: only its neck and flange change.
    let r = server.edit(&json!([
        { "op": "test", "path": "/vessels/0/nozzles/2/mark", "value": "N3" },
        { "op": "replace", "path": "/vessels/0/nozzles/2/projection", "value": 1600 }
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let answer = r.json();
    assert_eq!(answer["revision"], 1);
    // The neck is rebuilt and its opening cut again. A longer radial neck meets
    // the shell in the same curve (marched on the same canonical host), so the
    // host shell's region comes out the same and it is not re-meshed.
    assert_eq!(answer["changed"], json!(["V-101/N3"]), "{answer}");
    assert_eq!(answer["removed"], json!([]));
    let work = &answer["work"];
    assert_eq!(work["shapes_rebuilt"], 1, "{work}");
    assert_eq!(work["vessels_resolved"], 1, "{work}");
    assert_eq!(work["openings_cut"], 1, "{work}");
    assert_eq!(work["frames_updated"], 0, "{work}");
    let (after, revision) = state(&server);
    assert_eq!(revision, "1");
    assert_eq!(after["vessels"][0]["nozzles"][2]["projection"], 1600.0);
    let mut expected = before.clone();
    expected["vessels"][0]["nozzles"][2]["projection"] = json!(1600.0);
    assert_eq!(after, expected, "only the patched value changed");

    // A patch touching two parts is one edit: one revision, both ids changed.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/0/nozzles/2/projection", "value": 1500 },
        { "op": "replace", "path": "/vessels/0/nozzles/3/projection", "value": 1500 }
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 2);
    assert_eq!(r.json()["changed"], json!(["V-101/N3", "V-101/N4"]));

    // The model served is the edited one.
    let glb = server.request("GET", "/model.glb", &[], b"");
    assert_eq!(glb.status, 200);
    assert_eq!(glb.header("content-type"), Some("model/gltf-binary"));
    assert_eq!(glb.header("x-vesselcad-revision"), Some("2"));
    assert_eq!(&glb.body[..4], b"glTF");
}

#[test]
fn bad_edits_are_refused_with_a_clear_error_and_change_nothing() {
    let design = design_copy("horizontal-drum.json", "api-bad");
    let server = ServerProcess::start(&design, &[]);
    let before = state(&server);
    let glb_before = server.request("GET", "/model.glb", &[], b"").body;
    let length = "/vessels/0/parts/1/shell/length";
    let limit_message = format!("the limit is {MAX_BODY} bytes");
    let cases: Vec<(&str, Vec<u8>, u16, &str, &str)> =
        vec![
        ("malformed JSON", b"[{\"op\":".to_vec(), 400, "malformed", "not JSON"),
        ("not a patch", br#"{"op":"replace"}"#.to_vec(), 400, "malformed", "array of operations"),
        (
            "unknown op",
            json!([{ "op": "frobnicate", "path": length }]).to_string().into_bytes(),
            400,
            "malformed",
            "frobnicate",
        ),
        (
            "unknown path",
            json!([{ "op": "replace", "path": "/vessels/0/parts/42/shell/length", "value": 1 }])
                .to_string()
                .into_bytes(),
            422,
            "unappliable",
            "/vessels/0/parts/42/shell/length",
        ),
        (
            "unknown field",
            json!([{ "op": "add", "path": "/vessels/0/parts/1/shell/colour", "value": "red" }])
                .to_string()
                .into_bytes(),
            422,
            "invalid",
            "colour",
        ),
        (
            "wrong type",
            json!([{ "op": "replace", "path": length, "value": "long" }]).to_string().into_bytes(),
            422,
            "invalid",
            "vessels[0].parts[1].shell.length: invalid type: string \"long\", expected a number",
        ),
        (
            "invalid value",
            json!([{ "op": "replace", "path": length, "value": -5 }]).to_string().into_bytes(),
            422,
            "invalid",
            "entity V-101/S1, length = -5",
        ),
        (
            "duplicate vessel tag",
            json!([{ "op": "copy", "from": "/vessels/0", "path": "/vessels/-" }])
                .to_string()
                .into_bytes(),
            422,
            "invalid",
            "vessels[1].tag: duplicate tag",
        ),
        (
            "failed test",
            json!([
                { "op": "test", "path": length, "value": 1 },
                { "op": "replace", "path": length, "value": 8000 }
            ])
            .to_string()
            .into_bytes(),
            409,
            "test_failed",
            "value did not match",
        ),
        (
            "second operation fails: none applied",
            json!([
                { "op": "replace", "path": length, "value": 8000 },
                { "op": "replace", "path": "/vessels/0/nozzles/0/rating", "value": 175 }
            ])
            .to_string()
            .into_bytes(),
            422,
            "invalid",
            "rating",
        ),
        (
            "oversized",
            {
                let mut big = b"[".to_vec();
                big.resize(MAX_BODY + 10, b' ');
                big.push(b']');
                big
            },
            413,
            "too_large",
            &limit_message,
        ),
    ];
    for (name, body, status, kind, needle) in cases {
        let r = server.request("POST", "/edit", &[], &body);
        assert_eq!(r.status, status, "{name}: {}", r.text());
        let answer = r.json();
        assert_eq!(answer["kind"], kind, "{name}: {answer}");
        let error = answer["error"].as_str().unwrap();
        assert!(
            error.contains(needle),
            "{name}: {error:?} should mention {needle:?}"
        );
        assert_eq!(
            state(&server),
            before,
            "{name} changed the design or revision"
        );
    }
    let violations = server
        .edit(&json!([{ "op": "replace", "path": length, "value": -5 }]))
        .json()["violations"]
        .clone();
    assert_eq!(violations[0]["entity"], "V-101/S1");
    assert_eq!(violations[0]["field"], "length");
    assert_eq!(violations[0]["path"], "vessels[0].parts[1].shell.length");
    assert_eq!(
        server.request("GET", "/model.glb", &[], b"").body,
        glb_before
    );
    // Still editable after all that; a `test` compares numbers by value (7200 is
    // the design's 7200.0), as RFC 6902 says.
    let r = server.edit(&json!([
        { "op": "test", "path": length, "value": 7200 },
        { "op": "replace", "path": length, "value": 7000 }
    ]));
    assert_eq!((r.status, r.json()["revision"].clone()), (200, json!(1)));
}

#[test]
fn every_route_but_the_page_shell_needs_the_token_when_one_is_set() {
    let design = design_copy("storage-tank.json", "api-token");
    let server = ServerProcess::start(&design, &["--token", "s3cret"]);
    let patch = json!([{ "op": "replace", "path": "/vessels/0/placement/rotation", "value": 10 }])
        .to_string();
    for headers in [
        vec![],
        vec![("Authorization", "Bearer wrong")],
        vec![("Authorization", "s3cret")],
    ] {
        let r = server.request("POST", "/edit", &headers, patch.as_bytes());
        assert_eq!(r.status, 401, "{headers:?}");
        assert!(
            r.json()["error"]
                .as_str()
                .unwrap()
                .contains("Authorization: Bearer")
        );
        let r = server.request("POST", "/save", &headers, b"");
        assert_eq!(r.status, 401, "save {headers:?}");
    }
    let auth = [("Authorization", "Bearer s3cret")];
    let r = server.request("GET", "/design.json", &auth, b"");
    assert_eq!(r.header("x-vesselcad-revision"), Some("0"));
    let r = server.request("POST", "/edit", &auth, patch.as_bytes());
    assert_eq!(r.status, 200, "{}", r.text());
    assert_eq!(r.json()["revision"], 1);
    // Reading needs it too (a header, or the query for what a browser cannot
    // send headers with); only the page shell does not.
    for path in [
        "/model.glb",
        "/design.json",
        "/drawing.svg?vessel=TK-301",
        "/ws",
        "/nowhere",
    ] {
        let r = server.request("GET", path, &[], b"");
        assert_eq!(r.status, 401, "GET {path}: {}", r.text());
        let r = server.request("GET", &format!("{path}?token=wrong"), &[], b"");
        assert_eq!(r.status, 401, "GET {path}?token=wrong");
    }
    for path in ["/model.glb", "/design.json"] {
        assert_eq!(
            server.request("GET", path, &auth, b"").status,
            200,
            "{path}"
        );
        let r = server.request("GET", &format!("{path}?token=s3cret"), &[], b"");
        assert_eq!(r.status, 200, "GET {path}?token=s3cret");
    }
    for path in ["/", "/static/viewer.js"] {
        assert_eq!(server.request("GET", path, &[], b"").status, 200, "{path}");
    }
}

#[test]
fn static_files_cannot_escape_their_folder_and_unknown_routes_are_404() {
    let design = design_copy("storage-tank.json", "api-static");
    let server = ServerProcess::start(&design, &[]);
    let page = server.request("GET", "/", &[], b"");
    assert_eq!(page.status, 200);
    assert!(page.text().contains("/static/viewer.js"));
    let bundle = server.request("GET", "/static/three-bundle.js", &[], b"");
    assert_eq!(bundle.status, 200);
    assert!(
        bundle.text().starts_with("/**\n * @license"),
        "licence header kept"
    );
    for path in [
        "/static/../Cargo.toml",
        "/static/%2e%2e/Cargo.toml",
        "/static/..%2fCargo.toml",
        "/static/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
        "/static//etc/passwd",
        "/static/assets/index.html",
        "/../../etc/passwd",
        "/Cargo.toml",
        "/src/server/assets/viewer.js",
    ] {
        let r = server.request("GET", path, &[], b"");
        assert!(
            r.status == 404 || r.status == 400,
            "{path}: {} {}",
            r.status,
            r.text()
        );
        assert!(
            !r.text().contains("[package]") && !r.text().contains("root:"),
            "{path}"
        );
    }
    // The drawing route checks its query and the vessel.
    assert_eq!(server.request("GET", "/drawing.svg", &[], b"").status, 400);
    let r = server.request("GET", "/drawing.svg?vessel=NOPE", &[], b"");
    assert_eq!(r.status, 404);
    assert!(r.json()["error"].as_str().unwrap().contains("NOPE"));
}

/// An unknown vessel's error lists the design's tags, like the CLI's: the first
/// 20 in the message and in `vessels`, then how many more.
#[test]
fn an_unknown_vessel_lists_the_tags() {
    let design = design_copy("horizontal-drum.json", "api-unknown-tag");
    let mut value: Value = serde_json::from_slice(&std::fs::read(&*design).unwrap()).unwrap();
    let drum = value["vessels"][0].clone();
    value["vessels"] = (0..23)
        .map(|k| {
            let mut v = drum.clone();
            v["tag"] = json!(format!("D-{k:02}"));
            v["placement"]["position"] = json!([0, 10_000 * k, 2000]);
            v
        })
        .collect();
    std::fs::write(&*design, value.to_string()).unwrap();
    let server = ServerProcess::start(&design, &[]);
    let r = server.request("GET", "/drawing.svg?vessel=NOPE", &[], b"");
    assert_eq!(r.status, 404, "{}", r.text());
    let body = r.json();
    assert_eq!(body["kind"], "unknown_vessel");
    let message = body["error"].as_str().unwrap();
    assert!(
        message.contains("\"NOPE\"") && message.contains("D-00, D-01") && message.contains("D-19"),
        "{message}"
    );
    assert!(
        message.ends_with("and 3 more") && !message.contains("D-20"),
        "{message}"
    );
    let listed = body["vessels"].as_array().unwrap();
    assert_eq!(listed.len(), 20, "{body}");
    assert_eq!(listed[0], "D-00");
}

#[test]
fn the_drawing_route_serves_the_current_sheet() {
    let design = design_copy("horizontal-drum.json", "api-drawing");
    let server = ServerProcess::start(&design, &[]);
    let sheet = |server: &ServerProcess| {
        let r = server.request("GET", "/drawing.svg?vessel=V-101", &[], b"");
        assert_eq!(r.status, 200, "{}", r.text());
        assert_eq!(r.header("content-type"), Some("image/svg+xml"));
        let text = r.text();
        let doc = roxmltree::Document::parse(&text).expect("the sheet is well-formed XML");
        assert_eq!(doc.root_element().tag_name().name(), "svg");
        text
    };
    let before = sheet(&server);
    assert!(
        before.contains("liquid outlet"),
        "the schedule lists N2's service"
    );
    // An edit through the API shows on the next sheet.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/0/nozzles/1/service", "value": "product draw-off" }
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let after = sheet(&server);
    assert!(after.contains("product draw-off") && !after.contains("liquid outlet"));
}

#[test]
fn serve_refuses_a_missing_or_invalid_design_at_start() {
    let run = |path: &std::path::Path| {
        std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
            .args(["serve", path.to_str().unwrap(), "--port", "0"])
            .output()
            .unwrap()
    };
    let design = design_copy("storage-tank.json", "api-refuse");
    let missing = run(&design.with_file_name("nope.json"));
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("cannot read"));
    let text = std::fs::read_to_string(&design)
        .unwrap()
        .replace("\"od\": 8000", "\"od\": -8000");
    std::fs::write(&design, text).unwrap();
    let invalid = run(&design);
    assert_eq!(invalid.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&invalid.stderr);
    assert!(
        stderr.contains("TK-301/S1") && stderr.contains("od = -8000"),
        "{stderr}"
    );
    // Nothing was written beside the refused design.
    assert!(!design.with_file_name("design.json.journal").exists());
    // A viewer timeout that is not a positive number of seconds is refused.
    for bad in ["0", "-3", "NaN", "soon"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_vesselcad"))
            .args(["serve", design.to_str().unwrap(), "--port", "0"])
            .args(["--viewer-timeout", bad])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "--viewer-timeout {bad}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("--viewer-timeout"),
            "--viewer-timeout {bad}"
        );
    }
}
