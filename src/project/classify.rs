//! Hidden-line classification: a 3D polyline on a surface becomes runs of visible
//! and hidden view lines.
//!
//! Each polyline is cut into pieces no longer than the sampling step on the view
//! plane; every sample is tested against the view's [`Occluder`] from a point
//! nudged off its own surface along the exact normal (by a little more than the
//! chordal tolerance, so a surface never hides the lines drawn on it), and where two
//! neighbouring samples disagree the change is located by bisection, so hidden runs
//! start and end where the occluder's outline crosses the line.

use glam::DVec2;

use super::occlusion::Occluder;
use super::silhouette::SurfacePoint;
use super::{LineKind, Projection, ViewLine};

/// How finely lines are classified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// Longest step between samples on the view plane, mm (model scale).
    pub step: f64,
    /// How far a sample is moved off its surface along its normal, mm.
    pub nudge: f64,
    /// Depth difference below which an occluder does not hide, mm.
    pub depth_tolerance: f64,
}

/// Bisection steps locating a visibility change.
const BISECTIONS: usize = 12;

/// Whether the surface point is hidden in the view.
fn hidden(p: &SurfacePoint, projection: &Projection, occluder: &Occluder, s: &Sampling) -> bool {
    let q = p.point + p.normal * s.nudge;
    occluder.hides(
        projection.project(q),
        projection.depth(q),
        s.depth_tolerance,
    )
}

fn lerp(a: &SurfacePoint, b: &SurfacePoint, t: f64) -> SurfacePoint {
    SurfacePoint {
        point: a.point.lerp(b.point, t),
        normal: a.normal.lerp(b.normal, t).normalize_or(a.normal),
    }
}

/// Appends the visible and hidden runs of `line` to `out`.
pub fn classify(
    line: &[SurfacePoint],
    projection: &Projection,
    occluder: &Occluder,
    sampling: &Sampling,
    out: &mut Vec<ViewLine>,
) {
    if line.len() < 2 {
        return;
    }
    let mut runs: Vec<(bool, Vec<DVec2>)> = Vec::new();
    let push = |state: bool, p: DVec2, runs: &mut Vec<(bool, Vec<DVec2>)>| match runs.last_mut() {
        Some((s, pts)) if *s == state => {
            if pts.last() != Some(&p) {
                pts.push(p);
            }
        }
        _ => runs.push((state, vec![p])),
    };
    let mut prev = line[0];
    let mut prev_hidden = hidden(&prev, projection, occluder, sampling);
    push(prev_hidden, projection.project(prev.point), &mut runs);
    for next in &line[1..] {
        let len = (projection.project(next.point) - projection.project(prev.point)).length();
        let pieces = ((len / sampling.step).ceil() as usize).clamp(1, 10_000);
        let start = prev;
        for k in 1..=pieces {
            let cur = lerp(&start, next, k as f64 / pieces as f64);
            let cur_hidden = hidden(&cur, projection, occluder, sampling);
            if cur_hidden != prev_hidden {
                let (mut a, mut b) = (0.0, 1.0);
                for _ in 0..BISECTIONS {
                    let m = 0.5 * (a + b);
                    if hidden(&lerp(&prev, &cur, m), projection, occluder, sampling) == prev_hidden
                    {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let at = projection.project(lerp(&prev, &cur, 0.5 * (a + b)).point);
                push(prev_hidden, at, &mut runs);
                push(cur_hidden, at, &mut runs);
            }
            push(cur_hidden, projection.project(cur.point), &mut runs);
            prev = cur;
            prev_hidden = cur_hidden;
        }
    }
    for (state, points) in runs {
        let points = simplify(points);
        if points.len() >= 2 {
            out.push(ViewLine {
                kind: if state {
                    LineKind::Hidden
                } else {
                    LineKind::Visible
                },
                points,
            });
        }
    }
}

/// Drops vertices that lie on the straight line through their neighbours (within
/// 1e-9 of the segment length), so straight edges are two points.
fn simplify(points: Vec<DVec2>) -> Vec<DVec2> {
    if points.len() < 3 {
        return points;
    }
    let mut out: Vec<DVec2> = vec![points[0]];
    for i in 1..points.len() - 1 {
        let a = *out.last().unwrap_or(&points[0]);
        let (b, c) = (points[i], points[i + 1]);
        let ac = c - a;
        let off = (b - a).perp_dot(ac).abs();
        let along = (b - a).dot(ac);
        if !(off <= 1e-9 * ac.length_squared() && along >= 0.0 && along <= ac.length_squared()) {
            out.push(b);
        }
    }
    out.push(points[points.len() - 1]);
    out
}
