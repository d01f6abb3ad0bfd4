//! Supports and the boot: every patch lies on its analytic surface, normals face
//! the documented way, neighbouring patches share their edges, and bad numbers are
//! answered with `PartError::InvalidParameter` naming the field, never a panic.

mod common;

use common::supports::*;
use common::*;
use glam::DVec3;
use proptest::prelude::*;
use vesselcad::nurbs::Side;
use vesselcad::parts::heads::HeadKind;
use vesselcad::parts::{Boot, Legs, Lugs, Patch, Saddle, Skirt};

const TOL: f64 = 1e-9 * OD;

/// Asserts every grid normal of `patch` is `expected(point)` (unit, within 1e-9).
fn assert_normals(patch: &Patch, expected: impl Fn(DVec3) -> DVec3) {
    for (u, v) in grid(&patch.surface, 21) {
        let x = patch.surface.point(u, v);
        let n = patch.surface.normal(u, v);
        let e = expected(x);
        assert!(
            (n - e).length() < 1e-9,
            "{} {}: normal {n} at {x}, expected {e}",
            patch.name,
            patch.index
        );
    }
}

/// Horizontal unit vector from the Z axis to `x`.
fn radial(x: DVec3) -> DVec3 {
    DVec3::new(x.x, x.y, 0.0).normalize()
}

#[test]
fn skirts_are_exact_cylinders_and_cones_with_a_base_ring() {
    for angle in [0.0, 7.5, 30.0, 45.0] {
        for ring in [0.0, 150.0] {
            let s = skirt_with(angle, ring);
            let patches = s.patches().unwrap();
            assert_eq!(patches.len(), if ring > 0.0 { 2 } else { 1 });
            assert_on_analytic(&patches, TOL);
            assert_outward(&patches[..1], |x| DVec3::new(0.0, 0.0, x.z));
            let bottom = OD / 2.0 + 3000.0 * f64::to_radians(angle).tan();
            assert!((s.bottom_diameter() / 2.0 - bottom).abs() < TOL);
            let skirt = &patches[0].surface;
            for k in 0..=32 {
                let u = k as f64 / 32.0;
                let (b, t) = (skirt.point(u, 0.0), skirt.point(u, 1.0));
                assert!(b.z.abs() < TOL && (b.truncate().length() - bottom).abs() < TOL);
                assert!(
                    (t.z - 3000.0).abs() < TOL && (t.truncate().length() - OD / 2.0).abs() < TOL
                );
            }
            if let Some(ring) = patches.get(1) {
                assert_normals(ring, |_| -DVec3::Z);
                let b = &ring.surface;
                assert_same_curve(
                    &skirt.boundary(Side::VMin),
                    &b.boundary(Side::VMin),
                    false,
                    TOL,
                    "skirt–base ring",
                );
                let outer = b.boundary(Side::VMax);
                for k in 0..=32 {
                    let p = outer.point(k as f64 / 32.0);
                    assert!((p.truncate().length() - bottom - 150.0).abs() < TOL);
                }
            }
        }
    }
}

#[test]
fn saddle_plates_lie_on_the_shell_and_planes_and_meet() {
    for (angle, chord_base) in [
        (120.0, false),
        (135.0, false),
        (150.0, false),
        (150.0, true),
    ] {
        let mut s = saddle();
        s.contact_angle = angle;
        if chord_base {
            s.base_length = s.chord();
        }
        let patches = s.patches().unwrap();
        let names: Vec<_> = patches.iter().map(|p| p.name).collect();
        assert_eq!(names, ["wear plate", "web", "base plate"]);
        assert_on_analytic(&patches, TOL);
        let (wear, web, base) = (&patches[0], &patches[1], &patches[2]);
        assert_normals(wear, radial);
        assert_normals(web, |_| DVec3::Z);
        assert_normals(base, |_| -DVec3::Y);
        let r = OD / 2.0;
        let half = angle.to_radians() / 2.0;
        for (u, v) in grid(&wear.surface, GRID) {
            let p = wear.surface.point(u, v);
            assert!(p.z.abs() <= 150.0 + TOL);
            // Within the contact angle, symmetric about −Y.
            assert!(-p.y >= r * half.cos() - TOL, "{p}");
        }
        // The web's top edge is the wear plate's middle line, on the shell.
        let top = web.surface.boundary(Side::VMax);
        assert_same_curve(&wear.surface.isocurve_v(0.5), &top, false, TOL, "wear–web");
        // The web stays outside the shell and above the base; its bottom edge lies in
        // the base plate.
        for (u, v) in grid(&web.surface, GRID) {
            let p = web.surface.point(u, v);
            assert!(
                p.truncate().length() >= r - TOL && p.y >= -s.height - TOL,
                "{p}"
            );
        }
        let bottom = web.surface.boundary(Side::VMin);
        for k in 0..=32 {
            let p = bottom.point(k as f64 / 32.0);
            assert!((p.y + s.height).abs() < TOL && p.x.abs() <= s.base_length / 2.0 + TOL);
        }
        assert_same_curve(
            &bottom,
            &base.surface.isocurve_v(0.5),
            false,
            TOL,
            "web–base plate",
        );
    }
}

#[test]
fn legs_are_pipes_touching_the_shell_on_square_plates() {
    for count in [3, 4, 6, 8] {
        let mut l = legs();
        l.count = count;
        let patches = l.patches().unwrap();
        assert_eq!(patches.len(), 2 * count as usize);
        assert_on_analytic(&patches, 1e-9 * 1800.0);
        let axes = l.axis_points().unwrap();
        for (k, pair) in patches.chunks(2).enumerate() {
            let (pipe, plate) = (&pair[0], &pair[1]);
            assert_eq!((pipe.name, plate.name), ("leg", "leg base plate"));
            assert_eq!((pipe.index, plate.index), (k as u32 + 1, k as u32 + 1));
            let axis = axes[k];
            assert_normals(pipe, |x| radial(x - axis));
            assert_normals(plate, |_| -DVec3::Z);
            // The pipe touches the shell circle along its seam and never enters it.
            let mut nearest = f64::INFINITY;
            for (u, v) in grid(&pipe.surface, GRID) {
                let p = pipe.surface.point(u, v);
                assert!(p.z >= -TOL && p.z <= 1800.0 + TOL);
                nearest = nearest.min(p.truncate().length());
            }
            assert!((nearest - OD / 2.0).abs() < TOL, "{nearest}");
            let seam = pipe.surface.point(0.0, 0.5).truncate().length();
            assert!((seam - OD / 2.0).abs() < TOL);
            // The plate is a 2 × OD square centred on the leg axis.
            let corners = plate.surface.control_points();
            let d = 2.0 * 219.1;
            assert!(((corners[0] - corners[3]).length() - d * 2f64.sqrt()).abs() < TOL);
            let centre = corners.iter().sum::<DVec3>() / 4.0;
            assert!((centre - axis).length() < TOL);
        }
    }
}

#[test]
fn lugs_have_bearing_plates_between_gussets_on_the_shell() {
    let l = lugs();
    let patches = l.patches().unwrap();
    assert_eq!(patches.len(), 12);
    assert_on_analytic(&patches, TOL);
    let r = OD / 2.0;
    for (k, lug) in patches.chunks(3).enumerate() {
        let names: Vec<_> = lug.iter().map(|p| (p.name, p.index)).collect();
        let i = k as u32 + 1;
        assert_eq!(
            names,
            [
                ("lug bearing plate", i),
                ("lug gusset cw", i),
                ("lug gusset ccw", i)
            ]
        );
        let (plate, cw, ccw) = (&lug[0], &lug[1], &lug[2]);
        let phi = (90.0 * k as f64).to_radians();
        let t = DVec3::new(-phi.sin(), phi.cos(), 0.0);
        assert_normals(plate, |_| -DVec3::Z);
        assert_normals(cw, |_| -t);
        assert_normals(ccw, |_| t);
        // The plate's inner edge is the shell circle; its sides are the gussets' feet.
        let inner = plate.surface.boundary(Side::VMin);
        for j in 0..=32 {
            assert!((inner.point(j as f64 / 32.0).length() - r).abs() < TOL);
        }
        let foot = |g: &Patch| g.surface.boundary(Side::VMin);
        assert_same_curve(
            &plate.surface.boundary(Side::UMin),
            &foot(cw),
            false,
            TOL,
            "cw",
        );
        assert_same_curve(
            &plate.surface.boundary(Side::UMax),
            &foot(ccw),
            true,
            TOL,
            "ccw",
        );
        // The gussets' inner edges stand on the shell; they reach r + projection.
        for g in [cw, ccw] {
            for (u, v) in grid(&g.surface, GRID) {
                let p = g.surface.point(u, v);
                let rho = p.truncate().length();
                assert!(rho >= r - TOL && rho <= (r + 300.0).hypot(125.0) + TOL);
                assert!(p.z >= -TOL && p.z <= 400.0 + TOL);
            }
        }
        let inner_edge = cw.surface.boundary(Side::UMin);
        assert!((inner_edge.point(0.5).truncate().length() - r).abs() < TOL);
    }
}

#[test]
fn boots_are_cylinders_closed_by_smooth_heads() {
    let kinds = [
        HeadKind::TWO_TO_ONE,
        HeadKind::Hemispherical,
        HeadKind::asme_fd(600.0),
        HeadKind::Flat {
            knuckle_radius: 30.0,
        },
    ];
    for kind in kinds {
        let b = boot().with_head(kind);
        let patches = b.patches().unwrap();
        assert_eq!(patches[0].name, "boot shell");
        assert_on_analytic(&patches, 1e-9 * 3000.0);
        let top = b.tangent_line();
        assert!((top - (OD / 2.0 + 900.0)).abs() < TOL);
        assert_outward(&patches, |x| DVec3::new(0.0, 0.0, x.z.min(top)));
        let shell = &patches[0].surface;
        assert!(shell.point(0.3, 0.0).z.abs() < TOL);
        assert!((shell.point(0.3, 1.0).z - top).abs() < TOL);
        for pair in patches.windows(2) {
            assert_joint(&pair[0], &pair[1], TOL, true, 1e-9);
        }
    }
    // A conical head meets the boot with a corner: G0 only.
    let cone = HeadKind::Conical {
        half_angle: 30.0,
        small_diameter: 0.0,
    };
    let patches = boot().with_head(cone).patches().unwrap();
    assert_on_analytic(&patches, 1e-9 * 3000.0);
    assert_joint(&patches[0], &patches[1], TOL, false, 0.0);
}

/// 1e-9 × the part's size (its largest control-point distance from the origin).
fn relative_tolerance(patches: &[Patch]) -> f64 {
    let size = patches
        .iter()
        .flat_map(|p| p.surface.control_points())
        .map(|q| q.length())
        .fold(0.0, f64::max);
    1e-9 * size
}

/// Every valid part of realistic size lies on its analytic surfaces.
fn assert_exact(patches: &[Patch]) {
    assert_on_analytic(patches, relative_tolerance(patches));
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn random_skirts_are_exact(
        top in 100.0..6000.0f64,
        height in 100.0..10000.0f64,
        flare in prop_oneof![Just(0.0), Just(1e-6), Just(45.0), 0.0..45.0f64],
        ring in prop_oneof![Just(0.0), 10.0..500.0f64],
    ) {
        let s = Skirt { top_diameter: top, height, flare_angle: flare, thickness: 10.0, base_ring_width: ring };
        assert_exact(&s.patches().unwrap());
    }

    #[test]
    fn random_saddles_are_exact(
        d in 300.0..6000.0f64,
        angle in prop_oneof![Just(120.0), Just(150.0), 120.0..150.0f64],
        rise in 1.05..2.0f64,
        spread in 1.0..1.5f64,
        width in 50.0..1000.0f64,
    ) {
        let mut s = Saddle {
            shell_diameter: d, contact_angle: angle, width, height: rise * d / 2.0,
            web_thickness: width / 4.0, base_length: 0.0, base_width: width,
            base_thickness: (rise - 1.0) * d / 4.0,
        };
        s.base_length = spread * s.chord();
        assert_exact(&s.patches().unwrap());
    }

    #[test]
    fn random_legs_are_exact(
        count in 3..9u32,
        d in 300.0..6000.0f64,
        pipe in 0.02..0.1f64,
        length in 300.0..5000.0f64,
        first in -360.0..360.0f64,
    ) {
        let legs = Legs { count, pipe_diameter: pipe * d, length, shell_diameter: d, first_angle: first };
        assert_exact(&legs.patches().unwrap());
    }

    #[test]
    fn random_lugs_are_exact(
        count in 2..9u32,
        d in 300.0..6000.0f64,
        gap in 0.05..0.95f64,
        first in -360.0..360.0f64,
    ) {
        let width = gap * d * (std::f64::consts::PI / f64::from(count)).sin();
        let lugs = Lugs { count, shell_diameter: d, height: 0.2 * d, projection: 0.1 * d, width, first_angle: first };
        assert_exact(&lugs.patches().unwrap());
    }

    #[test]
    fn random_boots_are_exact(
        host in 600.0..6000.0f64,
        ratio in 0.1..0.9f64,
        length in 100.0..3000.0f64,
        hemispherical in any::<bool>(),
    ) {
        let kind = if hemispherical { HeadKind::Hemispherical } else { HeadKind::TWO_TO_ONE };
        let patches = Boot::new(ratio * host, length, host).with_head(kind).patches().unwrap();
        assert_exact(&patches);
    }
}
