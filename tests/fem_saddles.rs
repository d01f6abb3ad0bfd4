//! A horizontal vessel on two saddles meshed as shell parts (top plate
//! bonded to the course, web, base plate), solved by CalculiX: the mesh shares
//! the course's ring at each web node for node and is conforming and well
//! shaped; the vessel is held at the base plates only; the vertical
//! reactions equal the weight of the metal plus the liquid within 1 % in the
//! operating and hydrotest cases, half on each saddle; and the
//! circumferential stress at the saddle's horn is compared with Zick's S3
//! ([`vesselcad::calc::zick`]). Skipped, with a message, where `ccx` is not
//! installed (CI installs it).

mod common;

use common::fem_loads::{integrate, reaction_at, run};
use glam::DVec3;
use vesselcad::calc::MaterialTable;
use vesselcad::calc::zick;
use vesselcad::design::{Design, parse};
use vesselcad::fem::conditions::GRAVITY;
use vesselcad::fem::{FeModel, FemOptions, LoadCase, vessel_model};

/// Mean radius, wall, tangent length, saddle width and contact angle.
const R: f64 = 500.0;
const T: f64 = 10.0;
const L: f64 = 4000.0;
const B: f64 = 150.0;
const THETA: f64 = 120.0;

/// OD 1010 × 4000, t = 10, 2:1 heads, on two saddles (120°, 150 wide, 700
/// from the axis to the base) at the default 0.2·L from the tangent lines;
/// full of water in operation (the level 5 mm under the inner top: the
/// sliver above it is 0.06 % of the volume); 1 kPa design pressure (its hoop stress, 0.05
/// MPa, is negligible beside the saddle's).
fn design() -> Design {
    parse(&format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{
          "tag": "V-1", "kind": "horizontal",
          "placement": {{ "position": [0, 0, 1000], "rotation": 90 }},
          "design": {{ "pressure": 1, "temperature": 20, "material": "SA-516-70" }},
          "operating": {{ "liquid_level": 990, "liquid_density": 1000 }},
          "parts": [
            {{ "head": {{ "id": "H1", "shape": "ellipsoidal", "thickness": {T} }} }},
            {{ "shell": {{ "id": "S1", "od": {od}, "length": {L}, "thickness": {T} }} }},
            {{ "head": {{ "id": "H2", "shape": "ellipsoidal", "thickness": {T} }} }},
            {{ "saddle": {{ "id": "SD1", "contact_angle": {THETA}, "width": {B}, "height": 700 }} }},
            {{ "saddle": {{ "id": "SD2", "contact_angle": {THETA}, "width": {B}, "height": 700 }} }}
          ]}}]}}"#,
        od = 2.0 * R + T
    ))
    .unwrap_or_else(|e| panic!("test design: {e}"))
}

/// The model of case `case` at 70 mm: 48 divisions round, so the horns
/// (±60° from the bottom) fall on nodes.
fn model(case: LoadCase) -> FeModel {
    let options = FemOptions {
        size: Some(70.0),
        order: 2,
    };
    vessel_model(&design(), "V-1", &options, case, &MaterialTable::builtin())
        .unwrap_or_else(|e| panic!("fem model: {e}"))
}

fn part(m: &FeModel, id: &str) -> usize {
    m.mesh
        .parts
        .iter()
        .position(|p| p.id == id)
        .unwrap_or_else(|| panic!("no part {id}: {:?}", m.mesh.notes))
}

/// Axial position (plant frame, from the axis point) and angle from the
/// bottom, degrees, of `p`; and its distance from the axis.
fn cylindrical(m: &FeModel, p: DVec3) -> (f64, f64, f64) {
    let (o, d) = m.mesh.axis;
    let a = (p - o).dot(d);
    let radial = p - o - d * a;
    let angle = radial.normalize().dot(-DVec3::Z).clamp(-1.0, 1.0).acos();
    (a, angle.to_degrees(), radial.length())
}

#[test]
fn saddles_are_shells_on_a_node_line_of_the_course_held_at_their_base_plates() {
    let m = model(LoadCase::Operating);
    let mesh = &m.mesh;
    assert!(
        mesh.notes.iter().all(|n| !n.contains("saddle")),
        "{:?}",
        mesh.notes
    );
    common::fem::assert_good("saddles", mesh);
    let envelope: Vec<usize> = (0..mesh.parts.len())
        .filter(|k| !mesh.structural.contains(k))
        .flat_map(|k| mesh.part_nodes(k))
        .collect();
    for id in ["SD1", "SD2"] {
        let web = part(&m, &format!("{id}/web"));
        let base = part(&m, &format!("{id}/base plate"));
        let band = part(&m, &format!("{id}/wear plate"));
        assert!(mesh.structural.contains(&web) && mesh.structural.contains(&base));
        assert!(!mesh.structural.contains(&band));
        assert_eq!(mesh.parts[band].thickness, T + 12.0);
        // The web's top edge is the course's ring: corner and mid-side nodes
        // shared, on the mid-surface, in one plane, horn to horn.
        let shared: Vec<usize> = mesh
            .part_nodes(web)
            .into_iter()
            .filter(|n| envelope.contains(n))
            .collect();
        let at: Vec<(f64, f64, f64)> = shared
            .iter()
            .map(|&n| cylindrical(&m, mesh.nodes[n]))
            .collect();
        // 120° over 48 divisions: 16 edges, 33 nodes with the mid-side ones.
        assert_eq!(shared.len(), 33, "{id}: {at:?}");
        for &(a, _, r) in &at {
            assert!((a - at[0].0).abs() < 1e-6 && (r - R).abs() < 1e-6, "{at:?}");
        }
        let widest = at.iter().map(|x| x.1).fold(0.0, f64::max);
        assert!(
            (widest - THETA / 2.0).abs() < 1e-6,
            "{id}: horn at {widest}°"
        );
        // No pressure on the web or the base plate.
        for (e, el) in mesh.elements.iter().enumerate() {
            if el.part == web || el.part == base {
                assert_eq!(m.pressure[e], 0.0);
            }
        }
    }
    // Held at the base plates' nodes only, all at the bearing planes' height.
    let plates: Vec<usize> = ["SD1", "SD2"]
        .iter()
        .flat_map(|id| mesh.part_nodes(part(&m, &format!("{id}/base plate"))))
        .collect();
    assert!(
        m.support_note.starts_with("saddles SD1, SD2"),
        "{}",
        m.support_note
    );
    assert_eq!(m.supports.len(), plates.len());
    for s in &m.supports {
        assert!(plates.contains(&s.node));
    }
}

/// The weight the saddles carry: the metal of every part plus the water
/// inside the envelope's inner wall (full in both cases), N.
fn weight(m: &FeModel) -> f64 {
    let mesh = &m.mesh;
    let envelope = |e: usize| !mesh.structural.contains(&mesh.elements[e].part);
    let thickness = |e: usize| mesh.parts[mesh.elements[e].part].thickness;
    let metal = integrate(mesh, |e, _, n| thickness(e) * n.length()) * m.density * GRAVITY;
    // Node-surface volume (divergence theorem), less each element's wetted
    // area times its inner face's depth below the nodes (half the thickness,
    // plus the section's offset): CalculiX loads the inner face.
    let volume = integrate(
        mesh,
        |e, p, n| if envelope(e) { p.dot(n) / 3.0 } else { 0.0 },
    )
    .abs();
    let inner = integrate(mesh, |e, _, n| {
        if envelope(e) {
            let part = &mesh.parts[mesh.elements[e].part];
            (0.5 + part.offset) * part.thickness * n.length()
        } else {
            0.0
        }
    });
    let liquid = 1000e-12 * GRAVITY * (volume - inner);
    eprintln!(
        "{}: metal {metal:.1} N + water {liquid:.1} N",
        m.case.name()
    );
    metal + liquid
}

/// In operation and under the hydrotest. The top plate is bonded as a thicker
/// shell whose section is offset outwards so that its inner face is the
/// course's: the pressure then sees one smooth inner wall (with the section
/// about the mid-surface, the 6 mm step at the horns lifted the vessel:
/// reactions 35 466 N against a weight of 45 046 N at the test pressure).
#[test]
fn saddle_reactions_equal_the_weight_in_operation_and_test() {
    for case in [LoadCase::Operating, LoadCase::Test] {
        let m = model(case);
        let w = weight(&m);
        let Some(results) = run(&m, case.name()) else {
            return;
        };
        let each: Vec<DVec3> = ["SD1", "SD2"]
            .iter()
            .map(|id| {
                let plate = m.mesh.part_nodes(part(&m, &format!("{id}/base plate")));
                reaction_at(&m, &results, &plate)
            })
            .collect();
        let r = each[0] + each[1];
        eprintln!("{}: weight {w:.1} N; reactions {each:?}", case.name());
        assert!(
            (r.z - w).abs() <= 0.01 * w,
            "{}: vertical reaction {} N against weight {w} N",
            case.name(),
            r.z
        );
        assert!(r.x.abs() + r.y.abs() <= 1e-3 * w, "{}: {r:?}", case.name());
        // Symmetric vessel: half on each saddle.
        for x in &each {
            assert!(
                (x.z - w / 2.0).abs() <= 0.01 * w,
                "{}: {each:?}",
                case.name()
            );
        }
    }
}

/// The circumferential stress at the horn of a saddle against Zick's S3 for
/// the same load (the FE reaction at the saddle), geometry and contact angle.
///
/// Where: on the faces of the course's own wall (t = ts, as in Zick's S3
/// without a wear plate) at the horn's angle, at the edge of the saddle's top
/// plate (b/2 from the web), where the shell alone carries the horn's ring
/// moment. Not at the web's end itself: there a plate's corner meets the
/// shell at a point, a singularity of the shell idealisation whose value
/// depends on the mesh (−49.9 MPa at 70 mm, 2.5 × Zick).
///
/// Tolerance ±30 %: Zick's S3 is a ring-bending estimate over an assumed
/// effective width b + 1.56·√(R·ts) on a rigid saddle, with K6 from his ring
/// analysis, checked by him against strain gauges on full-size vessels; it is
/// used as a design stress, not a prediction of a point value. A flexible
/// web and a bonded top plate move the peak and its value within that band;
/// outside it the model (loads, supports, the plate's bonding) would be
/// wrong. Measured: see the message (FE/Zick 1.16 at 70 mm when written).
#[test]
fn horn_stress_against_zick() {
    let m = model(LoadCase::Operating);
    let Some(results) = run(&m, "horn") else {
        return;
    };
    let plate = m.mesh.part_nodes(part(&m, "SD1/base plate"));
    let q = reaction_at(&m, &results, &plate).z;
    // The web's plane, plant frame.
    let web = part(&m, "SD1/web");
    let (a_web, _, _) = cylindrical(&m, m.mesh.nodes[m.mesh.part_nodes(web)[0]]);
    let zick = zick::stresses(&zick::Saddle {
        load: q,
        a: 0.2 * L,
        l: L,
        r: R,
        ts: T,
        th: T,
        h: R / 2.0,
        b: B,
        theta: THETA,
        wear_plate: 0.0,
    })
    .unwrap_or_else(|e| panic!("{e}"));
    let (o, d) = m.mesh.axis;
    let mut faces = Vec::new();
    for (id, &p) in &results.nodes {
        let Some(&s) = results.stress.get(id) else {
            continue;
        };
        let (a, angle, r) = cylindrical(&m, p);
        // CalculiX's expanded nodes of the course's wall: ±ts/2 off the mid-surface.
        let on_edge = ((a - a_web).abs() - B / 2.0).abs() < 1.0;
        if on_edge && (angle - THETA / 2.0).abs() < 1.0 && ((r - R).abs() - T / 2.0).abs() < 0.5 {
            let radial = (p - o - d * (p - o).dot(d)).normalize();
            let hoop = d.cross(radial);
            faces.push((common::fem::along(s, hoop, hoop), r - R));
        }
    }
    assert!(faces.len() >= 4, "faces at the horn: {faces:?}");
    let (fe, face) = faces
        .iter()
        .copied()
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .expect("faces");
    let ratio = fe / zick.s3_horn;
    eprintln!(
        "Q {q:.0} N; Zick S3 {:.2} MPa (K6 {:.4}); FE at the horn, top plate's edge: {faces:.2?}; \
         most compressive {fe:.2} MPa ({:+.1} mm off the mid-surface); FE/Zick {ratio:.3}",
        zick.s3_horn, zick.k6_used, face
    );
    assert!(
        (0.7..=1.3).contains(&ratio),
        "horn stress {fe} MPa against Zick's {} MPa",
        zick.s3_horn
    );
}
