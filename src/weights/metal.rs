//! The metal of the parts outside the pressure envelope — skirt and base ring,
//! saddles, legs, lugs, boot, nozzles (neck and flange) and reinforcing pads —
//! each as a mass with its centre, from thickness × density.
//!
//! The envelope's walls are weighed exactly by [`crate::operating::weight`]; these items use
//! closed forms of their plates and pipes (stated per item below), and
//! [`super::weights`](super::weights()) adds them up. Plate thicknesses the design does not give
//! are the 12 mm the supports are built with (`constraints::supports`).

use std::f64::consts::PI;
use std::sync::OnceLock;

use glam::{DAffine3, DVec3};
use serde::Serialize;

use crate::constraints::{PartGeometry, ResolvedNozzle, ResolvedPart};
use crate::design::{PartDesign, VesselDesign};
use crate::nurbs::Aabb;
use crate::nurbs::GaussLegendre;
use crate::parts::tables::{PipeSchedule, flange, pipe};
use crate::parts::{FlangeType, Nozzle, Patch};

/// Plate thickness of a support the design gives none for, mm.
pub const DEFAULT_PLATE: f64 = 12.0;

/// mm³ → m³.
const MM3_TO_M3: f64 = 1e-9;

/// One weighed item.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MetalItem {
    /// Part id or nozzle mark.
    pub id: String,
    /// What it is: `skirt`, `saddle`, `legs`, `lugs`, `boot`, `nozzle`, `pad`.
    pub kind: &'static str,
    /// Mass, kg.
    pub mass: f64,
    /// Centre of the mass, vessel frame, mm.
    #[serde(skip)]
    pub centre: DVec3,
}

/// Centre of the patches' control-point boxes, in the frame `to` maps them into.
fn box_centre(patches: &[Patch], to: DAffine3) -> DVec3 {
    let b = patches
        .iter()
        .fold(Aabb::EMPTY, |b, p| b.union(&p.surface.bounding_box()));
    if b.min.is_finite() && b.max.is_finite() {
        to.transform_point3(0.5 * (b.min + b.max))
    } else {
        to.transform_point3(DVec3::ZERO)
    }
}

/// Volume (mm³) and mass centre (local frame) of one support or boot, by closed
/// forms of its plates; `None` for a pressure part.
fn support_volume(design: &PartDesign, part: &ResolvedPart, shell_thickness: f64) -> Option<f64> {
    Some(match (&part.geometry, design) {
        // Frustum of the mid-surface × t, and the base ring as a flat annulus of
        // its own thickness (default the skirt's).
        (PartGeometry::Skirt(s), design) => {
            let ring_t = match design {
                PartDesign::Skirt(d) => d.base_ring_thickness.unwrap_or(s.thickness),
                _ => s.thickness,
            };
            let t = s.thickness;
            let flare = s.flare_angle.to_radians();
            let top = s.top_diameter / 2.0 - t / 2.0;
            let bottom = top + s.height * flare.tan();
            let slant = s.height / flare.cos();
            let ring_in = bottom + t / 2.0;
            let ring_out = ring_in + s.base_ring_width;
            PI * (top + bottom) * slant * t
                + PI * (ring_out * ring_out - ring_in * ring_in) * ring_t
        }
        // Web (from the bearing plane up to the contact arc, and to the chord's
        // level beyond it), wear plate along the arc, and base plate; wear plate
        // as thick as the web. A design's separate `wear_plate` on the shell:
        // the saddle's width, over the contact arc and R/10 beyond each horn.
        (PartGeometry::Saddle(s), design) => {
            let r = s.shell_diameter / 2.0;
            let half = (s.contact_angle.to_radians() / 2.0).min(PI / 2.0);
            let c = r * half.sin();
            let chord_depth = r * half.cos();
            let under_arc = 2.0 * c * s.height - r * r * (half.sin() * half.cos() + half);
            let beyond = (s.base_length - 2.0 * c).max(0.0) * (s.height - chord_depth);
            let web = (under_arc + beyond) * s.web_thickness;
            let wear = 2.0 * half * r * s.width * s.web_thickness;
            let base = s.base_length * s.base_width * s.base_thickness;
            let shell_plate = match design {
                PartDesign::Saddle(d) => d
                    .wear_plate
                    .map_or(0.0, |t| (2.0 * half + 0.2) * r * s.width * t),
                _ => 0.0,
            };
            web + wear + base + shell_plate
        }
        // Standard-weight pipe of the leg's size, and a base plate of side twice
        // the pipe's outside diameter.
        (PartGeometry::Legs(l), PartDesign::Legs(d)) => {
            let nps = crate::parts::tables::Nps::try_new(d.size).ok()?;
            let row = pipe(nps);
            let wall = row
                .wall(PipeSchedule::Std)
                .unwrap_or(l.pipe_diameter / 20.0);
            let (ro, ri) = (l.pipe_diameter / 2.0, l.pipe_diameter / 2.0 - wall);
            let plate = (2.0 * l.pipe_diameter).powi(2) * DEFAULT_PLATE;
            f64::from(l.count) * (PI * (ro * ro - ri * ri) * l.length + plate)
        }
        // Two gussets (height × projection) and a bearing plate (projection ×
        // gap + both gussets) per lug.
        (PartGeometry::Lugs(l), _) => {
            let t = DEFAULT_PLATE;
            let gussets = 2.0 * l.height * l.projection * t;
            let plate = l.projection * (l.width + 2.0 * t) * t;
            f64::from(l.count) * (gussets + plate)
        }
        // Outside surface × the wall of the course it hangs from (the design
        // gives a boot no thickness).
        (PartGeometry::Boot(b), _) => {
            let patches = b.patches().ok()?;
            crate::parts::surface_area(&patches) * shell_thickness
        }
        _ => return None,
    })
}

/// Volume (mm³) of the metal of a nozzle's neck and flange body from `start`
/// mm along its axis (where it leaves the host's outside surface) to the face:
/// Pappus on the exact meridian of the model's patches, closed by the bore (a
/// blind flange by its plate of the flange's thickness).
fn nozzle_volume(nozzle: &Nozzle, start: f64) -> Option<f64> {
    static RULE: OnceLock<GaussLegendre> = OnceLock::new();
    let rule = RULE.get_or_init(|| GaussLegendre::new(24));
    let patches = nozzle.patches().ok()?;
    let row = pipe(nozzle.nps);
    let wall = row.wall(nozzle.schedule).ok()?;
    let (rp, rb) = (
        row.outside_diameter / 2.0,
        row.outside_diameter / 2.0 - wall,
    );
    // ∮ π r² dz along the meridian (u at the domain's start).
    let mut swept = 0.0;
    for p in &patches {
        let ((u0, _), (v0, v1)) = p.surface.domain();
        for (v, w) in rule.points_on(v0, v1) {
            let d = p.surface.derivatives(u0, v);
            let r2 = d.point.x * d.point.x + d.point.y * d.point.y;
            swept += PI * r2 * d.dv.z * w;
        }
    }
    let bore_top = match nozzle.flange {
        FlangeType::Blind => nozzle.projection - flange(nozzle.nps, nozzle.class).ok()?.thickness,
        _ => nozzle.projection,
    };
    let body = (swept - PI * rb * rb * bore_top).abs();
    let inside = PI * (rp * rp - rb * rb) * start.clamp(0.0, nozzle.neck_length().ok()?);
    Some(body - inside)
}

/// Whether `p` (host local frame) is inside the host's outside surface.
fn inside_host(host: &PartGeometry, p: DVec3) -> bool {
    let r = p.x.hypot(p.y);
    match host {
        PartGeometry::Shell(s) => r < s.outside_diameter / 2.0,
        PartGeometry::Head(h) => {
            r < h.outside_diameter / 2.0 && h.height_at_radius(r).is_ok_and(|top| p.z < top)
        }
        PartGeometry::Reducer(c) => {
            let f = (p.z / c.length).clamp(0.0, 1.0);
            r < 0.5 * (c.large_diameter + f * (c.small_diameter - c.large_diameter))
        }
        _ => false,
    }
}

/// Distance along a nozzle's axis from its neck start to where it leaves the
/// host's outside surface, mm (bisection; 0 when the start is outside).
pub fn neck_start_outside(n: &ResolvedNozzle, host: &ResolvedPart) -> f64 {
    let to_host = host.frame.inverse() * n.frame;
    let at = |t: f64| to_host.transform_point3(DVec3::new(0.0, 0.0, t));
    let end = n.geometry.neck_length().unwrap_or(0.0).max(0.0);
    if !inside_host(&host.geometry, at(0.0)) {
        return 0.0;
    }
    if inside_host(&host.geometry, at(end)) {
        return end;
    }
    let (mut lo, mut hi) = (0.0, end);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if inside_host(&host.geometry, at(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The metal items of a vessel outside its pressure envelope, at `density`
/// kg/m³: supports, boot, nozzles and pads, in design order.
pub fn items(
    design: &VesselDesign,
    parts: &[ResolvedPart],
    nozzles: &[ResolvedNozzle],
    density: f64,
) -> Vec<MetalItem> {
    let kg = |mm3: f64| mm3 * MM3_TO_M3 * density;
    let mut out = Vec::new();
    for (i, part) in parts.iter().enumerate() {
        let Some(d) = design.parts.iter().find(|d| d.id() == part.id) else {
            continue;
        };
        let host_t = part
            .host
            .and_then(|h| parts.get(h))
            .and_then(|h| design.parts.iter().find(|d| d.id() == h.id))
            .and_then(crate::operating::thickness)
            .unwrap_or(DEFAULT_PLATE);
        let Some(volume) = support_volume(d, part, host_t) else {
            continue;
        };
        let centre = part
            .geometry
            .patches()
            .map(|p| box_centre(&p, part.frame))
            .unwrap_or(part.frame.translation);
        out.push(MetalItem {
            id: parts[i].id.clone(),
            kind: part.geometry.kind(),
            mass: kg(volume),
            centre,
        });
    }
    for n in nozzles {
        let Some(host) = parts.get(n.host) else {
            continue;
        };
        let start = neck_start_outside(n, host);
        if let Some(volume) = nozzle_volume(&n.geometry, start) {
            let mid = 0.5 * (start + n.geometry.projection);
            out.push(MetalItem {
                id: n.mark.clone(),
                kind: "nozzle",
                mass: kg(volume),
                centre: n.frame.transform_point3(DVec3::new(0.0, 0.0, mid)),
            });
        }
        // A pad as a flat annulus of its thickness round the neck.
        if let Some((od, t)) = n.pad {
            let neck = n.geometry.outside_diameter();
            out.push(MetalItem {
                id: n.mark.clone(),
                kind: "pad",
                mass: kg(PI / 4.0 * (od * od - neck * neck).max(0.0) * t),
                centre: n
                    .frame
                    .transform_point3(DVec3::new(0.0, 0.0, start + t / 2.0)),
            });
        }
    }
    out
}
