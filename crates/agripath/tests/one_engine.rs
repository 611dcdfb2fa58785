//! One engine for every search (issue 18): the random-search baseline, written once in
//! `swarm/src/algorithms/random_search.rs`, runs through the same Runner on a continuous
//! function, on the swath-ordering problem and on a grid route; and the three searches of the
//! planning stages (seed 001's ant colony, our iterated local search, seed 004's HPSO) pass
//! the engine's conformance checks with the stages' own validity checkers.

use std::path::Path;

use agripath::coverage::drape::GroundPoint;
use agripath::grid_cover::hybrid_pso::{check_point_order, HybridPso, TurnProblem};
use agripath::grid_cover::PointGrid;
use agripath::input::{read_farm, CoordinateChoice};
use agripath::sequence::ant_colony::{AntColonySettings, SwathAntColony};
use agripath::sequence::local_search::IteratedLocalSearch;
use agripath::sequence::tour::{check_order, OrderingProblem, Start};
use agripath::sequence::TransferModel;
use swarm::algorithms::RandomSearch;
use swarm::functions::{self, FunctionProblem};
use swarm::{conformance, Problem, Runner, Termination};

fn data(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(name)
}

/// `passes` passes scattered over 480 × 320 m at three lengths and two directions: an
/// ordering instance with a real transfer model, irregular enough that searches from
/// different seeds end in different tours (on a small regular lattice of passes the local
/// search finds one tour from every seed, and the conformance check that runs differ could
/// not tell a shared stream).
fn with_ordering_problem<T>(passes: u32, body: impl FnOnce(&OrderingProblem) -> T) -> T {
    let farm = agripath::demo::scenario().unwrap().farm;
    let model = TransferModel::new(&farm, 10.0);
    let point = |x: f64, y: f64| GroundPoint {
        x,
        y,
        ground_m: 0.0,
    };
    let ends: Vec<[GroundPoint; 2]> = (0..passes)
        .map(|k| {
            let x = f64::from((k * 37) % 53) * 9.0 + f64::from(k / 53) * 3.0;
            let y = f64::from((k * 17) % 29) * 11.0 + f64::from(k / 29) * 4.0;
            let length = [40.0, 70.0, 100.0][(k % 3) as usize];
            if k % 2 == 0 {
                [point(x, y), point(x, y + length)]
            } else {
                [point(x, y), point(x + length, y)]
            }
        })
        .collect();
    let problem = OrderingProblem::new(ends, Start::Fixed(point(-50.0, -50.0)), &model);
    body(&problem)
}

fn seed004_grid() -> PointGrid {
    let farm = read_farm(&data("seed004_double_1.geojson"), CoordinateChoice::Local).unwrap();
    PointGrid::new(&farm, 0, 5.0).unwrap()
}

#[test]
fn random_search_runs_on_a_function_a_swath_order_and_a_grid_route_through_one_runner() {
    let runner = Runner::new(Termination::evaluations(2_000), 5).unwrap();

    let sphere = FunctionProblem::new(functions::by_key("f1").unwrap(), 10).unwrap();
    let continuous = runner.run(&mut RandomSearch::new(20), &sphere, 0);
    assert_eq!(continuous.evaluations, 2_000);
    assert!(continuous.best_cost.is_finite());
    assert_eq!(continuous.best_solution.len(), 10);

    let order = with_ordering_problem(30, |problem| {
        let outcome = runner.run_problem(&mut RandomSearch::new(20), problem, 0, &mut ());
        check_order(&outcome.best_solution, problem.passes()).unwrap();
        assert_eq!(problem.evaluate(&outcome.best_solution), outcome.best_cost);
        outcome
    });
    assert_eq!(order.evaluations, 2_000);

    let grid = seed004_grid();
    let turns = TurnProblem::new(&grid);
    let route = runner.run_problem(&mut RandomSearch::new(20), &turns, 0, &mut ());
    check_point_order(&route.best_solution, grid.points.len()).unwrap();
    assert_eq!(route.evaluations, 2_000);
    // Random permutations of 240 points cross the obstacles: far from the 30-odd turns of a
    // real planner, which is what a baseline is for.
    assert!(route.best_cost > 100.0, "{}", route.best_cost);
}

#[test]
fn the_planning_searches_pass_the_engine_conformance_checks() {
    with_ordering_problem(30, |problem| {
        let passes = problem.passes();
        let valid = |tour: &[agripath::sequence::tour::Step]| check_order(tour, passes);
        let settings = AntColonySettings {
            ants: 10,
            ..AntColonySettings::default()
        };
        let colony =
            conformance::check_problem(|| SwathAntColony::new(settings), problem, 400, valid)
                .unwrap();
        let random =
            conformance::check_problem(|| RandomSearch::new(10), problem, 400, valid).unwrap();
        assert!(colony.best_cost < random.best_cost);
    });
    // Our local search on a larger instance: on 30 passes it may reach one tour from every
    // seed, and the check that runs differ would fail for a search that is merely good.
    with_ordering_problem(150, |problem| {
        let passes = problem.passes();
        let valid = |tour: &[agripath::sequence::tour::Step]| check_order(tour, passes);
        let groups = vec![(0..passes).collect::<Vec<_>>()];
        let local = conformance::check_problem(
            || IteratedLocalSearch::new(&groups, 1),
            problem,
            20_000,
            valid,
        )
        .unwrap();
        let settings = AntColonySettings {
            ants: 10,
            ..AntColonySettings::default()
        };
        let colony =
            conformance::check_problem(|| SwathAntColony::new(settings), problem, 2_000, valid)
                .unwrap();
        assert!(local.best_cost <= colony.best_cost + 1e-6);
    });

    let grid = seed004_grid();
    let turns = TurnProblem::new(&grid);
    let points = grid.points.len();
    let hpso = conformance::check_problem(
        || HybridPso::new(10),
        &turns,
        3_000,
        |order: &[usize]| check_point_order(order, points),
    )
    .unwrap();
    assert!(hpso.best_cost < hpso.history[0].best_cost);
}
