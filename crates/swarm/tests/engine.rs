//! The engine's promises over every algorithm: conformance, parallel = serial, CEC 2005 data.

use swarm::algorithms::Algorithm;
use swarm::functions::{self, FunctionProblem};
use swarm::{conformance, Problem, Runner, Termination};

#[test]
fn every_optimizer_passes_the_conformance_suite() {
    for algorithm in Algorithm::ALL.iter().copied() {
        conformance::check(|| algorithm.build(40)).unwrap_or_else(|fault| panic!("{fault}"));
    }
}

#[test]
fn parallel_runs_equal_serial_runs() {
    let problem = FunctionProblem::new(functions::by_key("f5").unwrap(), 10).unwrap();
    let runner = Runner::new(Termination::iterations(20), 99).unwrap();
    for algorithm in [Algorithm::IBA_FCS, Algorithm::LSHADE] {
        let parallel = runner.run_many(|| algorithm.build(30), &problem, 6, &|_| {});
        for (run, outcome) in parallel.iter().enumerate() {
            let serial = runner.run(&mut algorithm.build(30), &problem, run as u64);
            assert_eq!(outcome.run, run as u64);
            assert_eq!(outcome.best_cost.to_bits(), serial.best_cost.to_bits());
            assert_eq!(outcome.history, serial.history);
        }
    }
}

#[test]
fn cec2005_functions_match_the_published_vectors() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/cec2005/vectors.json"
    ))
    .unwrap();
    let vectors: serde_json::Value = serde_json::from_str(&text).unwrap();
    let points: Vec<Vec<f64>> = serde_json::from_value(vectors["points"].clone()).unwrap();
    for (name, key) in [("F1", "f1"), ("F2", "f2"), ("F3", "f3"), ("F6", "f6")] {
        let expected: Vec<f64> = serde_json::from_value(vectors["values"][name].clone()).unwrap();
        let function = functions::by_key(key).unwrap();
        for (point, want) in points.iter().zip(&expected) {
            let got = function.evaluate(point);
            let error = (got - want).abs() / want.abs().max(1.0);
            assert!(
                error <= 1e-9,
                "{name}: {got} vs {want} (relative {error:e})"
            );
        }
    }
}

#[test]
fn f3_refuses_dimensions_without_a_rotation_matrix() {
    let f3 = functions::by_key("f3").unwrap();
    assert!(FunctionProblem::new(f3, 20).is_err());
    for dimension in [10, 30, 50] {
        assert!(FunctionProblem::new(f3, dimension).is_ok());
    }
    let error = f3.check_dimension(40).unwrap_err().to_string();
    assert!(error.contains("10, 30, 50"), "{error}");
    let one = functions::by_key("f7")
        .unwrap()
        .check_dimension(1)
        .unwrap_err();
    assert!(one.to_string().contains("2 or more"), "{one}");
    assert!(FunctionProblem::new(functions::by_key("f1").unwrap(), 101).is_err());
    assert!(FunctionProblem::new(functions::by_key("f1").unwrap(), 50).is_ok());
}

#[test]
fn an_evaluation_budget_is_never_exceeded_and_a_target_stops_early() {
    let problem = FunctionProblem::new(functions::by_key("f1").unwrap(), 10).unwrap();
    let runner = Runner::new(Termination::evaluations(1_234), 1).unwrap();
    for algorithm in Algorithm::ALL.iter().copied() {
        let outcome = runner.run(&mut algorithm.build(50), &problem, 0);
        assert!(
            outcome.evaluations <= 1_234,
            "{algorithm}: {}",
            outcome.evaluations
        );
    }
    let runner = Runner::new(Termination::iterations(10_000).and_target(-449.0), 1).unwrap();
    let outcome = runner.run(&mut Algorithm::IBA_FCS.build(50), &problem, 0);
    assert_eq!(outcome.stopped_by, swarm::StopReason::Target);
    assert!(outcome.iterations < 10_000);
}

/// An optimizer that evaluates one point per step and declares itself converged at step 3.
struct GivesUp;

impl<'p> swarm::Optimizer<swarm::Continuous<'p>> for GivesUp {
    fn name(&self) -> &'static str {
        "gives up"
    }
    fn start(&mut self, search: &mut swarm::Search<swarm::Continuous<'p>>) {
        let x = search.random_position();
        search.evaluate(&x);
    }
    fn step(&mut self, search: &mut swarm::Search<swarm::Continuous<'p>>) {
        let x = search.random_position();
        search.evaluate(&x);
        if search.iteration() == 3 {
            search.declare_converged();
        }
    }
}

#[test]
fn an_optimizer_that_declares_convergence_ends_its_run_there() {
    let problem = FunctionProblem::new(functions::by_key("f1").unwrap(), 5).unwrap();
    let runner = Runner::new(Termination::evaluations(1_000), 1).unwrap();
    let outcome = runner.run(&mut GivesUp, &problem, 0);
    assert_eq!(outcome.stopped_by, swarm::StopReason::Converged);
    assert_eq!((outcome.iterations, outcome.evaluations), (3, 4));
}

#[test]
fn f3_at_d10_and_d30_matches_numpy() {
    // tests/data/f3_rotated_vectors.json: NumPy's F3 from the same official data files.
    let text = include_str!("data/f3_rotated_vectors.json");
    let data: serde_json::Value = serde_json::from_str(text).unwrap();
    let function = functions::by_key("f3").unwrap();
    let mut dimensions = Vec::new();
    for case in data["cases"].as_array().unwrap() {
        let point: Vec<f64> = serde_json::from_value(case["point"].clone()).unwrap();
        let want = case["value"].as_f64().unwrap();
        function.check_dimension(point.len()).unwrap();
        let got = function.evaluate(&point);
        let error = (got - want).abs() / want.abs().max(1.0);
        assert!(error <= 1e-12, "D = {}: {got} vs {want}", point.len());
        dimensions.push(point.len());
    }
    dimensions.dedup();
    assert_eq!(dimensions, vec![10, 30]);
    assert!(function.check_dimension(20).is_err());
}

/// Random search from branches: `start` spends `per_branch` evaluations on each of three
/// branches (in series, or through `Search::branch_out`), `step` samples on the main stream.
struct Branching {
    parallel: bool,
    per_branch: usize,
    seed: u64,
}

impl<'p> swarm::Optimizer<swarm::Continuous<'p>> for Branching {
    fn name(&self) -> &'static str {
        "branching random search (test)"
    }

    fn start(&mut self, run: &mut swarm::Search<swarm::Continuous<'p>>) {
        let per_branch = self.per_branch;
        let sample = |search: &mut swarm::Search<swarm::Continuous<'_>>| {
            (0..per_branch)
                .map(|_| {
                    let x = search.random_solution();
                    search.evaluate(&x)
                })
                .fold(f64::INFINITY, f64::min)
        };
        if self.parallel {
            let problem = run.problem();
            let copies = [problem, problem, problem];
            let bests = run.branch_out(&copies, u64::MAX, |_, branch| sample(branch));
            assert_eq!(bests.len(), 3);
        } else {
            // What the branches do, here one after another: branch k's stream is the run's,
            // long-jumped k + 1 times.
            for k in 0..3 {
                let mut stream = swarm::random::run_stream(self.seed, 0);
                for _ in 0..=k {
                    stream.long_jump();
                }
                for _ in 0..per_branch {
                    let x = run.problem().random_solution(&mut stream);
                    run.evaluate(&x);
                }
            }
        }
    }

    fn step(&mut self, run: &mut swarm::Search<swarm::Continuous<'p>>) {
        let x = run.random_solution();
        run.evaluate(&x);
    }
}

/// Work branched out to other cores leaves the run where the same work done in series
/// leaves it (count, best, history, the stream the steps draw from), on any number of
/// threads; a budget smaller than the branches' work is shared among them and honoured.
#[test]
fn branches_merge_as_if_run_in_series() {
    let problem = FunctionProblem::new(functions::by_key("f1").unwrap(), 5).unwrap();
    for budget in [500u64, 100] {
        let runner = Runner::new(Termination::evaluations(budget), 7).unwrap();
        let serial = runner.run(
            &mut Branching {
                parallel: false,
                per_branch: 60,
                seed: 7,
            },
            &problem,
            0,
        );
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let branched = pool.install(|| {
                runner.run(
                    &mut Branching {
                        parallel: true,
                        per_branch: 60,
                        seed: 7,
                    },
                    &problem,
                    0,
                )
            });
            if budget >= 3 * 60 {
                assert_eq!(branched.best_cost.to_bits(), serial.best_cost.to_bits());
                assert_eq!(branched.best_solution, serial.best_solution);
                assert_eq!(branched.evaluations, serial.evaluations);
                assert_eq!(branched.history, serial.history);
                assert!(serial.iterations > 0);
            } else {
                // Three branches share 100 evaluations (34, 33, 33): the budget honoured.
                assert_eq!(branched.evaluations, budget);
                assert_eq!(branched.iterations, 0);
            }
        }
        assert!(serial.best_cost < problem.evaluate(&problem.first_solution()));
    }
}

/// First improvement over seven random neighbours per step: in series with `evaluate`, or
/// through `Search::evaluate_until` (batches on the pool's threads).
struct FirstImprovement {
    batched: bool,
}

impl<'p> swarm::Optimizer<swarm::Continuous<'p>> for FirstImprovement {
    fn name(&self) -> &'static str {
        "first improvement (test)"
    }

    fn start(&mut self, run: &mut swarm::Search<swarm::Continuous<'p>>) {
        let x = run.random_solution();
        run.evaluate(&x);
    }

    fn step(&mut self, run: &mut swarm::Search<swarm::Continuous<'p>>) {
        let best = run.best_solution().to_vec();
        let neighbours: Vec<Vec<f64>> = (0..7)
            .map(|_| {
                let mut x = best.clone();
                for value in &mut x {
                    *value += run.uniform_in(-10.0, 10.0);
                }
                run.clamp(&mut x);
                x
            })
            .collect();
        let threshold = run.best_cost();
        let accept = |cost: f64| cost < threshold;
        if self.batched {
            run.evaluate_until(&neighbours, usize::MAX, accept);
        } else {
            for x in &neighbours {
                if accept(run.evaluate(x)) {
                    break;
                }
            }
        }
    }
}

/// Candidates scored side by side and counted in order leave the run where `evaluate` one
/// after another leaves it (count, best, history), on one thread or four, with budgets that
/// end inside a batch.
#[test]
fn evaluate_until_is_evaluate_in_series() {
    let problem = FunctionProblem::new(functions::by_key("f1").unwrap(), 5).unwrap();
    for budget in [400u64, 57] {
        let runner = Runner::new(Termination::evaluations(budget), 3).unwrap();
        let serial = runner.run(&mut FirstImprovement { batched: false }, &problem, 0);
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let batched =
                pool.install(|| runner.run(&mut FirstImprovement { batched: true }, &problem, 0));
            assert_eq!(batched.best_cost.to_bits(), serial.best_cost.to_bits());
            assert_eq!(batched.best_solution, serial.best_solution);
            assert_eq!(batched.evaluations, serial.evaluations);
            assert_eq!(batched.history, serial.history);
        }
        assert_eq!(serial.evaluations, budget);
        assert!(serial.best_cost < problem.evaluate(&problem.first_solution()));
    }
}
