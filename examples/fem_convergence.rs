//! The convergence table of the peak stress at a radial nozzle's junction
//! (vessel OD 1000, t 10, 1 MPa, NPS 8 STD at elevation 750): element size,
//! elements, the course's far membrane stress and the peak membrane-plus-bending
//! stress intensity of the course and of the neck, solved by CalculiX. The
//! test `fem_nozzle::junction_peak_above_membrane_and_converging` solves the
//! two coarsest sizes in CI; this runs the whole table.
//!
//! `cargo run --profile test --example fem_convergence [-- 100 60 36 22]`

#[path = "../tests/common/fem.rs"]
#[expect(dead_code, reason = "the test helpers serve several test files")]
mod fem;

use vesselcad::fem::results::intensity;

fn main() {
    let sizes: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![100.0, 60.0, 36.0, 22.0]
    } else {
        sizes
    };
    let design = fem::with_nozzles(
        r#""shape": "ellipsoidal""#,
        1000.0,
        1500.0,
        10.0,
        1000.0,
        r#"{ "mark": "N1", "size": 8, "rating": 150, "host": "S1", "orientation": 60,
             "elevation": 750, "projection": 900 }"#,
    );
    println!("| size mm | elements | far Pm MPa | course peak Pm+Pb MPa | neck peak Pm+Pb MPa |");
    println!("|---|---|---|---|---|");
    for size in sizes {
        let m = fem::model(&design, size);
        let Some(results) = fem::solve(&m, &format!("nozzle{}", size as u32)) else {
            return;
        };
        let part = |id: &str| m.mesh.parts.iter().position(|p| p.id == id);
        let peak = |k: Option<usize>| {
            k.map_or(0.0, |k| {
                m.mesh
                    .part_nodes(k)
                    .into_iter()
                    .map(|n| results[n].surface_intensity)
                    .fold(0.0, f64::max)
            })
        };
        let far = part("S1").map_or(0.0, |k| {
            m.mesh
                .part_nodes(k)
                .into_iter()
                .filter(|&n| {
                    let p = m.mesh.nodes[n];
                    p.y < -300.0 && (p.z - 750.0).abs() < 150.0
                })
                .map(|n| intensity(results[n].membrane))
                .fold(0.0, f64::max)
        });
        println!(
            "| {size:.0} | {} | {far:.2} | {:.2} | {:.2} |",
            m.mesh.elements.len(),
            peak(part("S1")),
            peak(part("N1"))
        );
    }
}
