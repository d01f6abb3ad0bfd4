//! Compact storage of a finished patch mesh: what the model keeps (in
//! `PatchMesh`) and the exporters read, between the mesher's working [`Mesh`] and
//! the `f32` buffers of a glTF file.
//!
//! A plant of 10 000 vessels holds about a hundred million mesh vertices, so the
//! layout matters. Positions stay exact `f64` mm (neighbouring patches share
//! their edge vertices bit for bit, and the chordal bound is checked on them);
//! normals are octahedral-encoded in two signed 16-bit numbers (4 bytes instead
//! of 24; the decoded unit normal is within 5e-5 rad of the exact one, far below
//! what a viewer or a drawing can show); indices are `u16` when the patch has at
//! most 65 536 vertices, else `u32`. Packing is deterministic, so the
//! incremental model and a direct full build export the same bytes.

use glam::{DVec2, DVec3};

use super::Mesh;

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
        let q = |x: f64| (x.clamp(-1.0, 1.0) * SNORM16).round() as i16;
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

/// A finished patch mesh in compact form (see the module docs): exact positions,
/// octahedral normals, the narrowest indices.
#[derive(Clone, Debug, PartialEq)]
pub struct PackedMesh {
    positions: Box<[DVec3]>,
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
        let normals = mesh.normals.iter().map(|&n| OctNormal::encode(n)).collect();
        let indices = if mesh.positions.len() <= 1 << 16 {
            Indices::U16(mesh.indices.iter().map(|&i| i as u16).collect())
        } else {
            Indices::U32(mesh.indices.clone().into_boxed_slice())
        };
        // A mesh with an index out of range (never produced by the mesher) keeps
        // it visible to the exporters' checks: u32 storage.
        let indices = match indices {
            Indices::U16(_)
                if mesh
                    .indices
                    .iter()
                    .any(|&i| i as usize >= mesh.positions.len()) =>
            {
                Indices::U32(mesh.indices.clone().into_boxed_slice())
            }
            other => other,
        };
        Self {
            positions: mesh.positions.clone().into_boxed_slice(),
            normals,
            indices,
        }
    }

    /// The mesher's form again: positions, decoded normals, `u32` indices.
    pub fn unpack(&self) -> Mesh {
        Mesh {
            positions: self.positions.to_vec(),
            normals: self.normals.iter().map(|n| n.decode()).collect(),
            indices: self.indices().collect(),
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
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

    /// Vertex positions, mm, in the patch's part-local frame.
    pub fn positions(&self) -> &[DVec3] {
        &self.positions
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
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }

    /// Heap bytes held, with the struct itself.
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + std::mem::size_of_val(&*self.positions)
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
    fn octahedral_normals_round_trip_within_5e_5_rad() {
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
        assert!(worst < 5e-5, "{worst}");
        assert!(OctNormal::encode(DVec3::ZERO).decode().is_nan());
        assert!(OctNormal::encode(DVec3::NAN).decode().is_nan());
    }

    #[test]
    fn packing_keeps_positions_and_indices_exactly() {
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
            indices: vec![0, 1, 2, 2, 1, 0],
        };
        let packed = PackedMesh::pack(&mesh);
        assert_eq!(packed.positions(), &mesh.positions[..]);
        assert_eq!(packed.indices().collect::<Vec<_>>(), mesh.indices);
        assert_eq!(
            packed.triangles().collect::<Vec<_>>(),
            [[0, 1, 2], [2, 1, 0]]
        );
        let back = packed.unpack();
        for (a, b) in back.normals.iter().zip(&mesh.normals) {
            assert!(a.angle_between(*b) < 5e-5);
        }
        assert_eq!(packed.bounds(), mesh.bounds());
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
        assert!(packed.heap_bytes() > count * 28);
    }
}
