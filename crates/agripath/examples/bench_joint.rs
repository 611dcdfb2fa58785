//! The joint problem of issue 19 (item 5): order and returns together, one drone, one supply
//! point. For the seed 001 farm and random irregular farms, plans the mission with the library
//! and measures what the acceptance compares: the total non-spray distance (every transfer
//! flown along the sorties, plus every leg between the supply point and the route, the first
//! out-leg and the last home-leg included), split into transfers and supply legs, with the
//! non-spray time, the sorties and the runtime. With `--export DIR` it writes each farm as a
//! JSON instance (passes, transfer matrix between pass ends, supply legs, vehicle limits, our
//! result) for `benches/joint_vs_pyvrp.py`. Run:
//!
//! ```sh
//! cargo run --release -p agripath --example bench_joint -- \
//!     [--planner exact] [--farms 10] [--runs 3] [--export DIR] [--free-start-demo] \
//!     [--headland N] [--big SWATHS]
//! ```
//!
//! Farms: the seed 001 farm (`agripath::demo::scenario()`, supply point = its launch point
//! (0, 0)), then `irregular_farm(seed, target, 5.0)` for seeds 1, 2, … with targets cycling
//! through 120, 150, 180, 210, 240 swaths, flat ground, default vehicle and coverage, kept
//! when the plan has 100-250 interior swaths, until `--farms` are kept. A random farm's supply
//! point is 30 m south of the middle of the south side of the farm's bounding box: outside
//! every field, and a place a truck could stand by a farm's edge. `--free-start-demo` adds the
//! seed 001 farm as `agripath demo` plans it (no launch point: the supply point is the first
//! point of the route, issue 19's old rule); `--headland N` sets the edge passes around each
//! boundary and hole (default 1; issue 19's seed 001 figures are those of `--headland 0
//! --free-start-demo`, seed 001's own layout with the old supply rule). `--big SWATHS` adds one
//! large farm, `tiled_irregular_farm(1, SWATHS, 100, 5.0)` (random irregular farms of about
//! 100 swaths in rows, supply point in the gap between the middle rows), for the issue's
//! 5,000-swath time goal (not exported: its transfer matrix would be
//! hundreds of megabytes).

use std::path::PathBuf;
use std::str::FromStr;
use std::time::Instant;

use agripath::bench::farms::{irregular_farm, supply_south_of, ROUTING_SWATH_TARGETS};
use agripath::coverage::drape::GroundPoint;
use agripath::coverage::CoverageSettings;
use agripath::pipeline::{plan_mission, PlannedMission};
use agripath::scenario::{Scenario, ScenarioParts};
use agripath::sequence::ordering_problem;
use agripath::sequence::tour::{OrderingProblem, Start};
use agripath::sequence::{passes_of, Pass, TransferModel};
use agripath::settings::PlanSettings;
use agripath::sortie::route::{RoutePoint, Segment};
use agripath::sortie::{PlannedSorties, SortiePlanner, SortieSettings};
use serde_json::{json, Value};

/// Interior swaths a random farm's plan must have to be kept (issue 19's 100-250).
const KEPT_SWATHS: std::ops::RangeInclusive<usize> = 100..=250;
/// Seeds tried before giving up on finding enough farms of the kept size.
const MAX_SEEDS: u64 = 200;
/// Float slack of the consistency checks, metres or seconds (the report rounds to 1e-4).
const CHECK_SLACK: f64 = 1e-3;

/// What the command line asks for.
struct Options {
    planner: SortiePlanner,
    farms: usize,
    runs: usize,
    export: Option<PathBuf>,
    free_start_demo: bool,
    /// Edge passes around each boundary and hole; `None`: the library's default.
    headland: Option<usize>,
    /// Swaths asked of one more, large farm.
    big: Option<usize>,
}

fn usage() -> ! {
    eprintln!(
        "usage: bench_joint [--planner KEY] [--farms N] [--runs N] [--export DIR] \
         [--free-start-demo] [--headland N] [--big SWATHS]"
    );
    std::process::exit(2)
}

fn options() -> Options {
    let mut options = Options {
        planner: SortiePlanner::Exact,
        farms: 10,
        runs: 3,
        export: None,
        free_start_demo: false,
        headland: None,
        big: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        if flag == "--free-start-demo" {
            options.free_start_demo = true;
            continue;
        }
        let value = args.next().unwrap_or_else(|| usage());
        match flag.as_str() {
            // Parsed by the library, so a planner added there is known here without a change.
            "--planner" => {
                options.planner = SortiePlanner::from_str(&value).unwrap_or_else(|message| {
                    eprintln!("{message}");
                    std::process::exit(2)
                })
            }
            "--farms" => options.farms = value.parse().unwrap_or_else(|_| usage()),
            "--runs" => options.runs = value.parse().unwrap_or_else(|_| usage()),
            "--headland" => options.headland = Some(value.parse().unwrap_or_else(|_| usage())),
            "--export" => options.export = Some(PathBuf::from(value)),
            "--big" => options.big = Some(value.parse().unwrap_or_else(|_| usage())),
            _ => usage(),
        }
    }
    options.runs = options.runs.max(1);
    options
}

/// A benchmark farm: its name, the scenario, and the supply point in planning metres (`None`:
/// the library's own rule, a launch marker, else the first point of the route).
struct Farm {
    name: String,
    scenario: Scenario,
    supply: Option<[f64; 2]>,
}

/// The default plan settings with the asked planner splitting the route (and the asked edge
/// passes, if any), the drone starting and refilling at `supply`.
fn settings(options: &Options, supply: Option<[f64; 2]>) -> PlanSettings {
    let defaults = PlanSettings::default();
    PlanSettings {
        start: supply,
        coverage: CoverageSettings {
            headland_passes: options
                .headland
                .unwrap_or(defaults.coverage.headland_passes),
            ..defaults.coverage
        },
        sorties: SortieSettings {
            planner: Some(options.planner),
            ..SortieSettings::default()
        },
        ..defaults
    }
}

fn interior_swaths(mission: &PlannedMission) -> usize {
    mission.coverage.fields.iter().map(|f| f.swaths.len()).sum()
}

/// The seed 001 farm (and, with `free_start_demo`, the same farm planned as `agripath demo`
/// plans it: no launch point, so the supply point is the first point of the route), then
/// random irregular farms of 100-250 swaths until `count` of them.
fn farms(options: &Options) -> Vec<Farm> {
    let demo = || agripath::demo::scenario().expect("the embedded demo farm");
    let mut farms = vec![Farm {
        name: "seed001".into(),
        scenario: demo(),
        supply: Some([0.0, 0.0]),
    }];
    if options.free_start_demo {
        farms.push(Farm {
            name: "seed001_free_start".into(),
            scenario: demo(),
            supply: None,
        });
    }
    let wanted = farms.len() + options.farms;
    let mut seed = 0;
    while farms.len() < wanted && seed < MAX_SEEDS {
        seed += 1;
        let target = ROUTING_SWATH_TARGETS[(seed as usize - 1) % ROUTING_SWATH_TARGETS.len()];
        let farm = irregular_farm(seed, target, 5.0);
        let supply = supply_south_of(&farm);
        let scenario =
            Scenario::with_farm(farm, ScenarioParts::default()).expect("a random farm is valid");
        let Ok(mission) = plan_mission(&scenario, &settings(options, Some(supply))) else {
            eprintln!("seed {seed}: no plan, skipped");
            continue;
        };
        let swaths = interior_swaths(&mission);
        if KEPT_SWATHS.contains(&swaths) {
            farms.push(Farm {
                name: format!("random_s{seed}_{swaths}"),
                scenario,
                supply: Some(supply),
            });
        }
    }
    if let Some(swaths) = options.big {
        let (farm, supply) = agripath::bench::farms::tiled_irregular_farm(1, swaths, 100, 5.0);
        let supply = [supply.x, supply.y];
        let scenario =
            Scenario::with_farm(farm, ScenarioParts::default()).expect("a random farm is valid");
        farms.push(Farm {
            name: format!("big_{swaths}"),
            scenario,
            supply: Some(supply),
        });
    }
    farms
}

fn length_3d(a: &GroundPoint, b: &GroundPoint) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.ground_m - b.ground_m).powi(2)).sqrt()
}

/// Rounds to 0.1 mm, so that the files stay small and no figure moves by more than the
/// report's own rounding.
fn fine(value: f64) -> f64 {
    (value * 1e4).round() / 1e4
}

/// What the acceptance measures of a plan, computed from each sortie's own first and last
/// route points (so it stays right when a sortie starts past the previous one's return).
struct Measured {
    /// Flights from the supply point and back.
    sorties: usize,
    /// Transfers and turns flown inside the sorties, metres.
    transfers_m: f64,
    /// Out-legs and home-legs between the supply point and the route, metres.
    supply_legs_m: f64,
    /// Transfers at their speeds, supply legs at transit speed, a service per return, seconds.
    non_spray_s: f64,
    /// Spray metres over all sorties.
    spray_m: f64,
    /// Route turns and transfers between one sortie's last point and the next one's first
    /// (none while every sortie starts where the last returned), metres…
    skipped_m: f64,
    /// …and their seconds.
    skipped_s: f64,
}

/// Measures `split`, whose route sprays at `spray_mps` (the vehicle's spray speed, as the
/// pipeline times it).
fn measure(split: &PlannedSorties, spray_mps: f64) -> Measured {
    let (route, model) = (&split.work_route, &split.model);
    let points = route.points();
    let mut measured = Measured {
        sorties: split.plan.sorties.len(),
        transfers_m: 0.0,
        supply_legs_m: 0.0,
        non_spray_s: 0.0,
        spray_m: 0.0,
        skipped_m: 0.0,
        skipped_s: 0.0,
    };
    for (index, sortie) in split.plan.sorties.iter().enumerate() {
        let (first, last) = (sortie.first, sortie.last);
        let legs_m = model.leg_m(&points[first]) + model.leg_m(&points[last]);
        let spray_m = route.spray_between(first, last);
        measured.transfers_m += route.other_between(first, last);
        measured.supply_legs_m += legs_m;
        measured.spray_m += spray_m;
        measured.non_spray_s +=
            legs_m / model.transit_mps + route.flight_between(first, last) - spray_m / spray_mps;
        if index > 0 {
            let previous = split.plan.sorties[index - 1].last;
            measured.non_spray_s += model.service_s(spray_m);
            measured.skipped_m += route.other_between(previous, first);
            measured.skipped_s += route.flight_between(previous, first)
                - route.spray_between(previous, first) / spray_mps;
        }
    }
    measured
}

/// The checks of our figures against the plan's and the report's where they mean the same;
/// each failed check is a line of text.
fn check(mission: &PlannedMission, split: &PlannedSorties, measured: &Measured) -> Vec<String> {
    let mut failures = Vec::new();
    let mut expect = |what: &str, ours: f64, theirs: f64| {
        if (ours - theirs).abs() > CHECK_SLACK * theirs.abs().max(1.0) {
            failures.push(format!("{what}: ours {ours:.4}, the plan's {theirs:.4}"));
        }
    };
    let report = &mission.report;
    let points = split.work_route.points();
    let sorties = &split.plan.sorties;
    let (first, last) = (sorties[0].first, sorties[sorties.len() - 1].last);
    let end_legs_m = split.model.leg_m(&points[first]) + split.model.leg_m(&points[last]);
    // The report's return flying is every leg to and from the supply point but the first
    // out-leg and the last home-leg.
    expect(
        "supply legs − first out − last home vs report.return_length_m",
        measured.supply_legs_m - end_legs_m,
        report.return_length_m,
    );
    let between_m: f64 = mission.route.transfers.iter().map(|leg| leg.cost_m).sum();
    expect(
        "transfers + skipped vs Σ route transfers",
        measured.transfers_m + measured.skipped_m,
        between_m,
    );
    expect(
        "skipped transfers vs the plan's",
        measured.skipped_m,
        split.plan.skipped_m,
    );
    expect(
        "skipped seconds vs the plan's",
        measured.skipped_s,
        split.plan.skipped_s,
    );
    // The report counts the launch and home legs as eq. 8 transfers from the launch point;
    // ours are supply legs (leg_m) to the sorties' first and last points.
    let launch_home_m: f64 = mission
        .route
        .launch
        .iter()
        .chain(mission.route.home.iter())
        .map(|leg| leg.cost_m)
        .sum();
    expect(
        "transfers flown vs report.transfer_length_m − launch − home",
        measured.transfers_m,
        report.transfer_length_m - launch_home_m,
    );
    expect(
        "non-spray m − first out − last home vs report.non_spray_length_m − launch − home",
        measured.transfers_m + measured.supply_legs_m - end_legs_m,
        report.non_spray_length_m - launch_home_m,
    );
    // Seed 003's E leaves out the first out-leg and the last home-leg; ours flies them.
    expect(
        "non-spray time − first out − last home vs the plan's objective E",
        measured.non_spray_s - end_legs_m / split.model.transit_mps,
        split.plan.objective_s(),
    );
    expect(
        "spray over the sorties vs the route's",
        measured.spray_m,
        split.work_route.total_spray_m(),
    );
    if report.sorties != measured.sorties {
        failures.push(format!(
            "sorties: ours {}, the report's {}",
            measured.sorties, report.sorties
        ));
    }
    failures
}

/// Eq. 8 between every two pass ends (end 2p is pass p's first point, 2p + 1 its last), and
/// whether each leg climbs (0 or 1).
fn transfer_matrices(problem: &OrderingProblem) -> (Vec<Vec<f64>>, Vec<Vec<u8>>) {
    let count = 2 * problem.passes();
    let mut transfer_m = vec![vec![0.0; count]; count];
    let mut climbs = vec![vec![0u8; count]; count];
    for from in 0..count {
        for to in 0..count {
            if from != to {
                transfer_m[from][to] = fine(problem.cost(from, to));
                // A leg that leaves the field is flown at transit speed, one that stays in it
                // at turn speed (WorkRoute::from_route).
                climbs[from][to] = u8::from(problem.climbs(from, to));
            }
        }
    }
    (transfer_m, climbs)
}

/// The exported instance: passes, the transfer matrix between their ends, the supply legs of
/// each end, the vehicle limits, and our result.
fn instance(
    farm: &Farm,
    mission: &PlannedMission,
    split: &PlannedSorties,
    measured: &Measured,
    runtime_s: f64,
) -> Value {
    let vehicle = &farm.scenario.vehicle;
    let passes = passes_of(&mission.coverage);
    // The same transfer model and the same problem the sequencer costs its tours on.
    let model = TransferModel::new(&farm.scenario.farm, vehicle.safe_height_m);
    let supply = GroundPoint {
        x: split.supply.x,
        y: split.supply.y,
        ground_m: split.supply.ground_m,
    };
    let (problem, _) = ordering_problem(&mission.coverage, &model, Start::Fixed(supply));
    let (transfer_m, climbs) = transfer_matrices(&problem);
    let count = 2 * passes.len();
    let end_point = |end: usize| problem.point(end);
    let spray_mps = vehicle.spray_speed_mps;
    let pass_values: Vec<Value> = passes
        .iter()
        .map(|(_, points)| {
            let spray_m: f64 = points.windows(2).map(|w| length_3d(&w[0], &w[1])).sum();
            let end = |point: &GroundPoint| json!([point.x, point.y, point.ground_m]);
            json!({
                "ends": [end(&points[0]), end(&points[points.len() - 1])],
                "spray_m": spray_m,
                "spray_s": spray_m / spray_mps,
            })
        })
        .collect();
    let supply_leg_m: Vec<f64> = (0..count)
        .map(|end| fine(split.model.leg_m(&RoutePoint::from(end_point(end)))))
        .collect();
    let order = flown_order(mission);
    let sorties: Vec<Value> = split
        .plan
        .sorties
        .iter()
        .map(|sortie| {
            json!({
                "first_point": sortie.first,
                "last_point": sortie.last,
                "spray_m": sortie.spray_m,
                "flight_s": sortie.flight_s,
            })
        })
        .collect();
    json!({
        "name": farm.name,
        "supply": [supply.x, supply.y, supply.ground_m],
        "passes": pass_values,
        "transfer_m": transfer_m,
        "transfer_climbs": climbs,
        "supply_leg_m": supply_leg_m,
        "vehicle": {
            "spray_per_tank_m": split.model.spray_per_tank_m,
            "usable_battery_s": split.model.usable_s(),
            "endurance_s": split.model.endurance_s,
            "battery_reserve_s": split.model.battery_reserve_s,
            "spray_mps": spray_mps,
            "turn_mps": vehicle.turn_speed_mps,
            "transit_mps": split.model.transit_mps,
            "transfer_climb_s": agripath::sortie::route::Speeds::of(vehicle).transfer_climb_s,
            "battery_swap_s": split.model.battery_swap_s,
            "refill_base_s": split.model.refill_base_s,
            "refill_max_s": split.model.refill_max_s,
            "return_climb_m": split.model.return_climb_m,
        },
        "ours": {
            "planner": split.plan.planner.key(),
            "interior_swaths": interior_swaths(mission),
            "sorties": measured.sorties,
            "non_spray_m": measured.transfers_m + measured.supply_legs_m,
            "transfers_m": measured.transfers_m,
            "supply_legs_m": measured.supply_legs_m,
            "skipped_transfers_m": measured.skipped_m,
            "mid_pass_returns": mid_pass_returns(split),
            "non_spray_s": measured.non_spray_s,
            "runtime_s": runtime_s,
            "order": order,
            "sortie_details": sorties,
            "report_non_spray_time_s": mission.report.non_spray_time_s,
            "report_runtime_s": mission.report.runtime_s,
        },
    })
}

/// Returns where the drone breaks off in the middle of a pass (spraying before and after the
/// return point): what PyVRP's model, which returns at pass ends only, cannot do.
fn mid_pass_returns(split: &PlannedSorties) -> usize {
    let segments = split.work_route.segments();
    // Every sortie but the last returns at its last point.
    split
        .plan
        .sorties
        .iter()
        .rev()
        .skip(1)
        .filter(|sortie| {
            let at = sortie.last;
            at > 0
                && segments[at - 1] == Segment::Spray
                && segments.get(at) == Some(&Segment::Spray)
        })
        .count()
}

/// The route's passes as `[pass index, reversed]` in the numbering of `passes_of` (per field:
/// edge passes, then swaths).
fn flown_order(mission: &PlannedMission) -> Vec<[usize; 2]> {
    let passes = passes_of(&mission.coverage);
    let mut offsets = Vec::new();
    let mut next = 0;
    for field in &mission.coverage.fields {
        offsets.push(next);
        next += field.edges.len() + field.swaths.len();
    }
    mission
        .route
        .visits
        .iter()
        .map(|visit| {
            let index = match visit.pass {
                Pass::Edge { field, edge } => offsets[field] + edge,
                Pass::Swath { field, swath } => {
                    offsets[field] + mission.coverage.fields[field].edges.len() + swath
                }
            };
            let reversed = visit.points.as_slice() != passes[index].1;
            [index, usize::from(reversed)]
        })
        .collect()
}

/// Checks that each transfer of the route costs what the exported matrix says (the route
/// costs legs with the plain eq. 8 model, the matrix with the field-aware one).
fn check_matrix(mission: &PlannedMission, instance: &Value) -> Vec<String> {
    let order = flown_order(mission);
    let matrix = &instance["transfer_m"];
    order
        .windows(2)
        .zip(&mission.route.transfers)
        .filter_map(|(pair, leg)| {
            let exit = 2 * pair[0][0] + 1 - pair[0][1];
            let entry = 2 * pair[1][0] + pair[1][1];
            let listed = matrix[exit][entry].as_f64().expect("a number");
            ((listed - leg.cost_m).abs() > CHECK_SLACK).then(|| {
                format!(
                    "transfer {exit}→{entry}: matrix {listed:.4}, route {:.4}",
                    leg.cost_m
                )
            })
        })
        .collect()
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    let options = options();
    if let Some(folder) = &options.export {
        std::fs::create_dir_all(folder).expect("the export folder can be made");
    }
    println!(
        "joint problem, planner {} (runtime: median of {} runs)",
        options.planner, options.runs
    );
    println!(
        "{:<18} {:>6} {:>7} {:>8} {:>10} {:>10} {:>10} {:>10} {:>9}",
        "farm",
        "swaths",
        "passes",
        "sorties",
        "non-spray",
        "transfers",
        "supply",
        "time",
        "runtime"
    );
    let mut failed = false;
    for farm in farms(&options) {
        let plan_settings = settings(&options, farm.supply);
        let mut times = Vec::new();
        let mut planned = None;
        for _ in 0..options.runs {
            let started = Instant::now();
            let mission = plan_mission(&farm.scenario, &plan_settings).expect("a plan");
            times.push(started.elapsed().as_secs_f64());
            planned = Some(mission);
        }
        let mission = planned.expect("at least one run");
        let split = mission.sorties.as_ref().expect("the route is split");
        let measured = measure(split, farm.scenario.vehicle.spray_speed_mps);
        let runtime_s = median(times);
        let mut failures = check(&mission, split, &measured);
        // A large farm's matrix between every two pass ends is not built.
        let big = farm.name.starts_with("big");
        let mut value = if big {
            json!({ "passes": passes_of(&mission.coverage).len() })
        } else {
            instance(&farm, &mission, split, &measured, runtime_s)
        };
        if !big {
            failures.extend(check_matrix(&mission, &value));
            value["ours"]["check_failures"] = json!(failures);
        }
        println!(
            "{:<18} {:>6} {:>7} {:>8} {:>8.0} m {:>8.0} m {:>8.0} m {:>8.0} s {:>7.3} s",
            farm.name,
            interior_swaths(&mission),
            value["passes"].as_array().map_or(0, Vec::len),
            measured.sorties,
            measured.transfers_m + measured.supply_legs_m,
            measured.transfers_m,
            measured.supply_legs_m,
            measured.non_spray_s,
            runtime_s
        );
        for failure in &failures {
            println!("  CHECK FAILED: {failure}");
            failed = true;
        }
        if let Some(folder) = options.export.as_ref().filter(|_| !big) {
            let path = folder.join(format!("{}.json", farm.name));
            std::fs::write(&path, value.to_string()).expect("the instance can be written");
        }
    }
    if failed {
        std::process::exit(1);
    }
}
