//! Footprints of openings: where a nozzle or a boot is cut into its host, as a
//! ball round the opening's centre on the host surface, so that two openings in
//! one vessel can be refused when they might overlap.
//!
//! Every opening of a host patch becomes a hole of its mesh region; two holes that
//! overlap, or one inside the other (a nozzle placed within the boot's opening),
//! leave no host surface between them, so such a design cannot be built and is
//! refused here, naming both, rather than later by the mesher.

use glam::DVec3;

use super::ResolvedPart;
use crate::parts::PartGeometry;

/// The ball an opening lies in: what it belongs to, its centre on the host
/// surface (vessel frame) and its radius, mm.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Footprint {
    /// What is cut, for messages: `"nozzle N1"`, `"boot B1"`.
    pub name: String,
    /// The opening's centre on the host surface, vessel frame, mm.
    pub centre: DVec3,
    /// Radius of the ball round `centre` holding the opening, mm.
    pub radius: f64,
}

impl Footprint {
    /// The footprint of nozzle `mark`: centred where its axis meets the host, with
    /// half its reach (neck or pad OD) as radius, the rule nozzles have always
    /// had. On a curved host the opening reaches slightly further at its sides
    /// (√(r² + depth²), see [`Footprint::boot`]; 2.5 mm for a 24-inch nozzle on a
    /// 2400 mm course); two such openings that still meet cross in the mesher's
    /// layout, which reports it.
    pub fn nozzle(mark: &str, centre: DVec3, reach: f64) -> Self {
        Self {
            name: format!("nozzle {mark}"),
            centre,
            radius: reach / 2.0,
        }
    }

    /// The footprint of nozzle `mark` whose opening is held by the ball of
    /// `radius` about `centre` (a hillside or inclined nozzle's, worked out
    /// from its opening's shape).
    pub fn opening(mark: &str, centre: DVec3, radius: f64) -> Self {
        Self {
            name: format!("nozzle {mark}"),
            centre,
            radius,
        }
    }

    /// The footprint of a resolved boot, `None` for any other part. Its opening in
    /// the course (radius R) is where its cylinder (radius r) meets it: within r of
    /// the centre along the vessel axis, and across it down to the course's depth
    /// R − √(R² − r²) below the centre at the sides, so the ball holding it has
    /// radius √(r² + (R − √(R² − r²))²).
    pub fn boot(part: &ResolvedPart) -> Option<Self> {
        let PartGeometry::Boot(boot) = &part.geometry else {
            return None;
        };
        let (r, host) = (boot.diameter / 2.0, boot.host_diameter / 2.0);
        let depth = host - (host * host - r * r).max(0.0).sqrt();
        Some(Self {
            name: format!("boot {}", part.id),
            // The boot's frame has its axis (+Z) through the course's axis.
            centre: part.frame.transform_point3(DVec3::new(0.0, 0.0, host)),
            radius: r.hypot(depth),
        })
    }

    /// Whether the two balls overlap (touching is allowed).
    pub fn overlaps(&self, other: &Self) -> bool {
        (self.centre - other.centre).length() < self.radius + other.radius
    }
}

#[cfg(test)]
mod tests {
    use glam::{DAffine3, DMat3};

    use super::*;
    use crate::parts::Boot;

    fn boot(position: f64, od: f64, host_od: f64) -> ResolvedPart {
        ResolvedPart {
            id: "B1".into(),
            frame: DAffine3::from_mat3_translation(
                DMat3::from_rotation_x(std::f64::consts::FRAC_PI_2),
                DVec3::new(0.0, 0.0, position),
            ),
            geometry: PartGeometry::Boot(Boot::new(od, 900.0, host_od)),
            span: (position - od / 2.0, position + od / 2.0),
            host: Some(1),
        }
    }

    /// The boot's ball is centred at the bottom of the course and holds every
    /// point of its opening (the boot cylinder's points on the course).
    #[test]
    fn a_boot_footprint_holds_its_whole_opening() {
        let (od, host_od) = (1800.0, 2400.0);
        let f = Footprint::boot(&boot(4000.0, od, host_od)).unwrap();
        assert!((f.centre - DVec3::new(0.0, -1200.0, 4000.0)).length() < 1e-9);
        let (r, big) = (od / 2.0, host_od / 2.0);
        for k in 0..360 {
            let a = f64::from(k).to_radians();
            let (x, z) = (r * a.cos(), 4000.0 + r * a.sin());
            let on_course = DVec3::new(x, -(big * big - x * x).sqrt(), z);
            assert!((on_course - f.centre).length() <= f.radius * (1.0 + 1e-12));
        }
        assert_eq!(f.name, "boot B1");
    }

    #[test]
    fn other_parts_have_no_footprint() {
        let mut part = boot(4000.0, 600.0, 2400.0);
        part.geometry = PartGeometry::Shell(crate::parts::Shell {
            outside_diameter: 2400.0,
            length: 1000.0,
        });
        assert_eq!(Footprint::boot(&part), None);
    }
}
