//! Measures of a part from its exact patches: surface area and enclosed volume.
//!
//! These sit after the part builders in the data flow and read only the patches'
//! NURBS surfaces (never the parameters), so they check the geometry independently
//! of the closed-form formulas for each kind of part: the integrals are
//! [`NurbsSurface::area`](crate::nurbs::NurbsSurface::area) and
//! [`NurbsSurface::volume_integral`](crate::nurbs::NurbsSurface::volume_integral),
//! accurate to about 1e-13 relative.

use super::Patch;

/// Total area of the patches, mm².
pub fn surface_area(patches: &[Patch]) -> f64 {
    patches.iter().map(|p| p.surface.area()).sum()
}

/// Volume enclosed by the patches of a part that is open only at the plane z = 0,
/// with the origin on its axis there (a head in its local frame), mm³.
///
/// The patches' normals must point outward. The volume is the flux of the field x/3
/// (divergence 1) out of the closed surface made of the patches and the disk that
/// closes the open end. On that disk x lies in the plane z = 0 and the normal is −Z,
/// so x · n = 0 and the disk contributes nothing: the sum of the patches'
/// [`volume_integral`](crate::nurbs::NurbsSurface::volume_integral)s is the volume.
///
/// For a part open elsewhere too (a shell course, a reducer: open at z = length) the
/// result lacks the flux through that opening, (length / 3) × its area.
pub fn enclosed_volume(patches: &[Patch]) -> f64 {
    patches.iter().map(|p| p.surface.volume_integral()).sum()
}
