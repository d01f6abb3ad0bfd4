//! Nozzle openings on eccentric reducers (oblique cones,
//! `vesselcad::fab::oblique_openings`): the opening developed on its plate
//! rolls back — by an inverse written here, with its own quadrature, from
//! the design's numbers — onto the cutting cylinder and the oblique
//! mid-surface to 1e-6 mm; the pad's footprint and the neck's saddle lie on
//! the reducer's outside and inside; the developed opening and pad have the
//! area of the cone inside their cylinders (between π·ρ² and π·ρ² over the
//! cosine of the cone's largest tilt there); the plate's DXF carries the
//! opening inside its outline; an opening no plate layout can hold is an
//! error naming it and the seam; a moved nozzle re-develops one opening and
//! equals a fresh plan; `vesselcad fab` develops them.

use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::process::Command;

use glam::{DVec2, DVec3};
use vesselcad::constraints::resolve_vessel;
use vesselcad::design::parse;
use vesselcad::fab::openings::polygon_area;
use vesselcad::fab::plate_dxf::plate_drawing;
use vesselcad::fab::seams::inside;
use vesselcad::fab::template_dxf::write_templates;
use vesselcad::fab::{FabError, FabPlan, FabWork, Outline, Shop, plan, plan_vessel};
use vesselcad::parts::tables::pipe;

/// The eccentric reducer R1 of the test vessel: OD 2000 → 1400 over 900
/// mm, t = 12, flat side at 30°.
const LARGE: f64 = 1000.0;
const SMALL: f64 = 700.0;
const LENGTH: f64 = 900.0;
const T: f64 = 12.0;
const FLAT: f64 = 30.0;

/// A vertical vessel H1, S1 (OD 2000), R1 (from elevation 3000 to 3900),
/// S2 (OD 1400), H2, with `nozzles` (JSON objects).
fn design_text(nozzles: &[&str]) -> String {
    format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{"tag": "V-1", "kind": "vertical",
        "placement": {{"position": [0, 0, 0], "rotation": 0}},
        "design": {{"pressure": 350, "temperature": 100, "material": "SA-516-70"}},
        "parts": [
          {{"head": {{"id": "H1", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 12}}}},
          {{"shell": {{"id": "S1", "od": 2000, "length": 3000, "thickness": 12}}}},
          {{"reducer": {{"id": "R1", "length": 900, "thickness": 12, "eccentric": {FLAT}}}}},
          {{"shell": {{"id": "S2", "od": 1400, "length": 2000, "thickness": 10}}}},
          {{"head": {{"id": "H2", "shape": "ellipsoidal", "straight_flange": 50, "thickness": 10}}}}],
        "nozzles": [{}]}}]}}"#,
        nozzles.join(",")
    )
}

fn vessel(nozzles: &[&str], shop: &Shop) -> Result<FabPlan, FabError> {
    let design = parse(&design_text(nozzles)).expect("the test design parses");
    plan(&design, "V-1", shop)
}

/// On the side away from the flat one, where the wall slopes most.
const N4: &str = r#"{"mark": "N4", "size": 8, "rating": 150, "facing": "RF", "host": "R1",
    "orientation": 225, "elevation": 3450, "projection": 1300,
    "pad": {"od": 400, "thickness": 12}}"#;

/// The oblique cone of R1's walls at radius `large` (large end) from the
/// design's numbers: circles of radius `radius(z)` about `centre(z)`, the
/// small end's centre `LARGE − SMALL` towards the flat side.
struct Cone {
    large: f64,
    flat: DVec2,
}

impl Cone {
    /// The wall `inset` mm in from the outside, in the planes of the circles.
    fn new(inset: f64, flat: f64) -> Self {
        Cone {
            large: LARGE - inset,
            flat: DVec2::from_angle(flat),
        }
    }

    fn centre(&self, z: f64) -> DVec2 {
        self.flat * (LARGE - SMALL) * z / LENGTH
    }

    fn radius(&self, z: f64) -> f64 {
        self.large + (SMALL - LARGE) * z / LENGTH
    }

    /// How far `x` is off the cone, mm.
    fn off(&self, x: DVec3) -> f64 {
        ((x.truncate() - self.centre(x.z)).length() - self.radius(x.z)).abs()
    }

    /// The point at angle `theta` about the circle at height `z`.
    fn at(&self, theta: f64, z: f64) -> DVec3 {
        (self.centre(z) + DVec2::from_angle(theta) * self.radius(z)).extend(z)
    }

    /// The unit normal at `x` (on the cone): the gradient of
    /// `|xy − c(z)|² − r(z)²`.
    fn normal(&self, x: DVec3) -> DVec3 {
        let w = x.truncate() - self.centre(x.z);
        let dc = self.flat * (LARGE - SMALL) / LENGTH;
        let dr = (SMALL - LARGE) / LENGTH;
        w.extend(-w.dot(dc) - self.radius(x.z) * dr).normalize()
    }

    fn apex(&self) -> DVec3 {
        let small = self.radius(LENGTH);
        let d = self.large - small;
        (self.flat * d).extend(LENGTH) * (self.large / d)
    }

    fn base(&self, phi: f64) -> DVec3 {
        (DVec2::from_angle(phi) * self.large).extend(0.0)
    }

    /// dψ/dφ of the development: `|(P − A) × P′| / |P − A|²`.
    fn turn(&self, phi: f64) -> f64 {
        let p = self.base(phi) - self.apex();
        let dp = (DVec2::from_angle(phi + FRAC_PI_2) * self.large).extend(0.0);
        p.cross(dp).length() / p.length_squared()
    }
}

/// Composite Simpson's rule on `n` (even) steps.
fn simpson(f: &impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + f(b) + inner) * h / 3.0
}

/// The developed angle ψ of a plate from its first generator `from`,
/// tabulated on fine steps, and its inverse.
struct Unroll {
    from: f64,
    h: f64,
    table: Vec<f64>,
}

impl Unroll {
    fn new(cone: &Cone, from: f64, angle: f64) -> Self {
        let steps = 4096;
        let h = angle / steps as f64;
        let mut table = vec![0.0];
        for i in 0..steps {
            let x = from + i as f64 * h;
            let last = *table.last().unwrap();
            table.push(last + simpson(&|p| cone.turn(p), x, x + h, 8));
        }
        Unroll { from, h, table }
    }

    fn total(&self) -> f64 {
        *self.table.last().unwrap()
    }

    /// φ at developed angle `psi`: bisection in its step.
    fn phi(&self, cone: &Cone, psi: f64) -> f64 {
        let i = self
            .table
            .partition_point(|&t| t <= psi)
            .clamp(1, self.table.len() - 1)
            - 1;
        let x = self.from + i as f64 * self.h;
        let g = |p: f64| self.table[i] + simpson(&|q| cone.turn(q), x, p, 8) - psi;
        let (mut lo, mut hi) = (x - self.h, x + 2.0 * self.h);
        assert!(g(lo) <= 0.0 && g(hi) >= 0.0, "ψ {psi} in step {i}");
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// A plate's development rolled back: its bisector along +y, the apex at
/// the origin; a point's developed angle from the first generator gives φ,
/// its distance from the apex the point on that generator.
struct PlateRoll {
    cone: Cone,
    unroll: Unroll,
}

impl PlateRoll {
    fn new(cone: Cone, from: f64, angle: f64) -> Self {
        let unroll = Unroll::new(&cone, from, angle);
        PlateRoll { cone, unroll }
    }

    fn roll(&self, q: DVec2) -> DVec3 {
        let total = self.unroll.total();
        let lay = FRAC_PI_2 - 0.5 * total;
        let mut want = (q.y.atan2(q.x) - lay).rem_euclid(TAU);
        if want > 0.5 * (total + TAU) {
            want -= TAU;
        }
        let phi = self.unroll.phi(&self.cone, want);
        let (a, b) = (self.cone.apex(), self.cone.base(phi));
        a + (b - a) * (q.length() / (b - a).length())
    }
}

/// Distance of `q` from the line through `o` along unit `d`.
fn off_axis(q: DVec3, o: DVec3, d: DVec3) -> f64 {
    let v = q - o;
    (v - v.dot(d) * d).length()
}

#[test]
fn an_eccentric_reducer_opening_rolls_back_onto_its_cylinder_and_the_oblique_mid_surface() {
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
        .expect("a reducer plate holds N4");
    let course = &p.seams.courses[plate.course_index];
    let rolled = &p.developments.rolled[course.rolled];
    assert_eq!(rolled.id, "R1");
    // The flat side in R1's frame (the design's is a compass bearing).
    let flat = rolled.flat_side.expect("R1 is eccentric");
    let Outline::Oblique(_) = plate.outline else {
        panic!("an eccentric reducer's plate is an oblique cone's")
    };
    let opening = plate.openings.iter().find(|o| o.mark == "N4").unwrap();

    // The neck axis in R1's frame, from the resolved nozzle.
    let n = &p.resolved.nozzles[cut.nozzle];
    let m = rolled.frame.inverse() * n.frame;
    let (o, d) = (m.translation, m.matrix3.z_axis.normalize());
    let od = pipe(n.geometry.nps).outside_diameter;
    let rho = 0.5 * od + shop.bevel_allowance;

    // Roll a developed point back onto the mid-surface.
    let mid = Cone::new(0.5 * T, flat);
    let plate_roll = PlateRoll::new(
        Cone::new(0.5 * T, flat),
        course.seam(plate.seam),
        course.pitch(),
    );
    let roll = |q: DVec2| plate_roll.roll(q);
    assert!(opening.contour.len() >= 32);
    let mut worst: f64 = 0.0;
    let mut tilt: f64 = 0.0;
    let mut rolled_back = Vec::new();
    for &q in &opening.contour {
        let x = roll(q);
        assert!(x.z > 0.0 && x.z < LENGTH, "{x} is on R1");
        worst = worst.max(mid.off(x)).max((off_axis(x, o, d) - rho).abs());
        tilt = tilt.max(mid.normal(x).dot(d).abs().acos());
        rolled_back.push(x);
    }
    assert!(worst < 1e-6, "rolled back within {worst:e} mm");
    // The centre rolls back onto the nozzle's axis.
    let c = roll(opening.centre);
    assert!(off_axis(c, o, d) < 1e-6 && mid.off(c) < 1e-6, "{c}");
    // The development is an isometry: each developed chord is no shorter
    // than the chord in space it unrolls.
    let k = opening.contour.len();
    for i in 0..k {
        let j = (i + 1) % k;
        let chord2 = (opening.contour[j] - opening.contour[i]).length();
        let chord3 = (rolled_back[j] - rolled_back[i]).length();
        assert!(chord2 >= chord3 - 1e-9, "{chord2} < {chord3}");
    }
    // The developed area is the cone's inside the cylinder: at least its
    // projection π·ρ² (less the inscribed polygon's deficit), at most that
    // over the cosine of the largest tilt of the cone's normal from the
    // axis (along a generator the normal does not turn, so the boundary
    // holds the largest).
    let disc = PI * rho * rho;
    let deficit = 1.0 - (TAU / k as f64).sin() / (TAU / k as f64);
    let area = polygon_area(&opening.contour).abs();
    assert!(
        area >= disc * (1.0 - 2.0 * deficit) && area <= disc / tilt.cos(),
        "opening area {area} vs π·ρ² {disc} (tilt {tilt})"
    );
    assert!(
        tilt > 0.1,
        "the oblique wall is tilted from the neck: {tilt}"
    );

    // The neck's end: each saddle point, put back on the neck's mid-surface,
    // lies on R1's inside (set-in).
    let neck_mid = cut.saddle.last().unwrap().x / TAU;
    assert!(neck_mid < 0.5 * od && neck_mid > 0.5 * od - 20.0);
    let back = n.geometry.projection - n.geometry.flange_length().unwrap();
    let inside = Cone::new(T, flat);
    let (e1, e2) = (m.matrix3.x_axis.normalize(), m.matrix3.y_axis.normalize());
    for q in &cut.saddle {
        let phi = q.x / neck_mid;
        let x = o + neck_mid * (phi.cos() * e1 + phi.sin() * e2) + (back - q.y) * d;
        assert!(inside.off(x) < 1e-6, "saddle {q} off R1's inside");
    }

    // The pad's footprint lies on the pad's cylinder and the reducer's
    // outside, φ about each circle's centre.
    let pad = cut.pad.as_ref().expect("N4 has a pad");
    let outside = Cone::new(0.0, flat);
    let mut pad_tilt: f64 = 0.0;
    for s in &pad.footprint {
        let x = outside.at(s.x, s.y);
        assert!((off_axis(x, o, d) - 200.0).abs() < 1e-6, "{s}");
        pad_tilt = pad_tilt.max(outside.normal(x).dot(d).abs().acos());
    }
    // The pad developed on its own mid-surface: between π·R² and π·R² over
    // the cosine of the largest tilt (taken on the outside, 6 mm under the
    // pad's mid-surface: 1e-3 to spare); nested at that area less its hole.
    let ring = |p: &[DVec2]| polygon_area(p).abs();
    let disc = PI * 200.0 * 200.0;
    let deficit = 1.0 - (TAU / pad.outline.len() as f64).sin() / (TAU / pad.outline.len() as f64);
    let pad_area = ring(&pad.outline);
    assert!(
        pad_area >= disc * (1.0 - 2.0 * deficit) && pad_area <= disc / pad_tilt.cos() * 1.001,
        "pad area {pad_area} vs π·R² {disc}"
    );
    // Centred on the nozzle axis.
    let (lo, hi) = pad.outline.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), q| (lo.min(*q), hi.max(*q)),
    );
    assert!(lo.x < -150.0 && hi.x > 150.0 && lo.y < -150.0 && hi.y > 150.0);
    assert!(ring(&pad.hole) > PI * rho * rho * (1.0 - 1e-3));
    // Rolled as a cone about its apex: the developed apex is as far from
    // the axis as the pad's own cone's apex is from where the axis meets
    // that cone (found here by bisection along the axis from the centre).
    let pad_cone = Cone::new(-6.0, flat);
    let signed = |x: DVec3| (x.truncate() - pad_cone.centre(x.z)).length() - pad_cone.radius(x.z);
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
        (apex.length() - (meets - pad_cone.apex()).length()).abs() < 1e-6,
        "{apex} vs {}",
        (meets - pad_cone.apex()).length()
    );
    assert!(apex.x.abs() < 1e-9 && apex.y < 0.0, "along -y: {apex}");
    let piece = p
        .pieces()
        .into_iter()
        .find(|x| x.id == "V-1-N4-PAD")
        .expect("the reducer's pad is nested");
    assert!((piece.area - (pad_area - ring(&pad.hole))).abs() < 1e-9 * pad_area);
}

#[test]
fn the_reducer_plate_dxf_carries_the_opening_inside_its_outline() {
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
    let mut marks = 0;
    for e in drawing.entities() {
        match &e.specific {
            dxf::entities::EntityType::LwPolyline(l) if e.common.layer == "CUT" => cut.push(
                l.vertices
                    .iter()
                    .map(|v| DVec2::new(v.x, v.y))
                    .collect::<Vec<_>>(),
            ),
            dxf::entities::EntityType::Line(_) if e.common.layer == "MARK" => marks += 1,
            dxf::entities::EntityType::Text(t) => texts.push(t.value.clone()),
            _ => {}
        }
    }
    assert_eq!(cut.len(), 2, "the plate and N4's opening");
    let opening = &plate.openings[0];
    assert_eq!(cut[1], opening.contour);
    assert!(marks >= 2, "N4's centrelines");
    assert!(texts.iter().any(|t| t == "N4"));
    assert!(texts.iter().any(|t| t == &plate.id));
    let Outline::Oblique(o) = plate.outline else {
        panic!("an oblique plate")
    };
    assert_eq!(cut[0], o.outline());
    for q in &opening.contour {
        assert!(inside(*q, &cut[0]), "{q} inside the plate");
    }
}

/// The MARK lines and TEXT values of a drawing.
fn marks_and_texts(drawing: &dxf::Drawing) -> (Vec<(DVec2, DVec2)>, Vec<String>) {
    let (mut lines, mut texts) = (Vec::new(), Vec::new());
    for e in drawing.entities() {
        match &e.specific {
            dxf::entities::EntityType::Line(l) if e.common.layer == "MARK" => {
                lines.push((DVec2::new(l.p1.x, l.p1.y), DVec2::new(l.p2.x, l.p2.y)))
            }
            dxf::entities::EntityType::Text(t) => texts.push(t.value.clone()),
            _ => {}
        }
    }
    (lines, texts)
}

#[test]
fn the_reducer_plates_carry_the_vessel_quarter_lines_on_their_generators() {
    let p = vessel(&[N4], &Shop::default()).unwrap_or_else(|e| panic!("{e}"));
    let mut quarters = Vec::new();
    let mut labels = Vec::new();
    for plate in p.plates.iter().filter(|pl| pl.part == "R1") {
        let course = &p.seams.courses[plate.course_index];
        let rolled = &p.developments.rolled[course.rolled];
        let (lines, texts) = marks_and_texts(&plate_drawing(plate, &p.grade, rolled, course));
        let flat = rolled.flat_side.expect("R1 is eccentric");
        labels.extend(texts.into_iter().filter(|t| t.ends_with('°')));
        let roll = PlateRoll::new(
            Cone::new(0.5 * T, flat),
            course.seam(plate.seam),
            course.pitch(),
        );
        let mid = Cone::new(0.5 * T, flat);
        for (a, b) in lines {
            let (x, y) = (roll.roll(a), roll.roll(b));
            // A quarter line runs from the plate's lower edge to its upper.
            if (x.z - course.z.0).abs() > 1e-6 || (y.z - course.z.1).abs() > 1e-6 {
                continue;
            }
            let angle = |q: DVec3| {
                let w = q.truncate() - mid.centre(q.z);
                w.y.atan2(w.x)
            };
            assert!(mid.off(x) < 1e-6 && mid.off(y) < 1e-6);
            assert!((angle(x) - angle(y)).abs() < 1e-9, "a generator");
            // Towards the vessel's quarter, in the vessel's frame.
            let vessel =
                rolled
                    .frame
                    .transform_vector3(DVec3::new(angle(x).cos(), angle(x).sin(), 0.0));
            quarters.push(vessel.y.atan2(vessel.x).to_degrees().rem_euclid(360.0));
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
fn a_reducer_pad_gets_its_template_rolled_about_its_apex() {
    let p = vessel(&[N4], &Shop::default()).unwrap_or_else(|e| panic!("{e}"));
    let cut = p.openings.cones.iter().find(|c| c.mark == "N4").unwrap();
    let pad = cut.pad.as_ref().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let written = write_templates(dir.path(), &p.tag, cut, &p.grade, 0.0).unwrap();
    assert_eq!(written.len(), 2, "pad and neck");
    let drawing = dxf::Drawing::load_file(dir.path().join("V-1-N4-PAD.dxf")).unwrap();
    let mut cut_lines = Vec::new();
    for e in drawing.entities() {
        if let dxf::entities::EntityType::LwPolyline(l) = &e.specific {
            cut_lines.push(
                l.vertices
                    .iter()
                    .map(|v| DVec2::new(v.x, v.y))
                    .collect::<Vec<_>>(),
            );
        }
    }
    assert_eq!(cut_lines.len(), 2, "outline and hole");
    for (read, want) in cut_lines.iter().zip([&pad.outline, &pad.hole]) {
        assert_eq!(read.len(), want.len());
        for (q, w) in read.iter().zip(want) {
            assert!((*q - *w).length() < 1e-9, "{q} vs {w}");
        }
    }
    let (lines, texts) = marks_and_texts(&drawing);
    let apex = pad.apex.unwrap();
    assert!(
        texts.iter().any(|t| t.contains("roll as a cone")
            && t.contains(&format!("{:.1} from the axis", apex.length()))),
        "{texts:?}"
    );
    // The generator towards the apex is marked.
    assert!(
        lines.iter().any(|(a, b)| {
            a.length() < 1e-9 && b.normalize().dot(apex.normalize()) > 1.0 - 1e-12
        })
    );
}

#[test]
fn an_opening_no_reducer_plate_can_hold_is_an_error_naming_it_and_the_seam() {
    // Plates 200 mm long round R1: narrower than N4's opening.
    let shop = Shop {
        max_plate_length: 200.0,
        ..Shop::default()
    };
    let Err(FabError::Rules(errors)) = vessel(&[N4], &shop) else {
        panic!("an opening across a reducer plate's seam is refused");
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

#[test]
fn moving_a_reducer_nozzle_redevelops_it_and_equals_a_fresh_plan() {
    let shop = Shop::default();
    let before = vessel(&[N4], &shop).unwrap_or_else(|e| panic!("{e}"));
    let resolved = resolve_vessel(&before.vessel, 0).unwrap();
    let (again, work) = plan_vessel(&before.vessel, 0, &resolved, &shop, Some(&before)).unwrap();
    assert_eq!(work, FabWork::default());
    assert_eq!(again, before);
    // Turned by 30°: its opening is developed again, the result is the
    // plan made from nothing.
    let moved = N4.replace("\"orientation\": 225", "\"orientation\": 255");
    assert_ne!(moved, N4);
    let fresh = vessel(&[&moved], &shop).unwrap_or_else(|e| panic!("{e}"));
    let resolved = resolve_vessel(&fresh.vessel, 0).unwrap();
    let (kept, work) = plan_vessel(&fresh.vessel, 0, &resolved, &shop, Some(&before)).unwrap();
    assert_eq!(work.openings, 1);
    assert_eq!(work.parts, 0);
    assert_eq!(kept, fresh);
    assert_ne!(kept.openings.cones, before.openings.cones);
}

#[test]
fn vesselcad_fab_develops_the_openings_of_eccentric_reducers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("v1.json");
    std::fs::write(&path, design_text(&[N4])).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(["fab", "--vessel", "V-1", "-o"])
        .arg(dir.path().join("out"))
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = stdout
        .lines()
        .find(|l| l.contains("N4") && l.contains("opening on R1"))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(
        line.contains("developed on eccentric reducer (oblique cone) plate V-1-R1-P"),
        "{line}"
    );
    assert!(!stdout.contains("listed, not developed"), "{stdout}");
    let plate = line.rsplit(' ').next().unwrap();
    let dxf = std::fs::read_to_string(dir.path().join("out").join(format!("{plate}.dxf"))).unwrap();
    assert!(dxf.contains("N4"), "{plate}.dxf marks N4");
    assert!(dir.path().join("out/V-1-N4-NECK.dxf").exists());
}
