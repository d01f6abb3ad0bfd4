//! Grid evaluation, the meshing hot path: batched `evaluate_grid` and
//! `evaluate_grid_with_normals` against point-by-point `point` and `normal`, on the
//! rational biquadratic patches of an ASME F&D head (knuckle, crown) and the rational
//! quadratic × linear patch of a shell course. Throughput is grid points per second.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use glam::DVec3;
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::Shell;
use vesselcad::parts::heads::{Head, HeadKind};

/// Grid parameters per direction and patch.
const SIZE: usize = 256;
/// Outside diameter of the vessel, mm.
const OD: f64 = 2400.0;

/// The benchmarked patches: ASME F&D knuckle and crown, and a 6 m shell course.
fn surfaces() -> Vec<(String, NurbsSurface)> {
    let head = Head::new(OD, HeadKind::asme_fd(OD))
        .patches()
        .expect("the ASME F&D head is valid");
    let shell = Shell {
        outside_diameter: OD,
        length: 6000.0,
    }
    .patches()
    .expect("the shell is valid");
    let head = head
        .into_iter()
        .map(|p| (format!("F&D {}", p.name), p.surface));
    let shell = shell.into_iter().map(|p| (p.name.to_string(), p.surface));
    head.chain(shell).collect()
}

/// `n` parameters evenly spaced over `(a, b)`, both ends included.
fn spaced((a, b): (f64, f64), n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("grid");
    group.throughput(Throughput::Elements((SIZE * SIZE) as u64));
    let mut points: Vec<DVec3> = Vec::with_capacity(SIZE * SIZE);
    let mut normals: Vec<DVec3> = Vec::with_capacity(SIZE * SIZE);
    for (name, surface) in surfaces() {
        let (du, dv) = surface.domain();
        let (us, vs) = (spaced(du, SIZE), spaced(dv, SIZE));
        group.bench_function(BenchmarkId::new("points/grid", &name), |b| {
            b.iter(|| {
                surface.evaluate_grid(black_box(&us), black_box(&vs), &mut points);
                black_box(&points);
            })
        });
        group.bench_function(BenchmarkId::new("points/pointwise", &name), |b| {
            b.iter(|| {
                points.clear();
                for &u in black_box(&us) {
                    points.extend(vs.iter().map(|&v| surface.point(u, v)));
                }
                black_box(&points);
            })
        });
        group.bench_function(BenchmarkId::new("points+normals/grid", &name), |b| {
            b.iter(|| {
                surface.evaluate_grid_with_normals(
                    black_box(&us),
                    black_box(&vs),
                    &mut points,
                    &mut normals,
                );
                black_box((&points, &normals));
            })
        });
        group.bench_function(BenchmarkId::new("points+normals/pointwise", &name), |b| {
            b.iter(|| {
                points.clear();
                normals.clear();
                for &u in black_box(&us) {
                    for &v in &vs {
                        points.push(surface.point(u, v));
                        normals.push(surface.normal(u, v));
                    }
                }
                black_box((&points, &normals));
            })
        });
    }
    group.finish();
}

criterion_group! {
    name = group;
    config = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = bench
}
