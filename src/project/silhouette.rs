//! Exact silhouettes of a patch: the curves on the exact NURBS surface where the
//! normal is perpendicular to the viewing direction (`n · d = 0`).
//!
//! The patch's (u, v) domain is sampled on a grid fine enough for the view (the
//! sizing is in 3D, from the surface itself), with the normal at every node: a
//! [`NormalGrid`], the same for every view; every grid edge where `n · d` changes
//! sign holds a silhouette point, found by a bracketed root search on the exact
//! surface, so each point lies on the silhouette to round-off. The points are
//! joined cell by cell (marching squares) into polylines, which are cut where they
//! leave the patch's trimmed region (nozzle openings). A surface of revolution
//! seen across its axis thus shows its exact meridian profile; seen along its axis
//! `n · d` vanishes everywhere and the patch's boundary circles are its outline.
//! Sits between the Geometry/Tessellate outputs and the hidden-line classifier.

use rustc_hash::FxHashMap as HashMap;

use glam::{DAffine3, DVec2, DVec3};

use crate::mesh::cdt::{Region, UvLoop};
use crate::nurbs::NurbsSurface;

/// A point of a line on a surface, vessel frame, with the surface's unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Position, mm.
    pub point: DVec3,
    /// Unit outward normal.
    pub normal: DVec3,
}

/// `|n · d|` below this counts as zero (the patch is edge-on there).
const ZERO: f64 = 1e-9;

/// Grid parameters along one direction: each knot span cut into pieces no longer
/// than `spacing` in 3D (at least 4 per span).
fn grid_parameters(surface: &NurbsSurface, along_u: bool, spacing: f64) -> Vec<f64> {
    let knots = if along_u {
        surface.u_knots()
    } else {
        surface.v_knots()
    };
    let ((u0, u1), (v0, v1)) = surface.domain();
    let mut out = Vec::new();
    for (a, b) in knots.spans() {
        let mut length = 0.0f64;
        for k in 0..3 {
            let t = k as f64 / 2.0;
            let at = |s: f64| {
                if along_u {
                    surface.point(s, v0 + t * (v1 - v0))
                } else {
                    surface.point(u0 + t * (u1 - u0), s)
                }
            };
            let mut l = 0.0;
            let mut prev = at(a);
            for i in 1..=8 {
                let p = at(a + (b - a) * i as f64 / 8.0);
                l += (p - prev).length();
                prev = p;
            }
            length = length.max(l);
        }
        let n = ((length / spacing).ceil() as usize).clamp(4, 400);
        for i in 0..n {
            out.push(a + (b - a) * i as f64 / n as f64);
        }
    }
    out.push(if along_u { u1 } else { v1 });
    out
}

/// Whether the loop's even-odd interior contains `p`.
fn crossings(l: &UvLoop, p: DVec2) -> usize {
    l.segments()
        .filter(|(a, b)| {
            (a.y <= p.y) != (b.y <= p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)
        })
        .count()
}

/// A patch's trimmed region as the silhouette cutter asks it, with what every
/// question shares worked out once: the loops' boxes and the tolerance.
struct Trim<'a> {
    /// Each loop with its (u, v) box.
    loops: Vec<(&'a UvLoop, DVec2, DVec2)>,
    /// Points this close to a loop count as inside.
    eps: f64,
    /// The u period of a closed patch.
    period: Option<f64>,
}

impl<'a> Trim<'a> {
    fn new(region: &'a Region, period: Option<f64>) -> Self {
        let loops: Vec<(&UvLoop, DVec2, DVec2)> = region
            .loops()
            .map(|l| {
                let (a, b) = l.segments().fold(
                    (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN)),
                    |(lo, hi), (p, _)| (lo.min(p), hi.max(p)),
                );
                (l, a, b)
            })
            .collect();
        // The region's bounds are its outer loop's box, the first.
        let size = loops
            .first()
            .map_or(0.0, |&(_, lo, hi)| (hi - lo).max_element());
        Trim {
            loops,
            eps: 1e-9 * size.max(1e-300),
            period,
        }
    }

    /// Whether `(u, v)` lies in the region (trying u shifted by a period for
    /// loops that cross the seam of a closed patch). Points on a loop (a
    /// silhouette ending on a patch side) count as inside.
    fn contains(&self, uv: DVec2) -> bool {
        let shifts: &[f64] = match self.period {
            Some(_) => &[0.0, 1.0, -1.0],
            None => &[0.0],
        };
        let eps = self.eps;
        shifts.iter().any(|s| {
            let p = DVec2::new(uv.x + s * self.period.unwrap_or(0.0), uv.y);
            // A ray to +u can cross a loop only within its v range and left of
            // its right side; a point can be near it only within its grown box.
            let parity: usize = self
                .loops
                .iter()
                .filter(|(_, lo, hi)| lo.y <= p.y && p.y <= hi.y && p.x <= hi.x)
                .map(|(l, ..)| crossings(l, p))
                .sum();
            parity % 2 == 1
                || self.loops.iter().any(|(l, lo, hi)| {
                    p.cmpge(*lo - eps).all()
                        && p.cmple(*hi + eps).all()
                        && l.segments()
                            .any(|(a, b)| distance_squared_to_segment(p, a, b) <= eps * eps)
                })
        })
    }
}

/// Squared distance from `p` to the segment `ab`.
fn distance_squared_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length_squared()
}

/// The root of `f` between `a` and `b` (opposite signs at the ends), Illinois
/// regula falsi to parameter round-off.
fn root(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, mut fa: f64, mut fb: f64) -> f64 {
    let mut side = 0i8;
    for _ in 0..60 {
        let c = (a * fb - b * fa) / (fb - fa);
        let c = if c.is_finite() && c > a.min(b) && c < a.max(b) {
            c
        } else {
            0.5 * (a + b)
        };
        let fc = f(c);
        if fc == 0.0 || (b - a).abs() <= 1e-14 * (1.0 + a.abs().max(b.abs())) {
            return c;
        }
        if (fc > 0.0) == (fb > 0.0) {
            b = c;
            fb = fc;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            fa = fc;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

/// Key of a grid edge: `(horizontal?, i, j)` of its first node.
type EdgeKey = (bool, usize, usize);

/// A patch's sampling grid with the exact unit normal at every node (part
/// frame): what finding its silhouettes needs whatever the view, so an entity's
/// four views evaluate it once.
#[derive(Clone, Debug)]
pub struct NormalGrid {
    us: Vec<f64>,
    vs: Vec<f64>,
    /// Normal at `(us[i], vs[j])` is `normals[i * vs.len() + j]`.
    normals: Vec<DVec3>,
}

impl NormalGrid {
    /// The grid of `surface` with steps no longer than `spacing` mm.
    pub fn new(surface: &NurbsSurface, spacing: f64) -> Self {
        let us = grid_parameters(surface, true, spacing);
        let vs = grid_parameters(surface, false, spacing);
        // Row by row (a row's v half of the work done once), stored u-major.
        let nv = vs.len();
        let mut normals = vec![DVec3::ZERO; us.len() * nv];
        for (j, &v) in vs.iter().enumerate() {
            let row = surface.row(v);
            for (i, &u) in us.iter().enumerate() {
                normals[i * nv + j] = row.normal(u);
            }
        }
        Self { us, vs, normals }
    }
}

/// The silhouette polylines of one patch for the viewing direction
/// `toward_viewer` (vessel frame), in the vessel frame. `grid` is the patch's
/// [`NormalGrid`]; `frame` maps the part's frame to the vessel's; `closed_u`
/// says whether the patch closes on itself in u.
pub fn silhouettes(
    surface: &NurbsSurface,
    grid: &NormalGrid,
    region: Option<&Region>,
    frame: &DAffine3,
    toward_viewer: DVec3,
    closed_u: bool,
) -> Vec<Vec<SurfacePoint>> {
    let d = (frame.matrix3.transpose() * toward_viewer).normalize();
    let (us, vs) = (&grid.us, &grid.vs);
    let (nu, nv) = (us.len(), vs.len());
    let g: Vec<f64> = grid.normals.iter().map(|n| n.dot(d)).collect();
    let at = |i: usize, j: usize| g[i * nv + j];
    if g.iter().all(|x| x.abs() < 1e-6)
        || g.iter().all(|&x| x > -ZERO)
        || g.iter().all(|&x| x < ZERO)
    {
        return Vec::new();
    }
    // Values within round-off of zero count as positive, so a silhouette through
    // a grid node is found on the edge from that node to its negative neighbour,
    // and round-off noise along an edge-on row makes no crossings.
    let sign = |x: f64| if x < -ZERO { -1 } else { 1 };
    // Crossing point on each grid edge whose ends have strictly opposite signs.
    let mut points: HashMap<EdgeKey, DVec2> = HashMap::default();
    let mut crossing = |key: EdgeKey| -> Option<DVec2> {
        let (horizontal, i, j) = key;
        let (i2, j2) = if horizontal { (i + 1, j) } else { (i, j + 1) };
        let (ga, gb) = (at(i, j), at(i2, j2));
        if sign(ga) == sign(gb) {
            return None;
        }
        if let Some(p) = points.get(&key) {
            return Some(*p);
        }
        let p = if ga.abs() < ZERO {
            DVec2::new(us[i], vs[j])
        } else if gb.abs() < ZERO {
            DVec2::new(us[i2], vs[j2])
        } else if horizontal {
            let v = vs[j];
            let u = root(|u| surface.normal(u, v).dot(d), us[i], us[i2], ga, gb);
            DVec2::new(u, v)
        } else {
            let u = us[i];
            let v = root(|v| surface.normal(u, v).dot(d), vs[j], vs[j2], ga, gb);
            DVec2::new(u, v)
        };
        points.insert(key, p);
        Some(p)
    };
    // The seam of a closed patch: column nu - 1 is column 0.
    let canonical = |k: EdgeKey| -> EdgeKey {
        if closed_u && !k.0 && k.1 == nu - 1 {
            (false, 0, k.2)
        } else {
            k
        }
    };
    let mut segments: Vec<(EdgeKey, EdgeKey)> = Vec::new();
    for i in 0..nu - 1 {
        for j in 0..nv - 1 {
            // Most cells lie wholly on one side.
            let s = sign(at(i, j));
            if [at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)]
                .iter()
                .all(|&x| sign(x) == s)
            {
                continue;
            }
            let edges = [
                (true, i, j),
                (false, i + 1, j),
                (true, i, j + 1),
                (false, i, j),
            ];
            let mut hit = [(false, 0, 0); 4];
            let mut hits = 0;
            for k in edges.into_iter().map(canonical) {
                if crossing(k).is_some() {
                    hit[hits] = k;
                    hits += 1;
                }
            }
            if hits >= 2 {
                segments.push((hit[0], hit[1]));
            }
            if hits == 4 {
                segments.push((hit[2], hit[3]));
            }
        }
    }
    let chains = chain(&segments);
    let period = closed_u.then(|| us[nu - 1] - us[0]);
    let trim = region.map(|r| Trim::new(r, period));
    // A silhouette that runs into a pole (a collapsed v side) ends at the pole: the
    // grid row next to it holds the last crossing; the pole itself has `n · d = 0`.
    let collapsed = |v: f64| {
        let c = surface.isocurve_v(v).control_points();
        c.iter()
            .all(|p| (*p - c[0]).length() <= 1e-9 * (1.0 + p.length()))
    };
    let (pole_low, pole_high) = (collapsed(vs[0]), collapsed(vs[nv - 1]));
    let pole_of = |key: EdgeKey| -> Option<DVec2> {
        let uv = points[&key];
        match key {
            (true, _, j) if pole_high && j + 2 == nv => Some(DVec2::new(uv.x, vs[nv - 1])),
            (true, _, 1) if pole_low => Some(DVec2::new(uv.x, vs[0])),
            _ => None,
        }
    };
    let mut out = Vec::new();
    for keys in chains {
        let mut uvs: Vec<DVec2> = keys.iter().map(|k| points[k]).collect();
        if let (Some(first), Some(last)) = (keys.first(), keys.last())
            && first != last
        {
            if let Some(p) = pole_of(*first) {
                uvs.insert(0, p);
            }
            if let Some(p) = pole_of(*last) {
                uvs.push(p);
            }
        }
        let inside = |uv: DVec2| trim.as_ref().is_none_or(|t| t.contains(uv));
        let at = |uv: DVec2, last: Option<&SurfacePoint>| SurfacePoint {
            point: frame.transform_point3(surface.point(uv.x, uv.y)),
            normal: (frame.matrix3 * surface.normal(uv.x, uv.y))
                .normalize_or(last.map_or(DVec3::Z, |p| p.normal)),
        };
        let mut current: Vec<SurfacePoint> = Vec::new();
        let mut prev: Option<(DVec2, bool)> = None;
        for uv in uvs {
            let now = inside(uv);
            if let Some((p, was)) = prev
                && was != now
            {
                // The silhouette leaves or enters the region between p and uv: find
                // the crossing of the trimming loop and put it back on the
                // silhouette.
                let (mut a, mut b) = (p, uv);
                for _ in 0..40 {
                    let m = 0.5 * (a + b);
                    if inside(m) == was {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                let edge = snap(surface, d, if was { a } else { b });
                current.push(at(edge, current.last()));
                if was {
                    if current.len() >= 2 {
                        out.push(std::mem::take(&mut current));
                    }
                    current.clear();
                }
            }
            if now {
                current.push(at(uv, current.last()));
            }
            prev = Some((uv, now));
        }
        if current.len() >= 2 {
            out.push(current);
        }
    }
    out
}

/// Moves `uv` along u onto the silhouette `n · d = 0` nearby, when a root is
/// bracketed within a thousandth of the u-domain; otherwise returns it as is.
fn snap(surface: &NurbsSurface, d: DVec3, uv: DVec2) -> DVec2 {
    let ((u0, u1), _) = surface.domain();
    let h = 1e-3 * (u1 - u0);
    let g = |u: f64| surface.normal(u, uv.y).dot(d);
    let (a, b) = ((uv.x - h).max(u0), (uv.x + h).min(u1));
    let (ga, gb) = (g(a), g(b));
    if ga.abs() < ZERO {
        DVec2::new(a, uv.y)
    } else if gb.abs() < ZERO {
        DVec2::new(b, uv.y)
    } else if (ga < 0.0) != (gb < 0.0) {
        DVec2::new(root(g, a, b, ga, gb), uv.y)
    } else {
        uv
    }
}

/// Joins segments sharing an end into chains of keys (closed chains repeat their
/// first key at the end).
fn chain(segments: &[(EdgeKey, EdgeKey)]) -> Vec<Vec<EdgeKey>> {
    let mut by_key: HashMap<EdgeKey, Vec<usize>> = HashMap::default();
    for (s, (a, b)) in segments.iter().enumerate() {
        by_key.entry(*a).or_default().push(s);
        by_key.entry(*b).or_default().push(s);
    }
    let mut used = vec![false; segments.len()];
    let mut out = Vec::new();
    // Start at ends (keys with one segment) first, then at what is left (loops).
    let mut starts: Vec<usize> = (0..segments.len())
        .filter(|&s| by_key[&segments[s].0].len() == 1 || by_key[&segments[s].1].len() == 1)
        .collect();
    starts.extend(0..segments.len());
    for s in starts {
        if used[s] {
            continue;
        }
        used[s] = true;
        let (a, b) = segments[s];
        let (mut keys, mut end) = if by_key[&a].len() == 1 {
            (vec![a, b], b)
        } else {
            (vec![b, a], a)
        };
        while let Some(&next) = by_key[&end].iter().find(|&&n| !used[n]) {
            used[next] = true;
            let (p, q) = segments[next];
            end = if p == end { q } else { p };
            keys.push(end);
        }
        out.push(keys);
    }
    out
}
