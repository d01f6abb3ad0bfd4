//! Region layout: the (u, v) loops a patch is meshed within — its four sides sampled
//! once from the edge curves, nozzle openings as holes, and a nozzle neck's bottom
//! replaced by its intersection with the host.
//!
//! This sits between the Geometry stage (patches, openings) and the mesher. Sides
//! are sampled with [`edge_parameters`](super::edge_parameters) from the edge curve
//! alone, so two patches sharing an edge get the same vertices. A patch closed in u
//! (every revolved patch) may be cut at any of [`SEAM_CUTS`] angles; the cut is
//! chosen clear of every hole, and circle edges use a multiple of [`SEAM_CUTS`]
//! segments so every cut angle is a vertex of every circle.

use glam::DVec2;
use thiserror::Error;

use super::edge_parameters;
use crate::mesh::TessellationOptions;
use crate::mesh::cdt::{Region, UvLoop};
use crate::mesh::cut::Notch;
pub use crate::mesh::surface::closed_in_u;
use crate::nurbs::intersect::IntersectionLoop;
use crate::nurbs::{NurbsCurve, NurbsSurface, Side};

/// Number of evenly spaced angles (in u) at which a closed patch may be cut for
/// meshing: the quarter-circle knots and their midpoints, exact in u.
pub const SEAM_CUTS: usize = 8;

/// Why a patch's region could not be laid out.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LayoutError {
    /// Every seam cut angle of a closed patch lies inside an opening.
    #[error("openings cover every seam cut angle of the patch; spread the nozzles")]
    SeamBlocked,
    /// An opening across the patch's seam meets a patch that is also trimmed as a
    /// nozzle neck, or bites into the side a loop round the pole replaces.
    #[error(
        "an opening crosses the seam of a patch that is also trimmed as a nozzle neck, \
         or the side its loop round the pole replaces; move the nozzle inside one patch"
    )]
    NotchBlocked,
    /// An opening loop does not fit in the patch's parameter domain.
    #[error("an opening does not lie within one patch (it crosses the patch edge at v = {v})")]
    OpeningOffPatch {
        /// The offending v.
        v: f64,
    },
}

/// Relative tolerance for comparing control points and parameters.
const SAME: f64 = 1e-12;

/// Size of a curve's control polygon (for relative comparisons).
fn size(curve: &NurbsCurve) -> f64 {
    curve
        .control_points()
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs().max_element()))
        .max(1.0)
}

/// True when all points of `curve` coincide (a pole).
fn degenerate(curve: &NurbsCurve) -> bool {
    let pts = curve.control_points();
    let s = size(curve);
    pts.iter().all(|p| (*p - pts[0]).length() <= SAME * s)
}

/// Whether two curves have the same knots and homogeneous control points, bit for
/// bit.
fn same_bits(a: &NurbsCurve, b: &NurbsCurve) -> bool {
    let (ka, kb) = (a.knots(), b.knots());
    ka.degree() == kb.degree()
        && ka.as_slice().len() == kb.as_slice().len()
        && ka
            .as_slice()
            .iter()
            .zip(kb.as_slice())
            .all(|(x, y)| x.to_bits() == y.to_bits())
        && a.homogeneous_points().len() == b.homogeneous_points().len()
        && a.homogeneous_points()
            .iter()
            .zip(b.homogeneous_points())
            .all(|(p, q)| {
                p.to_array()
                    .iter()
                    .zip(q.to_array())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            })
}

/// Parameters along a side curve; a pole gives only its ends.
fn side(curve: &NurbsCurve, options: &TessellationOptions, multiple: usize) -> Vec<f64> {
    if degenerate(curve) {
        let (a, b) = curve.domain();
        vec![a, b]
    } else {
        edge_parameters(curve, options, multiple)
    }
}

/// A cut for a closed patch whose openings cover every standard cut angle: any u
/// that is a sample of both v sides (so neither neighbour gets a vertex it does
/// not have; a side collapsed to a pole has every u) and lies in no opening's
/// u-span, the one farthest from the spans; `None` when there is none.
fn other_cut(sides: &PatchSides, u0: f64, period: f64, spans: &[(f64, f64)]) -> Option<f64> {
    let on = |params: &[f64], c: f64| params.len() <= 2 || params.contains(&c);
    // Distance in u from `c` to the nearest span (each span taken in every
    // period), zero inside one.
    let clearance = |c: f64| {
        spans
            .iter()
            .flat_map(|&(lo, hi)| {
                (-1..=1).map(move |k| {
                    let shift = f64::from(k) * period;
                    (lo + shift - c).max(c - hi - shift).max(0.0)
                })
            })
            .fold(f64::INFINITY, f64::min)
    };
    let candidates: &[f64] = if sides.v0.len() > 2 {
        &sides.v0
    } else {
        &sides.v1
    };
    candidates
        .iter()
        .copied()
        .filter(|&c| c >= u0 && c < u0 + period)
        .filter(|&c| on(&sides.v0, c) && on(&sides.v1, c))
        .map(|c| (c, clearance(c)))
        .filter(|&(_, d)| d > 0.0)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(c, _)| c)
}

/// The v-side samples of a closed patch rotated to start at the cut `c`, as u values
/// from `c` to `c + period` inclusive.
fn rotated(params: &[f64], u0: f64, period: f64, c: f64) -> Vec<f64> {
    let eps = SAME * period.max(1.0) * 1e3;
    let mut rest = (params.iter().copied())
        .filter(|&t| t >= c - eps && t < u0 + period - eps)
        .chain(
            (params.iter().copied())
                .filter(|&t| t < c - eps)
                .map(|t| t + period),
        )
        .peekable();
    // `c` first, in place of a parameter within `eps` of it.
    let mut out = Vec::with_capacity(params.len() + 2);
    out.push(c);
    rest.next_if(|&t| (t - c).abs() <= eps);
    out.extend(rest);
    out.push(c + period);
    out
}

/// The u-interval of a loop shifted so its centre lies in `[c, c + period)`.
fn shifted(uv: &[DVec2], c: f64, period: f64) -> Vec<DVec2> {
    let mid = uv.iter().map(|p| p.x).sum::<f64>() / uv.len().max(1) as f64;
    let k = ((mid - c) / period).floor();
    uv.iter()
        .map(|p| DVec2::new(p.x - k * period, p.y))
        .collect()
}

/// The side at `v` through the u samples `along` (increasing), each notch (sorted
/// or not, all within `along`'s range) replacing the samples between its ends. A
/// sample closer to a notch's end than a quarter of its spacing to its neighbours
/// is left out too, unless it is a seam cut angle (a vertex of every circle), so no
/// sliver is left beside a crossing; both patches at a seam decide alike.
fn notched(
    along: &[f64],
    v: f64,
    mut notches: Vec<Vec<DVec2>>,
    u0: f64,
    period: f64,
) -> Vec<DVec2> {
    if notches.is_empty() {
        return along.iter().map(|&u| DVec2::new(u, v)).collect();
    }
    notches.sort_by(|a, b| a[0].x.total_cmp(&b[0].x));
    let eps = SAME * period.max(1.0) * 1e3;
    let ends: Vec<(f64, f64)> = notches.iter().map(|n| (n[0].x, n[n.len() - 1].x)).collect();
    let on_cut = |u: f64| {
        let step = period / SEAM_CUTS as f64;
        let k = (u - u0) / step;
        let r = (k - k.round()).abs() * step;
        r <= eps
    };
    let mut out = Vec::with_capacity(along.len() + notches.iter().map(Vec::len).sum::<usize>());
    let mut next = 0;
    for (i, &u) in along.iter().enumerate() {
        while next < notches.len() && ends[next].0 <= u + eps {
            out.extend(notches[next].iter().copied());
            next += 1;
        }
        let spacing = {
            let before = i.checked_sub(1).map_or(f64::INFINITY, |j| u - along[j]);
            let after = along.get(i + 1).map_or(f64::INFINITY, |&w| w - u);
            before.min(after)
        };
        let margin = if on_cut(u) {
            eps
        } else {
            eps.max(0.25 * spacing)
        };
        if ends
            .iter()
            .any(|&(a, b)| u >= a - margin && u <= b + margin)
        {
            continue;
        }
        out.push(DVec2::new(u, v));
    }
    for n in &notches[next..] {
        out.extend(n.iter().copied());
    }
    out
}

/// Signed area (×2) of a polygon.
fn area2(uv: &[DVec2]) -> f64 {
    (0..uv.len())
        .map(|i| uv[i].perp_dot(uv[(i + 1) % uv.len()]))
        .sum()
}

/// The loop round a pole as the top of a closed patch cut at `cut`: from
/// `cut + period` down to `cut`, starting and ending on its seam sample.
fn around_pole(l: &IntersectionLoop, cut: f64, period: f64) -> Vec<DVec2> {
    let n = l.host_uv.len();
    let on_seam = |u: f64| {
        let r = (u - cut).rem_euclid(period);
        r.min(period - r) <= 1e-9 * period
    };
    let start = (0..n).find(|&i| on_seam(l.host_uv[i].x)).unwrap_or(0);
    let mut seq: Vec<DVec2> = (0..n).map(|k| l.host_uv[(start + k) % n]).collect();
    // Unwrap continuously.
    for k in 1..seq.len() {
        let d = seq[k].x - seq[k - 1].x;
        seq[k].x -= period * (d / period).round();
    }
    let increasing = seq.last().map_or(0.0, |p| p.x) > seq[0].x;
    let first = seq[0];
    seq.push(DVec2::new(
        first.x + if increasing { period } else { -period },
        first.y,
    ));
    if increasing {
        seq.reverse();
    }
    let shift = cut + period - seq[0].x;
    seq.iter().map(|p| DVec2::new(p.x + shift, p.y)).collect()
}

/// The region of a patch: its sides, with `holes` (host-side loops of the
/// openings cutting it) and, for a nozzle neck, `bottom` replacing its v0 side.
pub fn patch_region(
    surface: &NurbsSurface,
    options: &TessellationOptions,
    holes: &[&IntersectionLoop],
    bottom: Option<&IntersectionLoop>,
) -> Result<Region, LayoutError> {
    host_region(surface, options, holes, &[], bottom)
}

/// What the layout of a patch takes from its surface and the options alone: its
/// two v-sides sampled from their edge curves (the costly part, an arc-length
/// profile of each) and the options its seam sides are sampled with. A caller that
/// lays out the same patch again with other openings may keep it
/// ([`host_region_with`]) instead of sampling the sides again.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchSides {
    /// Whether the patch closes in u (its u0 and u1 edges coincide).
    closed: bool,
    /// Parameters along the v0 side.
    v0: Vec<f64>,
    /// Parameters along the v1 side.
    v1: Vec<f64>,
    /// The options the seam sides (meridians) of the patch are sampled with.
    meridian_options: TessellationOptions,
}

impl PatchSides {
    /// The sides of `surface` sampled for `options`.
    pub fn of(surface: &NurbsSurface, options: &TessellationOptions) -> Self {
        Self::of_reusing(surface, options, None)
    }

    /// [`of`](Self::of), taking a v side's samples from `previous` (the sides an
    /// earlier surface of the same patch got with the same options) where that
    /// side's edge curve is the same to the bit: sampling is a function of the
    /// curve alone, so the result is what [`of`](Self::of) gives. A course whose
    /// length changed keeps its bottom side's samples.
    pub fn of_reusing(
        surface: &NurbsSurface,
        options: &TessellationOptions,
        previous: Option<(&NurbsSurface, &PatchSides)>,
    ) -> Self {
        let (_, (v0, v1)) = surface.domain();
        let closed = closed_in_u(surface);
        let multiple = if closed { SEAM_CUTS } else { 1 };
        let previous = previous.filter(|(_, sides)| sides.closed == closed);
        let sample = |which: Side| {
            let curve = surface.boundary(which);
            let kept = previous.and_then(|(before, sides)| {
                same_bits(&curve, &before.boundary(which)).then(|| match which {
                    Side::VMin => sides.v0.clone(),
                    _ => sides.v1.clone(),
                })
            });
            kept.unwrap_or_else(|| side(&curve, options, multiple))
        };
        let params_v0 = sample(Side::VMin);
        let params_v1 = sample(Side::VMax);
        // The seam sides of a closed patch belong to it alone: sample them no
        // coarser than `max_stretch` times the spacing along its v sides, so that the
        // triangles along a straight generator are not needles.
        let meridian_options = if let (true, Some(stretch)) = (closed, options.max_stretch) {
            let spacing = |params: &[f64], v: f64| {
                params
                    .windows(2)
                    .map(|w| (surface.point(w[1], v) - surface.point(w[0], v)).length())
                    .fold(0.0f64, f64::max)
            };
            let across = [spacing(&params_v0, v0), spacing(&params_v1, v1)]
                .into_iter()
                .filter(|&s| s > SAME)
                .fold(f64::INFINITY, f64::min);
            if across.is_finite() {
                let cap = stretch * across;
                options
                    .with_max_edge_length(Some(options.max_edge_length.map_or(cap, |m| m.min(cap))))
            } else {
                *options
            }
        } else {
            *options
        };
        Self {
            closed,
            v0: params_v0,
            v1: params_v1,
            meridian_options,
        }
    }

    /// Heap bytes held.
    pub fn heap_bytes(&self) -> usize {
        (self.v0.capacity() + self.v1.capacity()) * std::mem::size_of::<f64>()
    }
}

/// [`patch_region`] with `notches` too: pieces of openings that cross the patch's
/// v0 or v1 side (a seam with its neighbour), each replacing the side's samples
/// between its ends.
pub fn host_region(
    surface: &NurbsSurface,
    options: &TessellationOptions,
    holes: &[&IntersectionLoop],
    notches: &[&Notch],
    bottom: Option<&IntersectionLoop>,
) -> Result<Region, LayoutError> {
    let sides = PatchSides::of(surface, options);
    host_region_with(surface, &sides, holes, notches, bottom)
}

/// [`host_region`] with the patch's `sides` already sampled ([`PatchSides::of`] the
/// same surface, for the options the region is laid out for): the same region,
/// without sampling them again.
pub fn host_region_with(
    surface: &NurbsSurface,
    sides: &PatchSides,
    holes: &[&IntersectionLoop],
    notches: &[&Notch],
    bottom: Option<&IntersectionLoop>,
) -> Result<Region, LayoutError> {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let period = u1 - u0;
    let closed = sides.closed;
    // A loop round the pole (a nozzle centred on a head) replaces the pole side.
    let (around, holes): (Vec<&IntersectionLoop>, Vec<&IntersectionLoop>) = holes
        .iter()
        .copied()
        .partition(|h| closed && h.host_turns(surface) != 0);
    if around.len() > 1 {
        return Err(LayoutError::SeamBlocked);
    }
    let top = around.first().copied();
    // A loop round the pole replaces the v1 side: notches may bite into the v0
    // side only (the crown of a head with a centre nozzle and an opening across
    // its knuckle seam). A neck's cut bottom takes no notch.
    let notched_top = notches.iter().any(|n| n.side == Side::VMax);
    if (top.is_some() && notched_top) || (!notches.is_empty() && bottom.is_some()) {
        return Err(LayoutError::NotchBlocked);
    }
    // The u-spans of the holes and notches (after shifting each into one period).
    let spans: Vec<(f64, f64)> = holes
        .iter()
        .map(|h| h.host_uv.as_slice())
        .chain(notches.iter().map(|n| n.path.as_slice()))
        .map(|uv| {
            let s = shifted(uv, u0, period);
            let lo = s.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
            let hi = s.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        })
        .collect();
    let blocked = |c: f64| {
        spans
            .iter()
            .any(|&(lo, hi)| (-1..=1).any(|k| (lo..=hi).contains(&(c + f64::from(k) * period))))
    };
    // Choose the cut clear of every hole and notch.
    let cut = if top.is_some() {
        // The loop has a sample exactly on the seam angle u0: cut there.
        if blocked(u0) {
            return Err(LayoutError::SeamBlocked);
        }
        u0
    } else if closed && !spans.is_empty() {
        (0..SEAM_CUTS)
            .map(|k| u0 + period * k as f64 / SEAM_CUTS as f64)
            .find(|&c| !blocked(c))
            .or_else(|| other_cut(sides, u0, period, &spans))
            .ok_or(LayoutError::SeamBlocked)?
    } else {
        u0
    };
    let (left_u, right_u) = (cut, cut + if closed { period } else { u1 - u0 });
    let (params_v0, params_v1) = (&sides.v0, &sides.v1);
    let meridian_options = sides.meridian_options;
    let (along_v0, along_v1) = if closed {
        (
            rotated(params_v0, u0, period, cut),
            rotated(params_v1, u0, period, cut),
        )
    } else {
        (params_v0.clone(), params_v1.clone())
    };
    // Each notch shifted into the window [cut, cut + period], by side.
    let window = |side: Side| -> Vec<Vec<DVec2>> {
        notches
            .iter()
            .filter(|n| n.side == side)
            .map(|n| {
                if closed {
                    shifted(&n.path, cut, period)
                } else {
                    n.path.clone()
                }
            })
            .collect()
    };
    let (notches_v0, notches_v1) = (window(Side::VMin), window(Side::VMax));
    let mut outer: Vec<DVec2> = Vec::new();
    // Bottom: the v0 side, or the neck's intersection loop.
    let bottom_start_v;
    match bottom {
        Some(l) => {
            // Each sample wrapped into [cut, cut + period); the loop is monotonic in
            // neck u, so starting at the smallest u gives it in order.
            let mut pts: Vec<DVec2> = l
                .neck_uv
                .iter()
                .map(|p| DVec2::new(cut + (p.x - cut).rem_euclid(period), p.y))
                .collect();
            let start = pts
                .iter()
                .enumerate()
                .min_by(|a, b| a.1.x.total_cmp(&b.1.x))
                .map_or(0, |(i, _)| i);
            pts.rotate_left(start);
            bottom_start_v = pts.first().map_or(v0, |p| p.y);
            let first_u = pts.first().map_or(cut, |p| p.x);
            outer.extend(pts.iter().copied());
            // Close the turn at the seam on the right.
            outer.push(DVec2::new(first_u + period, bottom_start_v));
        }
        None => {
            bottom_start_v = v0;
            outer.extend(notched(&along_v0, v0, notches_v0, u0, period));
        }
    }
    let right_u_end = outer.last().map_or(right_u, |p| p.x);
    // The top: the v1 side from right to left, or the loop round the pole.
    let top_path: Vec<DVec2> = match top {
        Some(l) => around_pole(l, cut, period),
        None => {
            let shift = right_u_end - along_v1.last().copied().unwrap_or(right_u);
            let mut path = notched(&along_v1, v1, notches_v1, u0, period);
            path.reverse();
            path.iter_mut().for_each(|p| p.x += shift);
            path
        }
    };
    let top_v = top_path.first().map_or(v1, |p| p.y);
    let top_end_v = top_path.last().map_or(v1, |p| p.y);
    // Right side up, from the bottom to the top (interior samples of the meridian).
    let meridian = surface.isocurve_u(crate::mesh::cdt::wrap_u(surface, right_u_end));
    let right = side(&meridian, &meridian_options, 1);
    for &v in &right {
        if v > bottom_start_v.max(v0) + SAME && v < top_v - SAME {
            outer.push(DVec2::new(right_u_end, v));
        }
    }
    let top_left_u = outer.first().map_or(left_u, |p| p.x);
    outer.extend(top_path);
    // Left side down, interior samples only. On a closed patch it is the same
    // meridian a period to the left (the seam): the right side's samples serve.
    let left_side = if closed {
        right
    } else {
        side(
            &surface.isocurve_u(crate::mesh::cdt::wrap_u(surface, top_left_u)),
            &meridian_options,
            1,
        )
    };
    let mut left: Vec<f64> = left_side
        .into_iter()
        .filter(|&v| v > bottom_start_v.max(v0) + SAME && v < top_end_v - SAME)
        .collect();
    left.reverse();
    outer.extend(left.into_iter().map(|v| DVec2::new(top_left_u, v)));
    outer.dedup_by(|a, b| (*a - *b).length() <= SAME);
    if outer.len() > 1 && (outer[0] - outer[outer.len() - 1]).length() <= SAME {
        outer.pop();
    }
    let mut region = Region::new(UvLoop::new(outer));
    for h in holes {
        let mut uv = shifted(&h.host_uv, cut, period);
        if let Some(p) = uv.iter().find(|p| {
            p.y < v0 - SAME || p.y > v1 + SAME || (!closed && (p.x < u0 - SAME || p.x > u1 + SAME))
        }) {
            return Err(LayoutError::OpeningOffPatch { v: p.y });
        }
        if area2(&uv) > 0.0 {
            uv.reverse();
        }
        region = region.with_hole(UvLoop::new(uv));
    }
    Ok(region)
}

/// The region of a reinforcing pad: the part of its host patch between the pad's
/// outer loop and the neck's loop (both in the host patch's (u, v)). Around a pole
/// both loops go round it and the region is the band between them, cut at the seam.
pub fn pad_region(
    surface: &NurbsSurface,
    options: &TessellationOptions,
    outer: &IntersectionLoop,
    inner: &IntersectionLoop,
) -> Result<Region, LayoutError> {
    let ((u0, u1), _) = surface.domain();
    let period = u1 - u0;
    let closed = closed_in_u(surface);
    let around = closed && outer.host_turns(surface) != 0;
    if around != (closed && inner.host_turns(surface) != 0) {
        return Err(LayoutError::SeamBlocked);
    }
    if !around {
        let mut o = shifted(&outer.host_uv, u0, period);
        let shift = o[0].x - outer.host_uv[0].x;
        let mut i: Vec<DVec2> = inner
            .host_uv
            .iter()
            .map(|p| DVec2::new(p.x + shift, p.y))
            .collect();
        // Keep the inner loop in the outer loop's period.
        let mid_o = o.iter().map(|p| p.x).sum::<f64>() / o.len() as f64;
        let mid_i = i.iter().map(|p| p.x).sum::<f64>() / i.len() as f64;
        let k = ((mid_i - mid_o) / period).round();
        i.iter_mut().for_each(|p| p.x -= k * period);
        if area2(&o) < 0.0 {
            o.reverse();
        }
        if area2(&i) > 0.0 {
            i.reverse();
        }
        return Ok(Region::new(UvLoop::new(o)).with_hole(UvLoop::new(i)));
    }
    // Both round the pole: bottom = the pad's loop (further from the pole), top =
    // the neck's, both cut at the seam u0 where each has a sample.
    let cut = u0;
    let mut bottom = around_pole(outer, cut, period);
    bottom.reverse(); // from cut to cut + period
    let top = around_pole(inner, cut, period); // from cut + period to cut
    let (vb, vt) = (
        bottom.first().map_or(0.0, |p| p.y),
        top.first().map_or(0.0, |p| p.y),
    );
    let (lo, hi) = (vb.min(vt), vb.max(vt));
    let meridian = surface.isocurve_u(cut);
    let inside: Vec<f64> = side(&meridian, options, 1)
        .into_iter()
        .filter(|&v| v > lo + SAME && v < hi - SAME)
        .collect();
    let mut outer_loop = bottom;
    outer_loop.extend(inside.iter().map(|&v| DVec2::new(cut + period, v)));
    outer_loop.extend(top);
    outer_loop.extend(inside.iter().rev().map(|&v| DVec2::new(cut, v)));
    if area2(&outer_loop) < 0.0 {
        outer_loop.reverse();
    }
    Ok(Region::new(UvLoop::new(outer_loop)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parts::Shell;

    fn course(od: f64, length: f64) -> NurbsSurface {
        let patches = Shell {
            outside_diameter: od,
            length,
        }
        .patches()
        .expect("a valid course");
        patches[0].surface.clone()
    }

    /// Bits of a side's samples, so that equality is exact.
    fn bits(params: &[f64]) -> Vec<u64> {
        params.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn reused_sides_are_the_sides_sampled_afresh() {
        let options = TessellationOptions::chord(0.3);
        let short = course(2400.0, 3000.0);
        let kept = PatchSides::of(&short, &options);
        // Longer: the bottom circle is the same curve, the top one moved.
        let long = course(2400.0, 3200.0);
        let fresh = PatchSides::of(&long, &options);
        let reused = PatchSides::of_reusing(&long, &options, Some((&short, &kept)));
        assert_eq!(bits(&reused.v0), bits(&fresh.v0));
        assert_eq!(bits(&reused.v1), bits(&fresh.v1));
        assert_eq!(reused, fresh);
        assert!(same_bits(
            &short.boundary(Side::VMin),
            &long.boundary(Side::VMin)
        ));
        assert!(!same_bits(
            &short.boundary(Side::VMax),
            &long.boundary(Side::VMax)
        ));
        // Wider: neither side is the same curve, so neither is taken; a kept side
        // of another diameter would have too few samples for this one.
        let wide = course(3600.0, 3000.0);
        let fresh = PatchSides::of(&wide, &options);
        let reused = PatchSides::of_reusing(&wide, &options, Some((&short, &kept)));
        assert_eq!(reused, fresh);
        assert_ne!(fresh.v0.len(), kept.v0.len());
    }
}
