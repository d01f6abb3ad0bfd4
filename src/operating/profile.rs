//! The meridian profile of a vessel's pressure envelope — the inside surface or
//! the wall's mid-surface — as exact pieces in the (radius, axial position) plane
//! of the vessel frame.
//!
//! First step of the operating figures: [`super::liquid`] integrates circular
//! cross-sections over the inside profile, [`super::weight`] integrates the
//! mid-surface times the wall thickness. Every course, reducer and head is a
//! surface of revolution about the vessel axis, so its profile is a few lines and
//! conic arcs, here in closed form (no NURBS evaluation on the hot path).
//!
//! The inside of a part of outside radius R and wall thickness t (depth d = t for
//! the inside, t/2 for the mid-surface): courses at R − d; reducers offset by d
//! normal to the cone; spheres, knuckle tori and cones are their exact offsets
//! (radii reduced by d about the same centres, cones parallel); an ellipsoidal
//! head's inside is the ellipsoid with both semi-axes reduced by d (the usual
//! convention of a head specified on its inside diameter); a plain flat plate's
//! thickness lies outside the tangent line.
//!
//! Parts above an eccentric reducer stand on an axis shifted sideways: each piece
//! carries the centre of its cross-sections ([`Lateral`]), constant on a course
//! or head, moving linearly along an eccentric reducer (whose cross-sections
//! are circles on the line joining its end centres; its inside and mid-surfaces
//! are taken on the same centre line, within the wall's thickness times the
//! reducer's slope of the exact offset).

use std::f64::consts::FRAC_PI_2;

use glam::{DAffine3, DVec2, DVec3};

use super::OperatingError;
use crate::parts::PartGeometry;
use crate::parts::ReducerAlignment;
use crate::parts::heads::HeadKind;

/// One smooth, axially monotone piece of a profile.
///
/// `Line`: from `(r0, z0)` to `(r1, z1)` for s ∈ [0, 1]. `Arc`: r = rc + a cos s,
/// z = zc + b sin s for s ∈ [from, to] ⊂ [0, π/2] (a circle when |a| = |b|, an
/// ellipse otherwise; `b` is negative on a head turned over).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Piece {
    /// A straight segment.
    Line {
        /// Start radius, mm.
        r0: f64,
        /// Start axial position, mm.
        z0: f64,
        /// End radius, mm.
        r1: f64,
        /// End axial position, mm.
        z1: f64,
    },
    /// A quarter (or less) of a circle or an axis-aligned ellipse.
    Arc {
        /// Centre radius, mm.
        rc: f64,
        /// Centre axial position, mm.
        zc: f64,
        /// Radial semi-axis, mm.
        a: f64,
        /// Axial semi-axis, mm (signed).
        b: f64,
        /// Start angle, radians.
        from: f64,
        /// End angle, radians.
        to: f64,
    },
}

impl Piece {
    /// Parameter range.
    pub fn range(&self) -> (f64, f64) {
        match *self {
            Piece::Line { .. } => (0.0, 1.0),
            Piece::Arc { from, to, .. } => (from, to),
        }
    }

    /// (radius, axial position) at parameter `s`.
    pub fn point(&self, s: f64) -> (f64, f64) {
        match *self {
            Piece::Line { r0, z0, r1, z1 } => (r0 + (r1 - r0) * s, z0 + (z1 - z0) * s),
            Piece::Arc { rc, zc, a, b, .. } => (rc + a * s.cos(), zc + b * s.sin()),
        }
    }

    /// d(radius, axial position)/ds.
    pub fn derivative(&self, s: f64) -> (f64, f64) {
        match *self {
            Piece::Line { r0, z0, r1, z1 } => (r1 - r0, z1 - z0),
            Piece::Arc { a, b, .. } => (-a * s.sin(), b * s.cos()),
        }
    }

    /// The parameter where the axial position is `z`, clamped to the range (the
    /// piece is monotone in z).
    pub fn at_z(&self, z: f64) -> f64 {
        let (s0, s1) = self.range();
        let s = match *self {
            Piece::Line { z0, z1, .. } => {
                if z1 == z0 {
                    return s0;
                }
                (z - z0) / (z1 - z0)
            }
            Piece::Arc { zc, b, .. } => ((z - zc) / b).clamp(-1.0, 1.0).asin(),
        };
        s.clamp(s0.min(s1), s0.max(s1))
    }

    /// The parameter where the radius is `r`, clamped to the range (the piece is
    /// monotone in r).
    pub fn at_r(&self, r: f64) -> f64 {
        let (s0, s1) = self.range();
        let s = match *self {
            Piece::Line { r0, r1, .. } => {
                if r1 == r0 {
                    return s0;
                }
                (r - r0) / (r1 - r0)
            }
            Piece::Arc { rc, a, .. } => ((r - rc) / a).clamp(-1.0, 1.0).acos(),
        };
        s.clamp(s0.min(s1), s0.max(s1))
    }

    /// The piece with its axial positions mapped by z ↦ `offset` + `scale` z.
    fn mapped(self, offset: f64, scale: f64) -> Piece {
        match self {
            Piece::Line { r0, z0, r1, z1 } => Piece::Line {
                r0,
                z0: offset + scale * z0,
                r1,
                z1: offset + scale * z1,
            },
            Piece::Arc {
                rc,
                zc,
                a,
                b,
                from,
                to,
            } => Piece::Arc {
                rc,
                zc: offset + scale * zc,
                a,
                b: scale * b,
                from,
                to,
            },
        }
    }
}

/// A part of the stack as the operating figures need it.
#[derive(Clone, Copy, Debug)]
pub struct StackPart<'a> {
    /// Part id (for errors).
    pub id: &'a str,
    /// Resolved parameters.
    pub geometry: &'a PartGeometry,
    /// Part frame → vessel frame.
    pub frame: DAffine3,
    /// Wall thickness, mm (0 when the design gives none).
    pub thickness: f64,
}

/// Where the cross-sections of a piece are centred, in the vessel frame's
/// (x, y): `origin + slope · z` at axial position z.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lateral {
    /// The centre the line reaches at z = 0, mm.
    pub origin: DVec2,
    /// Change of the centre per mm of z.
    pub slope: DVec2,
}

impl Lateral {
    /// The centre of the cross-section at axial position `z`, mm.
    pub fn at(&self, z: f64) -> DVec2 {
        self.origin + self.slope * z
    }

    /// The line through the points `a` and `b` of the vessel frame (`b` higher).
    fn through(a: DVec3, b: DVec3) -> Lateral {
        let dz = b.z - a.z;
        if dz.abs() <= f64::EPSILON * (a.z.abs() + b.z.abs()) {
            return Lateral {
                origin: a.truncate(),
                slope: DVec2::ZERO,
            };
        }
        let slope = (b - a).truncate() / dz;
        Lateral {
            origin: a.truncate() - slope * a.z,
            slope,
        }
    }
}

/// A profile: its pieces with the wall thickness of the part each belongs to.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Profile {
    /// The pieces and their part's wall thickness, mm.
    pub pieces: Vec<(Piece, f64)>,
    /// The centre line of each piece's cross-sections (same order as `pieces`).
    pub centres: Vec<Lateral>,
}

impl Profile {
    /// The centre line of piece `k` (on the axis if none was recorded).
    pub fn centre(&self, k: usize) -> Lateral {
        self.centres.get(k).copied().unwrap_or_default()
    }

    /// Lowest and highest axial positions, mm.
    pub fn axial_extent(&self) -> (f64, f64) {
        self.pieces
            .iter()
            .flat_map(|(p, _)| {
                let (s0, s1) = p.range();
                [p.point(s0).1, p.point(s1).1]
            })
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), z| {
                (lo.min(z), hi.max(z))
            })
    }

    /// Largest radius, mm.
    pub fn max_radius(&self) -> f64 {
        self.pieces
            .iter()
            .flat_map(|(p, _)| {
                let (s0, s1) = p.range();
                [p.point(s0).0, p.point(s1).0]
            })
            .fold(0.0, f64::max)
    }
}

/// Which surface of the wall a profile follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surface {
    /// The inside surface (offset by the full thickness).
    Inside,
    /// The mid-surface (offset by half the thickness).
    Middle,
}

/// The profile of the stack (courses, reducers, heads) of a vessel; other parts
/// are skipped. `horizontal`: an eccentric reducer is refused (its cross-sections
/// are off the axis, which changes a horizontal vessel's liquid volume).
///
/// # Errors
///
/// [`OperatingError::ThickWall`] when a wall is too thick for its part's shape
/// (a knuckle or ellipsoid semi-axis not larger than the thickness), and
/// [`OperatingError::Eccentric`] for an eccentric reducer in a horizontal vessel.
pub fn stack_profile(
    stack: &[StackPart],
    surface: Surface,
    horizontal: bool,
) -> Result<Profile, OperatingError> {
    let mut out = Profile::default();
    for part in stack {
        let d = match surface {
            Surface::Inside => part.thickness,
            Surface::Middle => part.thickness / 2.0,
        };
        let thick = |what: &'static str, size: f64| OperatingError::ThickWall {
            part: part.id.to_string(),
            what,
            size,
            thickness: part.thickness,
        };
        let mut local = Vec::new();
        match part.geometry {
            PartGeometry::Shell(s) => {
                let r = s.outside_diameter / 2.0 - d;
                if r <= 0.0 {
                    return Err(thick("outside radius", s.outside_diameter / 2.0));
                }
                local.push(Piece::Line {
                    r0: r,
                    z0: 0.0,
                    r1: r,
                    z1: s.length,
                });
            }
            PartGeometry::Reducer(c) => {
                if horizontal && matches!(c.alignment, ReducerAlignment::Eccentric { .. }) {
                    return Err(OperatingError::Eccentric {
                        part: part.id.to_string(),
                    });
                }
                let (large, small) = (c.large_diameter / 2.0, c.small_diameter / 2.0);
                let radial = d * (1.0 + ((large - small) / c.length).powi(2)).sqrt();
                if small - radial <= 0.0 {
                    return Err(thick("small-end radius", small));
                }
                local.push(Piece::Line {
                    r0: large - radial,
                    z0: 0.0,
                    r1: small - radial,
                    z1: c.length,
                });
            }
            PartGeometry::Head(h) => {
                head_pieces(
                    h.outside_diameter / 2.0,
                    h.straight_flange,
                    h.kind,
                    d,
                    &mut local,
                )
                .map_err(|(what, size)| thick(what, size))?;
            }
            _ => continue,
        }
        let offset = part.frame.translation.z;
        let scale = part.frame.matrix3.z_axis.z;
        // Cross-sections centred on the part's axis, or on the line joining an
        // eccentric reducer's end centres.
        let top = match part.geometry {
            PartGeometry::Reducer(c) => c.small_end_center(),
            _ => DVec3::Z,
        };
        let centre = Lateral::through(
            part.frame.transform_point3(DVec3::ZERO),
            part.frame.transform_point3(top),
        );
        out.centres.extend(std::iter::repeat_n(centre, local.len()));
        out.pieces.extend(
            local
                .into_iter()
                .map(|p| (p.mapped(offset, scale), part.thickness)),
        );
    }
    Ok(out)
}

/// The pieces of a head of outside radius `r` offset inwards by `d`, in the
/// head's local frame (open end at z = 0, dome towards +z). On failure, the shape
/// size that is not larger than `d`.
fn head_pieces(
    r: f64,
    flange: f64,
    kind: HeadKind,
    d: f64,
    out: &mut Vec<Piece>,
) -> Result<(), (&'static str, f64)> {
    let ri = r - d;
    if ri <= 0.0 {
        return Err(("outside radius", r));
    }
    if flange > 0.0 {
        out.push(Piece::Line {
            r0: ri,
            z0: 0.0,
            r1: ri,
            z1: flange,
        });
    }
    let z0 = flange;
    let arc = |rc, zc, radius, from, to| Piece::Arc {
        rc,
        zc,
        a: radius,
        b: radius,
        from,
        to,
    };
    match kind {
        HeadKind::Hemispherical => out.push(arc(0.0, z0, ri, 0.0, FRAC_PI_2)),
        HeadKind::Ellipsoidal { ratio } => {
            let depth = r / ratio;
            if depth <= d {
                return Err(("depth", depth));
            }
            out.push(Piece::Arc {
                rc: 0.0,
                zc: z0,
                a: ri,
                b: depth - d,
                from: 0.0,
                to: FRAC_PI_2,
            });
        }
        HeadKind::Torispherical {
            crown_radius,
            knuckle_radius,
        } => {
            if knuckle_radius <= d {
                return Err(("knuckle radius", knuckle_radius));
            }
            let major = r - knuckle_radius;
            let offset = ((crown_radius - knuckle_radius).powi(2) - major.powi(2)).sqrt();
            let joint = FRAC_PI_2 - (major / (crown_radius - knuckle_radius)).asin();
            out.push(arc(major, z0, knuckle_radius - d, 0.0, joint));
            out.push(arc(0.0, z0 - offset, crown_radius - d, joint, FRAC_PI_2));
        }
        HeadKind::Toriconical {
            half_angle,
            knuckle_radius,
        } => {
            if knuckle_radius <= d {
                return Err(("knuckle radius", knuckle_radius));
            }
            let alpha = half_angle.to_radians();
            let major = r - knuckle_radius;
            let k = knuckle_radius - d;
            out.push(arc(major, z0, k, 0.0, alpha));
            let (er, ez) = (major + k * alpha.cos(), z0 + k * alpha.sin());
            out.push(Piece::Line {
                r0: er,
                z0: ez,
                r1: 0.0,
                z1: ez + er / alpha.tan(),
            });
        }
        HeadKind::Conical {
            half_angle,
            small_diameter,
        } => {
            let alpha = half_angle.to_radians();
            let apex = z0 + ri / alpha.tan();
            if small_diameter > 0.0 {
                // The small-end plate's inside face, d below its outside face.
                let top = z0 + (r - small_diameter / 2.0) / alpha.tan() - d;
                let r_top = ri - (top - z0) * alpha.tan();
                if top > z0 && r_top > 0.0 {
                    out.push(Piece::Line {
                        r0: ri,
                        z0,
                        r1: r_top,
                        z1: top,
                    });
                    out.push(Piece::Line {
                        r0: r_top,
                        z0: top,
                        r1: 0.0,
                        z1: top,
                    });
                    return Ok(());
                }
            }
            out.push(Piece::Line {
                r0: ri,
                z0,
                r1: 0.0,
                z1: apex,
            });
        }
        HeadKind::Flat { knuckle_radius } => {
            let mut plate_z = z0;
            if knuckle_radius > 0.0 {
                if knuckle_radius <= d {
                    return Err(("knuckle radius", knuckle_radius));
                }
                let k = knuckle_radius - d;
                out.push(arc(r - knuckle_radius, z0, k, 0.0, FRAC_PI_2));
                plate_z = z0 + k;
            }
            let plate_r = if knuckle_radius > 0.0 {
                r - knuckle_radius
            } else {
                ri
            };
            out.push(Piece::Line {
                r0: plate_r,
                z0: plate_z,
                r1: 0.0,
                z1: plate_z,
            });
        }
    }
    Ok(())
}
