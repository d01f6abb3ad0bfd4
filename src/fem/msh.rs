//! Gmsh's mesh format 4.1 (ASCII): one physical surface per part (named by the
//! part, `V-101/S1`), all nodes in one block, elements per part as 4-node (3)
//! or 8-node (16) quadrilaterals and 3-node (2) or 6-node (9) triangles; node
//! order as in Abaqus.

use std::fmt::Write;

use super::{ElementKind, FeMesh};

/// Gmsh's element type number.
fn gmsh_type(kind: ElementKind) -> u8 {
    match kind {
        ElementKind::Quad4 => 3,
        ElementKind::Quad8 => 16,
        ElementKind::Tri3 => 2,
        ElementKind::Tri6 => 9,
    }
}

/// The `.msh` text of `mesh`.
pub fn to_msh(mesh: &FeMesh) -> String {
    let mut out = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n");
    let _ = writeln!(out, "{}", mesh.parts.len());
    for (k, p) in mesh.parts.iter().enumerate() {
        let _ = writeln!(out, "2 {} \"{}\"", k + 1, p.name);
    }
    out.push_str("$EndPhysicalNames\n$Entities\n");
    let _ = writeln!(out, "0 0 {} 0", mesh.parts.len());
    for k in 0..mesh.parts.len() {
        let (lo, hi) = mesh
            .elements
            .iter()
            .filter(|e| e.part == k)
            .flat_map(|e| e.nodes.iter().map(|&n| mesh.nodes[n]))
            .fold(
                (
                    glam::DVec3::splat(f64::INFINITY),
                    glam::DVec3::splat(f64::NEG_INFINITY),
                ),
                |(lo, hi), p| (lo.min(p), hi.max(p)),
            );
        let _ = writeln!(
            out,
            "{} {} {} {} {} {} {} 1 {} 0",
            k + 1,
            lo.x,
            lo.y,
            lo.z,
            hi.x,
            hi.y,
            hi.z,
            k + 1
        );
    }
    out.push_str("$EndEntities\n$Nodes\n");
    let n = mesh.nodes.len();
    let _ = writeln!(out, "1 {n} 1 {n}\n2 1 0 {n}");
    for i in 0..n {
        let _ = writeln!(out, "{}", i + 1);
    }
    for p in &mesh.nodes {
        let _ = writeln!(out, "{} {} {}", p.x, p.y, p.z);
    }
    out.push_str("$EndNodes\n$Elements\n");
    let mut blocks = Vec::new();
    for k in 0..mesh.parts.len() {
        for kind in [
            ElementKind::Quad8,
            ElementKind::Tri6,
            ElementKind::Quad4,
            ElementKind::Tri3,
        ] {
            let els: Vec<usize> = (0..mesh.elements.len())
                .filter(|&e| mesh.elements[e].part == k && mesh.elements[e].kind == kind)
                .collect();
            if !els.is_empty() {
                blocks.push((k, kind, els));
            }
        }
    }
    let m = mesh.elements.len();
    let _ = writeln!(out, "{} {m} 1 {m}", blocks.len());
    for (k, kind, els) in blocks {
        let _ = writeln!(out, "2 {} {} {}", k + 1, gmsh_type(kind), els.len());
        for e in els {
            let nodes: Vec<String> = mesh.elements[e]
                .nodes
                .iter()
                .map(|n| (n + 1).to_string())
                .collect();
            let _ = writeln!(out, "{} {}", e + 1, nodes.join(" "));
        }
    }
    out.push_str("$EndElements\n");
    out
}
