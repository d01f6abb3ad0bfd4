//! Stage clock: the wall time each stage of the last run took, for the
//! breakdown `vesselcad bench` prints of where an edit's time goes.
//!
//! A tiny system runs before the first stage and after each one, stamping the
//! time into [`StageTimes`]; the differences are the stages' durations. It costs
//! a clock read per stage, nothing per entity.

use bevy_ecs::system::ResMut;

use crate::components::StageTimes;

/// Stamps mark `K` (the end of stage `K`, or the start of the run for 0).
pub fn stamp_stage<const K: usize>(mut times: ResMut<StageTimes>) {
    times.stamp(K);
}
