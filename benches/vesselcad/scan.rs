//! Scan fitting (`vesselcad::scan`): points per second through projection on the
//! exact patches, the per-patch least-squares fit and the deviation, end to end in
//! the vessel frame (registration apart), on one and two threads; and the least
//! squares alone on 10⁶ points of one course. The scan is a simulated 200,000
//! points of the test drum (`tests/common/scan.rs`).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use glam::DVec3;
use vesselcad::design::parse;
use vesselcad::scan::checks::CheckOptions;
use vesselcad::scan::fit::{FitOptions, Sample, fit_patch};
use vesselcad::scan::inspect::{InspectOptions, inspect};
use vesselcad::scan::simulate::{SimulateOptions, simulate};
use vesselcad::scan::{Envelope, Targets};

#[path = "../../tests/common/scan.rs"]
#[expect(dead_code, reason = "the bench uses the drum only")]
mod designs;

fn drum() -> Envelope {
    let design = parse(designs::DRUM).expect("the test drum parses");
    Envelope::of_design(&design, "V-1").expect("the test drum builds")
}

fn points(env: &Envelope, density: f64) -> Vec<DVec3> {
    let options = SimulateOptions {
        density,
        noise: 1.0,
        occlusion: 0.0,
        seed: 5,
        site: None,
        defects: Vec::new(),
    };
    simulate(env, &options).expect("simulates").points
}

fn bench(c: &mut Criterion) {
    let env = drum();
    let scan = points(&env, 4000.0);
    let mut group = c.benchmark_group("scan");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    group.throughput(Throughput::Elements(scan.len() as u64));
    let options = InspectOptions {
        register: None,
        fit: FitOptions::DEFAULT,
        checks: CheckOptions::DEFAULT,
    };
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        group.bench_with_input(BenchmarkId::new("end to end", threads), &threads, |b, _| {
            b.iter(|| {
                pool.install(|| black_box(inspect(&env, scan.clone(), &options).expect("inspects")))
            })
        });
    }
    // Least squares alone: 10⁶ samples on course S1.
    let index = env
        .surfaces
        .iter()
        .position(|s| env.parts[s.part].id == "S1")
        .expect("S1");
    let s = &env.surfaces[index];
    let to_vessel = env.frame.inverse();
    let mut samples: Vec<Sample> = Vec::new();
    let dense = points(&env, 60_000.0);
    for p in dense {
        let q = to_vessel.transform_point3(p);
        if let Some(f) = env.project(q, Targets::Envelope, 100.0)
            && f.surface == index
        {
            samples.push(Sample {
                u: f.u,
                v: f.v,
                offset: s.inverse.transform_vector3(q - f.point),
                normal: s.inverse.transform_vector3(f.normal),
            });
        }
        if samples.len() == 1_000_000 {
            break;
        }
    }
    group.throughput(Throughput::Elements(samples.len() as u64));
    group.bench_function("least squares 1e6", |b| {
        b.iter(|| {
            black_box(
                fit_patch(&s.patch.surface, &samples, &FitOptions::DEFAULT, "S1").expect("fits"),
            )
        })
    });
    group.finish();
}

criterion_group!(group, bench);
