//! `gsa`: seed 003 §1.2's return-point search. The variables are the spray metres of each
//! sortie but the last, D = (d_1 … d_N) for N returns: flying the route, the drone returns when
//! the spray metres of its sortie would pass d_n (at the last route point within d_n), and the
//! fitness is E (eq. 2). The dimension N cannot change during a search, so there is one search
//! per number of returns (seed 003: "还须对不同维数分别进行寻优计算").
//!
//! The search is the gravitational search algorithm of `swarm` (Rashedi 2009, docs/references.md; the seed's
//! eqs. 3-4 are its velocity and position updates) with G0 = 100, α = 20 and Kbest shrinking
//! linearly to 2 %. The seed does not give the population or the iterations: 50 agents (the
//! population of Rashedi's own code) and 500 iterations per number of returns (`GsaSettings`;
//! on the strip 30 × 100 found no 4-return split, 50 × 200 one 18 % above the paper's round
//! trip, 50 × 500 417-422 m over three seeds), tried for N from the fewest returns the tank
//! and battery allow to two more. The variables are searched as shares of a tank
//! (d_n = u_n·D_max, u ∈ [0, 1]): GSA's G0 = 100 and its pull scaled by distance are made
//! for unit-scale boxes; on a 2,700 m box it barely moves. A split that over-fills a tank or over-flies a
//! battery is penalised by 10⁶ s plus 10³ per metre or second of excess, so feasible splits
//! always win. Evaluations are counted by the Runner and never exceed the budget.

use swarm::algorithms::{GravitationalSearch, GravitationalSearchParameters};
use swarm::{Bounds, FnProblem, Runner, Termination};

use super::route::WorkRoute;
use super::SortieModel;
use crate::error::Fault;

/// The search budget per number of returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GsaSettings {
    /// Agents per search.
    pub population: usize,
    /// Iterations per search.
    pub iterations: usize,
    /// How many numbers of returns above the fewest possible to try.
    pub extra_returns: usize,
}

impl Default for GsaSettings {
    fn default() -> Self {
        Self {
            population: 50,
            iterations: 500,
            extra_returns: 2,
        }
    }
}

impl GsaSettings {
    /// Evaluations allowed per number of returns.
    pub fn evaluations_per_search(&self) -> u64 {
        (self.population * (self.iterations + 1)) as u64
    }
}

/// What the search found.
#[derive(Debug, Clone, PartialEq)]
pub struct GsaOutcome {
    /// Route point indices where the drone returns in the best split.
    pub breaks: Vec<usize>,
    /// The thresholds d_n of the best split.
    pub thresholds: Vec<f64>,
    /// Evaluations spent over all numbers of returns.
    pub evaluations: u64,
    /// (returns, best fitness) for every number of returns tried.
    pub tried: Vec<(usize, f64)>,
}

/// The breaks the thresholds `d` give: each sortie ends at the last point within d_n spray
/// metres of its start (at least one point on).
pub fn decode(route: &WorkRoute, thresholds: &[f64]) -> Vec<usize> {
    let last = route.len() - 1;
    let mut breaks = Vec::with_capacity(thresholds.len());
    let mut first = 0;
    for &threshold in thresholds {
        // The largest j with spray(first, j) ≤ threshold (spray only grows along the route).
        let (mut low, mut high) = (first, last);
        while low < high {
            let middle = (low + high).div_ceil(2);
            if route.spray_between(first, middle) <= threshold {
                low = middle;
            } else {
                high = middle - 1;
            }
        }
        let end = low.max(first + 1);
        if end >= last {
            break;
        }
        breaks.push(end);
        first = end;
    }
    breaks
}

/// E's return part for `breaks`, with the penalty for sorties one tank or battery cannot fly.
pub fn fitness(route: &WorkRoute, model: &SortieModel, breaks: &[usize]) -> f64 {
    let last = route.len() - 1;
    let mut total = 0.0;
    let mut first = 0;
    for end in breaks.iter().copied().chain(std::iter::once(last)) {
        if first > 0 {
            total += model.return_cost_s(route, first, end);
        }
        let spray_excess = model.spray_per_tank_m.map_or(0.0, |tank| {
            (route.spray_between(first, end) - tank).max(0.0)
        });
        let time_excess = (model.flight_s(route, first, end) - model.usable_s()).max(0.0);
        if spray_excess > 1e-6 || time_excess > 1e-6 {
            total += 1e6 + 1e3 * (spray_excess + time_excess);
        }
        first = end;
    }
    total
}

/// The fewest returns any split needs (tank and battery lower bounds).
fn fewest_returns(route: &WorkRoute, model: &SortieModel) -> usize {
    let by_tank = model
        .spray_per_tank_m
        .map_or(1.0, |tank| (route.total_spray_m() / tank).ceil());
    let by_battery = (route.flight_between(0, route.len() - 1) / model.usable_s()).ceil();
    (by_tank.max(by_battery).max(1.0) as usize) - 1
}

/// One GSA search per number of returns; the best feasible split overall.
pub fn search(
    route: &WorkRoute,
    model: &SortieModel,
    settings: &GsaSettings,
    seed: u64,
) -> Result<GsaOutcome, Fault> {
    let upper = model
        .spray_per_tank_m
        .unwrap_or_else(|| route.total_spray_m())
        .max(1e-3);
    let fewest = fewest_returns(route, model);
    let mut best: Option<(f64, Vec<usize>, Vec<f64>)> = None;
    let mut evaluations = 0;
    let mut tried = Vec::new();
    for returns in fewest..=fewest + settings.extra_returns {
        let (cost, breaks, thresholds) = if returns == 0 {
            (fitness(route, model, &[]), vec![], vec![])
        } else {
            // The variables are shares of a tank (d_n = u_n·D_max): GSA's G0 = 100 and its
            // distance-scaled pull are made for unit-scale boxes, not 2,700 m wide ones.
            let bounds = Bounds::cube(returns, 0.0, 1.0).expect("a unit box");
            let to_metres =
                |u: &[f64]| -> Vec<f64> { u.iter().map(|share| share * upper).collect() };
            let problem = FnProblem::new(bounds, |u: &[f64]| {
                fitness(route, model, &decode(route, &to_metres(u)))
            });
            let runner = Runner::new(
                Termination::evaluations(settings.evaluations_per_search()),
                seed,
            )
            .expect("a positive budget");
            let mut optimizer = GravitationalSearch::new(GravitationalSearchParameters {
                population: settings.population,
                ..Default::default()
            });
            let outcome = runner.run(&mut optimizer, &problem, returns as u64);
            evaluations += outcome.evaluations;
            let thresholds = to_metres(&outcome.best_solution);
            (outcome.best_cost, decode(route, &thresholds), thresholds)
        };
        tried.push((returns, cost));
        if cost < 1e6
            && best
                .as_ref()
                .is_none_or(|(best_cost, _, _)| cost < *best_cost)
        {
            best = Some((cost, breaks, thresholds));
        }
    }
    let (_, breaks, thresholds) = best.ok_or_else(|| {
        Fault::Structure(
            "--sorties gsa: the gravitational search (seed 003's planner, which tries a fixed range of return counts) found no split that one tank and one battery fly on this farm; the default planner (--sorties joint) and --sorties exact always find one when it exists".into(),
        )
    })?;
    Ok(GsaOutcome {
        breaks,
        thresholds,
        evaluations,
        tried,
    })
}
