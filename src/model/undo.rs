//! Undoing committed edits whose geometry cannot be built.
//!
//! The rules are checked before an edit is written (`staging`), but whether a
//! part can be meshed is only known once the schedule has run. [`Undo`] records,
//! before each commit, what every vessel the edit touches was at the last
//! update that built (its design and order, or that it did not exist): the
//! first record of a vessel wins, so edits applied one after another between
//! two updates all roll back together. If the run that follows reports a
//! failure, [`Undo::staged`] gives the staged edit that puts those vessels
//! back, so that a refused update leaves the model as it was, geometry
//! included. Recording reads only the vessels an edit touches.

use std::collections::BTreeMap;

use bevy_ecs::world::World;

use super::read;
use super::staging::{Staged, StagedVessel};
use crate::components::DesignOrder;
use crate::components::VesselIndex;
use crate::constraints::resolve_vessel;
use crate::design::VesselDesign;

/// What the touched vessels were at the last update that built.
#[derive(Default)]
pub(crate) struct Undo(BTreeMap<String, Option<(VesselDesign, u32)>>);

impl Undo {
    /// Records the vessels `staged` writes or removes, as the world holds them,
    /// unless an earlier edit since the last update recorded them already.
    pub(crate) fn record(&mut self, world: &World, staged: &Staged) {
        let index = &world.resource::<VesselIndex>().0;
        for s in &staged.0 {
            let tag = match s {
                StagedVessel::Put { design, .. } => &design.tag,
                StagedVessel::Remove { tag } => tag,
            };
            if self.0.contains_key(tag) {
                continue;
            }
            let was = index.get(tag).and_then(|&e| {
                let order = world.get::<DesignOrder>(e).map_or(0, |o| o.0);
                Some((read::vessel(world, e)?, order))
            });
            self.0.insert(tag.clone(), was);
        }
    }

    /// Whether no vessel was recorded (nothing to put back).
    pub(crate) fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The staged edit that puts every recorded vessel back. Each was valid
    /// when recorded, so resolving it again cannot fail; one that somehow
    /// does is left as the failed edit wrote it.
    pub(crate) fn staged(self) -> Staged {
        Staged(
            self.0
                .into_iter()
                .filter_map(|(tag, was)| match was {
                    None => Some(StagedVessel::Remove { tag }),
                    Some((design, order)) => {
                        resolve_vessel(&design, order as usize)
                            .ok()
                            .map(|resolved| StagedVessel::Put {
                                design: Box::new(design),
                                order,
                                resolved: Box::new(resolved),
                            })
                    }
                })
                .collect(),
        )
    }
}
