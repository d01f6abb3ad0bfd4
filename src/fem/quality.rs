//! Conformity and quality of a shell mesh: free and non-manifold edges,
//! coincident nodes (two nodes where one should be shared), corner angles and
//! the scaled Jacobian of quadrilaterals, minimum angles of triangles, inverted
//! elements (normal pointing into the vessel, or into a nozzle neck), the size ratio of neighbours,
//! and the seed's quality index cos(min angle) as a histogram.

use std::collections::{HashMap, HashSet};

use glam::DVec3;

use super::FeMesh;

/// The quality figures of a mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Quality {
    /// Elements.
    pub elements: usize,
    /// Edges used by one element whose ends are not both on a real boundary.
    pub free_edges: usize,
    /// Edges used by more than two elements.
    pub nonmanifold_edges: usize,
    /// Pairs of distinct nodes at one point (within 1e-6 mm).
    pub coincident_nodes: usize,
    /// Smallest and largest quadrilateral corner angle, degrees.
    pub quad_angles: (f64, f64),
    /// Quadrilaterals with every corner angle in 45–135°.
    pub quads_in_range: usize,
    /// Quadrilaterals.
    pub quads: usize,
    /// Smallest scaled Jacobian.
    pub min_scaled_jacobian: f64,
    /// Elements with scaled Jacobian ≥ 0.3.
    pub jacobian_ok: usize,
    /// Smallest triangle angle, degrees (180 when there is no triangle).
    pub min_triangle_angle: f64,
    /// Elements whose normal points into the vessel or whose Jacobian is ≤ 0.
    pub inverted: usize,
    /// Largest size ratio of two elements sharing an edge.
    pub max_size_ratio: f64,
    /// The two elements (indices) of that ratio, the larger first.
    pub max_size_ratio_elements: (usize, usize),
    /// Histogram of cos(min angle) in ten bins of 0.1.
    pub histogram: [usize; 10],
}

/// Measures `mesh`.
pub fn quality(mesh: &FeMesh) -> Quality {
    let mut q = Quality {
        elements: mesh.elements.len(),
        quad_angles: (180.0, 0.0),
        min_scaled_jacobian: 1.0,
        min_triangle_angle: 180.0,
        max_size_ratio: 1.0,
        ..Quality::default()
    };
    let boundary: HashSet<usize> = mesh.boundary.iter().copied().collect();
    let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    let (lo, hi) = mesh.nodes.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let centre = 0.5 * (lo + hi);
    let mut sizes = Vec::with_capacity(mesh.elements.len());
    for (e, el) in mesh.elements.iter().enumerate() {
        let nc = el.kind.corners();
        let c: Vec<DVec3> = el.nodes[..nc].iter().map(|&n| mesh.nodes[n]).collect();
        for k in 0..nc {
            let (a, b) = (el.nodes[k], el.nodes[(k + 1) % nc]);
            edges.entry((a.min(b), a.max(b))).or_default().push(e);
        }
        // Newell normal.
        let mut normal = DVec3::ZERO;
        for k in 0..nc {
            let (p, r) = (c[k], c[(k + 1) % nc]);
            normal += DVec3::new(
                (p.y - r.y) * (p.z + r.z),
                (p.z - r.z) * (p.x + r.x),
                (p.x - r.x) * (p.y + r.y),
            );
        }
        let area = 0.5 * normal.length();
        sizes.push(area.sqrt());
        let n = normal.normalize_or_zero();
        let centroid = c.iter().sum::<DVec3>() / nc as f64;
        let mut min_angle = 180.0f64;
        let mut max_angle = 0.0f64;
        let mut sj = 1.0f64;
        for k in 0..nc {
            let e1 = c[(k + 1) % nc] - c[k];
            let e2 = c[(k + nc - 1) % nc] - c[k];
            let angle = e1.angle_between(e2).to_degrees();
            min_angle = min_angle.min(angle);
            max_angle = max_angle.max(angle);
            sj = sj.min(e1.cross(e2).dot(n) / (e1.length() * e2.length()));
        }
        if nc == 4 {
            q.quads += 1;
            q.quad_angles.0 = q.quad_angles.0.min(min_angle);
            q.quad_angles.1 = q.quad_angles.1.max(max_angle);
            if min_angle >= 45.0 && max_angle <= 135.0 {
                q.quads_in_range += 1;
            }
        } else {
            q.min_triangle_angle = q.min_triangle_angle.min(min_angle);
            // A triangle's scaled Jacobian is its sin(angle) normalised to the
            // equilateral one.
            sj /= (60.0f64).to_radians().sin();
        }
        q.min_scaled_jacobian = q.min_scaled_jacobian.min(sj);
        if sj >= 0.3 {
            q.jacobian_ok += 1;
        }
        // Inside a neck is its axis; inside the envelope, its box's centre.
        let inside = match mesh.necks.iter().find(|k| k.part == el.part) {
            Some(neck) => neck.centre + neck.axis * (centroid - neck.centre).dot(neck.axis),
            None => centre,
        };
        if sj <= 0.0 || n.dot(centroid - inside) <= 0.0 {
            q.inverted += 1;
        }
        let bin = ((min_angle.to_radians().cos() * 10.0) as usize).min(9);
        q.histogram[bin] += 1;
    }
    for ((a, b), users) in &edges {
        match users.len() {
            1 => {
                if !(boundary.contains(a) && boundary.contains(b)) {
                    q.free_edges += 1;
                }
            }
            2 => {
                let (s, t) = (sizes[users[0]], sizes[users[1]]);
                let ratio = s.max(t) / s.min(t).max(1e-300);
                if ratio > q.max_size_ratio {
                    q.max_size_ratio = ratio;
                    q.max_size_ratio_elements = if s >= t {
                        (users[0], users[1])
                    } else {
                        (users[1], users[0])
                    };
                }
            }
            _ => q.nonmanifold_edges += 1,
        }
    }
    let key = |p: DVec3| ((p * 1e6).round().as_i64vec3()).to_array();
    let mut seen: HashMap<[i64; 3], usize> = HashMap::new();
    for &p in &mesh.nodes {
        *seen.entry(key(p)).or_default() += 1;
    }
    q.coincident_nodes = seen.values().map(|&c| c.saturating_sub(1)).sum();
    q
}
