//! Constrain stage: write each resolved vessel into its entities — the vessel frame
//! and summary, every part's and nozzle's frame and shape, the nozzle-on-host
//! (and boot-on-course) and note-target relations, and note anchors — each only
//! where the value differs. The vessels are compared with their entities in
//! parallel (a [`Plan`] each); the writes are serial.

use bevy_ecs::component::{Component, Mutable};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::world::World;
use rayon::prelude::*;

use crate::components::{
    Annotates, MountedOn, NoteAnchor, NoteSpec, NozzleSpec, Opening, PartFrame, PartSpan, PartSpec,
    Shape, VesselFrame, VesselSummary,
};
use crate::components::{DirtyParts, PendingResolutions, WorkCounters};
use crate::constraints::{NoteTarget, ResolvedVessel};

/// `value` if it differs from `entity`'s component `T` (or `entity` has none),
/// `None` if they are equal or `entity` does not exist.
fn differs<T: Component + PartialEq>(world: &World, entity: Entity, value: T) -> Option<T> {
    let e = world.get_entity(entity).ok()?;
    (e.get::<T>() != Some(&value)).then_some(value)
}

/// Writes `value` into `entity`'s component `T`, inserting it if absent.
fn put<T: Component<Mutability = Mutable>>(world: &mut World, entity: Entity, value: T) {
    let Ok(mut e) = world.get_entity_mut(entity) else {
        return;
    };
    match e.get_mut::<T>() {
        Some(mut current) => *current = value,
        None => {
            e.insert(value);
        }
    }
}

/// Points an immutable relationship component at a new target.
fn relate<T: Component>(world: &mut World, entity: Entity, value: T) {
    if let Ok(mut e) = world.get_entity_mut(entity) {
        e.insert(value);
    }
}

/// Children of a vessel keyed by kind and id.
struct Lookup<'w> {
    parts: Vec<(&'w str, Entity)>,
    nozzles: Vec<(&'w str, Entity)>,
    notes: Vec<(&'w str, Entity)>,
}

impl<'w> Lookup<'w> {
    fn of(world: &'w World, vessel: Entity) -> Self {
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
                out.parts.push((p.0.id(), c));
            } else if let Some(n) = world.get::<NozzleSpec>(c) {
                out.nozzles.push((&n.0.mark, c));
            } else if let Some(n) = world.get::<NoteSpec>(c) {
                out.notes.push((&n.0.id, c));
            }
        }
        out
    }

    fn find(list: &[(&str, Entity)], id: &str) -> Option<Entity> {
        list.iter().find(|(k, _)| *k == id).map(|(_, e)| *e)
    }
}

/// What a part or nozzle entity's mount relation becomes.
enum Mount {
    /// As it is.
    Keep,
    /// Mounted on another entity (newly, or on another one).
    On(MountedOn),
    /// No longer mounted: the relation and the opening go.
    Off,
}

/// The components of one part or nozzle that differ from the resolution's.
struct Child {
    entity: Entity,
    frame: Option<PartFrame>,
    span: Option<PartSpan>,
    shape: Option<Shape>,
    mount: Mount,
}

/// The components of one vessel's entities that differ from its resolution:
/// worked out in parallel (comparing shapes reads every parameter), written
/// in order by [`write`].
struct Plan {
    vessel: Entity,
    frame: Option<VesselFrame>,
    summary: Option<VesselSummary>,
    children: Vec<Child>,
    notes: Vec<(Entity, Option<NoteAnchor>, Option<Annotates>)>,
}

/// Compares one resolved vessel with its entities.
fn plan(world: &World, vessel: Entity, r: ResolvedVessel) -> Plan {
    let frame = differs(world, vessel, VesselFrame(r.frame));
    let summary = differs(
        world,
        vessel,
        VesselSummary {
            tangent_length: r.tangent_length,
            extent: r.extent,
            max_diameter: r.max_diameter,
        },
    );
    let ids = Lookup::of(world, vessel);
    let hosts: Vec<Option<Entity>> = r
        .parts
        .iter()
        .map(|p| {
            let host = p.host.and_then(|h| r.parts.get(h))?;
            Lookup::find(&ids.parts, &host.id)
        })
        .collect();
    let mut children = Vec::with_capacity(r.parts.len() + r.nozzles.len());
    for (p, host) in r.parts.into_iter().zip(hosts) {
        let Some(e) = Lookup::find(&ids.parts, &p.id) else {
            continue;
        };
        // A part cut into another (a boot into its course) is mounted on it, like a
        // nozzle on its host, so the Geometry stage cuts its opening.
        let mount = match host {
            Some(host) => differs(world, e, MountedOn(host)).map_or(Mount::Keep, Mount::On),
            None if world.get::<MountedOn>(e).is_some() => Mount::Off,
            None => Mount::Keep,
        };
        children.push(Child {
            entity: e,
            frame: differs(world, e, PartFrame(p.frame)),
            span: differs(world, e, PartSpan(p.span.0, p.span.1)),
            shape: differs(world, e, Shape::Part(p.geometry)),
            mount,
        });
    }
    let mut nozzle_entities = Vec::with_capacity(r.nozzles.len());
    for n in r.nozzles {
        let Some(e) = Lookup::find(&ids.nozzles, &n.mark) else {
            continue;
        };
        let host = world
            .get::<NozzleSpec>(e)
            .and_then(|s| Lookup::find(&ids.parts, &s.0.host));
        let mount = host
            .and_then(|host| differs(world, e, MountedOn(host)))
            .map_or(Mount::Keep, Mount::On);
        children.push(Child {
            entity: e,
            frame: differs(world, e, PartFrame(n.frame)),
            span: None,
            shape: differs(world, e, Shape::Nozzle(n.geometry, n.pad)),
            mount,
        });
        nozzle_entities.push(e);
    }
    let mut notes = Vec::with_capacity(r.notes.len());
    for note in r.notes {
        let Some(e) = Lookup::find(&ids.notes, &note.id) else {
            continue;
        };
        let anchor = differs(
            world,
            e,
            NoteAnchor {
                anchor: note.anchor,
                position: note.position,
            },
        );
        let target = world.get::<NoteSpec>(e).map_or("", |s| s.0.target.as_str());
        let target_entity = match note.target {
            NoteTarget::Vessel => Some(vessel),
            NoteTarget::Part(_) => Lookup::find(&ids.parts, target),
            NoteTarget::Nozzle(i) => nozzle_entities.get(i).copied(),
            NoteTarget::Note(_) => Lookup::find(&ids.notes, target),
        };
        let annotates = target_entity
            .filter(|&t| t != e)
            .and_then(|t| differs(world, e, Annotates(t)));
        notes.push((e, anchor, annotates));
    }
    Plan {
        vessel,
        frame,
        summary,
        children,
        notes,
    }
}

/// Writes one vessel's plan, listing what it wrote in `dirty`.
fn write(world: &mut World, plan: Plan, dirty: &mut DirtyParts) {
    let vessel = plan.vessel;
    if let Some(frame) = plan.frame {
        put(world, vessel, frame);
        dirty.vessel_frames.push(vessel);
    }
    if let Some(summary) = plan.summary {
        put(world, vessel, summary);
    }
    for c in plan.children {
        let e = c.entity;
        if let Some(frame) = c.frame {
            put(world, e, frame);
            dirty.frames.push(e);
        }
        if let Some(span) = c.span {
            put(world, e, span);
        }
        if let Some(shape) = c.shape {
            put(world, e, shape);
            dirty.shapes.push(e);
        }
        match c.mount {
            Mount::Keep => {}
            Mount::On(m) => {
                relate(world, e, m);
                dirty.mounts.push(e);
            }
            Mount::Off => {
                world.entity_mut(e).remove::<(MountedOn, Opening)>();
            }
        }
    }
    for (e, anchor, annotates) in plan.notes {
        if let Some(anchor) = anchor {
            put(world, e, anchor);
        }
        if let Some(a) = annotates {
            relate(world, e, a);
        }
    }
}

/// Writes every pending resolution into the world, listing what it wrote in
/// [`DirtyParts`]. The vessels are compared with their entities in parallel;
/// only what differs is written, in order.
pub fn apply_resolutions(world: &mut World) {
    let pending = std::mem::take(&mut world.resource_mut::<PendingResolutions>().0);
    let plans: Vec<Plan> = {
        let world = &*world;
        pending
            .into_par_iter()
            .map(|(vessel, resolved)| plan(world, vessel, resolved))
            .collect()
    };
    // Taken out while the entities are written, put back after.
    let mut dirty = std::mem::take(&mut *world.resource_mut::<DirtyParts>());
    let before = dirty.frames.len();
    for plan in plans {
        write(world, plan, &mut dirty);
    }
    let frames = (dirty.frames.len() - before) as u64;
    *world.resource_mut::<DirtyParts>() = dirty;
    world.resource_mut::<WorkCounters>().frames_updated += frames;
}
