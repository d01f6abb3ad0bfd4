//! STEP (ISO 10303-21) writer, application protocol AP214
//! (`AUTOMOTIVE_DESIGN`): the schema AutoCAD Plant 3D, AVEVA E3D, FreeCAD and
//! OpenCASCADE all read, and which holds everything written here (product
//! structure, rational B-spline faces with pcurves, shells, manifold solids,
//! named axis placements); AP242 adds nothing this file uses.
//!
//! Layout: a header block (contexts, units, the uncertainty — the exchange
//! tolerance, see [`write_step`](super::write_step) — and the identity placement) with ids below
//! [`LOCAL_BASE`]; one block per vessel — its product, its surfaces,
//! edges with pcurves, faces, shells and nozzle placements, in the vessel's own
//! frame — written with ids counted from [`LOCAL_BASE`] and moved to its place
//! in the file by adding an offset to every local id ([`rebase`]); last the
//! plant assembly, placing each vessel with its frame
//! (`NEXT_ASSEMBLY_USAGE_OCCURRENCE` and an `ITEM_DEFINED_TRANSFORMATION`, as
//! OpenCASCADE writes assemblies). A vessel's block depends on its own
//! parameters only, so an export after an edit can take the unchanged vessels'
//! blocks as they were ([`StepBlocks`]).
//!
//! Faces are named `tag/id/patch` (`V-101/S1/shell`), vessel products by tag,
//! the plant product `plant`; each nozzle's connection point is an
//! `AXIS2_PLACEMENT_3D` named `tag/mark/connection <size rating facing>` at its
//! gasket face centre with its axis outward.

use std::fmt::Write as _;

use glam::{DVec2, DVec3};

use super::brep::{EdgeCurve, Face, OrientedEdge, VesselBrep};
use crate::nurbs::{NurbsCurve, NurbsSurface};

/// First id of a vessel block's own entities; smaller ids are the header
/// block's.
pub const LOCAL_BASE: usize = 100;

/// Header block ids.
pub(super) const APPLICATION_CONTEXT: usize = 1;
pub(super) const PRODUCT_CONTEXT: usize = 3;
pub(super) const DEFINITION_CONTEXT: usize = 4;
pub(super) const CONTEXT_3D: usize = 9;
pub(super) const CONTEXT_2D: usize = 10;
pub(super) const IDENTITY: usize = 14;

/// Ids of a vessel block that the plant assembly refers to (local numbering).
pub(super) const VESSEL_DEFINITION: usize = LOCAL_BASE;
pub(super) const VESSEL_REPRESENTATION: usize = LOCAL_BASE + 1;
const VESSEL_IDENTITY: usize = LOCAL_BASE + 2;

/// One vessel's block of entities, numbered locally from [`LOCAL_BASE`].
#[derive(Clone, Debug, PartialEq)]
pub struct StepBlock {
    /// The entity lines.
    pub text: String,
    /// One past the largest local id.
    pub next: usize,
    /// The vessel's exchange tolerance, mm ([`VesselBrep::tolerance`]).
    pub tolerance: f64,
}

/// Appends `x` as a STEP real (a decimal point always, `E` for the exponent).
pub(super) fn real(out: &mut String, x: f64) {
    let x = if x == 0.0 { 0.0 } else { x };
    let mut buffer = ryu::Buffer::new();
    let text = buffer.format_finite(x);
    match text.find('e') {
        Some(e) => {
            let (mantissa, exponent) = text.split_at(e);
            out.push_str(mantissa);
            if !mantissa.contains('.') {
                out.push_str(".0");
            }
            out.push('E');
            out.push_str(&exponent[1..]);
        }
        None => out.push_str(text),
    }
}

/// Appends `n` in decimal (what `write!(out, "{n}")` writes, without the
/// formatting machinery: the writer appends some 40 000 ids per vessel).
pub(super) fn decimal(out: &mut String, mut n: usize) {
    let mut digits = [0u8; 20];
    let mut at = digits.len();
    loop {
        at -= 1;
        digits[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    // ASCII digits only.
    out.push_str(std::str::from_utf8(&digits[at..]).unwrap_or_default());
}

/// Appends `#n`.
fn reference(out: &mut String, n: usize) {
    out.push('#');
    decimal(out, n);
}

/// Appends a STEP string literal (quotes doubled, non-ASCII as `\X2\` hex).
pub(super) fn string(out: &mut String, s: &str) {
    out.push('\'');
    for c in s.chars() {
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            ' '..='~' => out.push(c),
            _ => {
                let mut units = [0u16; 2];
                out.push_str("\\X2\\");
                for u in c.encode_utf16(&mut units) {
                    let _ = write!(out, "{u:04X}");
                }
                out.push_str("\\X0\\");
            }
        }
    }
    out.push('\'');
}

/// Writes entity lines with increasing ids.
pub(super) struct Writer {
    pub(super) out: String,
    pub(super) next: usize,
}

impl Writer {
    /// Starts the next entity: `#id=`; returns its id.
    pub(super) fn begin(&mut self) -> usize {
        let id = self.next;
        self.next += 1;
        reference(&mut self.out, id);
        self.out.push('=');
        id
    }

    /// Ends an entity line.
    pub(super) fn end(&mut self) {
        self.out.push_str(";\n");
    }

    /// A list `(#a,#b,…)`.
    pub(super) fn refs(&mut self, ids: &[usize]) {
        self.out.push('(');
        for (i, id) in ids.iter().enumerate() {
            if i > 0 {
                self.out.push(',');
            }
            reference(&mut self.out, *id);
        }
        self.out.push(')');
    }

    /// A list of reals `(a,b,…)`.
    fn reals(&mut self, values: impl IntoIterator<Item = f64>) {
        self.out.push('(');
        for (i, x) in values.into_iter().enumerate() {
            if i > 0 {
                self.out.push(',');
            }
            real(&mut self.out, x);
        }
        self.out.push(')');
    }

    /// A list of integers.
    fn integers(&mut self, values: &[usize]) {
        self.out.push('(');
        for (i, x) in values.iter().enumerate() {
            if i > 0 {
                self.out.push(',');
            }
            decimal(&mut self.out, *x);
        }
        self.out.push(')');
    }

    fn point3(&mut self, p: DVec3) -> usize {
        let id = self.begin();
        self.out.push_str("CARTESIAN_POINT('',");
        self.reals([p.x, p.y, p.z]);
        self.out.push(')');
        self.end();
        id
    }

    fn point2(&mut self, p: DVec2) -> usize {
        let id = self.begin();
        self.out.push_str("CARTESIAN_POINT('',");
        self.reals([p.x, p.y]);
        self.out.push(')');
        self.end();
        id
    }

    fn direction(&mut self, d: DVec3) -> usize {
        let id = self.begin();
        self.out.push_str("DIRECTION('',");
        self.reals([d.x, d.y, d.z]);
        self.out.push(')');
        self.end();
        id
    }

    /// `AXIS2_PLACEMENT_3D(name, origin, axis, ref_direction)`.
    pub(super) fn placement(
        &mut self,
        name: &str,
        origin: DVec3,
        axis: DVec3,
        across: DVec3,
    ) -> usize {
        let (o, z, x) = (
            self.point3(origin),
            self.direction(axis),
            self.direction(across),
        );
        let id = self.begin();
        self.out.push_str("AXIS2_PLACEMENT_3D(");
        string(&mut self.out, name);
        let _ = write!(self.out, ",#{o},#{z},#{x})");
        self.end();
        id
    }

    /// Distinct knots and their multiplicities.
    fn knots(&mut self, knots: &[f64]) {
        let mut values: Vec<f64> = Vec::new();
        let mut counts: Vec<usize> = Vec::new();
        for &k in knots {
            if values.last() == Some(&k) {
                *counts.last_mut().expect("a count per value") += 1;
            } else {
                values.push(k);
                counts.push(1);
            }
        }
        self.integers(&counts);
        self.out.push(',');
        self.reals(values);
    }

    /// A B-spline curve through 3D control points (rational as the complex
    /// instance).
    fn curve3(&mut self, curve: &NurbsCurve) -> usize {
        let points: Vec<usize> = curve
            .control_points()
            .into_iter()
            .map(|p| self.point3(p))
            .collect();
        let id = self.begin();
        let degree = curve.degree();
        if curve.is_polynomial() {
            let _ = write!(self.out, "B_SPLINE_CURVE_WITH_KNOTS('',{degree},");
            self.refs(&points);
            self.out.push_str(",.UNSPECIFIED.,.U.,.F.,");
            self.knots(curve.knots().as_slice());
            self.out.push_str(",.UNSPECIFIED.)");
        } else {
            let _ = write!(self.out, "(BOUNDED_CURVE()B_SPLINE_CURVE({degree},");
            self.refs(&points);
            self.out
                .push_str(",.UNSPECIFIED.,.U.,.F.)B_SPLINE_CURVE_WITH_KNOTS(");
            self.knots(curve.knots().as_slice());
            self.out.push_str(
                ",.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE(",
            );
            self.reals(curve.weights());
            self.out.push_str(")REPRESENTATION_ITEM(''))");
        }
        self.end();
        id
    }

    /// A polynomial B-spline in (u, v) of `degree` through the 2D points
    /// `points` over the whole knot vector `knots`.
    fn spline2(&mut self, degree: usize, knots: &[f64], points: &[usize]) -> usize {
        let id = self.begin();
        let form = if degree == 1 {
            ".POLYLINE_FORM."
        } else {
            ".UNSPECIFIED."
        };
        let _ = write!(self.out, "B_SPLINE_CURVE_WITH_KNOTS('',{degree},");
        self.refs(points);
        let _ = write!(self.out, ",{form},.U.,.F.,");
        self.knots(knots);
        self.out.push_str(",.UNSPECIFIED.)");
        self.end();
        id
    }

    /// A surface (rational as the complex instance).
    fn surface(&mut self, surface: &NurbsSurface) -> usize {
        let (nu, nv) = (surface.u_count(), surface.v_count());
        let homogeneous = surface.homogeneous_points();
        let points: Vec<usize> = homogeneous
            .iter()
            .map(|h| self.point3(h.truncate() / h.w))
            .collect();
        let rational = homogeneous.iter().any(|h| h.w != 1.0);
        let id = self.begin();
        let (du, dv) = (surface.u_degree(), surface.v_degree());
        let net = |w: &mut Writer| {
            w.out.push('(');
            for i in 0..nu {
                if i > 0 {
                    w.out.push(',');
                }
                w.refs(&points[i * nv..(i + 1) * nv]);
            }
            w.out.push(')');
        };
        let knots = |w: &mut Writer| {
            let (mut cu, mut cv) = (Vec::new(), Vec::new());
            let (mut ku, mut kv) = (Vec::new(), Vec::new());
            for (knots, counts, values) in [
                (surface.u_knots().as_slice(), &mut cu, &mut ku),
                (surface.v_knots().as_slice(), &mut cv, &mut kv),
            ] {
                for &k in knots {
                    if values.last() == Some(&k) {
                        *counts.last_mut().expect("a count per value") += 1;
                    } else {
                        values.push(k);
                        counts.push(1);
                    }
                }
            }
            w.integers(&cu);
            w.out.push(',');
            w.integers(&cv);
            w.out.push(',');
            w.reals(ku);
            w.out.push(',');
            w.reals(kv);
        };
        if rational {
            let _ = write!(self.out, "(BOUNDED_SURFACE()B_SPLINE_SURFACE({du},{dv},");
            net(self);
            self.out
                .push_str(",.UNSPECIFIED.,.F.,.F.,.F.)B_SPLINE_SURFACE_WITH_KNOTS(");
            knots(self);
            self.out.push_str(
                ",.UNSPECIFIED.)GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_SURFACE((",
            );
            for i in 0..nu {
                if i > 0 {
                    self.out.push(',');
                }
                self.reals(homogeneous[i * nv..(i + 1) * nv].iter().map(|h| h.w));
            }
            self.out.push_str("))REPRESENTATION_ITEM('')SURFACE())");
        } else {
            let _ = write!(self.out, "B_SPLINE_SURFACE_WITH_KNOTS('',{du},{dv},");
            net(self);
            self.out.push_str(",.UNSPECIFIED.,.F.,.F.,.F.,");
            knots(self);
            self.out.push_str(",.UNSPECIFIED.)");
        }
        self.end();
        id
    }
}

/// Writes one vessel's block: product, geometry, topology, placements.
pub fn vessel_block(brep: &VesselBrep, solids: bool) -> StepBlock {
    let mut w = Writer {
        out: String::with_capacity(1 << 16),
        next: LOCAL_BASE,
    };
    // The ids the plant assembly refers to come first.
    let product = LOCAL_BASE + 3;
    let formation = product + 1;
    let definition_shape = formation + 1;
    // The representation and the identity placement are written last, under
    // their reserved ids.
    let _ = writeln!(
        w.out,
        "#{VESSEL_DEFINITION}=PRODUCT_DEFINITION('design','',#{formation},#{DEFINITION_CONTEXT});"
    );
    w.next = product;
    w.begin();
    w.out.push_str("PRODUCT(");
    string(&mut w.out, &brep.tag);
    w.out.push(',');
    string(&mut w.out, &brep.tag);
    let _ = write!(w.out, ",'vessel',(#{PRODUCT_CONTEXT}))");
    w.end();
    w.begin();
    let _ = write!(w.out, "PRODUCT_DEFINITION_FORMATION('','',#{product})");
    w.end();
    w.begin();
    let _ = write!(
        w.out,
        "PRODUCT_DEFINITION_SHAPE('','',#{VESSEL_DEFINITION})"
    );
    w.end();
    w.begin();
    let _ = write!(
        w.out,
        "SHAPE_DEFINITION_REPRESENTATION(#{definition_shape},#{VESSEL_REPRESENTATION})"
    );
    w.end();

    let surfaces: Vec<usize> = brep.faces.iter().map(|f| w.surface(&f.surface)).collect();
    let vertices: Vec<usize> = brep
        .vertices
        .iter()
        .map(|&p| {
            let point = w.point3(p);
            let id = w.begin();
            let _ = write!(w.out, "VERTEX_POINT('',#{point})");
            w.end();
            id
        })
        .collect();

    // Every use of every edge: (face, use), for its pcurves.
    let mut uses: Vec<Vec<(usize, &OrientedEdge)>> = vec![Vec::new(); brep.edges.len()];
    for (f, face) in brep.faces.iter().enumerate() {
        for e in face_edges(face) {
            uses[e.edge].push((f, e));
        }
    }
    let edges: Vec<usize> = brep
        .edges
        .iter()
        .zip(&uses)
        .map(|(edge, uses)| {
            let curve = match &edge.curve {
                EdgeCurve::Nurbs(c) | EdgeCurve::Loop(c) => w.curve3(c),
            };
            let geometry = if (1..=2).contains(&uses.len()) {
                let pcurves: Vec<usize> = uses
                    .iter()
                    .map(|(f, e)| {
                        let points: Vec<usize> = e.pcurve.iter().map(|&p| w.point2(p)).collect();
                        let line = match &edge.curve {
                            EdgeCurve::Nurbs(c) => {
                                let (a, b) = c.domain();
                                w.spline2(1, &[a, a, b, b], &points)
                            }
                            EdgeCurve::Loop(c) => {
                                w.spline2(c.degree(), c.knots().as_slice(), &points)
                            }
                        };
                        let representation = w.begin();
                        let _ = write!(
                            w.out,
                            "DEFINITIONAL_REPRESENTATION('',(#{line}),#{CONTEXT_2D})"
                        );
                        w.end();
                        let id = w.begin();
                        let _ = write!(w.out, "PCURVE('',#{},#{representation})", surfaces[*f]);
                        w.end();
                        id
                    })
                    .collect();
                let seam = uses.len() == 2 && uses[0].0 == uses[1].0;
                let id = w.begin();
                w.out.push_str(if seam {
                    "SEAM_CURVE('',#"
                } else {
                    "SURFACE_CURVE('',#"
                });
                let _ = write!(w.out, "{curve},");
                w.refs(&pcurves);
                w.out.push_str(",.CURVE_3D.)");
                w.end();
                id
            } else {
                curve
            };
            let id = w.begin();
            let _ = write!(
                w.out,
                "EDGE_CURVE('',#{},#{},#{geometry},.T.)",
                vertices[edge.start], vertices[edge.end]
            );
            w.end();
            id
        })
        .collect();

    let faces: Vec<usize> = brep
        .faces
        .iter()
        .zip(&surfaces)
        .map(|(face, &surface)| {
            let mut bounds = Vec::with_capacity(1 + face.holes.len());
            for (k, lp) in std::iter::once(&face.outer).chain(&face.holes).enumerate() {
                let oriented: Vec<usize> = lp
                    .iter()
                    .map(|e| {
                        let id = w.begin();
                        let _ = write!(
                            w.out,
                            "ORIENTED_EDGE('',*,*,#{},{})",
                            edges[e.edge],
                            if e.forward { ".T." } else { ".F." }
                        );
                        w.end();
                        id
                    })
                    .collect();
                let loop_id = w.begin();
                w.out.push_str("EDGE_LOOP('',");
                w.refs(&oriented);
                w.out.push(')');
                w.end();
                let id = w.begin();
                let kind = if k == 0 {
                    "FACE_OUTER_BOUND"
                } else {
                    "FACE_BOUND"
                };
                let _ = write!(w.out, "{kind}('',#{loop_id},.T.)");
                w.end();
                bounds.push(id);
            }
            let id = w.begin();
            w.out.push_str("ADVANCED_FACE(");
            string(
                &mut w.out,
                &format!("{}/{}/{}", brep.tag, brep.nodes[face.node], face.patch),
            );
            w.out.push(',');
            w.refs(&bounds);
            let _ = write!(w.out, ",#{surface},.T.)");
            w.end();
            id
        })
        .collect();

    // Closed shells become solids when asked; the others go in one surface
    // model.
    let mut solid_items = Vec::new();
    let mut open_shells = Vec::new();
    for shell in &brep.shells {
        let ids: Vec<usize> = shell.faces.iter().map(|&f| faces[f]).collect();
        let id = w.begin();
        w.out.push_str(if shell.closed {
            "CLOSED_SHELL("
        } else {
            "OPEN_SHELL("
        });
        string(&mut w.out, &brep.tag);
        w.out.push(',');
        w.refs(&ids);
        w.out.push(')');
        w.end();
        if solids && shell.closed {
            let solid = w.begin();
            w.out.push_str("MANIFOLD_SOLID_BREP(");
            string(&mut w.out, &format!("{} displacement", brep.tag));
            let _ = write!(w.out, ",#{id})");
            w.end();
            solid_items.push(solid);
        } else {
            open_shells.push(id);
        }
    }
    let mut items = solid_items;
    if !open_shells.is_empty() {
        let model = w.begin();
        w.out.push_str("SHELL_BASED_SURFACE_MODEL(");
        string(&mut w.out, &brep.tag);
        w.out.push(',');
        w.refs(&open_shells);
        w.out.push(')');
        w.end();
        items.push(model);
    }

    // The identity placement under its reserved id, then the connection points.
    let (o, z, x) = (
        w.point3(DVec3::ZERO),
        w.direction(DVec3::Z),
        w.direction(DVec3::X),
    );
    let _ = writeln!(
        w.out,
        "#{VESSEL_IDENTITY}=AXIS2_PLACEMENT_3D('',#{o},#{z},#{x});"
    );
    items.push(VESSEL_IDENTITY);
    for port in &brep.ports {
        let name = format!("{}/{}/connection {}", brep.tag, port.mark, port.description);
        items.push(w.placement(&name, port.origin, port.axis, port.across));
    }
    let _ = write!(
        w.out,
        "#{VESSEL_REPRESENTATION}={}(",
        if solids {
            "SHAPE_REPRESENTATION"
        } else {
            "MANIFOLD_SURFACE_SHAPE_REPRESENTATION"
        }
    );
    string(&mut w.out, &brep.tag);
    w.out.push(',');
    w.refs(&items);
    let _ = write!(w.out, ",#{CONTEXT_3D})");
    w.end();
    StepBlock {
        text: w.out,
        next: w.next,
        tolerance: brep.tolerance,
    }
}

/// A face's edge uses, outer loop first.
fn face_edges(face: &Face) -> impl Iterator<Item = &OrientedEdge> {
    face.outer.iter().chain(face.holes.iter().flatten())
}

/// Appends `block` with every local id (≥ [`LOCAL_BASE`]) moved by `offset`.
/// Ids inside string literals are left alone.
pub fn rebase(out: &mut String, block: &str, offset: usize) {
    if offset == 0 {
        out.push_str(block);
        return;
    }
    let bytes = block.as_bytes();
    let mut copied = 0;
    let mut quoted = false;
    // Only quotes and `#` matter; the digits after a `#` are neither.
    for i in memchr::memchr2_iter(b'#', b'\'', bytes) {
        if bytes[i] == b'\'' {
            quoted = !quoted;
            continue;
        }
        if quoted {
            continue;
        }
        let start = i + 1;
        let mut end = start;
        let mut id = Some(0usize);
        while end < bytes.len() && bytes[end].is_ascii_digit() {
            id = id
                .and_then(|n| n.checked_mul(10))
                .and_then(|n| n.checked_add(usize::from(bytes[end] - b'0')));
            end += 1;
        }
        let moved = id
            .filter(|&n| n >= LOCAL_BASE)
            .and_then(|n| n.checked_add(offset));
        if let (true, Some(moved)) = (end > start, moved) {
            out.push_str(&block[copied..start]);
            decimal(out, moved);
            copied = end;
        }
    }
    out.push_str(&block[copied..]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rebase_moves_local_ids_outside_strings_only() {
        let block = "#100=PRODUCT('V-1 #101 it''s #102','',(#3));\n#101=X(#100,#14,#99,#);\n#1000=Y('#5',#1000);";
        let mut out = String::new();
        rebase(&mut out, block, 7);
        assert_eq!(
            out,
            "#107=PRODUCT('V-1 #101 it''s #102','',(#3));\n#108=X(#107,#14,#99,#);\n#1007=Y('#5',#1007);"
        );
        let mut same = String::new();
        rebase(&mut same, block, 0);
        assert_eq!(same, block);
    }
}
