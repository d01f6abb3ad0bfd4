//! IGES 5.3 of the exact model: the B-rep [`vessel_brep`](super::vessel_brep)
//! builds for STEP (one exact model, two writers), in one of two
//! representations ([`IgesEntities`]): by default the B-rep itself (`iges_brep`:
//! shells of faces sharing edges, manifold solids with `solids`), or trimmed
//! surfaces that share nothing (`iges_trimmed`), which every importer reads
//! and a receiver sews.
//!
//! Geometry is in the plant frame, millimetres. Each face is named
//! `tag/id/patch` by a name property (406 form 15) and coloured (314) by what
//! it belongs to: a part of the envelope, a nozzle, a support; each vessel's
//! entities are on level 1 + its index and its faces (trimmed surfaces) or
//! shells and solids (B-rep) in a group (402 form 7) named by its tag.

use rayon::prelude::*;

use super::blocks::ExchangeOptions;
use super::brep::VesselBrep;
use super::error::ExchangeError;
use super::iges::{Entry, Global, IgesWriter, Params, status};
use super::iges_brep::brep_entities;
use super::iges_entities::VesselWriter;
use super::iges_trimmed::trimmed_faces;
use super::source::{NodeKind, vessel_sources};
use super::topology::vessel_brep_with;
use crate::design::Design;

/// Colours (per cent red, green, blue) and names of the three kinds of face.
const COLOURS: [(NodeKind, [f64; 3], &str); 3] = [
    (NodeKind::Part, [70.0, 72.0, 75.0], "shell"),
    (NodeKind::Nozzle, [25.0, 45.0, 80.0], "nozzle"),
    (NodeKind::Support, [45.0, 40.0, 35.0], "support"),
];

/// How an IGES file represents the faces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum IgesEntities {
    /// Manifold solid B-rep object entities: faces (510) on shared edges
    /// (504, 502) with pcurves, in shells (514; closed form 1, open form 2),
    /// each closed shell a solid (186) when solids are asked for.
    #[default]
    Brep,
    /// Trimmed surfaces (144/142/102/126), no shared edges.
    Trimmed,
}

/// Writes the vessels of `design` tagged in `tags` (all when empty) as one
/// IGES 5.3 file named `name`, as a B-rep ([`IgesEntities::Brep`]).
///
/// # Errors
///
/// As [`export_step`](super::export_step): an invalid design or options, an
/// unknown tag, a part, opening or trim that cannot be built.
pub fn export_iges(
    design: &Design,
    tags: &[String],
    options: &ExchangeOptions,
    name: &str,
) -> Result<String, ExchangeError> {
    export_iges_as(design, tags, options, IgesEntities::Brep, name)
}

/// [`export_iges`] in the representation `entities`.
///
/// # Errors
///
/// As [`export_iges`].
pub fn export_iges_as(
    design: &Design,
    tags: &[String],
    options: &ExchangeOptions,
    entities: IgesEntities,
    name: &str,
) -> Result<String, ExchangeError> {
    options.validate()?;
    let sources = vessel_sources(design, tags, options.tolerance)?;
    let vessels: Vec<(VesselBrep, Vec<NodeKind>)> = sources
        .par_iter()
        .map(|s| {
            let kinds = s.nodes.iter().map(|n| n.kind).collect();
            vessel_brep_with(s, options.solids).map(|b| (b, kinds))
        })
        .collect::<Result<_, _>>()?;
    write_iges(name, &vessels, options, entities)
}

/// Writes the file: colours, then each vessel's entities and group.
///
/// # Errors
///
/// [`ExchangeError::Geometry`] where a surface or curve cannot be placed in
/// the plant frame.
pub fn write_iges(
    name: &str,
    vessels: &[(VesselBrep, Vec<NodeKind>)],
    options: &ExchangeOptions,
    entities: IgesEntities,
) -> Result<String, ExchangeError> {
    let mut w = IgesWriter::default();
    let colours: Vec<(NodeKind, usize)> = COLOURS
        .iter()
        .map(|(kind, rgb, label)| {
            let mut p = Params::default();
            p.reals(*rgb).string(label);
            let de = w.entity(
                &Entry {
                    kind: 314,
                    form: 0,
                    level: 0,
                    colour: 0,
                    status: status::DEFINITION,
                    label: "COLOUR",
                    subscript: 0,
                },
                &p,
            );
            (*kind, de)
        })
        .collect();
    let mut max_coordinate = 0.0f64;
    for (index, (brep, kinds)) in vessels.iter().enumerate() {
        let level = index + 1;
        let by_node: Vec<usize> = kinds
            .iter()
            .map(|kind| colours.iter().find(|(k, _)| k == kind).map_or(0, |c| c.1))
            .collect();
        let mut vessel = VesselWriter::new(&mut w, brep, level);
        let members = match entities {
            IgesEntities::Brep => brep_entities(&mut vessel, &by_node, options.solids)?,
            IgesEntities::Trimmed => trimmed_faces(&mut vessel, &by_node)?,
        };
        let label = vessel.name(&brep.tag);
        max_coordinate = max_coordinate.max(vessel.extent);
        let mut p = Params::default();
        p.int(members.len() as i64);
        for &m in &members {
            p.ptr(m);
        }
        p.int(0).int(1).ptr(label);
        w.entity(
            &Entry {
                kind: 402,
                form: 7,
                level,
                colour: 0,
                status: status::INDEPENDENT,
                label: "VESSEL",
                subscript: level,
            },
            &p,
        );
    }
    Ok(w.finish(&Global {
        name,
        resolution: options.tolerance,
        max_coordinate,
    }))
}
