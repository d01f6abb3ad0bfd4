//! Simulation ticks for an instruction count: a generated plant, then ticks of
//! 100 random edits (as `vesselcad simulate` draws them, drawing views off)
//! inside a one-thread pool, all in the function `ticks`, so that
//! `valgrind --tool=callgrind --toggle-collect='tick_instructions::ticks'`
//! counts the ticks' instructions alone. Instruction counts are repeatable
//! whatever else the machine does, where wall time on this shared machine
//! varies by ±10 % between runs: compare two commits with this, and confirm in
//! wall time with `vesselcad bench`.
//!
//! `cargo run --release --example tick_instructions -- [vessels] [ticks]`
//! (default 400 vessels, 10 ticks); it prints the triangles meshed, which two
//! commits must agree on for their counts to compare like with like.

use vesselcad::mesh::TessellationOptions;
use vesselcad::model::{Model, Views};
use vesselcad::plant::{Simulation, generate_plant};

// What the binary runs (see `src/cli/alloc.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// `count` ticks of 100 edits; the triangles they meshed.
#[inline(never)]
fn ticks(simulation: &mut Simulation, count: usize) -> u64 {
    (0..count)
        .map(|_| simulation.tick(100, 0).counters.triangles_meshed)
        .sum()
}

type Error = Box<dyn std::error::Error + Send + Sync>;

fn main() -> Result<(), Error> {
    vesselcad::allocator::hold_freed_memory();
    let mut args = std::env::args().skip(1);
    let vessels: usize = args.next().map_or(Ok(400), |a| a.parse())?;
    let count: usize = args.next().map_or(Ok(10), |a| a.parse())?;
    // One thread, and the ticks run on it: callgrind's toggle follows the
    // thread whose stack holds `ticks`.
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    pool.install(|| {
        let design = generate_plant(vessels, 1)?;
        let model = Model::from_design_with(&design, TessellationOptions::chord(1.0), Views::Off)?;
        let mut simulation = Simulation::new(model, &design, 7);
        let triangles = ticks(&mut simulation, count);
        println!("{vessels} vessels, {count} ticks of 100 edits: {triangles} triangles meshed");
        Ok::<_, Error>(())
    })
}
