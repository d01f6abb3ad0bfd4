//! Writing a checked edit into the world: spawn, update (only where different) or
//! despawn the entities of each touched vessel, matching children by id.

use bevy_ecs::change_detection::DetectChangesMut;
use bevy_ecs::component::{Component, Mutable};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::world::World;

use super::staging::{Staged, StagedVessel};
use super::{VesselIndex, read};
use crate::components::{DesignOrder, NoteSpec, NozzleSpec, OperatingSpec, PartSpec, VesselSpec};
use crate::design::VesselDesign;
use crate::systems::{ChangeLog, CheckedResolutions, EditedVessels};

/// Sets a component if it differs; returns whether it was written.
fn put<T: Component<Mutability = Mutable> + PartialEq>(
    world: &mut World,
    entity: Entity,
    value: T,
) -> bool {
    match world.get_mut::<T>(entity) {
        Some(mut current) => current.set_if_neq(value),
        None => {
            world.entity_mut(entity).insert(value);
            true
        }
    }
}

/// Matches `wanted` children (by id) to `existing` ones, updating, spawning and
/// despawning; returns whether the set of children changed, the removed ids, and
/// whether any child's parameters were written.
fn sync_children<T: Component<Mutability = Mutable> + PartialEq>(
    world: &mut World,
    vessel: Entity,
    existing: Vec<(Entity, String)>,
    wanted: Vec<(String, T)>,
) -> (bool, Vec<String>, bool) {
    let mut pool = existing;
    let mut structure = false;
    let mut written = false;
    for (k, (id, spec)) in wanted.into_iter().enumerate() {
        let order = DesignOrder(k as u32);
        match pool.iter().position(|(_, i)| *i == id) {
            Some(at) => {
                let (e, _) = pool.swap_remove(at);
                written |= put(world, e, spec);
                put(world, e, order);
            }
            None => {
                world.spawn((spec, order, ChildOf(vessel)));
                structure = true;
            }
        }
    }
    let mut removed = Vec::new();
    for (e, id) in pool {
        world.despawn(e);
        removed.push(id);
        structure = true;
    }
    (structure, removed, written)
}

/// Writes one vessel's design into its entities.
fn put_vessel(world: &mut World, design: VesselDesign, order: u32) -> Entity {
    let existing = world.resource::<VesselIndex>().0.get(&design.tag).copied();
    let spec = VesselSpec {
        tag: design.tag.clone(),
        kind: design.kind,
        placement: design.placement,
        design: design.design,
        drawing: design.drawing,
    };
    let operating = OperatingSpec(design.operating);
    let mut edited = existing.is_none();
    let entity = match existing {
        Some(e) => {
            edited |= put(world, e, spec);
            put(world, e, DesignOrder(order));
            put(world, e, operating);
            e
        }
        None => {
            let e = world.spawn((spec, DesignOrder(order), operating)).id();
            world
                .resource_mut::<VesselIndex>()
                .0
                .insert(design.tag.clone(), e);
            e
        }
    };
    let parts = read::parts(world, entity)
        .into_iter()
        .map(|(e, p)| (e, p.0.id().to_string()))
        .collect();
    let nozzles = read::nozzles(world, entity)
        .into_iter()
        .map(|(e, n)| (e, n.0.mark))
        .collect();
    let notes = read::notes(world, entity)
        .into_iter()
        .map(|(e, n)| (e, n.0.id))
        .collect();
    let (a, ra, wa) = sync_children(
        world,
        entity,
        parts,
        design
            .parts
            .into_iter()
            .map(|p| (p.id().to_string(), PartSpec(p)))
            .collect(),
    );
    let (b, rb, wb) = sync_children(
        world,
        entity,
        nozzles,
        design
            .nozzles
            .into_iter()
            .map(|n| (n.mark.clone(), NozzleSpec(n)))
            .collect(),
    );
    let (c, rc, wc) = sync_children(
        world,
        entity,
        notes,
        design
            .notes
            .into_iter()
            .map(|n| (n.id.clone(), NoteSpec(n)))
            .collect(),
    );
    let mut log = world.resource_mut::<ChangeLog>();
    for id in ra.into_iter().chain(rb).chain(rc) {
        log.removed.insert(format!("{}/{id}", design.tag));
    }
    if a || b || c {
        // Added or removed children: the vessel must be resolved again.
        if let Some(mut s) = world.get_mut::<VesselSpec>(entity) {
            s.set_changed();
        }
    }
    if edited || a || b || c || wa || wb || wc {
        world.resource_mut::<EditedVessels>().0.push(entity);
    }
    entity
}

/// Applies a checked edit to the world.
pub(crate) fn commit(world: &mut World, staged: Staged) {
    for s in staged.0 {
        match s {
            StagedVessel::Put {
                design,
                order,
                resolved,
            } => {
                // What the Validate stage will read back: the design without its
                // operating data (kept in its own component).
                let checked = VesselDesign {
                    operating: None,
                    ..(*design).clone()
                };
                let entity = put_vessel(world, *design, order);
                world
                    .resource_mut::<CheckedResolutions>()
                    .0
                    .insert(entity, (order, checked, *resolved));
            }
            StagedVessel::Remove { tag } => {
                if let Some(e) = world.resource_mut::<VesselIndex>().0.remove(&tag) {
                    let children: Vec<String> = read::parts(world, e)
                        .into_iter()
                        .map(|(_, p)| p.0.id().to_string())
                        .chain(read::nozzles(world, e).into_iter().map(|(_, n)| n.0.mark))
                        .collect();
                    world.despawn(e);
                    let mut log = world.resource_mut::<ChangeLog>();
                    log.removed.insert(tag.clone());
                    for id in children {
                        log.removed.insert(format!("{tag}/{id}"));
                    }
                }
            }
        }
    }
}
