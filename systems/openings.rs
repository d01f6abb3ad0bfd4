//! Openings: for every nozzle whose frame or shape changed, or whose host part
//! changed or moved, compute the curve where its neck meets its host — once, in the
//! host's frame — and store it as the nozzle's [`Opening`]. Runs in the Geometry
//! stage after the patches are rebuilt, in parallel with rayon.

use std::collections::{BTreeSet, HashMap};
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::query::{Changed, Or, QueryState, With};
use bevy_ecs::resource::Resource;
use bevy_ecs::world::World;
use glam::DAffine3;
use rayon::prelude::*;

use super::{ModelErrors, Tessellation, WorkCounters};
use crate::components::{MountedOn, Mounts, NozzleSpec, Opening, PartFrame, PatchSurface, Patches, Shape};
use crate::design::RuleViolation;
use crate::mesh::cut_opening;
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// The host patch each nozzle's opening was last cut in (to re-lay-out a host patch
/// whose opening moved away or disappeared).
#[derive(Resource, Default, Debug)]
pub struct OpeningHosts(pub HashMap<Entity, Entity>);

/// Nozzles whose own frame or shape changed, or that were re-hosted.
pub type ChangedNozzle = (With<NozzleSpec>, Or<(Changed<PartFrame>, Changed<Shape>, Changed<MountedOn>)>);
/// Host parts that moved or changed shape.
pub type ChangedHost = Or<(Changed<PartFrame>, Changed<Shape>)>;

/// One opening to compute.
struct Job {
    nozzle: Entity,
    neck_patch: Entity,
    neck: Arc<Patch>,
    frame: DAffine3,
    host_frame: DAffine3,
    hosts: Vec<(Entity, Arc<Patch>)>,
}

fn violation(entity: Entity, rule: String) -> (String, Vec<RuleViolation>) {
    (
        format!("{entity}"),
        vec![RuleViolation { path: String::new(), entity: format!("{entity}"), field: "opening".into(), value: String::new(), rule }],
    )
}

/// Computes the opening of every nozzle that needs it.
pub fn cut_openings(
    world: &mut World,
    nozzles: &mut QueryState<Entity, ChangedNozzle>,
    hosts: &mut QueryState<&Mounts, ChangedHost>,
) {
    let mut dirty: BTreeSet<Entity> = nozzles.iter(world).collect();
    for mounts in hosts.iter(world) {
        dirty.extend(mounts.entities().iter().copied());
    }
    if dirty.is_empty() {
        return;
    }
    let tolerance = world.resource::<Tessellation>().0.tolerance;
    let mut jobs = Vec::new();
    for &nozzle in &dirty {
        let (Some(host), Some(frame)) = (world.get::<MountedOn>(nozzle).map(|m| m.0), world.get::<PartFrame>(nozzle).map(|f| f.0)) else {
            continue;
        };
        let Some(host_frame) = world.get::<PartFrame>(host).map(|f| f.0) else { continue };
        let Some(&neck_patch) = world.get::<Patches>(nozzle).and_then(|p| p.entities().first()) else { continue };
        let Some(neck) = world.get::<PatchSurface>(neck_patch).map(|s| s.0.clone()) else { continue };
        let hosts: Vec<_> = world
            .get::<Patches>(host)
            .map(|p| p.entities().iter().filter_map(|&e| Some((e, world.get::<PatchSurface>(e)?.0.clone()))).collect())
            .unwrap_or_default();
        jobs.push(Job { nozzle, neck_patch, neck, frame, host_frame, hosts });
    }
    let results: Vec<(Entity, Entity, Result<(Entity, IntersectionLoop), String>)> = jobs
        .par_iter()
        .map(|job| {
            let hosts: Vec<&Patch> = job.hosts.iter().map(|(_, p)| p.as_ref()).collect();
            let result = cut_opening(&job.neck, &job.frame, &job.host_frame, &hosts, tolerance)
                .map(|(k, curve)| (job.hosts[k].0, curve));
            (job.nozzle, job.neck_patch, result)
        })
        .collect();
    let mut cut = 0;
    let mut failures = 0;
    for (nozzle, neck_patch, result) in results {
        match result {
            Ok((host_patch, curve)) => {
                let opening = Opening { host_patch, neck_patch, curve: Arc::new(curve) };
                let changed = match world.get_mut::<Opening>(nozzle) {
                    Some(mut current) => {
                        if *current != opening {
                            *current = opening;
                            true
                        } else {
                            false
                        }
                    }
                    None => {
                        world.entity_mut(nozzle).insert(opening);
                        true
                    }
                };
                cut += u64::from(changed);
            }
            Err(rule) => {
                failures += 1;
                world.entity_mut(nozzle).remove::<Opening>();
                world.resource_mut::<ModelErrors>().0.push(violation(nozzle, rule));
            }
        }
    }
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.openings_cut += cut;
    counters.failures += failures;
}
