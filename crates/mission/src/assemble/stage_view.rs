//! The lower stages of a multi-stage mission (`[[stages]]`) seen as missions of their own: a
//! stage's `[rocket]` and `[motor]` put in the place of the top stage's, so that every builder
//! of a single-stage rocket builds it, and the errors found there named by the stage's keys
//! (`stages.<index>.rocket...`). The orchestration of the stages' flights is
//! [`super::stages`]'s; this module is what the builders below it need to know of stages.

use crate::schema::StageSpec;
use crate::{Mission, MissionError};

/// The name of lower stage `index` in reports.
pub(crate) fn stage_name(stage: &StageSpec, index: usize) -> String {
    stage
        .name
        .clone()
        .unwrap_or_else(|| format!("stage {}", index + 2))
}

/// The name of the top stage in reports.
pub const TOP_STAGE: &str = "sustainer";

/// `mission` with lower stage `index` as its `[rocket]` and `[motor]` (the top stage's motor
/// when the stage has none), its keys located at the stage's.
pub(crate) fn stage_mission(mission: &Mission, index: usize) -> Mission {
    let stage = &mission.spec.stages[index];
    let mut spec = mission.spec.clone();
    spec.rocket = stage.rocket.clone();
    if let Some(motor) = &stage.motor {
        spec.motor = motor.clone();
    }
    spec.stages.clear();
    mission.part(spec, &stage_prefix(index), STAGE_ROOTS)
}

/// The tables of a `[[stages]]` entry built as a mission's own.
const STAGE_ROOTS: &[&str] = &["rocket", "motor"];

/// The key prefix of `[[stages]]` entry `index`.
fn stage_prefix(index: usize) -> String {
    format!("stages.{index}.")
}

/// An error found while building stage `index` from its own mission, named by the stage's key.
pub(crate) fn in_stage(error: MissionError, index: usize) -> MissionError {
    error.in_part(&stage_prefix(index), STAGE_ROOTS)
}
