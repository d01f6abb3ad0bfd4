//! Openings: for every nozzle (or boot) whose frame or shape changed, or whose host
//! part changed or moved, compute the curve where its neck (the boot's shell) meets
//! its host — once, in the host's frame — and store it as its [`Opening`]. Every
//! entity `MountedOn` a host is cut this way: nozzles on their host part, a boot on
//! its shell course. Runs in the Geometry stage after the patches are rebuilt, in
//! parallel with rayon.

use crate::components::CutTable;
use std::collections::BTreeSet;
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::world::World;
use glam::DAffine3;
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use super::labels::{build_failure, stable_id};
use crate::components::{BuildCause, ModelErrors, ModelFailure, Tessellation, WorkCounters};
use crate::components::{DirtyParts, DirtyPatches};
use crate::components::{
    MountedOn, Mounts, Opening, OpeningInput, PadOf, PadPatch, PartFrame, PatchSurface, Patches,
    Shape,
};
use crate::mesh::{AxialCut, Cut, CutError, HostTrim, OpeningPlan, PadCut};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// One opening to compute.
pub(super) struct Job {
    pub nozzle: Entity,
    pub pad_od: Option<f64>,
    pub neck_patch: Entity,
    pub neck: Arc<Patch>,
    pub frame: DAffine3,
    pub host_frame: DAffine3,
    pub hosts: Vec<(Entity, Arc<Patch>)>,
}

impl Job {
    /// What this opening is cut from, keeping `axial`.
    fn input(&self, tolerance: f64, axial: Option<Arc<AxialCut>>) -> OpeningInput {
        OpeningInput::new(
            self.neck.clone(),
            self.hosts.iter().map(|(_, p)| p.clone()).collect(),
            self.pad_od,
            tolerance,
            self.frame,
            self.host_frame,
            axial,
        )
    }
}

/// The failure of an opening that cannot be cut: the nozzle (or boot), the
/// host it is mounted on and the cutter's reason.
fn cut_failure(world: &World, entity: Entity, source: CutError) -> ModelFailure {
    let host = world
        .get::<MountedOn>(entity)
        .map(|m| stable_id(world, m.0))
        .unwrap_or_default();
    build_failure(world, entity, BuildCause::Opening { host, source })
}

/// One opening cut: the nozzle, its neck patch, the cut (made into the
/// nozzle's new components, each compared with the world's), its inputs and
/// whether it was placed from a kept cut.
struct Cutting {
    nozzle: Entity,
    result: Result<Made, CutError>,
    input: OpeningInput,
    reused: bool,
}

/// An opening cut, as it will be written.
struct Made {
    opening: Opening,
    /// Whether it differs from the nozzle's current opening (or it has none).
    differs: bool,
    /// The pad patch, if the nozzle has a pad, and whether it differs from the
    /// current one's surface (or there is none).
    pad: Option<(Patch, bool)>,
}

impl Made {
    /// The components of `cut` for `job`'s nozzle, compared with the world's:
    /// done in parallel, since comparing loops and patches reads every number.
    fn of(
        world: &World,
        job: &Job,
        hosts: Vec<(Entity, HostTrim)>,
        cut: Cut,
        pad: Option<PadCut>,
    ) -> Self {
        let curve = Arc::new(cut.neck);
        let pad_loop = cut.pad.map(Arc::new);
        // Off a straight course the pad's trim is the opening's own loops:
        // held once.
        let share = |l: &Arc<IntersectionLoop>, own: Option<&Arc<IntersectionLoop>>| {
            own.filter(|o| o == &l).unwrap_or(l).clone()
        };
        let pad_trim = pad.as_ref().map(|p| {
            (
                share(&p.outer, pad_loop.as_ref()),
                share(&p.inner, Some(&curve)),
            )
        });
        let opening = Opening {
            hosts,
            neck_patch: job.neck_patch,
            curve,
            pad: pad_loop,
            pad_trim,
        };
        let differs = world
            .get::<Opening>(job.nozzle)
            .is_none_or(|current| *current != opening);
        let pad = pad.map(|p| {
            let current = world
                .get::<PadPatch>(job.nozzle)
                .and_then(|e| world.get::<PatchSurface>(e.entity()));
            let differs = current.is_none_or(|s| *s.0 != p.patch);
            (p.patch, differs)
        });
        Self {
            opening,
            differs,
            pad,
        }
    }
}

/// Cuts the openings of `jobs[ids]` by their `plans`, each placing its `kept`
/// cut where that applies, in parallel, in that order.
fn run(
    world: &World,
    jobs: &[Job],
    plans: &[OpeningPlan],
    kept: &[Option<Arc<AxialCut>>],
    ids: &[usize],
    tolerance: f64,
) -> Vec<Cutting> {
    // One job per split, so a thread done with its cuts takes another's (cuts
    // with a pad march two loops).
    ids.par_iter()
        .with_max_len(1)
        .map(|&i| {
            let job = &jobs[i];
            let cut = plans[i].cut(kept[i].as_ref());
            let (axial, reused) = cut
                .as_ref()
                .map_or((None, false), |c| (c.axial.clone(), c.reused));
            let result = cut.map(|c| {
                let trims = c
                    .cut
                    .hosts
                    .iter()
                    .map(|(k, trim)| (job.hosts[*k].0, trim.clone()))
                    .collect();
                Made::of(world, job, trims, c.cut, c.pad)
            });
            Cutting {
                nozzle: job.nozzle,
                result,
                input: job.input(tolerance, axial),
                reused,
            }
        })
        .collect()
}

/// Updates (if it differs) or removes a nozzle's pad patch; a new one is
/// returned, for the caller to spawn with the others in one batch.
fn set_pad(
    world: &mut World,
    nozzle: Entity,
    pad: Option<(Patch, bool)>,
) -> Option<(PadOf, PatchSurface)> {
    let existing = world.get::<PadPatch>(nozzle).map(PadPatch::entity);
    match (existing, pad) {
        (Some(e), Some((p, differs))) => {
            if differs && let Some(mut s) = world.get_mut::<PatchSurface>(e) {
                s.0 = Arc::new(p);
                world.resource_mut::<DirtyPatches>().surfaces.push(e);
            }
        }
        (None, Some((p, _))) => return Some((PadOf(nozzle), PatchSurface(Arc::new(p)))),
        (Some(e), None) => {
            world.despawn(e);
        }
        (None, None) => {}
    }
    None
}

/// A dirty opening, gathered (held only while the stage runs, so the job is
/// not boxed).
#[expect(
    clippy::large_enum_variant,
    reason = "held only while the stage runs; boxing the job would allocate per opening"
)]
enum Gathered {
    /// Cut before from the same inputs: nothing to do.
    Same,
    /// To cut, with the canonical cut its last cut kept, if it may apply.
    Cut(Job, Option<Arc<AxialCut>>),
}

/// The opening to cut for `nozzle`, if it has a host, a frame and a neck.
fn gather(world: &World, nozzle: Entity) -> Option<Job> {
    let host = world.get::<MountedOn>(nozzle)?.0;
    let frame = world.get::<PartFrame>(nozzle)?.0;
    let host_frame = world.get::<PartFrame>(host)?.0;
    let neck_patch = *world.get::<Patches>(nozzle)?.entities().first()?;
    let neck = world.get::<PatchSurface>(neck_patch)?.0.clone();
    let hosts: Vec<_> = world
        .get::<Patches>(host)
        .map(|p| {
            p.entities()
                .iter()
                .filter_map(|&e| Some((e, world.get::<PatchSurface>(e)?.0.clone())))
                .collect()
        })
        .unwrap_or_default();
    let pad_od = match world.get::<Shape>(nozzle) {
        Some(Shape::Nozzle(_, pad)) => pad.map(|p| p.0),
        _ => None,
    };
    Some(Job {
        nozzle,
        pad_od,
        neck_patch,
        neck,
        frame,
        host_frame,
        hosts,
    })
}

/// Computes the opening of every nozzle that needs it.
pub fn cut_openings(world: &mut World) {
    // Nozzles and boots whose own frame, shape or host changed, and those mounted
    // on a part that moved or changed shape (listed by the Constrain stage).
    let lists = world.resource::<DirtyParts>();
    let moved = lists.moved_or_reshaped();
    let mut dirty: BTreeSet<Entity> = moved
        .iter()
        .chain(&lists.mounts)
        .copied()
        .filter(|&e| world.get::<MountedOn>(e).is_some())
        .collect();
    for &part in &moved {
        if let Some(mounts) = world.get::<Mounts>(part) {
            dirty.extend(mounts.entities().iter().copied());
        }
    }
    if dirty.is_empty() {
        return;
    }
    let tolerance = world.resource::<Tessellation>().0.tolerance;
    // Gathered in parallel: each reads its host's patches and compares its
    // inputs with the last cut's.
    let world_ref = &*world;
    let dirty: Vec<Entity> = dirty.into_iter().collect();
    let gathered: Vec<Gathered> = dirty
        .par_iter()
        .filter_map(|&nozzle| {
            let job = gather(world_ref, nozzle)?;
            let last = world_ref
                .get::<OpeningInput>(nozzle)
                .filter(|_| world_ref.get::<Opening>(nozzle).is_some());
            // Cut before from the same inputs (and it succeeded): nothing to do.
            if last.is_some_and(|input| input.same(&job.input(tolerance, None))) {
                return Some(Gathered::Same);
            }
            let kept = last.and_then(|input| input.kept_for(&job.neck, job.pad_od, tolerance));
            Some(Gathered::Cut(job, kept))
        })
        .collect();
    let skipped = gathered
        .iter()
        .filter(|g| matches!(g, Gathered::Same))
        .count() as u64;
    let (jobs, mut kept): (Vec<Job>, Vec<Option<Arc<AxialCut>>>) = gathered
        .into_iter()
        .filter_map(|g| match g {
            Gathered::Cut(job, kept) => Some((job, kept)),
            Gathered::Same => None,
        })
        .unzip();
    // Openings cut from one canonical march share it: each distinct march is
    // looked up among the cuts in use, else made once (by the first opening
    // that needs it) and placed for the others.
    let plans: Vec<OpeningPlan> = jobs
        .par_iter()
        .map(|job| {
            let hosts: Vec<&Patch> = job.hosts.iter().map(|(_, p)| p.as_ref()).collect();
            let (neck, frames) = (&job.neck, (&job.frame, &job.host_frame));
            OpeningPlan::new(neck, job.pad_od, frames.0, frames.1, hosts, tolerance)
        })
        .collect();
    let keys: Vec<Option<u128>> = plans.iter().map(OpeningPlan::shared_key).collect();
    let mut first = Vec::with_capacity(jobs.len());
    let mut later: Vec<(usize, usize)> = Vec::new();
    {
        let table = &world.resource::<CutTable>().0;
        let mut leaders: FxHashMap<u128, usize> = FxHashMap::default();
        for (i, key) in keys.iter().enumerate() {
            match key {
                Some(k) => {
                    if let Some(cut) = table.get(*k) {
                        kept[i] = Some(cut);
                        first.push(i);
                    } else if let Some(&leader) = leaders.get(k) {
                        later.push((i, leader));
                    } else {
                        leaders.insert(*k, i);
                        first.push(i);
                    }
                }
                None => first.push(i),
            }
        }
    }
    let mut done: Vec<Option<Cutting>> = (0..jobs.len()).map(|_| None).collect();
    for (i, r) in first
        .iter()
        .zip(run(world, &jobs, &plans, &kept, &first, tolerance))
    {
        done[*i] = Some(r);
    }
    if !later.is_empty() {
        for &(i, leader) in &later {
            kept[i] = done[leader].as_ref().and_then(|r| r.input.axial.clone());
        }
        let ids: Vec<usize> = later.iter().map(|&(i, _)| i).collect();
        for (i, r) in ids
            .iter()
            .zip(run(world, &jobs, &plans, &kept, &ids, tolerance))
        {
            done[*i] = Some(r);
        }
    }
    {
        let table = &mut world.resource_mut::<CutTable>().0;
        for (key, r) in keys.iter().zip(&done) {
            if let (Some(k), Some(Some(cut))) = (key, r.as_ref().map(|r| &r.input.axial)) {
                table.insert(*k, cut);
            }
        }
    }
    let results = done.into_iter().flatten();
    let mut cut_count = 0;
    let mut placed = 0;
    let mut failures = 0;
    // Components new to their nozzle are inserted in batches after the loop
    // (see `remesh_dirty_patches`).
    let mut new_openings: Vec<(Entity, Opening)> = Vec::new();
    let mut new_inputs: Vec<(Entity, OpeningInput)> = Vec::new();
    let mut new_both: Vec<(Entity, (Opening, OpeningInput))> = Vec::new();
    let mut new_pads: Vec<(PadOf, PatchSurface)> = Vec::new();
    for Cutting {
        nozzle,
        result,
        input,
        reused,
    } in results
    {
        match result {
            Ok(Made {
                opening,
                differs,
                pad,
            }) => {
                new_pads.extend(set_pad(world, nozzle, pad));
                // A nozzle new to both takes them in one insertion (one move of
                // its row to their archetype, not two).
                let held_input = match world.get_mut::<OpeningInput>(nozzle) {
                    Some(mut held) => {
                        *held = input;
                        None
                    }
                    None => Some(input),
                };
                match (world.get_mut::<Opening>(nozzle), held_input) {
                    (Some(mut current), input) => {
                        new_inputs.extend(input.map(|i| (nozzle, i)));
                        if differs {
                            *current = opening;
                        }
                    }
                    (None, Some(input)) => new_both.push((nozzle, (opening, input))),
                    (None, None) => new_openings.push((nozzle, opening)),
                }
                cut_count += u64::from(differs);
                placed += u64::from(differs && reused);
                if differs {
                    world.resource_mut::<DirtyParts>().openings.push(nozzle);
                }
            }
            Err(cause) => {
                failures += 1;
                world.entity_mut(nozzle).remove::<(Opening, OpeningInput)>();
                let failure = cut_failure(world, nozzle, cause);
                world.resource_mut::<ModelErrors>().0.push(failure);
            }
        }
    }
    let pads: Vec<Entity> = world.spawn_batch(new_pads).collect();
    world.resource_mut::<DirtyPatches>().surfaces.extend(pads);
    world.insert_batch(new_both);
    world.insert_batch(new_openings);
    world.insert_batch(new_inputs);
    let mut counters = world.resource_mut::<WorkCounters>();
    counters.openings_cut += cut_count;
    counters.openings_unchanged += skipped;
    counters.openings_placed += placed;
    counters.failures += failures;
}
