//! What a built model's derived data holds in memory, by kind: the figures behind
//! the memory row of `vesselcad bench`.
//!
//! Counts the heap bytes (by capacity) of the big derived components — patch
//! meshes, exact surfaces, (u, v) regions, openings — without the ECS's own
//! tables; the rest of a model's heap (parameters, frames, relations, entity
//! storage) is the caller's total minus these.

use std::collections::HashSet;
use std::mem::size_of;
use std::sync::Arc;

use bevy_ecs::world::World;
use glam::{DVec2, DVec3};

use crate::components::{Opening, PatchCavities, PatchMesh, PatchRegion, PatchSurface};
use crate::mesh::HostTrim;
use crate::nurbs::intersect::IntersectionLoop;

/// Heap bytes held by a model's derived data, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MemoryBreakdown {
    /// Patch meshes: positions, normals, indices (a mesh shared by equal
    /// patches counted once).
    pub meshes: usize,
    /// Vertices of the patches' meshes (shared ones counted per patch).
    pub vertices: usize,
    /// Triangles of the meshes.
    pub triangles: usize,
    /// Exact patch surfaces: control points and knots.
    pub surfaces: usize,
    /// Patch regions: the (u, v) loops meshed within, and the sampled sides kept
    /// for host patches (`components::HostSides`).
    pub regions: usize,
    /// Openings: intersection loops (3D points and (u, v) on both surfaces),
    /// notches, and the inputs each was cut from (with the canonical loops kept
    /// for openings in straight courses).
    pub openings: usize,
    /// Cavities kept from the last meshing of patches with openings
    /// (`PatchCavities`: their loops' (u, v) and triangles).
    pub cavities: usize,
    /// Patch entities.
    pub patches: usize,
    /// Distinct meshes the patches hold (equal patches share one).
    pub distinct_meshes: usize,
}

fn loop_bytes(l: &IntersectionLoop) -> usize {
    size_of::<IntersectionLoop>()
        + l.points.capacity() * size_of::<DVec3>()
        + (l.neck_uv.capacity() + l.host_uv.capacity()) * size_of::<DVec2>()
}

/// The breakdown of `world`'s derived data (shared data counted once).
pub(crate) fn breakdown(world: &World) -> MemoryBreakdown {
    let mut out = MemoryBreakdown::default();
    if let Some(mut q) = world.try_query::<&PatchMesh>() {
        // A mesh shared by equal patches is held once.
        let mut seen = HashSet::new();
        for m in q.iter(world) {
            if seen.insert(Arc::as_ptr(&m.0)) {
                out.meshes += m.0.heap_bytes();
                out.distinct_meshes += 1;
            }
            out.vertices += m.0.vertex_count();
            out.triangles += m.0.triangle_count();
        }
    }
    if let Some(mut q) = world.try_query::<&PatchSurface>() {
        for s in q.iter(world) {
            let surface = &s.0.surface;
            out.patches += 1;
            out.surfaces += size_of::<crate::parts::Patch>()
                + std::mem::size_of_val(surface.homogeneous_points())
                + (surface.u_knots().len() + surface.v_knots().len()) * size_of::<f64>();
        }
    }
    if let Some(mut q) = world.try_query::<&PatchRegion>() {
        for r in q.iter(world) {
            out.regions += size_of::<PatchRegion>();
            let Some(r) = &r.region else { continue };
            out.regions += size_of::<crate::mesh::cdt::Region>()
                + r.loops()
                    .map(|l| {
                        size_of::<crate::mesh::cdt::UvLoop>() + l.uv.capacity() * size_of::<DVec2>()
                    })
                    .sum::<usize>();
        }
    }
    if let Some(mut q) = world.try_query::<&PatchCavities>() {
        // Equal patches share one.
        let mut seen = HashSet::new();
        for c in q.iter(world) {
            if seen.insert(Arc::as_ptr(&c.0)) {
                out.cavities += c.0.heap_bytes();
            }
        }
    }
    if let Some(sides) = world.get_resource::<crate::components::HostSides>() {
        out.regions += sides.heap_bytes();
    }
    // Loops shared between openings, their pads' trims and the kept canonical
    // cuts are counted once.
    let mut seen = HashSet::new();
    if let Some(mut q) = world.try_query::<&Opening>() {
        for o in q.iter(world) {
            out.openings += size_of::<Opening>();
            let trim = o.pad_trim.iter().flat_map(|(a, b)| [a, b]);
            for l in std::iter::once(&o.curve).chain(o.pad.as_ref()).chain(trim) {
                if seen.insert(std::sync::Arc::as_ptr(l)) {
                    out.openings += loop_bytes(l);
                }
            }
            for (_, trim) in &o.hosts {
                out.openings += size_of::<(bevy_ecs::entity::Entity, HostTrim)>();
                if let HostTrim::Notches(n) = trim {
                    out.openings += n
                        .iter()
                        .map(|n| {
                            size_of::<crate::mesh::Notch>() + n.path.capacity() * size_of::<DVec2>()
                        })
                        .sum::<usize>();
                }
            }
        }
    }
    // The inputs each opening was cut from, with the canonical cuts kept for
    // straight courses.
    if let Some(mut q) = world.try_query::<&crate::components::OpeningInput>() {
        // Canonical cuts are shared by every opening cut from the same march.
        let mut cuts = std::collections::HashSet::new();
        for input in q.iter(world) {
            out.openings += size_of::<crate::components::OpeningInput>() + input.heap_bytes();
            let Some(cut) = input.axial() else {
                continue;
            };
            if !cuts.insert(cut as *const crate::mesh::AxialCut) {
                continue;
            }
            out.openings += size_of::<crate::mesh::AxialCut>();
            // The canonical loops, shared with the pad's trim when there is one.
            for l in cut.loops() {
                if seen.insert(Arc::as_ptr(l)) {
                    out.openings += loop_bytes(l);
                }
            }
        }
    }
    out
}
