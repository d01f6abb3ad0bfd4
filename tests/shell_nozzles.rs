//! Hillside (offset), tangential and inclined nozzles on shell courses: the
//! design fields `offset` and `inclination` of a shell nozzle, their rules, the
//! exact opening, inch files and incremental edits. Closure of the envelope is
//! checked in `mesh_watertight.rs`.

use glam::DVec3;
use vesselcad::components::Opening;
use vesselcad::design::{Design, DesignError, parse, resolve};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::parts::tables::{Nps, pipe};

/// A vertical vessel with one course S1 (OD 2000, 3000 long) between 2:1 heads,
/// and nozzle N1 (`size`, with `fields` added: offset, inclination, pad…) on it
/// at 1500 mm, facing 30°, projecting 1800 mm.
fn vessel(size: f64, fields: &str) -> String {
    format!(
        r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "V", "kind": "vertical",
          "parts": [
            {{"head": {{"id": "H1", "shape": "ellipsoidal"}}}},
            {{"shell": {{"id": "S1", "od": 2000, "length": 3000}}}},
            {{"head": {{"id": "H2", "shape": "ellipsoidal"}}}}
          ],
          "nozzles": [
            {{"mark": "N1", "size": {size}, "rating": 150, "host": "S1", "orientation": 30,
              "elevation": 1500, "projection": 1800 {fields}}}
          ]}}]}}"#
    )
}

fn design(size: f64, fields: &str) -> Design {
    parse(&vessel(size, fields)).unwrap()
}

/// The one violation a design is refused with.
fn refused(text: &str) -> vesselcad::design::RuleViolation {
    let error: DesignError = match parse(text) {
        Ok(d) => resolve(&d).expect_err("the design must be refused"),
        Err(e) => e,
    };
    let violations = error.violations();
    assert_eq!(violations.len(), 1, "{error}");
    violations[0].clone()
}

/// The nozzle's axis is parallel to the radial direction of its orientation,
/// offset sideways (towards larger angles) by `offset`, and turned up by
/// `inclination`; its origin, where the projection is measured from, is
/// `offset` from the vessel axis at the elevation.
#[test]
fn hillside_and_inclined_nozzles_are_placed_as_their_fields_say() {
    let d = design(6.0, r#", "offset": 500, "inclination": 20"#);
    let n = &resolve(&d).unwrap()[0].nozzles[0];
    let (radial, side) = {
        let a = 30f64.to_radians();
        let b = 120f64.to_radians();
        (
            DVec3::new(a.sin(), a.cos(), 0.0),
            DVec3::new(b.sin(), b.cos(), 0.0),
        )
    };
    let origin = DVec3::new(0.0, 0.0, 1500.0) + side * 500.0;
    assert!((n.frame.translation - origin).length() < 1e-9);
    let axis = n.frame.matrix3 * DVec3::Z;
    let i = 20f64.to_radians();
    assert!((axis - (radial * i.cos() + DVec3::Z * i.sin())).length() < 1e-12);
    // Radial when both are zero: the same frame as without them.
    let zero = resolve(&design(6.0, r#", "offset": 0, "inclination": 0"#)).unwrap();
    let plain = resolve(&design(6.0, "")).unwrap();
    assert_eq!(zero[0].nozzles[0].frame, plain[0].nozzles[0].frame);
}

/// The neck–course loop of hillside, near-tangential and inclined nozzles lies
/// on both surfaces: on the course's cylinder (radius 1000) and on the neck's
/// (the pipe's outside radius about the nozzle axis), at every point.
#[test]
fn the_opening_lies_on_the_course_and_on_the_neck() {
    let r = pipe(Nps::try_new(6.0).unwrap()).outside_diameter / 2.0;
    for fields in [
        r#", "offset": 500"#.to_string(),
        r#", "offset": -300, "inclination": -30"#.to_string(),
        r#", "inclination": 45"#.to_string(),
        // Near tangential: the neck's outer wall 20 mm inside the course's face.
        format!(r#", "offset": {}"#, 980.0 - r),
    ] {
        let d = design(6.0, &fields);
        let resolved = resolve(&d).unwrap();
        let host = resolved[0].parts.iter().find(|p| p.id == "S1").unwrap();
        let nozzle = &resolved[0].nozzles[0];
        // Nozzle frame in the host's frame.
        let to_nozzle = nozzle.frame.inverse() * host.frame;
        let mut model = Model::from_design(&d, TessellationOptions::chord(0.5)).unwrap();
        assert!(
            model.errors().0.is_empty(),
            "{fields}: {:?}",
            model.errors()
        );
        let mut query = model.query::<&Opening>();
        let world = model.world();
        let openings: Vec<&Opening> = query.iter(world).collect();
        assert_eq!(openings.len(), 1, "{fields}");
        let points = &openings[0].curve.points;
        assert!(points.len() >= 16, "{fields}: {} points", points.len());
        for p in points {
            let on_course = p.truncate().length() - 1000.0;
            let q = to_nozzle.transform_point3(*p);
            let on_neck = q.truncate().length() - r;
            assert!(on_course.abs() < 1e-6, "{fields}: {on_course}");
            assert!(on_neck.abs() < 1e-6, "{fields}: {on_neck}");
        }
    }
}

/// Editing a nozzle's offset and inclination in place gives the very bytes of
/// a full build of the edited design.
#[test]
fn editing_offset_and_inclination_equals_a_full_build() {
    let options = TessellationOptions::chord(1.0);
    let mut model = Model::from_design(&design(6.0, ""), options).unwrap();
    for fields in [
        r#", "offset": 400"#,
        r#", "offset": 400, "inclination": 15"#,
        r#", "offset": -650, "inclination": -40, "pad": {"od": 400, "thickness": 12}"#,
        "",
    ] {
        let edited = design(6.0, fields);
        model.edit(Edit::ReplaceDesign(edited.clone())).unwrap();
        let full = Model::from_design(&edited, options).unwrap();
        let glb = |m: &Model| vesselcad::export::write_glb(&m.scene()).unwrap();
        assert!(glb(&model) == glb(&full), "{fields}");
    }
}

#[test]
fn out_of_range_fields_are_refused_naming_path_entity_field_value_and_rule() {
    let v = refused(&vessel(6.0, r#", "inclination": 50"#));
    assert_eq!(
        (
            v.path.as_str(),
            v.entity.as_str(),
            v.field.as_str(),
            v.value.as_str()
        ),
        (
            "vessels[0].nozzles[0].inclination",
            "V/N1",
            "inclination",
            "50"
        )
    );
    assert!(v.rule.contains("between -45 and 45"), "{v}");
    // Past the course's face: |offset| + half the pad OD beyond 0.98 R.
    let v = refused(&vessel(
        6.0,
        r#", "offset": 800, "pad": {"od": 400, "thickness": 10}"#,
    ));
    assert_eq!((v.field.as_str(), v.value.as_str()), ("offset", "800"));
    assert!(v.rule.contains("0.98") && v.rule.contains("pad OD"), "{v}");
    // Inclined far enough that the opening leaves the course.
    let text = vessel(6.0, r#", "inclination": 45"#)
        .replace(r#""elevation": 1500"#, r#""elevation": 2500"#);
    let v = refused(&text);
    assert_eq!(v.field, "elevation");
    assert!(v.rule.contains("must lie within its host S1"), "{v}");
    // A flange inside the shell at the side of a hillside nozzle.
    let text =
        vessel(6.0, r#", "offset": 600"#).replace(r#""projection": 1800"#, r#""projection": 850"#);
    let v = refused(&text);
    assert_eq!(v.field, "projection");
    assert!(v.rule.contains("farthest point"), "{v}");
    // On a head, inclination does not apply.
    let text = vessel(6.0, r#", "inclination": 10"#)
        .replace(r#""host": "S1""#, r#""host": "H2""#)
        .replace(r#""elevation": 1500,"#, "");
    let v = refused(&text);
    assert_eq!(
        (v.field.as_str(), v.path.as_str()),
        ("inclination", "vessels[0].nozzles[0].inclination")
    );
    assert!(v.rule.contains("shell nozzles only"), "{v}");
    // NaN-free but not finite: refused, not a panic.
    let v = refused(&vessel(6.0, r#", "offset": 1e300"#));
    assert_eq!(v.field, "offset");
}

/// Two hillside nozzles whose openings meet round the course are refused (the
/// footprint is measured from the stretched opening, not the neck's OD), and
/// the same two radial ones at those angles are not.
#[test]
fn hillside_openings_are_checked_for_overlap_by_their_true_shape() {
    let two = |offset: f64, second: f64| {
        format!(
            r#"{{"format": "vesselcad/1", "vessels": [{{"tag": "V", "kind": "vertical",
              "parts": [{{"shell": {{"id": "S1", "od": 2000, "length": 3000}}}}],
              "nozzles": [
                {{"mark": "N1", "size": 8, "rating": 150, "host": "S1", "orientation": 0,
                  "elevation": 1500, "projection": 1500, "offset": {offset}}},
                {{"mark": "N2", "size": 8, "rating": 150, "host": "S1", "orientation": {second},
                  "elevation": 1500, "projection": 1500}}
              ]}}]}}"#
        )
    };
    // N1 (OD 219.1) at 800 mm offset: its opening reaches from 43.7° to 65.4°
    // round the course (asin((800 ∓ 109.55) / 1000)); N2 radial at 68° reaches
    // back to 61.7°. The balls round the openings' centres meet (259 mm apart);
    // N1's ball, were it the neck's (109.55 mm), would not.
    let v = refused(&two(800.0, 68.0));
    assert_eq!((v.entity.as_str(), v.field.as_str()), ("V/N2", "mark"));
    assert!(v.rule.contains("nozzle N1"), "{v}");
    // Radial N1 (at 0°) is far from N2.
    assert!(resolve(&parse(&two(0.0, 68.0)).unwrap()).is_ok());
}

/// An inch file's offset is converted like any length; the inclination is an
/// angle and stays as written.
#[test]
fn inch_files_convert_the_offset_and_keep_the_inclination() {
    let text = r#"{"format": "vesselcad/1", "units": "in", "vessels": [{"tag": "V", "kind": "vertical",
      "parts": [{"shell": {"id": "S1", "od": 80, "length": 120}}],
      "nozzles": [{"mark": "N1", "size": 6, "rating": 150, "host": "S1", "orientation": 30,
        "elevation": 60, "projection": 60, "offset": 10, "inclination": 20}]}]}"#;
    let d = parse(text).unwrap();
    let n = &d.vessels[0].nozzles[0];
    assert!((n.offset.unwrap() - 254.0).abs() < 1e-9);
    assert_eq!(n.inclination, Some(20.0));
}

/// The nozzle schedule shows a hillside nozzle's offset and an inclined one's
/// angle beside its orientation.
#[test]
fn the_schedule_shows_offset_and_inclination() {
    let d = design(6.0, r#", "offset": 500, "inclination": -20"#);
    let model = Model::from_design(&d, TessellationOptions::chord(5.0)).unwrap();
    let data = vesselcad::drawing::vessel_data(&model, "V").unwrap();
    let sheet = vesselcad::drawing::compose(&data, &vesselcad::drawing::SheetOptions::default());
    let row = &sheet.schedule[0];
    assert_eq!(row.cells[9], "30° OFS 500 INC -20°", "{row:?}");
}
