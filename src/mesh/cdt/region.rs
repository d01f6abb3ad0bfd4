//! The region of a patch to mesh: closed polylines in the patch's (u, v) parameter
//! space, one outer loop and any number of holes.
//!
//! The caller builds the loops from the patch's boundary: the four sides of the
//! parameter rectangle, or trimming curves such as a nozzle–host intersection. The
//! loop vertices are exactly the boundary vertices of the mesh (shared edges are
//! sampled once so neighbouring patches conform). This module holds the types, their
//! validation, and the geometric queries the mesher asks of them (bounds, inside
//! tests along a row of constant v).

use glam::DVec2;

use super::CdtError;
use crate::nurbs::NurbsSurface;

/// A closed polyline in the patch's (u, v) parameter space. Consecutive vertices are
/// joined; the last joins the first.
///
/// u may lie outside the surface's u-domain when the surface is closed in u (a loop
/// that crosses the seam): the mesher evaluates at [`wrap_u`](super::wrap_u).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UvLoop {
    /// The vertices, (u, v); at least three, no two consecutive ones equal.
    pub uv: Vec<DVec2>,
}

/// The region of a patch to mesh: one outer loop (counter-clockwise in (u, v)) and
/// any number of holes (clockwise), none crossing another.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Region {
    /// The outer boundary, counter-clockwise in (u, v).
    pub outer: UvLoop,
    /// Holes, each clockwise in (u, v), inside the outer loop.
    pub holes: Vec<UvLoop>,
}

impl UvLoop {
    /// A loop through `uv`.
    pub fn new(uv: Vec<DVec2>) -> Self {
        Self { uv }
    }

    /// Twice the signed area enclosed (positive when counter-clockwise).
    pub fn signed_double_area(&self) -> f64 {
        self.segments().map(|(a, b)| a.perp_dot(b)).sum()
    }

    /// The segments `(uv[k], uv[k + 1])`, the last closing the loop.
    pub fn segments(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        let n = self.uv.len();
        (0..n).map(move |k| (self.uv[k], self.uv[(k + 1) % n]))
    }
}

impl Region {
    /// The whole parameter rectangle of `surface`: its four sides, with only the four
    /// corners as vertices, counter-clockwise from `(u0, v0)`.
    pub fn rectangle(surface: &NurbsSurface) -> Region {
        let ((u0, u1), (v0, v1)) = surface.domain();
        Region {
            outer: UvLoop::new(vec![
                DVec2::new(u0, v0),
                DVec2::new(u1, v0),
                DVec2::new(u1, v1),
                DVec2::new(u0, v1),
            ]),
            holes: Vec::new(),
        }
    }

    /// A 128-bit fingerprint of the loops: XXH3's 128-bit hash of every
    /// coordinate's bit pattern and of the loop lengths. Equal regions have
    /// equal fingerprints; different ones collide with probability about 2⁻¹²⁸,
    /// so the model compares fingerprints instead of keeping the loops. (XXH3
    /// reads the coordinates a block at a time, with no copy: a fifth of the
    /// instructions of the SipHash and FxHash pair it replaced, which took 1.7 %
    /// of a simulation tick's. The other mesh keys are `mesh::key::Key`s
    /// of the same hash.)
    pub fn fingerprint(&self) -> u128 {
        let mut hash = xxhash_rust::xxh3::Xxh3::with_seed(0x5EED);
        for l in self.loops() {
            hash.update(&(l.uv.len() as u64).to_le_bytes());
            hash.update(bytemuck::cast_slice::<DVec2, u8>(&l.uv));
        }
        hash.digest128()
    }

    /// A region bounded by `outer` with no holes.
    pub fn new(outer: UvLoop) -> Region {
        Region {
            outer,
            holes: Vec::new(),
        }
    }

    /// The same region with one more hole.
    pub fn with_hole(mut self, hole: UvLoop) -> Region {
        self.holes.push(hole);
        self
    }

    /// The loops, outer first: index 0 is the outer loop, 1 + k hole k.
    pub fn loops(&self) -> impl Iterator<Item = &UvLoop> + '_ {
        std::iter::once(&self.outer).chain(self.holes.iter())
    }

    /// Number of loop vertices in all loops.
    pub fn vertex_count(&self) -> usize {
        self.loops().map(|l| l.uv.len()).sum()
    }

    /// Checks every loop: at least three finite vertices, no two consecutive ones
    /// equal, non-zero area, the outer loop counter-clockwise and holes clockwise.
    /// Whether loops cross is found later, when spade inserts them.
    pub fn validate(&self) -> Result<(), CdtError> {
        for (loop_index, l) in self.loops().enumerate() {
            let bad = |reason| Err(CdtError::InvalidLoop { loop_index, reason });
            if l.uv.len() < 3 {
                return bad("fewer than three vertices");
            }
            if !l.uv.iter().all(|p| p.is_finite()) {
                return bad("a coordinate is not finite");
            }
            if l.segments().any(|(a, b)| a == b) {
                return bad("two consecutive vertices are equal");
            }
            let area = l.signed_double_area();
            let (lo, hi) = bounds_of(&l.uv);
            let extent = (hi - lo).max_element();
            if area.is_nan() || area.abs() <= 1e-14 * extent * extent {
                return bad("the loop encloses no area");
            }
            if loop_index == 0 && area < 0.0 {
                return bad("the outer loop must be counter-clockwise in (u, v)");
            }
            if loop_index > 0 && area > 0.0 {
                return bad("a hole must be clockwise in (u, v)");
            }
        }
        Ok(())
    }

    /// The same region with u and v exchanged (loops reversed, so the outer loop
    /// stays counter-clockwise).
    pub(super) fn transposed(&self) -> Region {
        let swap =
            |l: &UvLoop| UvLoop::new(l.uv.iter().rev().map(|p| DVec2::new(p.y, p.x)).collect());
        Region {
            outer: swap(&self.outer),
            holes: self.holes.iter().map(swap).collect(),
        }
    }

    /// Bounds `(min, max)` of the outer loop's vertices.
    pub fn bounds(&self) -> (DVec2, DVec2) {
        bounds_of(&self.outer.uv)
    }

    /// The u values where the loops cross the row `v`, sorted. A point `(u, v)` of
    /// the row is inside the region when an odd number of them are below `u`.
    pub(super) fn row_crossings(&self, v: f64, out: &mut Vec<f64>) {
        out.clear();
        for l in self.loops() {
            for (a, b) in l.segments() {
                if (a.y <= v) != (b.y <= v) {
                    out.push(a.x + (v - a.y) * (b.x - a.x) / (b.y - a.y));
                }
            }
        }
        out.sort_by(f64::total_cmp);
    }
}

/// Whether `u` is inside according to sorted row crossings.
pub(super) fn inside_by_crossings(crossings: &[f64], u: f64) -> bool {
    crossings.partition_point(|&c| c < u) % 2 == 1
}

/// Bounds `(min, max)` of a point set (`(0, 0)` twice when empty).
pub(super) fn bounds_of(points: &[DVec2]) -> (DVec2, DVec2) {
    let Some(&first) = points.first() else {
        return (DVec2::ZERO, DVec2::ZERO);
    };
    points
        .iter()
        .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)))
}
