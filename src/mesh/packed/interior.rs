//! Which vertices of a packed mesh are interior (on no edge a single triangle
//! uses): those get 32-bit positions, the boundary ones 40-bit.

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::PARALLEL_VERTICES;

/// For each of `count` vertices, whether it is used and on no edge that exactly
/// one triangle of `indices` uses (an edge is its two vertices, either way round).
///
/// Every triangle hands each of its vertices the other two, so the number of
/// times x appears in v's list is the number of triangles using the edge {v, x};
/// a vertex is interior when no neighbour appears exactly once. A short sort per
/// vertex (about a dozen entries) instead of a hash map of all edges. A triangle
/// naming a vertex twice uses an edge from that vertex to itself, which the lists
/// do not see: such meshes (never the mesher's) take the map.
pub(super) fn interior_vertices(indices: &[u32], count: usize) -> Vec<bool> {
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
pub(super) fn interior_vertices_by_edges(indices: &[u32], count: usize) -> Vec<bool> {
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
