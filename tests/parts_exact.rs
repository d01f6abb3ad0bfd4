//! Every part's patches lie on their analytic surfaces, meet G0 (and G1 where the
//! real part is smooth), and have outward normals.

mod common;

use common::heads::head_kinds;

use common::*;
use glam::DVec3;
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Reducer, ReducerAlignment, Shell};

const OD: f64 = 2400.0;
const TOL: f64 = 1e-9 * OD;

fn all_heads(od: f64) -> Vec<Head> {
    let kinds = head_kinds(od);
    kinds
        .into_iter()
        .flat_map(|k| {
            [
                Head::new(od, k),
                Head::new(od, k).with_straight_flange(50.0),
            ]
        })
        .collect()
}

#[test]
fn shell_is_an_exact_cylinder() {
    let patches = Shell {
        outside_diameter: OD,
        length: 6000.0,
    }
    .patches()
    .unwrap();
    assert_on_analytic(&patches, TOL);
    assert_outward(&patches, |x| DVec3::new(0.0, 0.0, x.z));
}

#[test]
fn every_head_lies_on_its_analytic_surfaces() {
    for head in all_heads(OD) {
        let patches = head.patches().unwrap();
        assert_on_analytic(&patches, TOL);
        assert_outward(&patches, |_| DVec3::new(0.0, 0.0, -1.0));
    }
}

#[test]
fn head_patches_meet_g0_and_g1_where_smooth() {
    for head in all_heads(OD) {
        let patches = head.patches().unwrap();
        for pair in patches.windows(2) {
            // Real corners: flange→cone of a conical head, cone→small-end plate, and
            // flange→plate of a plain flat head. Every other joint is smooth.
            let corner = matches!(
                head.kind,
                HeadKind::Conical { .. }
                    | HeadKind::Flat {
                        knuckle_radius: 0.0
                    }
            ) && pair[1].name != "knuckle";
            assert_joint(&pair[0], &pair[1], TOL, !corner, 1e-9);
        }
    }
}

#[test]
fn head_depths_match_closed_forms() {
    let r = OD / 2.0;
    let depth = |k| Head::new(OD, k).depth().unwrap();
    assert!((depth(HeadKind::Hemispherical) - r).abs() < TOL);
    assert!((depth(HeadKind::TWO_TO_ONE) - OD / 4.0).abs() < TOL);
    // ASME F&D: h = L − √((L − r)² − (R − r)²).
    let (l, k) = (OD, 0.06 * OD);
    let expect = l - ((l - k).powi(2) - (r - k).powi(2)).sqrt();
    assert!((depth(HeadKind::asme_fd(OD)) - expect).abs() < TOL);
    let cone = depth(HeadKind::Conical {
        half_angle: 30.0,
        small_diameter: 0.0,
    });
    assert!((cone - r / 30f64.to_radians().tan()).abs() < TOL);
}

#[test]
fn reducers_are_exact_cones() {
    for alignment in [
        ReducerAlignment::Concentric,
        ReducerAlignment::Eccentric { flat_side: 0.0 },
        ReducerAlignment::Eccentric { flat_side: 270.0 },
    ] {
        let red = Reducer {
            large_diameter: OD,
            small_diameter: 1500.0,
            length: 900.0,
            alignment,
        };
        let patches = red.patches().unwrap();
        assert_on_analytic(&patches, TOL);
        // Ends are the two circles.
        let s = &patches[0].surface;
        for k in 0..=32 {
            let u = k as f64 / 32.0;
            assert!((s.point(u, 0.0).truncate().length() - OD / 2.0).abs() < TOL);
            let top = s.point(u, 1.0);
            assert!(((top - red.small_end_center()).length() - 750.0).abs() < TOL);
            assert!((top.z - 900.0).abs() < TOL);
        }
    }
}

/// A head's knuckle and the crown, cone or plate tangent to it, joined in v
/// (the surface a reinforcing pad across their seam lies on), lie on their
/// `Analytic::knuckled` surface: points of both pieces at distance 0, points
/// 3 mm along the normal on either side at 3 mm, near the seam as well. Any
/// other pair of patches (a conical head's cone and plate, a knuckle with the
/// straight flange) has no such surface.
#[test]
fn a_knuckle_and_the_piece_beyond_lie_on_their_knuckled_surface() {
    use vesselcad::parts::Analytic;
    let mut joined = 0;
    for head in all_heads(OD) {
        let patches = head.patches().unwrap();
        for pair in patches.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            let ((u0, _), (_, v1)) = a.surface.domain();
            let seam = a.surface.point(u0, v1);
            let Some(analytic) = Analytic::knuckled(&a.analytic, &b.analytic, seam) else {
                assert!(
                    a.name != "knuckle" || b.name == "straight flange",
                    "{:?}: {} then {}",
                    head.kind,
                    a.name,
                    b.name
                );
                continue;
            };
            assert!(matches!(analytic, Analytic::Knuckled { .. }));
            joined += 1;
            for patch in [a, b] {
                let ((u0, u1), (v0, v1)) = patch.surface.domain();
                for i in 0..=8 {
                    for j in 0..=20 {
                        let (u, v) = (
                            u0 + (u1 - u0) * i as f64 / 8.0,
                            v0 + (v1 - v0) * j as f64 / 20.0,
                        );
                        let (p, n) = (patch.surface.point(u, v), patch.surface.normal(u, v));
                        if !n.is_finite() || n.length() < 0.5 {
                            continue; // a pole
                        }
                        let at = |d: f64| analytic.distance(p + n * d);
                        assert!(at(0.0) < TOL, "{:?} {}: {}", head.kind, patch.name, at(0.0));
                        // Off the surface, away from a cone's apex (where the
                        // nearest point inside is on the other side).
                        if p.truncate().length() < 50.0 {
                            continue;
                        }
                        for d in [-3.0, 3.0] {
                            assert!(
                                (at(d) - 3.0).abs() < 1e-6,
                                "{:?} {} at ({u}, {v}), {d} mm off: {}",
                                head.kind,
                                patch.name,
                                at(d)
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(joined >= 6, "{joined} knuckle seams");
}
