//! Operating figures of each vessel: liquid volume at its level, operating mass and
//! centre of gravity, kept as an `OperatingState` on the vessel entity.
//!
//! Runs after the Validate stage has resolved the dirty vessels: a vessel is redone
//! when it was resolved again (its parts, frame or conditions changed) or when its
//! `OperatingSpec` (level, liquid density) changed — a level change alone resolves
//! nothing else. The figures come from `operating::operating_state`, in parallel.

use bevy_ecs::change_detection::{DetectChanges, Ref};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::Children;
use bevy_ecs::system::{Commands, Query, Res, ResMut};
use glam::DAffine3;
use rayon::prelude::*;

use crate::components::{
    OperatingProblem, OperatingSpec, OperatingState, PartFrame, PartSpec, Shape, VesselFrame,
    VesselSpec,
};
use crate::components::{PendingResolutions, WorkCounters};
use crate::constraints::PartGeometry;
use crate::operating::{
    OperatingFigures, metal_density, operating_state, profile::StackPart, thickness,
};

/// What one vessel's figures are computed from.
struct Job {
    entity: Entity,
    spec: VesselSpec,
    operating: OperatingSpec,
    frame: DAffine3,
    /// (id, geometry, frame, thickness) of each stack part.
    parts: Vec<(String, PartGeometry, DAffine3, f64)>,
}

/// Recomputes the operating state of every vessel that was resolved in this run
/// or whose operating data changed; writes it only where it differs.
#[expect(clippy::type_complexity, reason = "one query per entity kind")]
pub fn update_operating_states(
    pending: Res<PendingResolutions>,
    vessels: Query<(
        Entity,
        &VesselSpec,
        Ref<OperatingSpec>,
        Option<&VesselFrame>,
        Option<&Children>,
    )>,
    parts: Query<(&PartSpec, Option<&Shape>, Option<&PartFrame>)>,
    current: Query<(Option<&OperatingState>, Option<&OperatingProblem>)>,
    mut commands: Commands,
    mut counters: ResMut<WorkCounters>,
) {
    let thickness_of = |children: Option<&Children>, id: &str| -> f64 {
        children
            .into_iter()
            .flatten()
            .filter_map(|&c| parts.get(c).ok())
            .find(|(spec, ..)| spec.0.id() == id)
            .and_then(|(spec, ..)| thickness(&spec.0))
            .unwrap_or(0.0)
    };
    let mut jobs: Vec<Job> = Vec::new();
    // Figures worked out while the vessel was checked, from the very inputs a
    // job would take.
    let mut known: Vec<(Entity, OperatingFigures)> = Vec::new();
    for (entity, resolved) in &pending.0 {
        let Ok((_, spec, operating, _, children)) = vessels.get(*entity) else {
            continue;
        };
        if let Some(k) = resolved.operating
            && k.data == operating.0
            && k.metal_density.to_bits() == metal_density(&spec.design).to_bits()
        {
            known.push((*entity, k.state));
            continue;
        }
        jobs.push(Job {
            entity: *entity,
            spec: spec.clone(),
            operating: *operating,
            frame: resolved.frame,
            parts: resolved
                .parts
                .iter()
                .map(|p| {
                    let t = thickness_of(children, &p.id);
                    (p.id.clone(), p.geometry.clone(), p.frame, t)
                })
                .collect(),
        });
    }
    let resolved: Vec<Entity> = pending.0.iter().map(|(e, _)| *e).collect();
    for (entity, spec, operating, frame, children) in &vessels {
        if !operating.is_changed() || resolved.contains(&entity) {
            continue;
        }
        let Some(frame) = frame else { continue };
        let stack = children
            .into_iter()
            .flatten()
            .filter_map(|&c| parts.get(c).ok())
            .filter_map(|(spec, shape, part_frame)| match (shape, part_frame) {
                (Some(Shape::Part(g)), Some(f)) => Some((
                    spec.0.id().to_string(),
                    g.clone(),
                    f.0,
                    thickness(&spec.0).unwrap_or(0.0),
                )),
                _ => None,
            })
            .collect();
        jobs.push(Job {
            entity,
            spec: spec.clone(),
            operating: *operating,
            frame: frame.0,
            parts: stack,
        });
    }
    counters.operating_updated += (jobs.len() + known.len()) as u64;
    let results: Vec<_> = jobs
        .par_iter()
        .map(|job| {
            let stack: Vec<StackPart> = job
                .parts
                .iter()
                .map(|(id, geometry, frame, thickness)| StackPart {
                    id,
                    geometry,
                    frame: *frame,
                    thickness: *thickness,
                })
                .collect();
            (
                job.entity,
                operating_state(
                    job.spec.kind,
                    job.frame,
                    &stack,
                    metal_density(&job.spec.design),
                    job.operating.0,
                ),
            )
        })
        .collect();
    let known = known.into_iter().map(|(e, state)| (e, Ok(state)));
    for (entity, result) in known.chain(results) {
        let Ok((state, problem)) = current.get(entity) else {
            continue;
        };
        match result {
            Ok(new) => {
                if state.map(|s| &s.0) != Some(&new) {
                    commands.entity(entity).insert(OperatingState(new));
                }
                if problem.is_some() {
                    commands.entity(entity).remove::<OperatingProblem>();
                }
            }
            Err(e) => {
                commands
                    .entity(entity)
                    .remove::<OperatingState>()
                    .insert(OperatingProblem(e));
            }
        }
    }
}
