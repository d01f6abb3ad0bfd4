//! Project stage: keep every part's and nozzle's lines in the four views up to
//! date, rebuilding only the (entity, view) pairs an update can have changed.
//!
//! An entity is *dirty* when one of its meshes changed (a nozzle opening moved
//! across its host re-meshes the host), its frame or shape changed, or it is new.
//! Dirty entities are rebuilt in every view. A clean entity is rebuilt in a view
//! only when one of its lines there passes through the old or new footprint (the
//! box of its meshes in that view) of an entity that moved, changed shape,
//! appeared or disappeared: only there can an occluder have come or gone, so only
//! then can its visibility have changed. A re-meshed host whose shape did not change does not hide more or
//! less than before (its openings are covered by the footprints of the nozzles that
//! cut them), so it does not spread the rebuild. A change of projection (the vessel
//! turned in plan), of sampling (its size doubled or halved) or of the tessellation
//! options rebuilds the whole vessel. The occluders of a vessel with any dirty
//! entity are re-binned (linear in its triangles); the line building runs in
//! parallel with rayon.

use crate::components::Views;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::{ChildOf, Children};
use bevy_ecs::query::{Changed, Or, QueryState, With, Without};
use bevy_ecs::system::Res;
use bevy_ecs::world::World;
use glam::DVec2;
use rayon::prelude::*;

use crate::components::{DirtyPatches, Tessellation, WorkCounters};
use crate::components::{
    EntityViews, Footprint, NozzleSpec, PadOf, PadPatch, PartFrame, PartSpec, PatchMesh, PatchOf,
    PatchRegion, PatchSurface, Patches, Shape, VesselFrame, VesselSpec, VesselSummary, VesselViews,
};
use crate::project::{
    EntityInput, EntityView, LineKind, Occluder, PatchInput, PreparedEntity, ViewSettings,
    build_entity_view, footprint, projections,
};

/// A part or nozzle whose frame or shape changed.
type Moved = (
    Or<(Changed<PartFrame>, Changed<Shape>)>,
    Or<(With<PartSpec>, With<NozzleSpec>)>,
);

/// A part or nozzle with patches and no views yet.
type Unviewed = (
    With<Patches>,
    Without<EntityViews>,
    Or<(With<PartSpec>, With<NozzleSpec>)>,
);

/// A vessel whose views may need a whole rebuild or lost a member: its kind,
/// frame or summary (projections and sampling) or its children changed, or it has
/// no views yet.
type Reframed = (
    With<VesselSpec>,
    Or<(
        Changed<VesselSpec>,
        Changed<VesselFrame>,
        Changed<VesselSummary>,
        Changed<Children>,
        Without<VesselViews>,
    )>,
);

/// The inputs of one member entity of vessel `tag`, or `None` when it has no frame
/// yet.
pub fn entity_input(world: &World, tag: &str, e: Entity) -> Option<EntityInput> {
    let frame = world.get::<PartFrame>(e)?.0;
    let id = world
        .get::<PartSpec>(e)
        .map(|p| p.0.id().to_string())
        .or_else(|| world.get::<NozzleSpec>(e).map(|n| n.0.mark.clone()))?;
    let pad = world.get::<PadPatch>(e).map(PadPatch::entity);
    let patches = world
        .get::<Patches>(e)
        .map(|p| p.entities().to_vec())
        .unwrap_or_default()
        .into_iter()
        .chain(pad)
        .filter_map(|p| {
            Some(PatchInput {
                patch: world.get::<PatchSurface>(p)?.0.clone(),
                region: world.get::<PatchRegion>(p).and_then(|r| r.region.clone()),
                mesh: Arc::new(world.get::<PatchMesh>(p)?.0.unpack()),
            })
        })
        .collect();
    Some(EntityInput {
        id: format!("{tag}/{id}"),
        frame,
        patches,
    })
}

/// Sampling settings for a vessel: its size rounded up to a power of two, so that
/// ordinary edits do not change them.
fn settings_for(summary: &VesselSummary, tolerance: f64) -> ViewSettings {
    let size = (summary.extent.1 - summary.extent.0).max(summary.max_diameter * 2.0);
    let rounded = 2f64.powi(size.max(1.0).log2().ceil() as i32);
    ViewSettings::for_vessel(rounded, tolerance)
}

/// Whether the polyline passes through the box `[lo, hi]`.
fn crosses_box(points: &[DVec2], lo: DVec2, hi: DVec2) -> bool {
    points
        .windows(2)
        .any(|w| segment_crosses_box(w[0], w[1], lo, hi))
}

/// Whether the segment `ab` meets the box `[lo, hi]` (Liang–Barsky clipping).
fn segment_crosses_box(a: DVec2, b: DVec2, lo: DVec2, hi: DVec2) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d.x, a.x - lo.x),
        (d.x, hi.x - a.x),
        (-d.y, a.y - lo.y),
        (d.y, hi.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// Run condition of the Project stage: views are kept.
pub fn views_kept(views: Res<Views>) -> bool {
    *views == Views::Kept
}

/// Rebuilds the views of dirty entities, and of clean ones whose visibility an
/// edit may have changed.
#[expect(
    clippy::too_many_lines,
    reason = "one pass: collect, decide, build, write"
)]
pub fn project_dirty_views(
    world: &mut World,
    meshed: &mut QueryState<&PatchOf, Changed<PatchMesh>>,
    padded: &mut QueryState<&PadOf, Changed<PatchMesh>>,
    moved: &mut QueryState<Entity, Moved>,
    unviewed: &mut QueryState<Entity, Unviewed>,
    vessels: &mut QueryState<(Entity, &VesselSpec, &VesselFrame, &VesselSummary)>,
    reframed: &mut QueryState<Entity, Reframed>,
) {
    let tessellation_changed = world.is_resource_changed::<Tessellation>();
    let views_changed = world.is_resource_changed::<Views>();
    let tolerance = world.resource::<Tessellation>().0.tolerance;
    let moved_set: BTreeSet<Entity> = moved.iter(world).chain(unviewed.iter(world)).collect();
    let mut dirty: BTreeSet<Entity> = moved_set.clone();
    if views_changed {
        // Views (back) on: every mesh written since the stage last ran, which
        // may be several updates ago.
        dirty.extend(meshed.iter(world).map(|p| p.0));
        dirty.extend(padded.iter(world).map(|p| p.0));
    } else {
        // The stage ran on the last update: the meshes written since are the
        // ones the Tessellate stage lists for this run (a scan of every patch's
        // mesh for changes cost more than the rest of an idle update).
        let owner = |e: Entity| {
            (world.get::<PatchOf>(e).map(|p| p.0)).or_else(|| world.get::<PadOf>(e).map(|p| p.0))
        };
        let meshes = &world.resource::<DirtyPatches>().meshes;
        dirty.extend(meshes.iter().filter_map(|&e| owner(e)));
    }
    let vessel_of = |e: Entity| world.get::<ChildOf>(e).map(ChildOf::parent);
    let mut by_vessel: BTreeMap<Entity, BTreeSet<Entity>> = BTreeMap::new();
    for &e in &dirty {
        if let Some(v) = vessel_of(e) {
            by_vessel.entry(v).or_default().insert(e);
        }
    }
    // The vessels to look at: every one when the options or the views themselves
    // changed, else those with a dirty member or a change of their own (looking
    // at each of a plant's vessels on every update cost milliseconds).
    let candidates: Vec<Entity> = if tessellation_changed || views_changed {
        vessels.iter(world).map(|(e, ..)| e).collect()
    } else {
        let mut set: BTreeSet<Entity> = by_vessel.keys().copied().collect();
        set.extend(reframed.iter(world));
        set.into_iter().collect()
    };
    let all_vessels: Vec<(Entity, String, [_; 4], ViewSettings)> = candidates
        .into_iter()
        .filter_map(|e| vessels.get(world, e).ok())
        .map(|(e, spec, frame, summary)| {
            (
                e,
                spec.tag.clone(),
                projections(spec.kind, &frame.0),
                settings_for(summary, tolerance),
            )
        })
        .collect();
    let mut rebuilt = 0u64;
    for (vessel, tag, views, settings) in all_vessels {
        let members: Vec<Entity> = world
            .get::<Children>(vessel)
            .map(|c| {
                c.iter()
                    .copied()
                    .filter(|&e| {
                        world.get::<PartSpec>(e).is_some() || world.get::<NozzleSpec>(e).is_some()
                    })
                    .collect()
            })
            .unwrap_or_default();
        let previous = world.get::<VesselViews>(vessel);
        let whole = tessellation_changed
            || previous.is_none_or(|p| p.projections != views || p.settings != settings);
        let removed: Vec<[Footprint; 4]> = previous
            .map(|p| {
                p.footprints
                    .iter()
                    .filter(|(e, _)| !members.contains(e))
                    .map(|(_, f)| *f)
                    .collect()
            })
            .unwrap_or_default();
        let dirty_here = by_vessel.remove(&vessel).unwrap_or_default();
        if !whole && dirty_here.is_empty() && removed.is_empty() {
            continue;
        }
        let inputs: HashMap<Entity, EntityInput> = members
            .iter()
            .filter_map(|&e| Some((e, entity_input(world, &tag, e)?)))
            .collect();
        let old_footprints: HashMap<Entity, [Footprint; 4]> =
            previous.map(|p| p.footprints.clone()).unwrap_or_default();
        let new_footprints: HashMap<Entity, [Footprint; 4]> = inputs
            .iter()
            .map(|(&e, input)| (e, views.map(|p| footprint(input, &p))))
            .collect();
        // Regions whose occlusion changed, per view.
        let mut changed: [Vec<Footprint>; 4] = Default::default();
        for f in &removed {
            for k in 0..4 {
                changed[k].push(f[k]);
            }
        }
        for e in dirty_here.iter().filter(|e| moved_set.contains(e)) {
            for k in 0..4 {
                changed[k].push(old_footprints.get(e).and_then(|f| f[k]));
                changed[k].push(new_footprints.get(e).and_then(|f| f[k]));
            }
        }
        let mut jobs: Vec<(Entity, usize)> = Vec::new();
        let mut ordered: Vec<Entity> = inputs.keys().copied().collect();
        ordered.sort();
        let grow = 1.5 * settings.sampling.nudge;
        for &e in &ordered {
            let current = world.get::<EntityViews>(e);
            for (k, regions) in changed.iter().enumerate() {
                let touched = || {
                    current.is_some_and(|v| {
                        regions.iter().flatten().any(|&(lo, hi)| {
                            let (lo, hi) = (lo - DVec2::splat(grow), hi + DVec2::splat(grow));
                            v.0[k]
                                .lines
                                .iter()
                                .filter(|l| l.kind != LineKind::Centre)
                                .any(|l| crosses_box(&l.points, lo, hi))
                        })
                    })
                };
                if whole || current.is_none() || dirty_here.contains(&e) || touched() {
                    jobs.push((e, k));
                }
            }
        }
        let occluders: Vec<Occluder> = views
            .par_iter()
            .map(|p| {
                Occluder::build(
                    p,
                    inputs
                        .values()
                        .flat_map(|i| i.patches.iter().map(move |patch| (&*patch.mesh, i.frame))),
                )
            })
            .collect();
        // What an entity's views share is evaluated once for all its jobs.
        let mut with_jobs: Vec<Entity> = jobs.iter().map(|&(e, _)| e).collect();
        with_jobs.dedup();
        let prepared: HashMap<Entity, PreparedEntity> = with_jobs
            .par_iter()
            .map(|&e| (e, PreparedEntity::new(&inputs[&e], &settings)))
            .collect();
        let built: Vec<(Entity, usize, EntityView)> = jobs
            .par_iter()
            .map(|&(e, k)| {
                let view = build_entity_view(
                    &inputs[&e],
                    &prepared[&e],
                    &views[k],
                    &occluders[k],
                    &settings,
                );
                (e, k, view)
            })
            .collect();
        rebuilt += built.len() as u64;
        for (e, k, view) in built {
            let view = Arc::new(view);
            let current = world.get::<EntityViews>(e).cloned();
            let mut next = current.unwrap_or_else(|| {
                EntityViews(std::array::from_fn(|_| {
                    Arc::new(EntityView {
                        id: inputs[&e].id.clone(),
                        lines: Vec::new(),
                    })
                }))
            });
            next.0[k] = view;
            world.entity_mut(e).insert(next);
        }
        world.entity_mut(vessel).insert(VesselViews {
            projections: views,
            settings,
            footprints: new_footprints,
        });
    }
    world.resource_mut::<WorkCounters>().views_rebuilt += rebuilt;
}
