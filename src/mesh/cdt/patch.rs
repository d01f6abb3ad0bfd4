//! What the mesher needs to know about one surface, computed once per call: whether
//! it is closed in u (so loop u values wrap), which sides of its domain collapse to a
//! point (a head's pole, a cone's apex), its size (for welding), the scales of the
//! (u, v) chart handed to spade, and the sizing; and the evaluation of one mesh
//! vertex (exact point, exact normal with the pole limit, metric).

use glam::{DVec2, DVec3};

use super::CdtError;
use super::metric::{Metric, Sizing};
use crate::mesh::Extrusion;
use crate::nurbs::{NurbsSurface, SurfaceDerivatives};
use crate::parts::Analytic;

/// Relative distance below which control points count as coincident (a collapsed
/// side) and two output vertices are welded, times the patch size.
pub(super) const COINCIDENT: f64 = 1e-12;
/// Samples along a collapsed side averaged for the normal of its point.
const POLE_NORMAL_SAMPLES: usize = 16;
/// Samples per direction used to average |S_u| and |S_v| over the region.
const SCALE_SAMPLES: usize = 4;

/// The value `u` wrapped into the u-domain when `surface` is closed in u (its first
/// and last control columns coincide), `u0 + (u − u0) mod (u1 − u0)`; `u` itself
/// otherwise.
pub fn wrap_u(surface: &NurbsSurface, u: f64) -> f64 {
    let (closed, _) = closed_and_collapsed(surface, net_size(surface));
    wrap(surface, closed, u)
}

/// Whether `surface` is better meshed transposed: the mesher lays its seed rows
/// along u and wraps only u, so a surface whose collapsed sides are u-sides (a
/// pole at u = u0 or u1), or that is closed in v but not in u, is meshed with u and
/// v exchanged.
pub(super) fn wants_transpose(surface: &NurbsSurface) -> bool {
    let size = net_size(surface);
    let (closed_u, collapsed) = closed_and_collapsed(surface, size);
    let (closed_v, _) = closed_and_collapsed(&surface.transposed(), size);
    let u_poles = collapsed[0] || collapsed[1];
    let v_poles = collapsed[2] || collapsed[3];
    (u_poles && !v_poles) || (closed_v && !closed_u && !v_poles)
}

fn wrap(surface: &NurbsSurface, closed: bool, u: f64) -> f64 {
    let (u0, u1) = surface.u_knots().domain();
    if closed {
        let (offset, period) = (u - u0, u1 - u0);
        // The remainder of an offset already in [0, period) is the offset itself.
        if (0.0..period).contains(&offset) {
            u0 + offset
        } else {
            u0 + offset.rem_euclid(period)
        }
    } else {
        u
    }
}

/// Diagonal of the control net's bounding box (at least 1e-300).
fn net_size(surface: &NurbsSurface) -> f64 {
    let points = surface.control_points();
    let Some(&first) = points.first() else {
        return 1e-300;
    };
    let (lo, hi) = points
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    (hi - lo).length().max(1e-300)
}

/// Whether the surface is closed in u, and which sides collapse to a point:
/// `[u = u0, u = u1, v = v0, v = v1]`.
fn closed_and_collapsed(surface: &NurbsSurface, size: f64) -> (bool, [bool; 4]) {
    let tol = COINCIDENT * size;
    let (nu, nv) = (surface.u_count(), surface.v_count());
    let at = |i: usize, j: usize| {
        let p = surface.homogeneous_point_at(i, j);
        p.truncate() / p.w
    };
    let closed = (0..nv).all(|j| (at(0, j) - at(nu - 1, j)).length() <= tol);
    let sides = [
        coincide((0..nv).map(|j| at(0, j)), tol),
        coincide((0..nv).map(|j| at(nu - 1, j)), tol),
        coincide((0..nu).map(|i| at(i, 0)), tol),
        coincide((0..nu).map(|i| at(i, nv - 1)), tol),
    ];
    (closed, sides)
}

/// Whether all `points` lie within `tol` of the first.
fn coincide(mut points: impl Iterator<Item = DVec3>, tol: f64) -> bool {
    let Some(first) = points.next() else {
        return false;
    };
    points.all(|p| (p - first).length() <= tol)
}

/// Derivatives of the first order only (the second left NaN: a lazy vertex's
/// metric is filled later, from a full evaluation).
fn first_order(point: DVec3, du: DVec3, dv: DVec3) -> SurfaceDerivatives {
    SurfaceDerivatives {
        point,
        du,
        dv,
        duu: DVec3::NAN,
        duv: DVec3::NAN,
        dvv: DVec3::NAN,
    }
}

/// One vertex of the mesh being built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Vertex {
    /// Parameters as given (u not wrapped).
    pub uv: DVec2,
    /// S(u, v).
    pub point: DVec3,
    /// Unit normal, the limit at a pole.
    pub normal: DVec3,
    /// Size metric.
    pub metric: Metric,
    /// On a side that collapses to a point.
    pub pole: bool,
}

/// Facts about the surface being meshed.
#[derive(Clone, Debug)]
pub(super) struct PatchInfo<'a> {
    /// The surface.
    pub surface: &'a NurbsSurface,
    /// Closed in u: loop u values wrap.
    pub closed_u: bool,
    /// Collapsed sides `[u = u0, u = u1, v = v0, v = v1]`.
    pub collapsed: [bool; 4],
    /// Distance within which two vertices are one, mm.
    pub weld_tolerance: f64,
    /// Mean |S_u| and |S_v| over the region: mm per unit parameter of spade's chart.
    pub scale: DVec2,
    /// Sizes for seeding and flips.
    pub sizing: Sizing,
    /// The analytic surface the patch lies on: probes then measure the distance
    /// in closed form instead of inverting the NURBS (whose inversion, clamped
    /// to the domain, measured a point off a cone's end ring to the ring, not
    /// along the normal: up to 1 / cos of the slope more).
    pub analytic: Option<Analytic>,
    /// The extrusion the surface is when it is swept straight along Z (a
    /// course): one row evaluator then serves every v (loop vertices, screen
    /// probes, the lattice's row metrics).
    pub swept: Option<Extrusion>,
    /// Normal of the point each collapsed side maps to: the mean of the limit
    /// normals along the side (the limit itself at a smooth pole, the axis
    /// direction at a cone's apex, where the limit depends on the approach).
    pole_normals: [Option<DVec3>; 4],
}

impl<'a> PatchInfo<'a> {
    /// Facts for meshing the part of `surface` inside the parameter box `lo..hi`;
    /// `sizing` gets its cap from the box's extent.
    pub fn new(
        surface: &'a NurbsSurface,
        lo: DVec2,
        hi: DVec2,
        sizing: impl FnOnce(f64) -> Sizing,
    ) -> Self {
        let size = net_size(surface);
        let (closed_u, collapsed) = closed_and_collapsed(surface, size);
        let mut sum = DVec2::ZERO;
        let n = SCALE_SAMPLES;
        for i in 0..n {
            for j in 0..n {
                let t = DVec2::new(i as f64, j as f64) / (n - 1) as f64;
                let p = lo + (hi - lo) * t;
                let d = surface.first_derivatives(wrap(surface, closed_u, p.x), p.y);
                sum += DVec2::new(d.du.length(), d.dv.length());
            }
        }
        let mean = sum / (n * n) as f64;
        let fix = |s: f64| if s.is_finite() && s > 0.0 { s } else { size };
        let scale = DVec2::new(fix(mean.x), fix(mean.y));
        let extent = ((hi - lo) * scale).max_element().max(size * 1e-9);
        let ((u0, u1), (v0, v1)) = surface.domain();
        let side = |k: usize, t: f64| match k {
            0 => DVec2::new(u0, v0 + (v1 - v0) * t),
            1 => DVec2::new(u1, v0 + (v1 - v0) * t),
            2 => DVec2::new(u0 + (u1 - u0) * t, v0),
            _ => DVec2::new(u0 + (u1 - u0) * t, v1),
        };
        let pole_normals = std::array::from_fn(|k| {
            collapsed[k].then(|| {
                (0..POLE_NORMAL_SAMPLES)
                    .map(|i| {
                        let p = side(k, (i as f64 + 0.5) / POLE_NORMAL_SAMPLES as f64);
                        surface.normal(p.x, p.y)
                    })
                    .sum::<DVec3>()
                    .normalize_or_zero()
            })
        });
        Self {
            surface,
            closed_u,
            collapsed,
            weld_tolerance: COINCIDENT * size,
            scale,
            sizing: sizing(extent),
            analytic: None,
            swept: Extrusion::of(surface),
            pole_normals,
        }
    }

    /// The same facts with the exact `analytic` surface the patch lies on.
    pub fn with_analytic(mut self, analytic: Option<&Analytic>) -> Self {
        self.analytic = analytic.copied();
        self
    }

    /// The normal of the pole `uv` lies on, if it lies on a collapsed side.
    fn pole_normal(&self, uv: DVec2) -> Option<DVec3> {
        // No pole (a course, a cone's frustum): nothing to look for, at every
        // vertex of the patch.
        if self.pole_normals.iter().all(Option::is_none) {
            return None;
        }
        let ((u0, u1), (v0, v1)) = self.surface.domain();
        let (eu, ev) = (1e-12 * (u1 - u0), 1e-12 * (v1 - v0));
        let u = self.wrap_u(uv.x);
        let on = [
            !self.closed_u && (u - u0).abs() <= eu,
            !self.closed_u && (u - u1).abs() <= eu,
            (uv.y - v0).abs() <= ev,
            (uv.y - v1).abs() <= ev,
        ];
        (0..4)
            .filter(|&k| on[k])
            .find_map(|k| self.pole_normals[k])
            .filter(|n| *n != DVec3::ZERO)
    }

    /// `u` wrapped into the domain when the surface is closed in u.
    pub fn wrap_u(&self, u: f64) -> f64 {
        wrap(self.surface, self.closed_u, u)
    }

    /// The exact normal at `uv`, the limit along u = `uv.x` at a pole.
    pub fn normal(&self, uv: DVec2) -> DVec3 {
        self.surface.normal(self.wrap_u(uv.x), uv.y)
    }

    /// Checks that loop coordinates lie in the domain (u may leave it only on a
    /// surface closed in u).
    pub fn check_loop_point(&self, uv: DVec2) -> Result<(), &'static str> {
        let ((u0, u1), (v0, v1)) = self.surface.domain();
        let (eu, ev) = (1e-9 * (u1 - u0), 1e-9 * (v1 - v0));
        if uv.y < v0 - ev || uv.y > v1 + ev {
            return Err("a v coordinate is outside the surface's domain");
        }
        if !self.closed_u && (uv.x < u0 - eu || uv.x > u1 + eu) {
            return Err("a u coordinate is outside the domain of a surface open in u");
        }
        Ok(())
    }

    /// The metric at `uv`; at a pole, just inside it.
    pub fn metric_at(&self, uv: DVec2) -> Metric {
        let ((u0, u1), (v0, v1)) = self.surface.domain();
        let mut p = DVec2::new(self.wrap_u(uv.x), uv.y);
        let centre = DVec2::new(0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let nudge = DVec2::new(u1 - u0, v1 - v0) * 1e-7;
        for _ in 0..4 {
            let d = self.surface.derivatives(p.x, p.y);
            let n = d.du.cross(d.dv).normalize_or_zero();
            if n != DVec3::ZERO
                && let Some(m) = self.sizing.metric(&d, n)
            {
                return m;
            }
            p += (centre - p).signum() * nudge;
            p = p.clamp(DVec2::new(u0, v0), DVec2::new(u1, v1));
        }
        self.sizing.fallback(self.scale)
    }

    /// The mesh vertex at `uv`: exact point and normal (the limit at a pole) and
    /// the metric.
    pub fn vertex(&self, uv: DVec2) -> Result<Vertex, CdtError> {
        let d = self.surface.derivatives(self.wrap_u(uv.x), uv.y);
        let mut vertex = self.vertex_from(uv, &d)?;
        vertex.metric = self.metric_from(uv, &d, vertex.normal);
        Ok(vertex)
    }

    /// The mesh vertex at `uv` from first derivatives only, its metric
    /// [unset](Metric::UNSET) (filled by [`fill_metric`](Self::fill_metric) when
    /// refinement needs it).
    pub fn vertex_lazy(&self, uv: DVec2) -> Result<Vertex, CdtError> {
        let f = self.surface.first_derivatives(self.wrap_u(uv.x), uv.y);
        let d = first_order(f.point, f.du, f.dv);
        self.vertex_from(uv, &d)
    }

    /// The mesh vertices at `uvs` ([`vertex_lazy`](Self::vertex_lazy) of each), in
    /// order. On a surface swept straight along Z (a course) one row evaluator at
    /// v0 serves them all: S(u, v) is that row's point at u moved to the axial
    /// coordinate of v, and S_u, S_v do not depend on v — the screen's shortcut
    /// (`screen::Swept`), at well under half the cost of a surface evaluation
    /// per vertex (a course's opening loops hold most of its vertices).
    pub fn vertices_lazy(&self, uvs: &[DVec2]) -> Result<Vec<Vertex>, CdtError> {
        let Some(extrusion) = self.swept else {
            return uvs.iter().map(|&uv| self.vertex_lazy(uv)).collect();
        };
        let row = self.surface.row(self.surface.domain().1.0);
        let mut out = Vec::with_capacity(uvs.len());
        for &uv in uvs {
            let (p, du, dv) = row.first_derivatives(self.wrap_u(uv.x));
            let point = DVec3::new(p.x, p.y, extrusion.z_at(uv.y));
            out.push(self.vertex_from(uv, &first_order(point, du, dv))?);
        }
        Ok(out)
    }

    /// The vertices of the row of constant `v` at the parameters `us`, evaluated
    /// along the row (see [`SurfaceRow`](crate::nurbs::SurfaceRow)), with their
    /// metrics [unset](Metric::UNSET): only refinement reads them, after
    /// [`fill_metric`](Self::fill_metric).
    pub fn row_vertices(&self, v: f64, us: &[f64]) -> Result<Vec<Vertex>, CdtError> {
        let row = self.surface.row(v);
        let mut out = Vec::with_capacity(us.len());
        for &u in us {
            let (point, du, dv) = row.first_derivatives(self.wrap_u(u));
            out.push(self.vertex_from(DVec2::new(u, v), &first_order(point, du, dv))?);
        }
        Ok(out)
    }

    /// The metrics at `us` along the row of constant `v` ([`metric_at`](Self::metric_at)
    /// of each, evaluated along the row).
    pub fn row_metrics(&self, v: f64, us: &[f64]) -> Vec<Metric> {
        let row = self.surface.row(v);
        us.iter()
            .map(|&u| {
                let d = row.derivatives(self.wrap_u(u));
                let n = d.du.cross(d.dv).normalize_or_zero();
                match (n != DVec3::ZERO)
                    .then(|| self.sizing.metric(&d, n))
                    .flatten()
                {
                    Some(m) => m,
                    None => self.metric_at(DVec2::new(u, v)),
                }
            })
            .collect()
    }

    /// A vertex whose metric is unset, with the metric at its (u, v).
    pub fn fill_metric(&self, vertex: &mut Vertex) {
        let d = self
            .surface
            .derivatives(self.wrap_u(vertex.uv.x), vertex.uv.y);
        vertex.metric = self.metric_from(vertex.uv, &d, vertex.normal);
    }

    /// The metric at `uv` from the derivatives there and the vertex normal; at a
    /// pole or an irregular point, just inside it.
    fn metric_from(&self, uv: DVec2, d: &SurfaceDerivatives, normal: DVec3) -> Metric {
        let cross = d.du.cross(d.dv);
        let scale = d.du.length_squared().max(d.dv.length_squared());
        let regular = cross.length_squared() > 1e-20 * scale * scale;
        match regular.then(|| self.sizing.metric(d, normal)).flatten() {
            Some(m) => m,
            None => self.metric_at(uv),
        }
    }

    /// The vertex at `uv` from the derivatives there: exact point and normal (the
    /// limit at a pole); the metric [unset](Metric::UNSET).
    fn vertex_from(&self, uv: DVec2, d: &SurfaceDerivatives) -> Result<Vertex, CdtError> {
        let cross = d.du.cross(d.dv);
        let scale = d.du.length_squared().max(d.dv.length_squared());
        let regular = cross.length_squared() > 1e-20 * scale * scale;
        let pole = self.pole_normal(uv);
        let normal = match (pole, regular) {
            (Some(n), _) => n,
            (None, true) => cross.normalize(),
            (None, false) => self.surface.normal(self.wrap_u(uv.x), uv.y),
        };
        if !(d.point.is_finite() && normal.is_finite() && normal != DVec3::ZERO) {
            return Err(CdtError::NonFiniteSurface { u: uv.x, v: uv.y });
        }
        Ok(Vertex {
            uv,
            point: d.point,
            normal,
            metric: Metric::UNSET,
            pole: pole.is_some(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::test_parts::{OD, course};
    use crate::parts::heads::{Head, HeadKind};

    /// Scattered (u, v) across a patch's domain, seam and sides included.
    fn scattered(surface: &NurbsSurface) -> Vec<DVec2> {
        let ((u0, u1), (v0, v1)) = surface.domain();
        let mut t = 0.37_f64;
        let mut out = vec![DVec2::new(u0, v0), DVec2::new(u1, v1), DVec2::new(u1, v0)];
        for _ in 0..200 {
            t = (t * 97.0 + 0.211).fract();
            let s = (t * 31.0).fract();
            out.push(DVec2::new(u0 + (u1 - u0) * t, v0 + (v1 - v0) * s));
        }
        out
    }

    #[test]
    fn a_courses_vertices_from_one_row_are_its_surface_points_and_normals() {
        let patch = course();
        let surface = &patch.surface;
        let options = crate::mesh::TessellationOptions::chord(1.0);
        let info = PatchInfo::new(surface, DVec2::ZERO, DVec2::ONE, |cap| {
            Sizing::new(&options, 1.0, cap)
        });
        assert!(info.swept.is_some());
        let uvs = scattered(surface);
        let fast = info.vertices_lazy(&uvs).expect("vertices");
        assert_eq!(fast.len(), uvs.len());
        let r = OD / 2.0;
        for (v, &uv) in fast.iter().zip(&uvs) {
            let exact = info.vertex_lazy(uv).expect("a vertex");
            assert_eq!(v.uv, uv);
            // On the cylinder, where the surface evaluation puts it.
            let p = v.point;
            assert!((p.truncate().length() - r).abs() <= 1e-9 * OD, "{p}");
            assert!(
                (p - exact.point).length() <= 1e-9 * OD,
                "{p} vs {}",
                exact.point
            );
            assert!((v.normal - exact.normal).length() <= 1e-12, "{uv}");
            assert!((v.normal - p.truncate().extend(0.0) / r).length() <= 1e-9);
        }
    }

    #[test]
    fn other_surfaces_take_the_vertex_by_vertex_evaluation() {
        let patch = Head::new(2400.0, HeadKind::TWO_TO_ONE)
            .patches()
            .expect("a head")
            .remove(0);
        let surface = &patch.surface;

        let ((u0, u1), (v0, v1)) = surface.domain();
        let options = crate::mesh::TessellationOptions::chord(1.0);
        let info = PatchInfo::new(surface, DVec2::new(u0, v0), DVec2::new(u1, v1), |cap| {
            Sizing::new(&options, 1.0, cap)
        });
        assert!(info.swept.is_none());
        let uvs = scattered(surface);
        let all = info.vertices_lazy(&uvs).expect("vertices");
        for (v, &uv) in all.iter().zip(&uvs) {
            // The same vertex (its metric is unset: NaN in both).
            let one = info.vertex_lazy(uv).expect("a vertex");
            assert_eq!(
                (v.uv, v.point, v.normal, v.pole),
                (one.uv, one.point, one.normal, one.pole)
            );
        }
    }
}
