//! Writing a checked edit into the world: spawn, update (only where different) or
//! despawn the entities of each touched vessel, matching children by id.

use bevy_ecs::change_detection::DetectChangesMut;
use bevy_ecs::component::{Component, Mutable};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::world::World;

use super::read;
use super::staging::{Staged, StagedVessel};
use crate::components::VesselIndex;
use crate::components::{ChangeLog, CheckedResolutions, EditedVessels};
use crate::components::{DesignOrder, NoteSpec, NozzleSpec, OperatingSpec, PartSpec, VesselSpec};
use crate::design::{PartDesign, VesselDesign};

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

/// Matches the `wanted` children's designs (by `id`) to the child entities
/// of `vessel` carrying `T`, updating (a design cloned only where it differs
/// from what `inner` reads off the entity's component), spawning (`wrap`) and
/// despawning; returns whether the set of children changed, the removed ids,
/// and whether any child's parameters were written.
fn sync_children<T, D>(
    world: &mut World,
    vessel: Entity,
    wanted: &[D],
    id: impl Fn(&D) -> &str,
    inner: impl Fn(&T) -> &D,
    wrap: impl Fn(D) -> T,
) -> (bool, Vec<String>, bool)
where
    T: Component<Mutability = Mutable>,
    D: PartialEq + Clone,
{
    let existing = read::children_with::<T>(world, vessel);
    // Read first: each wanted child's entity (most often the one at its own
    // place) and whether it already holds the design.
    let mut taken = vec![false; existing.len()];
    let mut plan: Vec<Option<(Entity, bool)>> = Vec::with_capacity(wanted.len());
    {
        let world = &*world;
        let held = |j: usize| world.get::<T>(existing[j]).map(&inner);
        for (k, design) in wanted.iter().enumerate() {
            let matches = |j: usize| !taken[j] && held(j).is_some_and(|h| id(h) == id(design));
            let at = if k < existing.len() && matches(k) {
                Some(k)
            } else {
                (0..existing.len()).find(|&j| matches(j))
            };
            plan.push(at.map(|j| {
                taken[j] = true;
                (existing[j], held(j) == Some(design))
            }));
        }
    }
    let gone: Vec<(Entity, String)> = existing
        .iter()
        .zip(&taken)
        .filter(|(_, taken)| !**taken)
        .map(|(&e, _)| {
            let id = world
                .get::<T>(e)
                .map_or(String::new(), |t| id(inner(t)).to_string());
            (e, id)
        })
        .collect();
    let mut structure = false;
    let mut written = false;
    for (k, (design, at)) in wanted.iter().zip(plan).enumerate() {
        let order = DesignOrder(k as u32);
        match at {
            Some((e, same)) => {
                if !same && let Some(mut held) = world.get_mut::<T>(e) {
                    *held = wrap(design.clone());
                    written = true;
                }
                put(world, e, order);
            }
            None => {
                world.spawn((wrap(design.clone()), order, ChildOf(vessel)));
                structure = true;
            }
        }
    }
    let mut removed = Vec::new();
    for (e, id) in gone {
        world.despawn(e);
        removed.push(id);
        structure = true;
    }
    (structure, removed, written)
}

/// Writes one vessel's design into its entities, cloning only what differs
/// from what they hold.
fn put_vessel(world: &mut World, design: &VesselDesign, order: u32) -> Entity {
    let existing = world.resource::<VesselIndex>().0.get(&design.tag).copied();
    let spec = || VesselSpec {
        tag: design.tag.clone(),
        kind: design.kind,
        placement: design.placement,
        design: design.design.clone(),
        drawing: design.drawing.clone(),
    };
    let operating = OperatingSpec(design.operating);
    let mut edited = existing.is_none();
    let entity = match existing {
        Some(e) => {
            // Built and written only when it differs.
            if !world.get::<VesselSpec>(e).is_some_and(|s| s.holds(design)) {
                edited |= put(world, e, spec());
            }
            put(world, e, DesignOrder(order));
            put(world, e, operating);
            e
        }
        None => {
            let e = world.spawn((spec(), DesignOrder(order), operating)).id();
            world
                .resource_mut::<VesselIndex>()
                .0
                .insert(design.tag.clone(), e);
            e
        }
    };
    let (a, ra, wa) = sync_children(
        world,
        entity,
        &design.parts,
        PartDesign::id,
        |p: &PartSpec| &p.0,
        PartSpec,
    );
    let (b, rb, wb) = sync_children(
        world,
        entity,
        &design.nozzles,
        |n| n.mark.as_str(),
        |n: &NozzleSpec| &n.0,
        NozzleSpec,
    );
    let (c, rc, wc) = sync_children(
        world,
        entity,
        &design.notes,
        |n| n.id.as_str(),
        |n: &NoteSpec| &n.0,
        NoteSpec,
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
                let entity = put_vessel(world, &design, order);
                // What the Validate stage will read back: the design without its
                // operating data (kept in its own component).
                let checked = VesselDesign {
                    operating: None,
                    ..*design
                };
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
