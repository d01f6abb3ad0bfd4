//! Staging an edit: compute the new design of every vessel it touches, drop those
//! that come out unchanged, and check the rest against every rule — all before the
//! world is written. A refused edit returns here, with the world untouched.

use std::collections::{BTreeMap, HashMap};

use bevy_ecs::world::World;
use rayon::prelude::*;

use super::{Edit, ModelError, read};
use crate::components::DesignOrder;
use crate::components::VesselIndex;
use crate::constraints::{ResolvedVessel, resolve_vessel};
use crate::design::{DesignError, FORMAT, RuleViolation, VesselDesign, units};

/// One vessel to write or remove.
#[derive(Debug)]
pub(crate) enum StagedVessel {
    /// Create or update the vessel to this design at this order.
    Put {
        /// New design.
        design: Box<VesselDesign>,
        /// Position in the plant's vessel list.
        order: u32,
        /// The design resolved by the rules when the edit was checked, handed to
        /// the Validate stage so that it need not resolve it again.
        resolved: Box<ResolvedVessel>,
    },
    /// Remove the vessel.
    Remove {
        /// Its tag.
        tag: String,
    },
}

/// The checked outcome of an edit.
pub(crate) struct Staged(pub Vec<StagedVessel>);

/// Working copy of the vessels an edit touches.
struct Work<'w> {
    world: &'w World,
    /// tag → new state (`None` = removed), with its order.
    touched: BTreeMap<String, Option<(VesselDesign, u32)>>,
    next_order: u32,
}

impl Work<'_> {
    fn current(&mut self, tag: &str) -> Option<(VesselDesign, u32)> {
        if let Some(state) = self.touched.get(tag) {
            return state.clone();
        }
        let entity = *self.world.resource::<VesselIndex>().0.get(tag)?;
        let order = self.world.get::<DesignOrder>(entity).map_or(0, |o| o.0);
        Some((read::vessel(self.world, entity)?, order))
    }

    fn vessel(&mut self, tag: &str) -> Result<(VesselDesign, u32), ModelError> {
        self.current(tag).ok_or_else(|| ModelError::UnknownVessel {
            tag: tag.to_string(),
        })
    }

    fn put(&mut self, design: VesselDesign, order: u32) {
        self.touched
            .insert(design.tag.clone(), Some((design, order)));
    }

    fn apply(&mut self, edit: Edit) -> Result<(), ModelError> {
        match edit {
            Edit::ReplaceDesign(mut design) => {
                if design.format != FORMAT {
                    return Err(DesignError::Format {
                        found: design.format,
                        expected: FORMAT,
                    }
                    .into());
                }
                units::to_millimetres(&mut design);
                let mut seen: HashMap<String, usize> = HashMap::new();
                let mut dup = Vec::new();
                for (i, v) in design.vessels.iter().enumerate() {
                    if let Some(first) = seen.insert(v.tag.clone(), i) {
                        dup.push(RuleViolation {
                            path: format!("vessels[{i}].tag"),
                            entity: v.tag.clone(),
                            field: "tag".into(),
                            value: v.tag.clone(),
                            rule: format!("duplicate tag: already used by vessels[{first}]"),
                        });
                    }
                }
                if !dup.is_empty() {
                    return Err(DesignError::Invalid(dup).into());
                }
                let existing: Vec<String> = self
                    .world
                    .resource::<VesselIndex>()
                    .0
                    .keys()
                    .cloned()
                    .collect();
                for tag in existing {
                    if !seen.contains_key(&tag) {
                        self.touched.insert(tag, None);
                    }
                }
                for (i, v) in design.vessels.into_iter().enumerate() {
                    self.put(v, i as u32);
                }
                self.next_order = seen.len() as u32;
            }
            Edit::SetVessel(v) => {
                let order = match self.current(&v.tag) {
                    Some((_, o)) => o,
                    None => {
                        self.next_order += 1;
                        self.next_order - 1
                    }
                };
                self.put(v, order);
            }
            Edit::RemoveVessel { tag } => {
                self.vessel(&tag)?;
                self.touched.insert(tag, None);
            }
            Edit::MoveVessel { tag, placement } => {
                let (mut v, o) = self.vessel(&tag)?;
                v.placement = placement;
                self.put(v, o);
            }
            Edit::SetPart { vessel, part } => {
                let (mut v, o) = self.vessel(&vessel)?;
                let slot = v.parts.iter_mut().find(|p| p.id() == part.id());
                let Some(slot) = slot else {
                    return Err(ModelError::UnknownEntity {
                        vessel,
                        kind: "part",
                        id: part.id().to_string(),
                    });
                };
                *slot = part;
                self.put(v, o);
            }
            Edit::InsertPart {
                vessel,
                index,
                part,
            } => {
                let (mut v, o) = self.vessel(&vessel)?;
                let at = index.min(v.parts.len());
                v.parts.insert(at, part);
                self.put(v, o);
            }
            Edit::RemovePart { vessel, id } => {
                let (mut v, o) = self.vessel(&vessel)?;
                let before = v.parts.len();
                v.parts.retain(|p| p.id() != id);
                if v.parts.len() == before {
                    return Err(ModelError::UnknownEntity {
                        vessel,
                        kind: "part",
                        id,
                    });
                }
                self.put(v, o);
            }
            Edit::SetNozzle { vessel, nozzle } => {
                let (mut v, o) = self.vessel(&vessel)?;
                match v.nozzles.iter_mut().find(|n| n.mark == nozzle.mark) {
                    Some(slot) => *slot = nozzle,
                    None => v.nozzles.push(nozzle),
                }
                self.put(v, o);
            }
            Edit::RemoveNozzle { vessel, mark } => {
                let (mut v, o) = self.vessel(&vessel)?;
                let before = v.nozzles.len();
                v.nozzles.retain(|n| n.mark != mark);
                if v.nozzles.len() == before {
                    return Err(ModelError::UnknownEntity {
                        vessel,
                        kind: "nozzle",
                        id: mark,
                    });
                }
                self.put(v, o);
            }
            Edit::SetNote { vessel, note } => {
                let (mut v, o) = self.vessel(&vessel)?;
                match v.notes.iter_mut().find(|n| n.id == note.id) {
                    Some(slot) => *slot = note,
                    None => v.notes.push(note),
                }
                self.put(v, o);
            }
            Edit::RemoveNote { vessel, id } => {
                let (mut v, o) = self.vessel(&vessel)?;
                let before = v.notes.len();
                v.notes.retain(|n| n.id != id);
                if v.notes.len() == before {
                    return Err(ModelError::UnknownEntity {
                        vessel,
                        kind: "note",
                        id,
                    });
                }
                self.put(v, o);
            }
            Edit::SetOperating { vessel, operating } => {
                let (mut v, o) = self.vessel(&vessel)?;
                v.operating = operating;
                self.put(v, o);
            }
            Edit::Batch(edits) => {
                for e in edits {
                    self.apply(e)?;
                }
            }
        }
        Ok(())
    }
}

/// Stages and checks an edit against the world.
pub(crate) fn stage(world: &World, edit: Edit) -> Result<Staged, ModelError> {
    let next_order = world.resource::<VesselIndex>().0.len() as u32;
    let mut work = Work {
        world,
        touched: BTreeMap::new(),
        next_order,
    };
    work.apply(edit)?;
    let Work { touched, .. } = work;
    // Each touched vessel is compared and resolved on its own: in parallel (a
    // whole plant's design replaced resolves every vessel here), in order.
    let index = &world.resource::<VesselIndex>().0;
    let touched: Vec<(String, Option<(VesselDesign, u32)>)> = touched.into_iter().collect();
    let staged: Vec<Result<Option<StagedVessel>, Vec<RuleViolation>>> = touched
        .into_par_iter()
        .map(|(tag, state)| {
            let entity = index.get(&tag).copied();
            match state {
                None => Ok(entity.map(|_| StagedVessel::Remove { tag })),
                Some((design, order)) => {
                    // Compared with the world in place (it is not written until
                    // the edit is checked).
                    let unchanged = entity.is_some_and(|e| {
                        world.get::<DesignOrder>(e).map(|o| o.0) == Some(order)
                            && read::holds(world, e, &design)
                    });
                    if unchanged {
                        return Ok(None);
                    }
                    resolve_vessel(&design, order as usize).map(|resolved| {
                        Some(StagedVessel::Put {
                            design: Box::new(design),
                            order,
                            resolved: Box::new(resolved),
                        })
                    })
                }
            }
        })
        .collect();
    let mut out = Vec::new();
    let mut violations = Vec::new();
    for result in staged {
        match result {
            Ok(put) => out.extend(put),
            Err(mut v) => violations.append(&mut v),
        }
    }
    if violations.is_empty() {
        Ok(Staged(out))
    } else {
        Err(DesignError::Invalid(violations).into())
    }
}
