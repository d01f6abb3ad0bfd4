//! A boot's fabrication (`vesselcad::fab::boot`): its developed plates have
//! the exact mid-surface area of the boot between its host end and its head's
//! tangent line (closed form with the complete elliptic integral), its host
//! end rolls back onto the intersection with the course, its opening is cut in
//! the course's plate (rolled back onto the boot's cutting cylinder) and kept
//! clear of the course's seams, and `vesselcad fab` writes its plate DXF, its
//! head's blank, its welds, BOM lines and operations.

mod common;

use std::f64::consts::{PI, TAU};

use common::examples::example;
use glam::{DVec2, DVec3};
use vesselcad::fab::openings::polygon_area;
use vesselcad::fab::seams::angle_gap;
use vesselcad::fab::welds::Category;
use vesselcad::fab::{FabPlan, Shop, ShopRules, plan, process_plan};

fn drum(shop: &Shop) -> FabPlan {
    plan(&example("horizontal-drum"), "V-101", shop).expect("the drum plans")
}

/// Complete elliptic integral of the second kind E(k) by the AGM.
fn elliptic_e(k: f64) -> f64 {
    let (mut a, mut b, mut c) = (1.0f64, (1.0 - k * k).sqrt(), k);
    let mut sum = 0.5 * c * c;
    let mut power = 0.5;
    for _ in 0..40 {
        let next = (0.5 * (a + b), (a * b).sqrt(), 0.5 * (a - b));
        (a, b, c) = next;
        power *= 2.0;
        sum += power * c * c;
        if c.abs() < 1e-17 {
            break;
        }
    }
    PI / (2.0 * a) * (1.0 - sum)
}

/// The radius of the host surface the boot's plate ends on (set-in: the
/// course's inside).
fn meets(p: &FabPlan) -> f64 {
    let cut = &p.openings.boots[0];
    let course = &p.developments.rolled[cut.rolled];
    course.outside.0 - course.thickness
}

#[test]
fn the_drum_boot_is_developed_with_its_head_blank() {
    let p = drum(&Shop::default());
    assert_eq!(p.developments.boots.len(), 1);
    let b = &p.developments.boots[0];
    assert_eq!(b.id, "B1");
    assert!(p.developments.skipped.iter().all(|s| s.id != "B1"));
    // Thickness from its host course, mid radius t/2 in from 610/2.
    assert_eq!(b.thickness, 14.0);
    assert_eq!(b.radius, 305.0 - 7.0);
    assert_eq!(b.tangent, 1200.0 + 900.0);
    let head = b.head.as_ref().expect("a blank for the boot's head");
    assert_eq!(head.id, "B1-HEAD");
    assert!(head.diameter > 610.0 && head.diameter < 800.0, "{head:?}");
    assert!(p.blanks().any(|h| h.id == "B1-HEAD"));
}

#[test]
fn developed_boot_area_is_the_exact_mid_surface_area() {
    for max in [10_000.0, 1_000.0] {
        let shop = Shop {
            max_plate_length: max,
            ..Shop::default()
        };
        let p = drum(&shop);
        let b = &p.developments.boots[0];
        let (r, big) = (b.radius, meets(&p));
        // The boot axis meets the host axis at right angles: the host end is
        // s(φ) = √(R² − r² sin² φ) from the host axis, so the region's area
        // is ∫ r (T − s) dφ = 2π r T − 4 r R E(r/R).
        let exact = TAU * r * b.tangent - 4.0 * r * big * elliptic_e(r / big);
        let plates = p.boot_plates();
        assert_eq!(plates.len(), if max > 5000.0 { 1 } else { 2 });
        let quadrature: f64 = plates.iter().map(|pl| pl.mid_area).sum();
        let developed: f64 = plates
            .iter()
            .map(|pl| polygon_area(&pl.outline).abs())
            .sum();
        for (what, got) in [("mid_area", quadrature), ("developed", developed)] {
            let rel = (got - exact).abs() / exact;
            assert!(rel < 1e-9, "{max}: {what} {got} exact {exact} ({rel:e})");
        }
        let widths: f64 = plates.iter().map(|pl| pl.extent().0).sum();
        assert!((widths - TAU * r).abs() < 1e-9);
    }
}

#[test]
fn the_host_end_rolls_back_onto_the_intersection() {
    let p = drum(&Shop::default());
    let b = &p.developments.boots[0];
    let cut = &p.openings.boots[0];
    let course = &p.developments.rolled[cut.rolled];
    let big = meets(&p);
    let to_course = course.frame.inverse() * b.frame;
    let mut worst = 0.0f64;
    let mut check = |x: f64, y: f64| {
        let phi = x / b.radius;
        let s = b.tangent - y;
        let q =
            to_course.transform_point3(DVec3::new(b.radius * phi.cos(), b.radius * phi.sin(), s));
        worst = worst.max((q.x.hypot(q.y) - big).abs());
    };
    for q in &cut.saddle {
        check(q.x, q.y);
    }
    // The plate's outline: its host end is the same curve.
    for plate in p.boot_plates() {
        let x0 = b.radius * plate.from;
        for q in &plate.outline[2..] {
            check(q.x + x0, q.y);
        }
    }
    assert!(
        worst < 1e-6,
        "host end off the intersection by {worst:e} mm"
    );
    assert!(cut.saddle.len() > 100);
}

#[test]
fn the_host_plate_carries_the_boot_opening() {
    let p = drum(&Shop::default());
    let b = &p.developments.boots[0];
    let cut = &p.openings.boots[0];
    let plate = p
        .plates
        .iter()
        .find(|pl| pl.openings.iter().any(|o| o.mark == "B1"))
        .expect("a plate of S1 carries B1's opening");
    let course = &p.seams.courses[plate.course_index];
    let rolled = &p.developments.rolled[course.rolled];
    let theta0 = course.seam(plate.seam);
    let r = rolled.radius_at(course.z.0);
    let opening = plate.openings.iter().find(|o| o.mark == "B1").unwrap();
    let to_boot = b.frame.inverse() * rolled.frame;
    let cut_radius = b.outside + Shop::default().bevel_allowance;
    assert_eq!(cut.cut_radius, cut_radius);
    let mut worst = 0.0f64;
    for q in &opening.contour {
        let theta = theta0 + q.x / r;
        let z = q.y + course.z.0;
        let local = to_boot.transform_point3(DVec3::new(r * theta.cos(), r * theta.sin(), z));
        worst = worst.max((local.x.hypot(local.y) - cut_radius).abs());
    }
    assert!(
        worst < 1e-6,
        "opening off the cutting cylinder by {worst:e} mm"
    );
    // Its centre is where the boot's axis meets the course's mid-surface.
    let c = opening.centre;
    let theta = theta0 + c.x / r;
    let local = to_boot.transform_point3(DVec3::new(
        r * theta.cos(),
        r * theta.sin(),
        c.y + course.z.0,
    ));
    assert!(local.x.hypot(local.y) < 1e-6, "{local}");
}

#[test]
fn course_seams_keep_clear_of_the_boot() {
    // The boot hangs under S1 at 4000 mm, in S1-C2; with one plate per
    // course the seams go where the clearance rule lets them.
    let p = drum(&Shop::default());
    let cut = &p.openings.boots[0];
    let clearance = Shop::default().clearance_for(14.0);
    for course in p.seams.courses.iter().filter(|c| c.rolled == cut.rolled) {
        let (lo, hi) = cut
            .hole
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                (l.min(q.y), h.max(q.y))
            });
        if hi < course.z.0 || lo > course.z.1 {
            continue;
        }
        let r = p.developments.rolled[cut.rolled].radius.0;
        for k in 0..course.plates {
            let gap = cut
                .hole
                .iter()
                .map(|q| r * angle_gap(q.x, course.seam(k)))
                .fold(f64::INFINITY, f64::min);
            assert!(
                gap >= clearance - 1e-9,
                "{} seam {k} at {:.1}° is {gap:.1} mm from B1 (clearance {clearance})",
                course.id,
                course.seam(k).to_degrees()
            );
        }
    }
    assert!(
        p.seams.deficiencies.is_empty(),
        "{:?}",
        p.seams.deficiencies
    );
}

#[test]
fn the_boot_has_its_welds_bom_lines_and_operations() {
    let p = drum(&Shop::default());
    let rules = ShopRules::builtin();
    let process = process_plan(&p, &rules).expect("the drum's process plan");
    let weld = |id: &str| {
        process
            .welds
            .iter()
            .find(|w| w.id == id)
            .unwrap_or_else(|| panic!("no weld {id}"))
    };
    assert_eq!(weld("N-B1").category, Some(Category::D));
    let long = weld("L-B1-1");
    assert_eq!(long.category, Some(Category::A));
    let plate = &p.boot_plates()[0];
    assert!((long.length - plate.outline.last().unwrap().y).abs() < 1e-9);
    let circ = weld("C-B1-B1-HEAD");
    assert_eq!(circ.category, Some(Category::B));
    assert!((circ.length - TAU * 298.0).abs() < 1e-9);
    let lines: Vec<_> = process
        .bom
        .lines
        .iter()
        .filter(|l| l.part == "B1")
        .collect();
    assert!(
        lines
            .iter()
            .any(|l| l.item == "V-101-B1-P1" && l.kind == "plate")
    );
    assert!(
        lines
            .iter()
            .any(|l| l.item == "B1-HEAD" && l.kind == "head")
    );
    let level = |id: &str| {
        process
            .operations
            .iter()
            .find(|o| o.id == id)
            .unwrap_or_else(|| panic!("no operation {id}"))
            .level
    };
    // The host's opening is cut before the boot is fitted, its long seam
    // welded before, its head formed before the boot-to-head seam.
    assert!(level("weld_long_seam:S1") < level("cut_opening:B1"));
    assert!(level("cut_opening:B1") < level("fit_weld_nozzle:B1"));
    assert!(level("weld_long_seam:B1") < level("fit_weld_nozzle:B1"));
    assert!(level("form_head:B1-HEAD") < level("fit_up:B1+B1-HEAD"));
    assert!(level("roll:B1") < level("weld_long_seam:B1"));
}

#[test]
fn fab_writes_the_boot_plate_and_blank_dxf() {
    let dir = common::fab::fab_files("horizontal-drum", "V-101");
    let p = drum(&Shop::default());
    let plate = &p.boot_plates()[0];
    let drawing = dxf::Drawing::load_file(dir.path().join("V-101-B1-P1.dxf")).unwrap();
    let cut: Vec<Vec<DVec2>> = drawing
        .entities()
        .filter(|e| e.common.layer == "CUT")
        .filter_map(|e| match &e.specific {
            dxf::entities::EntityType::LwPolyline(l) => {
                Some(l.vertices.iter().map(|v| DVec2::new(v.x, v.y)).collect())
            }
            _ => None,
        })
        .collect();
    assert_eq!(cut.len(), 1);
    assert_eq!(cut[0].len(), plate.outline.len());
    let area = polygon_area(&cut[0]).abs();
    assert!((area - plate.mid_area).abs() / plate.mid_area < 1e-9);
    for name in [
        "V-101-B1-HEAD-BLANK.dxf",
        "V-101-H1-BLANK.dxf",
        "V-101-H2-BLANK.dxf",
    ] {
        assert!(dir.path().join(name).exists(), "{name}");
    }
    let summary = std::fs::read_to_string(dir.path().join("summary.txt")).unwrap();
    assert!(summary.contains("boot plate V-101-B1-P1"), "{summary}");
    assert!(!summary.contains("not developed"), "{summary}");
}

#[test]
fn a_boot_no_plate_layout_can_hold_is_an_error_naming_it() {
    // Plates 700 mm round: B1's 616 mm opening and its clearance cannot fit
    // between two long seams of S1-C2 (loop validity, as for a nozzle).
    let shop = Shop {
        max_plate_length: 700.0,
        ..Shop::default()
    };
    let err = plan(&example("horizontal-drum"), "V-101", &shop).unwrap_err();
    let vesselcad::fab::FabError::Rules(v) = &err else {
        panic!("{err}");
    };
    assert!(
        v.iter().any(|e| e.entity == "V-101/B1"
            && e.path == "vessels[0].parts[5]"
            && e.rule.contains("longitudinal seam")),
        "{err}"
    );
}

#[test]
fn a_boot_higher_than_the_widest_plate_is_a_deficiency_naming_its_length() {
    let tall = |p: &FabPlan| {
        p.seams
            .deficiencies
            .iter()
            .filter(|d| d.entity == "V-101/B1")
            .cloned()
            .collect::<Vec<_>>()
    };
    // The drum's boot plate is about 952 mm high: it fits the default plates.
    let p = drum(&Shop::default());
    let high = p.boot_plates()[0].extent().1;
    assert!(
        high > 900.0 && high < Shop::default().max_plate_width,
        "{high}"
    );
    assert!(tall(&p).is_empty(), "{:?}", tall(&p));
    // With plates 900 mm wide the boot (one course) cannot be cut from one.
    let shop = Shop {
        max_plate_width: 900.0,
        ..Shop::default()
    };
    let d = tall(&drum(&shop));
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path, "vessels[0].parts[5].length");
    assert_eq!(d[0].field, "length");
    assert!(
        (d[0].value.parse::<f64>().unwrap() - high).abs() < 0.1,
        "{:?}",
        d[0]
    );
    assert!(d[0].rule.contains("max_plate_width"), "{}", d[0].rule);
}
