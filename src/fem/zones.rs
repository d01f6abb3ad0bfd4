//! Where a shell's membrane stress is local rather than general (ASME VIII-2
//! 5.2.2 and Table 5.6: a shell's membrane stress is general primary Pm
//! "remote from discontinuities", local primary PL at a junction, allowed
//! 1.5 S). The discontinuities are the junctions of the mesh: the nodes two
//! parts share (course to head, course to course, nozzle neck to its host
//! along the exact intersection, a pad's edge) and the tangent lines inside a
//! part ([`super::FeMesh::junctions`]). A node is local when it lies within
//! [`REACH`]·√(R·t) of a junction node, measured straight (the chord, never
//! longer than the path along the shell), with R that junction node's distance
//! from the vessel axis and t the thickest part meeting there.
//!
//! Why 3·√(R·t) and not ASME's 1.0·√(R·t) (which bounds how far a region
//! above 1.1 S may reach to count as local, a different check): a junction's
//! edge load dies out along a cylinder as e^(−βx)·(A·cos βx + B·sin βx),
//! β = 1.285/√(R·t), and at a 2:1 head the disturbance is as large as the
//! hoop stress itself (the head's equator is in hoop compression, −P·R/t). At
//! √(R·t) a quarter of it is left, and its overshoot round 1.6·√(R·t) (+6.6 %
//! of P·R/t on a course R 1000, t 10) went into Pm: 107.8 MPa for
//! P·R/t = 100. At 2.5·√(R·t) the hoop stress still read +2.2 % (Pm 103.3);
//! at 3·√(R·t) the envelope e^(−3.86) is 2.1 % of the disturbance, and Pm
//! reads 101.3 (tests/fem_solver.rs).
//! For a nozzle on a course R·t is the course's, the larger of the two decay
//! lengths; for the crown of a dished head the distance from the axis is
//! shorter than its radius of curvature, so its local zone errs small (more of
//! the head is checked against S).

use std::collections::HashMap;

use glam::DVec3;

use super::FeMesh;

/// Reach of a junction's local zone, in √(R·t).
pub const REACH: f64 = 3.0;

/// For every node of `mesh`, whether it lies within [`REACH`]·√(R·t) of a
/// junction.
pub fn local_nodes(mesh: &FeMesh) -> Vec<bool> {
    let count = mesh.nodes.len();
    let mut parts_of: Vec<Vec<usize>> = vec![Vec::new(); count];
    for e in &mesh.elements {
        for &n in &e.nodes {
            if !parts_of[n].contains(&e.part) {
                parts_of[n].push(e.part);
            }
        }
    }
    let (origin, axis) = mesh.axis;
    let axis = axis.normalize_or_zero();
    let mut junction: Vec<(DVec3, f64)> = Vec::new();
    let mut is_junction = vec![false; count];
    for n in mesh
        .junctions
        .iter()
        .copied()
        .chain((0..count).filter(|&n| parts_of[n].len() > 1))
    {
        if n >= count || is_junction[n] || parts_of[n].is_empty() {
            continue;
        }
        is_junction[n] = true;
        let p = mesh.nodes[n];
        let rel = p - origin;
        let r = (rel - axis * rel.dot(axis)).length();
        let t = parts_of[n]
            .iter()
            .map(|&k| mesh.parts[k].thickness)
            .fold(0.0, f64::max);
        junction.push((p, REACH * (r.max(t) * t).sqrt()));
    }
    let mut out = vec![false; count];
    let reach = junction.iter().map(|j| j.1).fold(0.0, f64::max);
    if reach <= 0.0 {
        return out;
    }
    let key = |p: DVec3| (p / reach).floor().as_i64vec3().to_array();
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (k, j) in junction.iter().enumerate() {
        grid.entry(key(j.0)).or_default().push(k);
    }
    for (n, flag) in out.iter_mut().enumerate() {
        if parts_of[n].is_empty() {
            continue;
        }
        let p = mesh.nodes[n];
        let [x, y, z] = key(p);
        *flag = (-1..=1).any(|dx| {
            (-1..=1).any(|dy| {
                (-1..=1).any(|dz| {
                    grid.get(&[x + dx, y + dy, z + dz]).is_some_and(|ks| {
                        ks.iter()
                            .any(|&k| junction[k].0.distance(p) < junction[k].1)
                    })
                })
            })
        });
    }
    out
}
