//! Local areas — dents and bulges — on a grid of the fitted deviation less its
//! background, for courses, heads and cones (concentric or eccentric) alike.
//!
//! An area is a 4-connected set of grid cells (wrapping around the axis) whose
//! residual is past the dent threshold, all of one sign. The fit can overshoot
//! where few points hold it (a patch's edges, a net grown to a noise below the
//! scan's), so an area is reported only when the scan points inside it confirm
//! it: their mean residual, less the same background, lies on the area's side
//! of zero by three standard errors of the scan's noise. Heads and cones are
//! gridded like courses: rows along the meridian about [`GRID`] apart, columns
//! evenly round each row's section circle (a head's or concentric cone's are
//! centred on its axis, an eccentric cone's move with its small end); each row
//! loses its trimmed harmonics 0–2 where the row is wide (radius at least a
//! quarter of the diameter) and only the part's best shift near a head's
//! crown, where a dent would fill the row. A head is several patches (flange,
//! knuckle, crown): areas of one part that reach a shared patch edge over
//! common columns are one dent, reported once with the deepest piece's depth
//! and place and the pieces' summed length along the meridian.

use std::f64::consts::{PI, TAU};

use glam::DVec3;

use super::{Finding, GRID, best_shift, section_harmonics};
use crate::nurbs::NurbsSurface;
use crate::nurbs::builders::FULL_TURN_KNOTS;
use crate::scan::envelope::Envelope;
use crate::scan::fit::{PatchFit, deviation_at};
use crate::scan::profile::{angle_of_u, u_of_angle};
use crate::scan::project::Foot;

/// The rule of a dent or bulge finding.
pub const LOCAL_RULE: &str =
    "local deviation from the section's best-fit shape past the dent threshold";

/// A connected area of cells past the threshold.
#[derive(Clone, Debug)]
pub struct Area {
    /// (row, column) of each cell.
    pub cells: Vec<(usize, usize)>,
    /// +1 outward (bulge, peaking), −1 inward (dent).
    pub sign: f64,
}

/// The areas of `residual` (rows × columns, wrapping in the column) past
/// `threshold`, in row-major order of their first cell; areas under 3 cells
/// are dropped.
pub fn areas(residual: &[Vec<f64>], threshold: f64) -> Vec<Area> {
    let rows = residual.len();
    let Some(nt) = residual.first().map(Vec::len) else {
        return Vec::new();
    };
    let mut seen = vec![vec![false; nt]; rows];
    let mut out = Vec::new();
    for iz in 0..rows {
        for it in 0..nt {
            if seen[iz][it] || residual[iz][it].abs() <= threshold {
                continue;
            }
            let sign = residual[iz][it].signum();
            let mut stack = vec![(iz, it)];
            seen[iz][it] = true;
            let mut cells = Vec::new();
            while let Some((a, b)) = stack.pop() {
                cells.push((a, b));
                let mut next = vec![(a, (b + 1) % nt), (a, (b + nt - 1) % nt)];
                if a > 0 {
                    next.push((a - 1, b));
                }
                if a + 1 < rows {
                    next.push((a + 1, b));
                }
                for (x, y) in next {
                    if !seen[x][y] && residual[x][y] * sign > threshold {
                        seen[x][y] = true;
                        stack.push((x, y));
                    }
                }
            }
            if cells.len() >= 3 {
                out.push(Area { cells, sign });
            }
        }
    }
    out
}

/// Harmonics 0–2 at angle `t` with coefficients `c`.
pub fn harmonic(c: &[f64; 5], t: f64) -> f64 {
    c[0] + c[1] * t.cos() + c[2] * t.sin() + c[3] * (2.0 * t).cos() + c[4] * (2.0 * t).sin()
}

/// Whether the scan points confirm each area: `points` are (row, column,
/// residual less the background) on the grid of `rows` × `columns`; `sigma`
/// the scan's noise, mm.
pub fn confirmed(
    areas: &[Area],
    rows: usize,
    columns: usize,
    points: impl Iterator<Item = (usize, usize, f64)>,
    sigma: f64,
) -> Vec<bool> {
    let mut label = vec![usize::MAX; rows * columns];
    for (k, a) in areas.iter().enumerate() {
        for &(r, c) in &a.cells {
            label[r * columns + c] = k;
        }
    }
    let mut sums = vec![(0usize, 0.0f64); areas.len()];
    for (r, c, value) in points {
        if r < rows && c < columns {
            let k = label[r * columns + c];
            if k != usize::MAX {
                sums[k].0 += 1;
                sums[k].1 += value;
            }
        }
    }
    areas
        .iter()
        .zip(sums)
        .map(|(a, (n, sum))| {
            n >= 3 && a.sign * sum / n as f64 >= 3.0 * sigma.max(1e-3) / (n as f64).sqrt()
        })
        .collect()
}

/// The grid cell (row, column) of a point at local angle `angle` and meridian
/// fraction `s01`.
pub fn cell(angle: f64, s01: f64, rows: usize, columns: usize) -> (usize, usize) {
    let r = (s01 * (rows - 1) as f64)
        .round()
        .clamp(0.0, (rows - 1) as f64) as usize;
    let c = ((angle / TAU * columns as f64).round() as i64).rem_euclid(columns as i64) as usize;
    (r, c)
}

/// Whether every v-isocurve of `design` is a full circle parametrized as
/// [`revolve`](crate::nurbs::builders::revolve)'s (so [`angle_of_u`] holds on
/// it): true of a revolved patch and of an eccentric cone (ruled between two
/// such circles), checked at sample points to 1e-9 of the patch's size.
fn has_circle_sections(design: &NurbsSurface) -> bool {
    if design.u_knots().as_slice() != FULL_TURN_KNOTS {
        return false;
    }
    let (v0, v1) = design.domain().1;
    let size = design
        .control_points()
        .iter()
        .map(|p| p.length())
        .fold(1.0, f64::max);
    [0.0, 0.29, 0.71, 1.0].into_iter().all(|t| {
        let v = v0 + (v1 - v0) * t;
        let (centre, radius) = section(design, v);
        [0.3, 1.9, 2.8, 4.4, 5.9].into_iter().all(|theta: f64| {
            let p = design.point(u_of_angle(theta), v);
            let expected = centre + radius * DVec3::new(theta.cos(), theta.sin(), 0.0);
            (p - expected).length() <= 1e-9 * size
        })
    })
}

/// The centre and radius of the section circle of `design` at `v`.
fn section(design: &NurbsSurface, v: f64) -> (DVec3, f64) {
    let a = design.point(0.0, v);
    let b = design.point(0.5, v);
    let centre = 0.5 * (a + b);
    (centre, (a - centre).length())
}

/// A dent or bulge of one patch, with what it takes to join it to the same
/// dent's piece on a neighbouring patch of the part.
#[derive(Clone, Debug)]
pub struct PatchArea {
    /// The finding as the patch alone reports it.
    pub finding: Finding,
    /// Index of the patch in [`Envelope::surfaces`].
    pub surface: usize,
    /// The part's diameter, mm.
    pub diameter: f64,
    /// Columns round the axis (the part's: the same on all its patches).
    pub columns: usize,
    /// Length along the meridian, mm.
    pub along: f64,
    /// Widest row's arc, mm.
    pub across: f64,
    /// The patch's v-start and v-end edge points at u = 0 (vessel frame), and
    /// the columns the area holds on the first and last rows.
    pub edges: [(DVec3, Vec<usize>); 2],
}

/// The findings of `pieces` with the pieces of one dent on neighbouring
/// patches of a part joined: same part and sign, a shared edge (edge points
/// within 1e-6 of the part's diameter) on which their columns meet
/// (within one column). A joined finding keeps the deepest piece's size and
/// place; its extent is the larger of the widest piece and the pieces' summed
/// lengths along the meridian.
pub fn join_across_patches(pieces: Vec<PatchArea>) -> Vec<Finding> {
    let n = pieces.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let touch = |a: &PatchArea, b: &PatchArea| {
        let tolerance = 1e-6 * a.diameter.max(1.0);
        a.finding.part == b.finding.part
            && a.finding.kind == b.finding.kind
            && a.surface != b.surface
            && a.columns == b.columns
            && a.edges.iter().any(|(pa, ca)| {
                b.edges.iter().any(|(pb, cb)| {
                    (*pa - *pb).length() <= tolerance
                        && ca.iter().any(|&x| {
                            cb.iter().any(|&y| {
                                let d = x.abs_diff(y);
                                d.min(a.columns - d) <= 1
                            })
                        })
                })
            })
    };
    for i in 0..n {
        for j in i + 1..n {
            if touch(&pieces[i], &pieces[j]) {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri.max(rj)] = ri.min(rj);
            }
        }
    }
    let mut out = Vec::new();
    for i in 0..n {
        if root(&mut parent, i) != i {
            continue;
        }
        let group: Vec<&PatchArea> = (0..n)
            .filter(|&j| root(&mut parent, j) == i)
            .map(|j| &pieces[j])
            .collect();
        let deepest = group
            .iter()
            .max_by(|a, b| a.finding.size.total_cmp(&b.finding.size))
            .unwrap_or(&group[0]);
        let along: f64 = group.iter().map(|p| p.along).sum();
        let across = group.iter().map(|p| p.across).fold(0.0, f64::max);
        let mut finding = deepest.finding.clone();
        finding.extent = Some(along.max(across));
        out.push(finding);
    }
    out
}

/// Dents and bulges on the head or cone patch `index`, each with its section
/// circles round the part's axis (a revolved patch or an eccentric cone).
pub fn revolution_areas(
    envelope: &Envelope,
    index: usize,
    fit: &PatchFit,
    feet: &[Option<Foot>],
    threshold: f64,
) -> Vec<PatchArea> {
    let s = &envelope.surfaces[index];
    let design = &s.patch.surface;
    if !has_circle_sections(design) {
        return Vec::new();
    }
    let part = &envelope.parts[s.part];
    let d = part.diameter;
    let (v0, v1) = design.domain().1;
    // The length of the meridian at `theta` between v = a and b.
    let meridian_length = |theta: f64, a: f64, b: f64| {
        let u = u_of_angle(theta);
        (0..64)
            .map(|k| {
                let (p, q) = (k as f64 / 64.0, (k + 1) as f64 / 64.0);
                (design.point(u, a + (b - a) * q) - design.point(u, a + (b - a) * p)).length()
            })
            .sum::<f64>()
    };
    // Rows: v evenly, about GRID apart along the longest meridian (an
    // eccentric cone's differ round it).
    let length = (0..4)
        .map(|k| meridian_length(k as f64 * PI / 2.0, v0, v1))
        .fold(0.0, f64::max);
    let nz = ((length / GRID).ceil() as usize).max(2);
    let rows = nz + 1;
    let nt = ((PI * d / GRID).ceil() as usize).clamp(72, 2880);
    let angles: Vec<f64> = (0..nt).map(|k| TAU * k as f64 / nt as f64).collect();
    let v_of = |iz: usize| v0 + (v1 - v0) * iz as f64 / nz as f64;
    let mut along = vec![0.0; rows];
    let mut radius = vec![0.0; rows];
    let mut previous = design.point(0.0, v0);
    for (iz, (a, r)) in along.iter_mut().zip(&mut radius).enumerate() {
        let p = design.point(0.0, v_of(iz));
        *a = (p - previous).length();
        previous = p;
        *r = section(design, v_of(iz)).1;
    }
    for iz in 1..rows {
        along[iz] += along[iz - 1];
    }
    let own: Vec<(Foot, f64)> = feet
        .iter()
        .flatten()
        .filter(|f| f.surface == index)
        .map(|f| (*f, deviation_at(design, &fit.surface, f.u, f.v)))
        .collect();
    if own.len() < 16 {
        return Vec::new();
    }
    let shift = best_shift(&own);
    let local_shift = s.inverse.transform_vector3(shift);
    // Covered cells: within 1.5 point spacings of a point.
    let area = (0..nz)
        .map(|iz| (along[iz + 1] - along[iz]) * PI * (radius[iz] + radius[iz + 1]))
        .sum::<f64>()
        .max(1.0);
    let reach = (1.5 * (area / own.len() as f64).sqrt()).max(GRID);
    let mut covered = vec![vec![false; nt]; rows];
    for (f, _) in &own {
        let (cz, ct) = cell(angle_of_u(f.u), (f.v - v0) / (v1 - v0), rows, nt);
        for (z, row) in covered.iter_mut().enumerate() {
            if (along[z] - along[cz]).abs() > reach {
                continue;
            }
            let arc = TAU * radius[z].max(1e-9) / nt as f64;
            let rt = ((reach / arc).ceil() as i64).min(nt as i64 / 2);
            for dt in -rt..=rt {
                row[(ct as i64 + dt).rem_euclid(nt as i64) as usize] = true;
            }
        }
    }
    let mut residual = vec![vec![0.0; nt]; rows];
    let mut background = vec![[0.0; 5]; rows];
    for iz in 0..rows {
        let v = v_of(iz);
        let values: Vec<f64> = angles
            .iter()
            .map(|&t| {
                let u = u_of_angle(t);
                deviation_at(design, &fit.surface, u, v) - design.normal(u, v).dot(local_shift)
            })
            .collect();
        let wide = radius[iz] >= d / 4.0;
        let res = if wide {
            let (c, res) = section_harmonics(&angles, &values, &covered[iz]);
            background[iz] = c;
            res
        } else {
            values
        };
        residual[iz] = res
            .iter()
            .zip(&covered[iz])
            .map(|(r, &c)| if c { *r } else { 0.0 })
            .collect();
    }
    let found = areas(&residual, threshold);
    let points = own.iter().map(|(f, _)| {
        let t = angle_of_u(f.u);
        let (r, c) = cell(t, (f.v - v0) / (v1 - v0), rows, nt);
        let local_normal = s.inverse.transform_vector3(f.normal);
        (
            r,
            c,
            f.deviation - local_normal.dot(local_shift) - harmonic(&background[r], t),
        )
    });
    let ok = confirmed(&found, rows, nt, points, fit.rms);
    let edge = |v: f64| s.frame.transform_point3(design.point(0.0, v));
    let mut out = Vec::new();
    for (a, ok) in found.iter().zip(ok) {
        if !ok {
            continue;
        }
        let (zmin, zmax) = a
            .cells
            .iter()
            .fold((usize::MAX, 0), |m, c| (m.0.min(c.0), m.1.max(c.0)));
        let across = (zmin..=zmax)
            .map(|z| {
                let n = a.cells.iter().filter(|c| c.0 == z).count();
                n as f64 * TAU * radius[z] / nt as f64
            })
            .fold(0.0, f64::max);
        let extreme = a
            .cells
            .iter()
            .copied()
            .max_by(|x, y| (residual[x.0][x.1] * a.sign).total_cmp(&(residual[y.0][y.1] * a.sign)))
            .unwrap_or(a.cells[0]);
        let at = s
            .frame
            .transform_point3(design.point(u_of_angle(angles[extreme.1]), v_of(extreme.0)));
        let along = meridian_length(angles[extreme.1], v_of(zmin), v_of(zmax));
        let on_row = |row: usize| -> Vec<usize> {
            a.cells.iter().filter(|c| c.0 == row).map(|c| c.1).collect()
        };
        out.push(PatchArea {
            finding: Finding {
                kind: if a.sign < 0.0 { "dent" } else { "bulge" },
                part: part.id.clone(),
                size: residual[extreme.0][extreme.1].abs(),
                unit: "mm",
                elevation: at.z,
                orientation: envelope.orientation_of(at),
                extent: Some(along.max(across)),
                limit: None,
                exceeds: false,
                rule: LOCAL_RULE,
            },
            surface: index,
            diameter: d,
            columns: nt,
            along,
            across,
            edges: [(edge(v0), on_row(0)), (edge(v1), on_row(rows - 1))],
        });
    }
    out
}
