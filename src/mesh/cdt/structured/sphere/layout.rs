//! The greedy rows of a sphere patch from its ring to its pole: part of
//! `structured::sphere`, which converts them to the surface's (u, v) rows.
//!
//! Each next row is the same count shifted by half a step (a strip of
//! near-isosceles triangles) or, when that covers too little, one of a few
//! smaller counts, each raised as far towards the pole as the zip of the two
//! rows keeps every triangle within the bound (`bound::zip_slack`); the
//! candidate covering the most area per triangle is kept, and the pole's fan
//! ends the rows once it fits and covers more.
//!
//! A candidate's height is searched between the least that would beat the
//! best so far (tried first: most candidates stop there) and a ceiling no row
//! of its count can pass ([`ceiling`], from the reach of its edges), by
//! regula falsi on the zip's least slack. Layouts are kept by what decides
//! them, bit for bit ([`laid_out`]).

use std::f64::consts::TAU;
use std::sync::{Mutex, PoisonError};

use glam::DVec3;

use super::bound::{Bound, zip_slack};
use super::row::{Row, Spacing};
use crate::mesh::cdt::CdtError;

/// A row's height is found to this share of its ceiling.
const PRECISION: f64 = 1e-4;

/// Smaller counts tried for the next row: `n·(1 − k/16)` for k = 1..=SMALLER.
const SMALLER: usize = 8;

/// A staggered row covering at least this share of an ideal triangle's area
/// per triangle is taken without trying smaller counts (they win only where
/// the shrinking parallels have squeezed the staggered strips).
const GOOD_ENOUGH: f64 = 0.9;

/// Layouts kept for reuse, most recent last.
const KEPT: usize = 64;

/// Segments seam to seam of a row of `count` vertices, shifted or not.
fn segments(count: usize, shifted: bool) -> usize {
    count + usize::from(shifted)
}

/// The spacings of one layout's rows and candidates.
#[derive(Default)]
struct Spacings(Vec<(usize, bool, Spacing)>);

impl Spacings {
    /// The index of the spacing of `count` vertices, shifted or not, made if
    /// new.
    fn index(&mut self, count: usize, shifted: bool) -> usize {
        match self.0.iter().position(|s| s.0 == count && s.1 == shifted) {
            Some(k) => k,
            None => {
                self.0.push((count, shifted, Spacing::new(count, shifted)));
                self.0.len() - 1
            }
        }
    }

    /// Forgets the spacings of more than `count` vertices: rows only get fewer.
    fn keep_up_to(&mut self, count: usize) {
        self.0.retain(|s| s.0 <= count);
    }
}

/// What decides a layout, bit for bit: the radius, the tolerance and edge
/// limit the rows hold, the ring's colatitude and count.
type Key = [u64; 5];

/// Layouts made so far in this process, by [`Key`], most recent last: a plant
/// repeats its diameters, and both heads of a vessel often share their crown.
/// A layout is reused only for exactly the sphere, bound and ring it was made
/// for, so it is the layout [`lay_out`] would make again.
static LAYOUTS: Mutex<Vec<(Key, Option<Vec<Row>>)>> = Mutex::new(Vec::new());

/// [`lay_out`], through [`LAYOUTS`]; the budget is checked on a kept layout
/// as it would be on a new one.
pub(super) fn laid_out(
    bound: &Bound,
    first: Row,
    budget: usize,
) -> Result<Option<Vec<Row>>, CdtError> {
    let key = [
        bound.r.to_bits(),
        bound.tolerance.to_bits(),
        bound.max_chord.to_bits(),
        first.phi.to_bits(),
        first.count as u64,
    ];
    let kept = {
        let layouts = LAYOUTS.lock().unwrap_or_else(PoisonError::into_inner);
        layouts
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, rows)| rows.clone())
    };
    let Some(rows) = kept else {
        let rows = lay_out(bound, first, budget)?;
        let mut layouts = LAYOUTS.lock().unwrap_or_else(PoisonError::into_inner);
        if layouts.len() >= KEPT {
            layouts.remove(0);
        }
        layouts.push((key, rows.clone()));
        return Ok(rows);
    };
    let placed: usize = rows
        .iter()
        .flatten()
        .map(|row| segments(row.count, row.shifted) + 1)
        .sum();
    if placed > budget {
        return Err(CdtError::BudgetExceeded {
            max_vertices: budget,
            needed: placed,
        });
    }
    Ok(rows)
}

/// A candidate row: its count, whether shifted, and its [`ceiling`].
type Candidate = (usize, bool, (f64, f64));

/// The greedy rows from the ring `first` to the pole (the ring and the pole
/// excluded); `None` when no row fits and the pole's fan does not either.
pub(super) fn lay_out(
    bound: &Bound,
    first: Row,
    budget: usize,
) -> Result<Option<Vec<Row>>, CdtError> {
    let (r, tolerance) = (bound.r, bound.tolerance);
    // Area per triangle of the ideal mesh: equilateral, circumradius at the bound.
    let ideal = 0.75 * 3f64.sqrt() * (2.0 * r * tolerance - tolerance * tolerance);
    // The area between colatitudes a < b.
    let band = |a: f64, b: f64| TAU * r * r * (a.cos() - b.cos());
    let pole = DVec3::new(0.0, 0.0, r);
    let mut spacings = Spacings::default();
    let mut rows: Vec<Row> = Vec::new();
    let mut current = first;
    let mut placed = 0usize;
    loop {
        let k = spacings.index(current.count, current.shifted);
        let lower = &spacings.0[k].2;
        let at = lower.at(r, current.phi);
        let n_lower = lower.segments();
        // The fan's triangles away from the seam are turns of one another.
        let fan_ok = [0, 1, n_lower / 2, n_lower.saturating_sub(2), n_lower - 1]
            .into_iter()
            .all(|k| bound.slack([lower.vertex(at, k), lower.vertex(at, k + 1), pole]) >= 0.0);
        let fan = fan_ok.then(|| band(0.0, current.phi) / n_lower as f64);
        let n = current.count;
        let staggered = !current.shifted;
        let mut candidates: Vec<Candidate> =
            vec![(n, staggered, ceiling(bound, current, n, staggered))];
        let mut best: Option<(f64, Row)> = None;
        let mut k = 0;
        while let Some(&(count, shifted, ceil)) = candidates.get(k) {
            k += 1;
            let beat = best.map(|b| b.0);
            if let Some(found) = raise(bound, &mut spacings, current, (count, shifted, ceil), beat)
            {
                best = Some(found);
            }
            if k == 1 && best.is_none_or(|b| b.0 < GOOD_ENOUGH * ideal) {
                let mut counts: Vec<usize> = (1..=SMALLER)
                    .map(|k| ((n * (16 - k)).div_ceil(16)).max(3))
                    .filter(|&m| m < n)
                    .collect();
                counts.dedup();
                // Most promising first: a good one found early prunes the rest.
                let mut more: Vec<Candidate> = counts
                    .into_iter()
                    .flat_map(|m| [(m, false), (m, true)])
                    .map(|(m, s)| (m, s, ceiling(bound, current, m, s)))
                    .collect();
                more.sort_by(|a, b| b.2.1.total_cmp(&a.2.1));
                candidates.extend(more);
            }
        }
        match (fan, best) {
            (Some(f), Some((area, _))) if f >= area => break,
            (Some(_), None) => break,
            (_, Some((_, row))) => {
                placed += segments(row.count, row.shifted) + 1;
                if placed > budget {
                    return Err(CdtError::BudgetExceeded {
                        max_vertices: budget,
                        needed: placed,
                    });
                }
                rows.push(row);
                current = row;
                spacings.keep_up_to(row.count);
            }
            (None, None) => return Ok(None),
        }
    }
    Ok(Some(rows))
}

/// The largest height (colatitude below `current`'s) a row of `count`
/// vertices could be raised to, and the area per triangle it would then
/// cover. Every edge of `current` is the base of a triangle whose apex is on
/// the new row, at least as far from the edge as the new row's nearest point;
/// every edge of the new row is the base of one whose apex is at least the
/// rows' distance along the axis away; neither may pass its edge's
/// [`Bound::reach`]. An upper bound (a little over, for rounding): it orders
/// and prunes the candidates and caps their search, the zips decide.
fn ceiling(bound: &Bound, current: Row, count: usize, shifted: bool) -> (f64, f64) {
    let r = bound.r;
    let phi = current.phi;
    let (lower, upper) = (TAU / current.count as f64, TAU / count as f64);
    let (s0, z0) = (r * phi.sin(), r * phi.cos());
    let Some(reach_lower) = bound.reach(2.0 * s0 * (0.5 * lower).sin()) else {
        return (0.0, 0.0);
    };
    let inner = s0 * (0.5 * lower).cos();
    let half_upper = (0.5 * upper).sin();
    let fits = |h: f64| {
        let (s1, z1) = (phi - h).sin_cos();
        let (s1, dz) = (r * s1, r * z1 - z0);
        let gap = (inner - s1).max(0.0);
        dz * dz + gap * gap <= reach_lower * reach_lower
            && bound.reach(2.0 * s1 * half_upper).is_some_and(|y| dz <= y)
    };
    let (mut ok, mut bad) = (0.0, phi);
    if fits(phi) {
        ok = phi;
    }
    while bad - ok > 1e-5 * phi {
        let mid = 0.5 * (ok + bad);
        if fits(mid) {
            ok = mid;
        } else {
            bad = mid;
        }
    }
    let h = (ok + 2e-5 * phi).min(phi);
    let triangles = segments(current.count, current.shifted) + segments(count, shifted);
    (
        h,
        TAU * r * r * ((phi - h).cos() - phi.cos()) / triangles as f64,
    )
}

/// The candidate row above `current`, raised as far towards the pole as the
/// zip of the two keeps within the bound, with the area it covers per
/// triangle; `None` when not even a sliver of a strip fits, the row would
/// reach the pole, or it cannot cover more than `beat` per triangle.
fn raise(
    bound: &Bound,
    spacings: &mut Spacings,
    current: Row,
    (count, shifted, (cap, most)): Candidate,
    beat: Option<f64>,
) -> Option<(f64, Row)> {
    let (r, phi) = (bound.r, current.phi);
    if cap <= 0.0 || beat.is_some_and(|b| most <= b) {
        return None;
    }
    let triangles = (segments(current.count, current.shifted) + segments(count, shifted)) as f64;
    let area = |h: f64| TAU * r * r * ((phi - h).cos() - phi.cos()) / triangles;
    // The least height that covers more than `beat`, or a sliver.
    let floor = match beat {
        Some(b) => {
            let c = phi.cos() + b * triangles / (TAU * r * r);
            if c >= 1.0 {
                return None;
            }
            phi - c.acos()
        }
        None => phi * 1e-6,
    };
    // Below the pole, with room for a fan.
    let top = cap.min(phi * (1.0 - 1e-3));
    if floor >= top {
        return None;
    }
    let (a, b) = (
        spacings.index(current.count, current.shifted),
        spacings.index(count, shifted),
    );
    let (lower, upper) = (&spacings.0[a].2, &spacings.0[b].2);
    let row = |h: f64| Row {
        phi: phi - h,
        count,
        shifted,
    };
    let slack = |h: f64, first_failure: bool| {
        zip_slack(bound, (current, lower), (row(h), upper), first_failure)
    };
    let f_floor = slack(floor, true);
    if f_floor < 0.0 {
        return None;
    }
    let f_top = slack(top, false);
    if f_top >= 0.0 {
        return (cap < phi * (1.0 - 1e-3)).then(|| (area(top), row(top)));
    }
    // Regula falsi (Illinois) on the least slack, kept bracketed.
    let ((mut a, mut fa), (mut b, mut fb)) = ((floor, f_floor), (top, f_top));
    let eps = 0.5 * PRECISION * top;
    let mut side = 0;
    while b - a > PRECISION * top {
        let m = (a + (b - a) * fa / (fa - fb)).clamp(a + eps, b - eps);
        let fm = slack(m, false);
        if fm >= 0.0 {
            (a, fa) = (m, fm);
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            (b, fb) = (m, fm);
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
    }
    (a > 0.0).then(|| (area(a), row(a)))
}
