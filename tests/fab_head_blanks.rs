//! Head openings on the head blanks (`vesselcad::fab::head_map`): the forming
//! map (cap area from the pole = π·ρ² on the blank, same angle) preserves the
//! area of annular zones (closed forms on spheres), its whole equals the
//! blank's area, a centre nozzle maps to a circle of the expected radius, an
//! off-centre opening and its pad map back onto the exact intersection of
//! their cylinders with the mid-surface, and the blank's DXF marks them.

mod common;

use std::f64::consts::PI;

use common::examples::{EXAMPLES, example};
use glam::{DVec2, DVec3};
use vesselcad::design::parse;
use vesselcad::fab::develop::mid_head;
use vesselcad::fab::head_map::HeadMap;
use vesselcad::fab::openings::FormedOpening;
use vesselcad::fab::{FabPlan, Shop, plan};
use vesselcad::parts::heads::{Head, HeadKind};

/// A vertical vessel OD 2000, t 12, whose top head `H2` is `head` (JSON)
/// and carries `nozzles` (JSON objects, host H2).
fn vessel(head: &str, nozzles: &[&str]) -> FabPlan {
    let text = format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{"tag": "V-1", "kind": "vertical",
        "placement": {{"position": [0, 0, 0], "rotation": 0}},
        "parts": [
          {{"head": {{"id": "H1", "shape": "ellipsoidal", "thickness": 12}}}},
          {{"shell": {{"id": "S1", "od": 2000, "length": 3000, "thickness": 12}}}},
          {{"head": {{"id": "H2", {head}, "straight_flange": 40, "thickness": 12}}}}],
        "nozzles": [{}]}}]}}"#,
        nozzles.join(",")
    );
    let design = parse(&text).expect("the test design parses");
    plan(&design, "V-1", &Shop::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn formed<'a>(p: &'a FabPlan, mark: &str) -> &'a FormedOpening {
    p.openings
        .formed
        .iter()
        .find(|f| f.mark == mark)
        .unwrap_or_else(|| panic!("{mark} not on a head"))
}

#[test]
fn the_map_preserves_annular_zone_areas() {
    // Hemisphere of mid radius R: the zone between polar angles a1 < a2 has
    // area 2πR²(cos a1 − cos a2).
    let head = Head::new(1988.0, HeadKind::Hemispherical).with_straight_flange(40.0);
    let map = HeadMap::new(&head).unwrap();
    let r = 994.0;
    let at = |a: f64| DVec3::new(r * a.sin() * 0.6, r * a.sin() * 0.8, 40.0 + r * a.cos());
    for (a1, a2) in [(0.1, 0.5), (0.3, 1.2), (1.0, 1.5), (0.0, PI / 2.0)] {
        let (p1, p2) = (map.forward(at(a1)).unwrap(), map.forward(at(a2)).unwrap());
        let zone = PI * (p2.length_squared() - p1.length_squared());
        let exact = 2.0 * PI * r * r * (a1.cos() - a2.cos());
        let rel = (zone - exact).abs() / exact;
        assert!(rel < 1e-9, "{a1}..{a2}: {zone} vs {exact} ({rel:e})");
        // Same angle about the axis.
        assert!((p2.y.atan2(p2.x) - 0.8f64.atan2(0.6)).abs() < 1e-12);
    }
    // Torispherical crown (sphere of radius L about the axis, pole at the
    // top): a zone of the crown likewise, 2πL²(cos a1 − cos a2).
    let tori = Head::new(
        1988.0,
        HeadKind::Torispherical {
            crown_radius: 1994.0,
            knuckle_radius: 194.0,
        },
    );
    let map = HeadMap::new(&tori).unwrap();
    let (l, top) = (1994.0, tori.height().unwrap());
    let at = |a: f64| DVec3::new(l * a.sin(), 0.0, top - l + l * a.cos());
    let (p1, p2) = (
        map.forward(at(0.05)).unwrap(),
        map.forward(at(0.4)).unwrap(),
    );
    let zone = PI * (p2.length_squared() - p1.length_squared());
    let exact = 2.0 * PI * l * l * (0.05f64.cos() - 0.4f64.cos());
    assert!((zone - exact).abs() / exact < 1e-9, "{zone} vs {exact}");
}

#[test]
fn the_whole_map_is_the_blank() {
    let mut checked = 0;
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            let p = plan(&design, &v.tag, &Shop::default()).unwrap();
            for h in &p.developments.heads {
                let vesselcad::constraints::PartGeometry::Head(head) =
                    &p.resolved.parts[h.part].geometry
                else {
                    panic!("{} is not a head", h.id);
                };
                let map = HeadMap::new(&mid_head(head, h.thickness)).unwrap();
                let rel = (map.total - h.mid_area).abs() / h.mid_area;
                assert!(
                    rel < 1e-9,
                    "{name} {}: {} vs {} ({rel:e})",
                    h.id,
                    map.total,
                    h.mid_area
                );
                assert!((2.0 * map.blank_radius() - h.diameter).abs() < 1e-6);
                checked += 1;
            }
        }
    }
    assert!(checked >= 6, "{checked}");
}

#[test]
fn a_centre_nozzle_maps_to_a_circle() {
    let p = vessel(
        r#""shape": "hemispherical""#,
        &[
            r#"{"mark": "N1", "size": 8, "rating": 150, "host": "H2", "orientation": 0, "projection": 1400}"#,
        ],
    );
    let mark = formed(&p, "N1")
        .blank
        .as_ref()
        .expect("mapped onto the blank");
    // Mid sphere R = (2000 − 12)/2; the cutting cylinder (OD/2 + bevel)
    // meets it on the parallel of radius ρ, a cap of height h = R − √(R² − ρ²)
    // and area 2πRh: blank radius √(2Rh).
    let (r, rho) = (994.0, 0.5 * 219.1 + 3.0);
    assert!((mark.cut_radius - rho).abs() < 1e-12);
    let expected = (2.0 * r * (r - (r * r - rho * rho).sqrt())).sqrt();
    for q in &mark.outline {
        assert!(
            (q.length() - expected).abs() < 1e-9,
            "{} vs {expected}",
            q.length()
        );
    }
    assert!(mark.centre.length() < 1e-6, "{}", mark.centre);
    assert!(mark.outline.len() > 100);
}

#[test]
fn an_off_centre_opening_maps_back_onto_the_intersection() {
    let p = vessel(
        r#""shape": "ellipsoidal""#,
        &[
            r#"{"mark": "N1", "size": 8, "rating": 150, "host": "H2", "offset": 450, "orientation": 60, "projection": 1000, "pad": {"od": 420, "thickness": 12}}"#,
        ],
    );
    let f = formed(&p, "N1");
    let mark = f.blank.as_ref().expect("mapped onto the blank");
    let n = &p.resolved.nozzles[mark.nozzle];
    let host = &p.resolved.parts[n.host];
    let vesselcad::constraints::PartGeometry::Head(head) = &host.geometry else {
        panic!()
    };
    let map = HeadMap::new(&mid_head(head, 12.0)).unwrap();
    // The neck axis in the head's frame.
    let to_head = host.frame.inverse() * n.frame;
    let (origin, axis) = (to_head.translation, to_head.matrix3.z_axis.normalize());
    // The mid-surface: the ellipsoid of semi-axes a = (D − t)/2 and
    // b = D/4 − t/2 about z = 40 (the straight flange).
    let (a, b) = (994.0, 500.0 - 6.0);
    let mut worst_axis = 0.0f64;
    let mut worst_surface = 0.0f64;
    let mut check = |q: DVec2, radius: f64| {
        let x = map.inverse(q).unwrap();
        let d = x - origin;
        let off = (d - d.dot(axis) * axis).length();
        worst_axis = worst_axis.max((off - radius).abs());
        let e = (x.x * x.x + x.y * x.y) / (a * a) + (x.z - 40.0) * (x.z - 40.0) / (b * b);
        worst_surface = worst_surface.max((e - 1.0).abs() * b);
    };
    for &q in &mark.outline {
        check(q, mark.cut_radius);
    }
    for &q in mark.pad.as_ref().expect("the pad is mapped") {
        check(q, 210.0);
    }
    assert!(
        worst_axis < 1e-6,
        "off the cutting cylinder by {worst_axis:e} mm"
    );
    assert!(
        worst_surface < 1e-6,
        "off the mid-surface by {worst_surface:e} mm"
    );
    // The centre maps back onto the axis, at the nozzle's orientation side.
    let c = map.inverse(mark.centre).unwrap() - origin;
    assert!((c - c.dot(axis) * axis).length() < 1e-6);
}

#[test]
fn the_blank_dxf_marks_the_opening_for_cutting_after_forming() {
    let dir = common::fab::fab_files("horizontal-drum", "V-101");
    let drawing = dxf::Drawing::load_file(dir.path().join("V-101-H1-BLANK.dxf")).unwrap();
    let polylines = |layer: &str| -> Vec<usize> {
        drawing
            .entities()
            .filter(|e| e.common.layer == layer)
            .filter_map(|e| match &e.specific {
                dxf::entities::EntityType::LwPolyline(l) => Some(l.vertices.len()),
                _ => None,
            })
            .collect()
    };
    // The blank's circle is the only cut; M1's opening and pad are marks.
    assert_eq!(polylines("CUT"), vec![2]);
    assert_eq!(polylines("MARK").len(), 2, "{:?}", polylines("MARK"));
    let texts: Vec<String> = drawing
        .entities()
        .filter_map(|e| match &e.specific {
            dxf::entities::EntityType::Text(t) => Some(t.value.clone()),
            _ => None,
        })
        .collect();
    assert!(
        texts.iter().any(|t| t == "M1: cut after forming"),
        "{texts:?}"
    );
    // H2 has no opening: its blank carries none.
    let h2 = dxf::Drawing::load_file(dir.path().join("V-101-H2-BLANK.dxf")).unwrap();
    assert!(!h2.entities().any(|e| matches!(&e.specific,
        dxf::entities::EntityType::Text(t) if t.value.contains("after forming:"))));
}
