//! The CalculiX / Abaqus input deck: `*NODE`, `*ELEMENT` (S8R, S6, S4R, S3) per
//! part, node and element sets named by part (`V-101/S1`), `*MATERIAL` with
//! `*ELASTIC` and `*DENSITY`, `*SHELL SECTION` per part, `*BOUNDARY`, one
//! `*STEP` with `*DLOAD` pressure on the inner side (`P` on the outward-normal
//! elements pushes them outwards), `*CLOAD` nozzle end thrusts and `GRAV`, and the output requests
//! (`*NODE FILE` U and RF, `*EL FILE` S, results on the mid-surface and both faces).

use std::fmt::Write;

use super::{ElementKind, FeModel};

/// The solver name of an element kind.
pub fn element_type(kind: ElementKind) -> &'static str {
    match kind {
        ElementKind::Quad8 => "S8R",
        ElementKind::Quad4 => "S4R",
        ElementKind::Tri6 => "S6",
        ElementKind::Tri3 => "S3",
    }
}

/// A set name as the deck spells it: the part's name with characters other
/// than letters, digits, `_` and `-` replaced by `_` (`V-101/S1` → `V-101_S1`).
pub fn set_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes 16 or fewer numbers a line.
fn id_lines(out: &mut String, ids: impl Iterator<Item = usize>) {
    let ids: Vec<usize> = ids.collect();
    for chunk in ids.chunks(16) {
        let line: Vec<String> = chunk.iter().map(|i| (i + 1).to_string()).collect();
        let _ = writeln!(out, "{}", line.join(", "));
    }
}

/// The `.inp` text of `model`.
pub fn to_inp(model: &FeModel) -> String {
    let mesh = &model.mesh;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "** vesselcad FE model of {}, load case {}\n** units: mm, N, MPa, t/mm^3, s\n*HEADING\n{} {}",
        model.tag,
        model.case.name(),
        model.tag,
        model.case.name()
    );
    for note in &mesh.notes {
        let _ = writeln!(out, "** {note}");
    }
    out.push_str("*NODE, NSET=NALL\n");
    for (i, p) in mesh.nodes.iter().enumerate() {
        let _ = writeln!(out, "{}, {:.9e}, {:.9e}, {:.9e}", i + 1, p.x, p.y, p.z);
    }
    for (k, part) in mesh.parts.iter().enumerate() {
        let set = set_name(&part.name);
        for kind in [
            ElementKind::Quad8,
            ElementKind::Tri6,
            ElementKind::Quad4,
            ElementKind::Tri3,
        ] {
            let els: Vec<usize> = (0..mesh.elements.len())
                .filter(|&e| mesh.elements[e].part == k && mesh.elements[e].kind == kind)
                .collect();
            if els.is_empty() {
                continue;
            }
            let _ = writeln!(out, "*ELEMENT, TYPE={}, ELSET={set}", element_type(kind));
            for e in els {
                let nodes: Vec<String> = mesh.elements[e]
                    .nodes
                    .iter()
                    .map(|n| (n + 1).to_string())
                    .collect();
                let _ = writeln!(out, "{}, {}", e + 1, nodes.join(", "));
            }
        }
        let _ = writeln!(out, "*NSET, NSET={set}");
        id_lines(&mut out, mesh.part_nodes(k).into_iter());
    }
    out.push_str("*ELSET, ELSET=EALL\n");
    for part in &mesh.parts {
        let _ = writeln!(out, "{}", set_name(&part.name));
    }
    let _ = writeln!(
        out,
        "*MATERIAL, NAME=STEEL\n** {}\n*ELASTIC\n{:.6e}, {}\n*DENSITY\n{:.6e}",
        model.material, model.modulus, model.poisson, model.density
    );
    for part in &mesh.parts {
        let _ = writeln!(
            out,
            "*SHELL SECTION, ELSET={}, MATERIAL=STEEL, OFFSET={}\n{}",
            set_name(&part.name),
            part.offset,
            part.thickness
        );
    }
    out.push_str("*BOUNDARY\n");
    for s in &model.supports {
        for d in &s.dofs {
            let _ = writeln!(out, "{}, {d}, {d}, 0.0", s.node + 1);
        }
    }
    let _ = writeln!(out, "** supports: {}", model.support_note);
    out.push_str("*STEP\n*STATIC\n*DLOAD\n");
    for (e, p) in model.pressure.iter().enumerate() {
        if *p != 0.0 {
            let _ = writeln!(out, "{}, P, {:.9e}", e + 1, p);
        }
    }
    if !model.loads.is_empty() {
        out.push_str("*CLOAD\n");
        for (n, f) in &model.loads {
            for (d, v) in [(1, f.x), (2, f.y), (3, f.z)] {
                if v != 0.0 {
                    let _ = writeln!(out, "{}, {d}, {v:.9e}", n + 1);
                }
            }
        }
    }
    if model.gravity {
        out.push_str("*DLOAD\nEALL, GRAV, 9806.65, 0., 0., -1.\n");
    }
    out.push_str("*NODE FILE\nU, RF\n*EL FILE\nS\n*END STEP\n");
    out
}
