//! Nozzle openings on concentric cones (`vesselcad::fab::cone_openings`):
//! the developed opening and pad footprint roll back onto the cutting
//! cylinder and the cone's mid-surface (outside) to 1e-6 mm, a nozzle
//! normal to a cone develops to an area within the bounds of π·r², the cone
//! plate's DXF carries the opening, and an opening no cone plate layout can
//! hold is a loop-validity error naming the opening and the seam.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use vesselcad::constraints::resolve_vessel;
use vesselcad::design::parse;
use vesselcad::fab::cone_openings::{ConeSurface, develop_point};
use vesselcad::fab::openings::{NeckAxis, polygon_area, samples};
use vesselcad::fab::plate_dxf::plate_drawing;
use vesselcad::fab::{FabError, FabPlan, FabWork, Shop, plan, plan_vessel};
use vesselcad::parts::tables::pipe;

/// The cone R1 of the test vessel: OD 2000 → 1400 over 900 mm, t = 12.
const LARGE: f64 = 1000.0;
const SMALL: f64 = 700.0;
const LENGTH: f64 = 900.0;
const T: f64 = 12.0;

/// A vertical vessel H1, S1 (OD 2000), R1 (the cone, from elevation 3000
/// to 3900), S2 (OD 1400), H2, with `nozzles` (JSON objects).
fn vessel(nozzles: &[&str], shop: &Shop) -> Result<FabPlan, FabError> {
    let text = format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{"tag": "V-1", "kind": "vertical",
        "placement": {{"position": [0, 0, 0], "rotation": 0}},
        "design": {{"pressure": 350, "temperature": 100, "material": "SA-516-70"}},
        "parts": [
          {{"head": {{"id": "H1", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12}}}},
          {{"shell": {{"id": "S1", "od": 2000, "length": 3000, "thickness": 12}}}},
          {{"reducer": {{"id": "R1", "length": 900, "thickness": 12}}}},
          {{"shell": {{"id": "S2", "od": 1400, "length": 2000, "thickness": 10}}}},
          {{"head": {{"id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 10}}}}],
        "nozzles": [{}]}}]}}"#,
        nozzles.join(",")
    );
    let design = parse(&text).expect("the test design parses");
    plan(&design, "V-1", shop)
}

const N4: &str = r#"{"mark": "N4", "size": 8, "rating": 150, "facing": "RF", "host": "R1",
    "orientation": 45, "elevation": 3450, "projection": 1300,
    "pad": {"od": 400, "thickness": 12}}"#;

/// dr/dz of R1's walls.
fn taper() -> f64 {
    (SMALL - LARGE) / LENGTH
}

/// R1's mid radius at part-local `z`, from the design's numbers: half the
/// wall in from the outside along the wall's normal.
fn mid_radius(z: f64) -> f64 {
    LARGE - 0.5 * T * taper().hypot(1.0) + taper() * z
}

/// Distance of `q` from the line through `o` along unit `d`.
fn off_axis(q: DVec3, o: DVec3, d: DVec3) -> f64 {
    let v = q - o;
    (v - v.dot(d) * d).length()
}

#[test]
fn a_cone_opening_rolls_back_onto_its_cylinder_and_the_mid_surface() {
    let shop = Shop::default();
    let p = vessel(&[N4], &shop).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        p.openings.formed.iter().all(|f| f.mark != "N4"),
        "N4 is developed, not listed"
    );
    let cut = p.openings.cones.iter().find(|c| c.mark == "N4").unwrap();
    let plate = p
        .plates
        .iter()
        .find(|pl| pl.openings.iter().any(|o| o.mark == "N4"))
        .expect("a cone plate holds N4");
    let course = &p.seams.courses[plate.course_index];
    let rolled = &p.developments.rolled[course.rolled];
    assert_eq!(rolled.id, "R1");
    assert_eq!(plate.part, "R1");
    let opening = plate.openings.iter().find(|o| o.mark == "N4").unwrap();

    // The neck axis in R1's frame, from the resolved nozzle.
    let n = &p.resolved.nozzles[cut.nozzle];
    let m = rolled.frame.inverse() * n.frame;
    let (o, d) = (m.translation, m.matrix3.z_axis.normalize());
    let rho = 0.5 * pipe(n.geometry.nps).outside_diameter + shop.bevel_allowance;

    // Roll a developed point back: slant distance and sector angle from the
    // plate's bisector (apex at the origin, bisector along +y).
    let k = taper();
    let sin = k.abs() / k.hypot(1.0);
    let mid = course.seam(plate.seam) + 0.5 * course.pitch();
    let roll = |q: DVec2| {
        let slant = q.length();
        let a = (-q.x).atan2(q.y);
        let theta = mid - k.signum() * a / sin;
        let r = slant * sin;
        let z = (r - mid_radius(0.0)) / k;
        DVec3::new(r * theta.cos(), r * theta.sin(), z)
    };
    assert!(opening.contour.len() >= 32);
    let mut worst: f64 = 0.0;
    for &q in &opening.contour {
        let x = roll(q);
        assert!(x.z > 0.0 && x.z < LENGTH, "{x} is on R1");
        let on_cone = (x.truncate().length() - mid_radius(x.z)).abs();
        let on_cylinder = (off_axis(x, o, d) - rho).abs();
        worst = worst.max(on_cone).max(on_cylinder);
    }
    assert!(worst < 1e-6, "rolled back within {worst:e} mm");
    // The centre rolls back onto the nozzle's axis.
    let c = roll(opening.centre);
    assert!(off_axis(c, o, d) < 1e-6);
    assert!((c.truncate().length() - mid_radius(c.z)).abs() < 1e-6);
    // A radial neck through a cone sloping at α: the opening is longer
    // along the generator than round the cone.
    let (lo, hi) = opening.contour.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
    );
    assert!(hi.y - lo.y > hi.x - lo.x);

    // The neck's end: each saddle point, put back on the neck's mid-surface,
    // lies on R1's inside (set-in), and the template is closed by the
    // flange's back.
    let od = pipe(n.geometry.nps).outside_diameter;
    let neck_mid = cut.saddle.last().unwrap().x / TAU;
    assert!(neck_mid < 0.5 * od && neck_mid > 0.5 * od - 20.0);
    let back = n.geometry.projection - n.geometry.flange_length().unwrap();
    let inside = |z: f64| LARGE - T * k.hypot(1.0) + k * z;
    let (e1, e2) = (m.matrix3.x_axis.normalize(), m.matrix3.y_axis.normalize());
    for q in &cut.saddle {
        let phi = q.x / neck_mid;
        let x = o + neck_mid * (phi.cos() * e1 + phi.sin() * e2) + (back - q.y) * d;
        assert!(
            (x.truncate().length() - inside(x.z)).abs() < 1e-6,
            "saddle {q} off R1's inside"
        );
    }
    // The pad's footprint lies on the pad's cylinder and the cone's outside.
    let pad = cut.pad.as_ref().expect("N4 has a pad");
    let outside = |z: f64| LARGE + k * z;
    for s in &pad.footprint {
        let x = DVec3::new(outside(s.y) * s.x.cos(), outside(s.y) * s.x.sin(), s.y);
        assert!((off_axis(x, o, d) - 200.0).abs() < 1e-6, "{s}");
    }
    // The pad developed on its own mid-surface: at least its projection
    // π·R² along the (radial) axis, at most that over the cosine of the
    // cone's half-angle plus the largest tilt of the cone's normal inside it;
    // nested as a piece at that area less its hole.
    let ring = |p: &[DVec2]| polygon_area(p).abs();
    let disc = PI * 200.0 * 200.0;
    let deficit = 1.0 - (TAU / pad.outline.len() as f64).sin() / (TAU / pad.outline.len() as f64);
    let tilt = sin.asin() + (200.0 / SMALL).asin();
    let area = ring(&pad.outline);
    assert!(
        area >= disc * (1.0 - 2.0 * deficit) && area <= disc / tilt.cos(),
        "pad area {area} vs π·R² {disc}"
    );
    assert!(ring(&pad.hole) > PI * rho * rho * (1.0 - 1e-3));
    // Rolled as a cone about its apex: the developed apex is the slant
    // distance from the pad cone's apex to where the axis meets it (found
    // by bisection along the axis from the centre), along -y.
    let pad_mid = |z: f64| LARGE + 6.0 * k.hypot(1.0) + k * z;
    let signed = |x: DVec3| x.truncate().length() - pad_mid(x.z);
    let (mut lo, mut hi) = (0.0, 100.0);
    assert!(signed(c) < 0.0 && signed(c + hi * d) > 0.0);
    for _ in 0..100 {
        let s = 0.5 * (lo + hi);
        if signed(c + s * d) > 0.0 {
            hi = s;
        } else {
            lo = s;
        }
    }
    let meets = c + lo * d;
    let apex = pad.apex.expect("a cone pad is rolled about its apex");
    assert!(
        (apex.length() - pad_mid(meets.z) / sin).abs() < 1e-6,
        "{apex}"
    );
    assert!(apex.x.abs() < 1e-6 && apex.y < 0.0, "along -y: {apex}");
    let piece = p
        .pieces()
        .into_iter()
        .find(|x| x.id == "V-1-N4-PAD")
        .expect("the cone pad is nested");
    assert!((piece.area - (area - ring(&pad.hole))).abs() < 1e-9 * area);
    assert_eq!(piece.thickness, 12.0);
}

#[test]
fn moving_a_cone_nozzle_redevelops_it_and_equals_a_fresh_plan() {
    let shop = Shop::default();
    let before = vessel(&[N4], &shop).unwrap_or_else(|e| panic!("{e}"));
    // The same design again: the cone cut is kept.
    let resolved = resolve_vessel(&before.vessel, 0).unwrap();
    let (again, work) = plan_vessel(&before.vessel, 0, &resolved, &shop, Some(&before)).unwrap();
    assert_eq!(work, FabWork::default());
    assert_eq!(again, before);
    // Turned by 30°: its opening is developed again, the result is the
    // plan made from nothing.
    let moved = N4.replace("\"orientation\": 45", "\"orientation\": 75");
    assert_ne!(moved, N4);
    let fresh = vessel(&[&moved], &shop).unwrap_or_else(|e| panic!("{e}"));
    let resolved = resolve_vessel(&fresh.vessel, 0).unwrap();
    let (kept, work) = plan_vessel(&fresh.vessel, 0, &resolved, &shop, Some(&before)).unwrap();
    assert_eq!(work.openings, 1);
    assert_eq!(work.parts, 0);
    assert_eq!(kept, fresh);
    let centre = |p: &FabPlan| p.openings.cones[0].centre.x;
    let turned = (centre(&kept) - centre(&before)).rem_euclid(TAU);
    let turned = turned.min(TAU - turned);
    assert!((turned - 30f64.to_radians()).abs() < 1e-9, "{turned}");
}

#[test]
fn a_neck_normal_to_a_cone_develops_to_about_pi_r_squared() {
    let k = taper();
    let cone = ConeSurface {
        r0: 994.0,
        z0: 0.0,
        k,
        lean: DVec2::ZERO,
    };
    let (theta, z) = (0.3_f64, 450.0);
    let r = cone.radius(z);
    let foot = DVec3::new(r * theta.cos(), r * theta.sin(), z);
    let normal = DVec3::new(theta.cos(), theta.sin(), -k).normalize();
    let e1 = DVec3::new(-theta.sin(), theta.cos(), 0.0);
    let e2 = normal.cross(e1);
    let neck = NeckAxis {
        origin: foot - 500.0 * normal,
        e1,
        e2,
        axis: normal,
    };
    for rho in [50.0, 100.0, 250.0] {
        let n = samples(rho, 0.05);
        let curve = cone
            .surface_loop(&neck, rho, theta, n)
            .expect("the neck meets the cone");
        let developed: Vec<DVec2> = curve
            .iter()
            .map(|&p| develop_point(&cone, theta, p))
            .collect();
        let area = polygon_area(&developed).abs();
        // The developed area is the cone's area inside the cylinder: at
        // least its projection π·ρ² (less the inscribed polygon's deficit),
        // at most that over the cosine of the largest tilt of the cone's
        // normal from the axis inside it (normal curvature 1/R_n, R_n ≥
        // r_min / cos α... here bounded by r_min).
        let z_top = curve.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.y));
        let r_min = cone.radius(z_top);
        let disc = PI * rho * rho;
        let deficit = 1.0 - (TAU / n as f64).sin() / (TAU / n as f64);
        let tilt = (rho / r_min).asin();
        assert!(
            area >= disc * (1.0 - 2.0 * deficit) && area <= disc / tilt.cos(),
            "ρ {rho}: area {area} vs π·ρ² {disc} (n {n}, tilt {tilt})"
        );
        // And the developed points are an isometry's image: each developed
        // chord is no shorter than the 3-D chord it maps.
        for w in curve.windows(2) {
            let at = |p: DVec2| {
                DVec3::new(
                    cone.radius(p.y) * p.x.cos(),
                    cone.radius(p.y) * p.x.sin(),
                    p.y,
                )
            };
            let chord3 = (at(w[1]) - at(w[0])).length();
            let chord2 =
                (develop_point(&cone, theta, w[1]) - develop_point(&cone, theta, w[0])).length();
            assert!(chord2 >= chord3 - 1e-9, "{chord2} < {chord3}");
        }
    }
}

#[test]
fn the_cone_plate_dxf_carries_the_opening() {
    let p = vessel(&[N4], &Shop::default()).unwrap_or_else(|e| panic!("{e}"));
    let plate = p
        .plates
        .iter()
        .find(|pl| pl.openings.iter().any(|o| o.mark == "N4"))
        .unwrap();
    let course = &p.seams.courses[plate.course_index];
    let rolled = &p.developments.rolled[course.rolled];
    let drawing = plate_drawing(plate, &p.grade, rolled, course);
    let mut cut = Vec::new();
    let mut texts = Vec::new();
    for e in drawing.entities() {
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
    assert_eq!(cut.len(), 2, "the sector and N4's opening");
    let opening = &plate.openings[0];
    assert_eq!(cut[1], opening.contour);
    assert!(texts.iter().any(|t| t == "N4"));
    assert!(texts.iter().any(|t| t == &plate.id));
    // The opening lies inside the sector: between its arcs and its edges.
    let vesselcad::fab::Outline::Sector {
        inner,
        outer,
        angle,
    } = plate.outline
    else {
        panic!("a cone plate is a sector");
    };
    for q in &opening.contour {
        assert!(q.length() > inner && q.length() < outer);
        assert!((-q.x).atan2(q.y).abs() < 0.5 * angle);
    }
}

#[test]
fn the_cone_plates_carry_the_vessel_quarter_lines_on_their_generators() {
    let p = vessel(&[N4], &Shop::default()).unwrap_or_else(|e| panic!("{e}"));
    let (k, mut labels, mut quarters) = (taper(), Vec::new(), Vec::new());
    let sin = k.abs() / k.hypot(1.0);
    for plate in p.plates.iter().filter(|pl| pl.part == "R1") {
        let course = &p.seams.courses[plate.course_index];
        let rolled = &p.developments.rolled[course.rolled];
        let drawing = plate_drawing(plate, &p.grade, rolled, course);
        let mid = course.seam(plate.seam) + 0.5 * course.pitch();
        for e in drawing.entities() {
            match &e.specific {
                dxf::entities::EntityType::Text(t) if t.value.ends_with('°') => {
                    labels.push(t.value.clone());
                }
                dxf::entities::EntityType::Line(l) if e.common.layer == "MARK" => {
                    // Rolled back: (θ, z) of each end.
                    let roll = |x: f64, y: f64| {
                        let theta = mid - k.signum() * (-x).atan2(y) / sin;
                        (theta, (x.hypot(y) * sin - mid_radius(0.0)) / k)
                    };
                    let (a, b) = (roll(l.p1.x, l.p1.y), roll(l.p2.x, l.p2.y));
                    if (a.1 - course.z.0).abs() > 1e-6 || (b.1 - course.z.1).abs() > 1e-6 {
                        continue;
                    }
                    assert!((a.0 - b.0).abs() < 1e-9, "a generator");
                    let v = rolled
                        .frame
                        .transform_vector3(DVec3::new(a.0.cos(), a.0.sin(), 0.0));
                    quarters.push(v.y.atan2(v.x).to_degrees().rem_euclid(360.0));
                }
                _ => {}
            }
        }
    }
    labels.sort();
    assert_eq!(labels, ["0°", "180°", "270°", "90°"]);
    quarters.sort_by(f64::total_cmp);
    assert_eq!(quarters.len(), 4, "{quarters:?}");
    for (q, want) in quarters.iter().zip([0.0, 90.0, 180.0, 270.0]) {
        let gap = (q - want).rem_euclid(360.0);
        assert!(gap.min(360.0 - gap) < 1e-6, "{quarters:?}");
    }
}

#[test]
fn an_opening_no_cone_plate_can_hold_is_an_error_naming_it_and_the_seam() {
    // Plates 200 mm long round R1: narrower than N4's opening.
    let shop = Shop {
        max_plate_length: 200.0,
        ..Shop::default()
    };
    let Err(FabError::Rules(errors)) = vessel(&[N4], &shop) else {
        panic!("an opening across a cone plate's seam is refused");
    };
    let e = errors
        .iter()
        .find(|e| e.entity == "V-1/N4")
        .unwrap_or_else(|| panic!("{errors:?}"));
    assert_eq!(e.path, "vessels[0].nozzles[0]");
    assert!(
        e.rule.contains("crosses longitudinal seam R1/R1-C1-L"),
        "{}",
        e.rule
    );
}
