//! Content-addressed sharing of patch meshes: patches that are the same surface,
//! trimmed by the same region and meshed to the same options get one mesh.
//!
//! The mesher is deterministic, so its output is a function of exactly those
//! inputs. In a plant, most of them repeat: every nozzle of one size, rating and
//! projection has the same flange faces, hub and rim in its own frame; every head
//! of one diameter and shape is the same in its part frame. The Tessellate stage
//! looks each dirty patch up here by [`mesh_key`] before meshing it, so a full
//! build meshes each distinct patch once, and an edit that makes a patch equal to
//! one already in the model (a head swapped to a shape some other vessel of that
//! diameter has, a flange moved to a projection another nozzle has) meshes
//! nothing. The table holds weak references: a mesh lives as long as a patch uses
//! it, and sharing never changes a byte of any mesh.

use super::key::Key;

use glam::DVec3;

use super::weak_table::WeakTable;
use crate::mesh::{PackedMesh, TessellationOptions};
use crate::parts::{Analytic, Patch};

/// A 128-bit key of everything the mesh of `patch` within the region with
/// fingerprint `region` at `options` depends on: the surface's key
/// ([`surface_key`]) and the region's fingerprint, as a `mesh::key::Key` (XXH3-128,
/// like [`Region::fingerprint`](crate::mesh::cdt::Region::fingerprint)):
/// different inputs collide with probability about 2⁻¹²⁸.
pub fn mesh_key(patch: &Patch, region: u128, options: &TessellationOptions) -> u128 {
    mesh_key_of(surface_key(patch, options), region)
}

/// [`mesh_key`] from the patch's [`surface_key`] (which the mesher also takes,
/// to tell whether kept cavities' screen verdicts hold).
pub fn mesh_key_of(surface: u128, region: u128) -> u128 {
    let mut key = Key::with_capacity(4);
    key.write_u128(surface);
    key.write_u128(region);
    key.finish()
}

/// A 128-bit key of everything a patch's mesh depends on but its region: the
/// surface's degrees, knots and homogeneous control points, the analytic
/// surface the probes measure against and the options, all by their exact bits
/// (a `mesh::key::Key`).
pub fn surface_key(patch: &Patch, options: &TessellationOptions) -> u128 {
    let s = &patch.surface;
    let mut key = Key::with_capacity(
        s.u_knots().as_slice().len()
            + s.v_knots().as_slice().len()
            + 4 * s.homogeneous_points().len()
            + 32,
    );
    let mut write = |x: u64| key.write(x);
    for knots in [s.u_knots(), s.v_knots()] {
        write(knots.degree() as u64);
        write(knots.as_slice().len() as u64);
        for k in knots.as_slice() {
            write(k.to_bits());
        }
    }
    for p in s.homogeneous_points() {
        for c in p.to_array() {
            write(c.to_bits());
        }
    }
    analytic_bits(&patch.analytic, &mut write);
    // Destructured, so that a new option cannot be left out of the key.
    let TessellationOptions {
        tolerance,
        angle_tolerance,
        max_edge_length,
        max_stretch,
        max_vertices,
    } = *options;
    let optional = |x: Option<f64>| x.map_or(u64::MAX, f64::to_bits);
    write(tolerance.to_bits());
    write(optional(angle_tolerance));
    write(optional(max_edge_length));
    write(optional(max_stretch));
    write(max_vertices as u64);
    key.finish()
}

/// Feeds the kind and every number of `analytic` to `write`.
fn analytic_bits(analytic: &Analytic, write: &mut impl FnMut(u64)) {
    let mut vector = |kind: u64, vectors: &[DVec3], scalars: &[f64]| {
        write(kind);
        for v in vectors {
            for c in v.to_array() {
                write(c.to_bits());
            }
        }
        for s in scalars {
            write(s.to_bits());
        }
    };
    match *analytic {
        Analytic::Plane { point, normal } => vector(0, &[point, normal], &[]),
        Analytic::Cylinder {
            point,
            axis,
            radius,
        } => vector(1, &[point, axis], &[radius]),
        Analytic::Cone {
            apex,
            axis,
            half_angle,
        } => vector(2, &[apex, axis], &[half_angle]),
        Analytic::ObliqueCone {
            apex,
            base_center,
            base_normal,
            radius,
        } => vector(3, &[apex, base_center, base_normal], &[radius]),
        Analytic::Sphere { center, radius } => vector(4, &[center], &[radius]),
        Analytic::Torus {
            center,
            axis,
            major,
            minor,
        } => vector(5, &[center, axis], &[major, minor]),
        Analytic::Spheroid {
            center,
            axis,
            equatorial,
            polar,
        } => vector(6, &[center, axis], &[equatorial, polar]),
        Analytic::Knuckled {
            center,
            axis,
            major,
            minor,
            seam,
            beyond,
        } => vector(7, &[center, axis], &[major, minor, seam, beyond]),
    }
}

/// The meshes in use, by [`mesh_key`]: weak references, so an entry dies with the
/// last patch using its mesh (dead entries are swept as the table grows).
pub type MeshInstances = WeakTable<PackedMesh>;

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::mesh::cdt::Region;
    use crate::parts::heads::{Head, HeadKind};

    fn crown(od: f64) -> Patch {
        let patches = Head::new(od, HeadKind::TWO_TO_ONE)
            .patches()
            .expect("a valid head");
        patches[0].clone()
    }

    #[test]
    fn keys_follow_every_input() {
        let options = TessellationOptions::chord(1.0);
        let a = crown(2000.0);
        let region = Region::rectangle(&a.surface).fingerprint();
        let key = mesh_key(&a, region, &options);
        assert_eq!(key, mesh_key(&crown(2000.0), region, &options));
        assert_ne!(key, mesh_key(&crown(2000.000001), region, &options));
        assert_ne!(key, mesh_key(&a, region ^ 1, &options));
        assert_ne!(key, mesh_key(&a, region, &TessellationOptions::chord(0.5)));
        let mut moved = a.clone();
        if let Analytic::Spheroid { center, .. } = &mut moved.analytic {
            center.z += 1e-9;
        }
        assert_ne!(key, mesh_key(&moved, region, &options));
    }

    #[test]
    fn entries_live_as_long_as_a_patch_holds_the_mesh() {
        let mut table = MeshInstances::default();
        let mesh = Arc::new(PackedMesh::pack(&crate::mesh::Mesh::default()));
        table.insert(7, &mesh);
        assert!(Arc::ptr_eq(&table.get(7).expect("held"), &mesh));
        drop(mesh);
        assert!(table.get(7).is_none());
        assert!(table.get(8).is_none());
    }
}
