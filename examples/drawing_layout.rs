//! The sheet layout check over many generated vessels: for each vessel of a
//! generated plant, on every size, its one-sheet drawing and every sheet of its
//! drawing's set: no two texts overlap, no text crosses a view's outline, every
//! text lies on the paper, and the set keeps the legibility rule (the checks
//! `tests/drawing_layout.rs` and `tests/drawing_sheets.rs` run on the examples
//! and a few vessels in CI).
//!
//! ```sh
//! cargo run --example drawing_layout -- [vessels=100] [seed=39]
//! ```

use std::process::ExitCode;

use vesselcad::drawing::{
    SheetOptions, SheetSize, layout_problems, legibility_problems, sheet, sheet_model, sheets,
    vessel_data,
};
use vesselcad::mesh::TessellationOptions;
use vesselcad::plant::generate_plant;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let vessels: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(39);
    let design = match generate_plant(vessels, seed) {
        Ok(d) => d,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let (mut count, mut problems, mut multi, mut details) = (0usize, 0usize, 0usize, 0usize);
    for v in &design.vessels {
        let model = match sheet_model(&design, &v.tag, TessellationOptions::chord(2.0)) {
            Ok((m, _)) => m,
            Err(e) => {
                println!("{}: not built: {e}", v.tag);
                problems += 1;
                continue;
            }
        };
        for size in SheetSize::ALL {
            let options = SheetOptions::sized(size);
            let (one, set) = match (
                sheet(&model, &v.tag, &options),
                sheets(&model, &v.tag, &options),
            ) {
                (Ok(one), Ok(set)) => (one, set),
                (Err(e), _) | (_, Err(e)) => {
                    println!("{} {size:?}: {e}", v.tag);
                    problems += 1;
                    continue;
                }
            };
            for s in std::iter::once(&one).chain(&set) {
                count += 1;
                let found = layout_problems(s);
                for p in &found {
                    println!(
                        "{} {size:?} sheet {} of {} 1:{}: {p}",
                        v.tag, s.number, s.of, s.scale
                    );
                }
                problems += found.len();
            }
            multi += usize::from(set.len() > 1);
            details += set.iter().map(|s| s.details.len()).sum::<usize>();
            if let Ok(data) = vessel_data(&model, &v.tag) {
                for p in legibility_problems(&data, &set) {
                    println!("{} {size:?}: {p}", v.tag);
                    problems += 1;
                }
            }
        }
    }
    println!(
        "{} vessels, {count} sheets checked ({multi} drawings of several sheets, \
         {details} detail views), {problems} layout problems",
        design.vessels.len()
    );
    if problems == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
