//! The sampled sides of the patches openings trim, kept by
//! `systems::lay_out_regions` between runs (see that module for how they are
//! reused).

use std::sync::Arc;

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
use glam::DVec2;
use rustc_hash::FxHashMap;

use crate::mesh::{Notch, PatchSides};
use crate::nurbs::intersect::IntersectionLoop;
use crate::parts::Patch;

/// The sampled sides of every patch an opening trims (a host, with openings or
/// notches, or a nozzle neck) as last laid out, with the surface they were
/// sampled from (held, so the pointer compared cannot be reused) and the trim.
/// Cleared when the tessellation options change.
#[derive(Resource, Default, Debug)]
pub struct HostSides(pub(crate) FxHashMap<Entity, Laid>);

/// A trimmed patch's last layout: what it was laid out from, and its sides.
#[derive(Debug)]
pub(crate) struct Laid {
    pub surface: Arc<Patch>,
    pub sides: Arc<PatchSides>,
    pub trim: Trim,
}

impl HostSides {
    /// Heap bytes held by the kept sides (not the surfaces, which the patches
    /// hold, nor the loops, which the openings hold).
    pub fn heap_bytes(&self) -> usize {
        self.0.capacity() * std::mem::size_of::<(Entity, Laid)>()
            + self
                .0
                .values()
                .map(|l| l.sides.heap_bytes() + l.trim.heap_bytes())
                .sum::<usize>()
    }
}

/// How a patch is trimmed.
#[derive(Debug)]
pub(crate) enum Trim {
    /// A part or nozzle patch: holes of the openings it hosts, notches of those
    /// crossing its seams, and a nozzle neck's bottom loop.
    Patch {
        holes: Vec<Arc<IntersectionLoop>>,
        notches: Vec<Arc<[Notch]>>,
        bottom: Option<Arc<IntersectionLoop>>,
    },
    /// A reinforcing pad: between its outer loop and the neck's loop.
    Pad {
        outer: Arc<IntersectionLoop>,
        inner: Arc<IntersectionLoop>,
    },
}

impl Trim {
    /// Whether a layout within `self` reads the same numbers as one within
    /// `last`: the holes' host (u, v), the notches' paths and the bottom's neck
    /// (u, v), bit for bit (the layout reads nothing else of them), in order.
    pub(crate) fn lays_out_as(&self, last: &Trim) -> bool {
        let (
            Trim::Patch {
                holes,
                notches,
                bottom,
            },
            Trim::Patch {
                holes: last_holes,
                notches: last_notches,
                bottom: last_bottom,
            },
        ) = (self, last)
        else {
            return false;
        };
        let same_holes = holes.len() == last_holes.len()
            && holes
                .iter()
                .zip(last_holes)
                .all(|(a, b)| Arc::ptr_eq(a, b) || same_bits(&a.host_uv, &b.host_uv));
        let same_notches = notches.len() == last_notches.len()
            && notches.iter().zip(last_notches).all(|(a, b)| {
                Arc::ptr_eq(a, b)
                    || (a.len() == b.len()
                        && a.iter()
                            .zip(b.iter())
                            .all(|(x, y)| x.side == y.side && same_bits(&x.path, &y.path)))
            });
        let same_bottom = match (bottom, last_bottom) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b) || same_bits(&a.neck_uv, &b.neck_uv),
            (None, None) => true,
            _ => false,
        };
        same_holes && same_notches && same_bottom
    }

    /// Heap bytes of the trim's own lists (the loops are the openings').
    fn heap_bytes(&self) -> usize {
        match self {
            Trim::Patch { holes, notches, .. } => {
                holes.capacity() * std::mem::size_of::<Arc<IntersectionLoop>>()
                    + notches.capacity() * std::mem::size_of::<Arc<[Notch]>>()
            }
            Trim::Pad { .. } => 0,
        }
    }
}

/// Whether `a` and `b` hold the same points, bit for bit.
fn same_bits(a: &[DVec2], b: &[DVec2]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| p.x.to_bits() == q.x.to_bits() && p.y.to_bits() == q.y.to_bits())
}
