//! A vessel's operating figures as components: kept by
//! `systems::update_operating_states`, computed by [`crate::operating`].

use std::ops::Deref;

use bevy_ecs::component::Component;

use crate::operating::{OperatingError, OperatingFigures};

/// The operating figures of a vessel (liquid volume and mass at its level, metal
/// mass, centre of gravity), read through `Deref` as [`OperatingFigures`].
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct OperatingState(pub OperatingFigures);

impl Deref for OperatingState {
    type Target = OperatingFigures;

    fn deref(&self) -> &OperatingFigures {
        &self.0
    }
}

/// Why a vessel has no [`OperatingState`] (a wall too thick for its shape, an
/// eccentric reducer in a horizontal vessel): kept on the vessel entity.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct OperatingProblem(pub OperatingError);
