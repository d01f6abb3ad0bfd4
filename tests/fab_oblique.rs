//! The development of an eccentric reducer (an oblique cone) is exact: its
//! area equals the exact area of the NURBS oblique cone through the same end
//! circles to 1e-9, generators keep their length, a developed point rolled
//! back lies on the NURBS surface to 1e-6 mm, and the outline's chords stay
//! within `OUTLINE_SAG` of the developed curves. In a plan, an eccentric
//! reducer gets plates, DXFs, BOM lines and welds like a concentric cone.

use std::f64::consts::TAU;

use vesselcad::design::parse;
use vesselcad::fab::oblique::{OUTLINE_SAG, ObliqueCone, ObliquePlate};
use vesselcad::fab::openings::polygon_area;
use vesselcad::fab::plate_dxf::plate_drawing;
use vesselcad::fab::process::process_plan;
use vesselcad::fab::{Outline, RolledKind, ShopRules, plan};
use vesselcad::parts::{Reducer, ReducerAlignment, surface_area};

/// (large OD, small OD, length, flat side °).
const CASES: [(f64, f64, f64, f64); 4] = [
    (1000.0, 600.0, 800.0, 0.0),
    (2400.0, 1800.0, 1200.0, 90.0),
    (1600.0, 400.0, 900.0, 225.0),
    (3000.0, 2900.0, 300.0, -30.0),
];

fn nurbs_reducer(cone: &ObliqueCone) -> Reducer {
    Reducer {
        large_diameter: 2.0 * cone.large,
        small_diameter: 2.0 * cone.small,
        length: cone.length,
        alignment: ReducerAlignment::Eccentric {
            flat_side: cone.flat_side.to_degrees(),
        },
    }
}

#[test]
fn an_oblique_cone_develops_to_its_exact_area() {
    for (large, small, length, flat) in CASES {
        let t = 12.0;
        let cone = ObliqueCone::mid_surface(large, small, length, flat, t);
        let exact = surface_area(&nurbs_reducer(&cone).patches().unwrap());
        let area = cone.area();
        assert!(
            (area - exact).abs() <= 1e-9 * exact,
            "{large}/{small}×{length} at {flat}°: developed {area}, NURBS {exact}"
        );
        // The plates of a split add up to the whole, exactly.
        let plates = 3;
        let split: f64 = (0..plates)
            .flat_map(|k| [(0.0, 0.4 * length), (0.4 * length, length)].map(|z| (k, z)))
            .map(|(k, z)| {
                ObliquePlate {
                    cone,
                    from: 0.7 + k as f64 * TAU / plates as f64,
                    angle: TAU / plates as f64,
                    z,
                }
                .area()
            })
            .sum();
        assert!((split - exact).abs() <= 1e-9 * exact, "{split} vs {exact}");
        // The outline as a polygon: its chords cut off at most the sag
        // bound times the edges' length.
        let whole = cone.whole();
        let outline = whole.outline();
        let polygon = polygon_area(&outline).abs();
        let perimeter = TAU * (cone.large + cone.small);
        assert!((area - polygon).abs() <= OUTLINE_SAG * perimeter);
        // Less than a full turn: a cone, not a plane.
        assert!(cone.angle() < TAU, "{}", cone.angle());
    }
}

#[test]
fn generators_keep_their_length_and_points_roll_back_onto_the_surface() {
    for (large, small, length, flat) in CASES {
        let cone = ObliqueCone::mid_surface(large, small, length, flat, 10.0);
        let surface = &nurbs_reducer(&cone).patches().unwrap()[0].surface;
        let plate = ObliquePlate {
            cone,
            from: cone.flat_side + 1.1,
            angle: 2.5,
            z: (0.2 * length, 0.9 * length),
        };
        for i in 0..=20 {
            let phi = plate.from + plate.angle * f64::from(i) / 20.0;
            let (a, b) = (plate.develop(phi, plate.z.0), plate.develop(phi, plate.z.1));
            let (pa, pb) = (cone.point(phi, plate.z.0), cone.point(phi, plate.z.1));
            // Generators: straight and of the same length; distances from the
            // apex too.
            assert!((a.distance(b) - pa.distance(pb)).abs() < 1e-9 * large);
            assert!(
                (a.distance(b) - cone.generator(phi, plate.z.0, plate.z.1)).abs() < 1e-9 * large
            );
            assert!((a.length() - pa.distance(cone.apex())).abs() < 1e-9 * large);
            for (q, z) in [(a, plate.z.0), (b, plate.z.1), ((a + b) * 0.5, 0.0)] {
                let back = plate.roll_back(q);
                let on = surface.closest_point(back).unwrap();
                assert!(
                    on.distance < 1e-6,
                    "{large}/{small} at {phi}: {} off",
                    on.distance
                );
                if z > 0.0 {
                    assert!((back.z - z).abs() < 1e-6 && back.distance(cone.point(phi, z)) < 1e-6);
                }
            }
        }
        // The chords of the outline stay within the sag bound of the curve.
        for z in [plate.z.0, plate.z.1] {
            let edge = plate.edge(z);
            let n = edge.len() - 1;
            for k in 0..n {
                let phi = plate.from + plate.angle * (k as f64 + 0.5) / n as f64;
                let mid = plate.develop(phi, z);
                let (p, q) = (edge[k], edge[k + 1]);
                let d = (q - p).perp().normalize().dot(mid - p).abs();
                assert!(d <= OUTLINE_SAG, "sag {d} mm");
            }
        }
    }
}

/// A vertical vessel with an eccentric reducer R1 (2000 → 1400 OD, 800 long,
/// flat side at 90°), every wall 12 mm.
fn eccentric_design() -> vesselcad::design::Design {
    parse(
        r#"{"format": "vesselcad/1", "vessels": [{"tag": "X", "kind": "vertical",
          "design": {"pressure": 500, "temperature": 100, "material": "SA-516-70"},
          "parts": [
            {"head": {"id": "H1", "shape": "ellipsoidal", "thickness": 12}},
            {"shell": {"id": "S1", "od": 2000, "length": 2000, "thickness": 12}},
            {"reducer": {"id": "R1", "length": 800, "eccentric": 90, "thickness": 12}},
            {"shell": {"id": "S2", "od": 1400, "length": 2000, "thickness": 12}},
            {"head": {"id": "H2", "shape": "ellipsoidal", "thickness": 12}}
          ],
          "nozzles": [
            {"mark": "N1", "size": 4, "rating": 150, "host": "S2", "orientation": 30,
              "elevation": 3800, "projection": 1200}
          ]}]}"#,
    )
    .unwrap()
}

#[test]
fn an_eccentric_reducer_gets_plates_dxfs_bom_lines_and_welds() {
    let design = eccentric_design();
    // Plates short enough that each course of the reducer is cut in two.
    let mut rules = ShopRules::builtin();
    rules.plates.max_plate_length = 4000.0;
    let shop = rules.plates.clone();
    let p = plan(&design, "X", &shop).unwrap();
    assert!(p.developments.skipped.iter().all(|s| s.id != "R1"));
    let (ri, r) = p
        .developments
        .rolled
        .iter()
        .enumerate()
        .find(|(_, r)| r.id == "R1")
        .unwrap();
    assert_eq!(r.kind, RolledKind::Cone);
    let cone = r.oblique().expect("an oblique cone");
    let plates: Vec<_> = p.plates.iter().filter(|pl| pl.part == "R1").collect();
    assert!(plates.len() >= 2, "{} plates", plates.len());
    let whole = cone.area();
    let mut sum = 0.0;
    for pl in &plates {
        let Outline::Oblique(o) = pl.outline else {
            panic!("{} is not an oblique plate", pl.id);
        };
        assert!((o.area() - pl.mid_area).abs() <= 1e-12 * whole);
        let (w, h) = pl.outline.extent();
        assert!(
            w <= shop.max_plate_length + 1e-6 && h > 0.0,
            "{} {w} x {h}",
            pl.id
        );
        sum += pl.mid_area;
        let course = &p.seams.courses[pl.course_index];
        assert_eq!(course.rolled, ri);
        let dxf = plate_drawing(pl, &p.grade, r, course);
        assert!(dxf.entities().count() >= 3, "{}", pl.id);
    }
    assert!((sum - whole).abs() <= 1e-9 * whole, "{sum} vs {whole}");
    let exact = surface_area(&nurbs_reducer(&cone).patches().unwrap());
    assert!((sum - exact).abs() <= 1e-9 * exact);

    let process = process_plan(&p, &rules).unwrap();
    let bom: Vec<_> = process
        .bom
        .lines
        .iter()
        .filter(|l| l.part == "R1")
        .collect();
    assert_eq!(bom.len(), plates.len(), "{bom:#?}");
    // Long seams of the reducer: category A, along its outside generators.
    let long: Vec<_> = process
        .welds
        .iter()
        .filter(|w| w.id.starts_with("L-R1-"))
        .collect();
    assert_eq!(long.len(), plates.len());
    for w in &long {
        assert_eq!(w.category.map(|c| format!("{c:?}")), Some("A".into()));
        // A generator of the outside: straight, at most the steep side's
        // hypot(800, 2 × 300) long.
        assert!((w.length - w.path[0].distance(w.path[1])).abs() < 1e-9);
        assert!(w.length > 0.0 && w.length < 800.0f64.hypot(600.0) + 1e-6);
        // Each end lies on the reducer's outside circle at its height.
        let local = r.frame.inverse();
        for end in &w.path {
            let q = local.transform_point3(*end);
            assert!(q.z > -1e-9 && q.z < 800.0 + 1e-9);
            let off = (q.truncate() - r.centre_at(q.z)).length() - r.outside_at(q.z);
            assert!(off.abs() < 1e-9, "{}: {off}", w.id);
        }
    }
}
