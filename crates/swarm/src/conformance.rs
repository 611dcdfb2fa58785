//! The checks every optimizer passes, usable on any new algorithm and any solution type:
//! same seed → same result; every evaluated solution valid (inside the box, a permutation, …);
//! the evaluation budget honoured; runs with different numbers on different streams; a
//! history that never gets worse; and, for continuous optimizers, a clear improvement on a
//! shifted sphere.

use crate::problem::{as_solution, Bounds, BoxProblem, Problem, SolutionOf};
use crate::runner::{Continuous, Observer, Optimizer, Outcome, Record, Runner, Termination};

/// Checks every solution costed during a run, keeping the first fault.
struct Inspector<'v, V> {
    valid: &'v V,
    first_fault: Option<String>,
}

impl<S: ?Sized, V: Fn(&S) -> Result<(), String>> Observer<S> for Inspector<'_, V> {
    fn observe(&mut self, _record: &Record) {}

    fn evaluated(&mut self, solution: &S, _cost: f64) {
        if self.first_fault.is_none() {
            if let Err(fault) = (self.valid)(solution) {
                self.first_fault = Some(fault);
            }
        }
    }
}

/// Runs the general suite on optimizers made by `make`, on `problem`, under an evaluation
/// budget of `budget`; `valid` says whether a solution is one (e.g. a permutation of every
/// pass). Returns the first run's outcome, for checks of quality by the caller.
pub fn check_problem<P, O, V>(
    make: impl Fn() -> O,
    problem: &P,
    budget: u64,
    valid: V,
) -> Result<Outcome<SolutionOf<P>>, String>
where
    P: Problem + ?Sized,
    SolutionOf<P>: PartialEq,
    O: Optimizer<P>,
    V: Fn(&P::Solution) -> Result<(), String> + Sync,
{
    let name = make().name();
    let runner = Runner::new(Termination::evaluations(budget), 2024).expect("a budget");
    let run = |number: u64| -> Result<Outcome<SolutionOf<P>>, String> {
        let mut inspector = Inspector {
            valid: &valid,
            first_fault: None,
        };
        let outcome = runner.run_problem(&mut make(), problem, number, &mut inspector);
        match inspector.first_fault {
            Some(fault) => Err(format!(
                "{name}: an evaluated solution was not valid: {fault}"
            )),
            None => Ok(outcome),
        }
    };
    let first = run(3)?;
    let again = run(3)?;
    if first.best_cost.to_bits() != again.best_cost.to_bits()
        || first.best_solution != again.best_solution
    {
        return Err(format!(
            "{name}: the same seed gave {} and {}",
            first.best_cost, again.best_cost
        ));
    }
    valid(as_solution::<P>(&first.best_solution))
        .map_err(|fault| format!("{name}: the best solution is not valid: {fault}"))?;
    if first.evaluations > budget {
        return Err(format!(
            "{name}: {} evaluations for a budget of {budget}",
            first.evaluations
        ));
    }
    if first.evaluations == 0 {
        return Err(format!("{name}: the run evaluated nothing"));
    }
    if first.best_cost.to_bits()
        != problem
            .evaluate(as_solution::<P>(&first.best_solution))
            .to_bits()
    {
        return Err(format!(
            "{name}: the reported cost is not the best solution's"
        ));
    }
    if first
        .history
        .windows(2)
        .any(|pair| pair[1].best_cost > pair[0].best_cost)
    {
        return Err(format!("{name}: the best cost got worse during the run"));
    }
    let other_run = run(4)?;
    if other_run.best_solution == first.best_solution && other_run.history == first.history {
        return Err(format!(
            "{name}: runs 3 and 4 gave the same history (shared stream?)"
        ));
    }
    Ok(first)
}

/// A shifted sphere in 10 dimensions on [-10, 10].
struct ShiftedSphere {
    bounds: Bounds,
    shift: Vec<f64>,
}

impl BoxProblem for ShiftedSphere {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        x.iter()
            .zip(&self.shift)
            .map(|(x, o)| (x - o) * (x - o))
            .sum()
    }
}

/// Runs the suite on continuous optimizers made by `make`: the general checks with "inside
/// the box" as validity, under 4,000 evaluations, then a clear improvement (best ≤ 1/10 of
/// the start's) on the shifted sphere. Returns the first failure.
pub fn check<O: for<'p> Optimizer<Continuous<'p>>>(make: impl Fn() -> O) -> Result<(), String> {
    let dimension = 10;
    let problem = ShiftedSphere {
        bounds: Bounds::cube(dimension, -10.0, 10.0).expect("a valid box"),
        shift: (0..dimension)
            .map(|d| 7.3 - 1.7 * d as f64 % 13.0)
            .collect(),
    };
    let bounds = problem.bounds.clone();
    let inside = move |x: &[f64]| {
        if bounds.contains(x) {
            Ok(())
        } else {
            Err("a point outside the box".to_string())
        }
    };
    let dynamic: &dyn BoxProblem = &problem;
    let first = check_problem(make, dynamic, 4_000, inside)?;
    let start = first.history[0].best_cost;
    if first.best_cost >= 0.1 * start {
        return Err(format!(
            "{}: no clear improvement on the shifted sphere ({start} → {})",
            first.algorithm, first.best_cost
        ));
    }
    Ok(())
}
