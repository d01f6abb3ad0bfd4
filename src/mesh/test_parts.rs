//! Parts the mesh module's unit tests cut openings with (tests only): a course,
//! an 8" weld-neck nozzle and a nozzle frame.

use glam::{DAffine3, DMat3, DVec3};

use crate::parts::tables::{FlangeClass, Nps, PipeSchedule};
use crate::parts::{Facing, FlangeType, Nozzle, Patch, Shell};

/// Outside diameter of [`course`], mm.
pub const OD: f64 = 2000.0;

/// A course of OD [`OD`], 3000 mm long.
pub fn course() -> Patch {
    let s = Shell {
        outside_diameter: OD,
        length: 3000.0,
    };
    s.patches().unwrap().remove(0)
}

/// An 8" class 150 weld-neck nozzle of `projection` mm.
pub fn nozzle(projection: f64) -> Nozzle {
    Nozzle {
        nps: Nps::try_new(8.0).unwrap(),
        schedule: PipeSchedule::Std,
        class: FlangeClass::C150,
        flange: FlangeType::WeldNeck,
        facing: Facing::RaisedFace,
        projection,
    }
}

/// The neck of [`nozzle`] of `projection` mm.
pub fn neck(projection: f64) -> Patch {
    nozzle(projection).patches().unwrap().remove(0)
}

/// A frame at `origin` whose +Z is `axis` (its +X made orthogonal from Z; `axis`
/// not along Z).
pub fn frame(origin: DVec3, axis: DVec3) -> DAffine3 {
    let z = axis.normalize();
    let x = (DVec3::Z - z * DVec3::Z.dot(z)).normalize();
    DAffine3::from_mat3_translation(DMat3::from_cols(x, z.cross(x), z), origin)
}
