//! On every example design, every triangle of every patch mesh — trimmed hosts,
//! necks, pads, supports — stays within the chordal tolerance of the exact
//! surface: the surface points nearest to the triangle's centroid and edge
//! midpoints (found by point inversion) are within the tolerance. No triangle is
//! degenerate or faces against the exact normals. The minimum-angle distribution
//! (the seed's quality index) is printed.

mod common;

use vesselcad::components::{PatchMesh, PatchSurface};
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::Model;

const TOLERANCE: f64 = 1.0;

#[test]
fn every_triangle_is_within_the_tolerance() {
    let mut histogram = [0usize; 4];
    for name in ["horizontal-drum", "vertical-column", "storage-tank"] {
        let design = common::examples::example(name);
        let mut model = Model::from_design(&design, TessellationOptions::chord(TOLERANCE)).unwrap();
        assert!(model.errors().0.is_empty(), "{name}: {:?}", model.errors());
        let mut query = model.query::<(&PatchSurface, &PatchMesh)>();
        let world = model.world();
        let mut worst = 0.0f64;
        let mut triangles = 0;
        for (surface, mesh) in query.iter(world) {
            let s = &surface.0.surface;
            let m = &mesh.0.unpack();
            for t in m.indices.chunks(3) {
                let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions[i as usize]);
                let n = (b - a).cross(c - a);
                assert!(
                    n.length() > 0.0,
                    "{name}/{}: zero-area triangle",
                    surface.0.name
                );
                let exact = [t[0], t[1], t[2]]
                    .map(|i| m.normals[i as usize])
                    .into_iter()
                    .fold(glam::DVec3::ZERO, |x, y| x + y);
                assert!(
                    n.dot(exact) > 0.0,
                    "{name}/{}: triangle faces against the surface",
                    surface.0.name
                );
                for q in [
                    (a + b + c) / 3.0,
                    (a + b) / 2.0,
                    (b + c) / 2.0,
                    (c + a) / 2.0,
                ] {
                    let d = s.closest_point(q).unwrap().distance;
                    if d > TOLERANCE {
                        eprintln!("{name}/{}: {d} at {q}", surface.0.name);
                    }
                    worst = worst.max(d);
                }
                let angles = [
                    (b - a).angle_between(c - a),
                    (a - b).angle_between(c - b),
                    (a - c).angle_between(b - c),
                ];
                let min = angles
                    .iter()
                    .copied()
                    .fold(f64::INFINITY, f64::min)
                    .to_degrees();
                histogram[((min / 10.0) as usize).min(3)] += 1;
                triangles += 1;
            }
        }
        println!(
            "{name}: {triangles} triangles, max deviation {worst:.4} mm at tolerance {TOLERANCE} mm"
        );
        assert!(
            worst <= TOLERANCE * 1.0001,
            "{name}: deviation {worst} mm exceeds {TOLERANCE} mm"
        );
    }
    let total: usize = histogram.iter().sum();
    println!(
        "minimum angle: <10° {:.1}%, 10–20° {:.1}%, 20–30° {:.1}%, ≥30° {:.1}%",
        100.0 * histogram[0] as f64 / total as f64,
        100.0 * histogram[1] as f64 / total as f64,
        100.0 * histogram[2] as f64 / total as f64,
        100.0 * histogram[3] as f64 / total as f64
    );
}

/// Share of triangles whose smallest angle is under 10°, the smallest angle, the
/// largest deviation and the triangle count of a design meshed with `options`.
fn quality(
    design: &vesselcad::design::Design,
    options: TessellationOptions,
) -> (f64, f64, f64, usize) {
    let mut model = Model::from_design(design, options).unwrap();
    assert!(model.errors().0.is_empty(), "{:?}", model.errors());
    let mut query = model.query::<(&PatchSurface, &PatchMesh)>();
    let world = model.world();
    let (mut slivers, mut total, mut smallest, mut worst) = (0usize, 0usize, f64::INFINITY, 0.0f64);
    for (surface, mesh) in query.iter(world) {
        let m = &mesh.0.unpack();
        for t in m.indices.chunks(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| m.positions[i as usize]);
            let min = [
                (b - a).angle_between(c - a),
                (a - b).angle_between(c - b),
                (a - c).angle_between(b - c),
            ]
            .into_iter()
            .fold(f64::INFINITY, f64::min)
            .to_degrees();
            smallest = smallest.min(min);
            slivers += usize::from(min < 10.0);
            total += 1;
            let d = surface
                .0
                .surface
                .closest_point((a + b + c) / 3.0)
                .unwrap()
                .distance;
            worst = worst.max(d);
        }
    }
    (slivers as f64 / total as f64, smallest, worst, total)
}

/// The stretch limit trades triangles for shape: on the drum at 1 mm it removes
/// the needles along straight generators while keeping the chordal bound.
#[test]
fn a_stretch_limit_removes_needles() {
    let design = common::examples::example("horizontal-drum");
    let plain = quality(&design, TessellationOptions::chord(TOLERANCE));
    let limited = quality(
        &design,
        TessellationOptions::chord(TOLERANCE).with_max_stretch(Some(3.0)),
    );
    println!("no limit: {plain:?}; stretch 3: {limited:?}");
    assert!(limited.2 <= TOLERANCE * 1.0001, "deviation {}", limited.2);
    assert!(limited.0 < 0.05, "{:.1}% under 10°", 100.0 * limited.0);
    assert!(limited.0 < plain.0 / 3.0);
    assert!(
        limited.1 > 10.0 * plain.1,
        "smallest angle {} vs {}",
        limited.1,
        plain.1
    );
}
