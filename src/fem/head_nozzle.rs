//! Nozzles on a head's centre, meshed as part of the meridian: such a neck is
//! coaxial with the vessel, so its mid-surface is one more piece of the chain
//! of revolution (a line at the neck's mid-surface radius r, from where it
//! meets the head's mid-surface to the flange's back). The head's pole piece is
//! cut at radius r (the exact intersection circle of the two mid-surfaces), the
//! neck's line is joined there, and the envelope's rings run on up the neck: the
//! intersection ring is shared node for node, it is graded to 0.5·√(r·t) like
//! every junction, and the neck's end is an open ring instead of the pole's cap.
//! A pad is a thicker shell region, as on a course ([`super::nozzle::pads`]).

use glam::DVec3;

use super::meridian::Segment;
use super::nozzle::PadSite;
use super::{FePart, NeckEnd};
use crate::constraints::ResolvedVessel;
use crate::operating::profile::Piece;
use crate::parts::PartGeometry;
use crate::parts::tables::pipe;

/// A centre head nozzle joined to the chain.
#[derive(Clone, Debug, PartialEq)]
pub struct CentreNeck {
    /// Nozzle mark.
    pub mark: String,
    /// FE part index of the neck.
    pub part: usize,
    /// FE part index of the head it stands on.
    pub host: usize,
    /// Whether the neck is at the chain's start (the lower head), else its end.
    pub at_start: bool,
    /// Nozzle frame origin (on the head's tangent plane), vessel frame.
    pub origin: DVec3,
    /// Unit nozzle axis, outwards (±z), vessel frame.
    pub axis: DVec3,
    /// Distance of the neck's end from the origin along the axis, mm.
    pub end: f64,
    /// Neck mid-surface radius, mm.
    pub r: f64,
    /// Pad (outside diameter, thickness), mm.
    pub pad: Option<(f64, f64)>,
}

impl CentreNeck {
    /// The pad's site, if the nozzle has a pad.
    pub fn pad_site(&self) -> Option<PadSite> {
        self.pad.map(|pad| PadSite {
            mark: self.mark.clone(),
            part: self.host,
            origin: self.origin,
            axis: self.axis,
            pad,
        })
    }

    /// The neck's open end: its ring of corner nodes `ring` (in order) and the
    /// mid-side nodes between them, `mid(a, b)`.
    pub fn end(&self, ring: Vec<usize>, mids: Vec<usize>) -> NeckEnd {
        NeckEnd {
            mark: self.mark.clone(),
            part: self.part,
            nodes: ring,
            mids,
            centre: self.origin + self.axis * self.end,
            axis: self.axis,
            radius: self.r,
        }
    }
}

/// Joins the necks of the nozzles on the centre of a head at either end of
/// `chain` (parts `parts`, vessel `tag`), adding a part per neck; returns
/// them. Nozzles it cannot take are left to [`super::window::plan`] (which
/// notes them) or noted here.
pub fn join(
    resolved: &ResolvedVessel,
    chain: &mut Vec<Segment>,
    parts: &mut Vec<FePart>,
    tag: &str,
    notes: &mut Vec<String>,
) -> Vec<CentreNeck> {
    let mut out: Vec<CentreNeck> = Vec::new();
    for nz in &resolved.nozzles {
        let host = &resolved.parts[nz.host];
        if !matches!(host.geometry, PartGeometry::Head(_)) {
            continue;
        }
        let Some(part) = parts.iter().position(|p| p.id == host.id) else {
            continue;
        };
        let o = nz.frame.translation;
        let d = (nz.frame.matrix3 * DVec3::Z).normalize();
        let (Some(first), Some(last)) = (chain.first().copied(), chain.last().copied()) else {
            continue;
        };
        // The chain's end segment on this head, at the pole.
        let at_start = if first.part == part && first.rz(first.s0).x <= 1e-6 {
            true
        } else if last.part == part && last.rz(last.s1).x <= 1e-6 {
            false
        } else {
            continue;
        };
        let seg = if at_start { first } else { last };
        if (o.truncate() - seg.centre.at(o.z)).length() > 1e-6 || d.z.abs() < 1.0 - 1e-12 {
            continue;
        }
        let mut skip = |why: &str| notes.push(format!("nozzle {} left out: {why}", nz.mark));
        if out.iter().any(|c| c.at_start == at_start) {
            skip("a second nozzle on the same head's centre");
            continue;
        }
        let g = nz.geometry;
        let (Ok(wall), Ok(flange)) = (pipe(g.nps).wall(g.schedule), g.flange_length()) else {
            skip("its pipe or flange is not in the tables");
            continue;
        };
        let r = 0.5 * (g.outside_diameter() - wall);
        let s_cut = seg.piece.at_r(r);
        let at = seg.rz(s_cut);
        let rim = seg.rz(seg.s0).x.max(seg.rz(seg.s1).x);
        if (at.x - r).abs() > 1e-9 * r.max(1.0) || r >= 0.9 * rim {
            skip("its neck is wider than 0.9 of its head's crown");
            continue;
        }
        let end = g.projection - flange;
        let z_end = o.z + d.z * end;
        if d.z * (z_end - at.y) <= 0.0 {
            skip("its neck ends inside its head's mid-surface");
            continue;
        }
        let neck = parts.len();
        parts.push(FePart {
            name: format!("{tag}/{}", nz.mark),
            id: nz.mark.clone(),
            thickness: wall,
            offset: 0.0,
        });
        let line = Segment {
            piece: Piece::Line {
                r0: r,
                z0: at.y,
                r1: r,
                z1: z_end,
            },
            s0: 0.0,
            s1: 1.0,
            part: neck,
            centre: seg.centre,
            thickness: wall,
        };
        if at_start {
            chain[0].s0 = s_cut;
            chain.insert(
                0,
                Segment {
                    s0: 1.0,
                    s1: 0.0,
                    ..line
                },
            );
        } else {
            let k = chain.len() - 1;
            chain[k].s1 = s_cut;
            chain.push(line);
        }
        out.push(CentreNeck {
            mark: nz.mark.clone(),
            part: neck,
            host: part,
            at_start,
            origin: o,
            axis: d,
            end,
            r,
            pad: nz.pad,
        });
    }
    out
}
