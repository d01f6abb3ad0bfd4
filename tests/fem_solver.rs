//! Shell models solved by CalculiX against the closed forms of thin shells
//! under internal pressure: a course between 2:1 heads (hoop P·R/t, axial
//! P·R/2t away from the heads) and a sphere (P·R/2t), each within 2 %. Skipped,
//! with a message, where `ccx` is not installed (CI installs it).

mod common;

use common::fem::{along, model, solve, vessel};
use glam::DVec3;
use vesselcad::fem::results::{part_stresses, principal};

/// R = 1000 mm on the mid-surface, t = 10 mm, P = 1 MPa: hoop 100 MPa, axial
/// 50 MPa on the course farther than 3·√(R·t) from the heads.
#[test]
fn course_between_two_to_one_heads() {
    let design = vessel(r#""shape": "ellipsoidal""#, 2010.0, 3000.0, 10.0, 1000.0);
    let m = model(&design, 200.0);
    let Some(results) = solve(&m, "course") else {
        return;
    };
    let course = m.mesh.parts.iter().position(|p| p.id == "S1").expect("S1");
    let mut checked = 0;
    for n in m.mesh.part_nodes(course) {
        let p = m.mesh.nodes[n];
        if !(750.0..=2250.0).contains(&p.z) {
            continue;
        }
        let radial = DVec3::new(p.x, p.y, 0.0).normalize();
        let hoop_dir = DVec3::Z.cross(radial);
        let s = results[n].membrane;
        let hoop = along(s, hoop_dir, hoop_dir);
        let axial = along(s, DVec3::Z, DVec3::Z);
        assert!(
            (hoop - 100.0).abs() <= 2.0,
            "node {n} at {p}: hoop {hoop} MPa"
        );
        assert!(
            (axial - 50.0).abs() <= 1.0,
            "node {n} at {p}: axial {axial} MPa"
        );
        checked += 1;
    }
    assert!(checked > 100, "only {checked} nodes checked");
    // The per-part table: the course's general membrane Pm (beyond
    // 3·√(R·t) of the heads, where the 2:1 heads' pull has died out) is the
    // hoop stress intensity P·R/t within 2 %; within √(R·t) alone it read
    // 107.8 MPa (the heads' hoop overshoot round 1.6·√(R·t)), within 2.5·√(R·t)
    // 103.3.
    let rows = part_stresses(&m, &results);
    let row = rows.iter().find(|r| r.name == "V-1/S1").expect("S1 row");
    eprintln!("{row:?}");
    let pm = row.membrane.expect("a general membrane region");
    assert!((98.0..=102.0).contains(&pm), "{row:?}");
    assert!(row.local.is_some(), "{row:?}");
}

/// Two hemispherical heads on a 20 mm course: the heads' membrane stresses
/// 30° and more from the junction are P·R/(2t) = 50 MPa in both directions.
#[test]
fn sphere() {
    let design = vessel(r#""shape": "hemispherical""#, 2010.0, 20.0, 10.0, 1000.0);
    let m = model(&design, 200.0);
    let Some(results) = solve(&m, "sphere") else {
        return;
    };
    let mut checked = 0;
    for (k, part) in m.mesh.parts.iter().enumerate() {
        if part.id == "S1" {
            continue;
        }
        for n in m.mesh.part_nodes(k) {
            let p = m.mesh.nodes[n];
            let centre = if p.z < 0.0 { 0.0 } else { 20.0 };
            let d = p - DVec3::new(0.0, 0.0, centre);
            // 30° or more from the equator.
            if d.z.abs() < 0.5 * d.length() {
                continue;
            }
            let s = principal(results[n].membrane);
            for v in &s[..2] {
                assert!((v - 50.0).abs() <= 1.0, "node {n} at {p}: principal {s:?}");
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} nodes checked");
}
