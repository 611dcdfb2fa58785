//! What a coverage plan is asked for: one value the CLI, a scenario or a library user fills
//! in, and every stage reads its part of.

use crate::coverage::CoverageSettings;
use crate::mission::flight::MissionSettings;
use crate::sequence::Sequencer;
use crate::sortie::SortieSettings;
use crate::supply::SupplyRequest;

/// Everything a coverage plan is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PlanSettings {
    /// How coverage is laid out.
    pub coverage: CoverageSettings,
    /// How the passes are ordered.
    pub sequencer: Sequencer,
    /// The supply point given (`--start`, `--supply X,Y`) in planning metres: the drone
    /// takes off, refills and lands there. `None`: as [`PlanSettings::supply`] says.
    pub start: Option<[f64; 2]>,
    /// How the supply point is chosen when none is given: the field file's launch marker, else
    /// `auto` when the plan has sorties (the default), or `auto` whatever the file marks.
    pub supply: SupplyRequest,
    /// How the route is split into sorties.
    pub sorties: SortieSettings,
    /// What the mission files are written with.
    pub mission: MissionSettings,
}
