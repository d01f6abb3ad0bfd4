//! Head openings on the head's blank, by the blank's forming rule.
//!
//! A head's blank is a disc whose area is the exact area of the head's
//! mid-surface ([`super::develop::HeadBlank`]). The same rule, applied zone by
//! zone, places every point of the formed head on the blank: a point at
//! angle θ about the head's axis whose cap (the mid-surface from the pole
//! down to the point's parallel) has area `A` goes to blank radius `ρ` with
//! `π·ρ² = A`, at the same θ ([`HeadMap`]). The map preserves the area of
//! every annular zone, and the blank's rim is the open end. Blank
//! coordinates: the pole at the origin, +x along the head's local +X.
//!
//! An opening is the cutting cylinder (the neck's outside plus the bevel
//! allowance set-in, its bore set-on) ∩ the head's mid-surface, solved for
//! each angle φ about the neck axis along the cylinder's generator exactly
//! (to rounding) on the exact meridian of the model's patches, then mapped.
//! A pad's outline is its cylinder ∩ the mid-surface, mapped alike. The
//! blank's DXF draws them as **marking** lines: shops cut head openings after
//! forming (pressing stretches the plate unevenly, the map only holds area),
//! so the outline and centre mark on the blank locate the opening, and the
//! cut is made on the formed head.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

use super::develop::{Developments, mid_head};
use super::openings::{BlankMark, NeckAxis, samples};
use super::shop::Shop;
use crate::constraints::{PartGeometry, ResolvedVessel};
use crate::nurbs::{GaussLegendre, NurbsCurve};
use crate::parts::heads::Head;
use crate::parts::tables::pipe;

/// One smooth piece of the meridian (x = radius, z = height).
#[derive(Clone, Debug)]
struct Piece {
    curve: NurbsCurve,
    /// Distinct knots of the curve.
    knots: Vec<f64>,
    /// Whether its radius is constant (a straight flange).
    flange: bool,
    /// Area of the mid-surface from the open end to the piece's start, mm².
    before: f64,
    /// Area of its own zone, mm².
    area: f64,
}

/// The forming map of one head's mid-surface onto its blank.
#[derive(Clone, Debug)]
pub struct HeadMap {
    pieces: Vec<Piece>,
    /// Area of the whole mid-surface, mm².
    pub total: f64,
}

fn rule() -> &'static GaussLegendre {
    static RULE: std::sync::OnceLock<GaussLegendre> = std::sync::OnceLock::new();
    RULE.get_or_init(|| GaussLegendre::new(24))
}

impl Piece {
    /// Area of the zone from the piece's start to parameter `v`, mm².
    fn area_to(&self, v: f64) -> f64 {
        let zone = |a: f64, b: f64| {
            rule().integrate(a, b, |t| {
                let d = self.curve.derivatives(t);
                TAU * d.point.x * d.first.length()
            })
        };
        self.knots
            .windows(2)
            .map(|w| {
                let b = w[1].min(v);
                if b <= w[0] { 0.0 } else { zone(w[0], b) }
            })
            .sum()
    }

    /// The parameter where coordinate `pick` of the curve is `value`, the
    /// coordinate monotone along the piece; `None` outside its range.
    fn solve(&self, value: f64, pick: fn(DVec3) -> f64) -> Option<f64> {
        let (a, b) = self.curve.domain();
        let (fa, fb) = (pick(self.curve.point(a)), pick(self.curve.point(b)));
        let (lo_v, hi_v) = (fa.min(fb), fa.max(fb));
        let slack = 1e-9 * (1.0 + hi_v.abs());
        if value < lo_v - slack || value > hi_v + slack {
            return None;
        }
        let rising = fb > fa;
        let (mut lo, mut hi) = (a, b);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if (pick(self.curve.point(mid)) < value) == rising {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 4.0 * f64::EPSILON * (b - a).abs().max(1.0) {
                break;
            }
        }
        Some(0.5 * (lo + hi))
    }
}

impl Piece {
    /// `v` refined to the foot of the meridian point `target` (x = radius),
    /// by Newton on `(C − P)·C′ = 0`: where the meridian is steep in x (near
    /// a vertical tangent) the radius alone places the point poorly, its
    /// height places it well. Kept in the piece's domain; `v` itself when
    /// `target` is far from the curve (a mere radius lookup).
    fn project(&self, v: f64, target: DVec3) -> f64 {
        let (a, b) = self.curve.domain();
        let mut v = v;
        for _ in 0..8 {
            let d = self.curve.derivatives(v);
            let e = d.point - target;
            let f = e.dot(d.first);
            let df = d.first.length_squared() + e.dot(d.second);
            if df <= 0.0 {
                break;
            }
            let next = (v - f / df).clamp(a, b);
            let done = (next - v).abs() <= 4.0 * f64::EPSILON * (b - a).abs().max(1.0);
            v = next;
            if done {
                break;
            }
        }
        v
    }
}

impl HeadMap {
    /// The map of `head`'s surface (the mid-surface head of
    /// [`mid_head`]); `None` when its patches cannot be built.
    pub fn new(head: &Head) -> Option<HeadMap> {
        let mut pieces = Vec::new();
        let mut before = 0.0;
        for patch in head.patches().ok()? {
            let ((u0, _), _) = patch.surface.domain();
            let curve = patch.surface.isocurve_u(u0);
            let mut knots = curve.knots().as_slice().to_vec();
            knots.dedup();
            let (a, b) = curve.domain();
            let flange = (curve.point(a).x - curve.point(b).x).abs() <= 1e-12;
            let mut piece = Piece {
                curve,
                knots,
                flange,
                before,
                area: 0.0,
            };
            piece.area = piece.area_to(b);
            before += piece.area;
            pieces.push(piece);
        }
        Some(HeadMap {
            pieces,
            total: before,
        })
    }

    /// Radius of the blank, √(total/π), mm.
    pub fn blank_radius(&self) -> f64 {
        (self.total / PI).sqrt()
    }

    /// The piece and parameter of the meridian point at radius `r` (the
    /// dished part; the straight flange by height `z` when `r` is its
    /// radius).
    /// With `on_curve`, `(r, z)` is a meridian point and the parameter is
    /// refined to it ([`Piece::project`]).
    fn locate(&self, r: f64, z: f64, on_curve: bool) -> Option<(usize, f64)> {
        let dished = self.pieces.iter().enumerate().filter(|(_, p)| !p.flange);
        for (i, p) in dished {
            if let Some(v) = p.solve(r, |q| q.x) {
                let v = if on_curve {
                    p.project(v, DVec3::new(r, 0.0, z))
                } else {
                    v
                };
                return Some((i, v));
            }
        }
        let (i, p) = self.pieces.iter().enumerate().find(|(_, p)| p.flange)?;
        p.solve(z, |q| q.z).map(|v| (i, v))
    }

    /// Height of the mid-surface at radius `r` from the axis, mm.
    pub fn height_at(&self, r: f64) -> Option<f64> {
        let (i, v) = self.locate(r, 0.0, false)?;
        (!self.pieces[i].flange).then(|| self.pieces[i].curve.point(v).z)
    }

    /// Area of the cap from the pole to the parallel of the mid-surface
    /// point `p` (head local frame), mm².
    pub fn cap_area(&self, p: DVec3) -> Option<f64> {
        let (i, v) = self.locate(p.x.hypot(p.y), p.z, true)?;
        let piece = &self.pieces[i];
        Some((self.total - piece.before - piece.area_to(v)).max(0.0))
    }

    /// The blank point of mid-surface point `p` (head local frame).
    pub fn forward(&self, p: DVec3) -> Option<DVec2> {
        let a = self.cap_area(p)?;
        let rho = (a / PI).sqrt();
        Some(DVec2::from_angle(p.y.atan2(p.x)) * rho)
    }

    /// The mid-surface point (head local frame) of blank point `q`.
    pub fn inverse(&self, q: DVec2) -> Option<DVec3> {
        let from_open = self.total - PI * q.length_squared();
        let piece = self
            .pieces
            .iter()
            .find(|p| from_open <= p.before + p.area)
            .or(self.pieces.last())?;
        let target = from_open - piece.before;
        let (mut lo, mut hi) = piece.curve.domain();
        let span = hi - lo;
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if piece.area_to(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo <= 4.0 * f64::EPSILON * span.max(1.0) {
                break;
            }
        }
        let m = piece.curve.point(0.5 * (lo + hi));
        let theta = q.y.atan2(q.x);
        Some(DVec3::new(m.x * theta.cos(), m.x * theta.sin(), m.z))
    }

    /// `f(t) = z − height(r)` along `a + t·d`; `None` off the dished part.
    fn gap(&self, a: DVec3, d: DVec3, t: f64) -> Option<f64> {
        let p = a + t * d;
        self.height_at(p.x.hypot(p.y)).map(|h| p.z - h)
    }

    /// The outermost crossing of the line `a + t·d` with the mid-surface's
    /// dished part, searched in `[lo, hi]`.
    fn crossing(&self, a: DVec3, d: DVec3, lo: f64, hi: f64, steps: usize) -> Option<DVec3> {
        let mut prev: Option<(f64, f64)> = None;
        for k in (0..=steps).rev() {
            let t = lo + (hi - lo) * k as f64 / steps as f64;
            let Some(f) = self.gap(a, d, t) else {
                prev = None;
                continue;
            };
            if let Some((tp, fp)) = prev
                && (f <= 0.0) != (fp <= 0.0)
            {
                // Illinois (regula falsi keeping the bracket), to a gap of
                // 1e-11 mm or a bracket at rounding.
                let (mut x0, mut f0, mut x1, mut f1) = (t, f, tp, fp);
                let mut side = 0;
                let mut best = if f.abs() < fp.abs() { t } else { tp };
                for _ in 0..200 {
                    let x = (x0 * f1 - x1 * f0) / (f1 - f0);
                    let fx = self.gap(a, d, x)?;
                    best = x;
                    if fx.abs() <= 1e-11
                        || (x1 - x0).abs() <= 4.0 * f64::EPSILON * x1.abs().max(1.0)
                    {
                        break;
                    }
                    if (fx <= 0.0) == (f0 <= 0.0) {
                        (x0, f0) = (x, fx);
                        if side == -1 {
                            f1 *= 0.5;
                        }
                        side = -1;
                    } else {
                        (x1, f1) = (x, fx);
                        if side == 1 {
                            f0 *= 0.5;
                        }
                        side = 1;
                    }
                }
                return Some(a + best * d);
            }
            prev = Some((t, f));
        }
        None
    }

    /// The loop where the cylinder of radius `rho` about `neck` (head local
    /// frame) meets the mid-surface, `n` points evenly in φ; `None` where
    /// part of it misses the dished part.
    pub fn cylinder_loop(&self, neck: &NeckAxis, rho: f64, n: usize) -> Option<Vec<DVec3>> {
        let reach = 2.0 * self.blank_radius();
        let mut last: Option<f64> = None;
        (0..n)
            .map(|i| {
                let phi = TAU * i as f64 / n as f64;
                let a = neck.origin + rho * (phi.cos() * neck.e1 + phi.sin() * neck.e2);
                let centre = -a.dot(neck.axis);
                let near = last.and_then(|t| {
                    let w = 0.05 * reach;
                    self.crossing(a, neck.axis, t - w, t + w, 8)
                });
                let p = near
                    .or_else(|| self.crossing(a, neck.axis, centre - reach, centre + reach, 400))?;
                last = Some((p - a).dot(neck.axis));
                Some(p)
            })
            .collect()
    }
}

/// The opening (and pad) of nozzle `index` of `resolved` mapped onto its
/// head's blank, or `None` when its host is not a head with a blank or the
/// opening does not lie on the head's dished part.
pub fn blank_mark(
    resolved: &ResolvedVessel,
    developments: &Developments,
    shop: &Shop,
    index: usize,
) -> Option<BlankMark> {
    let nozzle = &resolved.nozzles[index];
    let host = &resolved.parts[nozzle.host];
    let PartGeometry::Head(head) = &host.geometry else {
        return None;
    };
    let blank = developments.heads.iter().find(|h| h.part == nozzle.host)?;
    let map = HeadMap::new(&mid_head(head, blank.thickness))?;
    let g = &nozzle.geometry;
    let dims = pipe(g.nps);
    let wall = dims.wall(g.schedule).ok()?;
    let cut_radius = shop.cut_radius(dims.outside_diameter, wall);
    let neck = NeckAxis::new(host.frame, nozzle.frame);
    let mapped = |rho: f64| -> Option<Vec<DVec2>> {
        let n = samples(rho, shop.chord_tolerance);
        map.cylinder_loop(&neck, rho, n)?
            .iter()
            .map(|&p| map.forward(p))
            .collect()
    };
    let centre = map.cylinder_loop(&neck, 0.0, 1)?;
    Some(BlankMark {
        nozzle: index,
        cut_radius,
        centre: map.forward(centre[0])?,
        outline: mapped(cut_radius)?,
        pad: match nozzle.pad {
            Some((od, _)) => Some(mapped(0.5 * od)?),
            None => None,
        },
    })
}
