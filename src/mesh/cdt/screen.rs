//! The fast check of a structured mesh: which of its triangles are within the
//! chordal tolerance, measured exactly as refinement measures them, but with the
//! surface evaluated a row at a time.
//!
//! Refinement's measure (`refine::assess`) probes each triangle at its parametric
//! centroid and at the midpoint of every edge that is not a loop segment: the
//! distance from S at those parameters to the triangle's plane, and the closed-form
//! distance of the 3D probe point to the patch's analytic surface. Pointwise, that
//! is four independent NURBS evaluations per triangle, the bulk of the mesher's
//! time. In a structured mesh (`rings`) the probes of one strip between two rows
//! share a handful of v values — the rows' own for edges along them, the middle
//! for the diagonals, the thirds for the centroids — so here each strip's probes
//! are grouped by their exact v and evaluated with one grid call per group
//! (the isocurve at that v once, then one curve point per probe). Sits between `rings` (which builds the mesh) and `refine` (which takes over
//! the triangles found outside the limits).

use std::ops::Range;

use glam::{DVec2, DVec3};

use super::flip::effective_uv;
use super::patch::PatchInfo;
use super::refine::edge_probe_uv;
use super::trimesh::TriMesh;
use crate::mesh::TessellationOptions;
use crate::nurbs::NurbsSurface;
use crate::parts::Analytic;

/// One probe: the slot of the triangle it belongs to (in the list screened), the 3D point on the triangle and the
/// parameters (u wrapped) where the surface is evaluated.
struct Probe {
    triangle: u32,
    point: DVec3,
    uv: DVec2,
}

/// The screen of one patch: the surface's rows as isocurves, the analytic surface
/// and the limits.
pub(super) struct Screen<'a> {
    info: &'a PatchInfo<'a>,
    /// The surface with u and v exchanged: its isocurves at fixed "u" are the rows
    /// of constant v.
    transposed: NurbsSurface,
    analytic: Analytic,
    limits: Limits,
}

impl<'a> Screen<'a> {
    /// The screen of `info`'s patch against `options`; `None` when the patch has
    /// no analytic surface: then every triangle is measured in full.
    pub fn new(info: &'a PatchInfo<'a>, options: &TessellationOptions) -> Option<Self> {
        let analytic = info.analytic?;
        Some(Self {
            info,
            transposed: info.surface.transposed(),
            analytic,
            limits: Limits {
                tolerance: options.tolerance,
                min_cos: options
                    .angle_tolerance
                    .map_or(-1.0, |a| a.to_radians().cos()),
                max_edge: options.max_edge_length.unwrap_or(f64::INFINITY),
            },
        })
    }

    /// For every triangle of `range` in `mesh` (the triangles of one strip between
    /// two rows), whether it is certainly within the tolerance. `false` means
    /// "measure it in full": outside the tolerance, an edge turning more than the
    /// angle limit or longer than the length limit (which the full measure may
    /// still allow next to a loop that does as much), collapsed, at a pole, or
    /// turned against the surface.
    pub fn strip(&self, mesh: &TriMesh, range: Range<u32>) -> Vec<bool> {
        let triangles: Vec<u32> = range.collect();
        self.triangles(mesh, &triangles)
    }

    /// [`strip`](Self::strip) of any triangles of `mesh`, in the order given (best
    /// when they share few v values).
    pub fn triangles(&self, mesh: &TriMesh, triangles: &[u32]) -> Vec<bool> {
        screen_triangles(
            self.info,
            &self.transposed,
            &self.analytic,
            mesh,
            triangles,
            &self.limits,
        )
    }
}

/// The limits a triangle is screened against.
struct Limits {
    /// Chordal tolerance, mm.
    tolerance: f64,
    /// Cosine of the largest angle between the normals at an edge's ends.
    min_cos: f64,
    /// Longest edge, mm.
    max_edge: f64,
}

/// The screen of `triangles`.
fn screen_triangles(
    info: &PatchInfo,
    transposed: &NurbsSurface,
    analytic: &Analytic,
    mesh: &TriMesh,
    triangles: &[u32],
    limits: &Limits,
) -> Vec<bool> {
    let tolerance = limits.tolerance;
    let count = triangles.len();
    // The plane of each triangle, or None when the full measure must decide.
    let mut planes: Vec<Option<(DVec3, DVec3)>> = Vec::with_capacity(count);
    let mut within = vec![true; count];
    // Probes grouped by the exact bits of their v.
    let mut groups: Vec<(u64, Vec<Probe>)> = Vec::new();
    let mut add = |probe: Probe| {
        let bits = probe.uv.y.to_bits();
        match groups.iter_mut().find(|(b, _)| *b == bits) {
            Some((_, list)) => list.push(probe),
            None => groups.push((bits, vec![probe])),
        }
    };
    for (slot, &t) in triangles.iter().enumerate() {
        let tri = mesh.tris[t as usize];
        let v = tri.map(|k| &mesh.verts[k as usize]);
        let p = v.map(|x| x.point);
        if (0..3).any(|i| (p[i] - p[(i + 1) % 3]).length() <= info.weld_tolerance) {
            // Collapsed: dropped on output, never refined.
            planes.push(None);
            continue;
        }
        let normal = (p[1] - p[0]).cross(p[2] - p[0]);
        let turned = v.iter().any(|x| x.pole || x.normal.dot(normal) <= 0.0);
        let area = normal.length();
        if area.is_nan() || area <= 0.0 || turned {
            within[slot] = false;
            planes.push(None);
            continue;
        }
        planes.push(Some((p[0], normal / area)));
        let eff = tri.map(|k| effective_uv(mesh, k, &tri));
        let centroid = (eff[0] + eff[1] + eff[2]) / 3.0;
        add(Probe {
            triangle: slot as u32,
            point: (p[0] + p[1] + p[2]) / 3.0,
            uv: centroid,
        });
        for i in 0..3 {
            if mesh.fixed[t as usize][i] {
                continue;
            }
            let (x, y) = (v[i], v[(i + 1) % 3]);
            if x.normal.dot(y.normal) < limits.min_cos
                || (x.point - y.point).length() > limits.max_edge
            {
                within[slot] = false;
            }
            add(Probe {
                triangle: slot as u32,
                point: 0.5 * (x.point + y.point),
                uv: edge_probe_uv(x, y),
            });
        }
    }
    for (bits, probes) in &groups {
        let row = transposed.isocurve_u(f64::from_bits(*bits));
        for q in probes {
            let k = q.triangle as usize;
            let Some((origin, unit)) = planes[k] else {
                continue;
            };
            let s = row.point(info.wrap_u(q.uv.x));
            let deviation = analytic.distance(q.point).max((s - origin).dot(unit).abs());
            // NaN counts as outside.
            if deviation.is_nan() || deviation > tolerance {
                within[k] = false;
            }
        }
    }
    within
}
