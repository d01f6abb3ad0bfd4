//! Developed sizes of the rolled and formed parts as the BOM and the traveler
//! print them, and the wall metal of each pressure part.
//!
//! The BOM takes plates and head blanks from the plate layout (`fab::develop`,
//! `fab::plates`); these closed forms of the mid-surface are its fallback for
//! a part the development leaves out and for supports:
//! a course develops to a rectangle π·D_mid × length; a cone (reducer or
//! skirt) to an annular sector of slant length s between mid radii r₁, r₂
//! (area π·(r₁ + r₂)·s); a head's blank is the disc of the mid-surface's area
//! (equal-area rule, no forming allowance). [`developed`] is the one function
//! the BOM calls for them.
//!
//! Wall masses are the weight model's: the mid-surface of each part alone
//! (`operating::profile`) times its thickness, integrated as
//! `operating::weight::walls` does, so the pressure parts' masses add up to
//! `Weights::walls` exactly.

use std::f64::consts::PI;

use crate::operating::profile::{StackPart, Surface, stack_profile};
use crate::operating::weight::walls;
use crate::parts::PartGeometry;

/// mm³ → m³.
const MM3_TO_M3: f64 = 1e-9;

/// How a part is made from plate.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub enum Developed {
    /// A rolled course: a rectangle `width` (circumference at mid-thickness) ×
    /// `length`, rolled to `rolling_radius` (mid-thickness).
    Rectangle {
        /// Developed width, mm.
        width: f64,
        /// Course length, mm.
        length: f64,
        /// Rolling radius (mid-thickness), mm.
        rolling_radius: f64,
    },
    /// A rolled cone: an annular sector of radii `inner`, `outer` and angle
    /// `angle` degrees.
    Sector {
        /// Inner radius of the sector, mm.
        inner: f64,
        /// Outer radius of the sector, mm.
        outer: f64,
        /// Sector angle, degrees.
        angle: f64,
        /// Mean rolling radius (mid-thickness), mm.
        rolling_radius: f64,
    },
    /// A rolled eccentric reducer's plate (an oblique cone's development):
    /// its bounding box laid like a sector, and its developed angle.
    Oblique {
        /// Bounding width, mm.
        width: f64,
        /// Bounding height, mm.
        height: f64,
        /// Developed angle, degrees.
        angle: f64,
        /// Mean rolling radius (mid-thickness), mm.
        rolling_radius: f64,
    },
    /// A formed head's blank disc.
    Blank {
        /// Blank diameter, mm.
        diameter: f64,
    },
}

impl Developed {
    /// The size as the BOM prints it.
    pub fn label(&self) -> String {
        match self {
            Developed::Rectangle { width, length, .. } => format!("{width:.0} × {length:.0}"),
            Developed::Sector {
                inner,
                outer,
                angle,
                ..
            } => format!("sector R{outer:.0}/R{inner:.0} × {angle:.1}°"),
            Developed::Oblique {
                width,
                height,
                angle,
                ..
            } => format!("oblique cone {width:.0} × {height:.0}, {angle:.1}°"),
            Developed::Blank { diameter } => format!("blank Ø{diameter:.0}"),
        }
    }

    /// Rolling radius, mm (none for a head blank).
    pub fn rolling_radius(&self) -> Option<f64> {
        match self {
            Developed::Rectangle { rolling_radius, .. }
            | Developed::Sector { rolling_radius, .. }
            | Developed::Oblique { rolling_radius, .. } => Some(*rolling_radius),
            Developed::Blank { .. } => None,
        }
    }
}

/// Annular sector of a frustum of mid radii `r1`, `r2` and slant `s`.
fn sector(r1: f64, r2: f64, s: f64) -> Developed {
    let (small, large) = (r1.min(r2), r1.max(r2));
    if large - small <= 1e-12 * large.max(1.0) {
        return Developed::Rectangle {
            width: 2.0 * PI * large,
            length: s,
            rolling_radius: large,
        };
    }
    let outer = large * s / (large - small);
    Developed::Sector {
        inner: outer - s,
        outer,
        angle: (2.0 * PI * large / outer).to_degrees(),
        rolling_radius: 0.5 * (small + large),
    }
}

/// The developed plate of a part of wall `thickness` mm, and its mid-surface
/// area, mm²; `None` for parts not made from rolled or formed plate (saddles,
/// legs, lugs, boots are weighed as supports).
pub fn developed(geometry: &PartGeometry, thickness: f64) -> Option<(Developed, f64)> {
    let d = thickness / 2.0;
    Some(match geometry {
        PartGeometry::Shell(s) => {
            let r = s.outside_diameter / 2.0 - d;
            (
                Developed::Rectangle {
                    width: 2.0 * PI * r,
                    length: s.length,
                    rolling_radius: r,
                },
                2.0 * PI * r * s.length,
            )
        }
        PartGeometry::Reducer(c) => {
            let (r1, r2) = (c.large_diameter / 2.0 - d, c.small_diameter / 2.0 - d);
            let s = c.length.hypot(r1 - r2);
            (sector(r1, r2, s), PI * (r1 + r2) * s)
        }
        PartGeometry::Skirt(k) => {
            let flare = k.flare_angle.to_radians();
            let top = k.top_diameter / 2.0 - k.thickness / 2.0;
            let bottom = top + k.height * flare.tan();
            let s = k.height / flare.cos();
            (sector(top, bottom, s), PI * (top + bottom) * s)
        }
        PartGeometry::Head(_) => {
            let area = wall_area(geometry, thickness)?;
            (
                Developed::Blank {
                    diameter: (4.0 * area / PI).sqrt(),
                },
                area,
            )
        }
        _ => return None,
    })
}

/// Mid-surface area of a course, reducer or head of wall `thickness`, mm².
fn wall_area(geometry: &PartGeometry, thickness: f64) -> Option<f64> {
    if thickness <= 0.0 {
        return None;
    }
    Some(wall_volume(geometry, thickness)? / thickness)
}

/// Wall volume of one pressure part (course, reducer, head), mm³, as the weight
/// model integrates it; `None` for other parts or a wall too thick for its shape.
pub fn wall_volume(geometry: &PartGeometry, thickness: f64) -> Option<f64> {
    if !matches!(
        geometry,
        PartGeometry::Shell(_) | PartGeometry::Reducer(_) | PartGeometry::Head(_)
    ) {
        return None;
    }
    let part = StackPart {
        id: "",
        geometry,
        frame: glam::DAffine3::IDENTITY,
        thickness,
    };
    let profile = stack_profile(&[part], Surface::Middle, false).ok()?;
    Some(walls(&profile).volume)
}

/// Wall mass of one pressure part at `density` kg/m³, kg.
pub fn wall_mass(geometry: &PartGeometry, thickness: f64, density: f64) -> Option<f64> {
    wall_volume(geometry, thickness).map(|v| v * MM3_TO_M3 * density)
}
