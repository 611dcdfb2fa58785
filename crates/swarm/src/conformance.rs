//! The checks every optimizer passes (the conformance suite), usable on any new
//! algorithm: same seed → same result; every evaluated point inside the box; the evaluation
//! budget honoured; a clear improvement on a shifted sphere.

use std::sync::Mutex;

use crate::problem::{Bounds, Problem};
use crate::runner::{Optimizer, Runner, Termination};

/// A shifted sphere that records whether any evaluated point left its box.
struct WatchedSphere {
    bounds: Bounds,
    shift: Vec<f64>,
    outside: Mutex<usize>,
}

impl Problem for WatchedSphere {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        if !self.bounds.contains(x) {
            *self
                .outside
                .lock()
                .expect("no panics while holding the lock") += 1;
        }
        x.iter()
            .zip(&self.shift)
            .map(|(x, o)| (x - o) * (x - o))
            .sum()
    }
}

fn sphere(dimension: usize) -> WatchedSphere {
    WatchedSphere {
        bounds: Bounds::cube(dimension, -10.0, 10.0).expect("a valid box"),
        shift: (0..dimension)
            .map(|d| 7.3 - 1.7 * d as f64 % 13.0)
            .collect(),
        outside: Mutex::new(0),
    }
}

/// Runs the suite on optimizers made by `make`; returns the first failure.
pub fn check<O: Optimizer>(make: impl Fn() -> O) -> Result<(), String> {
    let name = make().name();
    let problem = sphere(10);
    let budget = 4_000;
    let runner = Runner::new(Termination::evaluations(budget), 2024).expect("a budget");

    let first = runner.run(&mut make(), &problem, 3);
    let again = runner.run(&mut make(), &problem, 3);
    if first.best_cost.to_bits() != again.best_cost.to_bits()
        || first.best_position != again.best_position
    {
        return Err(format!(
            "{name}: the same seed gave {} and {}",
            first.best_cost, again.best_cost
        ));
    }
    let outside = *problem.outside.lock().expect("no poisoned lock");
    if outside > 0 {
        return Err(format!(
            "{name}: {outside} evaluated points were outside the box"
        ));
    }
    if first.evaluations > budget {
        return Err(format!(
            "{name}: {} evaluations for a budget of {budget}",
            first.evaluations
        ));
    }
    if !problem.bounds.contains(&first.best_position) {
        return Err(format!("{name}: the best point is outside the box"));
    }
    let start = first.history[0].best_cost;
    if first.best_cost >= 0.1 * start {
        return Err(format!(
            "{name}: no clear improvement on the shifted sphere ({start} → {})",
            first.best_cost
        ));
    }
    let other_run = runner.run(&mut make(), &problem, 4);
    if other_run.best_position == first.best_position {
        return Err(format!(
            "{name}: runs 3 and 4 gave the same point (shared stream?)"
        ));
    }
    Ok(())
}
