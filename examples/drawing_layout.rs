//! The sheet layout check over many generated vessels: for each vessel of a
//! generated plant, its sheet on every size, no two texts overlap, no text
//! crosses a view's outline and every text lies on the paper (the check
//! `tests/drawing_layout.rs` runs on the examples and a few vessels in CI).
//!
//! ```sh
//! cargo run --example drawing_layout -- [vessels=100] [seed=39]
//! ```

use std::process::ExitCode;

use vesselcad::drawing::{SheetOptions, SheetSize, layout_problems, sheet, sheet_model};
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
    let (mut sheets, mut problems) = (0usize, 0usize);
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
            let s = match sheet(&model, &v.tag, &SheetOptions::sized(size)) {
                Ok(s) => s,
                Err(e) => {
                    println!("{} {size:?}: {e}", v.tag);
                    problems += 1;
                    continue;
                }
            };
            sheets += 1;
            let found = layout_problems(&s);
            for p in &found {
                println!("{} {size:?} 1:{}: {p}", v.tag, s.scale);
            }
            problems += found.len();
        }
    }
    println!(
        "{} vessels, {sheets} sheets, {problems} layout problems",
        design.vessels.len()
    );
    if problems == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
