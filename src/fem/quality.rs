//! Conformity and quality of a shell mesh: free and non-manifold edges,
//! coincident nodes (two nodes where one should be shared), corner angles and
//! the scaled Jacobian of quadrilaterals, minimum angles of triangles, inverted
//! elements (normal pointing into the vessel, or into a nozzle neck), the size ratio of neighbours,
//! the edge aspect ratio, and the seed's quality index cos(min angle) as a
//! histogram; for the whole mesh ([`quality`]) and per part ([`by_part`]).

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
    /// Largest aspect ratio (longest over shortest corner-to-corner edge).
    pub max_aspect: f64,
    /// Histogram of cos(min angle) in ten bins of 0.1.
    pub histogram: [usize; 10],
}

impl Quality {
    /// Figures with nothing counted yet.
    fn empty() -> Quality {
        Quality {
            quad_angles: (180.0, 0.0),
            min_scaled_jacobian: 1.0,
            min_triangle_angle: 180.0,
            max_size_ratio: 1.0,
            max_aspect: 1.0,
            ..Quality::default()
        }
    }

    /// Counts one element's shape figures in.
    fn add(&mut self, m: &Shape) {
        self.elements += 1;
        if m.corners == 4 {
            self.quads += 1;
            self.quad_angles.0 = self.quad_angles.0.min(m.min_angle);
            self.quad_angles.1 = self.quad_angles.1.max(m.max_angle);
            if m.min_angle >= 45.0 && m.max_angle <= 135.0 {
                self.quads_in_range += 1;
            }
        } else {
            self.min_triangle_angle = self.min_triangle_angle.min(m.min_angle);
        }
        self.min_scaled_jacobian = self.min_scaled_jacobian.min(m.scaled_jacobian);
        if m.scaled_jacobian >= 0.3 {
            self.jacobian_ok += 1;
        }
        if m.inverted {
            self.inverted += 1;
        }
        self.max_aspect = self.max_aspect.max(m.aspect);
        let bin = ((m.min_angle.to_radians().cos() * 10.0) as usize).min(9);
        self.histogram[bin] += 1;
    }

    /// Counts a pair of neighbours `(larger, smaller)` of size ratio `ratio` in.
    fn neighbours(&mut self, ratio: f64, pair: (usize, usize)) {
        if ratio > self.max_size_ratio {
            self.max_size_ratio = ratio;
            self.max_size_ratio_elements = pair;
        }
    }
}

/// The shape figures of one element.
#[derive(Clone, Copy, Debug)]
struct Shape {
    corners: usize,
    min_angle: f64,
    max_angle: f64,
    scaled_jacobian: f64,
    aspect: f64,
    size: f64,
    inverted: bool,
}

/// Measures `mesh`.
pub fn quality(mesh: &FeMesh) -> Quality {
    measure(mesh).0
}

/// Measures each part of `mesh` (index as [`FeMesh::parts`]): its elements'
/// shapes, and the size ratios across every edge one of its elements has
/// (to a neighbour in it or in the next part). Edge and node counts (free,
/// non-manifold, coincident) are the whole mesh's and stay zero here.
pub fn by_part(mesh: &FeMesh) -> Vec<Quality> {
    measure(mesh).1
}

/// The whole mesh's figures and each part's.
fn measure(mesh: &FeMesh) -> (Quality, Vec<Quality>) {
    let mut q = Quality::empty();
    let mut parts = vec![Quality::empty(); mesh.parts.len()];
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
        for k in 0..nc {
            let (a, b) = (el.nodes[k], el.nodes[(k + 1) % nc]);
            edges.entry((a.min(b), a.max(b))).or_default().push(e);
        }
        // Inside a neck is its axis; inside the envelope, its box's centre.
        let neck = mesh.necks.iter().find(|k| k.part == el.part);
        let m = shape(mesh, el, |centroid| match neck {
            Some(neck) => neck.centre + neck.axis * (centroid - neck.centre).dot(neck.axis),
            None => centre,
        });
        sizes.push(m.size);
        q.add(&m);
        if let Some(p) = parts.get_mut(el.part) {
            p.add(&m);
        }
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
                let pair = if s >= t {
                    (users[0], users[1])
                } else {
                    (users[1], users[0])
                };
                q.neighbours(ratio, pair);
                for &u in users {
                    if let Some(p) = parts.get_mut(mesh.elements[u].part) {
                        p.neighbours(ratio, pair);
                    }
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
    (q, parts)
}

/// The shape figures of element `el`; `inside(centroid)` is a point the
/// element's outward normal must point away from.
fn shape(mesh: &FeMesh, el: &super::Element, inside: impl Fn(DVec3) -> DVec3) -> Shape {
    let nc = el.kind.corners();
    let c: Vec<DVec3> = el.nodes[..nc].iter().map(|&n| mesh.nodes[n]).collect();
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
    let n = normal.normalize_or_zero();
    let centroid = c.iter().sum::<DVec3>() / nc as f64;
    let mut min_angle = 180.0f64;
    let mut max_angle = 0.0f64;
    let mut sj = 1.0f64;
    let (mut shortest, mut longest) = (f64::INFINITY, 0.0f64);
    for k in 0..nc {
        let e1 = c[(k + 1) % nc] - c[k];
        let e2 = c[(k + nc - 1) % nc] - c[k];
        let angle = e1.angle_between(e2).to_degrees();
        min_angle = min_angle.min(angle);
        max_angle = max_angle.max(angle);
        sj = sj.min(e1.cross(e2).dot(n) / (e1.length() * e2.length()));
        shortest = shortest.min(e1.length());
        longest = longest.max(e1.length());
    }
    if nc == 3 {
        // A triangle's scaled Jacobian is its sin(angle) normalised to the
        // equilateral one.
        sj /= (60.0f64).to_radians().sin();
    }
    Shape {
        corners: nc,
        min_angle,
        max_angle,
        scaled_jacobian: sj,
        aspect: longest / shortest.max(1e-300),
        size: area.sqrt(),
        inverted: sj <= 0.0 || n.dot(centroid - inside(centroid)) <= 0.0,
    }
}
