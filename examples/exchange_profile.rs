//! STEP and IGES export timed and ready for an instruction count: a design
//! (the example column by default) or a generated plant, exported whole with no
//! cached blocks inside a one-thread pool, in the function `export`, so that
//! `valgrind --tool=callgrind --toggle-collect='exchange_profile::export'`
//! counts the export's instructions alone. Prints the vessels, bytes, wall
//! time, vessels/s and MB/s of each export.
//!
//! `cargo run --release --example exchange_profile -- [design.json | --plant N] [step|iges] [repeats]`

use std::path::Path;
use std::time::Instant;

use vesselcad::design::{Design, load};
use vesselcad::exchange::{ExchangeOptions, StepBlocks, export_iges, export_step};
use vesselcad::plant::generate_plant;

// What the binary runs (see `src/cli/alloc.rs`).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

type Error = Box<dyn std::error::Error + Send + Sync>;

/// One export of `design` in `format`, its text.
#[inline(never)]
fn export(design: &Design, format: &str) -> Result<String, Error> {
    let options = ExchangeOptions::DEFAULT;
    Ok(match format {
        "iges" => export_iges(design, &[], &options, "profile.igs")?,
        _ => export_step(
            design,
            &[],
            &options,
            "profile.step",
            &mut StepBlocks::default(),
        )?,
    })
}

fn main() -> Result<(), Error> {
    let mut args = std::env::args().skip(1).peekable();
    let design = match args.next().as_deref() {
        Some("--plant") => generate_plant(args.next().map_or(Ok(1000), |a| a.parse())?, 1)?,
        Some(path) => load(Path::new(path))?,
        None => load(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/designs/vertical-column.json"),
        )?,
    };
    let format = args.next().unwrap_or_else(|| "step".to_string());
    let repeats: usize = args.next().map_or(Ok(1), |a| a.parse())?;
    let vessels = design.vessels.len();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    pool.install(|| {
        for _ in 0..repeats {
            let start = Instant::now();
            let text = export(&design, &format)?;
            let seconds = start.elapsed().as_secs_f64();
            println!(
                "{format}: {vessels} vessels, {} bytes ({:.1} kB/vessel), {:.3} s, {:.1} vessels/s, {:.2} MB/s",
                text.len(),
                text.len() as f64 / vessels as f64 / 1e3,
                seconds,
                vessels as f64 / seconds,
                text.len() as f64 / seconds / 1e6
            );
        }
        Ok::<_, Error>(())
    })
}
