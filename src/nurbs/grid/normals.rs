//! The normal kernels along v: points and unit normals of one grid row.
//!
//! Per grid point the homogeneous value `A`, `A_u` and `A_v` are contracted from the
//! isocurve control points of the value and of the u derivative with the v basis
//! values and derivatives; then `P = A / w`, `w S_u = A_u − w_u P`,
//! `w S_v = A_v − w_v P` (the quotient rule without its common factor `1/w`, which the
//! normal does not need), the cross product and its normalization. Like the point
//! kernels this runs [`LANES`] points at a time in structure-of-arrays form, so the
//! reciprocal and the square root are packed operations.
//!
//! Where `|S_u × S_v|` is small next to the partials (a pole, an apex) the normal is
//! recomputed by the pointwise [`NurbsSurface::normal`](crate::nurbs::NurbsSurface::normal)
//! in a cold second pass over just those points.

use std::ops::Range;

use glam::{DVec3, DVec4};

use super::basis::{GridBasis, Run};
use super::kernel::{LANES, contract, lanes, run_points, streams};

/// Below this ratio `|S_u × S_v| / max(|S_u|, |S_v|)²` the normal is recomputed
/// pointwise. It is far above the pointwise function's own degeneracy threshold, so
/// every degenerate point and every point where the cross product has lost digits
/// to cancellation gets exactly the pointwise result; elsewhere the batched normal
/// agrees with the pointwise one to rounding (about 1e-16 / this ratio, relative).
const RECOMPUTE_BELOW: f64 = 1e-4;

/// Points and normals of one grid row from the isocurve control points of the value
/// (`iso`) and of the u derivative (`iso_du`). `exact(j)` is the pointwise normal at
/// grid index `j`, used where the batched one is unreliable.
pub(super) fn normals_row(
    iso: &[DVec4],
    iso_du: &[DVec4],
    v: &GridBasis,
    points: &mut [DVec3],
    normals: &mut [DVec3],
    exact: impl Fn(usize) -> DVec3,
) {
    match v.order() {
        2 => normals_row_fixed::<2>(iso, iso_du, v, points, normals, exact),
        3 => normals_row_fixed::<3>(iso, iso_du, v, points, normals, exact),
        4 => normals_row_fixed::<4>(iso, iso_du, v, points, normals, exact),
        _ => normals_row_dynamic(iso, iso_du, v, points, normals, exact),
    }
}

/// Points and normals of [`LANES`] grid points, and whether any normal is suspect.
struct Chunk {
    point: [[f64; LANES]; 3],
    normal: [[f64; LANES]; 3],
    suspect: bool,
}

impl Chunk {
    /// Stores the first `points.len()` lanes.
    #[inline(always)]
    fn store(&self, points: &mut [DVec3], normals: &mut [DVec3]) {
        let (p, n) = (&self.point, &self.normal);
        for (l, (pl, nl)) in points.iter_mut().zip(normals.iter_mut()).enumerate() {
            *pl = DVec3::new(p[0][l], p[1][l], p[2][l]);
            *nl = DVec3::new(n[0][l], n[1][l], n[2][l]);
        }
    }
}

#[inline(always)]
fn chunk<const N: usize>(
    c: &[[f64; 4]; N],
    cu: &[[f64; 4]; N],
    b: &[[f64; LANES]; N],
    db: &[[f64; LANES]; N],
) -> Chunk {
    let a = contract(c, b);
    let au = contract(cu, b);
    let av = contract(c, db);
    let mut point = [[0.0; LANES]; 3];
    let mut normal = [[0.0; LANES]; 3];
    let mut suspect = false;
    for l in 0..LANES {
        let inv = 1.0 / a[3][l];
        let p = [a[0][l] * inv, a[1][l] * inv, a[2][l] * inv];
        let su = [0, 1, 2].map(|d| au[d][l] - p[d] * au[3][l]);
        let sv = [0, 1, 2].map(|d| av[d][l] - p[d] * av[3][l]);
        let (n, is_suspect) = cross_checked(su, sv);
        let r = 1.0 / (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        for d in 0..3 {
            point[d][l] = p[d];
            normal[d][l] = n[d] * r;
        }
        suspect |= is_suspect;
    }
    Chunk {
        point,
        normal,
        suspect,
    }
}

/// `su × sv` and whether it is too small next to the partials to be trusted.
#[inline(always)]
fn cross_checked(su: [f64; 3], sv: [f64; 3]) -> ([f64; 3], bool) {
    let n = [
        su[1] * sv[2] - su[2] * sv[1],
        su[2] * sv[0] - su[0] * sv[2],
        su[0] * sv[1] - su[1] * sv[0],
    ];
    let nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let su2 = su[0] * su[0] + su[1] * su[1] + su[2] * su[2];
    let sv2 = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2];
    let scale = if su2 > sv2 { su2 } else { sv2 };
    let limit = RECOMPUTE_BELOW * RECOMPUTE_BELOW * scale * scale;
    // Written so that a NaN counts as suspect too.
    let trusted = nn > limit;
    (n, !trusted)
}

#[inline(always)]
fn normals_row_fixed<const N: usize>(
    iso: &[DVec4],
    iso_du: &[DVec4],
    v: &GridBasis,
    points: &mut [DVec3],
    normals: &mut [DVec3],
    exact: impl Fn(usize) -> DVec3,
) {
    let total = v.len();
    for run in v.runs() {
        let c = run_points::<N>(iso, run);
        let cu = run_points::<N>(iso_du, run);
        let b = streams::<N>(v.values(), total, run);
        let db = streams::<N>(v.derivatives(), total, run);
        let points = &mut points[run.start..run.end];
        let normals = &mut normals[run.start..run.end];
        let mut suspects = Suspects::NONE;
        let mut base = 0;
        for (p, n) in points
            .chunks_exact_mut(LANES)
            .zip(normals.chunks_exact_mut(LANES))
        {
            let out = chunk(&c, &cu, &lanes(&b, base, LANES), &lanes(&db, base, LANES));
            out.store(p, n);
            suspects.note(base..base + LANES, out.suspect);
            base += LANES;
        }
        let count = points.len() - base;
        if count > 0 {
            let out = chunk(&c, &cu, &lanes(&b, base, count), &lanes(&db, base, count));
            out.store(&mut points[base..], &mut normals[base..]);
            suspects.note(base..base + count, out.suspect);
        }
        suspects.recompute(iso, iso_du, v, run, normals, &exact);
    }
}

fn normals_row_dynamic(
    iso: &[DVec4],
    iso_du: &[DVec4],
    v: &GridBasis,
    points: &mut [DVec3],
    normals: &mut [DVec3],
    exact: impl Fn(usize) -> DVec3,
) {
    for run in v.runs() {
        let mut suspects = Suspects::NONE;
        for j in run.start..run.end {
            let (point, su, sv) = frame_dynamic(iso, iso_du, v, run, j);
            let (n, suspect) = cross_checked(su, sv);
            points[j] = point;
            normals[j] = DVec3::from_array(n).normalize();
            suspects.note(j - run.start..j - run.start + 1, suspect);
        }
        let normals = &mut normals[run.start..run.end];
        suspects.recompute(iso, iso_du, v, run, normals, &exact);
    }
}

/// Point, `w S_u` and `w S_v` at grid index `j` of `run`, for any order.
fn frame_dynamic(
    iso: &[DVec4],
    iso_du: &[DVec4],
    v: &GridBasis,
    run: &Run,
    j: usize,
) -> (DVec3, [f64; 3], [f64; 3]) {
    let total = v.len();
    let (values, derivatives) = (v.values(), v.derivatives());
    let (mut a, mut au, mut av) = (DVec4::ZERO, DVec4::ZERO, DVec4::ZERO);
    for k in 0..v.order() {
        let (c, cu) = (iso[run.first + k], iso_du[run.first + k]);
        let (b, db) = (values[k * total + j], derivatives[k * total + j]);
        a += c * b;
        au += cu * b;
        av += c * db;
    }
    let point = a.truncate() * (1.0 / a.w);
    let su = au.truncate() - point * au.w;
    let sv = av.truncate() - point * av.w;
    (point, su.to_array(), sv.to_array())
}

/// The offsets `first..end` of a run that hold suspect normals, tracked without
/// branches in the hot loop; at a pole or apex it is one point per row.
struct Suspects {
    first: usize,
    end: usize,
}

impl Suspects {
    /// No suspect yet (an empty range).
    const NONE: Self = Self {
        first: usize::MAX,
        end: 0,
    };

    /// Widens the range to cover `offsets` if `suspect`.
    #[inline(always)]
    fn note(&mut self, offsets: Range<usize>, suspect: bool) {
        let first = self.first.min(offsets.start);
        let end = self.end.max(offsets.end);
        self.first = if suspect { first } else { self.first };
        self.end = if suspect { end } else { self.end };
    }

    /// Replaces every suspect normal in the range by the pointwise normal `exact(j)`;
    /// `normals` is the run's slice.
    #[inline(always)]
    fn recompute(
        &self,
        iso: &[DVec4],
        iso_du: &[DVec4],
        v: &GridBasis,
        run: &Run,
        normals: &mut [DVec3],
        exact: &impl Fn(usize) -> DVec3,
    ) {
        if self.first < self.end {
            recompute_suspects(iso, iso_du, v, run, self.first..self.end, normals, exact);
        }
    }
}

/// Second pass over the offsets `range` of a run: replaces each suspect normal by the
/// pointwise one.
#[cold]
fn recompute_suspects(
    iso: &[DVec4],
    iso_du: &[DVec4],
    v: &GridBasis,
    run: &Run,
    range: Range<usize>,
    normals: &mut [DVec3],
    exact: &impl Fn(usize) -> DVec3,
) {
    for t in range {
        let j = run.start + t;
        let (_, su, sv) = frame_dynamic(iso, iso_du, v, run, j);
        if cross_checked(su, sv).1 {
            normals[t] = exact(j);
        }
    }
}
