//! Regions: for every patch whose surface changed, or whose openings changed, lay
//! out the (u, v) region it is meshed within — its sides sampled from the edge
//! curves, the openings of the nozzles it hosts as holes, and for a nozzle neck the
//! intersection with its host as its bottom edge. Runs in the Tessellate stage
//! before meshing, in parallel with rayon.
//!
//! A host patch is laid out again whenever one of its openings changes, and a
//! nozzle neck whenever its opening moves, mostly with their own surface
//! unchanged; their sampled sides ([`PatchSides`], the costly part of a layout)
//! are kept in [`HostSides`] and reused while the surface is the same. When the
//! surface changed, a side whose edge curve did not (the bottom of a course whose
//! length changed) is still taken from the kept sides. With the sides,
//! [`HostSides`] keeps the trim the patch was laid out with: a patch whose surface
//! is the same and whose trim reads the same (u, v), bit for bit, would come out
//! the same region, so it is not laid out at all — the neck of a nozzle placed
//! again along its course (its loop's neck side is the canonical march's), the
//! host of an opening whose host side did not change.

use crate::components::{HostSides, Laid, Trim};
use std::collections::BTreeSet;
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::query::{QueryState, With};
use bevy_ecs::world::World;
use rayon::prelude::*;

use super::labels::{build_failure, patch_name};
use crate::components::BuildCause;
use crate::components::unique;
use crate::components::{DirtyParts, DirtyPatches};
use crate::components::{ModelErrors, OpeningHosts, Tessellation, Views, WorkCounters};
use crate::components::{Mounts, Opening, PadOf, PadPatch, PatchOf, PatchRegion, PatchSurface};
use crate::mesh::{HostTrim, Notch, PatchSides, host_region_with, pad_region};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// One region to lay out.
struct Job {
    patch: Entity,
    surface: Arc<Patch>,
    trim: Trim,
    /// The surface and sides kept from the patch's last layout: the sides as
    /// they are while the surface is the same, else the source of any v side
    /// whose edge curve did not change (`PatchSides::of_reusing`).
    kept: Option<(Arc<Patch>, Arc<PatchSides>)>,
    /// Same surface, trim read the same as at the last layout: the region
    /// would come out the same, so it is not laid out.
    same: bool,
}

impl Job {
    /// Whether an opening trims the patch — it hosts one, or it is a neck cut at
    /// its host: the patch is laid out again whenever that opening moves, mostly
    /// with its own surface unchanged, so its sides are worth keeping.
    fn trimmed(&self) -> bool {
        matches!(&self.trim, Trim::Patch { holes, notches, bottom }
            if !holes.is_empty() || !notches.is_empty() || bottom.is_some())
    }
}

/// How `patch` is trimmed: by the openings that cut it, its own neck bottom, or as
/// a pad.
fn trims(world: &World, patch: Entity) -> Option<Trim> {
    if let Some(nozzle) = world.get::<PadOf>(patch).map(|p| p.0) {
        let (outer, inner) = world.get::<Opening>(nozzle)?.pad_trim.clone()?;
        return Some(Trim::Pad { outer, inner });
    }
    let Some(owner) = world.get::<PatchOf>(patch).map(|p| p.0) else {
        return Some(Trim::Patch {
            holes: Vec::new(),
            notches: Vec::new(),
            bottom: None,
        });
    };
    let bottom = world
        .get::<Opening>(owner)
        .filter(|o| o.neck_patch == patch)
        .map(|o| o.curve.clone());
    let mut holes = Vec::new();
    let mut notches = Vec::new();
    let openings = world
        .get::<Mounts>(owner)
        .map(|m| m.entities())
        .unwrap_or_default()
        .iter()
        .filter_map(|&n| world.get::<Opening>(n));
    for o in openings {
        match o.hosts.iter().find(|(h, _)| *h == patch).map(|(_, t)| t) {
            Some(HostTrim::Hole) => holes.push(o.pad.clone().unwrap_or_else(|| o.curve.clone())),
            Some(HostTrim::Notches(n)) => notches.push(n.clone()),
            None => {}
        }
    }
    Some(Trim::Patch {
        holes,
        notches,
        bottom,
    })
}

/// Lays out the region of every patch that needs it.
pub fn lay_out_regions(world: &mut World, all: &mut QueryState<Entity, With<PatchSurface>>) {
    let options = world.resource::<Tessellation>().0;
    let keep = *world.resource::<Views>() == Views::Kept;
    if !world.contains_resource::<HostSides>() {
        world.init_resource::<HostSides>();
    }
    let mut kept = std::mem::take(&mut world.resource_mut::<HostSides>().0);
    if world.is_resource_changed::<Tessellation>() {
        kept.clear();
    }
    for patch in world.removed::<PatchSurface>() {
        kept.remove(&patch);
    }
    // Views turned back on: lay every region out again to keep its loops (the
    // fingerprints come out equal, so nothing is re-meshed).
    let restore = keep && world.is_resource_changed::<Views>();
    let mut dirty: BTreeSet<Entity> = if world.is_resource_changed::<Tessellation>() || restore {
        all.iter(world).collect()
    } else {
        world
            .resource::<DirtyPatches>()
            .surfaces
            .iter()
            .copied()
            .collect()
    };
    // Openings cut in this run (listed by `cut_openings`).
    let cut = unique(world.resource::<DirtyParts>().openings.iter().copied());
    let changed: Vec<(Entity, Vec<Entity>, Entity)> = cut
        .into_iter()
        .filter_map(|n| {
            let o = world.get::<Opening>(n)?;
            Some((n, o.hosts.iter().map(|h| h.0).collect(), o.neck_patch))
        })
        .collect();
    for &(nozzle, ..) in &changed {
        if let Some(pad) = world.get::<PadPatch>(nozzle) {
            dirty.insert(pad.entity());
        }
    }
    let mut hosts = std::mem::take(&mut world.resource_mut::<OpeningHosts>().0);
    for (nozzle, host, neck) in changed {
        dirty.extend(host.iter().copied());
        dirty.insert(neck);
        if let Some(previous) = hosts.insert(nozzle, host) {
            dirty.extend(previous);
        }
    }
    // Openings that disappeared (nozzle removed, or its opening failed): the
    // world's removal messages since the model's last update, not a scan of all.
    let removed: Vec<Entity> = world.removed::<Opening>().collect();
    for nozzle in removed {
        if world.get::<Opening>(nozzle).is_none()
            && let Some(host) = hosts.remove(&nozzle)
        {
            dirty.extend(host);
        }
    }
    world.resource_mut::<OpeningHosts>().0 = hosts;
    // A patch laid out within the same surface and trim as last time keeps its
    // region, unless views were switched (the component's loops change).
    let force = world.is_resource_changed::<Views>();
    let dirty: Vec<Entity> = dirty.into_iter().collect();
    let last = &kept;
    // Gathered in parallel: a host's trim reads every opening it hosts.
    let jobs: Vec<Job> = dirty
        .par_iter()
        .filter_map(|&patch| {
            let surface = world.get::<PatchSurface>(patch)?.0.clone();
            let trim = trims(world, patch)?;
            let laid = last.get(&patch);
            let same = !force
                && laid.is_some_and(|l| {
                    Arc::ptr_eq(&l.surface, &surface) && trim.lays_out_as(&l.trim)
                });
            Some(Job {
                patch,
                surface,
                trim,
                kept: laid.map(|l| (l.surface.clone(), l.sides.clone())),
                same,
            })
        })
        .collect();
    // One job per split: a host with many openings next to many necks would
    // otherwise sit in one thread's half of the list (see `biggest_first`).
    let results: Vec<_> = jobs
        .par_iter()
        .with_max_len(1)
        .map(|j| {
            if j.same {
                return None;
            }
            let region = match &j.trim {
                Trim::Patch {
                    holes,
                    notches,
                    bottom,
                } => {
                    let holes: Vec<&IntersectionLoop> = holes.iter().map(|h| h.as_ref()).collect();
                    let notches: Vec<&Notch> = notches.iter().flat_map(|n| n.iter()).collect();
                    let sides = match &j.kept {
                        Some((from, sides)) if Arc::ptr_eq(from, &j.surface) => sides.clone(),
                        kept => Arc::new(PatchSides::of_reusing(
                            &j.surface.surface,
                            &options,
                            kept.as_ref().map(|(p, s)| (&p.surface, s.as_ref())),
                        )),
                    };
                    let region = host_region_with(
                        &j.surface.surface,
                        &sides,
                        &holes,
                        &notches,
                        bottom.as_deref(),
                    );
                    (region, j.trimmed().then_some(sides))
                }
                Trim::Pad { outer, inner } => {
                    (pad_region(&j.surface.surface, &options, outer, inner), None)
                }
            };
            // The fingerprint hashes every loop coordinate: done here, in
            // parallel, not in the serial loop below.
            let (region, sides) = region;
            let region = region.map(|r| {
                let fingerprint = r.fingerprint();
                (Arc::new(r), fingerprint)
            });
            Some((region, sides))
        })
        .collect();
    let mut laid = 0;
    let mut failures = 0;
    // New components are inserted in one batch (see `remesh_dirty_patches`);
    // the dirty lists are extended once.
    let mut new_regions: Vec<(Entity, PatchRegion)> = Vec::new();
    let mut laid_out = Vec::with_capacity(results.len());
    let mut changed_regions = Vec::with_capacity(results.len());
    let mut skipped = 0;
    for (job, result) in jobs.into_iter().zip(results) {
        let patch = job.patch;
        let Some((result, sides)) = result else {
            // Not laid out: the trim's loops are the openings' new ones now.
            if let Some(l) = kept.get_mut(&patch) {
                l.trim = job.trim;
            }
            skipped += 1;
            continue;
        };
        // The sides are kept for the next layout, and the trim when the
        // region came out.
        match (sides, &result) {
            (Some(sides), Ok(_)) => {
                let surface = job.surface;
                let trim = job.trim;
                kept.insert(
                    patch,
                    Laid {
                        surface,
                        sides,
                        trim,
                    },
                );
            }
            _ => {
                kept.remove(&patch);
            }
        }
        match result {
            Ok((region, fingerprint)) => {
                let component = PatchRegion {
                    fingerprint,
                    region: keep.then(|| region.clone()),
                };
                laid_out.push((patch, region, fingerprint));
                let changed = match world.get_mut::<PatchRegion>(patch) {
                    Some(mut current) => {
                        let differs = current.fingerprint != component.fingerprint;
                        if differs || current.region.is_some() != keep {
                            *current = component;
                        }
                        differs
                    }
                    None => {
                        new_regions.push((patch, component));
                        true
                    }
                };
                if changed {
                    changed_regions.push(patch);
                }
                laid += u64::from(changed);
            }
            Err(e) => {
                failures += 1;
                let cause = BuildCause::Region {
                    patch: patch_name(world, patch),
                    source: e,
                };
                let failure = build_failure(world, patch, cause);
                world.resource_mut::<ModelErrors>().0.push(failure);
            }
        }
    }
    world.resource_mut::<HostSides>().0 = kept;
    world.insert_batch(new_regions);
    let mut dirty = world.resource_mut::<DirtyPatches>();
    dirty.laid_out.extend(laid_out);
    dirty.regions.extend(changed_regions);
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.regions_laid_out += laid;
    counters.regions_unchanged += skipped;
    counters.failures += failures;
}
