//! Undoing a committed edit whose geometry cannot be built.
//!
//! The rules are checked before an edit is written (`staging`), but whether a
//! part can be meshed is only known once the schedule has run. [`Undo`] records,
//! before the commit, what each vessel the edit touches was (its design and
//! order, or that it did not exist); if the run that follows reports a failure,
//! [`Undo::staged`] gives the staged edit that puts those vessels back, so that a
//! refused edit leaves the model as it was, geometry included.

use bevy_ecs::world::World;

use super::read;
use super::staging::{Staged, StagedVessel};
use crate::components::DesignOrder;
use crate::components::VesselIndex;
use crate::constraints::resolve_vessel;
use crate::design::VesselDesign;

/// What the touched vessels were before an edit.
pub(crate) struct Undo(Vec<(String, Option<(VesselDesign, u32)>)>);

impl Undo {
    /// Records the vessels `staged` writes or removes, as the world holds them.
    pub(crate) fn record(world: &World, staged: &Staged) -> Self {
        let index = &world.resource::<VesselIndex>().0;
        let before = staged
            .0
            .iter()
            .map(|s| {
                let tag = match s {
                    StagedVessel::Put { design, .. } => design.tag.clone(),
                    StagedVessel::Remove { tag } => tag.clone(),
                };
                let was = index.get(&tag).and_then(|&e| {
                    let order = world.get::<DesignOrder>(e).map_or(0, |o| o.0);
                    Some((read::vessel(world, e)?, order))
                });
                (tag, was)
            })
            .collect();
        Undo(before)
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
