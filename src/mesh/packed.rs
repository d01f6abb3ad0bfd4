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

use glam::{DVec3, IVec3};
use rayon::prelude::*;

use super::Mesh;
use interior::interior_vertices;
pub use normal::OctNormal;
use normal::round_small;

mod interior;
mod normal;
#[cfg(test)]
mod tests;

/// Vertices per parallel task when packing a big patch (a head of 14 m has
/// some 8 000; most patches have a few hundred and pack on one thread).
const PARALLEL_VERTICES: usize = 4096;
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
