//! Conditions of a shell model (the seed's conditions and intervals): the
//! material, the load case and the supports, attached to the mesh's geometry.
//!
//! Load cases:
//! - `design`: the design pressure on the inner side of every element; no weight.
//!   Supported statically determinately (3-2-1 on the lowest ring: six
//!   restraints, no reaction under a self-balanced load).
//! - `operating`: design pressure, plus the liquid's hydrostatic pressure
//!   ρ·g·(level − z) at the operating level (taken at each element's centroid),
//!   plus gravity on the metal; supported where the vessel rests.
//! - `test`: the UG-99(b) hydrotest pressure at the top (from [`crate::calc`]),
//!   the vessel full of water, gravity; supported where the vessel rests.
//!
//! Where a vessel rests: a skirt's base ring when the skirt is meshed
//! ([`super::skirt`]: x, y and z held on its corner and mid-side nodes; the
//! skirt carries no pressure), else its top ring (the envelope's ring nearest
//! the skirt's top: axial displacement held all round, plus two nodes across
//! the axis against sliding and turning), each saddle's base plate when the
//! saddles are meshed ([`super::saddle`]: every node held vertically and across
//! the axis, the first saddle's also along it: anchored, the others sliding on
//! slotted holes), else each saddle's contact arc (vertical
//! displacement held on the nodes of the saddle's ring within its contact
//! angle, the first saddle also held along and across the axis at its lowest
//! node, the second across it). Legs and lugs are not modelled yet: such a
//! vessel falls back to the 3-2-1 restraints. Each nozzle neck's end carries
//! its closed flange's pressure thrust. Units: mm, N, MPa, t/mm³, s.

use glam::DVec3;

use super::{FeMesh, FemError};
use crate::calc::{MaterialTable, calculate};
use crate::constraints::ResolvedVessel;
use crate::design::VesselDesign;
use crate::format::WATER_DENSITY;
use crate::operating::metal_density;
use crate::parts::PartGeometry;

/// Standard gravity, mm/s².
pub const GRAVITY: f64 = 9806.65;
/// Poisson's ratio of steel (the materials table carries no ν).
pub const POISSON: f64 = 0.3;
/// Modulus used when the design names no material, MPa (carbon steel).
pub const DEFAULT_MODULUS: f64 = 200_000.0;

/// A load case.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadCase {
    /// Design pressure alone.
    Design,
    /// Design pressure, liquid at the operating level, weight.
    Operating,
    /// Hydrotest pressure, full of water, weight.
    Test,
}

impl LoadCase {
    /// The case's name in files and reports.
    pub fn name(self) -> &'static str {
        match self {
            LoadCase::Design => "design",
            LoadCase::Operating => "operating",
            LoadCase::Test => "test",
        }
    }
}

/// A displacement restraint: node and the global degrees of freedom (1 = x,
/// 2 = y, 3 = z) held at zero.
#[derive(Clone, Debug, PartialEq)]
pub struct Support {
    /// Node index.
    pub node: usize,
    /// Degrees of freedom held.
    pub dofs: Vec<u8>,
}

/// A mesh with its material, loads and supports: what a solver deck needs.
#[derive(Clone, Debug, PartialEq)]
pub struct FeModel {
    /// The mesh.
    pub mesh: FeMesh,
    /// Vessel tag.
    pub tag: String,
    /// Load case.
    pub case: LoadCase,
    /// Material name.
    pub material: String,
    /// Young's modulus, MPa.
    pub modulus: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Metal density, t/mm³.
    pub density: f64,
    /// Allowable stress S at the design temperature, MPa (when the design's
    /// material is in the table).
    pub allowable: Option<f64>,
    /// Pressure on the inner side of each element, MPa (same order as the
    /// elements).
    pub pressure: Vec<f64>,
    /// Nodal forces, N: the pressure thrust of each nozzle's closed flange on
    /// its neck's end, P·π·r² along the neck axis, spread over the end's nodes
    /// as a uniform line load (consistent nodal forces).
    pub loads: Vec<(usize, DVec3)>,
    /// Gravity on the metal.
    pub gravity: bool,
    /// Supports.
    pub supports: Vec<Support>,
    /// How the supports were chosen.
    pub support_note: String,
}

/// Axial coordinate of `p` along the mesh's axis.
fn axial(mesh: &FeMesh, p: DVec3) -> f64 {
    (p - mesh.axis.0).dot(mesh.axis.1)
}

/// The nodes of the ring nearest axial position `a` (all nodes within a
/// micrometre of the nearest node's axial position).
fn ring_at(mesh: &FeMesh, a: f64) -> Vec<usize> {
    let best = mesh
        .nodes
        .iter()
        .map(|&p| axial(mesh, p))
        .min_by(|x, y| (x - a).abs().total_cmp(&(y - a).abs()))
        .unwrap_or(a);
    (0..mesh.nodes.len())
        .filter(|&i| (axial(mesh, mesh.nodes[i]) - best).abs() < 1e-3)
        .collect()
}

/// Among `ring`, the node farthest along `dir` from the axis.
fn extreme(mesh: &FeMesh, ring: &[usize], dir: DVec3) -> usize {
    ring.iter()
        .copied()
        .max_by(|&i, &j| mesh.nodes[i].dot(dir).total_cmp(&mesh.nodes[j].dot(dir)))
        .unwrap_or(0)
}

/// Six restraints on one ring, statically determinate: node A held in x, y, z;
/// node B (across the axis) in the two directions across AB... chosen so no
/// rigid-body mode is left and no reaction arises under a self-balanced load.
fn three_two_one(mesh: &FeMesh, ring: &[usize]) -> Vec<Support> {
    let axis = mesh.axis.1;
    let across = axis.any_orthonormal_vector();
    let other = axis.cross(across);
    let a = extreme(mesh, ring, across);
    let b = extreme(mesh, ring, -across);
    let c = extreme(mesh, ring, other);
    // Global dof closest to a direction.
    let dof = |d: DVec3| -> u8 {
        let d = d.abs();
        if d.x >= d.y && d.x >= d.z {
            1
        } else if d.y >= d.z {
            2
        } else {
            3
        }
    };
    let ax = dof(axis);
    let ot = dof(other);
    vec![
        Support {
            node: a,
            dofs: vec![1, 2, 3],
        },
        Support {
            node: b,
            dofs: {
                let mut d = vec![ax, ot];
                d.sort_unstable();
                d.dedup();
                d
            },
        },
        Support {
            node: c,
            dofs: vec![ax],
        },
    ]
}

/// Supports where the vessel rests, or the 3-2-1 restraints and why.
fn resting(mesh: &FeMesh, resolved: &ResolvedVessel) -> (Vec<Support>, String) {
    let to_plant = |z: f64| {
        axial(
            mesh,
            resolved.frame.transform_point3(DVec3::new(0.0, 0.0, z)),
        )
    };
    for part in &resolved.parts {
        if let PartGeometry::Skirt(_) = &part.geometry
            && let Some(k) = mesh.parts.iter().position(|p| p.id == part.id)
            && mesh.structural.contains(&k)
        {
            // The skirt is meshed: its base ring (corner and mid-side nodes)
            // stands on the foundation.
            let nodes = mesh.part_nodes(k);
            let low = nodes
                .iter()
                .map(|&n| axial(mesh, mesh.nodes[n]))
                .fold(f64::INFINITY, f64::min);
            let out = nodes
                .into_iter()
                .filter(|&n| (axial(mesh, mesh.nodes[n]) - low).abs() < 1e-3)
                .map(|n| Support {
                    node: n,
                    dofs: vec![1, 2, 3],
                })
                .collect();
            return (
                out,
                format!(
                    "skirt {}: meshed as a shell, its base held in x, y and z",
                    part.id
                ),
            );
        }
        if let PartGeometry::Skirt(s) = &part.geometry {
            let top = part
                .frame
                .transform_point3(DVec3::new(0.0, 0.0, s.height))
                .z;
            let ring = ring_at(mesh, to_plant(top));
            let axis = mesh.axis.1;
            let across = axis.any_orthonormal_vector();
            let a = extreme(mesh, &ring, across);
            let b = extreme(mesh, &ring, -across);
            let mut out: Vec<Support> = ring
                .iter()
                .map(|&n| Support {
                    node: n,
                    dofs: vec![3],
                })
                .collect();
            out.push(Support {
                node: a,
                dofs: vec![1, 2],
            });
            out.push(Support {
                node: b,
                dofs: vec![if across.x.abs() > across.y.abs() {
                    2
                } else {
                    1
                }],
            });
            return (
                out,
                format!(
                    "skirt {}: axial displacement held on the ring at its top",
                    part.id
                ),
            );
        }
    }
    let saddles: Vec<_> = resolved
        .parts
        .iter()
        .filter_map(|p| match &p.geometry {
            PartGeometry::Saddle(s) => Some((p, s)),
            _ => None,
        })
        .collect();
    let plates: Vec<(&str, usize)> = saddles
        .iter()
        .filter_map(|(part, _)| {
            let id = format!("{}/{}", part.id, super::saddle::BASE_PLATE);
            let k = mesh.parts.iter().position(|p| p.id == id)?;
            mesh.structural
                .contains(&k)
                .then_some((part.id.as_str(), k))
        })
        .collect();
    if !plates.is_empty() && plates.len() == saddles.len() {
        // The saddles are meshed: each base plate (corner and mid-side nodes)
        // bears on the foundation; the first is anchored, the others slide
        // along the axis on slotted holes.
        let axis = mesh.axis.1;
        let across = if axis.x.abs() > axis.y.abs() { 2 } else { 1 };
        let mut out = Vec::new();
        for (k, &(_, part)) in plates.iter().enumerate() {
            let dofs = if k == 0 {
                vec![1, 2, 3]
            } else {
                let mut d = vec![across, 3];
                d.sort_unstable();
                d
            };
            out.extend(mesh.part_nodes(part).into_iter().map(|n| Support {
                node: n,
                dofs: dofs.clone(),
            }));
        }
        let names: Vec<&str> = plates.iter().map(|p| p.0).collect();
        return (
            out,
            format!(
                "saddles {}: base plates held on the foundation ({} anchored; the others \
                 held vertically and across the axis, free to slide along it)",
                names.join(", "),
                names[0]
            ),
        );
    }
    if !saddles.is_empty() {
        let mut out = Vec::new();
        let axis = mesh.axis.1;
        for (k, (part, saddle)) in saddles.iter().enumerate() {
            let z = part.frame.translation.z;
            let ring = ring_at(mesh, to_plant(z));
            let centre = mesh.axis.0 + axis * to_plant(z);
            let half = (saddle.contact_angle / 2.0).to_radians();
            let contact: Vec<usize> = ring
                .iter()
                .copied()
                .filter(|&n| {
                    let d = (mesh.nodes[n] - centre).normalize_or_zero();
                    d.dot(-DVec3::Z) >= half.cos() - 1e-9
                })
                .collect();
            out.extend(contact.iter().map(|&n| Support {
                node: n,
                dofs: vec![3],
            }));
            let low = extreme(mesh, &ring, -DVec3::Z);
            let across = if axis.x.abs() > axis.y.abs() { 2 } else { 1 };
            out.push(Support {
                node: low,
                dofs: if k == 0 { vec![1, 2] } else { vec![across] },
            });
        }
        return (
            out,
            "saddles: vertical displacement held on each saddle's contact arc".into(),
        );
    }
    let lowest = mesh
        .nodes
        .iter()
        .map(|&p| p.z)
        .fold(f64::INFINITY, f64::min);
    let ring = ring_at(mesh, axial(mesh, DVec3::new(0.0, 0.0, lowest)));
    (
        three_two_one(mesh, &ring),
        "no skirt or saddle modelled: statically determinate 3-2-1 restraints".into(),
    )
}

/// The nodal forces of pressure `p` on the closed end of `neck`: P·π·r² along
/// its axis as a uniform load along the end's edges (a quadratic edge's
/// consistent forces are 1/6, 2/3, 1/6 of its share; a linear one's 1/2, 1/2).
fn thrust(mesh: &FeMesh, neck: &super::NeckEnd, p: f64) -> Vec<(usize, DVec3)> {
    let count = neck.nodes.len();
    let mut weights: Vec<(usize, f64)> = Vec::with_capacity(2 * count);
    for j in 0..count {
        let (a, b) = (neck.nodes[j], neck.nodes[(j + 1) % count]);
        let length = mesh.nodes[a].distance(mesh.nodes[b]);
        match neck.mids.get(j) {
            Some(&m) => {
                weights.push((a, length / 6.0));
                weights.push((m, 2.0 * length / 3.0));
                weights.push((b, length / 6.0));
            }
            None => {
                weights.push((a, 0.5 * length));
                weights.push((b, 0.5 * length));
            }
        }
    }
    let total: f64 = weights.iter().map(|w| w.1).sum();
    let force = p * std::f64::consts::PI * neck.radius * neck.radius;
    let mut by_node: std::collections::BTreeMap<usize, f64> = Default::default();
    for (n, w) in weights {
        *by_node.entry(n).or_default() += w / total;
    }
    by_node
        .into_iter()
        .map(|(n, w)| (n, neck.axis * force * w))
        .collect()
}

/// Attaches load case `case` to `mesh` of `design` (resolved as `resolved`).
///
/// # Errors
///
/// [`FemError::Conditions`] when the case needs a design field that is missing:
/// the design pressure, or the allowable stresses of the hydrotest.
pub fn conditions(
    mesh: FeMesh,
    design: &VesselDesign,
    resolved: &ResolvedVessel,
    case: LoadCase,
    table: &MaterialTable,
) -> Result<FeModel, FemError> {
    let missing = |path: &str, value: String, rule: &str| FemError::Conditions {
        vessel: design.tag.clone(),
        path: path.into(),
        value,
        rule: rule.into(),
    };
    let pressure_kpa = design.design.pressure.ok_or_else(|| {
        missing(
            "design.pressure",
            "missing".into(),
            "every load case needs the design pressure",
        )
    })?;
    if !(pressure_kpa.is_finite() && pressure_kpa > 0.0) {
        return Err(missing(
            "design.pressure",
            pressure_kpa.to_string(),
            "internal pressure only: a positive kPa(g)",
        ));
    }
    let material = design
        .design
        .material
        .as_deref()
        .and_then(|m| table.get(m).ok());
    let modulus = material.map_or(DEFAULT_MODULUS, |m| m.modulus.value);
    let allowable = material.and_then(|m| {
        design
            .design
            .temperature
            .and_then(|t| m.allowable_stress(t).ok())
    });
    let density = metal_density(&design.design) * 1e-12;
    // The pressure envelope's extent (a skirt reaches below it).
    let envelope = |e: &super::Element| !mesh.structural.contains(&e.part);
    let zs = || {
        mesh.elements
            .iter()
            .filter(|e| envelope(e))
            .flat_map(|e| e.nodes.iter().map(|&n| mesh.nodes[n].z))
    };
    let top = zs().fold(f64::NEG_INFINITY, f64::max);
    let bottom = zs().fold(f64::INFINITY, f64::min);
    let (p_top, liquid): (f64, Option<(f64, f64)>) = match case {
        LoadCase::Design => (pressure_kpa * 1e-3, None),
        LoadCase::Operating => {
            let liquid = design.operating.map(|o| {
                let rho = o.liquid_density.unwrap_or(WATER_DENSITY) * 1e-12;
                // Level above the lowest point of the mid-surface (within t/2
                // of the lowest inside point).
                let level = bottom + o.liquid_level;
                (rho, level)
            });
            (pressure_kpa * 1e-3, liquid)
        }
        LoadCase::Test => {
            let calc = calculate(design, resolved, table);
            let test = calc.vessel.hydrotest.ok_or_else(|| {
                missing(
                    "design",
                    "no hydrotest pressure".into(),
                    &format!(
                        "the test case needs the UG-99(b) pressure: {}",
                        calc.vessel.problems.join("; ")
                    ),
                )
            })?;
            (test.value, Some((WATER_DENSITY * 1e-12, top)))
        }
    };
    let at = |c: DVec3| {
        p_top + liquid.map_or(0.0, |(rho, level)| rho * GRAVITY * (level - c.z).max(0.0))
    };
    let pressure = mesh
        .elements
        .iter()
        .map(|e| {
            if !envelope(e) {
                return 0.0;
            }
            let c = e.nodes[..e.kind.corners()]
                .iter()
                .map(|&n| mesh.nodes[n])
                .sum::<DVec3>()
                / e.kind.corners() as f64;
            at(c)
        })
        .collect();
    let loads = mesh
        .necks
        .iter()
        .flat_map(|neck| thrust(&mesh, neck, at(neck.centre)))
        .collect();
    let (supports, support_note) = match case {
        LoadCase::Design => {
            let lowest = mesh.nodes.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
            let ring = ring_at(&mesh, axial(&mesh, DVec3::new(0.0, 0.0, lowest)));
            let ring = if ring.len() < 3 {
                // A pole: take the first ring of the mesh instead.
                ring_at(&mesh, axial(&mesh, mesh.nodes[0]))
            } else {
                ring
            };
            (
                three_two_one(&mesh, &ring),
                "statically determinate 3-2-1 restraints (pressure is self-balanced)".into(),
            )
        }
        _ => resting(&mesh, resolved),
    };
    Ok(FeModel {
        tag: design.tag.clone(),
        case,
        material: design
            .design
            .material
            .clone()
            .unwrap_or_else(|| "steel".into()),
        modulus,
        poisson: POISSON,
        density,
        allowable,
        pressure,
        loads,
        gravity: case != LoadCase::Design,
        supports,
        support_note,
        mesh,
    })
}
