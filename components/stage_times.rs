//! The wall time each stage of the last run took ([`StageTimes`], stamped by
//! `systems::stamp_stage`), for the breakdown `vesselcad bench` prints.

use std::time::{Duration, Instant};

use bevy_ecs::resource::Resource;

/// Number of stages timed (Validate, Constrain, Geometry, Tessellate, Project,
/// Export).
pub const STAGES: usize = 6;

/// When each stage of the last run ended (index 0: when the run started).
#[derive(Resource, Clone, Copy, Debug, Default)]
pub struct StageTimes {
    marks: [Option<Instant>; STAGES + 1],
}

impl StageTimes {
    /// Stamps mark `k` now (the end of stage `k`, or the start of the run for 0).
    pub(crate) fn stamp(&mut self, k: usize) {
        self.marks[k] = Some(Instant::now());
    }

    /// Durations of the stages in the last run, in schedule order (zero for a
    /// stage not timed).
    pub fn durations(&self) -> [Duration; STAGES] {
        std::array::from_fn(|k| match (self.marks[k], self.marks[k + 1]) {
            (Some(a), Some(b)) => b.saturating_duration_since(a),
            _ => Duration::ZERO,
        })
    }
}
