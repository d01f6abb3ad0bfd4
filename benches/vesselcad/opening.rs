//! Nozzle openings: one neck–host intersection loop (the Geometry stage's work per
//! cut nozzle) on a shell and on heads at the plant's 1 mm chordal tolerance, a
//! whole cut with a reinforcing pad (two loops) and the same cut placed again
//! after a move along the shell's axis, and the region layout of a shell
//! course holding six openings (the Tessellate stage's work per host patch before
//! meshing), afresh and with the course's sides kept from its last layout. These are the costs a nozzle or shell edit pays per opening.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group};
use glam::{DAffine3, DMat3, DVec3};
use vesselcad::mesh::{
    PatchSides, TessellationOptions, cut_opening, cut_opening_reusing, host_region,
    host_region_with,
};
use vesselcad::nurbs::{NurbsSurface, neck_host_intersection};
use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::tables::{FlangeClass, Nps, PipeSchedule};
use vesselcad::parts::{Facing, FlangeType, Nozzle, Patch, Shell};

/// The plant's chordal tolerance, mm.
const TOLERANCE: f64 = 1.0;

/// A weld-neck class-150 nozzle of `nps` inches and `projection` mm.
fn nozzle(nps: f64, projection: f64) -> Nozzle {
    Nozzle {
        nps: Nps::try_new(nps).expect("a table size"),
        schedule: PipeSchedule::Std,
        class: FlangeClass::C150,
        flange: FlangeType::WeldNeck,
        facing: Facing::RaisedFace,
        projection,
    }
}

/// A frame whose +Z is `axis` and whose +X is `x_hint` made orthogonal.
fn frame_along(origin: DVec3, axis: DVec3, x_hint: DVec3) -> DAffine3 {
    let z = axis.normalize();
    let x = (x_hint - z * x_hint.dot(z)).normalize();
    DAffine3::from_mat3_translation(DMat3::from_cols(x, z.cross(x), z), origin)
}

fn neck_patch(n: &Nozzle) -> Patch {
    n.patches().expect("valid nozzle").remove(0)
}

fn shell(od: f64, length: f64) -> Patch {
    let s = Shell {
        outside_diameter: od,
        length,
    };
    s.patches().expect("valid shell").remove(0)
}

fn crown(kind: HeadKind) -> Patch {
    let head = Head::new(2000.0, kind).with_straight_flange(50.0);
    let patches = head.patches().expect("valid head");
    patches
        .into_iter()
        .find(|p| p.name == "crown")
        .expect("a crown")
}

/// A nozzle placed on a host: the neck in the host's frame.
struct Case {
    name: &'static str,
    neck: NurbsSurface,
    host: NurbsSurface,
}

fn cases() -> Vec<Case> {
    let on_shell = shell(2000.0, 3000.0);
    let ellipsoid = crown(HeadKind::TWO_TO_ONE);
    let place = |n: &Nozzle, frame: DAffine3| {
        neck_patch(n)
            .surface
            .transformed(&frame)
            .expect("finite frame")
    };
    let radial = frame_along(
        DVec3::new(0.0, 0.0, 1500.0),
        DVec3::new(0.6, 0.8, 0.0),
        DVec3::Z,
    );
    let hillside = frame_along(DVec3::new(600.0, 0.0, 1500.0), DVec3::Y, DVec3::Z);
    let off_centre = frame_along(DVec3::new(600.0, 100.0, 50.0), DVec3::Z, DVec3::X);
    let centred = frame_along(DVec3::new(0.0, 0.0, 50.0), DVec3::Z, DVec3::X);
    vec![
        Case {
            name: "4in radial on a 2 m shell",
            neck: place(&nozzle(4.0, 1400.0), radial),
            host: on_shell.surface.clone(),
        },
        Case {
            name: "8in radial on a 2 m shell",
            neck: place(&nozzle(8.0, 1400.0), radial),
            host: on_shell.surface.clone(),
        },
        Case {
            name: "8in hillside on a 2 m shell",
            neck: place(&nozzle(8.0, 1400.0), hillside),
            host: on_shell.surface.clone(),
        },
        Case {
            name: "6in off-centre on a 2:1 head",
            neck: place(&nozzle(6.0, 900.0), off_centre),
            host: ellipsoid.surface.clone(),
        },
        Case {
            name: "6in centred on a 2:1 head",
            neck: place(&nozzle(6.0, 900.0), centred),
            host: ellipsoid.surface,
        },
    ]
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("opening");
    group
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(30);
    for case in cases() {
        group.bench_function(format!("loop: {}", case.name), |b| {
            b.iter(|| {
                black_box(
                    neck_host_intersection(&case.neck, &case.host, TOLERANCE).expect("a loop"),
                )
            })
        });
    }

    // A whole cut with a pad: the neck's loop and the pad's outer loop.
    let course = shell(2000.0, 3000.0);
    let n = nozzle(8.0, 1400.0);
    let neck = neck_patch(&n);
    let frame = frame_along(
        DVec3::new(0.0, 0.0, 1500.0),
        DVec3::new(0.6, 0.8, 0.0),
        DVec3::Z,
    );
    let pad_od = Some(2.0 * n.outside_diameter());
    group.bench_function("cut: 8in with pad on a 2 m shell", |b| {
        b.iter(|| {
            black_box(
                cut_opening(
                    &neck,
                    pad_od,
                    &frame,
                    &DAffine3::IDENTITY,
                    &[&course],
                    TOLERANCE,
                )
                .expect("a cut"),
            )
        })
    });

    // The same cut after the nozzle moved 100 mm along the course's axis, placed
    // from the canonical cut kept from the first (what an elevation edit, or a
    // longer course below, costs per opening).
    let kept = cut_opening_reusing(
        &neck,
        pad_od,
        &frame,
        &DAffine3::IDENTITY,
        &[&course],
        TOLERANCE,
        None,
    )
    .expect("a cut")
    .axial
    .expect("a course keeps its canonical cut");
    // Placed at `at` from the kept canonical cut (asserted).
    let placed = |at: &DAffine3| {
        let cut = cut_opening_reusing(
            &neck,
            pad_od,
            at,
            &DAffine3::IDENTITY,
            &[&course],
            TOLERANCE,
            Some(&kept),
        )
        .expect("a cut");
        assert!(cut.reused);
        cut
    };
    let moved = DAffine3::from_translation(DVec3::new(0.0, 0.0, 100.0)) * frame;
    group.bench_function("cut: 8in with pad moved along the shell's axis", |b| {
        b.iter(|| black_box(placed(&moved)))
    });

    // The same cut turned 70° about the course's axis (an orientation edit):
    // placed from the kept canonical cut too, host u in closed form.
    let turned = DAffine3::from_rotation_z(70f64.to_radians()) * frame;
    group.bench_function("cut: 8in with pad turned about the shell's axis", |b| {
        b.iter(|| black_box(placed(&turned)))
    });

    // Region layout of a course with six openings at two elevations.
    let loops: Vec<_> = (0..6)
        .map(|k| {
            let angle = f64::from(k) * std::f64::consts::TAU / 6.0 + 0.3;
            let axis = DVec3::new(angle.cos(), angle.sin(), 0.0);
            let z = if k % 2 == 0 { 900.0 } else { 2100.0 };
            let placed = neck
                .surface
                .transformed(&frame_along(DVec3::new(0.0, 0.0, z), axis, DVec3::Z))
                .expect("finite frame");
            neck_host_intersection(&placed, &course.surface, TOLERANCE).expect("a loop")
        })
        .collect();
    let holes: Vec<_> = loops.iter().collect();
    let options = TessellationOptions::chord(TOLERANCE);
    group.bench_function("layout: 2 m course with six openings", |b| {
        b.iter(|| {
            black_box(host_region(&course.surface, &options, &holes, &[], None).expect("a region"))
        })
    });
    // The same with the course's sides kept from its last layout (as the Regions
    // system does while the course's surface is unchanged).
    let sides = PatchSides::of(&course.surface, &options);
    group.bench_function("layout: the same, sides kept", |b| {
        b.iter(|| {
            black_box(
                host_region_with(&course.surface, &sides, &holes, &[], None).expect("a region"),
            )
        })
    });
    group.finish();
}

criterion_group!(group, bench);
