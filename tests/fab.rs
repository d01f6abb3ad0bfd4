//! Fabrication planning (`vesselcad::fab`): exact developments, openings
//! rolled back onto their course, seam rules on every example and on random
//! layouts, loop-validity errors, and plate DXFs read back (and audited by
//! ezdxf where `target/occt-venv` has it).

mod common;

use std::f64::consts::TAU;
use std::process::Command;

use common::examples::{EXAMPLES, example};
use common::occt::occt_python;
use glam::{DVec2, DVec3};
use proptest::prelude::*;
use vesselcad::design::parse;
use vesselcad::fab::plate_dxf::{plate_drawing, write_plate};
use vesselcad::fab::seams::{angle_gap, vessel_angle};
use vesselcad::fab::{FabError, FabPlan, Outline, RolledKind, Shop, plan};
use vesselcad::parts::{Reducer, ReducerAlignment, Shell, surface_area};

fn plans() -> Vec<(String, FabPlan)> {
    let shop = Shop::default();
    let mut out = Vec::new();
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            let p =
                plan(&design, &v.tag, &shop).unwrap_or_else(|e| panic!("{name} {}: {e}", v.tag));
            out.push((format!("{name}/{}", v.tag), p));
        }
    }
    out
}

/// The exact mid-surface area of a rolled part from its NURBS patches.
fn nurbs_area(p: &FabPlan, rolled: usize) -> f64 {
    let r = &p.developments.rolled[rolled];
    let length = r.z.1 - r.z.0;
    let patches = if r.is_cylinder() {
        Shell {
            outside_diameter: 2.0 * r.radius.0,
            length,
        }
        .patches()
    } else {
        let (a, b) = (2.0 * r.radius.0, 2.0 * r.radius.1);
        Reducer {
            large_diameter: a.max(b),
            small_diameter: a.min(b),
            length,
            alignment: ReducerAlignment::Concentric,
        }
        .patches()
    };
    surface_area(&patches.expect("mid-surface builds"))
}

#[test]
fn developed_plates_have_the_exact_mid_surface_area() {
    let mut checked = 0;
    for (name, p) in plans() {
        for (ri, r) in p.developments.rolled.iter().enumerate() {
            let plates: Vec<_> = p
                .plates
                .iter()
                .filter(|pl| p.seams.courses[pl.course_index].rolled == ri)
                .collect();
            let developed: f64 = plates.iter().map(|pl| pl.outline.area()).sum();
            let exact = nurbs_area(&p, ri);
            let rel = (developed - exact).abs() / exact;
            assert!(
                rel < 1e-9,
                "{name} {}: developed {developed} exact {exact} ({rel:e})",
                r.id
            );
            for pl in &plates {
                let rel = (pl.outline.area() - pl.mid_area).abs() / pl.mid_area;
                assert!(rel < 1e-12, "{name} {}", pl.id);
            }
            checked += 1;
        }
        for h in &p.developments.heads {
            let blank = 0.25 * std::f64::consts::PI * h.diameter * h.diameter;
            assert!(
                (blank - h.mid_area).abs() / h.mid_area < 1e-12,
                "{name} {}",
                h.id
            );
        }
    }
    assert!(checked >= 8, "{checked} parts checked");
}

#[test]
fn cone_sector_is_the_exact_development() {
    let (_, p) = plans()
        .into_iter()
        .find(|(n, _)| n == "vertical-column/C-201")
        .expect("the column");
    let (ri, cone) = p
        .developments
        .rolled
        .iter()
        .enumerate()
        .find(|(_, r)| r.kind == RolledKind::Cone)
        .expect("the column's reducer");
    let Outline::Sector {
        inner,
        outer,
        angle,
    } = cone.outline(0.0, TAU, cone.z.0, cone.z.1)
    else {
        panic!("a cone develops to a sector");
    };
    // Arc lengths of the sector equal the circumferences of the ends; the
    // radial width equals the slant height.
    let (ra, rb) = (
        cone.radius.0.max(cone.radius.1),
        cone.radius.0.min(cone.radius.1),
    );
    assert!((outer * angle - TAU * ra).abs() < 1e-9 * ra);
    assert!((inner * angle - TAU * rb).abs() < 1e-9 * ra);
    assert!((outer - inner - cone.slant(cone.z.0, cone.z.1)).abs() < 1e-9 * ra);
    let exact = nurbs_area(&p, ri);
    assert!(
        (Outline::Sector {
            inner,
            outer,
            angle
        }
        .area()
            - exact)
            .abs()
            / exact
            < 1e-9
    );
}

/// Distance from `p` to the neck axis of a cut.
fn axis_distance(origin: DVec3, axis: DVec3, p: DVec3) -> f64 {
    let d = p - origin;
    (d - d.dot(axis) * axis).length()
}

#[test]
fn openings_rolled_back_onto_the_course_lie_on_the_intersection_curve() {
    let mut points = 0;
    for (name, p) in plans() {
        for plate in &p.plates {
            let course = &p.seams.courses[plate.course_index];
            let rolled = &p.developments.rolled[course.rolled];
            let r = rolled.radius.0;
            let theta0 = course.seam(plate.seam);
            for o in &plate.openings {
                // A nozzle's or a boot's.
                let cut = p.openings.all().find(|c| c.mark == o.mark).expect("a cut");
                for q in &o.contour {
                    // Roll the developed point back onto the mid-surface cylinder.
                    let theta = theta0 + q.x / r;
                    let z = course.z.0 + q.y;
                    let back = DVec3::new(r * theta.cos(), r * theta.sin(), z);
                    let off = axis_distance(cut.neck.origin, cut.neck.axis, back) - cut.cut_radius;
                    assert!(
                        off.abs() < 1e-6,
                        "{name} {} {}: {off:e} mm",
                        plate.id,
                        o.mark
                    );
                    points += 1;
                }
            }
        }
    }
    assert!(points > 1000, "{points} points");
}

#[test]
fn pads_and_neck_ends_lie_on_their_curves() {
    for (name, p) in plans() {
        for cut in &p.openings.cuts {
            // The neck end: each point, wrapped back onto the neck's mid
            // cylinder, lies on the shell's inside (set-in, the default).
            let rolled = &p.developments.rolled[cut.rolled];
            let inside = rolled.outside.0 - rolled.thickness;
            let nozzle = &p.resolved.nozzles[cut.nozzle];
            let back = nozzle.geometry.projection - nozzle.geometry.flange_length().unwrap();
            let neck_mid = cut.saddle.last().unwrap().x / TAU;
            for q in &cut.saddle {
                let phi = q.x / neck_mid;
                let s = back - q.y;
                let n = cut.neck;
                let point =
                    n.origin + neck_mid * (phi.cos() * n.e1 + phi.sin() * n.e2) + s * n.axis;
                let off = point.truncate().length() - inside;
                assert!(off.abs() < 1e-6, "{name} {}: {off:e}", cut.mark);
            }
            if let Some(pad) = &cut.pad {
                assert!(pad.area() > 0.0);
                // Footprint points on the shell's outside, at the pad radius
                // from the axis.
                for f in &pad.footprint {
                    let point = DVec3::new(
                        rolled.outside.0 * f.x.cos(),
                        rolled.outside.0 * f.x.sin(),
                        f.y,
                    );
                    let off = axis_distance(cut.neck.origin, cut.neck.axis, point) - 0.5 * pad.od;
                    assert!(off.abs() < 1e-6, "{name} {} pad: {off:e}", cut.mark);
                }
            }
        }
    }
}

/// Checks every seam rule of `p` with `shop`, independently of the layout:
/// plate sizes, stagger across each joint of the stack, clearance from every
/// opening and pad, and returns the broken rules (each should be a reported
/// deficiency).
fn broken_seam_rules(p: &FabPlan, shop: &Shop) -> Vec<String> {
    let mut broken = Vec::new();
    for c in &p.seams.courses {
        let r = &p.developments.rolled[c.rolled];
        let rmax = r.radius_at(c.z.0).max(r.radius_at(c.z.1));
        assert!(
            TAU * rmax / c.plates as f64 <= shop.max_plate_length + 1e-6,
            "{} too long",
            c.id
        );
        assert!(
            r.slant(c.z.0, c.z.1) <= shop.max_plate_width + 1e-6,
            "{} too wide",
            c.id
        );
        let clearance = shop.clearance_for(r.thickness);
        for cut in p.openings.cuts.iter().filter(|x| x.rolled == c.rolled) {
            let mut loops = vec![(cut.mark.clone(), &cut.hole)];
            if let Some(pad) = &cut.pad {
                loops.push((format!("{} pad", cut.mark), &pad.footprint));
            }
            for (what, points) in loops {
                for k in 0..c.plates {
                    let seam = c.seam(k);
                    // Developed distance from the seam segment to the loop.
                    let d = points
                        .iter()
                        .map(|q| {
                            let du = angle_gap(q.x, seam) * r.radius.0;
                            let dv = (c.z.0 - q.y).max(q.y - c.z.1).max(0.0);
                            du.hypot(dv)
                        })
                        .fold(f64::INFINITY, f64::min);
                    if d < clearance - 1e-6 {
                        broken.push(format!("{what} {}", c.seam_id(k)));
                    }
                }
            }
        }
    }
    // Stagger across every joint of the stack (skirts apart).
    let stack: Vec<_> = p
        .seams
        .courses
        .iter()
        .filter(|c| p.developments.rolled[c.rolled].kind != RolledKind::Skirt)
        .collect();
    for a in &stack {
        for b in &stack {
            let (ra, rb) = (
                &p.developments.rolled[a.rolled],
                &p.developments.rolled[b.rolled],
            );
            let top_a = ra
                .frame
                .transform_point3(DVec3::Z * a.z.1)
                .z
                .max(ra.frame.transform_point3(DVec3::Z * a.z.0).z);
            let bottom_b = rb
                .frame
                .transform_point3(DVec3::Z * b.z.0)
                .z
                .min(rb.frame.transform_point3(DVec3::Z * b.z.1).z);
            if (top_a - bottom_b).abs() > 1e-6 {
                continue;
            }
            let r = ra
                .radius_at(a.z.0)
                .min(ra.radius_at(a.z.1))
                .min(rb.radius_at(b.z.0))
                .min(rb.radius_at(b.z.1));
            let need = shop.stagger_for(ra.thickness.max(rb.thickness));
            for i in 0..a.plates {
                for j in 0..b.plates {
                    let gap =
                        angle_gap(vessel_angle(ra, a.seam(i)), vessel_angle(rb, b.seam(j))) * r;
                    if gap < need - 1e-6 {
                        broken.push(format!("{} {}", a.seam_id(i), b.seam_id(j)));
                    }
                }
            }
        }
    }
    broken
}

#[test]
fn seam_rules_hold_on_every_example() {
    let shop = Shop::default();
    for (name, p) in plans() {
        assert!(
            p.seams.deficiencies.is_empty(),
            "{name}: {:?}",
            p.seams.deficiencies
        );
        let broken = broken_seam_rules(&p, &shop);
        assert!(broken.is_empty(), "{name}: {broken:?}");
    }
}

#[test]
fn seam_rules_hold_with_small_plates() {
    // Narrow, short plates: many courses and plates, joints moved clear.
    let shop = Shop::from_json(
        "test",
        r#"{"max_plate_width": 1500, "max_plate_length": 2500}"#,
        Some(Shop::default()),
    )
    .unwrap();
    for name in EXAMPLES {
        let design = example(name);
        for v in &design.vessels {
            let p =
                plan(&design, &v.tag, &shop).unwrap_or_else(|e| panic!("{name} {}: {e}", v.tag));
            let broken = broken_seam_rules(&p, &shop);
            assert!(
                broken.is_empty() || !p.seams.deficiencies.is_empty(),
                "{name} {}: broken {broken:?} but no deficiency",
                v.tag
            );
            assert!(
                broken.len() <= p.seams.deficiencies.len(),
                "{name}: {broken:?}"
            );
        }
    }
}

/// A vertical vessel: one course with 2:1 heads and the given nozzles
/// `(size, orientation, elevation, pad od)`.
fn vessel(od: f64, length: f64, t: f64, nozzles: &[(f64, f64, f64, Option<f64>)]) -> String {
    let nozzles: Vec<String> = nozzles
        .iter()
        .enumerate()
        .map(|(i, (size, orientation, elevation, pad))| {
            let pad = pad.map_or(String::new(), |d| format!(r#", "pad": {{"od": {d}, "thickness": {t}}}"#));
            format!(
                r#"{{"mark": "N{}", "size": {size}, "rating": 150, "host": "S1", "orientation": {orientation}, "elevation": {elevation}, "projection": {}{pad}}}"#,
                i + 1,
                od / 2.0 + 400.0
            )
        })
        .collect();
    format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{"tag": "V-1", "kind": "vertical",
        "placement": {{"position": [0, 0, 0], "rotation": 0}},
        "parts": [
          {{"head": {{"id": "H1", "shape": "ellipsoidal", "thickness": {t}}}}},
          {{"shell": {{"id": "S1", "od": {od}, "length": {length}, "thickness": {t}}}}},
          {{"head": {{"id": "H2", "shape": "ellipsoidal", "thickness": {t}}}}}],
        "nozzles": [{}]}}]}}"#,
        nozzles.join(",")
    )
}

#[test]
fn an_opening_across_a_joint_that_cannot_move_is_an_error_naming_both() {
    // Courses of 300 mm: the 420 mm pad of N1 cannot fit in one.
    let shop =
        Shop::from_json("test", r#"{"max_plate_width": 300}"#, Some(Shop::default())).unwrap();
    let design = parse(&vessel(
        2000.0,
        3000.0,
        12.0,
        &[(8.0, 90.0, 1500.0, Some(420.0))],
    ))
    .unwrap();
    let err = plan(&design, "V-1", &shop).unwrap_err();
    let FabError::Rules(v) = &err else {
        panic!("{err}");
    };
    assert!(
        v.iter().any(|e| e.entity.contains("N1")
            && e.rule.contains("circumferential seam")
            && e.rule.contains("S1-C")),
        "{err}"
    );
    assert!(
        v.iter()
            .all(|e| e.path.starts_with("vessels[0].nozzles[0]")),
        "{err}"
    );
}

#[test]
fn a_joint_near_an_opening_is_moved_clear() {
    // The preferred joint of a 4000 mm course with 2500 mm plates is at
    // 2000; a nozzle with its pad there pushes it aside, to the nearer side
    // at the clearance from the pad.
    let shop = Shop::default();
    let design = parse(&vessel(
        2000.0,
        4000.0,
        12.0,
        &[(8.0, 90.0, 2000.0 + 45.0, Some(420.0))],
    ))
    .unwrap();
    let p = plan(&design, "V-1", &shop).unwrap();
    let joint = p.seams.courses[0].z.1;
    let pad = p.openings.cuts[0].pad.as_ref().unwrap();
    let low = pad
        .footprint
        .iter()
        .map(|q| q.y)
        .fold(f64::INFINITY, f64::min);
    assert!(
        (joint - (low - 50.0)).abs() < 1e-9,
        "joint at {joint}, pad from {low}"
    );
    assert!(broken_seam_rules(&p, &shop).is_empty());
    assert!(
        p.seams.deficiencies.is_empty(),
        "{:?}",
        p.seams.deficiencies
    );
}

#[test]
fn an_unavoidable_long_seam_is_a_deficiency_naming_both() {
    // One plate per course on a small course; openings all around leave no
    // angle at the clearance: each seam closer than it is reported.
    let shop = Shop::from_json("test", r#"{"clearance": 400}"#, Some(Shop::default())).unwrap();
    let nozzles: Vec<_> = (0..6)
        .map(|i| (4.0, 60.0 * i as f64, 1000.0, None))
        .collect();
    let design = parse(&vessel(1500.0, 2000.0, 10.0, &nozzles)).unwrap();
    let p = plan(&design, "V-1", &shop).unwrap();
    assert!(!p.seams.deficiencies.is_empty());
    for d in &p.seams.deficiencies {
        assert!(
            d.entity.starts_with("V-1/N") && d.rule.contains("S1-C1-L"),
            "{d}"
        );
    }
}

#[test]
fn plate_dxf_reads_back_at_one_to_one_in_millimetres() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("fab_dxf");
    std::fs::create_dir_all(&dir).unwrap();
    let (_, p) = plans()
        .into_iter()
        .find(|(n, _)| n == "vertical-column/C-201")
        .unwrap();
    let python = occt_python();
    let mut with_openings = 0;
    for plate in &p.plates {
        let course = &p.seams.courses[plate.course_index];
        let rolled = &p.developments.rolled[course.rolled];
        let path = write_plate(&dir, plate, &p.grade, rolled, course).unwrap();
        assert_eq!(
            path.file_name().unwrap().to_str().unwrap(),
            format!("{}.dxf", plate.id)
        );
        assert!(plate.id.starts_with("C-201-"));
        let back = dxf::Drawing::load_file(&path).unwrap();
        assert_eq!(
            back.header.default_drawing_units,
            dxf::enums::Units::Millimeters
        );
        let mut cut = Vec::new();
        let mut texts = Vec::new();
        for e in back.entities() {
            match &e.specific {
                dxf::entities::EntityType::LwPolyline(l) if e.common.layer == "CUT" => cut.push(
                    l.vertices
                        .iter()
                        .map(|v| DVec2::new(v.x, v.y))
                        .collect::<Vec<_>>(),
                ),
                dxf::entities::EntityType::Text(t) => texts.push(t.value.clone()),
                _ => {}
            }
        }
        assert_eq!(cut.len(), 1 + plate.openings.len(), "{}", plate.id);
        assert!(texts.iter().any(|t| t == &plate.id));
        assert!(texts.iter().any(|t| t.contains("SA-516-70") && t.contains(&format!("t = {}", plate.thickness))));
        if let Outline::Rectangle { width, height } = plate.outline {
            let far = cut[0].iter().fold(DVec2::ZERO, |m, q| m.max(*q));
            assert!(
                (far - DVec2::new(width, height)).length() < 1e-9,
                "{}",
                plate.id
            );
        }
        for (o, back) in plate.openings.iter().zip(&cut[1..]) {
            assert_eq!(o.contour.len(), back.len());
            for (a, b) in o.contour.iter().zip(back) {
                assert!((*a - *b).length() < 1e-9);
            }
            with_openings += 1;
        }
        let _ = plate_drawing(plate, &p.grade, rolled, course);
        if let Some(python) = &python {
            let script = "import sys, ezdxf\ndoc = ezdxf.readfile(sys.argv[1])\na = doc.audit()\nprint(doc.header['$INSUNITS'], len(a.errors))\n";
            let out = Command::new(python)
                .arg("-c")
                .arg(script)
                .arg(&path)
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&out.stdout);
            if out.status.success() {
                assert_eq!(text.trim(), "4 0", "{}: {text}", plate.id);
            } else {
                let err = String::from_utf8_lossy(&out.stderr);
                assert!(
                    err.contains("No module named 'ezdxf'"),
                    "{}: {err}",
                    plate.id
                );
            }
        }
    }
    assert!(with_openings >= 5, "{with_openings}");
}

#[test]
fn a_part_without_thickness_is_named() {
    let text = vessel(2000.0, 3000.0, 12.0, &[]).replace(
        r#", "length": 3000, "thickness": 12"#,
        r#", "length": 3000"#,
    );
    let design = parse(&text).unwrap();
    let err = plan(&design, "V-1", &Shop::default())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("vessels[0].parts[1].thickness") && err.contains("V-1/S1"),
        "{err}"
    );
    let err = plan(&design, "V-9", &Shop::default())
        .unwrap_err()
        .to_string();
    assert!(err.contains("V-9"), "{err}");
}

fn cases() -> u32 {
    std::env::var("FAB_PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), ..ProptestConfig::default() })]

    /// Random courses, nozzles and plate sizes: every seam rule holds or is
    /// a reported deficiency; a refused layout names a nozzle.
    #[test]
    fn seam_rules_hold_on_random_layouts(
        od in 800.0f64..4000.0,
        length in 1500.0f64..9000.0,
        t in 6.0f64..30.0,
        width in 1000.0f64..3000.0,
        plate_length in 2000.0f64..12000.0,
        nozzles in prop::collection::vec((prop::sample::select(vec![2.0, 4.0, 6.0, 8.0, 12.0]), 0.0f64..360.0, 0.05f64..0.95, prop::bool::ANY), 0..6),
    ) {
        let nozzles: Vec<_> = nozzles
            .iter()
            .map(|&(size, o, e, pad)| (size, o.round(), (e * length).round(), pad.then_some(size * 25.4 * 2.2 + 50.0)))
            .collect();
        let Ok(design) = parse(&vessel(od.round(), length.round(), t.round(), &nozzles)) else {
            return Ok(()); // refused by the design rules (overlap, too close to an end)
        };
        let shop = Shop::from_json(
            "test",
            &format!(r#"{{"max_plate_width": {width}, "max_plate_length": {plate_length}}}"#),
            Some(Shop::default()),
        )
        .unwrap();
        match plan(&design, "V-1", &shop) {
            Ok(p) => {
                let broken = broken_seam_rules(&p, &shop);
                prop_assert!(broken.len() <= p.seams.deficiencies.len(), "{:?} vs {:?}", broken, p.seams.deficiencies);
            }
            Err(FabError::Rules(v)) => {
                for e in v {
                    prop_assert!(e.entity.starts_with("V-1/N") && e.path.starts_with("vessels[0].nozzles["), "{}", e);
                }
            }
            Err(e) => prop_assert!(false, "{}", e),
        }
    }
}
