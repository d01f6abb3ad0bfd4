//! Constrain stage: write each resolved vessel into its entities — the vessel frame
//! and summary, every part's and nozzle's frame and shape, the nozzle-on-host
//! (and boot-on-course) and note-target relations, and note anchors — each only where the value differs.

use bevy_ecs::change_detection::DetectChangesMut;
use bevy_ecs::component::{Component, Mutable};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::world::World;

use super::{DirtyParts, PendingResolutions, WorkCounters};
use crate::components::{
    Annotates, MountedOn, NoteAnchor, NoteSpec, NozzleSpec, Opening, PartFrame, PartSpan, PartSpec,
    Shape, VesselFrame, VesselSummary,
};
use crate::constraints::{NoteTarget, ResolvedVessel};

/// Writes `value` into `entity`'s component `T` if it differs (inserting it if
/// absent); returns whether anything was written.
fn put<T: Component<Mutability = Mutable> + PartialEq>(
    world: &mut World,
    entity: Entity,
    value: T,
) -> bool {
    let Ok(mut e) = world.get_entity_mut(entity) else {
        return false;
    };
    match e.get_mut::<T>() {
        Some(mut current) => current.set_if_neq(value),
        None => {
            e.insert(value);
            true
        }
    }
}

/// Points an immutable relationship component at a new target if it differs;
/// returns whether anything was written.
fn relate<T: Component + PartialEq>(world: &mut World, entity: Entity, value: T) -> bool {
    if world.get::<T>(entity) != Some(&value)
        && let Ok(mut e) = world.get_entity_mut(entity)
    {
        e.insert(value);
        return true;
    }
    false
}

/// Children of a vessel keyed by kind and id.
struct Lookup {
    parts: Vec<(String, Entity)>,
    nozzles: Vec<(String, Entity)>,
    notes: Vec<(String, Entity)>,
}

impl Lookup {
    fn of(world: &World, vessel: Entity) -> Self {
        let mut out = Lookup {
            parts: vec![],
            nozzles: vec![],
            notes: vec![],
        };
        let Some(children) = world.get::<Children>(vessel) else {
            return out;
        };
        for &c in children {
            if let Some(p) = world.get::<PartSpec>(c) {
                out.parts.push((p.0.id().to_string(), c));
            } else if let Some(n) = world.get::<NozzleSpec>(c) {
                out.nozzles.push((n.0.mark.clone(), c));
            } else if let Some(n) = world.get::<NoteSpec>(c) {
                out.notes.push((n.0.id.clone(), c));
            }
        }
        out
    }

    fn find(list: &[(String, Entity)], id: &str) -> Option<Entity> {
        list.iter().find(|(k, _)| k == id).map(|(_, e)| *e)
    }
}

/// Applies one resolved vessel, listing what it wrote in `dirty`.
fn apply(world: &mut World, vessel: Entity, r: ResolvedVessel, dirty: &mut DirtyParts) {
    if put(world, vessel, VesselFrame(r.frame)) {
        dirty.vessel_frames.push(vessel);
    }
    put(
        world,
        vessel,
        VesselSummary {
            tangent_length: r.tangent_length,
            extent: r.extent,
            max_diameter: r.max_diameter,
        },
    );
    let ids = Lookup::of(world, vessel);
    let hosts: Vec<Option<String>> = r
        .parts
        .iter()
        .map(|p| p.host.and_then(|h| r.parts.get(h)).map(|h| h.id.clone()))
        .collect();
    for (p, host_id) in r.parts.into_iter().zip(hosts) {
        let Some(e) = Lookup::find(&ids.parts, &p.id) else {
            continue;
        };
        if put(world, e, PartFrame(p.frame)) {
            dirty.frames.push(e);
        }
        put(world, e, PartSpan(p.span.0, p.span.1));
        if put(world, e, Shape::Part(p.geometry)) {
            dirty.shapes.push(e);
        }
        // A part cut into another (a boot into its course) is mounted on it, like a
        // nozzle on its host, so the Geometry stage cuts its opening.
        match host_id.and_then(|h| Lookup::find(&ids.parts, &h)) {
            Some(host) => {
                if relate(world, e, MountedOn(host)) {
                    dirty.mounts.push(e);
                }
            }
            None => {
                if world.get::<MountedOn>(e).is_some() {
                    world.entity_mut(e).remove::<(MountedOn, Opening)>();
                }
            }
        }
    }
    let mut nozzle_entities = Vec::with_capacity(r.nozzles.len());
    for n in r.nozzles {
        let Some(e) = Lookup::find(&ids.nozzles, &n.mark) else {
            continue;
        };
        if put(world, e, PartFrame(n.frame)) {
            dirty.frames.push(e);
        }
        if put(world, e, Shape::Nozzle(n.geometry, n.pad)) {
            dirty.shapes.push(e);
        }
        let host_id = world
            .get::<NozzleSpec>(e)
            .map(|s| s.0.host.clone())
            .unwrap_or_default();
        if let Some(host) = Lookup::find(&ids.parts, &host_id)
            && relate(world, e, MountedOn(host))
        {
            dirty.mounts.push(e);
        }
        nozzle_entities.push(e);
    }
    for note in r.notes {
        let Some(e) = Lookup::find(&ids.notes, &note.id) else {
            continue;
        };
        put(
            world,
            e,
            NoteAnchor {
                anchor: note.anchor,
                position: note.position,
            },
        );
        let target = world
            .get::<NoteSpec>(e)
            .map(|s| s.0.target.clone())
            .unwrap_or_default();
        let target_entity = match note.target {
            NoteTarget::Vessel => Some(vessel),
            NoteTarget::Part(_) => Lookup::find(&ids.parts, &target),
            NoteTarget::Nozzle(i) => nozzle_entities.get(i).copied(),
            NoteTarget::Note(_) => Lookup::find(&ids.notes, &target),
        };
        if let Some(t) = target_entity.filter(|&t| t != e) {
            relate(world, e, Annotates(t));
        }
    }
}

/// Writes every pending resolution into the world, listing what it wrote in
/// [`DirtyParts`].
pub fn apply_resolutions(world: &mut World) {
    let pending = std::mem::take(&mut world.resource_mut::<PendingResolutions>().0);
    // Taken out while the entities are written, put back after.
    let mut dirty = std::mem::take(&mut *world.resource_mut::<DirtyParts>());
    let before = dirty.frames.len();
    for (vessel, resolved) in pending {
        apply(world, vessel, resolved, &mut dirty);
    }
    let frames = (dirty.frames.len() - before) as u64;
    *world.resource_mut::<DirtyParts>() = dirty;
    world.resource_mut::<WorkCounters>().frames_updated += frames;
}
