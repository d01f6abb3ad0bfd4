//! The parts the `mesh_cdt` tests mesh: a shell course, a head of every kind,
//! nozzles, and mirror images of head patches.

use glam::DVec4;
use vesselcad::nurbs::NurbsSurface;
use vesselcad::parts::heads::Head;
use vesselcad::parts::tables::{FlangeClass, Nps, PipeSchedule};
use vesselcad::parts::{Facing, FlangeType, Nozzle, Patch, Shell};

/// One head of every kind: the list every head suite sweeps.
pub use crate::common::heads::head_kinds;

/// Three NPS 4 nozzles: weld-neck raised face, slip-on flat face, blind ring joint.
pub fn nozzles() -> Vec<Nozzle> {
    let nps = Nps::try_new(4.0).unwrap();
    [
        (FlangeType::WeldNeck, Facing::RaisedFace),
        (FlangeType::SlipOn, Facing::FlatFace),
        (FlangeType::Blind, Facing::RingJoint),
    ]
    .into_iter()
    .map(|(flange, facing)| {
        let n = Nozzle {
            nps,
            schedule: PipeSchedule::Std,
            class: FlangeClass::C300,
            flange,
            facing,
            projection: 0.0,
        };
        Nozzle {
            projection: n.flange_length().unwrap() + Nozzle::MIN_NECK_LENGTH + 100.0,
            ..n
        }
    })
    .collect()
}

/// Every patch of the test parts: a shell course, every head kind, nozzles.
pub fn all_patches() -> Vec<(String, Patch)> {
    let od = 2400.0;
    let mut out = Vec::new();
    let shell = Shell {
        outside_diameter: od,
        length: 3000.0,
    };
    for p in shell.patches().unwrap() {
        out.push(("shell".to_string(), p));
    }
    for kind in head_kinds(od) {
        let head = Head::new(od, kind).with_straight_flange(50.0);
        for p in head.patches().unwrap() {
            out.push((format!("{} head", kind.name()), p));
        }
    }
    for (k, n) in nozzles().into_iter().enumerate() {
        for p in n.patches().unwrap() {
            out.push((format!("nozzle {k}"), p));
        }
    }
    out
}

/// The mirror image of a head patch in z = 0, with u reversed so that the normal
/// still points outward.
pub fn mirrored(s: &NurbsSurface) -> NurbsSurface {
    let (nu, nv) = (s.u_count(), s.v_count());
    let mut points = Vec::with_capacity(nu * nv);
    for i in (0..nu).rev() {
        for j in 0..nv {
            let p = s.homogeneous_point_at(i, j);
            points.push(DVec4::new(p.x, p.y, -p.z, p.w));
        }
    }
    NurbsSurface::try_new(s.u_knots().reversed(), s.v_knots().clone(), points).unwrap()
}
