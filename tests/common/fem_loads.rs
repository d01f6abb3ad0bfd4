//! Finite-element test helpers for load cases: positions and area vectors on
//! S8R elements (Gauss integration over a mesh), a CalculiX run kept as its
//! `.frd`, and the sum of the reactions at given nodes.

use glam::DVec3;
use vesselcad::fem::frd::Frd;
use vesselcad::fem::results::{run_ccx, solver_available};
use vesselcad::fem::{ElementKind, FeMesh, FeModel, frd, inp};

/// Position on quadratic element `e` at (ξ, η) ∈ [−1, 1]² (serendipity S8R).
pub fn at(mesh: &FeMesh, e: usize, xi: f64, eta: f64) -> DVec3 {
    let el = &mesh.elements[e];
    assert_eq!(el.kind, ElementKind::Quad8);
    let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut p = DVec3::ZERO;
    for (i, &(a, b)) in c.iter().enumerate() {
        let n = 0.25 * (1.0 + xi * a) * (1.0 + eta * b) * (xi * a + eta * b - 1.0);
        p += mesh.nodes[el.nodes[i]] * n;
    }
    let mids = [
        0.5 * (1.0 - xi * xi) * (1.0 - eta),
        0.5 * (1.0 + xi) * (1.0 - eta * eta),
        0.5 * (1.0 - xi * xi) * (1.0 + eta),
        0.5 * (1.0 - xi) * (1.0 - eta * eta),
    ];
    for (i, n) in mids.iter().enumerate() {
        p += mesh.nodes[el.nodes[4 + i]] * *n;
    }
    p
}

/// Σ over 3×3 Gauss points of `f(element, position, area vector)` over every
/// element.
pub fn integrate(mesh: &FeMesh, f: impl Fn(usize, DVec3, DVec3) -> f64) -> f64 {
    let g = [
        (-(0.6f64).sqrt(), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        ((0.6f64).sqrt(), 5.0 / 9.0),
    ];
    let h = 1e-6;
    let mut sum = 0.0;
    for e in 0..mesh.elements.len() {
        for &(xi, wi) in &g {
            for &(eta, wj) in &g {
                let dx = (at(mesh, e, xi + h, eta) - at(mesh, e, xi - h, eta)) / (2.0 * h);
                let dy = (at(mesh, e, xi, eta + h) - at(mesh, e, xi, eta - h)) / (2.0 * h);
                sum += wi * wj * f(e, at(mesh, e, xi, eta), dx.cross(dy));
            }
        }
    }
    sum
}

/// Runs `ccx` on `model` and reads its results; `None` (after saying so)
/// where `ccx` is not installed.
pub fn run(model: &FeModel, name: &str) -> Option<Frd> {
    if !solver_available() {
        eprintln!("SKIPPED {name}: ccx (CalculiX) is not installed here; CI installs calculix-ccx");
        return None;
    }
    let dir = tempfile::tempdir().expect("temporary directory");
    let deck = dir.path().join(format!("{name}.inp"));
    std::fs::write(&deck, inp::to_inp(model)).expect("write deck");
    let path = run_ccx(&deck).unwrap_or_else(|e| panic!("{e}"));
    Some(frd::read(&path).unwrap_or_else(|e| panic!("{e}")))
}

/// The sum of the reactions of `results` at mesh nodes `held`, N. CalculiX
/// restrains (and reports) the nodes it expands each shell node into,
/// through the thickness: they are traced back by position (within half the
/// thickest part of a held node).
pub fn reaction_at(model: &FeModel, results: &Frd, held: &[usize]) -> DVec3 {
    let t = model
        .mesh
        .parts
        .iter()
        .map(|p| p.thickness)
        .fold(0.0, f64::max);
    let held: Vec<DVec3> = held.iter().map(|&n| model.mesh.nodes[n]).collect();
    let mut ids: Vec<usize> = results
        .nodes
        .iter()
        .filter(|(_, p)| held.iter().any(|h| h.distance(**p) <= 0.51 * t))
        .map(|(&id, _)| id)
        .collect();
    ids.sort_unstable();
    ids.dedup();
    ids.iter()
        .filter_map(|n| results.reactions.get(n))
        .copied()
        .sum()
}

/// The sum of the reactions at every supported node of a CalculiX run of
/// `model`, N.
pub fn reactions(model: &FeModel, name: &str) -> Option<DVec3> {
    let results = run(model, name)?;
    let held: Vec<usize> = model.supports.iter().map(|s| s.node).collect();
    Some(reaction_at(model, &results, &held))
}
