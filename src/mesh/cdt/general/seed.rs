//! Interior seed points: a structured lattice sized by the curvature metric and
//! clipped to the region.
//!
//! Rows run at constant v (the parallels of a revolved patch, so a row's point count
//! follows its radius and shrinks to a few points next to a pole). Row positions come
//! from integrating the metric's spacing across v inside each v knot span, so every
//! interior v knot is a row; each row's points come from integrating the metric's
//! spacing along u, shifted by half a step on every other row, which makes the
//! lattice equilateral in the metric: its triangles deviate from the surface by about
//! the sizing's δ. Points outside the outer loop, inside a hole or nearer a loop than
//! [`MARGIN`] of the local spacing are dropped, so boundary triangles stay well
//! shaped and no seed can fall on a loop segment.

use glam::DVec2;
use rayon::prelude::*;

use crate::mesh::cdt::CdtError;
use crate::mesh::cdt::metric::Metric;
use crate::mesh::cdt::patch::PatchInfo;
use crate::mesh::cdt::region::{Region, inside_by_crossings};

/// Evaluation samples per knot span when integrating spacings.
const SAMPLES_PER_SPAN: usize = 8;
/// Samples per u knot span of each row's spacing profile: the spacing along a
/// row varies only as smoothly as the parametrization's speed (a rational arc's
/// varies by a factor of at most 1.4 over a quarter), which 4 trapezoids follow
/// to well under a percent.
const ROW_SAMPLES_PER_U_SPAN: usize = 4;
/// Samples per u knot span of the grid giving the row density across v (its
/// maximum over u) and the lattice size estimate. Coarser than
/// [`ROW_SAMPLES_PER_U_SPAN`]: on a revolved patch the spacing across v does not depend
/// on u at all, and elsewhere the density only sizes the lattice (the chordal
/// bound comes from the screen and refinement); the full grid was most of a
/// small patch's planning time.
const GRID_SAMPLES_PER_U_SPAN: usize = 2;
/// Seeds closer to a loop than this many local spacings are dropped.
pub(in crate::mesh::cdt) const MARGIN: f64 = 0.55;
/// Consecutive rows keep one point count while it is at most this factor above
/// what the row needs.
const COUNT_SLACK: f64 = 1.1;
/// Fewest points of a row [`pole_rows`] adds (a whole turn round a pole).
const POLE_ROW_POINTS: usize = 8;
/// Row spacing of an equilateral lattice with unit edges.
const ROW_HEIGHT: f64 = 0.866_025_403_784_438_6;

/// `intervals + 1` evenly spaced samples of `[a, b]` (at least 2 intervals).
fn samples(a: f64, b: f64, intervals: usize) -> Vec<f64> {
    let n = intervals.max(2);
    (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect()
}

/// Cumulative integral of `density` over `params` (trapezoids).
fn cumulative(params: &[f64], density: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; params.len()];
    for k in 1..params.len() {
        out[k] = out[k - 1] + 0.5 * (density[k] + density[k - 1]) * (params[k] - params[k - 1]);
    }
    out
}

/// Points along `params` at shares `k + offset` (k = 0, 1, …) of `n` equal shares
/// of the integral `cumulative`, up to the last parameter.
fn place(params: &[f64], cumulative: &[f64], n: usize, offset: f64) -> Vec<f64> {
    let total = cumulative[params.len() - 1];
    if !(total.is_finite() && total > 0.0 && n > 0) {
        return Vec::new();
    }
    let n = n as f64;
    let mut out = Vec::with_capacity(n as usize + 1);
    let mut seg = 1;
    let mut k = offset;
    while k <= n + 1e-9 {
        let target = total * (k / n).min(1.0);
        while seg < params.len() - 1 && cumulative[seg] < target {
            seg += 1;
        }
        let (c0, c1) = (cumulative[seg - 1], cumulative[seg]);
        let t = if c1 > c0 {
            (target - c0) / (c1 - c0)
        } else {
            0.0
        };
        out.push(params[seg - 1] + t.clamp(0.0, 1.0) * (params[seg] - params[seg - 1]));
        k += 1.0;
    }
    out
}

/// `per_span` samples per u knot span across `lo.x..hi.x`.
fn u_samples(info: &PatchInfo, lo: DVec2, hi: DVec2, per_span: usize) -> Vec<f64> {
    let (u0, u1) = info.surface.u_knots().domain();
    let u_spans = info.surface.u_knots().spans().len().max(1);
    let periods = (hi.x - lo.x) / (u1 - u0);
    samples(
        lo.x,
        hi.x,
        (per_span as f64 * u_spans as f64 * periods).ceil() as usize,
    )
}

/// The u samples across `lo..hi` and the v samples of each v knot span inside it.
fn sample_grid(info: &PatchInfo, lo: DVec2, hi: DVec2) -> (Vec<f64>, Vec<Vec<f64>>) {
    let surface = info.surface;
    let us = u_samples(info, lo, hi, ROW_SAMPLES_PER_U_SPAN);
    let mut v_spans: Vec<Vec<f64>> = Vec::new();
    for (a, b) in surface.v_knots().spans() {
        let (a, b) = (a.max(lo.y), b.min(hi.y));
        if b > a {
            v_spans.push(samples(a, b, SAMPLES_PER_SPAN));
        }
    }
    if v_spans.is_empty() {
        v_spans.push(samples(lo.y, hi.y, SAMPLES_PER_SPAN));
    }
    (us, v_spans)
}

/// The lattice's plan: u samples, one profile per row (constant v, increasing),
/// and each row's point count.
struct Plan {
    us: Vec<f64>,
    profiles: Vec<RowProfile>,
    counts: Vec<usize>,
}

/// Plans the lattice of `region`, or [`CdtError::BudgetExceeded`] when it would
/// exceed `budget` points (the error counts seeds alone: the caller adds the
/// loop vertices and names the option).
fn plan(info: &PatchInfo, region: &Region, budget: usize) -> Result<Plan, CdtError> {
    let (lo, hi) = region.bounds();
    let (us, v_spans) = sample_grid(info, lo, hi);
    let grid_us = u_samples(info, lo, hi, GRID_SAMPLES_PER_U_SPAN);
    // On a surface swept straight along Z (a course) every row is the same
    // cross-section: its metrics are the first row's, evaluated once.
    let swept = info.swept.is_some();
    // Row density across v (max over u) and an estimate of the lattice size.
    let mut rows: Vec<f64> = Vec::new();
    let mut estimate = 0.0;
    for vs in &v_spans {
        let metrics: Vec<Vec<Metric>> = if swept {
            vec![info.row_metrics(vs[0], &grid_us); vs.len()]
        } else {
            vs.par_iter()
                .map(|&v| info.row_metrics(v, &grid_us))
                .collect()
        };
        let density: Vec<f64> = metrics
            .iter()
            .map(|row| row.iter().map(Metric::across_v).fold(0.0, f64::max) / ROW_HEIGHT)
            .collect();
        for (j, w) in vs.windows(2).enumerate() {
            for (i, x) in grid_us.windows(2).enumerate() {
                let cell = [
                    metrics[j][i],
                    metrics[j][i + 1],
                    metrics[j + 1][i],
                    metrics[j + 1][i + 1],
                ];
                let area = Metric::mean(&cell).det().max(0.0).sqrt();
                estimate += area * (x[1] - x[0]) * (w[1] - w[0]) / ROW_HEIGHT;
            }
        }
        if estimate.is_nan() || estimate > budget as f64 {
            return Err(CdtError::BudgetExceeded {
                max_vertices: budget,
                needed: if estimate.is_nan() {
                    budget + 1
                } else {
                    estimate.ceil() as usize
                },
            });
        }
        let total = cumulative(vs, &density);
        let count = total[total.len() - 1].ceil() as usize;
        let placed = place(vs, &total, count.max(1), 0.0);
        let placed = if placed.is_empty() {
            vec![vs[0], vs[vs.len() - 1]]
        } else {
            placed
        };
        for v in placed {
            if rows.last().is_none_or(|&last| v > last) {
                rows.push(v);
            }
        }
    }
    let profiles: Vec<RowProfile> = match rows.first() {
        Some(&first) if swept => {
            let profile = RowProfile::new(info, &us, first);
            rows.iter()
                .map(|&v| RowProfile {
                    v,
                    ..profile.clone()
                })
                .collect()
        }
        _ => rows
            .par_iter()
            .map(|&v| RowProfile::new(info, &us, v))
            .collect(),
    };
    let counts = row_counts(&profiles);
    let total: usize = counts.iter().sum();
    if total > budget {
        return Err(CdtError::BudgetExceeded {
            max_vertices: budget,
            needed: total,
        });
    }
    Ok(Plan {
        us,
        profiles,
        counts,
    })
}

/// The seed points of `region` (rows of constant v, increasing u), or
/// [`CdtError::BudgetExceeded`] when the lattice would exceed `budget` points.
pub(in crate::mesh::cdt) fn seeds(
    info: &PatchInfo,
    region: &Region,
    budget: usize,
) -> Result<Vec<DVec2>, CdtError> {
    let Plan {
        us,
        profiles,
        counts,
    } = plan(info, region, budget)?;
    let segments: Vec<(DVec2, DVec2)> = region.loops().flat_map(|l| l.segments()).collect();
    let per_row: Vec<Vec<DVec2>> = profiles
        .par_iter()
        .zip(counts.par_iter())
        .enumerate()
        .map(|(r, (profile, &n))| profile.seeds(region, &segments, &us, n, r % 2 == 1))
        .collect();
    let mut out: Vec<DVec2> = per_row.into_iter().flatten().collect();
    let extra = pole_rows(info, region, &us, &out);
    out.extend(extra);
    Ok(out)
}

/// A row of seeds halfway between each pole and the loop vertex nearest it, for
/// every collapsed side with no seed nearer the pole than that vertex (a cone:
/// straight generators need no rows).
///
/// Without it spade fans the pole's vertices straight to the loops. A triangle
/// of a loop segment and a pole vertex is turned over on the surface when the
/// segment runs nearly along a generator and the line through it passes the apex
/// on the loop's side: the pole is one point, so no choice of its (u, v) mends
/// that, and refinement, splitting such triangles at their centroids, only
/// adds triangles with the same pole corner (a conical roof with two openings
/// ran past 50 000 vertices at 1 and 0.7 mm). With a row in between, the pole
/// is zipped to the row ([`with_pole_vertices`]) and the loops meet the row.
fn pole_rows(info: &PatchInfo, region: &Region, us: &[f64], seeds: &[DVec2]) -> Vec<DVec2> {
    let (_, (v0, v1)) = info.surface.domain();
    let eps = 1e-12 * (v1 - v0).abs().max(f64::MIN_POSITIVE);
    let mut out = Vec::new();
    for (collapsed, pole) in [(info.collapsed[2], v0), (info.collapsed[3], v1)] {
        if !collapsed {
            continue;
        }
        let nearest = region
            .loops()
            .flat_map(|l| l.uv.iter())
            .map(|p| (p.y - pole).abs())
            .filter(|&d| d > eps)
            .fold(f64::INFINITY, f64::min);
        if !nearest.is_finite() || seeds.iter().any(|s| (s.y - pole).abs() < nearest) {
            continue;
        }
        // Every loop vertex, and so every loop segment off the seam, is at
        // least `nearest / 2` away across v; along the row the points keep
        // [`MARGIN`] of their spacing from where loops cross it (the seam).
        let v = pole + 0.5 * nearest * if pole == v0 { 1.0 } else { -1.0 };
        let profile = RowProfile::new(info, us, v);
        let n = (profile.total().ceil() as usize).max(POLE_ROW_POINTS);
        let placed = place(us, &profile.cumulative, n, 0.5);
        let mut crossings = Vec::new();
        region.row_crossings(v, &mut crossings);
        for (k, &u) in placed.iter().enumerate() {
            let before = k.checked_sub(1).map_or(f64::INFINITY, |j| u - placed[j]);
            let after = placed.get(k + 1).map_or(f64::INFINITY, |&w| w - u);
            let step = before.min(after);
            let step = if step.is_finite() {
                step
            } else {
                us[us.len() - 1] - us[0]
            };
            if inside_by_crossings(&crossings, u)
                && crossings.iter().all(|&c| (c - u).abs() >= MARGIN * step)
            {
                out.push(DVec2::new(u, v));
            }
        }
    }
    out
}

/// The region with vertices added along each side of its outer loop that
/// collapses to a pole: one under the middle of every two neighbouring seeds of
/// the seed row nearest the pole (as the structured path's pole chains), or of
/// the opposite side's loop vertices when there are no seeds, in the loop's
/// order; `None` when nothing is added.
///
/// A pole side comes from the layout as one segment from seam to seam. spade
/// then joins the interior vertices near the pole to its two ends, a fan whose
/// raw (u, v) order is not the order of the vertices round the pole: a vertex
/// nearer the pole at a smaller u can sit on the wrong side of the (u, v) line from
/// the corner to one farther away. Such a triangle is valid in (u, v) and turned
/// over on the surface, and splitting it only ever adds vertices on that line,
/// so refinement ran away (a conical roof with an opening near its apex reached
/// millions of vertices). With a pole vertex under every gap of the nearest row,
/// the row and the pole are zipped like any two rows instead.
pub(in crate::mesh::cdt) fn with_pole_vertices(
    info: &PatchInfo,
    region: &Region,
    seeds: &[DVec2],
) -> Option<Region> {
    let (_, (v0, v1)) = info.surface.domain();
    let eps = 1e-12 * (v1 - v0).abs().max(f64::MIN_POSITIVE);
    let at = |v: f64, w: f64| (v - w).abs() <= eps;
    let pole_v = |a: DVec2, b: DVec2| {
        [(info.collapsed[2], v0), (info.collapsed[3], v1)]
            .into_iter()
            .find(|&(collapsed, v)| collapsed && at(a.y, v) && at(b.y, v))
            .map(|(_, v)| v)
    };
    let loop_uv = &region.outer.uv;
    let n = loop_uv.len();
    let mut outer = Vec::with_capacity(n);
    let mut added = false;
    for k in 0..n {
        let (a, b) = (loop_uv[k], loop_uv[(k + 1) % n]);
        outer.push(a);
        let Some(v) = pole_v(a, b) else {
            continue;
        };
        // Without seeds (a cone: straight generators need no rows) the row is
        // the opposite side's loop vertices.
        let other = if v == v0 { v1 } else { v0 };
        let row_of: &[DVec2] = if seeds.is_empty() { loop_uv } else { seeds };
        let nearest = if seeds.is_empty() {
            (other - v).abs()
        } else {
            seeds
                .iter()
                .map(|s| (s.y - v).abs())
                .fold(f64::INFINITY, f64::min)
        };
        let mut row: Vec<f64> = row_of
            .iter()
            .filter(|s| ((s.y - v).abs() - nearest).abs() <= eps)
            .map(|s| s.x)
            .collect();
        row.sort_by(f64::total_cmp);
        let (lo, hi) = (a.x.min(b.x), a.x.max(b.x));
        let margin = 1e-9 * (hi - lo);
        let mut mids: Vec<f64> = row
            .windows(2)
            .map(|w| 0.5 * (w[0] + w[1]))
            .filter(|&u| u > lo + margin && u < hi - margin)
            .collect();
        if a.x > b.x {
            mids.reverse();
        }
        added |= !mids.is_empty();
        outer.extend(mids.into_iter().map(|u| DVec2::new(u, v)));
    }
    added.then(|| Region {
        outer: crate::mesh::cdt::region::UvLoop::new(outer),
        holes: region.holes.clone(),
    })
}

/// The lattice's rows strictly inside `lo.y..hi.y` across the whole u range of the
/// region, as `(v, u values)`: every row runs from `lo.x` to `hi.x` (the ends
/// included), every other one shifted by half a step in between. The rows of the
/// structured path for whole closed patches, where the row ends lie on the seam.
pub(in crate::mesh::cdt) fn rows(
    info: &PatchInfo,
    region: &Region,
    budget: usize,
) -> Result<Vec<(f64, Vec<f64>)>, CdtError> {
    let (lo, hi) = region.bounds();
    let eps = 1e-9 * (hi.y - lo.y);
    let Plan {
        us,
        profiles,
        counts,
    } = plan(info, region, budget)?;
    let out = profiles
        .iter()
        .zip(&counts)
        .filter(|(p, _)| p.v > lo.y + eps && p.v < hi.y - eps)
        .enumerate()
        .map(|(r, (p, &n))| {
            let mut u = place(&us, &p.cumulative, n, if r % 2 == 1 { 0.5 } else { 0.0 });
            if r % 2 == 1 {
                u.insert(0, lo.x);
                u.push(hi.x);
            }
            // The ends exactly on the seam; no repeated values.
            if let Some(first) = u.first_mut() {
                *first = lo.x;
            }
            if let Some(last) = u.last_mut() {
                *last = hi.x;
            }
            u.dedup_by(|a, b| *a <= *b);
            (p.v, u)
        })
        .collect();
    Ok(out)
}

/// Point counts per row: each row needs at least the integral of its spacing
/// along u; consecutive rows keep the same count while it stays within
/// [`COUNT_SLACK`] of that, so that blocks of rows form an exact lattice.
fn row_counts(profiles: &[RowProfile]) -> Vec<usize> {
    let mut counts = Vec::with_capacity(profiles.len());
    let mut previous: Option<(usize, f64)> = None;
    for p in profiles {
        let need = p.total();
        let n = match previous {
            Some((n, _)) if need <= n as f64 && (n as f64) <= need * COUNT_SLACK => n,
            Some((_, last)) if need > last => {
                (need * COUNT_SLACK).floor().max(need.ceil()) as usize
            }
            _ => need.ceil() as usize,
        };
        counts.push(n.max(1));
        previous = Some((n.max(1), need));
    }
    counts
}

/// The metric along one row and the integral of its spacing.
#[derive(Clone)]
struct RowProfile {
    v: f64,
    metrics: Vec<Metric>,
    cumulative: Vec<f64>,
}

impl RowProfile {
    fn new(info: &PatchInfo, us: &[f64], v: f64) -> Self {
        let metrics = info.row_metrics(v, us);
        let density: Vec<f64> = metrics.iter().map(Metric::along_u).collect();
        let cumulative = cumulative(us, &density);
        Self {
            v,
            metrics,
            cumulative,
        }
    }

    /// Unit spacings along the row.
    fn total(&self) -> f64 {
        self.cumulative[self.cumulative.len() - 1]
    }

    /// The row's `n`-share points, shifted by half a share when `odd`, inside the
    /// region and clear of its loops.
    fn seeds(
        &self,
        region: &Region,
        segments: &[(DVec2, DVec2)],
        us: &[f64],
        n: usize,
        odd: bool,
    ) -> Vec<DVec2> {
        let v = self.v;
        let placed = place(us, &self.cumulative, n, if odd { 0.5 } else { 0.0 });
        let mut crossings = Vec::new();
        region.row_crossings(v, &mut crossings);
        // Loop segments that can come within the margin of this row.
        let reach = self
            .metrics
            .iter()
            .map(|m| m.ball_extent(MARGIN).y)
            .fold(0.0, f64::max);
        let near: Vec<(DVec2, DVec2)> = segments
            .iter()
            .copied()
            .filter(|(a, b)| a.y.min(b.y) <= v + reach && a.y.max(b.y) >= v - reach)
            .collect();
        let mut out = Vec::with_capacity(placed.len());
        for u in placed {
            if !inside_by_crossings(&crossings, u) {
                continue;
            }
            let k = us.partition_point(|&s| s < u).min(us.len() - 1);
            let metric = self.metrics[k];
            let p = DVec2::new(u, v);
            let box_u = metric.ball_extent(MARGIN).x;
            let clear = near.iter().all(|&(a, b)| {
                a.x.min(b.x) > u + box_u
                    || a.x.max(b.x) < u - box_u
                    || distance_sq(metric, p, a, b) >= MARGIN * MARGIN
            });
            if clear {
                out.push(p);
            }
        }
        out
    }
}

/// Squared metric distance from `p` to the segment `a`–`b`.
fn distance_sq(metric: Metric, p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let (ab, ap) = (b - a, p - a);
    let len = metric.length_sq(ab);
    let dot =
        metric.uu * ab.x * ap.x + metric.uv * (ab.x * ap.y + ab.y * ap.x) + metric.vv * ab.y * ap.y;
    let t = if len > 0.0 {
        (dot / len).clamp(0.0, 1.0)
    } else {
        0.0
    };
    metric.length_sq(ap - ab * t)
}
