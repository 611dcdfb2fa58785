//! What a coverage plan is asked for: one value the CLI, a scenario or a library user fills
//! in, and every stage reads its part of.

use crate::coverage::CoverageSettings;
use crate::mission::flight::MissionSettings;
use crate::sequence::Sequencer;
use crate::sortie::SortieSettings;

/// Everything a coverage plan is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PlanSettings {
    /// How coverage is laid out.
    pub coverage: CoverageSettings,
    /// How the passes are ordered.
    pub sequencer: Sequencer,
    /// Launch point in planning metres; `None`: a `launch` or `supply` marker of the field
    /// file, else a free start.
    pub start: Option<[f64; 2]>,
    /// How the route is split into sorties.
    pub sorties: SortieSettings,
    /// What the mission files are written with.
    pub mission: MissionSettings,
}
