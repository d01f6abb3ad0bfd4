//! Reading the world back: a vessel's design (for edits and saving), the whole
//! design, and the exporters' scene.

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::world::World;

use crate::components::VesselIndex;
use crate::components::{
    DesignOrder, MountedOn, NoteSpec, NozzleCalculation, NozzleSpec, OperatingSpec, PadPatch,
    PartCalculation, PartFrame, PartSpan, PartSpec, PatchMesh, PatchSurface, Patches, Shape,
    VesselCalculation, VesselFrame, VesselSpec, VesselSummary, same_in_order,
};
use crate::constraints::{ResolvedNozzle, ResolvedPart, ResolvedVessel};
use crate::design::{Design, FORMAT, Units, VesselDesign};
use crate::export::{
    Scene, SceneNode, SceneNodeKind, ScenePatch, SceneVessel, nozzle_extras, part_extras,
    patch_name, vessel_extras,
};

/// Children of `vessel` that carry component `T`, in design order (nothing
/// is cloned).
pub(crate) fn children_with<T: bevy_ecs::component::Component>(
    world: &World,
    vessel: Entity,
) -> Vec<Entity> {
    let mut out: Vec<(DesignOrder, Entity)> = world
        .get::<Children>(vessel)
        .map(|c| {
            c.iter()
                .filter(|&&e| world.get::<T>(e).is_some())
                .filter_map(|&e| Some((*world.get::<DesignOrder>(e)?, e)))
                .collect()
        })
        .unwrap_or_default();
    out.sort_by_key(|(o, _)| *o);
    out.into_iter().map(|(_, e)| e).collect()
}

/// Children of `vessel` that carry component `T`, in design order, with it.
fn ordered<T: bevy_ecs::component::Component + Clone>(
    world: &World,
    vessel: Entity,
) -> Vec<(Entity, T)> {
    children_with::<T>(world, vessel)
        .into_iter()
        .filter_map(|e| Some((e, world.get::<T>(e)?.clone())))
        .collect()
}

/// Part entities of a vessel in design order.
pub(crate) fn parts(world: &World, vessel: Entity) -> Vec<(Entity, PartSpec)> {
    ordered(world, vessel)
}

/// Nozzle entities of a vessel in design order.
pub(crate) fn nozzles(world: &World, vessel: Entity) -> Vec<(Entity, NozzleSpec)> {
    ordered(world, vessel)
}

/// Note entities of a vessel in design order.
pub(crate) fn notes(world: &World, vessel: Entity) -> Vec<(Entity, NoteSpec)> {
    ordered(world, vessel)
}

/// The design of one vessel entity (`None` if it is not a vessel).
pub(crate) fn vessel(world: &World, entity: Entity) -> Option<VesselDesign> {
    let spec = world.get::<VesselSpec>(entity)?.clone();
    Some(VesselDesign {
        tag: spec.tag,
        kind: spec.kind,
        placement: spec.placement,
        design: spec.design,
        drawing: spec.drawing,
        parts: parts(world, entity).into_iter().map(|(_, p)| p.0).collect(),
        nozzles: nozzles(world, entity)
            .into_iter()
            .map(|(_, n)| n.0)
            .collect(),
        notes: notes(world, entity).into_iter().map(|(_, n)| n.0).collect(),
        operating: world.get::<OperatingSpec>(entity).and_then(|o| o.0),
    })
}

/// Whether `entity` holds exactly `design`: what [`vessel`] would read back
/// equals it, compared in place (nothing is cloned).
pub(crate) fn holds(world: &World, entity: Entity, design: &VesselDesign) -> bool {
    world
        .get::<VesselSpec>(entity)
        .is_some_and(|spec| spec.holds(design))
        && world.get::<OperatingSpec>(entity).and_then(|o| o.0) == design.operating
        && same_children(world, entity, &design.parts, |p: &PartSpec| &p.0)
        && same_children(world, entity, &design.nozzles, |n: &NozzleSpec| &n.0)
        && same_children(world, entity, &design.notes, |n: &NoteSpec| &n.0)
}

/// Whether the children of `vessel` carrying `T`, in design order, hold
/// exactly `wanted` (as `inner` reads them).
fn same_children<T: bevy_ecs::component::Component, D: PartialEq>(
    world: &World,
    vessel: Entity,
    wanted: &[D],
    inner: impl Fn(&T) -> &D,
) -> bool {
    let kids: &[Entity] = world.get::<Children>(vessel).map_or(&[], |c| c);
    let found = kids
        .iter()
        .filter_map(|&e| Some((inner(world.get::<T>(e)?), *world.get::<DesignOrder>(e)?)));
    same_in_order(found, wanted)
}

/// A vessel's calculation from its calculation components, in design order.
pub(crate) fn calculation(world: &World, entity: Entity) -> Option<crate::calc::Calculation> {
    let vessel = world.get::<VesselCalculation>(entity)?.calc.clone();
    let parts = children_with::<PartCalculation>(world, entity)
        .into_iter()
        .filter_map(|e| world.get::<PartCalculation>(e)?.0.clone().ok())
        .collect();
    let nozzles = children_with::<NozzleCalculation>(world, entity)
        .into_iter()
        .filter_map(|e| world.get::<NozzleCalculation>(e)?.0.clone().ok())
        .collect();
    Some(crate::calc::Calculation {
        vessel,
        parts,
        nozzles,
    })
}

/// Vessel entities in design order.
pub(crate) fn vessels(world: &World) -> Vec<Entity> {
    let mut v: Vec<(u32, Entity)> = world
        .resource::<VesselIndex>()
        .0
        .values()
        .map(|&e| (world.get::<DesignOrder>(e).map_or(u32::MAX, |o| o.0), e))
        .collect();
    v.sort();
    v.into_iter().map(|(_, e)| e).collect()
}

/// The whole design.
pub(crate) fn design(world: &World) -> Design {
    Design {
        format: FORMAT.to_string(),
        units: Units::Mm,
        vessels: vessels(world)
            .into_iter()
            .filter_map(|e| vessel(world, e))
            .collect(),
    }
}

/// The vessel as resolved by the last update, rebuilt from its derived components
/// (parts and nozzles that have not been resolved yet are left out).
fn resolved(world: &World, entity: Entity) -> Option<(VesselDesign, ResolvedVessel)> {
    let design = vessel(world, entity)?;
    let frame = world.get::<VesselFrame>(entity)?.0;
    let summary = *world.get::<VesselSummary>(entity)?;
    let part_entities = parts(world, entity);
    let mut resolved_parts = Vec::new();
    for (e, spec) in &part_entities {
        if let (Some(f), Some(span), Some(Shape::Part(g))) = (
            world.get::<PartFrame>(*e),
            world.get::<PartSpan>(*e),
            world.get::<Shape>(*e),
        ) {
            resolved_parts.push(ResolvedPart {
                id: spec.0.id().to_string(),
                frame: f.0,
                geometry: g.clone(),
                span: (span.0, span.1),
                host: world
                    .get::<MountedOn>(*e)
                    .and_then(|m| part_entities.iter().position(|(p, _)| *p == m.0)),
            });
        }
    }
    let mut resolved_nozzles = Vec::new();
    for (e, spec) in nozzles(world, entity) {
        if let (Some(f), Some(Shape::Nozzle(n, pad))) =
            (world.get::<PartFrame>(e), world.get::<Shape>(e))
        {
            let host = part_entities
                .iter()
                .position(|(_, p)| p.0.id() == spec.0.host)
                .unwrap_or(0);
            resolved_nozzles.push(ResolvedNozzle {
                mark: spec.0.mark.clone(),
                host,
                frame: f.0,
                geometry: *n,
                pad: *pad,
            });
        }
    }
    let resolved = ResolvedVessel {
        tag: design.tag.clone(),
        kind: design.kind,
        frame,
        parts: resolved_parts,
        nozzles: resolved_nozzles,
        notes: Vec::new(),
        tangent_length: summary.tangent_length,
        extent: summary.extent,
        max_diameter: summary.max_diameter,
        operating: None,
    };
    Some((design, resolved))
}

/// The meshed patches of a part or nozzle entity, in build order (a nozzle's pad
/// last).
fn scene_patches(world: &World, entity: Entity) -> Vec<ScenePatch> {
    let Some(patches) = world.get::<Patches>(entity) else {
        return Vec::new();
    };
    let pad = world.get::<PadPatch>(entity).map(PadPatch::entity);
    patches
        .entities()
        .iter()
        .chain(pad.as_ref())
        .filter_map(|&p| {
            let surface = world.get::<PatchSurface>(p)?;
            let mesh = world.get::<PatchMesh>(p)?;
            Some(ScenePatch {
                name: patch_name(&surface.0),
                mesh: mesh.0.clone(),
            })
        })
        .collect()
}

/// The exporters' scene of the whole plant, in design order.
pub(crate) fn scene(world: &World) -> Scene {
    scene_of(world, vessels(world))
}

/// The exporters' scene of the vessel `entities`, in the order given.
pub(crate) fn scene_of(world: &World, entities: Vec<Entity>) -> Scene {
    let mut out = Scene::default();
    for entity in entities {
        let Some((design, resolved)) = resolved(world, entity) else {
            continue;
        };
        let mut nodes = Vec::new();
        let part_entities = parts(world, entity);
        for part in &resolved.parts {
            let Some((e, spec)) = part_entities.iter().find(|(_, s)| s.0.id() == part.id) else {
                continue;
            };
            nodes.push(SceneNode {
                id: part.id.clone(),
                kind: SceneNodeKind::Part,
                frame: part.frame,
                extras: part_extras(&spec.0, part),
                patches: scene_patches(world, *e),
            });
        }
        let nozzle_entities = nozzles(world, entity);
        for nozzle in &resolved.nozzles {
            let Some((e, spec)) = nozzle_entities
                .iter()
                .find(|(_, s)| s.0.mark == nozzle.mark)
            else {
                continue;
            };
            nodes.push(SceneNode {
                id: nozzle.mark.clone(),
                kind: SceneNodeKind::Nozzle,
                frame: nozzle.frame,
                extras: nozzle_extras(&spec.0, nozzle),
                patches: scene_patches(world, *e),
            });
        }
        out.vessels.push(SceneVessel {
            tag: resolved.tag.clone(),
            frame: resolved.frame,
            extras: vessel_extras(&design, &resolved),
            nodes,
        });
    }
    out
}
