//! Where a one-parameter edit's time goes in a generated plant: the cost of an
//! update with nothing to do (change-detection scans) and of each kind of edit,
//! with the work counters of each.
//!
//! `cargo run --release --example plant_edits -- [vessels] [tolerance]`

use std::time::Instant;

use vesselcad::design::PartDesign;
use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Edit, Model};
use vesselcad::plant::generate_plant;

fn main() {
    let mut args = std::env::args().skip(1);
    let vessels: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(200);
    let tolerance: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1.0);
    let design = generate_plant(vessels, 1).expect("generated");
    let start = Instant::now();
    let mut model =
        Model::from_design(&design, TessellationOptions::chord(tolerance)).expect("valid");
    println!(
        "{vessels} vessels built in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    let time = |model: &mut Model, edit: Option<Edit>| {
        let start = Instant::now();
        let counters = match edit {
            Some(e) => model.edit(e).expect("valid edit"),
            None => model.update(),
        };
        (start.elapsed().as_secs_f64() * 1e3, counters)
    };
    for _ in 0..3 {
        let (ms, _) = time(&mut model, None);
        println!("empty update: {ms:.3} ms");
    }
    let v = &design.vessels[vessels / 2];
    let mut nozzle = v.nozzles[0].clone();
    for (what, delta) in [("projection", 50.0), ("projection back", -50.0)] {
        nozzle.projection += delta;
        let (ms, c) = time(
            &mut model,
            Some(Edit::SetNozzle {
                vessel: v.tag.clone(),
                nozzle: nozzle.clone(),
            }),
        );
        println!("nozzle {what}: {ms:.3} ms {c:?}");
    }
    for (what, delta) in [("elevation", 100.0), ("elevation back", -100.0)] {
        nozzle.elevation = nozzle.elevation.map(|z| z + delta);
        let (ms, c) = time(
            &mut model,
            Some(Edit::SetNozzle {
                vessel: v.tag.clone(),
                nozzle: nozzle.clone(),
            }),
        );
        println!("nozzle {what}: {ms:.3} ms {c:?}");
    }
    let mut placement = v.placement;
    placement.position[0] += 100.0;
    let (ms, c) = time(
        &mut model,
        Some(Edit::MoveVessel {
            tag: v.tag.clone(),
            placement,
        }),
    );
    println!("move vessel: {ms:.3} ms {c:?}");
    if let Some(PartDesign::Shell(s)) = v.parts.iter().find(|p| p.kind() == "shell") {
        let mut s = s.clone();
        s.length += 100.0;
        let (ms, c) = time(
            &mut model,
            Some(Edit::SetPart {
                vessel: v.tag.clone(),
                part: PartDesign::Shell(s),
            }),
        );
        println!("shell length: {ms:.3} ms {c:?}");
    }
}
