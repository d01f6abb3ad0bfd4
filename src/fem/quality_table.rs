//! The mesh quality report of `vesselcad fem --quality`: per part, the
//! element count, the quadrilaterals' corner angles (and the share in
//! 45–135°), the smallest triangle angle, the smallest scaled Jacobian (and the
//! share ≥ 0.3), the largest aspect ratio and the largest neighbour size ratio;
//! then the whole mesh's conformity counts and the seed's quality index
//! cos(min angle) as a histogram of ten bins (0 is a right-angled quad, 0.5 an
//! equilateral triangle, 1 a sliver).

use std::fmt::Write;

use super::FeMesh;
use super::quality::{Quality, by_part, quality};

/// One row of the table.
fn row(out: &mut String, name: &str, q: &Quality) {
    let share = |k: usize, of: usize| {
        if of == 0 {
            "-".to_string()
        } else {
            format!("{:.1}", 100.0 * k as f64 / of as f64)
        }
    };
    let quads = if q.quads == 0 {
        "-".to_string()
    } else {
        format!("{:.1}-{:.1}", q.quad_angles.0, q.quad_angles.1)
    };
    let tri = if q.quads == q.elements {
        "-".to_string()
    } else {
        format!("{:.1}", q.min_triangle_angle)
    };
    let _ = writeln!(
        out,
        "{name:<24} {:>8} {:>13} {:>7} {:>8} {:>7.3} {:>7} {:>7.2} {:>7.2}",
        q.elements,
        quads,
        share(q.quads_in_range, q.quads),
        tri,
        q.min_scaled_jacobian,
        share(q.jacobian_ok, q.elements),
        q.max_aspect,
        q.max_size_ratio,
    );
}

/// The quality report of `mesh`, as text (one line per part, then the whole
/// mesh, its conformity counts and the histogram).
pub fn report(mesh: &FeMesh) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<24} {:>8} {:>13} {:>7} {:>8} {:>7} {:>7} {:>7} {:>7}",
        "part",
        "elements",
        "quad angles",
        "% 45-135",
        "tri min",
        "min SJ",
        "% SJ>=.3",
        "aspect",
        "grading"
    );
    for (part, q) in mesh.parts.iter().zip(by_part(mesh)) {
        row(&mut out, &part.name, &q);
    }
    let q = quality(mesh);
    row(&mut out, "(all)", &q);
    let _ = writeln!(
        out,
        "conformity: {} free edges, {} non-manifold edges, {} coincident nodes, {} inverted elements",
        q.free_edges, q.nonmanifold_edges, q.coincident_nodes, q.inverted
    );
    let _ = writeln!(out, "cos(min angle)   elements");
    let most = q.histogram.iter().copied().max().unwrap_or(0).max(1);
    for (k, &count) in q.histogram.iter().enumerate() {
        let bar = "#".repeat((40 * count).div_ceil(most));
        let _ = writeln!(
            out,
            "{:.1}-{:.1}      {count:>9} {bar}",
            0.1 * k as f64,
            0.1 * (k + 1) as f64
        );
    }
    out
}
