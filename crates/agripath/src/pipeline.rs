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
use crate::sortie::route::{RoutePoint, Speeds, WorkRoute};
use crate::sortie::{plan_sorties, SortieModel, SortiePlan, SortiePlanner};

/// Everything a coverage plan is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PlanSettings {
    pub coverage: CoverageSettings,
    pub sequencer: Sequencer,
    /// Launch point in planning metres; `None`: a `launch` or `supply` marker of the field
    /// file, else a free start.
    pub start: Option<[f64; 2]>,
    pub sorties: SortieSettings,
}

/// How the route is split into sorties (seed 003): the planner, or `None` for one flight
/// whatever the tank and battery; `seed` drives GSA.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SortieSettings {
    pub planner: Option<SortiePlanner>,
    pub seed: u64,
}

impl Default for SortieSettings {
    fn default() -> Self {
        Self {
            planner: Some(SortiePlanner::Exact),
            seed: 1,
        }
    }
}

/// A route split into sorties, with what the map and the mission need to draw it.
#[derive(Debug, Clone)]
pub struct PlannedSorties {
    pub plan: SortiePlan,
    /// Where the drone refills and swaps batteries: the launch point, else the first point
    /// of the route.
    pub supply: RoutePoint,
    /// The route as the planner saw it.
    pub work_route: WorkRoute,
    /// The index in `work_route` of each visit's first point.
    pub visit_offsets: Vec<usize>,
}

impl PlannedSorties {
    /// The sortie flying work-route point `index` (a return point belongs to the sortie it ends).
    pub fn sortie_at(&self, index: usize) -> usize {
        self.plan.breaks.partition_point(|&b| b < index)
    }
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
    pub sorties: Option<PlannedSorties>,
    pub report: Report,
}

/// Splits the route into sorties at the launch point (or the route's first point).
fn split_into_sorties(
    scenario: &Scenario,
    route: &Route,
    start: Option<GroundPoint>,
    settings: &SortieSettings,
) -> Result<Option<PlannedSorties>, Fault> {
    let Some(planner) = settings.planner else {
        return Ok(None);
    };
    let vehicle = &scenario.vehicle;
    let speeds = Speeds {
        spray_mps: vehicle.spray_speed_mps,
        turn_mps: vehicle.turn_speed_mps,
        transit_mps: vehicle.transit_speed_mps,
    };
    let work_route = WorkRoute::from_route(route, speeds);
    let Some(first) = work_route.points().first().copied() else {
        return Ok(None);
    };
    let supply = start.map_or(first, |point| RoutePoint {
        x: point.x,
        y: point.y,
        ground_m: point.ground_m,
    });
    // Returns fly at the safe height, as transfers that leave the field do (decision 0008).
    let model = SortieModel::new(vehicle, supply, 2.0 * vehicle.safe_height_m);
    let plan = plan_sorties(&work_route, &model, planner, settings.seed)?;
    let visit_offsets = route
        .visits
        .iter()
        .scan(0, |offset, visit| {
            let here = *offset;
            *offset += visit.points.len();
            Some(here)
        })
        .collect();
    Ok(Some(PlannedSorties {
        plan,
        supply,
        work_route,
        visit_offsets,
    }))
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
    let sorties = split_into_sorties(scenario, &route, start, &settings.sorties)?;
    let runtime_s = crate::report::round(started.elapsed().as_secs_f64(), 1e-4);
    let report = Report::new(
        scenario,
        &coverage,
        &route,
        sorties.as_ref(),
        settings,
        runtime_s,
    );
    Ok(PlannedMission {
        coverage,
        route,
        sorties,
        report,
    })
}

/// The files of a plan folder, by name.
pub fn render(scenario: &Scenario, mission: &PlannedMission) -> Vec<(&'static str, Vec<u8>)> {
    let geojson = plan_geojson(
        &scenario.farm,
        &mission.coverage,
        &mission.route,
        mission.sorties.as_ref(),
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
