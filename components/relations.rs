//! Relations between entities, as bevy_ecs relationships (the target side is kept
//! by bevy's hooks): a nozzle is mounted on a host part, a note annotates a target,
//! a patch belongs to a part or nozzle. Parts, nozzles and notes are `ChildOf`
//! their vessel (bevy's own hierarchy).

use bevy_ecs::component::Component;
use bevy_ecs::entity::Entity;

/// The host part a nozzle is mounted on, or the shell course a boot hangs from:
/// its first patch is cut at their intersection.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
#[relationship(relationship_target = Mounts)]
pub struct MountedOn(pub Entity);

/// The nozzles (and boot) mounted on a part (kept by bevy from [`MountedOn`]).
#[derive(Component, Debug, Default)]
#[relationship_target(relationship = MountedOn)]
pub struct Mounts(Vec<Entity>);

impl Mounts {
    /// The mounted nozzles.
    pub fn entities(&self) -> &[Entity] {
        &self.0
    }
}

/// The entity a note annotates (a vessel, part, nozzle or another note).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
#[relationship(relationship_target = AnnotatedBy)]
pub struct Annotates(pub Entity);

/// The notes annotating an entity (kept by bevy from [`Annotates`]).
#[derive(Component, Debug, Default)]
#[relationship_target(relationship = Annotates)]
pub struct AnnotatedBy(Vec<Entity>);

/// The part or nozzle a patch belongs to.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
#[relationship(relationship_target = Patches)]
pub struct PatchOf(pub Entity);

/// The patches of a part or nozzle, in build order; despawned with it.
#[derive(Component, Debug, Default)]
#[relationship_target(relationship = PatchOf, linked_spawn)]
pub struct Patches(Vec<Entity>);

impl Patches {
    /// The patch entities.
    pub fn entities(&self) -> &[Entity] {
        &self.0
    }
}

/// The nozzle a reinforcing-pad patch belongs to.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
#[relationship(relationship_target = PadPatch)]
pub struct PadOf(pub Entity);

/// A nozzle's reinforcing-pad patch (kept by bevy from [`PadOf`]); despawned with it.
#[derive(Component, Debug)]
#[relationship_target(relationship = PadOf, linked_spawn)]
pub struct PadPatch(Entity);

impl PadPatch {
    /// The pad patch entity.
    pub fn entity(&self) -> Entity {
        self.0
    }
}
