//! `vesselcad scan interpolate` through the binary: a sampled sphere zone (an
//! ordered grid, rows separated by blank lines) is interpolated exactly (the
//! seed's equation (12)), the JSON surface passes through every grid point and
//! stays within cubic interpolation's error of the sphere between them; a
//! ragged grid is refused naming its row.

use std::f64::consts::FRAC_PI_2;
use std::fmt::Write;
use std::path::Path;
use std::process::Command;

use glam::{DVec3, DVec4};
use vesselcad::nurbs::{KnotVector, NurbsSurface};

const R: f64 = 1000.0;
const ROWS: usize = 13;
const COLUMNS: usize = 17;

fn vesselcad(args: &[&str], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_vesselcad"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("vesselcad runs")
}

/// A sphere zone: latitudes 10° to 80° along the rows, a quarter turn of
/// longitude along each row; the angular steps of the grid.
fn sphere(i: usize, j: usize) -> DVec3 {
    let lat = (10.0 + 70.0 * i as f64 / (ROWS - 1) as f64).to_radians();
    let lon = FRAC_PI_2 * j as f64 / (COLUMNS - 1) as f64;
    R * DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin())
}

/// The grid as CSV: a header, rows separated by blank lines; `skip` leaves the
/// last point of that row (0-based) out.
fn grid_csv(skip: Option<usize>) -> String {
    let mut out = String::from("x,y,z\n");
    for i in 0..ROWS {
        if i > 0 {
            out.push('\n');
        }
        let n = if skip == Some(i) {
            COLUMNS - 1
        } else {
            COLUMNS
        };
        for j in 0..n {
            let p = sphere(i, j);
            writeln!(out, "{:.15e},{:.15e},{:.15e}", p.x, p.y, p.z).unwrap();
        }
    }
    out
}

fn floats(v: &serde_json::Value, key: &str) -> Vec<f64> {
    v[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} missing"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn a_sphere_zone_grid_is_interpolated_exactly_through_the_cli() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("zone.csv"), grid_csv(None)).unwrap();
    let out = vesselcad(&["scan", "interpolate", "zone.csv", "-o", "zone.json"], d);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("13 × 17 grid") && stdout.contains("max residual"),
        "{stdout}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("zone.json")).unwrap()).unwrap();
    let reported = json["max_residual_mm"].as_f64().unwrap();
    assert!(reported <= 1e-9, "reported residual {reported} mm");

    // The surface rebuilt from the file alone.
    let (p, q) = (
        json["degree_u"].as_u64().unwrap() as usize,
        json["degree_v"].as_u64().unwrap() as usize,
    );
    assert_eq!((p, q), (3, 3));
    let poles: Vec<DVec4> = json["control_points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let c: Vec<f64> = c
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            DVec4::new(c[0], c[1], c[2], 1.0)
        })
        .collect();
    let surface = NurbsSurface::try_new(
        KnotVector::try_new(p, floats(&json, "knots_u")).unwrap(),
        KnotVector::try_new(q, floats(&json, "knots_v")).unwrap(),
        poles,
    )
    .unwrap();
    let (u, v) = (floats(&json, "parameters_u"), floats(&json, "parameters_v"));
    assert_eq!((u.len(), v.len()), (ROWS, COLUMNS));
    let mut residual: f64 = 0.0;
    for (i, &ui) in u.iter().enumerate() {
        for (j, &vj) in v.iter().enumerate() {
            residual = residual.max((surface.point(ui, vj) - sphere(i, j)).length());
        }
    }
    assert!(
        residual <= 1e-9,
        "residual {residual} mm at the grid points"
    );

    // Between grid points (cell centres and edge midpoints) the surface is off
    // the sphere by cubic interpolation's error, about (5/384)·R·Δθ⁴ with Δθ
    // the larger angular step (70°/12 here: 1.4e-3 mm) away from the ends,
    // held to twice that; in the end cells (free ends: knots by averaging, no
    // end derivatives) the constant is larger, held to five times. A bilinear
    // patch would be off by R·Δθ²/8 ≈ 1.3 mm.
    let step = (70.0_f64 / (ROWS - 1) as f64).to_radians();
    let expected = 5.0 / 384.0 * R * step.powi(4);
    let (mut inner, mut worst): (f64, f64) = (0.0, 0.0);
    for i in 0..ROWS - 1 {
        for j in 0..COLUMNS - 1 {
            let (um, vm) = ((u[i] + u[i + 1]) / 2.0, (v[j] + v[j + 1]) / 2.0);
            for (a, b) in [(um, vm), (um, v[j]), (u[i], vm)] {
                let off = (surface.point(a, b).length() - R).abs();
                worst = worst.max(off);
                if (1..ROWS - 2).contains(&i) && (1..COLUMNS - 2).contains(&j) {
                    inner = inner.max(off);
                }
            }
        }
    }
    assert!(
        inner <= 2.0 * expected && worst <= 5.0 * expected,
        "{inner} mm (inner cells), {worst} mm (all) off the sphere between grid points, \
         expected ≤ {expected} mm"
    );
    eprintln!(
        "between grid points: {inner:.3e} mm inner, {worst:.3e} mm all, estimate {expected:.3e} mm"
    );
    assert!(worst > residual, "the test measures something: {worst} mm");
}

#[test]
fn a_ragged_grid_and_an_unsupported_output_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // Row 5 (0-based 4) one point short: its first line is the header, four
    // rows of 17 points and four blank lines in, 1 + 4·18 + 1 = 74.
    std::fs::write(d.join("ragged.csv"), grid_csv(Some(4))).unwrap();
    let out = vesselcad(&["scan", "interpolate", "ragged.csv", "-o", "s.json"], d);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("ragged.csv:74:")
            && err.contains("row 5 has 16 points")
            && err.contains("has 17"),
        "{err}"
    );
    assert!(!d.join("s.json").exists());

    std::fs::write(d.join("zone.csv"), grid_csv(None)).unwrap();
    let out = vesselcad(&["scan", "interpolate", "zone.csv", "-o", "s.step"], d);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("-o") && err.contains("s.step") && err.contains(".json"),
        "{err}"
    );
    let out = vesselcad(&["scan", "interpolate", "zone.csv", "-o", "zone.csv"], d);
    assert_eq!(out.status.code(), Some(1));
    let out = vesselcad(
        &[
            "scan",
            "interpolate",
            "zone.csv",
            "-o",
            "s.json",
            "--parametrization",
            "arc",
        ],
        d,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--parametrization") && err.contains("\"arc\""),
        "{err}"
    );
}
