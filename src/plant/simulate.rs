//! Operating simulation on a plant model: ticks of random valid edits (dimension
//! changes, nozzle moves, head swaps) and liquid-level changes, each tick followed
//! by one incremental update of the model.
//!
//! Drives [`Model`] from outside the data flow, like a user or a process
//! historian would. A tick's edits are drawn in rounds on distinct vessels and
//! go through [`Model::apply_each`]'s checks (in parallel); one the rules refuse
//! is counted and replaced by another draw, so every applied edit is valid. The
//! simulation keeps its own copy of each vessel's design to draw edits from,
//! updated only when an edit is accepted; with the same seed, the same plant
//! sees the same edits.

use std::collections::HashMap;
use std::time::{Duration, Instant};

use bevy_ecs::entity::Entity;

use super::rng::SplitMix64;
use crate::components::OperatingState;
use crate::components::VesselSpec;
use crate::design::{Design, OperatingDesign, PartDesign, VesselDesign};
use crate::model::{Edit, Model};
use crate::systems::{STAGES, WorkCounters};

/// Draws tried for one edit before the tick moves on without it.
const MAX_TRIES: usize = 16;

/// What one tick did.
#[derive(Clone, Copy, Debug, Default)]
pub struct TickReport {
    /// Wall time of the tick: drawing and checking the edits, and the update.
    pub latency: Duration,
    /// Of which the update (the rest is drawing and checking the edits).
    pub update: Duration,
    /// Edits applied.
    pub edits: usize,
    /// Drawn edits the rules refused (redrawn).
    pub refused: usize,
    /// Liquid levels changed.
    pub levels: usize,
    /// Work done by the update.
    pub counters: WorkCounters,
    /// Of the update, each stage's time (Validate, Constrain, Geometry,
    /// Tessellate, Project, Export).
    pub stages: [Duration; STAGES],
}

/// A plant model under simulation.
pub struct Simulation {
    model: Model,
    vessels: Vec<VesselDesign>,
    entities: Vec<Entity>,
    rng: SplitMix64,
}

impl Simulation {
    /// A simulation of `model`, which holds `design`, drawing from `seed`.
    pub fn new(model: Model, design: &Design, seed: u64) -> Self {
        let mut model = model;
        let by_tag: HashMap<String, Entity> = {
            let mut q = model.query::<(Entity, &VesselSpec)>();
            let world = model.world();
            q.iter(world).map(|(e, s)| (s.tag.clone(), e)).collect()
        };
        let vessels = design.vessels.clone();
        let entities = vessels
            .iter()
            .map(|v| by_tag.get(&v.tag).copied().unwrap_or(Entity::PLACEHOLDER))
            .collect();
        Self {
            model,
            vessels,
            entities,
            rng: SplitMix64::new(seed),
        }
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The model, mutably.
    pub fn model_mut(&mut self) -> &mut Model {
        &mut self.model
    }

    /// One tick: `edits` random valid edits and `levels` level changes, then one
    /// update.
    pub fn tick(&mut self, edits: usize, levels: usize) -> TickReport {
        let start = Instant::now();
        let mut report = TickReport::default();
        (report.edits, report.refused) = self.apply_random_edits(edits);
        for _ in 0..levels {
            report.levels += usize::from(self.change_level());
        }
        let update = Instant::now();
        report.counters = self.model.update();
        report.update = update.elapsed();
        report.stages = self.model.stage_times();
        report.latency = start.elapsed();
        report
    }

    /// Draws and applies `count` random valid edits; returns how many were
    /// applied and how many drawn edits the rules refused (each redrawn, within
    /// `MAX_TRIES` draws per edit in all).
    ///
    /// Edits are drawn in rounds, each on vessels no other edit of the round
    /// touches (a vessel drawn twice ends the round: its next edit is drawn from
    /// the design the first one leaves), and each round is checked in parallel
    /// by [`Model::apply_each`].
    pub fn apply_random_edits(&mut self, count: usize) -> (usize, usize) {
        let (mut applied, mut refused) = (0, 0);
        let mut draws = count * MAX_TRIES;
        while applied < count && draws > 0 {
            let mut round: Vec<(usize, Edit)> = Vec::new();
            let mut edits = Vec::new();
            while applied + round.len() < count && draws > 0 {
                draws -= 1;
                let i = self.rng.int(0, self.vessels.len() as u64 - 1) as usize;
                if round.iter().any(|(j, _)| *j == i) {
                    break;
                }
                if let Some(edit) = draw_edit(&mut self.rng, &self.vessels[i]) {
                    round.push((i, edit.clone()));
                    edits.push(edit);
                }
            }
            for ((i, edit), outcome) in round.into_iter().zip(self.model.apply_each(edits)) {
                if outcome.is_ok() {
                    after_edit(&mut self.vessels[i], &edit);
                    applied += 1;
                } else {
                    refused += 1;
                }
            }
        }
        (applied, refused)
    }

    /// Moves one random vessel's liquid level by up to ±10 % of its interior's
    /// height (kept within it); returns whether it changed.
    pub fn change_level(&mut self) -> bool {
        let i = self.rng.int(0, self.vessels.len() as u64 - 1) as usize;
        let Some(state) = self.model.world().get::<OperatingState>(self.entities[i]) else {
            return false;
        };
        let height = state.interior_height;
        let old = self.vessels[i].operating.unwrap_or(OperatingDesign {
            liquid_level: 0.0,
            liquid_density: None,
        });
        let level = (old.liquid_level + self.rng.range(-0.1, 0.1) * height)
            .clamp(0.0, height)
            .round()
            .min(height.floor());
        let operating = Some(OperatingDesign {
            liquid_level: level,
            ..old
        });
        let edit = Edit::SetOperating {
            vessel: self.vessels[i].tag.clone(),
            operating,
        };
        if self.model.apply(edit).is_ok() {
            self.vessels[i].operating = operating;
            true
        } else {
            false
        }
    }

    /// Total operating mass of the plant (metal + liquid of every vessel), kg.
    pub fn total_operating_mass(&self) -> f64 {
        let world = self.model.world();
        self.entities
            .iter()
            .filter_map(|&e| world.get::<OperatingState>(e))
            .map(|s| s.operating_mass)
            .sum()
    }
}

/// A random edit of `vessel`: a course's length or diameter, a nozzle's
/// elevation, orientation or projection, or a head's shape. `None` when the
/// vessel has nothing of the drawn kind. Only the edited part or nozzle is
/// copied; [`after_edit`] brings a copy of the design up to date once the edit
/// is accepted.
pub fn draw_edit(rng: &mut SplitMix64, vessel: &VesselDesign) -> Option<Edit> {
    let v = vessel;
    let roll = rng.unit();
    if roll < 0.35 {
        // A dimension: a course's length (mostly) or diameter.
        let shells: Vec<usize> = (0..v.parts.len())
            .filter(|&i| matches!(v.parts[i], PartDesign::Shell(_)))
            .collect();
        let i = *rng.pick(&shells);
        let mut part = v.parts[i].clone();
        let PartDesign::Shell(s) = &mut part else {
            return None;
        };
        if rng.chance(0.8) {
            s.length += rng.pick(&[-200.0, -100.0, 100.0, 200.0]);
        } else {
            s.od += rng.pick(&[-100.0, 100.0]);
        }
        Some(Edit::SetPart {
            vessel: v.tag.clone(),
            part,
        })
    } else if roll < 0.85 {
        // A shell nozzle's move (a head nozzle on the pole is left alone: turning
        // it there moves its opening across the head's seam, which the opening
        // cutter does not support).
        let shell: Vec<usize> = (0..v.nozzles.len())
            .filter(|&i| v.nozzles[i].elevation.is_some())
            .collect();
        if shell.is_empty() {
            return None;
        }
        let i = *rng.pick(&shell);
        let mut n = v.nozzles[i].clone();
        match (rng.int(0, 2), n.elevation) {
            (0, Some(z)) => n.elevation = Some(z + rng.pick(&[-100.0, 100.0])),
            (1, _) => n.orientation = (n.orientation + rng.pick(&[-15.0, 15.0])).rem_euclid(360.0),
            _ => n.projection += rng.pick(&[-50.0, 50.0]),
        }
        Some(Edit::SetNozzle {
            vessel: v.tag.clone(),
            nozzle: n,
        })
    } else {
        // A head swap, on a head no nozzle is mounted on (a nozzle's opening may
        // not fit every head shape, e.g. across a conical head's apex).
        let heads: Vec<usize> = (0..v.parts.len())
            .filter(|&i| matches!(v.parts[i], PartDesign::Head(_)))
            .filter(|&i| !v.nozzles.iter().any(|n| n.host == v.parts[i].id()))
            .collect();
        if heads.is_empty() {
            return None;
        }
        let i = *rng.pick(&heads);
        let mut part = v.parts[i].clone();
        let PartDesign::Head(h) = &mut part else {
            return None;
        };
        let shape = *rng.pick(&super::generate::SHAPES);
        if shape == h.shape {
            return None;
        }
        h.shape = shape;
        h.ratio = None;
        h.crown_radius = None;
        h.knuckle_radius = None;
        h.half_angle = None;
        h.small_od = None;
        Some(Edit::SetPart {
            vessel: v.tag.clone(),
            part,
        })
    }
}

/// Brings `vessel` up to date with an accepted edit of a part or a nozzle
/// (as [`draw_edit`] draws): the one with the same id or mark replaced.
pub fn after_edit(vessel: &mut VesselDesign, edit: &Edit) {
    match edit {
        Edit::SetPart { part, .. } => {
            if let Some(slot) = vessel.parts.iter_mut().find(|p| p.id() == part.id()) {
                *slot = part.clone();
            }
        }
        Edit::SetNozzle { nozzle, .. } => {
            if let Some(slot) = vessel.nozzles.iter_mut().find(|n| n.mark == nozzle.mark) {
                *slot = nozzle.clone();
            }
        }
        _ => {}
    }
}

/// The `q`-quantile (0–1) of `samples` (sorted in place); zero when empty.
pub fn quantile(samples: &mut [Duration], q: f64) -> Duration {
    if samples.is_empty() {
        return Duration::ZERO;
    }
    samples.sort_unstable();
    let rank = ((samples.len() - 1) as f64 * q).round() as usize;
    samples[rank]
}
