//! The occluder of one view: every triangle of a vessel's meshes projected onto the
//! view plane, with its depth, binned in a uniform 2D grid.
//!
//! Rays of an orthographic view are parallel, so "is this point hidden?" is a 2D
//! lookup: the grid cell under the point lists the triangles whose projection may
//! cover it; the point is hidden when one of them covers it and lies nearer the
//! viewer, by more than the depth tolerance, at that spot (barycentric depth). The
//! grid is rebuilt when any mesh of the vessel changes (binning is linear in the
//! triangle count); the expensive part, classifying lines, stays per entity.

use glam::{DAffine3, DVec2, DVec3};

use super::Projection;
use crate::mesh::Mesh;

/// A projected triangle, ready for point tests: its first corner, the inverse of
/// its edge matrix (view point → barycentric coordinates of the second and third
/// corners), its corners' depths and the nearest of them.
#[derive(Clone, Copy, Debug)]
struct Facet {
    a: DVec2,
    inverse: [f64; 4],
    depths: [f64; 3],
    nearest: f64,
}

impl Facet {
    fn new([a, b, c]: [DVec3; 3]) -> Self {
        let (e1, e2) = ((b - a).truncate(), (c - a).truncate());
        let det = e1.perp_dot(e2);
        Facet {
            a: a.truncate(),
            inverse: [e2.y / det, -e2.x / det, -e1.y / det, e1.x / det],
            depths: [a.z, b.z, c.z],
            nearest: a.z.max(b.z).max(c.z),
        }
    }

    /// Whether the triangle covers `p` and lies nearer than `depth` there.
    fn hides(&self, p: DVec2, depth: f64) -> bool {
        // Behind everywhere: most of a cell's triangles (the far side).
        if self.nearest <= depth {
            return false;
        }
        let d = p - self.a;
        let [m0, m1, m2, m3] = self.inverse;
        let wb = m0 * d.x + m1 * d.y;
        let wc = m2 * d.x + m3 * d.y;
        let wa = 1.0 - wb - wc;
        const INSIDE: f64 = -1e-12;
        wa >= INSIDE
            && wb >= INSIDE
            && wc >= INSIDE
            && wa * self.depths[0] + wb * self.depths[1] + wc * self.depths[2] > depth
    }
}

/// Projected triangles of a vessel in one view, binned in a grid.
#[derive(Clone, Debug, Default)]
pub struct Occluder {
    /// Triangles in view coordinates.
    facets: Vec<Facet>,
    /// Lower-left corner of the grid.
    origin: DVec2,
    /// Cell side, mm.
    cell: f64,
    /// Cells across and up.
    size: (usize, usize),
    /// CSR: triangle indices of cell `c` are `items[starts[c]..starts[c + 1]]`.
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl Occluder {
    /// Bins the triangles of `meshes` (each with its part → vessel frame) as seen
    /// through `projection`.
    pub fn build<'a>(
        projection: &Projection,
        meshes: impl Iterator<Item = (&'a Mesh, DAffine3)>,
    ) -> Occluder {
        let mut triangles = Vec::new();
        for (mesh, frame) in meshes {
            let view: Vec<DVec3> = mesh
                .positions
                .iter()
                .map(|&p| {
                    let q = frame.transform_point3(p);
                    let xy = projection.project(q);
                    DVec3::new(xy.x, xy.y, projection.depth(q))
                })
                .collect();
            for t in mesh.indices.chunks_exact(3) {
                let tri = [
                    view[t[0] as usize],
                    view[t[1] as usize],
                    view[t[2] as usize],
                ];
                // Edge-on triangles cover nothing.
                let area = (tri[1] - tri[0])
                    .truncate()
                    .perp_dot((tri[2] - tri[0]).truncate());
                if area.abs() > 1e-12 {
                    triangles.push(tri);
                }
            }
        }
        if triangles.is_empty() {
            return Occluder::default();
        }
        let (mut lo, mut hi) = (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN));
        for t in &triangles {
            for p in t {
                lo = lo.min(p.truncate());
                hi = hi.max(p.truncate());
            }
        }
        let extent = (hi - lo).max(DVec2::splat(1e-9));
        let target = (triangles.len() as f64).clamp(1.0, 4.0e6);
        let cell = (extent.x * extent.y / target)
            .sqrt()
            .max(extent.max_element() / 4096.0);
        let size = (
            ((extent.x / cell).floor() as usize + 1).max(1),
            ((extent.y / cell).floor() as usize + 1).max(1),
        );
        let mut occluder = Occluder {
            facets: Vec::new(),
            origin: lo,
            cell,
            size,
            starts: Vec::new(),
            items: Vec::new(),
        };
        let mut counts = vec![0u32; size.0 * size.1 + 1];
        for t in &triangles {
            occluder.for_cells(t, |c| counts[c] += 1);
        }
        let mut starts = Vec::with_capacity(counts.len());
        let mut total = 0u32;
        for c in &counts {
            starts.push(total);
            total += c;
        }
        let mut fill = starts.clone();
        let mut items = vec![0u32; total as usize];
        for (i, t) in triangles.iter().enumerate() {
            occluder.for_cells(t, |c| {
                items[fill[c] as usize] = i as u32;
                fill[c] += 1;
            });
        }
        occluder.starts = starts;
        occluder.items = items;
        occluder.facets = triangles.into_iter().map(Facet::new).collect();
        occluder
    }

    /// Cell coordinates of a view point, clamped to the grid.
    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.origin) / self.cell;
        (
            (q.x.max(0.0) as usize).min(self.size.0 - 1),
            (q.y.max(0.0) as usize).min(self.size.1 - 1),
        )
    }

    /// Calls `f` with every cell index the triangle's bounds touch.
    fn for_cells(&self, t: &[DVec3; 3], mut f: impl FnMut(usize)) {
        let lo = t[0].truncate().min(t[1].truncate()).min(t[2].truncate());
        let hi = t[0].truncate().max(t[1].truncate()).max(t[2].truncate());
        let (i0, j0) = self.cell_of(lo);
        let (i1, j1) = self.cell_of(hi);
        for j in j0..=j1 {
            for i in i0..=i1 {
                f(j * self.size.0 + i);
            }
        }
    }

    /// Whether the view point `p` at `depth` is hidden: some triangle covers `p`
    /// and is nearer the viewer there by more than `tolerance`.
    pub fn hides(&self, p: DVec2, depth: f64, tolerance: f64) -> bool {
        if self.facets.is_empty() {
            return false;
        }
        let q = (p - self.origin) / self.cell;
        if q.x < 0.0 || q.y < 0.0 || q.x >= self.size.0 as f64 || q.y >= self.size.1 as f64 {
            return false;
        }
        let c = (q.y as usize) * self.size.0 + q.x as usize;
        let range = self.starts[c] as usize..self.starts[c + 1] as usize;
        let behind = depth + tolerance;
        self.items[range]
            .iter()
            .any(|&i| self.facets[i as usize].hides(p, behind))
    }

    /// Number of triangles binned.
    pub fn triangle_count(&self) -> usize {
        self.facets.len()
    }
}
