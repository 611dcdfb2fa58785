//! The flight through a coverage plan: the order of the passes, the end each is entered by,
//! and the transfer legs between them (seed 001 §3). Sequencers, chosen by value:
//! `greedy` (the seed's baseline), `aco` (the seed's improved ant colony) and `best` (ours:
//! construction, 2-opt with end flips, Or-opt, iterated kicks). Every one returns a tour of
//! [`tour::Step`]s that [`route`] turns into the flight, with eq. (8)'s transfers.

pub mod ant_colony;
pub mod greedy;
pub mod local_search;
pub mod tour;
pub mod transfer;

use geo::Coord;
use serde::Serialize;

use crate::coverage::drape::GroundPoint;
use crate::coverage::CoveragePlan;
use ant_colony::{ant_colony, AntColonySettings};
use local_search::{best_tour, LocalSearchSettings};
use tour::{OrderingProblem, Start, Step};
pub use transfer::{Transfer, TransferModel};

/// A pass of the plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Pass {
    /// Interior swath `swath` of field `field`.
    Swath {
        /// The field's index.
        field: usize,
        /// The swath's index in the field.
        swath: usize,
    },
    /// Edge pass `edge` of field `field`.
    Edge {
        /// The field's index.
        field: usize,
        /// The edge pass's index in the field.
        edge: usize,
    },
}

/// One pass in flight order.
#[derive(Debug, Clone, PartialEq)]
pub struct Visit {
    /// Which pass.
    pub pass: Pass,
    /// The points in the direction flown.
    pub points: Vec<GroundPoint>,
}

/// The flight: an optional leg from the launch point, the passes in order with the transfers
/// between them (`transfers[i]` leads from `visits[i]` to `visits[i + 1]`), and the leg home.
#[derive(Debug, Clone, PartialEq)]
pub struct Route {
    /// From the launch point to the first pass, when there is one.
    pub launch: Option<Transfer>,
    /// The passes in flight order.
    pub visits: Vec<Visit>,
    /// `transfers[i]` leads from `visits[i]` to `visits[i + 1]`.
    pub transfers: Vec<Transfer>,
    /// From the last pass back to the launch point, when there is one.
    pub home: Option<Transfer>,
    /// The tour cost the sequencer minimised ([`OrderingProblem::tour_cost`]), metres: every
    /// leg flown for a start point the flight comes back to (`Start::Fixed`) and for an open
    /// path (`Start::Open`); without the leg home from a point (`Start::From`, seed 001's
    /// Table 8 measure); with the closing leg, not flown, for a closed tour (`Start::Closed`).
    pub tour_cost_m: f64,
}

impl Route {
    /// Every leg flown: launch, transfers, home.
    pub fn legs(&self) -> impl Iterator<Item = &Transfer> {
        self.launch
            .iter()
            .chain(&self.transfers)
            .chain(self.home.iter())
    }

    /// Length of every leg flown between passes, metres.
    pub fn transfer_length_m(&self) -> f64 {
        self.legs().map(|leg| leg.cost_m).sum()
    }

    /// Changes of direction at path points along the flown polyline (every angle counts, as
    /// in contract decision 5, docs/contract.md), and the U-turns among the pass-to-pass junctions.
    pub fn turns(&self) -> (usize, usize) {
        let mut polyline: Vec<Coord<f64>> = Vec::new();
        let mut push = |point: &GroundPoint| {
            let coord = Coord {
                x: point.x,
                y: point.y,
            };
            if polyline
                .last()
                .is_none_or(|last| (last.x - coord.x).hypot(last.y - coord.y) > 1e-9)
            {
                polyline.push(coord);
            }
        };
        let mut u_turns = 0;
        for (index, visit) in self.visits.iter().enumerate() {
            visit.points.iter().for_each(&mut push);
            if let Some(next) = self.visits.get(index + 1) {
                if reverses(&visit.points, &next.points) {
                    u_turns += 1;
                }
            }
        }
        // 1°: draped points wiggle by float noise along a straight swath.
        let turns = crate::geometry::turn_count(&polyline, 1f64.to_radians());
        (turns, u_turns)
    }
}

/// Whether the next pass runs back against this one (a U-turn at the headland).
fn reverses(points: &[GroundPoint], next: &[GroundPoint]) -> bool {
    let open = |points: &[GroundPoint]| points.len() >= 2 && points[0] != points[points.len() - 1];
    if !open(points) || !open(next) {
        return false;
    }
    let direction = |points: &[GroundPoint]| {
        let (first, last) = (points[0], points[points.len() - 1]);
        let length = (last.x - first.x).hypot(last.y - first.y);
        ((last.x - first.x) / length, (last.y - first.y) / length)
    };
    let (a, b) = (direction(points), direction(next));
    a.0 * b.0 + a.1 * b.1 < -0.99
}

/// A way to order the passes: the one signature every sequencer has. `groups` lists the
/// passes of each field (edge passes, then swaths by scan line), for the constructions that
/// fly a field as a block. The result is a tour of every pass once ([`tour::check_order`]).
pub trait OrderPasses {
    /// The name on the command line and in `report.json`.
    fn key(&self) -> &'static str;
    /// The tour of `problem`'s passes.
    fn order(&self, problem: &OrderingProblem, groups: &[Vec<usize>]) -> Vec<Step>;
}

/// Seed 001's baseline: the nearest unflown pass end next ([`greedy::greedy`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Greedy;

impl OrderPasses for Greedy {
    fn key(&self) -> &'static str {
        "greedy"
    }

    fn order(&self, problem: &OrderingProblem, _groups: &[Vec<usize>]) -> Vec<Step> {
        greedy::greedy(problem)
    }
}

impl OrderPasses for AntColonySettings {
    fn key(&self) -> &'static str {
        "aco"
    }

    fn order(&self, problem: &OrderingProblem, _groups: &[Vec<usize>]) -> Vec<Step> {
        ant_colony(problem, self).0
    }
}

impl OrderPasses for LocalSearchSettings {
    fn key(&self) -> &'static str {
        "best"
    }

    fn order(&self, problem: &OrderingProblem, groups: &[Vec<usize>]) -> Vec<Step> {
        best_tour(problem, groups, self)
    }
}

/// Which sequencer orders the passes, with its settings: the registry of [`OrderPasses`]
/// implementations (a new sequencer is its file, its variant and its arm in
/// [`Sequencer::sequencer`] and [`Sequencer::from_key`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "sequencer", rename_all = "snake_case")]
pub enum Sequencer {
    /// [`Greedy`].
    Greedy,
    /// Seed 001's improved ant colony ([`ant_colony()`]).
    #[serde(rename = "aco")]
    AntColony(AntColonySettings),
    /// Ours: constructions, local search, iterated kicks ([`local_search`]).
    Best(LocalSearchSettings),
}

impl Sequencer {
    /// The names [`Sequencer::from_key`] knows, default first.
    pub const KEYS: [&'static str; 3] = ["best", "greedy", "aco"];

    /// The sequencer called `key`, seeded with `seed`; the ant colony flies `ants` ants for
    /// `batches` batches. `None` for an unknown name.
    pub fn from_key(key: &str, seed: u64, ants: usize, batches: usize) -> Option<Self> {
        match key {
            "greedy" => Some(Sequencer::Greedy),
            "aco" => Some(Sequencer::AntColony(AntColonySettings {
                ants,
                batches,
                seed,
                ..AntColonySettings::default()
            })),
            "best" => Some(Sequencer::Best(LocalSearchSettings {
                seed,
                ..LocalSearchSettings::default()
            })),
            _ => None,
        }
    }

    /// The same sequencer without `best`'s chained-LK restarts on closed tours (the iterated
    /// search alone: a closed tour in tens of milliseconds instead of about a second).
    pub fn without_restarts(&self) -> Sequencer {
        match self {
            Sequencer::Best(settings) => Sequencer::Best(LocalSearchSettings {
                restarts: 0,
                ..*settings
            }),
            other => *other,
        }
    }

    /// The sequencer of the joint search's start (the sortie planner `joint`): `best` with a
    /// quarter of its kicks. The joint search reworks the order through the split anyway: on
    /// `bench_joint`'s 11 farms the plans' non-spray time moved by −0.74 … +0.46 % by farm
    /// (mean −0.01 %), and the demo's planning takes about a fifth less time (decision
    /// 0039).
    pub fn for_joint_start(&self) -> Sequencer {
        match self {
            Sequencer::Best(settings) => Sequencer::Best(LocalSearchSettings {
                kicks: (settings.kicks / 4).max(1),
                ..*settings
            }),
            other => *other,
        }
    }

    /// The sequencer itself.
    pub fn sequencer(&self) -> &dyn OrderPasses {
        match self {
            Sequencer::Greedy => &Greedy,
            Sequencer::AntColony(settings) => settings,
            Sequencer::Best(settings) => settings,
        }
    }
}

impl Default for Sequencer {
    fn default() -> Self {
        Self::Best(LocalSearchSettings::default())
    }
}

/// The passes of a plan in a fixed numbering, with their points as generated.
pub fn passes_of(plan: &CoveragePlan) -> Vec<(Pass, &[GroundPoint])> {
    let mut passes = Vec::new();
    for (field_index, field) in plan.fields.iter().enumerate() {
        for (edge, pass) in field.edges.iter().enumerate() {
            passes.push((
                Pass::Edge {
                    field: field_index,
                    edge,
                },
                pass.points.as_slice(),
            ));
        }
        for (swath, pass) in field.swaths.iter().enumerate() {
            passes.push((
                Pass::Swath {
                    field: field_index,
                    swath,
                },
                pass.points.as_slice(),
            ));
        }
    }
    passes
}

/// Orders the plan's passes and builds the flight from and back to `start`'s point when it
/// has one, optimised for what `start` counts ([`Start`]).
pub fn route(
    plan: &CoveragePlan,
    model: &TransferModel,
    start: Start,
    sequencer: &Sequencer,
) -> Route {
    let (problem, groups) = ordering_problem(plan, model, start);
    let tour: Vec<Step> = sequencer.sequencer().order(&problem, &groups);
    route_of_tour(plan, model, &problem, &tour)
}

/// The start of a flight from the launch or supply point when there is one (it starts and
/// ends there), else an open path (decision 0018).
pub fn start_of(point: Option<GroundPoint>) -> Start {
    point.map_or(Start::Open, Start::Fixed)
}

/// The ordering problem of the plan's passes ([`passes_of`]'s numbering) from `start`, and
/// the groups for the constructions that fly a field as a block: per field, its edge passes
/// then its swaths by scan line.
pub fn ordering_problem<'m>(
    plan: &CoveragePlan,
    model: &'m TransferModel<'m>,
    start: Start,
) -> (OrderingProblem<'m>, Vec<Vec<usize>>) {
    let passes = passes_of(plan);
    let ends: Vec<[GroundPoint; 2]> = passes
        .iter()
        .map(|(_, points)| [points[0], points[points.len() - 1]])
        .collect();
    let fields: Vec<usize> = passes
        .iter()
        .map(|(pass, _)| match pass {
            Pass::Swath { field, .. } | Pass::Edge { field, .. } => *field,
        })
        .collect();
    let problem = OrderingProblem::with_fields(ends, fields, start, model);
    let mut groups: Vec<Vec<usize>> = vec![Vec::new(); plan.fields.len()];
    for (index, (pass, _)) in passes.iter().enumerate() {
        let field = match pass {
            Pass::Swath { field, .. } | Pass::Edge { field, .. } => *field,
        };
        groups[field].push(index);
    }
    for (field, group) in groups.iter_mut().enumerate() {
        group.sort_by_key(|&index| match passes[index].0 {
            Pass::Edge { edge, .. } => (0, edge),
            Pass::Swath { swath, .. } => (1, plan.fields[field].swaths[swath].line),
        });
    }
    (problem, groups)
}

/// The flight that flies `problem`'s passes in the order of `tour`, from and back to the
/// problem's start point when there is one.
pub fn route_of_tour(
    plan: &CoveragePlan,
    model: &TransferModel,
    problem: &OrderingProblem,
    tour: &[Step],
) -> Route {
    let start = problem.start.point();
    let passes = passes_of(plan);
    debug_assert_eq!(tour::check_order(tour, passes.len()), Ok(()));
    let tour_cost_m = problem.tour_cost(tour);
    let visits: Vec<Visit> = tour
        .iter()
        .map(|step| {
            let (pass, points) = passes[step.pass];
            let mut points = points.to_vec();
            if step.reversed {
                points.reverse();
            }
            Visit { pass, points }
        })
        .collect();
    let transfers = visits
        .windows(2)
        .map(|pair| {
            model.transfer(
                *pair[0].points.last().expect("a pass has points"),
                pair[1].points[0],
            )
        })
        .collect();
    let launch = start
        .zip(visits.first())
        .map(|(start, first)| model.transfer(start, first.points[0]));
    let home = start.zip(visits.last()).map(|(start, last)| {
        model.transfer(*last.points.last().expect("a pass has points"), start)
    });
    Route {
        launch,
        visits,
        transfers,
        home,
        tour_cost_m,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_listed_sequencer_is_registered_under_its_own_key() {
        for key in Sequencer::KEYS {
            let sequencer = Sequencer::from_key(key, 1, 5, 5).expect("a listed key is registered");
            assert_eq!(sequencer.sequencer().key(), key);
        }
        assert!(Sequencer::from_key("lkh", 1, 5, 5).is_none());
    }

    use super::*;
    use crate::coverage::{plan_coverage, CoverageSettings};
    use proptest::prelude::*;
    use tour::is_permutation;

    /// Above the full matrix's limit the costs within each field are precomputed: they must
    /// be eq. (8) as the model computes it over the whole farm, pair by pair.
    #[test]
    fn a_large_farm_costs_the_same_from_its_field_blocks_as_computed() {
        let (farm, _) = crate::bench::farms::tiled_irregular_farm(3, 1300, 100, 5.0);
        let scenario =
            crate::scenario::Scenario::with_farm(farm, crate::scenario::ScenarioParts::default())
                .unwrap();
        let plan = coverage_of(&scenario, 0);
        let model = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
        let (problem, _) = ordering_problem(&plan, &model, Start::Open);
        assert!(problem.passes() > 1000 && !problem.has_cost_matrix());
        let fields = problem.fields.clone().unwrap();
        let (mut same_field, mut flat) = (0, 0);
        for from in (0..2 * problem.passes()).step_by(17) {
            // Every end of the same pass's field neighbourhood, and a spread of the others.
            for to in (from.saturating_sub(40)..from + 40)
                .chain((0..2 * problem.passes()).step_by(97))
                .filter(|&to| to < 2 * problem.passes())
            {
                let computed = model.cost(problem.point(from), problem.point(to));
                let looked_up = problem.cost(from, to);
                assert!(
                    (computed - looked_up).abs() < 1e-9,
                    "ends {from} and {to}: {looked_up} against {computed}"
                );
                if fields[from / 2] == fields[to / 2] && from != to {
                    same_field += 1;
                    flat += usize::from(!problem.climbs(from, to));
                }
            }
        }
        assert!(same_field > 1000 && flat > 500, "{same_field} {flat}");
    }

    /// The scenario's coverage with `headland` edge passes, the other settings default.
    fn coverage_of(scenario: &crate::scenario::Scenario, headland: usize) -> CoveragePlan {
        let settings = CoverageSettings {
            headland_passes: headland,
            ..CoverageSettings::default()
        };
        plan_coverage(
            &scenario.farm,
            scenario.terrain.as_ref(),
            &scenario.vehicle,
            &settings,
        )
        .unwrap()
    }

    fn demo_plan(headland: usize) -> (crate::scenario::Scenario, CoveragePlan) {
        let scenario = crate::demo::scenario().unwrap();
        let plan = coverage_of(&scenario, headland);
        (scenario, plan)
    }

    fn quick_colony(seed: u64) -> Sequencer {
        Sequencer::AntColony(AntColonySettings {
            ants: 10,
            batches: 10,
            seed,
            ..AntColonySettings::default()
        })
    }

    /// The four kinds of start, from the origin where there is a point.
    fn every_start() -> [Start; 4] {
        let origin = GroundPoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        };
        [
            Start::Fixed(origin),
            Start::From(origin),
            Start::Closed,
            Start::Open,
        ]
    }

    #[test]
    fn every_sequencer_flies_each_pass_once_and_legs_add_up() {
        let (scenario, plan) = demo_plan(1);
        let model = TransferModel::new(&scenario.farm, 18.0);
        let total_passes: usize = plan
            .fields
            .iter()
            .map(|f| f.swaths.len() + f.edges.len())
            .sum();
        for sequencer in [Sequencer::Greedy, quick_colony(3), Sequencer::default()] {
            for start in every_start() {
                let flight = route(&plan, &model, start, &sequencer);
                assert_eq!(flight.visits.len(), total_passes);
                let mut seen: Vec<Pass> = flight.visits.iter().map(|visit| visit.pass).collect();
                seen.sort_by_key(|pass| format!("{pass:?}"));
                seen.dedup();
                assert_eq!(seen.len(), total_passes, "{sequencer:?}: a pass twice");
                let legs: f64 = flight.legs().map(|leg| leg.cost_m).sum();
                assert!((legs - flight.transfer_length_m()).abs() < 1e-9);
                assert_eq!(flight.launch.is_some(), start.point().is_some());
                assert_eq!(flight.home.is_some(), start.point().is_some());
                // What the tour cost counts, against the legs flown.
                let first = flight.visits[0].points[0];
                let last = *flight.visits[total_passes - 1].points.last().unwrap();
                let expected = match start {
                    Start::Fixed(_) | Start::Open => legs,
                    Start::From(_) => legs - flight.home.unwrap().cost_m,
                    Start::Closed => legs + model.cost(last, first),
                };
                assert!(
                    (flight.tour_cost_m - expected).abs() < 1e-6,
                    "{sequencer:?} {start:?}: {} against {expected}",
                    flight.tour_cost_m
                );
            }
        }
    }

    #[test]
    fn ant_colony_is_repeatable_with_a_seed_and_best_beats_greedy() {
        let (scenario, plan) = demo_plan(0);
        let model = TransferModel::new(&scenario.farm, 18.0);
        let start = Start::From(GroundPoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        });
        let first = route(&plan, &model, start, &quick_colony(7));
        let again = route(&plan, &model, start, &quick_colony(7));
        assert_eq!(first, again);
        let greedy = route(&plan, &model, start, &Sequencer::Greedy).tour_cost_m;
        let best = route(&plan, &model, start, &Sequencer::default()).tour_cost_m;
        assert!(best <= greedy, "best {best} greedy {greedy}");
    }

    /// Random points as passes: the ordering is a permutation whatever the instance.
    fn random_problem_tours(
        points: Vec<(f64, f64, f64, f64)>,
        start: Start,
    ) -> Vec<Vec<tour::Step>> {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let ends: Vec<[GroundPoint; 2]> = points
            .iter()
            .map(|&(x1, y1, x2, y2)| {
                [
                    GroundPoint {
                        x: x1,
                        y: y1,
                        ground_m: 0.0,
                    },
                    GroundPoint {
                        x: x2,
                        y: y2,
                        ground_m: 0.0,
                    },
                ]
            })
            .collect();
        let problem = OrderingProblem::new(ends, start, &model);
        let groups = vec![(0..points.len()).collect::<Vec<_>>()];
        vec![
            greedy::greedy(&problem),
            ant_colony(
                &problem,
                &AntColonySettings {
                    ants: 5,
                    batches: 5,
                    ..AntColonySettings::default()
                },
            )
            .0,
            best_tour(
                &problem,
                &groups,
                &LocalSearchSettings {
                    kicks: 20,
                    seed: 1,
                    restarts: 2,
                },
            ),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]
        /// What each start counts, on random passes in a random order: an open path is its
        /// transfers alone (no closing leg); a closed tour adds the leg from the last pass to
        /// the first; `From` adds the leg out; `Fixed` the leg out and the leg home.
        #[test]
        fn each_start_counts_its_own_legs(points in proptest::collection::vec((-300.0f64..300.0, -300.0f64..300.0, -300.0f64..300.0, -300.0f64..300.0), 2..30), seed in 0u64..1000) {
            let farm = crate::demo::scenario().unwrap().farm;
            let model = TransferModel::new(&farm, 10.0);
            let ground = |x: f64, y: f64| GroundPoint { x, y, ground_m: 0.0 };
            let ends: Vec<[GroundPoint; 2]> = points.iter().map(|&(a, b, c, d)| [ground(a, b), ground(c, d)]).collect();
            let point = ground(7.0, -3.0);
            let problem = |start| OrderingProblem::new(ends.clone(), start, &model);
            let open = problem(Start::Open);
            let tour = swarm::Problem::random_solution(&open, &mut swarm::run_stream(seed, 0));
            let between: f64 = tour.windows(2).map(|pair| model.cost(open.point(pair[0].exit()), open.point(pair[1].entry()))).sum();
            let (first, last) = (open.point(tour[0].entry()), open.point(tour[tour.len() - 1].exit()));
            prop_assert!((open.tour_cost(&tour) - between).abs() < 1e-6);
            prop_assert!((problem(Start::Closed).tour_cost(&tour) - between - model.cost(last, first)).abs() < 1e-6);
            prop_assert!((problem(Start::From(point)).tour_cost(&tour) - between - model.cost(point, first)).abs() < 1e-6);
            let fixed = problem(Start::Fixed(point));
            prop_assert!((fixed.tour_cost(&tour) - between - model.cost(point, first) - model.cost(last, point)).abs() < 1e-6);
            // Every sequencer's open path: its objective is the sum of the transfers it flies.
            let groups = vec![(0..ends.len()).collect::<Vec<_>>()];
            let best = best_tour(&open, &groups, &LocalSearchSettings { kicks: 20, seed, restarts: 2 });
            let flown: f64 = best.windows(2).map(|pair| model.cost(open.point(pair[0].exit()), open.point(pair[1].entry()))).sum();
            prop_assert!((open.tour_cost(&best) - flown).abs() < 1e-6);
        }

        /// On the demo plan, a route from a fixed point starts and ends there, and its cost is
        /// the sum of its legs; an open route has no launch and no home leg.
        #[test]
        fn fixed_routes_start_and_end_at_their_point(x in -200.0f64..800.0, y in -200.0f64..300.0, open in any::<bool>()) {
            let (scenario, plan) = demo_plan(0);
            let model = TransferModel::new(&scenario.farm, 18.0);
            let point = GroundPoint { x, y, ground_m: 0.0 };
            let start = if open { Start::Open } else { Start::Fixed(point) };
            let flight = route(&plan, &model, start, &Sequencer::Greedy);
            let legs: f64 = flight.legs().map(|leg| leg.cost_m).sum();
            prop_assert!((flight.tour_cost_m - legs).abs() < 1e-6);
            if open {
                prop_assert!(flight.launch.is_none() && flight.home.is_none());
            } else {
                prop_assert_eq!(flight.launch.unwrap().from, point);
                prop_assert_eq!(flight.home.unwrap().to, point);
                prop_assert_eq!(flight.launch.unwrap().to, flight.visits[0].points[0]);
            }
        }

        #[test]
        fn tours_are_permutations(points in proptest::collection::vec((-300.0f64..300.0, -300.0f64..300.0, -300.0f64..300.0, -300.0f64..300.0), 1..40), kind in 0usize..4) {
            let count = points.len();
            for tour in random_problem_tours(points, every_start()[kind]) {
                prop_assert!(is_permutation(&tour, count));
            }
        }
    }
}
