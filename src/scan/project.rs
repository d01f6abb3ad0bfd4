//! Point inversion of scan points on the vessel's exact patches: each point to
//! the nearest patch it projects onto, with the patch parameters, the foot point,
//! the outward normal and the signed normal deviation.
//!
//! Candidate patches are those whose control-net box, grown by a search margin,
//! holds the point. Patches of revolution use their [`Profile`](super::profile)
//! (exact, one-variable Newton); any other patch the kernel's
//! [`closest_point`](crate::nurbs::NurbsSurface::closest_point). A projection
//! inside a patch beats one that falls off its edge; among those, the smaller
//! distance wins.

use glam::DVec3;
use rayon::prelude::*;

use super::envelope::{Envelope, Role};

/// Which parts a projection may land on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Targets {
    /// Courses, heads and cones.
    Envelope,
    /// The envelope and the nozzles (registration: nozzles fix the turn about
    /// a vertical axis).
    WithNozzles,
}

impl Targets {
    fn admits(self, role: Role) -> bool {
        match self {
            Targets::Envelope => role.is_envelope(),
            Targets::WithNozzles => role.is_envelope() || role == Role::Nozzle,
        }
    }
}

/// A scan point's projection on the design.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Foot {
    /// Index in [`Envelope::surfaces`].
    pub surface: usize,
    /// u of the patch.
    pub u: f64,
    /// v of the patch.
    pub v: f64,
    /// The closest point, vessel frame.
    pub point: DVec3,
    /// Unit outward normal there, vessel frame.
    pub normal: DVec3,
    /// Signed distance along the normal (positive outside), mm.
    pub deviation: f64,
    /// Whether the closest point is inside the patch (not on an edge the
    /// point lies beyond).
    pub inside: bool,
}

impl Envelope {
    /// The projection of `p` (vessel frame) on the nearest admitted patch whose box
    /// grown by `margin` mm holds it; `None` when no box does.
    pub fn project(&self, p: DVec3, targets: Targets, margin: f64) -> Option<Foot> {
        let mut best: Option<Foot> = None;
        for (index, s) in self.surfaces.iter().enumerate() {
            if !targets.admits(self.parts[s.part].role) {
                continue;
            }
            let b = &s.bbox;
            if p.cmplt(b.min - margin).any() || p.cmpgt(b.max + margin).any() {
                continue;
            }
            let local = s.inverse.transform_point3(p);
            let foot = if let Some(profile) = &s.profile {
                let f = profile.project(local);
                Foot {
                    surface: index,
                    u: f.u,
                    v: f.v,
                    point: s.frame.transform_point3(f.point),
                    normal: s.frame.transform_vector3(f.normal).normalize_or_zero(),
                    deviation: f.deviation,
                    inside: f.inside,
                }
            } else {
                let Ok(f) = s.patch.surface.closest_point(local) else {
                    continue;
                };
                let n = s.patch.surface.normal(f.u, f.v);
                let ((u0, u1), (v0, v1)) = s.patch.surface.domain();
                let edge = 1e-9;
                let inside = f.distance < 1e-9
                    || !(f.u <= u0 + edge
                        || f.u >= u1 - edge
                        || f.v <= v0 + edge
                        || f.v >= v1 - edge)
                    || (local - f.point).normalize_or_zero().dot(n).abs() > 0.999;
                let d = (local - f.point).dot(n);
                Foot {
                    surface: index,
                    u: f.u,
                    v: f.v,
                    point: s.frame.transform_point3(f.point),
                    normal: s.frame.transform_vector3(n).normalize_or_zero(),
                    deviation: if inside { d } else { d.signum() * f.distance },
                    inside,
                }
            };
            let better = match &best {
                None => true,
                Some(b) => match (foot.inside, b.inside) {
                    (true, false) => true,
                    (false, true) => false,
                    _ => foot.deviation.abs() < b.deviation.abs(),
                },
            };
            if better {
                best = Some(foot);
            }
        }
        best
    }

    /// [`project`](Self::project) of many points, in parallel.
    pub fn project_all(
        &self,
        points: &[DVec3],
        targets: Targets,
        margin: f64,
    ) -> Vec<Option<Foot>> {
        points
            .par_iter()
            .with_min_len(1024)
            .map(|&p| self.project(p, targets, margin))
            .collect()
    }

    /// The search margin for this vessel: 5 % of its largest diameter, at least
    /// 100 mm.
    pub fn default_margin(&self) -> f64 {
        let d = self
            .parts
            .iter()
            .filter(|p| p.role.is_envelope())
            .map(|p| p.diameter)
            .fold(0.0, f64::max);
        (0.05 * d).max(100.0)
    }
}
