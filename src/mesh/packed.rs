//! Compact storage of a finished patch mesh: what the model keeps (in
//! `PatchMesh`) and the exporters read, between the mesher's working [`Mesh`] and
//! the `f32` buffers of a glTF file.
//!
//! A plant of 10 000 vessels holds about a hundred million mesh vertices, so the
//! layout matters. Positions are fixed-point offsets from the patch's centre in
//! a power-of-two unit. Boundary vertices (on an edge used by one triangle: the
//! patch's sides, opening loops — shared with a neighbour, welded at 1e-6 mm)
//! get 40 bits per coordinate, within 2⁻⁴⁰ of the patch's extent of the exact
//! point (5e-9 mm for a 5 m course); interior vertices get 32 bits, within 2⁻³²
//! of the extent (1e-6 mm), far below any meshing tolerance. Boundary vertices
//! come first, so vertex order differs from the mesher's. Normals are
//! octahedral-encoded in two signed 16-bit numbers (4 bytes instead of 24; the
//! decoded unit normal is within 1e-4 rad of the exact one, far below what a
//! viewer or a drawing can show); indices are `u16` when the patch has at most
//! 65 536 vertices, else `u32`. 15 bytes per boundary and 12 per interior vertex
//! instead of 48, 6 per triangle instead of 12. Packing is deterministic, so the
//! incremental model and a direct full build export the same bytes.

use glam::{DVec2, DVec3, IVec3};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::Mesh;

/// Vertices per parallel task when packing a big patch (a head of 14 m has
/// some 8 000; most patches have a few hundred and pack on one thread).
const PARALLEL_VERTICES: usize = 4096;

/// Largest value of a signed-normalised 16-bit component.
const SNORM16: f64 = i16::MAX as f64;

/// A unit vector in octahedral encoding: its projection on the octahedron
/// `|x| + |y| + |z| = 1`, the lower half folded over the upper, as two snorm16.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct OctNormal(pub [i16; 2]);

impl OctNormal {
    /// What a zero or non-finite vector encodes as (never a unit vector's
    /// code: components are clamped to ±32767); it decodes as NaN, so the
    /// exporters' checks still see it.
    pub const INVALID: Self = Self([i16::MIN, i16::MIN]);

    /// Encodes a unit vector (a zero or non-finite one as [`OctNormal::INVALID`]).
    pub fn encode(n: DVec3) -> Self {
        let l1 = n.x.abs() + n.y.abs() + n.z.abs();
        if !(l1.is_finite() && l1 > 0.0) {
            return Self::INVALID;
        }
        let mut p = DVec2::new(n.x, n.y) / l1;
        if n.z < 0.0 {
            p = (DVec2::ONE - DVec2::new(p.y.abs(), p.x.abs())) * sign(p);
        }
        let q = |x: f64| round_small(x.clamp(-1.0, 1.0) * SNORM16) as i16;
        Self([q(p.x), q(p.y)])
    }

    /// The unit vector it encodes (NaN for [`OctNormal::INVALID`]).
    pub fn decode(self) -> DVec3 {
        if self == Self::INVALID {
            return DVec3::NAN;
        }
        let mut p = DVec2::new(f64::from(self.0[0]), f64::from(self.0[1])) / SNORM16;
        let z = 1.0 - p.x.abs() - p.y.abs();
        if z < 0.0 {
            p = (DVec2::ONE - DVec2::new(p.y.abs(), p.x.abs())) * sign(p);
        }
        DVec3::new(p.x, p.y, z).normalize()
    }
}

/// `x.round()` (half away from zero) for |x| < 2⁶², as packing's offsets and
/// normal components are: the truncation is the hardware's conversion to an
/// integer, where `f64::round` is a library call on CPUs without SSE4.1 — and
/// packing rounds five numbers per vertex. The difference `x − trunc(x)` is
/// exact, so the result is `round`'s value (a zero may lose its sign, which the
/// integer conversion after it drops anyway; tested).
#[inline]
fn round_small(x: f64) -> f64 {
    let t = x as i64 as f64;
    let d = x - t;
    // Without branches: which way a coordinate rounds is a coin toss, and
    // mispredicted branches cost more than the library call saved.
    t + f64::from(u8::from(d >= 0.5)) - f64::from(u8::from(d <= -0.5))
}

/// Component-wise sign, with +1 for zero (so the fold is defined on the axes).
fn sign(p: DVec2) -> DVec2 {
    DVec2::new(
        if p.x >= 0.0 { 1.0 } else { -1.0 },
        if p.y >= 0.0 { 1.0 } else { -1.0 },
    )
}

/// Triangle indices, as small as the vertex count allows.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Indices {
    /// At most 65 536 vertices.
    U16(Box<[u16]>),
    /// More.
    U32(Box<[u32]>),
}

/// Vertex positions as fixed-point offsets from `origin` in units of `fine` (a
/// power of two, so decoding is exact up to the final addition): the first
/// `lo.len()` (boundary) vertices as 40-bit integers `hi · 256 + lo`, the others
/// (interior) as 32-bit integers `hi` in units of `256 · fine`.
#[derive(Clone, Debug, Default, PartialEq)]
struct FixedPoints {
    origin: DVec3,
    fine: f64,
    hi: Box<[IVec3]>,
    lo: Box<[[u8; 3]]>,
}

impl FixedPoints {
    /// Largest offset used, in units of `fine` (keeps `hi` and the interior's
    /// rounding inside `i32`).
    const RANGE: f64 = ((1u64 << 39) - (1 << 10)) as f64;

    /// Encodes `points`, the first `boundary` of them to 40 bits; `None` when a
    /// point is not finite.
    fn encode(points: &[DVec3], boundary: usize) -> Option<Self> {
        let Some(&first) = points.first() else {
            return Some(Self::default());
        };
        // One pass: finiteness and the bounds.
        let (lo, hi, finite) = points
            .iter()
            .fold((first, first, true), |(lo, hi, ok), &p| {
                (lo.min(p), hi.max(p), ok & p.is_finite())
            });
        if !finite {
            return None;
        }
        let origin = (lo + hi) * 0.5;
        // The largest |p − origin| of any point, from the bounds alone: the
        // rounded difference grows with p, so each component's largest is at
        // the bound (`hi − origin` or `origin − lo`), bit for bit.
        let reach = (hi - origin).max(origin - lo).max_element().max(0.0);
        // Smallest power of two with reach / fine within range.
        let fine = if reach > 0.0 {
            2f64.powi((reach / Self::RANGE).log2().ceil() as i32)
        } else {
            1.0
        };
        let coarse = 256.0 * fine;
        // Powers of two: multiplying by the reciprocal is the division, bit for
        // bit, unless the reciprocal overflows (a mesh some 1e-300 mm across).
        let (per_fine, per_coarse) = (1.0 / fine, 1.0 / coarse);
        let scaled = |p: DVec3, unit: f64, per_unit: f64| {
            if per_unit.is_finite() {
                (p - origin) * per_unit
            } else {
                (p - origin) / unit
            }
        };
        let mut his = Vec::with_capacity(points.len());
        let mut los = Vec::with_capacity(boundary);
        for (k, &p) in points.iter().enumerate() {
            if k < boundary {
                let q = scaled(p, fine, per_fine).map(round_small);
                let q = [q.x as i64, q.y as i64, q.z as i64];
                his.push(IVec3::from_array(q.map(|c| (c >> 8) as i32)));
                los.push(q.map(|c| (c & 0xFF) as u8));
            } else {
                let q = scaled(p, coarse, per_coarse).map(round_small);
                his.push(IVec3::new(q.x as i32, q.y as i32, q.z as i32));
            }
        }
        Some(Self {
            origin,
            fine,
            hi: his.into_boxed_slice(),
            lo: los.into_boxed_slice(),
        })
    }

    fn decode(&self, k: usize) -> DVec3 {
        let hi = self.hi[k].as_dvec3() * 256.0;
        let units = match self.lo.get(k) {
            Some(lo) => hi + DVec3::from_array(lo.map(f64::from)),
            None => hi,
        };
        self.origin + units * self.fine
    }
}

/// Vertex positions: fixed point, or as given when one is not finite (kept for
/// the exporters' checks to name).
#[derive(Clone, Debug, PartialEq)]
enum Positions {
    Fixed(FixedPoints),
    AsGiven(Box<[DVec3]>),
}

/// A finished patch mesh in compact form (see the module docs): exact boundary
/// positions, fixed-point interior ones, octahedral normals, the narrowest
/// indices.
#[derive(Clone, Debug, PartialEq)]
pub struct PackedMesh {
    /// The boundary vertices first, then the interior ones.
    positions: Positions,
    /// Number of boundary vertices.
    boundary: usize,
    normals: Box<[OctNormal]>,
    indices: Indices,
}

impl Default for PackedMesh {
    fn default() -> Self {
        Self::pack(&Mesh::default())
    }
}

impl From<&Mesh> for PackedMesh {
    fn from(mesh: &Mesh) -> Self {
        Self::pack(mesh)
    }
}

/// For each of `count` vertices, whether it is used and on no edge that exactly
/// one triangle of `indices` uses (an edge is its two vertices, either way round).
///
/// Every triangle hands each of its vertices the other two, so the number of
/// times x appears in v's list is the number of triangles using the edge {v, x};
/// a vertex is interior when no neighbour appears exactly once. A short sort per
/// vertex (about a dozen entries) instead of a hash map of all edges. A triangle
/// naming a vertex twice uses an edge from that vertex to itself, which the lists
/// do not see: such meshes (never the mesher's) take the map.
fn interior_vertices(indices: &[u32], count: usize) -> Vec<bool> {
    let mut start = vec![0u32; count + 1];
    let mut repeated = false;
    for t in indices.chunks_exact(3) {
        repeated |= t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
        for &i in t {
            start[i as usize + 1] += 2;
        }
    }
    if repeated {
        return interior_vertices_by_edges(indices, count);
    }
    for k in 0..count {
        start[k + 1] += start[k];
    }
    let mut fill: Vec<u32> = start[..count].to_vec();
    let mut neighbours = vec![0u32; 2 * indices.len()];
    for t in indices.chunks_exact(3) {
        for k in 0..3 {
            let v = t[k] as usize;
            let at = fill[v] as usize;
            neighbours[at] = t[(k + 1) % 3];
            neighbours[at + 1] = t[(k + 2) % 3];
            fill[v] += 2;
        }
    }
    // Each vertex's list copied, sorted and read on its own: in parallel on a
    // big patch.
    let classify = |v: usize| {
        let list = &neighbours[start[v] as usize..start[v + 1] as usize];
        let mut buffer = [0u32; 32];
        match buffer.get_mut(..list.len()) {
            Some(copy) => {
                copy.copy_from_slice(list);
                single_free(copy)
            }
            None => single_free(&mut list.to_vec()),
        }
    };
    if count > PARALLEL_VERTICES {
        (0..count)
            .into_par_iter()
            .with_min_len(PARALLEL_VERTICES)
            .map(classify)
            .collect()
    } else {
        (0..count).map(classify).collect()
    }
}

/// Whether the neighbour list of a used vertex (sorted here) names no
/// neighbour exactly once; false for an empty list (an unused vertex).
fn single_free(list: &mut [u32]) -> bool {
    if list.is_empty() {
        return false;
    }
    list.sort_unstable();
    let mut k = 0;
    while k < list.len() {
        let mut end = k + 1;
        while end < list.len() && list[end] == list[k] {
            end += 1;
        }
        if end == k + 1 {
            return false;
        }
        k = end;
    }
    true
}

/// [`interior_vertices`] by counting every edge in a hash map: the reference, and
/// the way for triangles that name a vertex twice.
fn interior_vertices_by_edges(indices: &[u32], count: usize) -> Vec<bool> {
    let mut uses: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    // About 1.5 distinct edges per triangle in a patch mesh.
    uses.reserve(indices.len() / 2 + 8);
    for t in indices.chunks_exact(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let mut interior = vec![false; count];
    for &i in indices {
        interior[i as usize] = true;
    }
    for (&(a, b), &n) in &uses {
        if n == 1 {
            interior[a as usize] = false;
            interior[b as usize] = false;
        }
    }
    interior
}

impl PackedMesh {
    /// Packs `mesh`. Nothing is repaired: counts stay as they are and a bad
    /// normal stays bad, for the exporters' checks.
    pub fn pack(mesh: &Mesh) -> Self {
        Self::pack_with(mesh, |mesh| {
            interior_vertices(&mesh.indices, mesh.positions.len())
        })
    }

    /// [`pack`](Self::pack) of a mesh whose vertices on its boundary are known:
    /// `on_loops` marks, for each vertex, whether it lies on a loop of the meshed
    /// region (the mesher's `RegionMesh::on_loops`, a superset of the vertices on
    /// edges one triangle alone uses). Those and unused vertices stay exact; the
    /// edges are not counted again. Without one flag per vertex, packs as
    /// [`pack`](Self::pack) does.
    pub fn pack_marked(mesh: &Mesh, on_loops: &[bool]) -> Self {
        if on_loops.len() != mesh.positions.len() {
            return Self::pack(mesh);
        }
        Self::pack_with(mesh, |mesh| {
            let mut interior = vec![false; on_loops.len()];
            for &i in &mesh.indices {
                interior[i as usize] = !on_loops[i as usize];
            }
            interior
        })
    }

    /// Packs `mesh` with the interior vertices `interior` finds (indices already
    /// checked in range).
    fn pack_with(mesh: &Mesh, interior: impl FnOnce(&Mesh) -> Vec<bool>) -> Self {
        let count = mesh.positions.len();
        let well_formed = mesh.normals.len() == count
            && mesh.indices.len().is_multiple_of(3)
            && mesh.indices.iter().all(|&i| (i as usize) < count);
        if !well_formed {
            // Never produced by the mesher: kept as it is (all exact, u32), for
            // the exporters' checks to name.
            return Self {
                positions: Positions::AsGiven(mesh.positions.clone().into_boxed_slice()),
                boundary: count,
                normals: mesh.normals.iter().map(|&n| OctNormal::encode(n)).collect(),
                indices: Indices::U32(mesh.indices.clone().into_boxed_slice()),
            };
        }
        // Edges used by one triangle bound the patch; their vertices are shared
        // with neighbours (or are opening loops) and stay exact. Unused vertices
        // stay exact too.
        let interior = interior(mesh);
        let order: Vec<usize> = (0..count)
            .filter(|&i| !interior[i])
            .chain((0..count).filter(|&i| interior[i]))
            .collect();
        let boundary = count - interior.iter().filter(|&&i| i).count();
        let mut new_index = vec![0u32; count];
        for (k, &i) in order.iter().enumerate() {
            new_index[i] = k as u32;
        }
        let remap = |&i: &u32| new_index[i as usize];
        let indices = if count <= 1 << 16 {
            Indices::U16(mesh.indices.iter().map(|i| remap(i) as u16).collect())
        } else {
            Indices::U32(mesh.indices.iter().map(remap).collect())
        };
        let points: Vec<DVec3> = order.iter().map(|&i| mesh.positions[i]).collect();
        let encode_normals = || -> Box<[OctNormal]> {
            let encode = |&i: &usize| OctNormal::encode(mesh.normals[i]);
            if count > PARALLEL_VERTICES {
                order
                    .par_iter()
                    .with_min_len(PARALLEL_VERTICES)
                    .map(encode)
                    .collect()
            } else {
                order.iter().map(encode).collect()
            }
        };
        let encode_points = || match FixedPoints::encode(&points, boundary) {
            Some(fixed) => Positions::Fixed(fixed),
            None => Positions::AsGiven(points.clone().into_boxed_slice()),
        };
        // The normals beside the positions on a big patch.
        let (positions, normals) = if count > PARALLEL_VERTICES {
            rayon::join(encode_points, encode_normals)
        } else {
            (encode_points(), encode_normals())
        };
        Self {
            positions,
            boundary,
            normals,
            indices,
        }
    }

    /// The mesher's form again: positions, decoded normals, `u32` indices.
    pub fn unpack(&self) -> Mesh {
        Mesh {
            positions: self.positions().collect(),
            normals: self.normals.iter().map(|n| n.decode()).collect(),
            indices: self.indices().collect(),
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        match &self.positions {
            Positions::Fixed(f) => f.hi.len(),
            Positions::AsGiven(p) => p.len(),
        }
    }

    /// Number of boundary vertices (stored to 40 bits; they come first).
    pub fn boundary_count(&self) -> usize {
        self.boundary
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.index_count() / 3
    }

    /// Number of indices (three per triangle).
    pub fn index_count(&self) -> usize {
        match &self.indices {
            Indices::U16(i) => i.len(),
            Indices::U32(i) => i.len(),
        }
    }

    /// The position of vertex `i`, mm, in the patch's part-local frame.
    pub fn position(&self, i: usize) -> DVec3 {
        match &self.positions {
            Positions::Fixed(f) => f.decode(i),
            Positions::AsGiven(p) => p[i],
        }
    }

    /// Vertex positions, mm, in the patch's part-local frame.
    pub fn positions(&self) -> impl ExactSizeIterator<Item = DVec3> + '_ {
        (0..self.vertex_count()).map(|i| self.position(i))
    }

    /// Number of normals (equal to [`vertex_count`](Self::vertex_count) for
    /// every mesh the mesher makes).
    pub fn normal_count(&self) -> usize {
        self.normals.len()
    }

    /// The unit normal of vertex `i` (decoded).
    pub fn normal(&self, i: usize) -> DVec3 {
        self.normals[i].decode()
    }

    /// The encoded normals.
    pub fn oct_normals(&self) -> &[OctNormal] {
        &self.normals
    }

    /// The indices, three per triangle, counter-clockwise seen from outside.
    pub fn indices(&self) -> impl ExactSizeIterator<Item = u32> + '_ {
        (0..self.index_count()).map(move |k| self.index(k))
    }

    /// The triangles as vertex-index triples.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        (0..self.triangle_count()).map(move |t| [0, 1, 2].map(|k| self.index(3 * t + k)))
    }

    /// Index `k` of the index list.
    pub fn index(&self, k: usize) -> u32 {
        match &self.indices {
            Indices::U16(i) => u32::from(i[k]),
            Indices::U32(i) => i[k],
        }
    }

    /// Axis-aligned bounds `(min, max)` of the vertices; `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = (self.vertex_count() > 0).then(|| self.position(0))?;
        Some(
            self.positions()
                .fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))),
        )
    }

    /// Heap bytes held, with the struct itself.
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + match &self.positions {
                Positions::Fixed(f) => {
                    std::mem::size_of_val(&*f.hi) + std::mem::size_of_val(&*f.lo)
                }
                Positions::AsGiven(p) => std::mem::size_of_val(&**p),
            }
            + std::mem::size_of_val(&*self.normals)
            + match &self.indices {
                Indices::U16(i) => std::mem::size_of_val(&**i),
                Indices::U32(i) => std::mem::size_of_val(&**i),
            }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octahedral_normals_round_trip_within_1e_4_rad() {
        let mut worst = 0.0f64;
        let n = 60;
        for i in 0..=n {
            for j in 0..2 * n {
                let theta = std::f64::consts::PI * i as f64 / n as f64;
                let phi = std::f64::consts::PI * j as f64 / n as f64;
                let v = DVec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let back = OctNormal::encode(v).decode();
                assert!((back.length() - 1.0).abs() < 1e-12);
                worst = worst.max(back.angle_between(v));
            }
        }
        for axis in [
            DVec3::X,
            DVec3::NEG_X,
            DVec3::Y,
            DVec3::NEG_Y,
            DVec3::Z,
            DVec3::NEG_Z,
        ] {
            assert!(OctNormal::encode(axis).decode().angle_between(axis) < 1e-9);
        }
        assert!(worst < 1e-4, "{worst}");
        assert!(OctNormal::encode(DVec3::ZERO).decode().is_nan());
        assert!(OctNormal::encode(DVec3::NAN).decode().is_nan());
    }

    #[test]
    fn packing_keeps_indices_and_positions_to_40_bits() {
        let mesh = Mesh {
            positions: vec![
                DVec3::new(0.1, 0.2, 0.3),
                DVec3::new(1e4 + 1e-9, 0.0, -3.0),
                DVec3::new(0.0, 7.0, 1.0 / 3.0),
            ],
            normals: vec![
                DVec3::Z,
                DVec3::NEG_Y,
                DVec3::new(1.0, 1.0, -1.0).normalize(),
            ],
            indices: vec![0, 1, 2],
        };
        let packed = PackedMesh::pack(&mesh);
        // All three on the boundary: within 2^-40 of the extent (1e4 mm).
        for (a, b) in packed.positions().zip(&mesh.positions) {
            assert!(
                (a - *b).abs().max_element() <= 1e4 * 2f64.powi(-40),
                "{a} {b}"
            );
        }
        assert_eq!(packed.indices().collect::<Vec<_>>(), mesh.indices);
        assert_eq!(packed.triangles().collect::<Vec<_>>(), [[0, 1, 2]]);
        let back = packed.unpack();
        for (a, b) in back.normals.iter().zip(&mesh.normals) {
            assert!(a.angle_between(*b) < 1e-4);
        }
        let ((a0, a1), (b0, b1)) = (packed.bounds().unwrap(), mesh.bounds().unwrap());
        assert!((a0 - b0).abs().max_element() <= 1e-8 && (a1 - b1).abs().max_element() <= 1e-8);
    }

    #[test]
    fn boundary_vertices_within_2e_40_and_interior_ones_within_2e_32_of_the_extent() {
        // A fan round an interior vertex on a 10 m patch; the rim is the boundary.
        let rim = 12;
        let centre = DVec3::new(1_234.567_890_123, -9_876.543_21, 0.1);
        let mut positions: Vec<DVec3> = (0..rim)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / rim as f64;
                centre + DVec3::new(5000.0 * a.cos(), 5000.0 * a.sin(), 1.0 / 3.0)
            })
            .collect();
        positions.insert(3, centre + DVec3::new(0.123_456_789, 1e-7, 2.0 / 3.0));
        positions.push(centre + DVec3::new(-7.654_321, 3.3, 0.7));
        let (hub, other) = (3u32, rim as u32 + 1);
        let ring: Vec<u32> = (0..=rim as u32).filter(|&i| i != hub).collect();
        let mut indices = Vec::new();
        for k in 0..rim {
            let (a, b) = (ring[k], ring[(k + 1) % rim]);
            // Split every other wedge through the second interior vertex.
            if k == 5 {
                indices.extend([hub, a, other, other, a, b, hub, other, b]);
            } else {
                indices.extend([hub, a, b]);
            }
        }
        let mesh = Mesh {
            normals: vec![DVec3::Z; positions.len()],
            positions,
            indices,
        };
        let packed = PackedMesh::pack(&mesh);
        assert_eq!(packed.boundary_count(), rim);
        assert_eq!(packed.vertex_count(), rim + 2);
        // Same triangles (by position) in the same order.
        let before: Vec<[DVec3; 3]> = mesh
            .indices
            .chunks(3)
            .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize]))
            .collect();
        let after: Vec<[DVec3; 3]> = packed
            .triangles()
            .map(|t| t.map(|i| packed.position(i as usize)))
            .collect();
        let extent = 10_000.0;
        for (b, a) in before.iter().zip(&after) {
            for k in 0..3 {
                // The rim is the boundary; the two hub vertices are not.
                if (b[k] - centre).truncate().length() > 4999.0 {
                    assert!((a[k] - b[k]).abs().max_element() <= extent * 2f64.powi(-40));
                } else {
                    assert!((a[k] - b[k]).abs().max_element() <= extent * 2f64.powi(-32));
                }
            }
        }
        assert!(packed.heap_bytes() < mesh.heap_bytes());
    }

    proptest::proptest! {
        /// The per-vertex lists name the same interior vertices as counting every
        /// edge, on any triangles: repeated indices, edges used three times,
        /// triangles turned either way, vertices used by none.
        #[test]
        fn interior_vertices_agree_with_counting_edges(
            count in 3usize..24,
            raw in proptest::collection::vec((0u32..24, 0u32..24, 0u32..24), 0..40),
            degenerate in proptest::bool::weighted(0.2),
        ) {
            let n = count as u32;
            // Without repeats (the mesher's kind) unless `degenerate`.
            let indices: Vec<u32> = raw
                .iter()
                .map(|&(a, b, c)| [a % n, b % n, c % n])
                .filter(|t| degenerate || (t[0] != t[1] && t[1] != t[2] && t[2] != t[0]))
                .flatten()
                .collect();
            proptest::prop_assert_eq!(
                super::interior_vertices(&indices, count),
                super::interior_vertices_by_edges(&indices, count)
            );
        }
    }

    #[test]
    fn interior_vertices_of_a_big_patch_agree_with_counting_edges() {
        // A 120 × 90 grid (more vertices than one parallel task takes) with
        // every seventh quad left out, so that holes' rims are boundary too.
        let (nu, nv) = (120u32, 90u32);
        let mut indices = Vec::new();
        for j in 0..nv {
            for i in 0..nu {
                if (i * 31 + j * 17) % 7 == 0 {
                    continue;
                }
                let a = j * (nu + 1) + i;
                let (b, c) = (a + 1, a + nu + 1);
                indices.extend([a, b, c + 1, a, c + 1, c]);
            }
        }
        let count = ((nu + 1) * (nv + 1)) as usize;
        assert!(count > 2 * super::PARALLEL_VERTICES);
        let interior = super::interior_vertices(&indices, count);
        assert_eq!(interior, super::interior_vertices_by_edges(&indices, count));
        assert!(interior.iter().filter(|&&i| i).count() > count / 3);
        assert!(interior.iter().filter(|&&i| !i).count() > count / 10);
    }

    #[test]
    fn interior_vertices_of_a_closed_fan_and_an_open_one() {
        // A closed fan of six round vertex 0 (1..=6), then an open one round 7.
        let mut indices = Vec::new();
        for k in 0..6u32 {
            indices.extend([0, 1 + k, 1 + (k + 1) % 6]);
        }
        indices.extend([7, 8, 9, 7, 9, 10]);
        let interior = super::interior_vertices(&indices, 12);
        assert!(interior[0]);
        assert!(interior[1..].iter().all(|&i| !i), "{interior:?}");
    }

    #[test]
    fn round_small_is_round() {
        let mut cases = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4503599627370495.5,
            4503599627370497.0,
            -4503599627370495.5,
            (1u64 << 61) as f64 + 512.0,
            32767.0,
            -32766.5,
        ];
        let mut x = 0.123_456_789_f64;
        for _ in 0..10_000 {
            x = (x * 7919.0 + 0.3251).fract();
            cases.push((x - 0.5) * 1e12);
            cases.push((x - 0.5) * 65536.0);
            cases.push(((x - 0.5) * 1000.0).floor() + 0.5);
        }
        for c in cases {
            assert_eq!(super::round_small(c), c.round(), "{c:e}");
        }
    }

    #[test]
    fn large_meshes_keep_u32_indices() {
        let count = (1 << 16) + 3;
        let mesh = Mesh {
            positions: (0..count).map(|i| DVec3::new(i as f64, 0.0, 0.0)).collect(),
            normals: vec![DVec3::Z; count],
            indices: vec![0, 1, (count - 1) as u32],
        };
        let packed = PackedMesh::pack(&mesh);
        assert_eq!(packed.index(2), (count - 1) as u32);
        assert!(packed.heap_bytes() > count * 19);
        // A non-finite position is kept as it is, for the exporters to report.
        let mut bad = mesh.clone();
        bad.positions[1].y = f64::NAN;
        assert!(PackedMesh::pack(&bad).position(1).y.is_nan());
    }
}
