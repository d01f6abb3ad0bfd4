//! Edge discretization: the circle closed form, the chordal bound on every segment,
//! equal points for equal curves (reversed, rotated, shared by two patches), arc
//! length placement, rounding, lines, poles and bad input.

use std::f64::consts::{PI, TAU};

use glam::{DAffine3, DVec3};
use vesselcad::mesh::{MAX_EDGE_SEGMENTS, TessellationOptions, edge_parameters, edge_segments};
use vesselcad::nurbs::builders::{circle, circular_arc, elliptical_arc, line};
use vesselcad::nurbs::{KnotVector, NurbsCurve, Side};
use vesselcad::parts::Shell;
use vesselcad::parts::heads::{Head, HeadKind};

/// Samples per segment when measuring the chordal deviation.
const DEVIATION_SAMPLES: usize = 32;

/// Chordal tolerance only: no angle or edge-length limit.
fn chord_only(tolerance: f64) -> TessellationOptions {
    TessellationOptions::chord(tolerance).with_angle_tolerance(None)
}

/// The closed-form segment count of a full circle: ⌈2π / (2·arccos(1 − δ/R))⌉.
fn circle_rule(radius: f64, tolerance: f64) -> (f64, usize) {
    let raw = TAU / (2.0 * (1.0 - tolerance / radius).acos());
    (raw, raw.ceil() as usize)
}

fn xy_circle(radius: f64) -> NurbsCurve {
    circular_arc(DVec3::ZERO, DVec3::X, DVec3::Y, radius, 0.0, TAU).unwrap()
}

/// Distance from `p` to the segment `a`–`b`.
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length()
}

/// Largest distance of the true curve between consecutive vertices from their chord.
fn max_chord_deviation(curve: &NurbsCurve, params: &[f64]) -> f64 {
    params
        .windows(2)
        .map(|w| {
            let (a, b) = (curve.point(w[0]), curve.point(w[1]));
            (1..DEVIATION_SAMPLES)
                .map(|k| {
                    let u = w[0] + (w[1] - w[0]) * k as f64 / DEVIATION_SAMPLES as f64;
                    distance_to_segment(curve.point(u), a, b)
                })
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// The invariants of any result: both ends, non-decreasing, finite, count matches.
fn assert_well_formed(curve: &NurbsCurve, options: &TessellationOptions, multiple: usize) {
    let params = edge_parameters(curve, options, multiple);
    let (a, b) = curve.domain();
    assert!(params.len() >= 2);
    assert_eq!(params[0], a);
    assert_eq!(params[params.len() - 1], b);
    assert!(params.iter().all(|u| u.is_finite()));
    assert!(params.windows(2).all(|w| w[0] <= w[1]), "{params:?}");
    assert_eq!(params.len(), edge_segments(curve, options, multiple) + 1);
}

/// Asserts the chordal bound and arc-length placement of `curve`'s edge vertices.
fn assert_edge(curve: &NurbsCurve, options: &TessellationOptions) -> Vec<f64> {
    assert_well_formed(curve, options, 1);
    let params = edge_parameters(curve, options, 1);
    let deviation = max_chord_deviation(curve, &params);
    assert!(
        deviation <= options.tolerance * (1.0 + 1e-9),
        "deviation {deviation} > {}",
        options.tolerance
    );
    // Equal arc-length steps (each step measured on its own, so the check is
    // linear in the vertex count).
    let length = curve.arc_length();
    let step = length / (params.len() - 1) as f64;
    for (k, w) in params.windows(2).enumerate() {
        let s = curve.arc_length_between(w[0], w[1]);
        assert!(
            (s - step).abs() <= 1e-12 * length,
            "segment {k}: {s} mm, expected {step} mm"
        );
    }
    params
}

/// The vertices of `curve`'s edge.
fn points(curve: &NurbsCurve, options: &TessellationOptions, multiple: usize) -> Vec<DVec3> {
    edge_parameters(curve, options, multiple)
        .into_iter()
        .map(|u| curve.point(u))
        .collect()
}

/// Asserts two point sets are equal within `tol` (each point has a partner).
fn assert_same_points(a: &[DVec3], b: &[DVec3], tol: f64) {
    assert_eq!(a.len(), b.len());
    for (x, y) in [(a, b), (b, a)] {
        for p in x {
            let nearest = y
                .iter()
                .map(|q| (*p - *q).length())
                .fold(f64::MAX, f64::min);
            assert!(
                nearest <= tol,
                "{p} has no partner within {tol} ({nearest})"
            );
        }
    }
}

#[test]
fn circle_of_1000_mm_at_half_a_millimetre_has_100_segments() {
    let c = xy_circle(1000.0);
    for options in [chord_only(0.5), TessellationOptions::chord(0.5)] {
        assert_eq!(edge_segments(&c, &options, 1), 100);
        let params = assert_edge(&c, &options);
        assert_eq!(params.len(), 101);
        let sagitta = max_chord_deviation(&c, &params);
        let exact = 1000.0 * (1.0 - (PI / 100.0).cos());
        assert!((exact - 0.4934).abs() < 1e-4);
        assert!((sagitta - exact).abs() < 1e-6 * 1000.0, "{sagitta}");
    }
}

#[test]
fn circles_follow_the_closed_form() {
    let mut checked = 0;
    for radius in [5.0, 37.5, 150.0, 600.0, 1000.0, 1200.0, 2500.0, 8000.0] {
        for tolerance in [0.01, 0.05, 0.1, 0.25, 0.5, 1.0, 2.0] {
            if tolerance >= radius {
                continue;
            }
            let (raw, expected) = circle_rule(radius, tolerance);
            // Counts within rounding of an integer are not a test of the rule.
            if (raw - raw.round()).abs() < 1e-6 * raw {
                continue;
            }
            let c = xy_circle(radius);
            let options = chord_only(tolerance);
            assert_eq!(
                edge_segments(&c, &options, 1),
                expected,
                "R = {radius}, δ = {tolerance}"
            );
            checked += 1;
        }
    }
    assert!(checked > 40);
}

#[test]
fn chords_stay_within_the_tolerance() {
    let options = [
        chord_only(0.5),
        chord_only(0.01),
        TessellationOptions::chord(2.0),
        chord_only(1.0).with_max_edge_length(Some(40.0)),
    ];
    let ellipse = |rx, ry| elliptical_arc(DVec3::ZERO, DVec3::X, DVec3::Z, rx, ry, 0.0, PI / 2.0);
    let curves = [
        xy_circle(1000.0),
        xy_circle(12.0),
        circular_arc(
            DVec3::new(5.0, 1.0, 2.0),
            DVec3::Y,
            DVec3::Z,
            300.0,
            0.3,
            2.2,
        )
        .unwrap(),
        ellipse(1200.0, 600.0).unwrap(),
        ellipse(1200.0, 200.0).unwrap(),
        elliptical_arc(DVec3::ZERO, DVec3::X, DVec3::Y, 50.0, 400.0, -1.0, 4.0).unwrap(),
    ];
    for curve in &curves {
        for o in &options {
            assert_edge(curve, o);
        }
    }
}

#[test]
fn random_splines_meet_the_tolerance() {
    let mut seed: u64 = 0x5eed_0003_0004;
    let mut next = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for case in 0..20 {
        let degree = 2 + case % 3;
        let count = degree + 1 + case % 5;
        let knots = KnotVector::uniform(degree, count).unwrap();
        let pts: Vec<DVec3> = (0..count)
            .map(|_| DVec3::new(next(), next(), next() * 0.3) * 500.0)
            .collect();
        let weights: Vec<f64> = (0..count).map(|_| 0.5 + next()).collect();
        let curve = NurbsCurve::try_from_weighted(knots, &pts, &weights).unwrap();
        assert_edge(&curve, &chord_only(0.2));
        assert_edge(&curve, &TessellationOptions::chord(1.0));
    }
}

#[test]
fn the_same_circle_gives_the_same_points_in_any_direction_and_frame() {
    let options = TessellationOptions::chord(0.5);
    let forward = xy_circle(1000.0);
    let reversed = forward.reversed();
    let turned = forward.transformed(&DAffine3::from_rotation_x(PI)).unwrap();
    let built_clockwise = circular_arc(DVec3::ZERO, DVec3::X, -DVec3::Y, 1000.0, 0.0, TAU).unwrap();
    assert_eq!(points(&forward, &options, 1).len(), 101);
    for multiple in [1, 16] {
        let reference = points(&forward, &options, multiple);
        for other in [&reversed, &turned, &built_clockwise] {
            assert_same_points(&reference, &points(other, &options, multiple), 1e-9);
        }
    }
    // A 3D circle tilted out of every coordinate plane, also reversed.
    let normal = DVec3::new(0.3, -0.5, 0.8).normalize();
    let tilted = circle(DVec3::new(10.0, 20.0, -30.0), normal, 750.0).unwrap();
    let a = points(&tilted, &options, 4);
    let b = points(&tilted.reversed(), &options, 4);
    assert_same_points(&a, &b, 1e-9);
}

#[test]
fn segment_counts_round_up_to_the_multiple() {
    let c = xy_circle(1000.0);
    let options = TessellationOptions::chord(0.5);
    assert_eq!(edge_segments(&c, &options, 16), 112);
    assert_eq!(edge_parameters(&c, &options, 16).len(), 113);
    assert_eq!(edge_segments(&c, &options, 4), 100);
    assert_eq!(edge_segments(&c, &options, 0), 100);
    assert_eq!(edge_segments(&c, &options, 3), 102);
    assert_well_formed(&c, &options, 16);
    assert_well_formed(&c, &options, usize::MAX);
}

#[test]
fn lines_are_one_segment_unless_edges_are_limited() {
    let l = line(DVec3::new(1.0, 2.0, 3.0), DVec3::new(1.0, 2.0, 1003.0)).unwrap();
    assert_eq!(
        edge_parameters(&l, &TessellationOptions::chord(0.5), 1),
        vec![0.0, 1.0]
    );
    assert_eq!(edge_segments(&l, &chord_only(1e-6), 1), 1);
    let limited = chord_only(0.5).with_max_edge_length(Some(100.0));
    assert_eq!(edge_segments(&l, &limited, 1), 10);
    let params = edge_parameters(&l, &limited, 1);
    for (k, u) in params.iter().enumerate() {
        assert!((u - k as f64 / 10.0).abs() < 1e-14);
    }
    assert_eq!(
        edge_segments(&l, &chord_only(0.5).with_max_edge_length(Some(99.9)), 1),
        11
    );
    assert_eq!(edge_segments(&l, &chord_only(0.5), 8), 8);
    // A straight cubic with uneven speed is still one segment, and a limited one is
    // split evenly in length.
    let knots = KnotVector::uniform(3, 4).unwrap();
    let pts = [0.0, 1.0, 5.0, 100.0].map(|x| DVec3::new(x, 0.0, 0.0));
    let cubic = NurbsCurve::try_polynomial(knots, &pts).unwrap();
    assert_eq!(edge_segments(&cubic, &chord_only(0.5), 1), 1);
    let split = edge_parameters(&cubic, &limited.with_max_edge_length(Some(25.0)), 1);
    let xs: Vec<f64> = split.iter().map(|&u| cubic.point(u).x).collect();
    for (k, x) in xs.iter().enumerate() {
        assert!((x - 25.0 * k as f64).abs() < 1e-10, "{xs:?}");
    }
}

#[test]
fn degenerate_curves_give_their_end_parameters() {
    let p = DVec3::new(0.0, 0.0, 500.0);
    let point = line(p, p).unwrap();
    assert_eq!(
        edge_parameters(&point, &TessellationOptions::chord(0.5), 16),
        vec![0.0, 1.0]
    );
    assert_eq!(
        edge_segments(&point, &TessellationOptions::chord(0.5), 16),
        1
    );
    let knots = KnotVector::new(2, vec![2.0, 2.0, 2.0, 3.0, 3.0, 3.0]);
    let quadratic = NurbsCurve::try_from_weighted(knots, &[p, p, p], &[1.0, 0.7, 1.0]).unwrap();
    assert_eq!(
        edge_parameters(&quadratic, &TessellationOptions::chord(0.5), 1),
        vec![2.0, 3.0]
    );
    // The pole of every dished head.
    for head in [
        Head::new(2400.0, HeadKind::Hemispherical),
        Head::new(2400.0, HeadKind::TWO_TO_ONE),
        Head::new(2400.0, HeadKind::asme_fd(2400.0)),
    ] {
        let patches = head.patches().unwrap();
        let top = patches.last().unwrap();
        let pole = top.surface.boundary(Side::VMax);
        assert_eq!(
            edge_segments(&pole, &TessellationOptions::chord(0.5), 16),
            1
        );
        assert_eq!(
            edge_parameters(&pole, &TessellationOptions::chord(0.5), 16).len(),
            2
        );
    }
}

#[test]
fn head_meridians_are_sampled_to_the_tolerance() {
    let od = 2400.0;
    let kinds = [
        HeadKind::Hemispherical,
        HeadKind::TWO_TO_ONE,
        HeadKind::Ellipsoidal { ratio: 3.0 },
        HeadKind::asme_fd(od),
        HeadKind::eighty_ten(od),
        HeadKind::Toriconical {
            half_angle: 30.0,
            knuckle_radius: 0.1 * od,
        },
        HeadKind::Flat {
            knuckle_radius: 0.05 * od,
        },
    ];
    for kind in kinds {
        let head = Head::new(od, kind).with_straight_flange(50.0);
        for patch in head.patches().unwrap() {
            for tolerance in [0.1, 0.5, 2.0] {
                let options = chord_only(tolerance);
                let meridian = patch.surface.boundary(Side::UMin);
                let params = assert_edge(&meridian, &options);
                // Circular arcs (knuckles, crowns) follow the closed form.
                let radius = match patch.analytic {
                    vesselcad::parts::Analytic::Torus { minor, .. } => Some(minor),
                    vesselcad::parts::Analytic::Sphere { radius, .. } => Some(radius),
                    _ => None,
                };
                if let Some(r) = radius {
                    let step = 2.0 * (1.0 - tolerance / r).acos();
                    let raw = meridian.arc_length() / r / step;
                    if (raw - raw.round()).abs() > 1e-6 {
                        assert_eq!(params.len() - 1, raw.ceil() as usize, "{}", patch.name);
                    }
                }
            }
        }
    }
}

#[test]
fn patches_sharing_an_edge_share_its_vertices() {
    let od = 2400.0;
    let options = TessellationOptions::chord(0.5);
    // Knuckle top circle = crown bottom circle; flange top = knuckle bottom.
    let head = Head::new(od, HeadKind::asme_fd(od)).with_straight_flange(50.0);
    let patches = head.patches().unwrap();
    for pair in patches.windows(2) {
        let below = pair[0].surface.boundary(Side::VMax);
        let above = pair[1].surface.boundary(Side::VMin);
        assert_same_points(
            &points(&below, &options, 1),
            &points(&above, &options, 1),
            1e-9,
        );
    }
    // A bottom head's open end (its frame turned over about X) against the shell's
    // bottom circle: opposite directions, same points.
    let turn = DAffine3::from_rotation_x(PI);
    let open_end = patches[0]
        .surface
        .transformed(&turn)
        .unwrap()
        .boundary(Side::VMin);
    let shell = Shell {
        outside_diameter: od,
        length: 3000.0,
    }
    .patches()
    .unwrap();
    let shell_bottom = shell[0].surface.boundary(Side::VMin);
    for multiple in [1, 4, 16] {
        assert_same_points(
            &points(&open_end, &options, multiple),
            &points(&shell_bottom, &options, multiple),
            1e-9,
        );
    }
    // The shell's top circle against a top head placed at z = length.
    let lift = DAffine3::from_translation(DVec3::new(0.0, 0.0, 3000.0));
    let top_end = patches[0]
        .surface
        .transformed(&lift)
        .unwrap()
        .boundary(Side::VMin);
    let shell_top = shell[0].surface.boundary(Side::VMax);
    assert_same_points(
        &points(&top_end, &options, 8),
        &points(&shell_top, &options, 8),
        1e-9,
    );
}

#[test]
fn bad_curves_and_options_never_panic() {
    let knots = |d: usize, n: usize| KnotVector::uniform(d, n).unwrap();
    let a = DVec3::new(1.0, 2.0, 3.0);
    let b = DVec3::new(40.0, -5.0, 9.0);
    let c = DVec3::new(-3.0, 8.0, 0.5);
    let mut curves = vec![
        // Folds back on itself (C′ = 0 in the middle).
        NurbsCurve::try_polynomial(knots(2, 3), &[a, b, a]).unwrap(),
        // Stationary start (repeated control points).
        NurbsCurve::try_polynomial(knots(3, 4), &[a, a, a, b]).unwrap(),
        // A stationary span between two moving ones.
        NurbsCurve::try_polynomial(knots(1, 5), &[a, b, b, b, c]).unwrap(),
        // A planar cusp.
        NurbsCurve::try_polynomial(knots(3, 4), &[a, b, c, a + (b - c)]).unwrap(),
        // Extreme weights.
        NurbsCurve::try_from_weighted(knots(2, 3), &[a, b, c], &[1e-150, 1e150, 1e-150]).unwrap(),
        NurbsCurve::try_from_weighted(knots(2, 3), &[a, b, c], &[1.0, 1e-12, 1.0]).unwrap(),
        // Huge and tiny coordinates.
        NurbsCurve::try_polynomial(knots(2, 3), &[a * 1e200, b * 1e200, c * 1e200]).unwrap(),
        NurbsCurve::try_polynomial(knots(2, 3), &[a * 1e-200, b * 1e-200, c * 1e-200]).unwrap(),
        NurbsCurve::try_polynomial(knots(1, 2), &[a * 1e300, -a * 1e300]).unwrap(),
    ];
    // The highest degree, wiggling.
    let wiggle: Vec<DVec3> = (0..20)
        .map(|i| DVec3::new(i as f64, if i % 2 == 0 { 1.0 } else { -1.0 } * 300.0, 0.0))
        .collect();
    curves.push(NurbsCurve::try_polynomial(knots(12, 20), &wiggle).unwrap());
    let options = [
        TessellationOptions::chord(0.5),
        TessellationOptions::chord(1e-6),
        TessellationOptions::chord(f64::NAN),
        TessellationOptions::chord(0.0),
        TessellationOptions::chord(-1.0),
        TessellationOptions::chord(f64::INFINITY),
        TessellationOptions::chord(0.5).with_angle_tolerance(Some(f64::NAN)),
        TessellationOptions::chord(0.5).with_angle_tolerance(Some(0.0)),
        TessellationOptions::chord(0.5).with_max_edge_length(Some(0.0)),
        TessellationOptions::chord(0.5).with_max_edge_length(Some(f64::NAN)),
    ];
    curves.push(xy_circle(1000.0));
    for curve in &curves {
        for multiple in [0, 1, usize::MAX] {
            assert_well_formed(curve, &options[0], multiple);
        }
        for o in &options {
            assert_well_formed(curve, o, 7);
            assert!(edge_segments(curve, o, 1) <= MAX_EDGE_SEGMENTS);
        }
    }
    // Invalid options ask for the finest edge, not the coarsest.
    let circle = xy_circle(1000.0);
    assert_eq!(
        edge_segments(&circle, &TessellationOptions::chord(f64::NAN), 1),
        MAX_EDGE_SEGMENTS
    );
}
