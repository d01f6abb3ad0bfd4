//! Which vertices of a mesh a compact glTF file writes, and in what order:
//! vertices written the same are welded into one, and for meshopt compression
//! the triangles go in vertex-cache order and the vertices in first-use order.
//!
//! Part of the glTF writer, between [`super::gltf_encoding`] (which decides how
//! a mesh's positions and normals are written, and calls this) and the bytes of
//! its streams. A patch mesh repeats the vertices of a periodic surface's seam,
//! and a mesh merged per part, vessel or plant (`--granularity`) repeats every
//! vertex its patches share along their boundaries; a compact file writes each
//! of them once. Two vertices are welded when they would be written the same:
//! equal positions (the same quantized integers, or the same `f32` metres) and
//! equal normals (the same normalized bytes, or the same octahedral code, from
//! which the `f32` normal is made). Welding changes no number the file holds, so
//! the chordal bound and the shading are what they were, and a crease (a
//! nozzle's neck meeting its shell) keeps a vertex per side. Triangles keep their count and their corners' positions (a
//! sliver whose corners quantize to one point keeps its place, as it would
//! without welding). The plain file (`f32`, no compression) is written as the
//! mesh is.

use rustc_hash::FxHashMap;

use crate::mesh::PackedMesh;

/// The vertices written and the triangles over them.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct WrittenVertices {
    /// The mesh's index of each written vertex, in written order.
    pub kept: Vec<u32>,
    /// The triangles, three indices each, into the written vertices.
    pub indices: Vec<u32>,
}

/// The vertices of `mesh` with equal `key` (what is written of them) welded
/// into the first of them, in the mesh's order.
pub(super) fn weld<K>(mesh: &PackedMesh, key: impl Fn(usize) -> K) -> WrittenVertices
where
    K: std::hash::Hash + Eq,
{
    let count = mesh.vertex_count();
    let mut first: FxHashMap<K, u32> =
        FxHashMap::with_capacity_and_hasher(count, Default::default());
    let mut kept = Vec::with_capacity(count);
    let mut welded = Vec::with_capacity(count);
    for v in 0..count {
        let next = kept.len() as u32;
        let at = *first.entry(key(v)).or_insert(next);
        if at == next {
            kept.push(v as u32);
        }
        welded.push(at);
    }
    // A mesh is checked before it is encoded: every index is in range.
    let indices = mesh.indices().map(|i| welded[i as usize]).collect();
    WrittenVertices { kept, indices }
}

impl WrittenVertices {
    /// The same vertices and triangles in the order meshopt compresses best:
    /// triangles in vertex-cache order (meshoptimizer's `optimizeVertexCache`),
    /// vertices in the order the triangles first use them
    /// (`optimizeVertexFetchRemap`); vertices no triangle uses go last, in order.
    pub fn cache_ordered(self) -> Self {
        let count = self.kept.len();
        let indices = meshopt::optimize_vertex_cache(&self.indices, count);
        let remap = meshopt::optimize_vertex_fetch_remap(&indices, count);
        let mut next = remap.iter().filter(|&&r| r != u32::MAX).count() as u32;
        let remap: Vec<u32> = remap
            .into_iter()
            .map(|r| {
                if r == u32::MAX {
                    next += 1;
                    next - 1
                } else {
                    r
                }
            })
            .collect();
        let mut kept = vec![0u32; count];
        for (old, &new) in remap.iter().enumerate() {
            kept[new as usize] = self.kept[old];
        }
        let indices = indices.into_iter().map(|i| remap[i as usize]).collect();
        Self { kept, indices }
    }
}
