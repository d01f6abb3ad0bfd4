//! Neck–host intersection: the trim loop of nozzles placed on shells, heads and
//! reducers (by hand-built frames and by the constraint resolver on the example
//! designs) lies on both surfaces and both analytic forms, closes once around the
//! neck, is simple and meets its chordal tolerance; the radial nozzle on a cylinder
//! matches the closed form; misplaced nozzles give typed errors; the loop's
//! crossings with host isolines (seam samples) are exact on the isoline and on both
//! surfaces.

use std::path::Path;

use glam::{DAffine3, DMat3, DVec2, DVec3};
use vesselcad::design::{load, resolve};
use vesselcad::nurbs::builders::{line, revolve};
use vesselcad::nurbs::intersect::{HostIsoline, LoopSample, loop_crossing};
use vesselcad::nurbs::{NurbsError, NurbsSurface, intersect_generator, neck_host_intersection};
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::tables::{FlangeClass, Nps, PipeSchedule};
use vesselcad::parts::{
    Analytic, Facing, FlangeType, Nozzle, Patch, Reducer, ReducerAlignment, Shell,
};

/// A weld-neck class-150 nozzle of `nps` inches and `projection` mm.
fn nozzle(nps: f64, projection: f64) -> Nozzle {
    Nozzle {
        nps: Nps::try_new(nps).unwrap(),
        schedule: PipeSchedule::Std,
        class: FlangeClass::C150,
        flange: FlangeType::WeldNeck,
        facing: Facing::RaisedFace,
        projection,
    }
}

/// A frame whose +Z is `axis` and whose +X is `x_hint` made orthogonal (as the
/// constraint resolver builds nozzle frames).
fn frame_along(origin: DVec3, axis: DVec3, x_hint: DVec3) -> DAffine3 {
    let z = axis.normalize();
    let x = (x_hint - z * x_hint.dot(z)).normalize();
    DAffine3::from_mat3_translation(DMat3::from_cols(x, z.cross(x), z), origin)
}

/// A neck-like patch (nozzle-local) placed in the host's frame.
struct Neck {
    surface: NurbsSurface,
    analytic: Analytic,
    /// Host frame → neck-local frame.
    to_local: DAffine3,
}

fn place(patch: &Patch, to_host: DAffine3) -> Neck {
    Neck {
        surface: patch.surface.transformed(&to_host).unwrap(),
        analytic: patch.analytic,
        to_local: to_host.inverse(),
    }
}

/// The neck of `n` placed by `to_host` (nozzle-local → host-local).
fn neck(n: &Nozzle, to_host: DAffine3) -> Neck {
    place(&n.patches().unwrap()[0], to_host)
}

fn shell(od: f64, length: f64) -> Patch {
    let s = Shell {
        outside_diameter: od,
        length,
    };
    s.patches().unwrap().remove(0)
}

fn head_patch(head: Head, name: &str) -> Patch {
    let patches = head.patches().unwrap();
    patches.into_iter().find(|p| p.name == name).unwrap()
}

/// Host u brought into its domain (all hosts here close in u).
fn wrap(host: &NurbsSurface, uv: DVec2) -> DVec2 {
    let (u0, u1) = host.domain().0;
    DVec2::new(u0 + (uv.x - u0).rem_euclid(u1 - u0), uv.y)
}

fn size(s: &NurbsSurface) -> f64 {
    let pts = s.control_points();
    let lo = pts.iter().fold(DVec3::splat(f64::MAX), |a, &p| a.min(p));
    let hi = pts.iter().fold(DVec3::splat(f64::MIN), |a, &p| a.max(p));
    (hi - lo).length()
}

/// The true curve point at neck angle `u`: Newton on neck(u, s) = host(a, b) from
/// `seed` = (s, a, b), written independently of the library's solver.
fn curve_point(neck: &NurbsSurface, host: &NurbsSurface, u: f64, seed: DVec3) -> DVec3 {
    let mut x = seed;
    let mut residual = f64::MAX;
    for _ in 0..40 {
        let n = neck.derivatives(u, x.x);
        let h = host.derivatives(wrap(host, DVec2::new(x.y, x.z)).x, x.z);
        let f = n.point - h.point;
        residual = f.length();
        x += DMat3::from_cols(n.dv, -h.du, -h.dv).inverse() * -f;
    }
    assert!(
        residual < 1e-9 * size(host),
        "reference Newton: residual {residual}"
    );
    neck.point(u, x.x)
}

fn point_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let t = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (p - a - d * t).length()
}

/// Distance between segments [p1, q1] and [p2, q2] (Ericson, Real-Time Collision
/// Detection §5.1.9).
fn segment_segment(p1: DVec3, q1: DVec3, p2: DVec3, q2: DVec3) -> f64 {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.length_squared(), d2.length_squared(), d2.dot(r));
    let (c, b) = (d1.dot(r), d1.dot(d2));
    let denom = a * e - b * b;
    let mut s = if denom > 0.0 {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (p1 + d1 * s - (p2 + d2 * t)).length()
}

/// Intersects, checks every invariant of the loop, and returns its sample count.
fn check(name: &str, neck: &Neck, host: &Patch, tolerance: f64) -> usize {
    let h = &host.surface;
    let l = neck_host_intersection(&neck.surface, h, tolerance)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let n = l.points.len();
    let on = 1e-9 * size(h);
    assert!(n >= 18, "{name}: only {n} samples");
    assert_eq!((l.neck_uv.len(), l.host_uv.len()), (n, n), "{name}");
    let ((nu0, nu1), (nv0, nv1)) = neck.surface.domain();
    let ((hu0, hu1), (hv0, hv1)) = h.domain();
    let period = hu1 - hu0;
    assert_eq!(
        l.neck_uv[0].x, nu0,
        "{name}: the loop starts at the neck's u0"
    );
    for i in 0..n {
        let (p, nuv, huv) = (l.points[i], l.neck_uv[i], l.host_uv[i]);
        let on_neck = (neck.surface.point(nuv.x, nuv.y) - p).length();
        let on_host = (h.point(wrap(h, huv).x, huv.y) - p).length();
        let analytic_neck = neck.analytic.distance(neck.to_local.transform_point3(p));
        let analytic_host = host.analytic.distance(p);
        for (what, d) in [
            ("neck", on_neck),
            ("host", on_host),
            ("neck analytic", analytic_neck),
            ("host analytic", analytic_host),
        ] {
            assert!(d <= on, "{name}: point {i} is {d} mm off the {what}");
        }
        assert!(
            (nv0..=nv1).contains(&nuv.y) && (hv0..=hv1).contains(&huv.y),
            "{name}"
        );
        assert!(
            huv.x >= hu0 - period && huv.x <= hu1 + period,
            "{name}: host u {}",
            huv.x
        );
        // Neighbour along the loop; the last joins the first one turn later.
        let j = (i + 1) % n;
        let (next_u, next_host) = if j == 0 {
            let h0 = l.host_uv[0];
            let shift = ((huv.x - h0.x) / period).round() * period;
            (nu1, DVec2::new(h0.x + shift, h0.y))
        } else {
            (l.neck_uv[j].x, l.host_uv[j])
        };
        assert!(next_u > nuv.x, "{name}: neck u not increasing at {i}");
        // Unwrapped: no jump by a period across the host's seam.
        let jump = (next_host - huv).abs();
        assert!(
            jump.x < 0.5 * period && jump.y < 0.5 * (hv1 - hv0),
            "{name}: host jump {jump} at {i}"
        );
        // The true curve within the chord: at its midpoint parameter (the sampling
        // criterion) and, for good measure, at its quarter points.
        let next_s = l.neck_uv[j].y;
        let (start, end) = (
            DVec3::new(nuv.y, huv.x, huv.y),
            DVec3::new(next_s, next_host.x, next_host.y),
        );
        for f in [0.25, 0.5, 0.75] {
            let u = nuv.x + f * (next_u - nuv.x);
            let truth = curve_point(&neck.surface, h, u, start.lerp(end, f));
            let deviation = point_segment(truth, p, l.points[j]);
            assert!(
                deviation <= tolerance + on,
                "{name}: chord {i} deviates {deviation} mm at {f}"
            );
        }
    }
    assert!(l.neck_uv[n - 1].x < nu1, "{name}: more than one turn");
    for i in 0..n {
        for k in i + 2..n {
            if (k + 1) % n == i {
                continue;
            }
            let d = segment_segment(
                l.points[i],
                l.points[(i + 1) % n],
                l.points[k],
                l.points[(k + 1) % n],
            );
            assert!(d > 1e-3 * on, "{name}: segments {i} and {k} touch ({d} mm)");
        }
    }
    n
}

/// Checks at 1, 0.1 and 0.01 mm; returns the sample counts.
fn check_all(name: &str, neck: &Neck, host: &Patch) -> [usize; 3] {
    let counts = [1.0, 0.1, 0.01].map(|t| check(name, neck, host, t));
    eprintln!("{name}: samples at 1 / 0.1 / 0.01 mm: {counts:?}");
    assert!(
        counts[0] <= counts[1] && counts[1] <= counts[2],
        "{name}: {counts:?}"
    );
    counts
}

#[test]
fn radial_nozzle_on_a_shell_matches_the_closed_form() {
    let (big_r, host) = (1000.0, shell(2000.0, 3000.0));
    let n = nozzle(8.0, 1400.0);
    let r = n.outside_diameter() / 2.0;
    let dir = DVec3::new(0.6, 0.8, 0.0);
    let to_host = frame_along(DVec3::new(0.0, 0.0, 1500.0), dir, DVec3::Z);
    let neck = neck(&n, to_host);
    let counts = check_all("radial on shell", &neck, &host);
    // Chord-limited sampling: h ∝ √tolerance.
    let ratio = counts[2] as f64 / counts[1] as f64;
    assert!((2.0..5.0).contains(&ratio), "{counts:?}");
    let l = neck_host_intersection(&neck.surface, &host.surface, 0.1).unwrap();
    for &p in &l.points {
        assert!((p.truncate().length() - big_r).abs() < 1e-9 * big_r, "{p}");
        // Nozzle-local: x along the vessel axis, y across; the saddle height.
        let q = neck.to_local.transform_point3(p);
        assert!((q.truncate().length() - r).abs() < 1e-9 * big_r, "{q}");
        assert!(
            (q.z - (big_r * big_r - q.y * q.y).sqrt()).abs() < 1e-9 * big_r,
            "{q}"
        );
    }
    // The same loop in a plant frame far from the origin: the same points, mapped.
    let plant =
        DAffine3::from_rotation_z(0.3) * DAffine3::from_translation(DVec3::new(3e4, -2e4, 5e3));
    let (far_neck, far_host) = (
        neck.surface.transformed(&plant).unwrap(),
        host.surface.transformed(&plant).unwrap(),
    );
    let far = neck_host_intersection(&far_neck, &far_host, 0.1).unwrap();
    assert_eq!(far.points.len(), l.points.len());
    for (a, b) in far.points.iter().zip(&l.points) {
        assert!((*a - plant.transform_point3(*b)).length() < 1e-9 * big_r);
    }
}

#[test]
fn hillside_angled_and_seam_crossing_nozzles_on_a_shell() {
    let host = shell(2000.0, 3000.0);
    let n = nozzle(8.0, 1400.0);
    // Axis parallel to +Y, offset 600 mm sideways.
    let hillside = frame_along(DVec3::new(600.0, 0.0, 1500.0), DVec3::Y, DVec3::Z);
    check_all("hillside on shell", &neck(&n, hillside), &host);
    // Tilted 30° uphill from the radial direction.
    let tilted = DVec3::new(-(30f64.to_radians().cos()), 0.0, 30f64.to_radians().sin());
    let angled = frame_along(DVec3::new(0.0, 0.0, 1200.0), tilted, DVec3::Z);
    check_all("angled on shell", &neck(&n, angled), &host);
    // Radial along +X: the opening straddles the shell's u seam.
    let seam = neck(
        &n,
        frame_along(DVec3::new(0.0, 0.0, 1500.0), DVec3::X, DVec3::Z),
    );
    check_all("across the seam", &seam, &host);
    let l = neck_host_intersection(&seam.surface, &host.surface, 0.1).unwrap();
    let (lo, hi) = l.host_uv.iter().fold((f64::MAX, f64::MIN), |(a, b), uv| {
        (a.min(uv.x), b.max(uv.x))
    });
    assert!(
        lo < 0.0 && hi > 0.0 && hi - lo < 0.1,
        "host u {lo}..{hi} should straddle 0"
    );
    assert_eq!(l.host_turns(&host.surface), 0);
}

#[test]
fn large_nozzle_on_a_small_shell_has_a_saddle_loop() {
    let host = shell(323.9, 1000.0);
    let n = nozzle(10.0, 600.0); // OD 273.1 on OD 323.9
    let to_host = frame_along(
        DVec3::new(0.0, 0.0, 500.0),
        DVec3::new(-1.0, 1.0, 0.0),
        DVec3::Z,
    );
    let counts = check_all("10\" on 12\"", &neck(&n, to_host), &host);
    assert!(counts[2] > 3 * counts[0], "{counts:?}");
}

#[test]
fn nozzles_on_heads() {
    let n = nozzle(6.0, 900.0);
    let up = |offset: f64, angle: f64| {
        let a = f64::to_radians(angle);
        frame_along(
            DVec3::new(offset * a.cos(), offset * a.sin(), 50.0),
            DVec3::Z,
            DVec3::X,
        )
    };
    let head = |kind| Head::new(2000.0, kind).with_straight_flange(50.0);
    let sphere = head_patch(head(HeadKind::Hemispherical), "crown");
    check_all(
        "hemispherical",
        &neck(&nozzle(6.0, 1600.0), up(500.0, 200.0)),
        &sphere,
    );
    let ellipsoid = head_patch(head(HeadKind::TWO_TO_ONE), "crown");
    check_all("2:1 ellipsoidal", &neck(&n, up(600.0, 10.0)), &ellipsoid);
    // Centred: the loop winds once around the head's axis and its pole.
    let centred = neck(&n, up(0.0, 0.0));
    check_all("2:1 centred", &centred, &ellipsoid);
    let l = neck_host_intersection(&centred.surface, &ellipsoid.surface, 0.1).unwrap();
    let turn = l.host_uv[l.host_uv.len() - 1].x - l.host_uv[0].x;
    assert!((turn.abs() - 1.0).abs() < 0.1, "host u turns by {turn}");
    assert_eq!(l.host_turns(&ellipsoid.surface).abs(), 1);
    let fd = head(HeadKind::asme_fd(2000.0));
    check_all(
        "torispherical crown",
        &neck(&n, up(500.0, 45.0)),
        &head_patch(fd, "crown"),
    );
    let knuckle = head_patch(Head::new(4000.0, HeadKind::eighty_ten(4000.0)), "knuckle");
    let small = nozzle(4.0, 600.0);
    let in_knuckle = frame_along(DVec3::new(0.0, -1915.0, 0.0), DVec3::Z, DVec3::X);
    check_all("torispherical knuckle", &neck(&small, in_knuckle), &knuckle);
    let cone = HeadKind::Conical {
        half_angle: 60.0,
        small_diameter: 0.0,
    };
    check_all(
        "conical head",
        &neck(&n, up(500.0, 300.0)),
        &head_patch(head(cone), "cone"),
    );
}

#[test]
fn nozzle_on_a_concentric_reducer() {
    let reducer = Reducer {
        large_diameter: 2000.0,
        small_diameter: 1400.0,
        length: 900.0,
        alignment: ReducerAlignment::Concentric,
    };
    let host = reducer.patches().unwrap().remove(0);
    let to_host = frame_along(
        DVec3::new(0.0, 0.0, 450.0),
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::Z,
    );
    check_all("reducer", &neck(&nozzle(6.0, 1200.0), to_host), &host);
}

/// The coaxial cylinder of a reinforcing pad's outside diameter, nozzle-local.
fn pad_cylinder(od: f64) -> Patch {
    let r = od / 2.0;
    let profile = line(DVec3::new(r, 0.0, 0.0), DVec3::new(r, 0.0, 3000.0)).unwrap();
    let surface = revolve(&profile, DVec3::ZERO, DVec3::Z, std::f64::consts::TAU).unwrap();
    let (point, axis) = (DVec3::ZERO, DVec3::Z);
    Patch::new(
        "pad",
        surface,
        Analytic::Cylinder {
            point,
            axis,
            radius: r,
        },
    )
}

#[test]
fn every_nozzle_and_pad_of_the_example_designs() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let mut checked = 0;
    for path in files
        .iter()
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
    {
        let file = path.file_name().unwrap().to_string_lossy();
        for vessel in resolve(&load(path).unwrap()).unwrap() {
            for nz in &vessel.nozzles {
                let part = &vessel.parts[nz.host];
                let to_host = part.frame.inverse() * nz.frame;
                let name = format!("{file} {} {}", vessel.tag, nz.mark);
                let mut necks = vec![(name.clone(), neck(&nz.geometry, to_host))];
                if let Some((od, _)) = nz.pad {
                    necks.push((format!("{name} pad"), place(&pad_cylinder(od), to_host)));
                }
                let patches = part.geometry.patches().unwrap();
                for (name, neck) in necks {
                    // The opening lies within one patch of its host part.
                    let host = patches
                        .iter()
                        .find(|p| neck_host_intersection(&neck.surface, &p.surface, 1.0).is_ok())
                        .unwrap_or_else(|| panic!("{name}: no host patch holds the opening"));
                    check(&format!("{name} on {}", host.name), &neck, host, 0.5);
                    checked += 1;
                }
            }
        }
    }
    eprintln!("{checked} openings of the example designs checked");
    assert!(checked >= 30, "{checked}");
}

#[test]
fn one_generator_and_misplaced_nozzles_give_typed_errors() {
    let host = shell(2000.0, 3000.0);
    let n = nozzle(8.0, 1400.0);
    let radial = neck(
        &n,
        frame_along(DVec3::new(0.0, 0.0, 1500.0), DVec3::Y, DVec3::Z),
    );
    let hit = intersect_generator(&radial.surface, &host.surface, 0.0).unwrap();
    let expected = DVec3::new(
        0.0,
        (1000f64.powi(2) - 0.0).sqrt(),
        1500.0 + n.outside_diameter() / 2.0,
    );
    assert!((hit.point - expected).length() < 1e-9, "{}", hit.point);
    assert!((host.surface.point(hit.host_uv.x, hit.host_uv.y) - hit.point).length() < 1e-9);

    let beside = neck(
        &n,
        frame_along(DVec3::new(0.0, 1500.0, 1500.0), DVec3::X, DVec3::Z),
    );
    let partly = neck(
        &n,
        frame_along(DVec3::new(950.0, 0.0, 1500.0), DVec3::Y, DVec3::Z),
    );
    let off_end = neck(
        &n,
        frame_along(DVec3::new(0.0, 0.0, 2990.0), DVec3::Y, DVec3::Z),
    );
    for (what, neck) in [
        ("beside", &beside),
        ("partly beside", &partly),
        ("off the end", &off_end),
    ] {
        match neck_host_intersection(&neck.surface, &host.surface, 0.1) {
            Err(NurbsError::GeneratorMissesHost { distance, .. }) => assert!(distance > 0.0),
            other => panic!("{what}: {other:?}"),
        }
    }
    let outside = neck(
        &n,
        frame_along(DVec3::new(0.0, 1100.0, 1500.0), DVec3::Y, DVec3::Z),
    );
    let e = neck_host_intersection(&outside.surface, &host.surface, 0.1);
    assert!(
        matches!(e, Err(NurbsError::IntersectionOutsideNeck { .. })),
        "{e:?}"
    );
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = neck_host_intersection(&radial.surface, &host.surface, bad);
        assert!(
            matches!(e, Err(NurbsError::InvalidGeometry { .. })),
            "{bad}: {e:?}"
        );
    }
    let half = revolve(
        &line(DVec3::new(50.0, 0.0, 0.0), DVec3::new(50.0, 0.0, 2000.0)).unwrap(),
        DVec3::ZERO,
        DVec3::Y,
        3.0,
    );
    let e = neck_host_intersection(&half.unwrap(), &host.surface, 0.1);
    assert!(
        matches!(e, Err(NurbsError::InvalidGeometry { .. })),
        "{e:?}"
    );
}

#[test]
fn nearly_tangent_generators_and_loops_near_a_pole() {
    // Hillside nozzles up to 1e-9 mm from tangent, and tilted ones, on shells down
    // to a 12" nozzle on a 12" pipe.
    for (od, nps) in [(2000.0, 24.0), (2000.0, 1.0), (610.0, 20.0), (323.9, 12.0)] {
        let (host, n) = (shell(od, 12000.0), nozzle(nps, 4000.0));
        let room = od / 2.0 - n.outside_diameter() / 2.0;
        for e in [0.0, 0.3, 0.6, 0.9, 0.99, 1.0 - 1e-6, 1.0 - 1e-12].map(|f| f * room) {
            let f = frame_along(DVec3::new(e, 0.0, 6000.0), DVec3::Y, DVec3::Z);
            check(
                &format!("{nps}\" on {od}, offset {e}"),
                &neck(&n, f),
                &host,
                0.1,
            );
        }
        for deg in [20.0, 45.0, 70.0] {
            let a = f64::to_radians(deg);
            let axis = DVec3::new(0.0, a.cos(), a.sin());
            let f = frame_along(DVec3::new(0.0, 0.0, 6000.0), axis, DVec3::Z);
            check(
                &format!("{nps}\" on {od}, tilt {deg}"),
                &neck(&n, f),
                &host,
                0.1,
            );
        }
    }
    // A hemispherical head: the opening passes 1 mm and 1 µm from the pole, and
    // reaches within 1 µm of the equator.
    let sphere = head_patch(Head::new(2000.0, HeadKind::Hemispherical), "crown");
    let n = nozzle(8.0, 1400.0);
    let r = n.outside_diameter() / 2.0;
    for offset in [r - 1.0, r - 1e-3, r + 1e-3, r + 1.0, 1000.0 - r - 1e-3] {
        let f = frame_along(DVec3::new(offset, 0.0, 0.0), DVec3::Z, DVec3::X);
        check(
            &format!("sphere, offset {offset}"),
            &neck(&n, f),
            &sphere,
            0.1,
        );
    }
}

#[test]
fn sample_counts_follow_the_square_root_of_the_tolerance() {
    let host = shell(2000.0, 3000.0);
    let n = neck(
        &nozzle(24.0, 1400.0),
        frame_along(DVec3::new(0.0, 0.0, 1500.0), DVec3::Y, DVec3::Z),
    );
    let counts = [1.0, 0.1, 0.01, 1e-3, 1e-4].map(|t| {
        neck_host_intersection(&n.surface, &host.surface, t)
            .unwrap()
            .points
            .len()
    });
    eprintln!("24\" on 2000: samples at 1 mm … 0.1 µm: {counts:?}");
    for w in counts[1..].windows(2) {
        let ratio = w[1] as f64 / w[0] as f64;
        assert!((2.5..4.0).contains(&ratio), "{counts:?}");
    }
    // Even a huge tolerance keeps the turning limit: at least 360° / 20° chords.
    let coarse = neck_host_intersection(&n.surface, &host.surface, 1e4).unwrap();
    assert!(coarse.points.len() >= 18);
}

#[test]
fn loop_crossings_lie_on_their_isoline_and_on_both_surfaces() {
    let host = shell(2000.0, 3000.0);
    let h = &host.surface;
    let on = 1e-9 * size(h);
    let n = neck(
        &nozzle(8.0, 1400.0),
        frame_along(
            DVec3::new(0.0, 0.0, 1500.0),
            DVec3::new(0.6, 0.8, 0.0),
            DVec3::Z,
        ),
    );
    let l = neck_host_intersection(&n.surface, h, 1.0).unwrap();
    let sample = |i: usize| LoopSample {
        neck_uv: l.neck_uv[i],
        host_uv: l.host_uv[i],
    };
    // Every chord crosses the isolines through its ends' midpoint parameters: the
    // meridian (host u held) and the parallel (host v held).
    let mut crossed = 0;
    for i in 0..l.points.len() - 1 {
        let (a, b) = (sample(i), sample(i + 1));
        let middle = 0.5 * (a.host_uv + b.host_uv);
        for isoline in [HostIsoline::U(middle.x), HostIsoline::V(middle.y)] {
            let (held, from, to) = match isoline {
                HostIsoline::U(x) => (x, a.host_uv.x, b.host_uv.x),
                HostIsoline::V(y) => (y, a.host_uv.y, b.host_uv.y),
            };
            if from == to {
                continue;
            }
            let c = loop_crossing(&n.surface, h, isoline, a, b).unwrap();
            let got = match isoline {
                HostIsoline::U(_) => c.host_uv.x,
                HostIsoline::V(_) => c.host_uv.y,
            };
            assert_eq!(got, held, "chord {i}: the held parameter is exact");
            assert!(c.neck_uv.x > a.neck_uv.x && c.neck_uv.x < b.neck_uv.x);
            let on_neck = (n.surface.point(c.neck_uv.x, c.neck_uv.y) - c.point).length();
            let on_host = (h.point(wrap(h, c.host_uv).x, c.host_uv.y) - c.point).length();
            let analytic = host.analytic.distance(c.point);
            for (what, d) in [("neck", on_neck), ("host", on_host), ("analytic", analytic)] {
                assert!(d <= on, "chord {i}: crossing {d} mm off the {what}");
            }
            crossed += 1;
        }
    }
    assert!(crossed >= 2 * (l.points.len() - 1) - 4, "{crossed}");
    // An isoline the chord does not cross: a typed error, not a point elsewhere.
    let (a, b) = (sample(0), sample(1));
    let beyond = a.host_uv.y + 10.0 * (b.host_uv.y - a.host_uv.y);
    if a.host_uv.y != b.host_uv.y {
        assert!(matches!(
            loop_crossing(&n.surface, h, HostIsoline::V(beyond), a, b),
            Err(NurbsError::IntersectionNotConverged { .. })
        ));
    }
}
