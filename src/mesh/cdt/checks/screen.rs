//! The fast check of a structured mesh: which of its triangles are within the
//! chordal tolerance, measured exactly as refinement measures them, but with the
//! surface evaluated a row at a time.
//!
//! Refinement's measure (`refine::assess`) probes each triangle at its parametric
//! centroid and at the midpoint of every edge that is not a loop segment: the
//! distance from S at those parameters to the triangle's plane, and the closed-form
//! distance of the 3D probe point to the patch's analytic surface (here skipped
//! when |P − S| is already within the tolerance: S lies on that surface, so
//! |P − S| bounds the distance from above and the verdict is the same; it spares
//! the Newton steps of a spheroid), then, for a triangle near the limit or on a
//! loop, at the peak of its cubic model (`peak`); on a plane, cylinder or sphere
//! the closed-form bound (`certify`) decides without probes. Pointwise, that
//! is four independent NURBS evaluations per triangle, the bulk of the mesher's
//! time. In a structured mesh (`rings`) the probes of one strip between two rows
//! share a handful of v values — the rows' own for edges along them, the middle
//! for the diagonals, the thirds for the centroids — so here each strip's probes
//! are grouped by their exact v and evaluated along one
//! [`SurfaceRow`](crate::nurbs::SurfaceRow) per group (the v half of the work once,
//! then a short contraction per probe). On a surface swept along Z (a course) one
//! row at v0 serves every probe, its axial coordinate read off v: the same surface
//! points up to rounding, with no grouping. Sits between `rings` (which builds the
//! mesh) and `mend` (which re-triangulates around the triangles found outside the
//! limits, and screens its new triangles here again).

use std::ops::Range;

use glam::{DVec2, DVec3};

use super::certify::Bound;
use super::measure::{edge_probe_uv, edge_uv_at, end_normal};
use super::peak::{Cubic, PEAK_GATE, THIRDS, point_at, uv_at};
use crate::mesh::cdt::patch::PatchInfo;
use rustc_hash::FxHashMap;

use crate::mesh::cdt::trimesh::TriMesh;
use crate::mesh::{Extrusion, TessellationOptions};
use crate::nurbs::SurfaceRow;
use crate::parts::Analytic;

/// One probe: the slot of the triangle it belongs to (in the list screened), the
/// 3D point on the triangle and the parameters where the surface is evaluated.
struct Probe {
    triangle: u32,
    /// The slot of the other triangle sharing the probed edge, when it was
    /// screened right after (`u32::MAX` for none).
    other: u32,
    /// Which of the triangle's edges is probed, and of the other's ([`CENTROID`]
    /// for the centroid).
    edges: [u8; 2],
    /// Index of its v in [`Groups`].
    group: u32,
    point: DVec3,
    uv: DVec2,
}

/// The screen of one patch: the patch, its analytic surface and the limits.
pub(in crate::mesh::cdt) struct Screen<'a> {
    info: &'a PatchInfo<'a>,
    analytic: Analytic,
    /// The closed-form bound of a plane or cylinder (`certify`).
    bound: Option<Bound>,
    limits: Limits,
    /// Whether the surface is swept straight along Z (a course): see [`Swept`].
    swept: Option<Extrusion>,
}

/// A surface swept straight along Z (a course, `mesh::axial`): S(u, v) is the
/// v0 row's point at u moved to the axial coordinate of v, so one row evaluator
/// serves the probes at every v, with no grouping.
struct Swept<'a> {
    row: SurfaceRow<'a>,
    extrusion: Extrusion,
}

impl Swept<'_> {
    fn point(&self, u: f64, v: f64) -> DVec3 {
        let p = self.row.point(u);
        DVec3::new(p.x, p.y, self.extrusion.z_at(v))
    }
}

impl<'a> Screen<'a> {
    /// The screen of `info`'s patch against `options`; `None` when the patch has
    /// no analytic surface: then every triangle is measured in full.
    pub fn new(info: &'a PatchInfo<'a>, options: &TessellationOptions) -> Option<Self> {
        let analytic = info.analytic?;
        let swept = info.swept;
        Some(Self {
            info,
            analytic,
            bound: Bound::of(&analytic),
            swept,
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

    /// This screen with every triangle probed (no closed-form bound): the
    /// reference the bound must agree with.
    #[cfg(test)]
    pub fn probes_only(self) -> Self {
        Self {
            bound: None,
            ..self
        }
    }

    /// Whether the surface is swept straight along Z (a course): then every
    /// probe goes through one row evaluator, so a triangle's verdict depends
    /// on it alone, not on the others screened with it.
    pub fn is_swept(&self) -> bool {
        self.swept.is_some()
    }

    /// The chordal tolerance screened against, mm.
    pub fn tolerance(&self) -> f64 {
        self.limits.tolerance
    }

    /// [`strip`](Self::strip) of any triangles of `mesh`, in the order given (best
    /// when they share few v values).
    pub fn triangles(&self, mesh: &TriMesh, triangles: &[u32]) -> Vec<bool> {
        screen_triangles(
            self.info,
            &self.analytic,
            self.bound.as_ref(),
            self.swept.map(|extrusion| Swept {
                row: self.info.surface.row(self.info.surface.domain().1.0),
                extrusion,
            }),
            mesh,
            triangles,
            &self.limits,
        )
    }
}

/// The distinct v values of a screen's probes, by their exact bits: a few per
/// strip of a structured mesh (searched in order), many after mending (then
/// hashed).
#[derive(Default)]
struct Groups {
    values: Vec<f64>,
    hashed: FxHashMap<u64, u32>,
}

impl Groups {
    /// Groups searched in order before the hash map takes over.
    const LINEAR: usize = 16;

    /// The index of the group of `v`, added if new.
    fn index(&mut self, v: f64) -> u32 {
        let bits = v.to_bits();
        if self.values.len() <= Self::LINEAR {
            if let Some(g) = self.values.iter().position(|x| x.to_bits() == bits) {
                return g as u32;
            }
            if self.values.len() == Self::LINEAR {
                self.hashed = (0..self.values.len() as u32)
                    .map(|g| (self.values[g as usize].to_bits(), g))
                    .collect();
            }
        } else if let Some(&g) = self.hashed.get(&bits) {
            return g;
        }
        let g = self.values.len() as u32;
        self.values.push(v);
        if self.values.len() > Self::LINEAR {
            self.hashed.insert(bits, g);
        }
        g
    }
}

/// [`Probe::edges`] of a centroid probe.
const CENTROID: u8 = 3;

/// Probes of one v beyond which they are evaluated along a row.
const ROW_WORTH: usize = 2;

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
    analytic: &Analytic,
    bound: Option<&Bound>,
    swept: Option<Swept>,
    mesh: &TriMesh,
    triangles: &[u32],
    limits: &Limits,
) -> Vec<bool> {
    let tolerance = limits.tolerance;
    let count = triangles.len();
    // The plane of each triangle, or None when the full measure must decide.
    let mut planes: Vec<Option<(DVec3, DVec3)>> = Vec::with_capacity(count);
    let mut within = vec![true; count];
    let mut probes: Vec<Probe> = Vec::with_capacity(4 * count);
    let mut groups = Groups::default();
    let add = |probes: &mut Vec<Probe>, probe: Probe, groups: &mut Groups| {
        // A swept surface needs no groups: every probe goes through one row.
        let group = if swept.is_some() {
            0
        } else {
            groups.index(probe.uv.y)
        };
        probes.push(Probe { group, ..probe });
        (probes.len() - 1) as u32
    };
    // The edge probes of the triangle screened just before, by directed edge: a
    // strip's consecutive triangles share a diagonal, probed once for both.
    let mut previous: [(u32, u32, u32); 3] = [(u32::MAX, u32::MAX, u32::MAX); 3];
    for (slot, &t) in triangles.iter().enumerate() {
        let last = std::mem::replace(&mut previous, [(u32::MAX, u32::MAX, u32::MAX); 3]);
        let tri = mesh.tris[t as usize];
        let v = tri.map(|k| &mesh.verts[k as usize]);
        let p = v.map(|x| x.point);
        let weld = info.weld_tolerance * info.weld_tolerance;
        if (0..3).any(|i| (p[i] - p[(i + 1) % 3]).length_squared() <= weld) {
            // Collapsed: dropped on output, never refined.
            planes.push(None);
            continue;
        }
        let normal = (p[1] - p[0]).cross(p[2] - p[0]);
        // A pole vertex's normal is the limit along its own meridian, inside its
        // fan triangle's sector: the one the full measure takes there.
        let turned = v.iter().any(|x| x.normal.dot(normal) <= 0.0);
        let area = normal.length();
        if area.is_nan() || area <= 0.0 || turned {
            within[slot] = false;
            planes.push(None);
            continue;
        }
        // The closed form decides: it is the largest distance over the whole
        // triangle. Within, no probes (the limits below still apply).
        let certified = bound.is_some_and(|b| {
            if b.deviation(p) > tolerance {
                within[slot] = false;
            }
            true
        });
        planes.push((!certified).then_some((p[0], normal / area)));
        // The vertices' own parameters: a pole vertex of the structured path
        // stands under the middle of its ring segment, where the full measure
        // puts it too.
        let centroid = (v[0].uv + v[1].uv + v[2].uv) / 3.0;
        if !certified {
            add(
                &mut probes,
                Probe {
                    triangle: slot as u32,
                    other: u32::MAX,
                    edges: [CENTROID; 2],
                    group: 0,
                    point: (p[0] + p[1] + p[2]) / 3.0,
                    uv: centroid,
                },
                &mut groups,
            );
        }
        for i in 0..3 {
            if mesh.fixed[t as usize][i] {
                continue;
            }
            let (x, y) = (v[i], v[(i + 1) % 3]);
            // Towards a pole the normal that counts is the limit along the
            // other end's meridian (as the full measure takes it).
            // (No length limit by default: not even the length is worked out.)
            if end_normal(info, x, y.uv).dot(end_normal(info, y, x.uv)) < limits.min_cos
                || (limits.max_edge.is_finite()
                    && (x.point - y.point).length_squared() > limits.max_edge * limits.max_edge)
            {
                within[slot] = false;
            }
            if certified {
                continue;
            }
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            if let Some(&(_, _, k)) = last.iter().find(|e| e.0 == b && e.1 == a) {
                probes[k as usize].other = slot as u32;
                probes[k as usize].edges[1] = i as u8;
                continue;
            }
            let k = add(
                &mut probes,
                Probe {
                    triangle: slot as u32,
                    other: u32::MAX,
                    edges: [i as u8, CENTROID],
                    group: 0,
                    point: 0.5 * (x.point + y.point),
                    uv: edge_probe_uv(x, y),
                },
                &mut groups,
            );
            previous[i] = (a, b, k);
        }
    }
    let mut judged = Judged {
        planes: &planes,
        within: &mut within,
        probed: vec![0.0; count],
        centroids: vec![0.0; count],
    };
    let point = |u: f64, v: f64| match &swept {
        Some(swept) => swept.point(info.wrap_u(u), v),
        None => info.surface.point(info.wrap_u(u), v),
    };
    if swept.is_some() {
        for q in &probes {
            judged.judge(q, point(q.uv.x, q.uv.y), analytic, tolerance);
        }
        peaks(mesh, triangles, &point, analytic, tolerance, &mut judged);
        return within;
    }
    // Counting sort by group, then one row evaluator per group.
    let mut starts = vec![0usize; groups.values.len() + 1];
    for q in &probes {
        starts[q.group as usize + 1] += 1;
    }
    for g in 0..groups.values.len() {
        starts[g + 1] += starts[g];
    }
    let mut order = vec![0u32; probes.len()];
    let mut next = starts.clone();
    for (k, q) in probes.iter().enumerate() {
        order[next[q.group as usize]] = k as u32;
        next[q.group as usize] += 1;
    }
    for (g, &v) in groups.values.iter().enumerate() {
        let members = &order[starts[g]..starts[g + 1]];
        // A row evaluator pays the v half once for every control column: worth it
        // for a strip's shared v values, not for a lone probe (a cavity's).
        let row = (members.len() > ROW_WORTH).then(|| info.surface.row(v));
        for &k in members {
            let q = &probes[k as usize];
            let u = info.wrap_u(q.uv.x);
            let s = match &row {
                Some(row) => row.point(u),
                None => info.surface.point(u, v),
            };
            judged.judge(q, s, analytic, tolerance);
        }
    }
    peaks(mesh, triangles, &point, analytic, tolerance, &mut judged);
    within
}

/// What the probes found: per screened triangle, its plane (`None` when the
/// full measure decides or the closed form did), whether it is within so far,
/// the largest deviation its probes measured and the signed height of S over
/// its plane at its centroid.
struct Judged<'a> {
    planes: &'a [Option<(DVec3, DVec3)>],
    within: &'a mut [bool],
    probed: Vec<f64>,
    centroids: Vec<f64>,
}

/// Probes every triangle still within whose plain probes passed [`PEAK_GATE`]
/// of the tolerance, or that has a loop segment (not probed), at the peak of
/// its cubic model (see `peak`): its edges' third points and then the peak are
/// evaluated. Few triangles come near the limit, so the surface is evaluated
/// point by point.
fn peaks(
    mesh: &TriMesh,
    triangles: &[u32],
    point: &impl Fn(f64, f64) -> DVec3,
    analytic: &Analytic,
    tolerance: f64,
    judged: &mut Judged,
) {
    for (slot, &t) in triangles.iter().enumerate() {
        let Some((origin, unit)) = judged.planes[slot] else {
            continue;
        };
        if !judged.within[slot] {
            continue;
        }
        let loop_edge = mesh.fixed[t as usize].iter().any(|&f| f);
        if !loop_edge && judged.probed[slot] <= PEAK_GATE * tolerance {
            continue;
        }
        let tri = mesh.tris[t as usize];
        let v = tri.map(|k| &mesh.verts[k as usize]);
        let thirds = [0, 1, 2].map(|i| {
            THIRDS.map(|s| {
                let at = edge_uv_at(v[i], v[(i + 1) % 3], s);
                (point(at.x, at.y) - origin).dot(unit)
            })
        });
        let (l, _) = Cubic::new(thirds, judged.centroids[slot]).peak();
        let at = uv_at(v.map(|x| x.uv), l);
        let q = Probe {
            triangle: slot as u32,
            other: u32::MAX,
            edges: [CENTROID; 2],
            group: 0,
            point: point_at(v.map(|x| x.point), l),
            uv: at,
        };
        judged.judge(&q, point(at.x, at.y), analytic, tolerance);
    }
}

impl Judged<'_> {
    /// Marks the triangles of probe `q` (one or two) outside when the surface
    /// point `s` at its parameters strays from their planes, or the probe's
    /// point on them from the analytic surface, by more than `tolerance`; keeps
    /// the heights of an edge probe.
    fn judge(&mut self, q: &Probe, s: DVec3, analytic: &Analytic, tolerance: f64) {
        // S lies on the analytic surface, so |P − S| bounds P's distance to it
        // from above: within the tolerance, the closed form (Newton steps on a
        // spheroid) cannot change the verdict and is skipped.
        let bound = (q.point - s).length();
        let distance = if bound <= tolerance {
            bound
        } else {
            analytic.distance(q.point)
        };
        for (slot, edge) in [q.triangle, q.other].into_iter().zip(q.edges) {
            let Some(&Some((origin, unit))) = self.planes.get(slot as usize) else {
                continue;
            };
            let height = (s - origin).dot(unit);
            if edge == CENTROID {
                self.centroids[slot as usize] = height;
            }
            let deviation = distance.max(height.abs());
            let probed = &mut self.probed[slot as usize];
            *probed = probed.max(deviation);
            // NaN counts as outside.
            if deviation.is_nan() || deviation > tolerance {
                self.within[slot as usize] = false;
            }
        }
    }
}
