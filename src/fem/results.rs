//! Runs CalculiX on a deck and reads the stresses back onto the model's nodes.
//!
//! CalculiX expands each shell node into nodes through the thickness (on the
//! mid-surface and on both faces) and reports stresses there. Each expanded
//! node is traced to the model node it came from (the nearest, within half the
//! thickest wall); the membrane stress at a node is the stress on the
//! mid-surface (the mean of the two faces where no mid-surface node was
//! written), the membrane-plus-bending stress the worse of the two faces.
//! Stress intensity is the largest difference of principal stresses (Tresca),
//! compared per part with the allowable S (general membrane Pm, away from
//! junctions), 1.5 S (local membrane PL, within 3·√(R·t) of a junction, see
//! [`super::zones`]) and 1.5 S (membrane plus bending), as ASME VIII-2 5.2.2
//! classifies a shell's linearised stresses.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::DVec3;

use super::frd::Frd;
use super::{FeModel, FemError};

/// The solver's program name.
pub const CCX: &str = "ccx";

/// Whether `ccx` can be run here.
pub fn solver_available() -> bool {
    Command::new(CCX)
        .arg("-v")
        .output()
        .is_ok_and(|o| !o.stdout.is_empty())
}

/// Runs `ccx` on the deck `inp` (one thread) in its directory; returns the
/// `.frd` path.
///
/// # Errors
///
/// [`FemError::Solver`] when `ccx` is missing, fails, or writes no results.
pub fn run_ccx(inp: &Path) -> Result<PathBuf, FemError> {
    let dir = inp
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let stem = inp
        .file_stem()
        .and_then(|s| s.to_str())
        .ok_or_else(|| FemError::Solver(format!("{}: no file name", inp.display())))?;
    let output = Command::new(CCX)
        .arg("-i")
        .arg(stem)
        .current_dir(dir)
        .env("OMP_NUM_THREADS", "1")
        .output()
        .map_err(|e| FemError::Solver(format!("cannot run {CCX} ({e}); install calculix-ccx")))?;
    let text = String::from_utf8_lossy(&output.stdout);
    let frd = dir.join(format!("{stem}.frd"));
    if !output.status.success() || text.contains("*ERROR") || !frd.exists() {
        let errors: Vec<&str> = text
            .lines()
            .filter(|l| l.contains("ERROR"))
            .take(5)
            .collect();
        return Err(FemError::Solver(format!(
            "{} failed ({}): {}",
            inp.display(),
            output.status,
            errors.join(" | ")
        )));
    }
    Ok(frd)
}

/// Results at one model node.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NodeResult {
    /// Displacement, mm.
    pub displacement: DVec3,
    /// Membrane (mid-surface) stress: xx, yy, zz, xy, yz, zx, MPa.
    pub membrane: [f64; 6],
    /// Membrane-plus-bending stress intensity (worse face), MPa.
    pub surface_intensity: f64,
    /// Largest von Mises stress through the thickness, MPa.
    pub von_mises: f64,
}

/// Principal stresses of a symmetric tensor (xx, yy, zz, xy, yz, zx), descending.
pub fn principal(s: [f64; 6]) -> [f64; 3] {
    let [a, b, c, d, e, f] = s;
    let p1 = d * d + e * e + f * f;
    let q = (a + b + c) / 3.0;
    let p2 = (a - q).powi(2) + (b - q).powi(2) + (c - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p <= f64::MIN_POSITIVE {
        return [q, q, q];
    }
    // det((A − qI)/p) / 2
    let (ba, bb, bc) = ((a - q) / p, (b - q) / p, (c - q) / p);
    let (bd, be, bf) = (d / p, e / p, f / p);
    let r = 0.5 * (ba * (bb * bc - be * be) - bd * (bd * bc - be * bf) + bf * (bd * be - bb * bf));
    let phi = r.clamp(-1.0, 1.0).acos() / 3.0;
    let l1 = q + 2.0 * p * phi.cos();
    let l3 = q + 2.0 * p * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos();
    [l1, 3.0 * q - l1 - l3, l3]
}

/// Stress intensity (Tresca): largest minus smallest principal stress.
pub fn intensity(s: [f64; 6]) -> f64 {
    let p = principal(s);
    p[0] - p[2]
}

/// Von Mises equivalent stress.
pub fn von_mises(s: [f64; 6]) -> f64 {
    let [a, b, c, d, e, f] = s;
    (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2)) + 3.0 * (d * d + e * e + f * f))
        .sqrt()
}

/// The results at every node of `model` from a run's `frd`.
pub fn nodal(model: &FeModel, frd: &Frd) -> Vec<NodeResult> {
    let mesh = &model.mesh;
    let t_max = mesh.parts.iter().map(|p| p.thickness).fold(0.0, f64::max);
    let cell = t_max.max(1e-3);
    let key = |p: DVec3| {
        (
            (p.x / cell).floor() as i64,
            (p.y / cell).floor() as i64,
            (p.z / cell).floor() as i64,
        )
    };
    let mut grid: HashMap<(i64, i64, i64), Vec<usize>> = HashMap::new();
    for (i, &p) in mesh.nodes.iter().enumerate() {
        grid.entry(key(p)).or_default().push(i);
    }
    let nearest = |p: DVec3| -> Option<(usize, f64)> {
        let (x, y, z) = key(p);
        let mut best: Option<(usize, f64)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &i in grid.get(&(x + dx, y + dy, z + dz)).into_iter().flatten() {
                        let d = mesh.nodes[i].distance(p);
                        if best.is_none_or(|b| d < b.1) {
                            best = Some((i, d));
                        }
                    }
                }
            }
        }
        best.filter(|b| b.1 <= 0.51 * t_max + 1e-6)
    };
    #[derive(Default, Clone)]
    struct Acc {
        mid: Option<([f64; 6], DVec3)>,
        faces: Vec<([f64; 6], DVec3)>,
    }
    let mut acc = vec![Acc::default(); mesh.nodes.len()];
    for (id, p) in &frd.nodes {
        let (Some(s), Some((i, d))) = (frd.stress.get(id), nearest(*p)) else {
            continue;
        };
        let u = frd.displacement.get(id).copied().unwrap_or_default();
        if d <= 1e-6 * (1.0 + p.length()) {
            acc[i].mid = Some((*s, u));
        } else {
            acc[i].faces.push((*s, u));
        }
    }
    acc.iter()
        .map(|a| {
            let n = a.faces.len().max(1) as f64;
            let mean_s = a.faces.iter().fold([0.0; 6], |mut m, (s, _)| {
                for k in 0..6 {
                    m[k] += s[k] / n;
                }
                m
            });
            let mean_u = a.faces.iter().map(|f| f.1).sum::<DVec3>() / n;
            let (membrane, displacement) = a.mid.unwrap_or((mean_s, mean_u));
            let all = a.faces.iter().map(|f| f.0).chain(a.mid.map(|m| m.0));
            NodeResult {
                displacement,
                membrane,
                surface_intensity: a
                    .faces
                    .iter()
                    .map(|f| intensity(f.0))
                    .fold(intensity(membrane), f64::max),
                von_mises: all.map(von_mises).fold(0.0, f64::max),
            }
        })
        .collect()
}

/// The stresses of one part against its allowable, classified as VIII-2
/// 5.2.2 does ([`super::zones`]): general membrane away from junctions, local
/// membrane near them.
#[derive(Clone, Debug, PartialEq)]
pub struct PartStress {
    /// Part name (`V-101/S1`).
    pub name: String,
    /// Largest general membrane stress intensity Pm (nodes farther than
    /// 3·√(R·t) from every junction), MPa; `None` when the whole part is near one.
    pub membrane: Option<f64>,
    /// Largest local membrane stress intensity PL (nodes within 3·√(R·t) of a
    /// junction), MPa; `None` when no node of the part is near one.
    pub local: Option<f64>,
    /// Largest membrane-plus-bending stress intensity (Pm + Pb or PL + Pb),
    /// MPa.
    pub membrane_bending: f64,
    /// Allowable S at the design temperature, MPa, if known.
    pub allowable: Option<f64>,
}

impl PartStress {
    /// Whether Pm ≤ S, PL ≤ 1.5 S and Pm + Pb (PL + Pb) ≤ 1.5 S (unknown S:
    /// `None`).
    pub fn passes(&self) -> Option<bool> {
        self.allowable.map(|s| {
            self.membrane.is_none_or(|pm| pm <= s)
                && self.local.is_none_or(|pl| pl <= 1.5 * s)
                && self.membrane_bending <= 1.5 * s
        })
    }
}

/// Per-part maxima of `results` (one per model node).
pub fn part_stresses(model: &FeModel, results: &[NodeResult]) -> Vec<PartStress> {
    let local = super::zones::local_nodes(&model.mesh);
    let max = |it: &mut dyn Iterator<Item = f64>| it.reduce(f64::max);
    (0..model.mesh.parts.len())
        .map(|k| {
            let nodes = model.mesh.part_nodes(k);
            let si = |n: &usize| intensity(results[*n].membrane);
            PartStress {
                name: model.mesh.parts[k].name.clone(),
                membrane: max(&mut nodes.iter().filter(|&&n| !local[n]).map(si)),
                local: max(&mut nodes.iter().filter(|&&n| local[n]).map(si)),
                membrane_bending: nodes
                    .iter()
                    .map(|&n| results[n].surface_intensity)
                    .fold(0.0, f64::max),
                allowable: model.allowable,
            }
        })
        .collect()
}
