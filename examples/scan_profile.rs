//! Times the scan inspection's steps on a simulated scan of the test drum
//! (`tests/common/scan.rs`): projection of every point on the exact patches,
//! the per-patch least-squares fits, the checks, and the whole `inspect` in the
//! vessel frame; then the least squares alone on 10⁶ points of course S1. For
//! profiling (`perf record`, callgrind) of one step.
//!
//! `cargo run --profile test --example scan_profile -- [all|project|fit|check|inspect|ls] [density] [threads]`
//! (`inspect` stops before the least squares on 10⁶ points, `ls` skips the
//! whole inspect, `all` runs everything)
use glam::DVec3;
use vesselcad::design::parse;
use vesselcad::scan::checks::{CheckOptions, check};
use vesselcad::scan::fit::{FitOptions, Sample, fit_patch};
use vesselcad::scan::inspect::{InspectOptions, inspect};
use vesselcad::scan::{Envelope, Foot, Targets};

#[path = "../tests/common/scan.rs"]
#[expect(dead_code, reason = "the example uses the drum only")]
mod designs;
#[path = "support/scan_run.rs"]
mod run;

use run::{points, timed};

fn samples_of(
    env: &Envelope,
    points: &[DVec3],
    feet: &[Option<Foot>],
    index: usize,
) -> Vec<Sample> {
    let s = &env.surfaces[index];
    points
        .iter()
        .zip(feet)
        .filter_map(|(p, f)| {
            let f = f.as_ref().filter(|f| f.surface == index && f.inside)?;
            Some(Sample {
                u: f.u,
                v: f.v,
                offset: s.inverse.transform_vector3(*p - f.point),
                normal: s.inverse.transform_vector3(f.normal),
            })
        })
        .collect()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let which = args.next().unwrap_or_else(|| "all".into());
    let density: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(4000.0);
    let threads: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(2);
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global()
        .expect("the global pool");
    let design = parse(designs::DRUM).expect("the test drum parses");
    let env = Envelope::of_design(&design, "V-1").expect("the test drum builds");
    let to_vessel = env.frame.inverse();
    let scan: Vec<DVec3> = points(&env, density)
        .into_iter()
        .map(|p| to_vessel.transform_point3(p))
        .collect();
    println!("{} points, {threads} threads", scan.len());
    let margin = env.default_margin();
    let candidates = scan
        .iter()
        .map(|p| {
            env.surfaces
                .iter()
                .filter(|s| {
                    !(p.cmplt(s.bbox.min - margin).any() || p.cmpgt(s.bbox.max + margin).any())
                })
                .count()
        })
        .sum::<usize>() as f64
        / scan.len() as f64;
    println!(
        "{} patches, {candidates:.2} grown boxes hold a point on average",
        env.surfaces.len()
    );
    let (feet, wall, cpu_s) = timed(|| env.project_all(&scan, Targets::WithNozzles, margin));
    println!(
        "project: {wall:.3} s wall, {cpu_s:.2} s CPU ({:.0} points per CPU second)",
        scan.len() as f64 / cpu_s.max(0.01)
    );
    if which == "project" {
        return;
    }
    let per_surface: Vec<Vec<Sample>> = (0..env.surfaces.len())
        .map(|i| samples_of(&env, &scan, &feet, i))
        .collect();
    let (fits, wall, cpu_s) = timed(|| -> Vec<_> {
        per_surface
            .iter()
            .enumerate()
            .map(|(i, data)| {
                let s = &env.surfaces[i];
                (env.parts[s.part].role.is_envelope() && data.len() >= 16).then(|| {
                    fit_patch(&s.patch.surface, data, &FitOptions::DEFAULT, s.patch.name)
                        .expect("fits")
                })
            })
            .collect()
    });
    println!("fit: {wall:.3} s wall, {cpu_s:.2} s CPU");
    if which == "fit" {
        return;
    }
    let (checks, wall, cpu_s) = timed(|| check(&env, &fits, &scan, &feet, &CheckOptions::DEFAULT));
    println!(
        "check: {wall:.3} s wall, {cpu_s:.2} s CPU ({} findings)",
        checks.findings.len()
    );
    if which == "check" {
        return;
    }
    if which == "all" || which == "inspect" {
        let options = InspectOptions {
            register: None,
            ..InspectOptions::DEFAULT
        };
        let site: Vec<DVec3> = scan
            .iter()
            .map(|&p| env.frame.transform_point3(p))
            .collect();
        let (_, wall, cpu_s) = timed(|| inspect(&env, site, &options).expect("inspects"));
        println!(
            "inspect: {wall:.3} s wall ({:.0} points/s), {cpu_s:.2} s CPU ({:.0} points per CPU second)",
            scan.len() as f64 / wall,
            scan.len() as f64 / cpu_s.max(0.01)
        );
    }
    if which == "inspect" {
        return;
    }
    let index = env
        .surfaces
        .iter()
        .position(|s| env.parts[s.part].id == "S1")
        .expect("S1");
    let dense: Vec<DVec3> = points(&env, 60_000.0)
        .into_iter()
        .map(|p| to_vessel.transform_point3(p))
        .collect();
    let feet = env.project_all(&dense, Targets::Envelope, 100.0);
    let mut samples = samples_of(&env, &dense, &feet, index);
    samples.truncate(1_000_000);
    let (fit, wall, cpu_s) = timed(|| {
        fit_patch(
            &env.surfaces[index].patch.surface,
            &samples,
            &FitOptions::DEFAULT,
            "S1",
        )
        .expect("fits")
    });
    println!(
        "least squares {} samples: {wall:.3} s wall, {cpu_s:.2} s CPU (net {:?}, {} rounds)",
        samples.len(),
        fit.net,
        fit.rounds
    );
}
