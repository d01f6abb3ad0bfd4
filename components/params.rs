//! Parameter components: what a designer sets. Each wraps the design-file type of
//! its entity kind; systems only read them.

use bevy_ecs::component::Component;

use crate::design::{
    DesignConditions, DrawingInfo, NoteDesign, NozzleDesign, OperatingDesign, PartDesign,
    Placement, VesselDesign, VesselKind,
};

/// A vessel's own parameters (its parts, nozzles and notes are child entities).
#[derive(Component, Clone, Debug, PartialEq)]
pub struct VesselSpec {
    /// Unique tag.
    pub tag: String,
    /// Kind.
    pub kind: VesselKind,
    /// Placement in the plant.
    pub placement: Placement,
    /// Design conditions.
    pub design: DesignConditions,
    /// Title-block data of its drawing.
    pub drawing: DrawingInfo,
}

impl VesselSpec {
    /// Whether these are `design`'s own parameters (its children and operating
    /// data aside), compared in place.
    pub fn holds(&self, design: &VesselDesign) -> bool {
        self.tag == design.tag
            && self.kind == design.kind
            && self.placement == design.placement
            && self.design == design.design
            && self.drawing == design.drawing
    }
}

/// Whether `children` (each child's parameters with its design order), taken in
/// design order, are exactly `wanted`.
pub fn same_in_order<'a, D: PartialEq + 'a>(
    children: impl Iterator<Item = (&'a D, DesignOrder)>,
    wanted: &[D],
) -> bool {
    let mut have: Vec<(&D, DesignOrder)> = children.collect();
    if have.len() != wanted.len() {
        return false;
    }
    have.sort_by_key(|(_, o)| *o);
    have.iter().zip(wanted).all(|((h, _), w)| *h == w)
}

/// A vessel's operating state (liquid level and density), its own component so
/// that a level change re-resolves nothing: only the operating figures follow.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct OperatingSpec(pub Option<OperatingDesign>);

/// Position of an entity in its list in the design file (vessels in the plant;
/// parts, nozzles and notes in their vessel), for stable, deterministic order.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct DesignOrder(pub u32);

/// A part's parameters.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct PartSpec(pub PartDesign);

/// A nozzle's parameters.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct NozzleSpec(pub NozzleDesign);

/// A note's parameters.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct NoteSpec(pub NoteDesign);
