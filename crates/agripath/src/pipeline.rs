//! The coverage pipeline end to end: scenario → coverage → route → report, and the files that
//! present it. Computing and rendering are separate; writing is the caller's.

use std::time::Instant;

use crate::coverage::drape::GroundPoint;
use crate::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
use crate::error::Fault;
use crate::mission::csv::waypoints_csv;
use crate::mission::flight::{build_missions, MissionSettings};
use crate::mission::kml::mission_kml;
use crate::mission::plan_geojson::plan_geojson;
use crate::mission::{qgc_plan, wpl};
use crate::model::{CoordinateSystem, Scenario};
use crate::plot::map_svg::{plan_svg, Underlay};
use crate::plot::plan_html::{plan_html, Overlay};
use crate::plot::raster::svg_to_png;
use crate::report::Report;
use crate::sequence::{route, Route, Sequencer, TransferModel};
use crate::sortie::route::{RoutePoint, Speeds, WorkRoute};
use crate::sortie::{plan_sorties, SortieModel, SortiePlan, SortiePlanner};
use crate::terrain::hillshade::hillshade;
use crate::terrain::Extent;

/// Everything a coverage plan is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct PlanSettings {
    pub coverage: CoverageSettings,
    pub sequencer: Sequencer,
    /// Launch point in planning metres; `None`: a `launch` or `supply` marker of the field
    /// file, else a free start.
    pub start: Option<[f64; 2]>,
    pub sorties: SortieSettings,
    pub mission: MissionSettings,
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
    /// The costs and limits the split was made with (return legs, service times).
    pub model: SortieModel,
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
    pub settings: PlanSettings,
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
        model,
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
        settings: *settings,
    })
}

/// The hillshade under the plan: the farm's box with a margin, heights exaggerated so that
/// low relief still shows ((50 m / relief) clamped to 1..10).
pub fn terrain_overlay(scenario: &Scenario) -> (Extent, Vec<u8>) {
    let bounds = scenario.farm.bounds();
    let margin = 0.05 * bounds.width().max(bounds.height()) + 10.0;
    let extent = Extent {
        min_x: bounds.min().x - margin,
        min_y: bounds.min().y - margin,
        max_x: bounds.max().x + margin,
        max_y: bounds.max().y + margin,
    };
    let relief = scenario
        .terrain
        .height_range_m(extent)
        .map_or(0.0, |(low, high)| high - low);
    let exaggeration = (50.0 / relief.max(1e-9)).clamp(1.0, 10.0);
    let shaded = hillshade(scenario.terrain.as_ref(), extent, 1024, exaggeration);
    (extent, shaded.to_png())
}

/// The files of a plan folder, by name: the contract files (`plan.geojson`, `report.json`),
/// the maps (`plan.svg`, `plan.html`, `terrain.png`) and the mission files (per sortie
/// `sortie_NN.plan` and `sortie_NN.waypoints`, `mission.kml`, `waypoints.csv`).
pub fn render(
    scenario: &Scenario,
    mission: &PlannedMission,
) -> Result<Vec<(String, Vec<u8>)>, Fault> {
    let vehicle = &scenario.vehicle;
    let geojson = plan_geojson(
        &scenario.farm,
        &mission.coverage,
        &mission.route,
        mission.sorties.as_ref(),
        vehicle.spray_height_m,
        vehicle.safe_height_m,
    );
    let title = format!(
        "{} — {} fields, swath {} m, {:.0} m sprayed, {:.1}% covered",
        scenario.name,
        scenario.farm.fields.len(),
        vehicle.swath_width_m,
        mission.report.spray_length_m + mission.report.edge_length_m,
        100.0 * mission.report.covered_fraction
    );
    let json = |value: &serde_json::Value| {
        (serde_json::to_string_pretty(value).expect("JSON value") + "\n").into_bytes()
    };
    let mut files = vec![
        ("plan.geojson".to_string(), json(&geojson)),
        (
            "report.json".to_string(),
            (serde_json::to_string_pretty(&mission.report).expect("report serialises") + "\n")
                .into_bytes(),
        ),
    ];
    // The viewer draws in plan metres: the same features in the local frame.
    let mut local_farm = scenario.farm.clone();
    local_farm.coordinate_system = CoordinateSystem::Local;
    let local = plan_geojson(
        &local_farm,
        &mission.coverage,
        &mission.route,
        mission.sorties.as_ref(),
        vehicle.spray_height_m,
        vehicle.safe_height_m,
    );
    let (extent, png) = terrain_overlay(scenario);
    let underlay = Underlay {
        png: &png,
        min_x: extent.min_x,
        min_y: extent.min_y,
        max_x: extent.max_x,
        max_y: extent.max_y,
    };
    let map = plan_svg(
        &scenario.farm,
        &mission.coverage,
        &mission.route,
        mission.sorties.as_ref(),
        Some(&underlay),
        &title,
    );
    files.push((
        "plan.png".to_string(),
        svg_to_png(&map, 1600).map_err(Fault::Structure)?,
    ));
    files.push(("plan.svg".to_string(), map.into_bytes()));
    let overlay = Overlay {
        png: &png,
        min_x: extent.min_x,
        min_y: extent.min_y,
        max_x: extent.max_x,
        max_y: extent.max_y,
    };
    files.push((
        "plan.html".to_string(),
        plan_html(&title, &local, Some(&overlay)).into_bytes(),
    ));
    let settings = &mission.settings.mission;
    let missions = build_missions(scenario, mission, settings)?;
    for sortie in &missions {
        let name = format!("sortie_{:02}", sortie.sortie + 1);
        files.push((
            format!("{name}.plan"),
            qgc_plan::plan_file(
                sortie,
                &scenario.farm,
                settings,
                vehicle.transit_speed_mps,
                vehicle.spray_speed_mps,
            )
            .into_bytes(),
        ));
        files.push((
            format!("{name}.waypoints"),
            wpl::waypoints_file(sortie, settings).into_bytes(),
        ));
    }
    files.push((
        "mission.kml".to_string(),
        mission_kml(&scenario.name, &scenario.farm, &missions, settings).into_bytes(),
    ));
    files.push((
        "waypoints.csv".to_string(),
        waypoints_csv(&missions).into_bytes(),
    ));
    files.push(("terrain.png".to_string(), png));
    Ok(files)
}
