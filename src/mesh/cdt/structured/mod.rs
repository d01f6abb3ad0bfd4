//! The structured path: a whole patch closed in u (a head, a course, a cone, a
//! flange face, with or without nozzle openings) meshed ring by ring without a
//! triangulation search over the whole patch.
//!
//! Such a patch's region is its parameter rectangle cut at a seam: the two v sides
//! (given rings of loop vertices, or a pole) and the two copies of the seam. The
//! seed lattice's rows (see `seed`) already are parallels sized by the curvature
//! metric; here every row runs from seam to seam and consecutive rows — the bottom
//! ring, the rows, the top ring — are zipped into a strip of triangles, choosing at
//! each step the shorter diagonal in 3D. A pole is met by a fan of sector-shaped
//! triangles whose pole vertices weld into one on output. The seam's vertices are
//! the rows' ends (the seam belongs to this patch alone, so no neighbour has to
//! agree with them); the v sides keep the loop's vertices exactly.
//!
//! Every strip is screened with the same probes as the general path (every
//! triangle's deviation, angle and edge limits, seam edges included); `mend` fans
//! the failing triangles' quads around their centres and bisects what still
//! fails. When all pass it is the mesh; otherwise the caller refines what is left
//! like any other mesh. No spade, no flood fill, no neighbour links and no second
//! derivatives beyond the vertices' own in the common case: this is where whole
//! heads and courses get their speed.
//!
//! The files: this one (rows and strips); `lattice` (the types it builds: chains,
//! the whole patch's mesh, a sector's copies); `cavity` (each opening's cavity cut
//! out of the strips and filled) with `cavity_fill` (the fills: zip, then `sweep`,
//! ears, spade) and `kept` (cavities kept from a previous meshing); `mend` (fans
//! and bisections of what the screen fails); `sector` (a whole turn from its first
//! quarter). It uses the checks (`checks::screen`) and, for seeds and spade, the
//! general path (`general::seed`, `general::initial`); neither uses it.

use std::ops::Range;

use glam::DVec2;
use rayon::prelude::*;

use super::CdtError;
use super::checks::screen::Screen;
use super::general::seed;
use super::patch::{PatchInfo, Vertex};
use super::plan::{MeshPath, Plan};
use super::quarter::QUARTERS;
use super::region::Region;
use super::trimesh::{NONE, TriMesh};
use crate::mesh::TessellationOptions;
use crate::parts::Analytic;
use cavity::Cavity;
use kept::Memo;
use lattice::{Chain, Kind, Rings};

mod cavity;
mod cavity_fill;
pub(super) mod kept;
pub(super) mod lattice;
mod mend;
mod ruled;
mod sector;
mod sphere;
mod sweep;

/// Relative tolerance (to the region's extent) of "on a side of the rectangle".
const ON_SIDE: f64 = 1e-12;

/// A v side of the region: its loop vertices' u values (increasing, seam to seam),
/// a path whose v varies (a nozzle neck's bottom, where its host cuts it: (u, v)
/// seam to seam, u increasing), or a pole.
enum Side {
    Ring(Vec<f64>),
    Path(Vec<DVec2>),
    Pole,
}

/// The structured mesh of `region` when it is a whole patch closed in u, holes
/// included; `None` for any other region, or when a hole's cavity would reach the
/// seam or a pole (see `cavity`).
///
/// The chains (bottom side, the lattice's rows, top side) are zipped into strips
/// round the holes' cavities, each cavity is triangulated to its holes, and every
/// strip and cavity is screened; `mend` re-triangulates around the triangles that
/// fail. What still fails is left to the caller's refinement.
pub(super) fn triangulate(
    info: &PatchInfo,
    region: &Region,
    plan: &Plan,
    options: &TessellationOptions,
    budget: usize,
    memo: &mut Memo,
) -> Result<Option<(MeshPath, Rings)>, CdtError> {
    // A whole surface of revolution: its first quarter, turned round (within a
    // quarter of the budget, as the whole turn has four times its vertices).
    // A whole sphere patch takes its own rows on the whole turn (see `sphere`).
    if let Some(quarter) = plan
        .quarter
        .as_ref()
        .filter(|_| !sphere::applies(info, region, options))
        && let Some(part) = structured(info, quarter, options, budget / QUARTERS, QUARTERS, memo)
            .map_err(|e| match e {
                CdtError::BudgetExceeded { needed, .. } => CdtError::BudgetExceeded {
                    max_vertices: budget,
                    needed: needed.saturating_mul(QUARTERS),
                },
                e => e,
            })?
        && let Some(whole) = sector::whole_turn(info, quarter, part)?
    {
        return Ok(Some((MeshPath::Sector, whole)));
    }
    if !plan.structured {
        return Ok(None);
    }
    Ok(structured(info, region, options, budget, 1, memo)?.map(|r| (MeshPath::Structured, r)))
}

/// [`triangulate`] of a region spanning `1 / parts` of the patch's period.
fn structured(
    info: &PatchInfo,
    region: &Region,
    options: &TessellationOptions,
    budget: usize,
    parts: usize,
    memo: &mut Memo,
) -> Result<Option<Rings>, CdtError> {
    memo.restart();
    let Some((bottom, top)) = sides(info, region, options, parts) else {
        return Ok(None);
    };
    let (lo, hi) = region.bounds();
    // A path (on a surface straight along v, see `path_side`) needs no lattice
    // row: it and the top ring are zipped directly, their triangles straight
    // along the generators.
    let rows = match &bottom {
        Side::Path(_) => Vec::new(),
        _ => match sphere::rows(info, region, options, &bottom, &top, budget)? {
            Some(rows) => rows,
            None => seed::rows(info, region, budget)?,
        },
    };
    // An oblique cone without openings: rows holding its rings' own u values,
    // zipped along its generators (see `ruled`).
    let by_u =
        matches!(info.analytic, Some(Analytic::ObliqueCone { .. })) && region.holes.is_empty();
    let (rows, by_u) = match (&bottom, &top) {
        (Side::Ring(b), Side::Ring(t)) if by_u => {
            (ruled::rows(rows, b, t, (lo.x, hi.x), (lo.y, hi.y)), true)
        }
        _ => (rows, false),
    };
    if rows.is_empty() && matches!((&bottom, &top), (Side::Pole, Side::Pole)) {
        return Ok(None);
    }
    let (bottom, path) = match bottom {
        Side::Path(path) => (Side::Ring(path.iter().map(|p| p.x).collect()), Some(path)),
        side => (side, None),
    };
    let mut lists: Vec<(f64, Option<Vec<f64>>)> = Vec::with_capacity(rows.len() + 2);
    lists.push((lo.y, ring(bottom)));
    lists.extend(rows.into_iter().map(|(v, u)| (v, Some(u))));
    lists.push((hi.y, ring(top)));
    let mut mesh = TriMesh::default();
    let mut chains = Vec::with_capacity(lists.len());
    let rows: Vec<(f64, &[f64])> = lists
        .iter()
        .skip(usize::from(path.is_some()))
        .filter_map(|(v, u)| u.as_deref().map(|u| (*v, u)))
        .collect();
    let mut evaluated = evaluate(info, &rows)?.into_iter();
    // The rows' vertices, then the holes' (`cavity::fill`): one allocation.
    mesh.verts.reserve(
        rows.iter().map(|(_, u)| u.len()).sum::<usize>()
            + region.holes.iter().map(|h| h.uv.len()).sum::<usize>(),
    );
    for (k, (v, u)) in lists.iter().enumerate() {
        let row = match (u, &path) {
            (Some(_), Some(path)) if k == 0 => path
                .par_chunks(super::MIN_VERTICES)
                .map(|chunk| info.vertices_lazy(chunk))
                .collect::<Result<Vec<_>, _>>()?
                .concat(),
            (Some(_), _) => evaluated.next().unwrap_or_default(),
            (None, _) => Vec::new(),
        };
        let first = mesh.verts.len() as u32;
        let len = row.len();
        mesh.verts.extend(row);
        chains.push(Chain {
            v: *v,
            kind: if u.is_some() { Kind::Row } else { Kind::Pole },
            first,
            len,
        });
    }
    // A pole's vertices, under the middle of each segment of its neighbour row
    // (which stays its neighbour: only strips between two rows are split).
    for k in 0..chains.len() {
        if !matches!(chains[k].kind, Kind::Pole) {
            continue;
        }
        let next = if k == 0 { 1 } else { k - 1 };
        let Some(&row) = chains.get(next).filter(|c| matches!(c.kind, Kind::Row)) else {
            return Ok(None);
        };
        let first = mesh.verts.len() as u32;
        let us: Vec<f64> = (0..row.len.saturating_sub(1))
            .map(|i| {
                let (x, y) = (row.first as usize + i, row.first as usize + i + 1);
                0.5 * (mesh.verts[x].uv.x + mesh.verts[y].uv.x)
            })
            .collect();
        let pole = evaluate(info, &[(chains[k].v, &us)])?;
        mesh.verts.extend(pole.into_iter().flatten());
        chains[k].first = first;
        chains[k].len = us.len();
    }
    if mesh.verts.len() + region.vertex_count() > budget {
        return Err(CdtError::BudgetExceeded {
            max_vertices: budget,
            needed: mesh.verts.len() + region.vertex_count(),
        });
    }
    let cavities = if region.holes.is_empty() {
        Vec::new()
    } else {
        match cavity::plan(&mesh, &chains, region) {
            Some(cavities) => cavities,
            None => return Ok(None),
        }
    };
    let Some(mut strips) = build(&mut mesh, &chains, &cavities, path.is_some(), by_u) else {
        return Ok(None);
    };
    // Rows are parallel in (u, v), so their strips cannot fold; a path's strip
    // folds where the zip's shorter diagonal crosses the path's ups and downs.
    if path.is_some() && !strips.first().is_some_and(|s| unfolded(&mesh, s.clone())) {
        return Ok(None);
    }
    let mut zipped: Vec<bool> = (0..strips.len())
        .map(|k| matches!((chains[k].kind, chains[k + 1].kind), (Kind::Row, Kind::Row)))
        .collect();
    // The cavities follow the strips, each screened on its own (so that its
    // verdicts depend on its triangles alone and can be kept with them).
    let first_cavity = strips.len();
    let mut filled = Vec::new();
    if !cavities.is_empty() {
        let Some(pieces) = cavity::fill(info, &mut mesh, &chains, &cavities, region, memo)? else {
            return Ok(None);
        };
        let start = pieces.first().map_or(0, |p| p.range.start);
        let range = start..pieces.last().map_or(start, |p| p.range.end);
        // The cavities' edges along the v sides are loop segments too.
        let last = chains.len() - 1;
        if matches!(chains[0].kind, Kind::Row) {
            fix_ring(
                &mut mesh,
                range.clone(),
                (chains[0].first, chains[0].len),
                true,
            );
        }
        if matches!(chains[last].kind, Kind::Row) {
            let top = (chains[last].first, chains[last].len);
            fix_ring(&mut mesh, range.clone(), top, false);
        }
        for piece in &pieces {
            strips.push(piece.range.clone());
            zipped.push(false);
        }
        filled = pieces;
    }
    let Some(screen) = Screen::new(info, options) else {
        keep(memo, filled, None, &[]);
        let seam = seam_edges(&mesh, lo.x, hi.x);
        return Ok(Some(Rings {
            mesh,
            seam,
            within: None,
            insertions: 0,
            copies: None,
        }));
    };
    // A kept cavity screened on this very surface keeps its verdicts: they are
    // a function of its triangles' vertices, the surface and the options alone
    // on a course, whose probes all go through one row (see `screen::Swept`).
    let surface = memo.surface.filter(|_| screen.is_swept());
    let known = |k: usize| -> Option<&[bool]> {
        let piece = filled.get(k.checked_sub(first_cavity)?)?;
        piece.kept.as_ref()?.verdicts(surface?)
    };
    // One task per strip: strips differ in size by as much as their rows do
    // (a head's next to its pole against its widest), and rayon's even split of
    // the list left one thread idle for much of a big head's screen. The
    // cavities, each screened on its own, make one task.
    let flag = |k: usize| match known(k) {
        Some(verdicts) if verdicts.len() == strips[k].len() => verdicts.to_vec(),
        _ => screen.strip(&mesh, strips[k].clone()),
    };
    let tasks: Vec<Range<usize>> = (0..first_cavity)
        .map(|k| k..k + 1)
        .chain((first_cavity < strips.len()).then_some(first_cavity..strips.len()))
        .collect();
    let flags: Vec<Vec<bool>> = tasks
        .into_par_iter()
        .with_max_len(1)
        .map(|task| task.map(flag).collect::<Vec<_>>())
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    keep(memo, filled, surface, &flags[first_cavity..]);
    let (mut within, mended) = mend::mend(info, &screen, &mut mesh, &strips, &zipped, flags)?;
    let bisected = mend::bisect(info, &screen, &mut mesh, &mut within)?;
    let seam = seam_edges(&mesh, lo.x, hi.x);
    Ok(Some(Rings {
        mesh,
        seam,
        within: Some(within),
        insertions: mended + bisected,
        copies: None,
    }))
}

/// Records the cavities `filled` in `memo` (when it records), each with its
/// screen's `verdicts` on the surface with key `surface` when there is one.
fn keep(
    memo: &mut Memo,
    filled: Vec<cavity::Filled>,
    surface: Option<u128>,
    verdicts: &[Vec<bool>],
) {
    if !memo.record {
        return;
    }
    for (k, piece) in filled.into_iter().enumerate() {
        let Some(kept) = piece.kept else {
            continue;
        };
        memo.found.push(match (surface, verdicts.get(k)) {
            (Some(surface), Some(v)) => kept.with_verdicts(surface, v),
            _ => kept,
        });
    }
}

/// The seam edges of a structured mesh: every edge between two row ends on one
/// side of the seam (`lo` or `hi`), as `(triangle, edge)`.
fn seam_edges(mesh: &TriMesh, lo: f64, hi: f64) -> Vec<(u32, usize)> {
    // 1 on the `lo` copy of the seam, 2 on the `hi` copy, 0 elsewhere.
    let side: Vec<u8> = mesh
        .verts
        .iter()
        .map(|v| match v.uv.x {
            _ if v.pole => 0,
            x if x == lo => 1,
            x if x == hi => 2,
            _ => 0,
        })
        .collect();
    let mut out = Vec::new();
    for (t, tri) in mesh.tris.iter().enumerate() {
        let s = tri.map(|k| side[k as usize]);
        for i in 0..3 {
            if s[i] != 0 && s[i] == s[(i + 1) % 3] {
                out.push((t as u32, i));
            }
        }
    }
    out
}

/// The vertices of rows `(v, u values)`, evaluated in parallel.
fn evaluate(info: &PatchInfo, rows: &[(f64, &[f64])]) -> Result<Vec<Vec<Vertex>>, CdtError> {
    rows.par_iter()
        .map(|(v, us)| info.row_vertices(*v, us))
        .collect()
}

/// Zips every pair of consecutive chains into `mesh` (replacing its triangles);
/// returns each strip's range of triangles, or `None` when two poles meet.
///
/// With `path`, the first chain is a path whose v varies: its strip is zipped by
/// u alone (the shorter diagonal in u), so that every triangle spans as little of
/// the turn as the two chains allow, whatever the path's ups and downs. With
/// `by_u`, every strip is zipped so (an oblique cone's rows, see `ruled`).
fn build(
    mesh: &mut TriMesh,
    chains: &[Chain],
    cavities: &[Cavity],
    path: bool,
    by_u: bool,
) -> Option<Vec<Range<u32>>> {
    mesh.tris.clear();
    mesh.adj.clear();
    mesh.fixed.clear();
    mesh.touched.clear();
    // Each strip has as many triangles as its chains have vertices, less two.
    let estimate = 2 * chains.iter().map(|c| c.len).sum::<usize>() + 16;
    mesh.tris.reserve(estimate);
    mesh.adj.reserve(estimate);
    mesh.fixed.reserve(estimate);
    mesh.touched.reserve(estimate);
    let mut strips = Vec::with_capacity(chains.len());
    let last = chains.len() - 1;
    for k in 0..last {
        let start = mesh.tris.len() as u32;
        let (a, b) = (chains[k], chains[k + 1]);
        match (a.kind, b.kind) {
            (Kind::Row, Kind::Row) => {
                // Zip the pieces between the cavities crossing this strip.
                let mut cuts: Vec<_> = cavities
                    .iter()
                    .filter(|c| c.lo <= k && k < c.hi)
                    .filter_map(|c| Some((c.cut(k)?, c.cut(k + 1)?)))
                    .collect();
                cuts.sort_unstable();
                let (mut sa, mut sb) = (0usize, 0usize);
                for ((la, ra), (lb, rb)) in cuts {
                    let (pa, pb) = (a.first + sa as u32, b.first + sb as u32);
                    zip(mesh, (pa, la + 1 - sa), (pb, lb + 1 - sb));
                    (sa, sb) = (ra, rb);
                }
                let (pa, pb) = (a.first + sa as u32, b.first + sb as u32);
                if by_u || (path && k == 0) {
                    zip_by(mesh, (pa, a.len - sa), (pb, b.len - sb), |x, y| {
                        (x.uv.x - y.uv.x).abs()
                    });
                } else {
                    zip(mesh, (pa, a.len - sa), (pb, b.len - sb));
                }
            }
            (Kind::Pole, Kind::Row) => fan(mesh, (b.first, b.len), a.first, true),
            (Kind::Row, Kind::Pole) => fan(mesh, (a.first, a.len), b.first, false),
            // Two poles and no row between them: not a structured patch.
            (Kind::Pole, Kind::Pole) => return None,
        }
        let range = start..mesh.tris.len() as u32;
        // The given v sides are loop segments.
        if k == 0 && matches!(a.kind, Kind::Row) {
            fix_ring(mesh, range.clone(), (a.first, a.len), true);
        }
        if k + 1 == last && matches!(b.kind, Kind::Row) {
            fix_ring(mesh, range.clone(), (b.first, b.len), false);
        }
        strips.push(range);
    }
    Some(strips)
}

/// Marks the seam edges fixed (loop segments of the region).
pub(super) fn fix_seam(mesh: &mut TriMesh, seam: &[(u32, usize)]) {
    for &(t, i) in seam {
        mesh.fixed[t as usize][i] = true;
    }
}

/// The region's v sides, when it is a whole patch closed in u: one outer loop on
/// the rectangle `lo..hi` spanning one period, every vertex on one of its sides.
fn sides(
    info: &PatchInfo,
    region: &Region,
    options: &TessellationOptions,
    parts: usize,
) -> Option<(Side, Side)> {
    if !info.closed_u {
        return None;
    }
    let (lo, hi) = region.bounds();
    let ((u0, u1), (v0, v1)) = info.surface.domain();
    let eps = ON_SIDE * ((hi - lo).max_element() + (u1 - u0) + (v1 - v0));
    if ((hi.x - lo.x) - (u1 - u0) / parts as f64).abs() > eps || hi.y - lo.y <= eps {
        return None;
    }
    let on = |a: f64, b: f64| (a - b).abs() <= eps;
    let pts = &region.outer.uv;
    if !pts
        .iter()
        .all(|p| on(p.y, lo.y) || on(p.y, hi.y) || on(p.x, lo.x) || on(p.x, hi.x))
    {
        return path_side(info, region, options, eps);
    }
    let side = |v: f64, collapsed: bool| -> Option<Side> {
        let mut u: Vec<f64> = pts.iter().filter(|p| on(p.y, v)).map(|p| p.x).collect();
        u.sort_by(f64::total_cmp);
        if u.len() < 2 || !on(u[0], lo.x) || !on(u[u.len() - 1], hi.x) {
            return None;
        }
        if collapsed && u.len() == 2 {
            return Some(Side::Pole);
        }
        Some(Side::Ring(u))
    };
    let bottom = side(lo.y, info.collapsed[2] && on(lo.y, v0))?;
    let top = side(hi.y, info.collapsed[3] && on(hi.y, v1))?;
    Some((bottom, top))
}

/// The sides of a whole closed patch whose bottom is a path (a nozzle neck cut by
/// its host) and whose top is a ring: the outer loop runs along the path from the
/// left copy of the seam to the right one (u strictly increasing, both ends at one
/// v), up the right copy, back along the top ring and down the left copy.
///
/// Only on a surface straight along v (one linear span: a neck's cylinder), where
/// the zip of the path and the ring deviates from the surface only round the turn,
/// and without a stretch or edge-length limit (the zip's triangles run the whole
/// length of the neck). `None` for any other region, or one with holes.
fn path_side(
    info: &PatchInfo,
    region: &Region,
    options: &TessellationOptions,
    eps: f64,
) -> Option<(Side, Side)> {
    let (lo, hi) = region.bounds();
    let on = |a: f64, b: f64| (a - b).abs() <= eps;
    let pts = &region.outer.uv;
    let n = pts.len();
    let v_knots = info.surface.v_knots();
    let straight = v_knots.degree() == 1 && v_knots.as_slice().len() == 4;
    if !straight
        || options.max_stretch.is_some()
        || options.max_edge_length.is_some()
        || !region.holes.is_empty()
        || info.collapsed[3] && on(hi.y, info.surface.domain().1.1)
    {
        return None;
    }
    // The path starts at the left seam's lowest vertex: the one the loop leaves
    // the seam from.
    let start = (0..n).find(|&i| on(pts[i].x, lo.x) && !on(pts[(i + 1) % n].x, lo.x))?;
    let mut path = vec![pts[start]];
    for k in 1..n {
        let p = pts[(start + k) % n];
        // u strictly increasing (NaN refused).
        if p.x.partial_cmp(&path[path.len() - 1].x) != Some(std::cmp::Ordering::Greater)
            || on(p.y, hi.y)
        {
            return None;
        }
        path.push(p);
        if on(p.x, hi.x) {
            break;
        }
    }
    let (first, last) = (path[0], path[path.len() - 1]);
    if path.len() < 3 || !on(last.x, hi.x) || !on(first.y, last.y) {
        return None;
    }
    // The rest: the seam copies and the top ring, strictly above the path.
    let rest = (path.len()..n).map(|k| pts[(start + k) % n]);
    let top_of_path = path.iter().fold(f64::NEG_INFINITY, |m, p| m.max(p.y));
    let mut top = Vec::new();
    for p in rest {
        if on(p.y, hi.y) {
            top.push(p.x);
        } else if !(on(p.x, lo.x) || on(p.x, hi.x)) || p.y <= top_of_path {
            return None;
        }
    }
    top.sort_by(f64::total_cmp);
    if top.len() < 2 || !on(top[0], lo.x) || !on(top[top.len() - 1], hi.x) || hi.y <= top_of_path {
        return None;
    }
    // The path's ends exactly on the seam copies, as rows' ends are.
    let len = path.len();
    path[0].x = lo.x;
    path[len - 1].x = hi.x;
    Some((Side::Path(path), Side::Ring(top)))
}

/// Whether every triangle of `range` turns counter-clockwise in (u, v).
fn unfolded(mesh: &TriMesh, range: Range<u32>) -> bool {
    mesh.tris[range.start as usize..range.end as usize]
        .iter()
        .all(|t| {
            let [a, b, c] = t.map(|k| mesh.verts[k as usize].uv);
            (b - a).perp_dot(c - a) > 0.0
        })
}

/// A side's u values, `None` for a pole.
fn ring(side: Side) -> Option<Vec<f64>> {
    match side {
        Side::Ring(u) => Some(u),
        Side::Path(path) => Some(path.iter().map(|p| p.x).collect()),
        Side::Pole => None,
    }
}

/// Pushes a triangle (counter-clockwise in (u, v)) with no neighbours.
fn push(mesh: &mut TriMesh, tri: [u32; 3]) -> u32 {
    mesh.tris.push(tri);
    mesh.adj.push([NONE; 3]);
    mesh.fixed.push([false; 3]);
    mesh.touched.push(0);
    (mesh.tris.len() - 1) as u32
}

/// Zips the chain `a` (lower v) with the chain `b` (upper v), each `(first vertex,
/// count)` running seam to seam, choosing at each step the shorter diagonal.
fn zip(mesh: &mut TriMesh, a: (u32, usize), b: (u32, usize)) {
    zip_by(mesh, a, b, |x, y| (x.point - y.point).length_squared());
}

/// [`zip`] choosing the diagonal that is shorter by `length`.
fn zip_by(
    mesh: &mut TriMesh,
    a: (u32, usize),
    b: (u32, usize),
    length: impl Fn(&Vertex, &Vertex) -> f64,
) {
    let (mut i, mut j) = (0usize, 0usize);
    let (na, nb) = (a.1 - 1, b.1 - 1);
    fn at(mesh: &TriMesh, k: u32) -> &Vertex {
        &mesh.verts[k as usize]
    }
    while i < na || j < nb {
        let (ai, bj) = (a.0 + i as u32, b.0 + j as u32);
        let advance_a = if i == na {
            false
        } else if j == nb {
            true
        } else {
            // The shorter diagonal: a[i+1]–b[j] (advance a) or a[i]–b[j+1].
            let da = length(at(mesh, ai + 1), at(mesh, bj));
            let db = length(at(mesh, ai), at(mesh, bj + 1));
            da <= db
        };
        if advance_a {
            i += 1;
            push(mesh, [ai, ai + 1, bj]);
        } else {
            j += 1;
            push(mesh, [ai, bj + 1, bj]);
        }
    }
}

/// A fan from the chain `row` to its pole vertices `pole..` (one under the middle
/// of each row segment). `below` when the pole is under the row (lower v).
fn fan(mesh: &mut TriMesh, row: (u32, usize), pole: u32, below: bool) {
    for k in 0..row.1 as u32 - 1 {
        let (x, y, p) = (row.0 + k, row.0 + k + 1, pole + k);
        if below {
            push(mesh, [p, y, x]);
        } else {
            push(mesh, [x, y, p]);
        }
    }
}

/// Marks the loop segments of a ring: the edges between consecutive ring vertices
/// `ring` in the triangles `range` of the strip above (`bottom`) or below it.
fn fix_ring(mesh: &mut TriMesh, range: Range<u32>, ring: (u32, usize), bottom: bool) {
    let (start, end) = (ring.0, ring.0 + ring.1 as u32);
    let in_ring = |k: u32| (start..end).contains(&k);
    for t in range {
        let tri = mesh.tris[t as usize];
        for i in 0..3 {
            let (x, y) = (tri[i], tri[(i + 1) % 3]);
            // Ring segments run with increasing index along the bottom ring's
            // triangles and decreasing along the top ring's.
            let segment = if bottom { y == x + 1 } else { x == y + 1 };
            if in_ring(x) && in_ring(y) && segment {
                mesh.fixed[t as usize][i] = true;
            }
        }
    }
}
