//! The live server's plate files (issue 38 §4): `GET /plates.json?vessel=T`
//! lists a vessel's plates and `GET /plates/<id>.dxf?vessel=T` serves each
//! one's cutting DXF, made from the session's current design, so the plates
//! follow an edit.

mod server_support;

use serde_json::json;
use server_support::{ServerProcess, design_copy};

#[test]
fn plate_dxfs_are_served_beside_the_traveler_and_follow_an_edit() {
    let design = design_copy("small-plant.json", "fab-plates");
    let server = ServerProcess::start(&design, &[]);
    let list = server.get_json("/plates.json?vessel=C-201");
    let plates = list["plates"].as_array().unwrap();
    assert!(plates.len() > 4, "{list}");
    // The plate holding N1 (on S1).
    let holding = |list: &serde_json::Value| -> String {
        list["plates"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["openings"].as_array().unwrap().contains(&json!("N1")))
            .unwrap()["file"]
            .as_str()
            .unwrap()
            .to_string()
    };
    let file = holding(&list);
    assert!(
        file.starts_with("C-201-S1-P") && file.ends_with(".dxf"),
        "{file}"
    );
    let dxf = server.request("GET", &format!("/plates/{file}?vessel=C-201"), &[], b"");
    assert_eq!(dxf.status, 200, "{}", dxf.text());
    assert!(dxf.header("content-disposition").unwrap().contains(&file));
    let before = dxf.text();
    assert!(before.contains("SECTION") && before.contains(file.trim_end_matches(".dxf")));
    // Turn N1 by 10°: its plate's DXF follows.
    let r = server.edit(&json!([
        { "op": "replace", "path": "/vessels/2/nozzles/0/orientation", "value": 100 }
    ]));
    assert_eq!(r.status, 200, "{}", r.text());
    let file = holding(&server.get_json("/plates.json?vessel=C-201"));
    let after = server.request("GET", &format!("/plates/{file}?vessel=C-201"), &[], b"");
    assert_eq!(after.status, 200, "{}", after.text());
    assert_ne!(after.text(), before, "the plate's DXF follows the edit");
    // Unknown plate, unknown vessel, no vessel.
    let r = server.request("GET", "/plates/C-201-S9-P1.dxf?vessel=C-201", &[], b"");
    assert_eq!(r.status, 404, "{}", r.text());
    assert!(
        r.text().contains(&file),
        "the error lists the plates: {}",
        r.text()
    );
    let r = server.request("GET", &format!("/plates/{file}?vessel=NOPE"), &[], b"");
    assert_eq!(r.status, 404, "{}", r.text());
    let r = server.request("GET", "/plates.json", &[], b"");
    assert_eq!(r.status, 400, "{}", r.text());
}

#[test]
fn boot_plates_and_head_blanks_are_served_with_the_plates() {
    let design = design_copy("small-plant.json", "fab-boot-blanks");
    let server = ServerProcess::start(&design, &[]);
    let list = server.get_json("/plates.json?vessel=V-101");
    let plates = list["plates"].as_array().unwrap();
    let of_kind = |kind: &str| -> Vec<&serde_json::Value> {
        plates.iter().filter(|p| p["kind"] == kind).collect()
    };
    let boots = of_kind("boot plate");
    assert!(!boots.is_empty(), "V-101 has a boot: {list}");
    assert_eq!(boots[0]["part"], "B1", "{list}");
    let blanks = of_kind("head blank");
    assert!(
        blanks.iter().any(|b| b["part"] == "H1"),
        "V-101's heads have blanks: {list}"
    );
    for piece in boots.iter().chain(&blanks) {
        let file = piece["file"].as_str().unwrap();
        let dxf = server.request("GET", &format!("/plates/{file}?vessel=V-101"), &[], b"");
        assert_eq!(dxf.status, 200, "{file}: {}", dxf.text());
        let text = dxf.text();
        assert!(
            text.contains("SECTION") && text.contains(piece["id"].as_str().unwrap()),
            "{file} is a DXF naming its piece"
        );
    }
}
