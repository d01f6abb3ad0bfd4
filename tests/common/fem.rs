//! Finite-element test helpers: a one-vessel design of given heads and course,
//! and a CalculiX run of a model in a temporary directory (`None`, with a
//! message, where `ccx` is not installed; CI installs it).

use glam::DVec3;
use vesselcad::calc::MaterialTable;
use vesselcad::design::{Design, parse};
use vesselcad::fem::results::{NodeResult, nodal, run_ccx, solver_available};
use vesselcad::fem::{FeModel, FemOptions, LoadCase, frd, inp, vessel_model};

/// A vertical vessel `V-1`: head `head` (a JSON object's fields, e.g.
/// `"shape": "hemispherical"`), a course of `od` × `length`, the same head on
/// top, all of thickness `t`; design pressure `kpa`, SA-516-70 at 20 °C.
pub fn vessel(head: &str, od: f64, length: f64, t: f64, kpa: f64) -> Design {
    let text = format!(
        r#"{{"format": "vesselcad/1", "units": "mm", "vessels": [{{
          "tag": "V-1", "kind": "vertical",
          "placement": {{ "position": [0, 0, 0], "rotation": 0 }},
          "design": {{ "pressure": {kpa}, "temperature": 20, "material": "SA-516-70" }},
          "parts": [
            {{ "head": {{ "id": "H1", {head}, "thickness": {t} }} }},
            {{ "shell": {{ "id": "S1", "od": {od}, "length": {length}, "thickness": {t} }} }},
            {{ "head": {{ "id": "H2", {head}, "thickness": {t} }} }}
          ]}}]}}"#
    );
    parse(&text).unwrap_or_else(|e| panic!("test design: {e}"))
}

/// The design-case model of `V-1` at element size `size`.
pub fn model(design: &Design, size: f64) -> FeModel {
    let options = FemOptions {
        size: Some(size),
        order: 2,
    };
    vessel_model(
        design,
        "V-1",
        &options,
        LoadCase::Design,
        &MaterialTable::builtin(),
    )
    .unwrap_or_else(|e| panic!("fem model: {e}"))
}

/// Solves `model` with `ccx`; `None` (after saying so) when `ccx` is absent.
pub fn solve(model: &FeModel, name: &str) -> Option<Vec<NodeResult>> {
    if !solver_available() {
        eprintln!("SKIPPED {name}: ccx (CalculiX) is not installed here; CI installs calculix-ccx");
        return None;
    }
    let dir = tempfile::tempdir().expect("temporary directory");
    let deck = dir.path().join(format!("{name}.inp"));
    std::fs::write(&deck, inp::to_inp(model)).expect("write deck");
    let frd_path = run_ccx(&deck).unwrap_or_else(|e| panic!("{e}"));
    let frd = frd::read(&frd_path).unwrap_or_else(|e| panic!("{e}"));
    Some(nodal(model, &frd))
}

/// The membrane stress `s` (xx, yy, zz, xy, yz, zx) along unit `a` and `b`: aᵀ σ b.
pub fn along(s: [f64; 6], a: DVec3, b: DVec3) -> f64 {
    let [xx, yy, zz, xy, yz, zx] = s;
    let sa = DVec3::new(
        xx * a.x + xy * a.y + zx * a.z,
        xy * a.x + yy * a.y + yz * a.z,
        zx * a.x + yz * a.y + zz * a.z,
    );
    sa.dot(b)
}
