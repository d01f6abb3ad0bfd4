//! What a sheet is drawn from, read out of the model: the vessel's design, its four
//! views (assembled from the per-entity cache the Project stage keeps), its
//! resolved figures (spans, nozzle frames, note anchors) and its report figures.

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::world::World;
use glam::{DAffine3, DVec3};

use super::DrawingError;
use crate::components::{
    DesignOrder, EntityViews, NoteAnchor, NoteSpec, NozzleSpec, OperatingSpec, PartFrame, PartSpan,
    PartSpec, Shape, VesselFrame, VesselSpec, VesselSummary, VesselViews,
};
use crate::constraints::PartGeometry;
use crate::design::{NozzleDesign, PartDesign, VesselDesign, VesselKind};
use crate::model::Model;
use crate::parts::Nozzle;
use crate::project::{EntityInput, Projection, View, ViewKind, ViewSettings};
use crate::systems::entity_input;

/// A part as the sheet needs it.
#[derive(Clone, Debug)]
pub struct PartData {
    /// Its parameters.
    pub design: PartDesign,
    /// Axial extent in the vessel frame, mm.
    pub span: (f64, f64),
    /// Part → vessel frame.
    pub frame: DAffine3,
    /// Resolved parameters.
    pub geometry: PartGeometry,
}

/// A nozzle as the sheet needs it.
#[derive(Clone, Debug)]
pub struct NozzleData {
    /// Its parameters.
    pub design: NozzleDesign,
    /// Nozzle → vessel frame (axis +Z, neck start at the origin).
    pub frame: DAffine3,
    /// The resolved nozzle (projection, flange).
    pub geometry: Nozzle,
}

/// A note with its resolved anchor and text position, vessel frame.
#[derive(Clone, Debug)]
pub struct NoteData {
    /// Id.
    pub id: String,
    /// Text.
    pub text: String,
    /// Target's anchor point.
    pub anchor: DVec3,
    /// Text position.
    pub position: DVec3,
}

/// Everything a sheet of one vessel is drawn from.
#[derive(Clone, Debug)]
pub struct VesselData {
    /// The vessel's design (canonical, mm).
    pub design: VesselDesign,
    /// Vessel → plant frame.
    pub frame: DAffine3,
    /// Resolved figures.
    pub summary: VesselSummary,
    /// Parts in design order (resolved ones).
    pub parts: Vec<PartData>,
    /// Nozzles in design order (resolved ones).
    pub nozzles: Vec<NozzleData>,
    /// Notes in design order.
    pub notes: Vec<NoteData>,
    /// The four views, in [`ViewKind::ALL`](crate::project::ViewKind::ALL) order.
    pub views: [View; 4],
}

/// Children of `vessel` with component `T`, in design order.
fn ordered<T: bevy_ecs::component::Component>(world: &World, vessel: Entity) -> Vec<Entity> {
    let mut out: Vec<(DesignOrder, Entity)> = world
        .get::<Children>(vessel)
        .map(|c| {
            c.iter()
                .copied()
                .filter(|&e| world.get::<T>(e).is_some())
                .filter_map(|e| Some((*world.get::<DesignOrder>(e)?, e)))
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out.into_iter().map(|(_, e)| e).collect()
}

/// The vessel entity with `tag`.
fn find_vessel(world: &World, tag: &str) -> Option<Entity> {
    let mut q = world.try_query::<(Entity, &VesselSpec)>()?;
    q.iter(world).find(|(_, s)| s.tag == tag).map(|(e, _)| e)
}

/// The four views of vessel `tag`, as of the model's last update.
pub fn vessel_views(model: &Model, tag: &str) -> Result<[View; 4], DrawingError> {
    let world = model.world();
    let vessel = find_vessel(world, tag).ok_or_else(|| DrawingError::UnknownVessel {
        tag: tag.to_string(),
    })?;
    views_of(world, vessel, tag)
}

fn views_of(world: &World, vessel: Entity, tag: &str) -> Result<[View; 4], DrawingError> {
    let state = world
        .get::<VesselViews>(vessel)
        .ok_or_else(|| DrawingError::NotBuilt {
            tag: tag.to_string(),
        })?;
    let members: Vec<Entity> = ordered::<PartSpec>(world, vessel)
        .into_iter()
        .chain(ordered::<NozzleSpec>(world, vessel))
        .collect();
    Ok(std::array::from_fn(|k| View {
        projection: state.projections[k],
        entities: members
            .iter()
            .filter_map(|&e| world.get::<EntityViews>(e).map(|v| Arc::clone(&v.0[k])))
            .collect(),
    }))
}

/// Everything the sheet of vessel `tag` needs, as of the model's last update.
pub fn vessel_data(model: &Model, tag: &str) -> Result<VesselData, DrawingError> {
    let world = model.world();
    let vessel = find_vessel(world, tag).ok_or_else(|| DrawingError::UnknownVessel {
        tag: tag.to_string(),
    })?;
    let not_built = || DrawingError::NotBuilt {
        tag: tag.to_string(),
    };
    let spec = world.get::<VesselSpec>(vessel).ok_or_else(not_built)?;
    let frame = world.get::<VesselFrame>(vessel).ok_or_else(not_built)?.0;
    let summary = *world.get::<VesselSummary>(vessel).ok_or_else(not_built)?;
    let views = views_of(world, vessel, tag)?;
    let part_entities = ordered::<PartSpec>(world, vessel);
    let nozzle_entities = ordered::<NozzleSpec>(world, vessel);
    let note_entities = ordered::<NoteSpec>(world, vessel);
    let parts = part_entities
        .iter()
        .filter_map(|&e| {
            Some(PartData {
                design: world.get::<PartSpec>(e)?.0.clone(),
                span: world.get::<PartSpan>(e).map(|s| (s.0, s.1))?,
                frame: world.get::<PartFrame>(e)?.0,
                geometry: match world.get::<Shape>(e)? {
                    Shape::Part(g) => g.clone(),
                    Shape::Nozzle(..) => return None,
                },
            })
        })
        .collect();
    let nozzles = nozzle_entities
        .iter()
        .filter_map(|&e| {
            let Some(Shape::Nozzle(geometry, _)) = world.get::<Shape>(e) else {
                return None;
            };
            Some(NozzleData {
                design: world.get::<NozzleSpec>(e)?.0.clone(),
                frame: world.get::<PartFrame>(e)?.0,
                geometry: *geometry,
            })
        })
        .collect();
    let notes = note_entities
        .iter()
        .filter_map(|&e| {
            let n = &world.get::<NoteSpec>(e)?.0;
            let a = world.get::<NoteAnchor>(e)?;
            Some(NoteData {
                id: n.id.clone(),
                text: n.text.clone(),
                anchor: a.anchor,
                position: a.position,
            })
        })
        .collect();
    let design = VesselDesign {
        tag: spec.tag.clone(),
        kind: spec.kind,
        placement: spec.placement,
        design: spec.design.clone(),
        drawing: spec.drawing.clone(),
        operating: world.get::<OperatingSpec>(vessel).and_then(|o| o.0),
        parts: part_entities
            .iter()
            .filter_map(|&e| Some(world.get::<PartSpec>(e)?.0.clone()))
            .collect(),
        nozzles: nozzle_entities
            .iter()
            .filter_map(|&e| Some(world.get::<NozzleSpec>(e)?.0.clone()))
            .collect(),
        notes: note_entities
            .iter()
            .filter_map(|&e| Some(world.get::<NoteSpec>(e)?.0.clone()))
            .collect(),
    };
    Ok(VesselData {
        design,
        frame,
        summary,
        parts,
        nozzles,
        notes,
        views,
    })
}

impl VesselData {
    /// Whether the vessel's axis is vertical.
    pub fn is_vertical(&self) -> bool {
        self.design.kind != VesselKind::Horizontal
    }

    /// The view of `kind`.
    pub fn view(&self, kind: ViewKind) -> &View {
        &self.views[ViewKind::ALL.iter().position(|&k| k == kind).unwrap_or(0)]
    }
}

/// The Project stage's inputs for vessel `tag` (parts then nozzles in design
/// order), its projections and sampling: for rebuilding its views outside the
/// schedule (benchmarks, tools).
pub fn view_inputs(
    model: &Model,
    tag: &str,
) -> Result<(Vec<EntityInput>, [Projection; 4], ViewSettings), DrawingError> {
    let world = model.world();
    let vessel = find_vessel(world, tag).ok_or_else(|| DrawingError::UnknownVessel {
        tag: tag.to_string(),
    })?;
    let state = world
        .get::<VesselViews>(vessel)
        .ok_or_else(|| DrawingError::NotBuilt {
            tag: tag.to_string(),
        })?;
    let inputs = ordered::<PartSpec>(world, vessel)
        .into_iter()
        .chain(ordered::<NozzleSpec>(world, vessel))
        .filter_map(|e| entity_input(world, tag, e))
        .collect();
    Ok((inputs, state.projections, state.settings))
}
