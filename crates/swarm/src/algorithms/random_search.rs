//! Random search: the baseline every search has to beat, and the proof that an optimizer is
//! one file. Each step draws `samples` solutions uniformly from the problem's whole space
//! ([`Problem::random_solution`]) and costs them; the Runner keeps the best.
//!
//! It is written against [`Problem`] alone, so the same value runs on a box of reals, on a
//! swath order with its entry ends, and on a grid route: whatever the problem declares as
//! its solution.

use crate::problem::{as_solution, Problem};
use crate::runner::{Optimizer, Search};

use super::Algorithm;

/// On the command line and in tables: `random`, "Random search".
pub const ALGORITHM: Algorithm = Algorithm::new("random", "Random search", |population| {
    Box::new(RandomSearch::new(population))
});

/// Pure random search with `samples` draws per step.
#[derive(Debug, Clone, PartialEq)]
pub struct RandomSearch {
    samples: usize,
}

impl RandomSearch {
    /// `samples` draws per step (at least one).
    pub fn new(samples: usize) -> Self {
        Self {
            samples: samples.max(1),
        }
    }

    fn sample<P: Problem + ?Sized>(&self, search: &mut Search<P>) {
        for _ in 0..self.samples {
            let solution = search.random_solution();
            search.evaluate(as_solution::<P>(&solution));
        }
    }
}

impl Default for RandomSearch {
    /// 50 draws per step, as many as seed 000's populations.
    fn default() -> Self {
        Self::new(50)
    }
}

impl<P: Problem + ?Sized> Optimizer<P> for RandomSearch {
    fn name(&self) -> &'static str {
        "Random search"
    }

    fn start(&mut self, search: &mut Search<P>) {
        self.sample(search);
    }

    fn step(&mut self, search: &mut Search<P>) {
        self.sample(search);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Bounds, FnProblem, Runner, Termination};

    #[test]
    fn random_search_spends_its_budget_exactly_and_keeps_the_best_draw() {
        let problem = FnProblem::new(Bounds::cube(3, -1.0, 1.0).unwrap(), |x: &[f64]| {
            x.iter().map(|v| v * v).sum::<f64>()
        });
        let runner = Runner::new(Termination::evaluations(1_000), 7).unwrap();
        let outcome = runner.run(&mut RandomSearch::new(10), &problem, 0);
        assert_eq!(outcome.evaluations, 1_000);
        let cost: f64 = outcome.best_solution.iter().map(|v| v * v).sum();
        assert_eq!(cost, outcome.best_cost);
        // 1,000 uniform draws in [-1, 1]³: the best is well inside a ball of radius 0.3.
        assert!(outcome.best_cost < 0.09, "{}", outcome.best_cost);
    }
}
