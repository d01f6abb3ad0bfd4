//! ParaView's unstructured grid (`.vtu`, ASCII): points, cells (quadratic quads
//! 23, quads 9, quadratic triangles 22, triangles 5), the part index and shell
//! thickness per cell, and, after a run, displacement, von Mises stress and
//! membrane stress intensity per point.

use std::fmt::Write;

use super::results::{NodeResult, intensity};
use super::{ElementKind, FeMesh};

/// VTK's cell type number.
fn vtk_type(kind: ElementKind) -> u8 {
    match kind {
        ElementKind::Quad4 => 9,
        ElementKind::Quad8 => 23,
        ElementKind::Tri3 => 5,
        ElementKind::Tri6 => 22,
    }
}

/// The `.vtu` text of `mesh`, with `results` (one per node) when given.
pub fn to_vtu(mesh: &FeMesh, results: Option<&[NodeResult]>) -> String {
    let mut out = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n",
    );
    let _ = writeln!(
        out,
        "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.nodes.len(),
        mesh.elements.len()
    );
    out.push_str(
        "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
    );
    for p in &mesh.nodes {
        let _ = writeln!(out, "{} {} {}", p.x, p.y, p.z);
    }
    out.push_str("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for e in &mesh.elements {
        let nodes: Vec<String> = e.nodes.iter().map(|n| n.to_string()).collect();
        let _ = writeln!(out, "{}", nodes.join(" "));
    }
    out.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    let mut offset = 0;
    for e in &mesh.elements {
        offset += e.nodes.len();
        let _ = writeln!(out, "{offset}");
    }
    out.push_str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for e in &mesh.elements {
        let _ = writeln!(out, "{}", vtk_type(e.kind));
    }
    out.push_str("</DataArray>\n</Cells>\n<CellData Scalars=\"part\">\n<DataArray type=\"Int32\" Name=\"part\" format=\"ascii\">\n");
    for e in &mesh.elements {
        let _ = writeln!(out, "{}", e.part);
    }
    out.push_str(
        "</DataArray>\n<DataArray type=\"Float64\" Name=\"thickness\" format=\"ascii\">\n",
    );
    for e in &mesh.elements {
        let _ = writeln!(out, "{}", mesh.parts[e.part].thickness);
    }
    out.push_str("</DataArray>\n</CellData>\n");
    if let Some(results) = results {
        out.push_str("<PointData Scalars=\"von_mises\" Vectors=\"displacement\">\n<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"ascii\">\n");
        for r in results {
            let u = r.displacement;
            let _ = writeln!(out, "{} {} {}", u.x, u.y, u.z);
        }
        out.push_str(
            "</DataArray>\n<DataArray type=\"Float64\" Name=\"von_mises\" format=\"ascii\">\n",
        );
        for r in results {
            let _ = writeln!(out, "{}", r.von_mises);
        }
        out.push_str("</DataArray>\n<DataArray type=\"Float64\" Name=\"membrane_intensity\" format=\"ascii\">\n");
        for r in results {
            let _ = writeln!(out, "{}", intensity(r.membrane));
        }
        out.push_str("</DataArray>\n</PointData>\n");
    }
    out.push_str("</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    out
}
