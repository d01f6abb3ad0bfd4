//! Stage clock: the wall time each stage of the last run took, for the
//! breakdown `vesselcad bench` prints of where an edit's time goes.
//!
//! A tiny system runs before the first stage and after each one, stamping the
//! time into [`StageTimes`]; the differences are the stages' durations. It costs
//! a clock read per stage, nothing per entity.

use std::time::{Duration, Instant};

use bevy_ecs::resource::Resource;
use bevy_ecs::system::ResMut;

/// Number of stages timed (Validate, Constrain, Geometry, Tessellate, Project,
/// Export).
pub const STAGES: usize = 6;

/// When each stage of the last run ended (index 0: when the run started).
#[derive(Resource, Clone, Copy, Debug, Default)]
pub struct StageTimes {
    marks: [Option<Instant>; STAGES + 1],
}

impl StageTimes {
    /// Durations of the stages in the last run, in schedule order (zero for a
    /// stage not timed).
    pub fn durations(&self) -> [Duration; STAGES] {
        std::array::from_fn(|k| match (self.marks[k], self.marks[k + 1]) {
            (Some(a), Some(b)) => b.saturating_duration_since(a),
            _ => Duration::ZERO,
        })
    }
}

/// Stamps mark `K` (the end of stage `K`, or the start of the run for 0).
pub fn stamp_stage<const K: usize>(mut times: ResMut<StageTimes>) {
    times.marks[K] = Some(Instant::now());
}
