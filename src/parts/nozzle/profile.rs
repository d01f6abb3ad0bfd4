//! The meridian profile of a nozzle: its smooth pieces in the XZ half-plane
//! (x = radius, z along the nozzle axis), from the neck start at z = 0 up to the
//! gasket face at z = projection, each with its patch name and analytic surface.
//!
//! The profile runs with the metal on its left in the (radius, z) half-plane, so the
//! revolved patches have outward normals `S_u × S_v`: up the neck and hub (normals
//! away from the axis), out along the flange back (−Z), up the rim, in along the
//! front faces (+Z). Consecutive pieces share their end points exactly (G0); every
//! joint is a real corner.

use glam::DVec3;

use super::FlangeType;
use crate::nurbs::NurbsCurve;
use crate::nurbs::builders::line;
use crate::parts::{Analytic, PartError};

/// One smooth piece of the meridian, running from the neck start to the face.
pub(super) struct Segment {
    /// Patch name.
    pub name: &'static str,
    /// The profile curve in the XZ half-plane.
    pub curve: NurbsCurve,
    /// The surface its revolution about +Z lies on.
    pub analytic: Analytic,
}

/// The resolved dimensions of one nozzle (mm), from the tables and the projection.
#[derive(Clone, Copy, Debug)]
pub(super) struct Resolved {
    /// Flange style: decides the hub and whether the face closes at the axis.
    pub flange: FlangeType,
    /// Neck (pipe) outside radius; also the weld-neck hub radius at the weld (A/2).
    pub pipe_radius: f64,
    /// Pipe inside radius, where the gasket face stops (not used by a blind).
    pub bore_radius: f64,
    /// Hub radius at the flange back (X/2).
    pub hub_base_radius: f64,
    /// Flange outside radius (O/2).
    pub flange_radius: f64,
    /// Raised-face radius (R/2).
    pub raised_face_radius: f64,
    /// Raised-face height; 0 for a flat face.
    pub raised_face_height: f64,
    /// Flange thickness tf, raised face excluded.
    pub thickness: f64,
    /// Length through hub Y (weld-neck or slip-on), raised face excluded.
    pub hub_length: f64,
    /// z of the gasket face.
    pub projection: f64,
}

/// A point of the XZ half-plane at radius `x` and height `z`.
fn xz(x: f64, z: f64) -> DVec3 {
    DVec3::new(x, 0.0, z)
}

/// The cylinder of `radius` about the nozzle axis.
fn cylinder(radius: f64) -> Analytic {
    Analytic::Cylinder {
        point: DVec3::ZERO,
        axis: DVec3::Z,
        radius,
    }
}

/// The plane z = `z` with outward normal ±Z.
fn plane(z: f64, normal: DVec3) -> Analytic {
    Analytic::Plane {
        point: DVec3::new(0.0, 0.0, z),
        normal,
    }
}

/// The straight piece from (`r0`, `z0`) to (`r1`, `z1`) named `name` on `analytic`.
fn piece(
    name: &'static str,
    (r0, z0): (f64, f64),
    (r1, z1): (f64, f64),
    analytic: Analytic,
) -> Result<Segment, PartError> {
    Ok(Segment {
        name,
        curve: line(xz(r0, z0), xz(r1, z1))?,
        analytic,
    })
}

/// The profile of a nozzle whose dimensions were validated: neck, hub, flange back,
/// rim, front faces.
pub(super) fn profile(d: &Resolved) -> Result<Vec<Segment>, PartError> {
    let z_face = d.projection;
    let z_front = z_face - d.raised_face_height;
    let z_back = z_front - d.thickness;
    let z_hub = z_front - d.hub_length;
    let (a, x, o) = (d.pipe_radius, d.hub_base_radius, d.flange_radius);

    let mut out = vec![piece("neck", (a, 0.0), (a, z_hub), cylinder(a))?];
    match d.flange {
        FlangeType::WeldNeck | FlangeType::Blind => {
            // The hub cone widens from A at the weld to X at the flange back, so its
            // apex lies below the weld, on the axis.
            let rise = z_back - z_hub;
            let apex = DVec3::new(0.0, 0.0, z_hub - a * rise / (x - a));
            out.push(piece(
                "hub",
                (a, z_hub),
                (x, z_back),
                Analytic::Cone {
                    apex,
                    axis: DVec3::Z,
                    half_angle: (x - a).atan2(rise),
                },
            )?);
        }
        FlangeType::SlipOn => {
            out.push(piece(
                "hub end",
                (a, z_hub),
                (x, z_hub),
                plane(z_hub, DVec3::NEG_Z),
            )?);
            out.push(piece("hub", (x, z_hub), (x, z_back), cylinder(x))?);
        }
    }
    out.push(piece(
        "flange back",
        (x, z_back),
        (o, z_back),
        plane(z_back, DVec3::NEG_Z),
    )?);
    out.push(piece("flange rim", (o, z_back), (o, z_front), cylinder(o))?);
    let face_outer = if d.raised_face_height > 0.0 {
        let r = d.raised_face_radius;
        out.push(piece(
            "flange face",
            (o, z_front),
            (r, z_front),
            plane(z_front, DVec3::Z),
        )?);
        out.push(piece(
            "raised face rim",
            (r, z_front),
            (r, z_face),
            cylinder(r),
        )?);
        r
    } else {
        o
    };
    let face_inner = match d.flange {
        FlangeType::Blind => 0.0,
        FlangeType::WeldNeck | FlangeType::SlipOn => d.bore_radius,
    };
    out.push(piece(
        "gasket face",
        (face_outer, z_face),
        (face_inner, z_face),
        plane(z_face, DVec3::Z),
    )?);
    Ok(out)
}
