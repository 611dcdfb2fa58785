//! The coverage pipeline end to end: scenario → coverage → route → report, and the files that
//! present it. Computing and rendering are separate; writing is the caller's.

use std::time::Instant;

use crate::coverage::drape::GroundPoint;
use crate::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
use crate::error::Fault;
use crate::mission::plan_geojson::plan_geojson;
use crate::model::Scenario;
use crate::plot::map_svg::plan_svg;
use crate::report::Report;
use crate::sequence::{route, Route, Sequencer, TransferModel};

/// Everything a coverage plan is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PlanSettings {
    pub coverage: CoverageSettings,
    pub sequencer: Sequencer,
    /// Launch point in planning metres; `None`: a `launch` or `supply` marker of the field
    /// file, else a free start.
    pub start: Option<[f64; 2]>,
}

/// The start point of the flight: the given one, else the field file's `launch`/`supply`
/// marker, else none (free start).
pub fn start_point(
    scenario: &Scenario,
    settings: &PlanSettings,
) -> Result<Option<GroundPoint>, Fault> {
    let position = settings.start.or_else(|| {
        scenario
            .farm
            .markers
            .iter()
            .find(|marker| matches!(marker.kind.as_str(), "launch" | "supply" | "start"))
            .map(|marker| [marker.position.x, marker.position.y])
    });
    position
        .map(|[x, y]| {
            Ok(GroundPoint {
                x,
                y,
                ground_m: scenario.terrain.height_m(x, y)?,
            })
        })
        .transpose()
}

/// A planned coverage mission.
pub struct PlannedMission {
    pub coverage: CoveragePlan,
    pub route: Route,
    pub report: Report,
}

/// Plans the scenario's fields with `settings`.
pub fn plan_mission(scenario: &Scenario, settings: &PlanSettings) -> Result<PlannedMission, Fault> {
    let started = Instant::now();
    let start = start_point(scenario, settings)?;
    let coverage = plan_coverage(
        &scenario.farm,
        scenario.terrain.as_ref(),
        &scenario.vehicle,
        &settings.coverage,
    )?;
    let model = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
    let route = route(&coverage, &model, start, &settings.sequencer);
    let runtime_s = crate::report::round(started.elapsed().as_secs_f64(), 1e-4);
    let report = Report::new(scenario, &coverage, &route, settings, runtime_s);
    Ok(PlannedMission {
        coverage,
        route,
        report,
    })
}

/// The files of a plan folder, by name.
pub fn render(scenario: &Scenario, mission: &PlannedMission) -> Vec<(&'static str, Vec<u8>)> {
    let geojson = plan_geojson(
        &scenario.farm,
        &mission.coverage,
        &mission.route,
        scenario.vehicle.spray_height_m,
        scenario.vehicle.safe_height_m,
    );
    let title = format!(
        "{} — {} fields, swath {} m, {:.0} m sprayed, {:.1}% covered",
        scenario.name,
        scenario.farm.fields.len(),
        scenario.vehicle.swath_width_m,
        mission.report.spray_length_m + mission.report.edge_length_m,
        100.0 * mission.report.covered_fraction
    );
    vec![
        (
            "plan.geojson",
            (serde_json::to_string_pretty(&geojson).expect("JSON value") + "\n").into_bytes(),
        ),
        (
            "report.json",
            (serde_json::to_string_pretty(&mission.report).expect("report serialises") + "\n")
                .into_bytes(),
        ),
        (
            "plan.svg",
            plan_svg(&scenario.farm, &mission.coverage, &mission.route, &title).into_bytes(),
        ),
    ]
}
