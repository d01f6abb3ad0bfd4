//! Builds every head type at one diameter and prints its depth, surface area,
//! enclosed volume and the largest deviation of its NURBS from the analytic shape.
//!
//! ```sh
//! cargo run --release --example head_gallery -- --diameter 2400 [--straight-flange 50]
//! ```

use std::process::ExitCode;

use vesselcad::parts::heads::{Head, HeadKind};
use vesselcad::parts::{Patch, enclosed_volume, surface_area};

/// Samples per parameter direction when measuring the deviation.
const SAMPLES: usize = 101;

/// Largest distance of a dense grid of NURBS points from the analytic surfaces.
fn max_deviation(patches: &[Patch]) -> f64 {
    let mut worst = 0.0f64;
    for p in patches {
        let ((u0, u1), (v0, v1)) = p.surface.domain();
        for i in 0..SAMPLES {
            for j in 0..SAMPLES {
                let u = u0 + (u1 - u0) * i as f64 / (SAMPLES - 1) as f64;
                let v = v0 + (v1 - v0) * j as f64 / (SAMPLES - 1) as f64;
                worst = worst.max(p.analytic.distance(p.surface.point(u, v)));
            }
        }
    }
    worst
}

fn arg(name: &str, default: f64) -> Result<f64, String> {
    let args: Vec<String> = std::env::args().collect();
    match args.iter().position(|a| a == name) {
        None => Ok(default),
        Some(i) => args
            .get(i + 1)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| format!("{name} needs a number")),
    }
}

fn main() -> ExitCode {
    let (d, sf) = match (arg("--diameter", 2400.0), arg("--straight-flange", 0.0)) {
        (Ok(d), Ok(sf)) => (d, sf),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let kinds = [
        ("hemispherical", HeadKind::Hemispherical),
        ("2:1 ellipsoidal", HeadKind::TWO_TO_ONE),
        ("ASME F&D (L = D, r = 0.06 L)", HeadKind::asme_fd(d)),
        ("80:10 torispherical", HeadKind::eighty_ten(d)),
        (
            "toriconical 30°, r = 0.1 D",
            HeadKind::Toriconical {
                half_angle: 30.0,
                knuckle_radius: 0.1 * d,
            },
        ),
        (
            "conical 30°",
            HeadKind::Conical {
                half_angle: 30.0,
                small_diameter: 0.0,
            },
        ),
        (
            "flat, knuckle 0.05 D",
            HeadKind::Flat {
                knuckle_radius: 0.05 * d,
            },
        ),
    ];
    println!("heads of outside diameter {d} mm, straight flange {sf} mm\n");
    println!(
        "{:<30} {:>10} {:>12} {:>12} {:>14}",
        "head", "depth mm", "area m²", "volume m³", "max dev mm"
    );
    for (name, kind) in kinds {
        let head = Head::new(d, kind).with_straight_flange(sf);
        let result = head.patches().and_then(|p| Ok((head.depth()?, p)));
        match result {
            Ok((depth, patches)) => println!(
                "{:<30} {:>10.2} {:>12.4} {:>12.4} {:>14.2e}",
                name,
                depth,
                surface_area(&patches) * 1e-6,
                enclosed_volume(&patches) * 1e-9,
                max_deviation(&patches)
            ),
            Err(e) => {
                eprintln!("error: {name}: {e}");
                return ExitCode::from(1);
            }
        }
    }
    ExitCode::SUCCESS
}
