//! The coverage pipeline end to end: scenario → coverage → route → report, and the files that
//! present it. Computing and rendering ([`render`]) are separate; writing is the caller's.

mod render;

pub use render::{
    is_mission_file, preflight_settings, render, render_flyable, terrain_overlay, Rendered,
};

use std::time::Instant;

use crate::coverage::drape::GroundPoint;
use crate::coverage::{plan_coverage, CoveragePlan};
use crate::error::Fault;
use crate::report::Report;
use crate::scenario::Scenario;
use crate::sequence::tour::{Start, Step};
use crate::sequence::{ordering_problem, route, route_of_tour, start_of, Route, TransferModel};
use crate::settings::PlanSettings;
use crate::sortie::joint::{starts, JointProblem, JointSettings};
use crate::sortie::route::{RoutePoint, Speeds, WorkRoute};
use crate::sortie::{plan_sorties, PlannedSorties, SortiePlanner, SortieSettings};
use crate::supply::evaluator::{plan_cost_s, FixedRouteSplit};
use crate::supply::{SupplyChoice, SupplyRequest, SupplySource};

/// What is wrong when the field file marks more than one launch point: `plan` needs
/// `--start` or `--supply` to choose (and `validate` notes it).
pub fn several_launch_points(farm: &crate::model::Farm) -> Option<String> {
    let names: Vec<&str> = farm
        .markers
        .iter()
        .filter(|marker| marker.is_launch())
        .map(|marker| marker.name.as_str())
        .collect();
    (names.len() > 1).then(|| {
        format!(
            "{} launch points ('{}'): keep one, or choose with --start X,Y or --supply auto|X,Y",
            names.len(),
            names.join("', '")
        )
    })
}

/// The start point the inputs give: the given one, else the field file's launch marker (a
/// point named or typed launch, home, takeoff, supply, base or start), else none (the supply
/// point is chosen by [`supply_point`], or the start is free). Two launch markers and no
/// `--start` are an error naming both. `--supply auto` ignores markers: none.
pub fn start_point(
    scenario: &Scenario,
    settings: &PlanSettings,
) -> Result<Option<GroundPoint>, Fault> {
    if settings.start.is_none() && matches!(settings.supply, SupplyRequest::Auto { .. }) {
        return Ok(None);
    }
    if let (None, Some(why)) = (settings.start, several_launch_points(&scenario.farm)) {
        return Err(Fault::Structure(why));
    }
    let launches: Vec<&crate::model::Marker> = scenario
        .farm
        .markers
        .iter()
        .filter(|marker| marker.is_launch())
        .collect();
    let position = settings.start.or_else(|| {
        launches
            .first()
            .map(|marker| [marker.position.x, marker.position.y])
    });
    position
        .map(|[x, y]| {
            // Farther than a farm is wide is not a launch point but a typo (or a swapped
            // lon/lat); the battery check would otherwise blame the vehicle.
            let away = scenario.farm.distance_outside_bounds_m(x, y);
            if away.is_nan() || away > crate::limits::MAX_FARM_EXTENT_M {
                return Err(Fault::InvalidValue {
                    what: "the launch point".into(),
                    value: format!("({x:.1}, {y:.1})"),
                    why: format!(
                        "it is {:.0} km from the fields (at most {:.0} km): is it in the fields' coordinates?",
                        away / 1000.0,
                        crate::limits::MAX_FARM_EXTENT_M / 1000.0
                    ),
                });
            }
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
    /// The swaths and edge passes of every field.
    pub coverage: CoveragePlan,
    /// The order the fields and passes are flown in, with the transfers between them.
    pub route: Route,
    /// The route split into sorties; `None` when no sortie planner is chosen or the route is empty.
    pub sorties: Option<PlannedSorties>,
    /// The figures of the plan, as `report.json` holds them.
    pub report: Report,
    /// The settings the mission was planned with.
    pub settings: PlanSettings,
}

pub use crate::mission::flight::battery::sortie_model;
use crate::mission::flight::battery::sortie_model_over;

/// The `joint` planner's route from the supply point (the launch point, else the first
/// point of the closed tour flown without one): the joint search of order and returns
/// ([`crate::sortie::joint`]) from the sequencer's open path and, when the supply search made
/// one, its closed tour ([`starts::of_paths`], which says why not the order from the supply
/// point).
fn joint_route(
    scenario: &Scenario,
    coverage: &CoveragePlan,
    model: &TransferModel,
    start: Option<GroundPoint>,
    closed_tour: Option<&[Step]>,
    settings: &PlanSettings,
) -> Result<Route, Fault> {
    let supply = start.or_else(|| {
        let free = route(coverage, model, Start::Closed, &settings.sequencer);
        free.visits.first().map(|visit| visit.points[0])
    });
    let Some(supply) = supply else {
        return Ok(route(coverage, model, start_of(start), &settings.sequencer));
    };
    let (problem, _) = ordering_problem(coverage, model, Start::Fixed(supply));
    // The same passes, numbered alike, with no supply point: its open path.
    let (open_problem, groups) = ordering_problem(coverage, model, Start::Open);
    let open = settings
        .sequencer
        .for_joint_start()
        .sequencer()
        .order(&open_problem, &groups);
    let vehicle = &scenario.vehicle;
    let points = crate::sequence::passes_of(coverage)
        .into_iter()
        .flat_map(|(_, points)| points.iter().copied());
    let mut sorties = sortie_model_over(vehicle, supply.into(), scenario.terrain.as_ref(), points)?;
    sorties.battery_reserve_s += settings.sorties.battery_margin_s;
    let joint = JointProblem::of_coverage(&problem, coverage, &sorties, Speeds::of(vehicle));
    let joint_settings = JointSettings {
        seed: settings.sorties.seed,
        ..JointSettings::default()
    };
    let starts = starts::of_paths(&problem, &open, closed_tour);
    let tour = crate::sortie::joint::improve(&joint, starts, &joint_settings);
    Ok(route_of_tour(coverage, model, &problem, &tour))
}

/// The supply point of the plan and the rule that chose it ([`crate::supply`]): the point
/// `given` by [`start_point`] (`given` or `marker`); else, when the plan has sorties or
/// `--supply auto` asks, the `auto` search over the route planned without a start point,
/// scored by [`FixedRouteSplit`]; else `None` (a free start).
pub fn supply_point(
    scenario: &Scenario,
    settings: &PlanSettings,
    coverage: &CoveragePlan,
    transfers: &TransferModel,
    given: Option<GroundPoint>,
) -> Result<Option<SupplyChoice>, Fault> {
    Ok(choose_supply(scenario, settings, coverage, transfers, given)?.choice)
}

/// Why a vehicle cannot stand at a supply point the operator gave, or `None`: in a field, a
/// hole or an obstacle, too far from the fields (decision 0016), or on ground `auto` would
/// not take as level (decisions 0029, 0036).
fn given_point_warning(scenario: &Scenario, point: GroundPoint) -> Option<String> {
    let place = geo::Coord {
        x: point.x,
        y: point.y,
    };
    crate::supply::standing::StandingRule::new(&scenario.farm)
        .why_not(&scenario.farm, place)
        .or_else(|| {
            let ground = |x: f64, y: f64| scenario.terrain.height_m(x, y).ok();
            crate::supply::level::unlevel(&ground, place)
                .map(|why| format!("{why}: a drone takes off and lands on level ground"))
        })
}

/// The supply point [`supply_point`] chooses, and the closed tour its `auto` search was scored
/// along (a start of the joint search, [`joint_route`]).
struct SupplyPlan {
    choice: Option<SupplyChoice>,
    closed_tour: Option<Vec<Step>>,
}

fn choose_supply(
    scenario: &Scenario,
    settings: &PlanSettings,
    coverage: &CoveragePlan,
    transfers: &TransferModel,
    given: Option<GroundPoint>,
) -> Result<SupplyPlan, Fault> {
    let chosen = |choice| SupplyPlan {
        choice,
        closed_tour: None,
    };
    let listed = match (given, settings.supply) {
        (Some(point), _) => {
            return Ok(chosen(Some(SupplyChoice {
                source: if settings.start.is_some() {
                    SupplySource::Given
                } else {
                    SupplySource::Marker
                },
                point,
                auto: None,
                standing_warning: given_point_warning(scenario, point),
            })))
        }
        (None, SupplyRequest::Auto { listed }) => listed,
        (None, SupplyRequest::FromInputs) if settings.sorties.planner.is_some() => 0,
        (None, SupplyRequest::FromInputs) => return Ok(chosen(None)),
    };
    let vehicle = &scenario.vehicle;
    // The flight will come back to the point being chosen: the route it is scored along is
    // the closed tour, flown open from and back to each candidate (decision 0018).
    let (problem, groups) = ordering_problem(coverage, transfers, Start::Closed);
    // Scored fast: the closed tour only places the candidates (the flight is ordered again
    // from the point chosen), and the demo's whole plan has 250 ms (decision 0018).
    let closed_tour = settings
        .sequencer
        .without_restarts()
        .sequencer()
        .order(&problem, &groups);
    let free = route_of_tour(coverage, transfers, &problem, &closed_tour);
    let work_route = WorkRoute::from_route(&free, Speeds::of(vehicle));
    let Some(&first) = work_route.points().first() else {
        return Ok(chosen(None));
    };
    let ground = |x: f64, y: f64| scenario.terrain.height_m(x, y).ok();
    let model = sortie_model(vehicle, first);
    if settings.sorties.planner.is_some() {
        // A tank too small for one step of the route: no place serves it, and the search's
        // "no place" would blame the battery.
        crate::sortie::step_over_tank(&work_route, model.spray_per_tank_m, model.endurance_s)?;
    }
    let evaluator = FixedRouteSplit::new(
        &work_route,
        model,
        settings.sorties.planner.is_some(),
        &ground,
    );
    // Level ground first (decision 0029); where none serves the route, any ground, with a
    // warning naming the slope.
    let level = crate::supply::level::OnLevelGround {
        inner: &evaluator,
        ground: &ground,
    };
    let mut slope_warning = None;
    let mut auto = crate::supply::choose_auto(&scenario.farm, &work_route, &level, listed)
        .or_else(|_| {
            let auto =
                crate::supply::choose_auto(&scenario.farm, &work_route, &evaluator, listed)?;
            // The search is a heuristic: on any ground it may still end on level ground.
            if let Some(why) = crate::supply::level::unlevel(&ground, auto.best().point) {
                slope_warning = Some(format!(
                    "{why}, and no level place (at most {:.0}%, within {} m) serves the route (a drone takes off and lands on level ground: give one with --supply X,Y)",
                    100.0 * crate::supply::level::MAX_SLOPE,
                    crate::supply::level::STAND_RADIUS_M
                ));
            }
            Ok(auto)
        })
        .map_err(|fault| match fault {
            // No point serves the route. If none would even where the route begins, the
            // vehicle is what is short, and the fault names it rather than the field file (a
            // tenth trial's battery typed in minutes was blamed on the supply point).
            Fault::Structure(why) => {
                let at_first = scenario
                    .terrain
                    .height_m(first.x, first.y)
                    .map(|ground_m| GroundPoint {
                        x: first.x,
                        y: first.y,
                        ground_m,
                    });
                match at_first.map(|point| {
                    split_into_sorties(scenario, &free, Some(point), &settings.sorties)
                }) {
                    Ok(Err(fault @ Fault::UnreachableOnOneBattery { .. })) => fault,
                    // A share of the battery kept for landing may be why.
                    _ if vehicle.battery_reserve_percent > 0.0 => Fault::Structure(format!(
                        "{why} (the vehicle lands with {}% of its battery, battery_reserve_percent: {:.0} s of {} s usable)",
                        crate::error::figure(vehicle.battery_reserve_percent),
                        vehicle.usable_battery_s(),
                        crate::error::figure(vehicle.battery_endurance_s)
                    )),
                    _ => Fault::Structure(why),
                }
            }
            other => other,
        })?;
    // The old rule's point is scored as it is, level or not: the saving stays like for like;
    // but a moved point the level search refused is named for what it is.
    if slope_warning.is_none() {
        auto.first_point_moved_unlevel = auto
            .first_point_moved
            .and_then(|moved| crate::supply::level::unlevel(&ground, moved.point));
    }
    for old_rule in std::iter::once(&mut auto.first_point).chain(auto.first_point_moved.as_mut()) {
        if !old_rule.cost_s.is_finite() {
            old_rule.cost_s = crate::supply::SupplyCost::cost_s(&evaluator, old_rule.point);
        }
    }
    let best = auto.best().point;
    Ok(SupplyPlan {
        choice: Some(SupplyChoice {
            source: SupplySource::Auto,
            point: GroundPoint {
                x: best.x,
                y: best.y,
                ground_m: scenario.terrain.height_m(best.x, best.y)?,
            },
            auto: Some(auto),
            standing_warning: slope_warning,
        }),
        closed_tour: Some(closed_tour),
    })
}

/// The evaluator's measure (non-spray seconds: the split's E plus the first leg out and the
/// last home) on the route as planned from the supply point.
fn planned_cost_s(
    scenario: &Scenario,
    route: &Route,
    sorties: Option<&PlannedSorties>,
    supply: GroundPoint,
) -> f64 {
    match sorties {
        Some(split) => plan_cost_s(&split.work_route, &split.model, &split.plan),
        None => {
            let vehicle = &scenario.vehicle;
            let work_route = WorkRoute::from_route(route, Speeds::of(vehicle));
            let model = sortie_model(vehicle, supply.into());
            let plan = model.evaluate(&work_route, crate::sortie::SortiePlanner::Exact, vec![]);
            plan_cost_s(&work_route, &model, &plan)
        }
    }
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
    let work_route = WorkRoute::from_route(route, Speeds::of(vehicle));
    let Some(first) = work_route.points().first().copied() else {
        return Ok(None);
    };
    let supply = start
        .or(route.launch.map(|leg| leg.from))
        .map_or(first, RoutePoint::from);
    let points = route
        .visits
        .iter()
        .flat_map(|visit| visit.points.iter().copied());
    let mut model = sortie_model_over(vehicle, supply, scenario.terrain.as_ref(), points)?;
    model.battery_reserve_s += settings.battery_margin_s;
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
    let given = start_point(scenario, settings)?;
    let coverage = plan_coverage(
        &scenario.farm,
        scenario.terrain.as_ref(),
        &scenario.vehicle,
        &settings.coverage,
    )?;
    let model = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
    crate::progress::stage(|| "choosing the supply point".into());
    let SupplyPlan {
        choice: supply,
        closed_tour,
    } = choose_supply(scenario, settings, &coverage, &model, given)?;
    let start = supply.as_ref().map(|choice| choice.point);
    crate::progress::stage(|| {
        let passes = crate::sequence::passes_of(&coverage).len();
        format!("ordering {passes} passes")
    });
    let route = if settings.sorties.planner == Some(SortiePlanner::Joint) {
        joint_route(
            scenario,
            &coverage,
            &model,
            start,
            closed_tour.as_deref(),
            settings,
        )?
    } else {
        // From and back to the supply point, else an open path (decision 0018).
        route(&coverage, &model, start_of(start), &settings.sequencer)
    };
    crate::progress::stage(|| "splitting the route into sorties".into());
    let sorties = split_into_sorties(scenario, &route, start, &settings.sorties)?;
    let runtime_s = crate::numbers::round(started.elapsed().as_secs_f64(), 1e-4);
    let mut report = Report::new(
        scenario,
        &coverage,
        &route,
        sorties.as_ref(),
        settings,
        runtime_s,
    );
    report.supply = supply.as_ref().map(|choice| {
        let planned = planned_cost_s(scenario, &route, sorties.as_ref(), choice.point);
        crate::report::supply::SupplyReport::new(choice, scenario.farm.coordinate_system, planned)
    });
    Ok(PlannedMission {
        coverage,
        route,
        sorties,
        report,
        settings: *settings,
    })
}
