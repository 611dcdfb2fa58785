//! Our planner: lattice corridors ([`super::lattice`]) refined waypoint by waypoint on the
//! real cost.
//!
//! Every cost model here is a sum over legs and corners, so moving one waypoint changes only
//! the terms next to it: the refinement moves one waypoint at a time. Each lane (one
//! corridor) keeps a step size per waypoint; a waypoint tries a Gaussian move of its step
//! (or, every other pass, a pull towards the middle of its neighbours, which straightens the
//! track), keeps it if the track's cost falls, and its step grows by half on success and
//! shrinks by a tenth on failure (a per-waypoint one-fifth rule). Once per pass a lane also
//! tries merging a waypoint into a neighbour (with costs counted per leg, fewer legs along
//! a threat's danger band cost less; SPSO's best runs do this too) and a shortcut: a random
//! run of waypoints laid evenly on the straight leg between its outer neighbours. Lanes that trail the best
//! by then are dropped at a third of the budget, so the rest goes to the best corridor.
//!
//! It runs on the swarm engine like every planner (the Runner counts its evaluations and
//! keeps its convergence history) with the Cartesian encoding. Once one lane is left and a
//! tenth of the budget has passed without its cost falling by a thousandth, it declares
//! itself converged and hands the rest of the budget back.

use swarm::{Continuous, Optimizer, Search};

use super::lattice;
use super::scenario::TrackScenario;

/// Waypoint `k` of the Cartesian vector `x`; −1 is the cruise's start and one past the last
/// its goal.
fn waypoint(scenario: &TrackScenario, x: &[f64], k: isize) -> [f64; 3] {
    let count = (x.len() / 3) as isize;
    if k < 0 {
        scenario.cruise_start
    } else if k >= count {
        scenario.cruise_goal
    } else {
        let k = 3 * k as usize;
        [x[k], x[k + 1], x[k + 2]]
    }
}

/// Corridors searched.
const LANES: usize = 4;

struct Lane {
    x: Vec<f64>,
    cost: f64,
    /// Step per waypoint, as a share of the box width of each coordinate.
    steps: Vec<f64>,
}

/// Our track planner as an optimizer: lattice corridors refined waypoint by waypoint, on a
/// track problem with the Cartesian encoding.
pub struct LatticeRefine<'a> {
    scenario: &'a TrackScenario,
    lanes: Vec<Lane>,
    pass: usize,
    /// The best cost at the last real improvement, and the share of the budget used then.
    improved: (f64, f64),
}

/// Share of the budget without a relative improvement of [`STILL`] after which the lane
/// has converged.
const PATIENCE: f64 = 0.1;
const STILL: f64 = 1e-3;

impl<'a> LatticeRefine<'a> {
    /// The planner over `scenario`; the corridors are laid when the run starts.
    pub fn new(scenario: &'a TrackScenario) -> Self {
        Self {
            scenario,
            lanes: Vec::new(),
            pass: 0,
            improved: (f64::INFINITY, 0.0),
        }
    }
}

impl<'p> Optimizer<Continuous<'p>> for LatticeRefine<'_> {
    fn name(&self) -> &'static str {
        "lattice + refine"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let encoding = super::encoding::Encoding::Cartesian;
        let mut starts: Vec<Vec<f64>> = lattice::corridors(self.scenario, LANES)
            .iter()
            .map(|waypoints| encoding.encode(self.scenario, waypoints))
            .collect();
        if starts.is_empty() {
            // No corridor on the lattice (every way closed): start from random tracks.
            starts = (0..LANES).map(|_| search.random_position()).collect();
        }
        let waypoints = search.dimension() / 3;
        self.lanes = starts
            .into_iter()
            .map(|mut x| {
                search.clamp(&mut x);
                let cost = search.evaluate(&x);
                Lane {
                    x,
                    cost,
                    steps: vec![0.02; waypoints],
                }
            })
            .collect();
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        self.pass += 1;
        let best = search.best_cost();
        if !self.improved.0.is_finite() || best < self.improved.0 - STILL * self.improved.0.abs() {
            self.improved = (best, search.progress());
        } else if self.lanes.len() == 1 && search.progress() - self.improved.1 > PATIENCE {
            search.declare_converged();
            return;
        }
        if search.progress() > 0.15 && self.lanes.len() > 1 {
            let best = self
                .lanes
                .iter()
                .map(|lane| lane.cost)
                .fold(f64::INFINITY, f64::min);
            self.lanes.retain(|lane| lane.cost <= best);
            self.lanes.truncate(1);
        }
        let dimension = search.dimension();
        let widths: Vec<f64> = (0..dimension).map(|d| search.bounds().width(d)).collect();
        let straighten = self.pass.is_multiple_of(2);
        for lane in &mut self.lanes {
            let waypoints = lane.steps.len();
            for _ in 0..waypoints {
                let index = search.below(waypoints);
                let mut candidate = lane.x.clone();
                if straighten {
                    // Towards the middle of the neighbours (start and goal at the ends).
                    let (before, after) = (
                        waypoint(self.scenario, &lane.x, index as isize - 1),
                        waypoint(self.scenario, &lane.x, index as isize + 1),
                    );
                    let pull = search.uniform_in(0.1, 0.6);
                    for axis in 0..2 {
                        let middle = 0.5 * (before[axis] + after[axis]);
                        candidate[3 * index + axis] +=
                            pull * (middle - candidate[3 * index + axis]);
                    }
                    candidate[3 * index + 2] +=
                        lane.steps[index] * widths[3 * index + 2] * search.normal();
                } else {
                    for axis in 0..3 {
                        let d = 3 * index + axis;
                        candidate[d] += lane.steps[index] * widths[d] * search.normal();
                    }
                }
                search.clamp(&mut candidate);
                let cost = search.evaluate(&candidate);
                if cost < lane.cost {
                    lane.x = candidate;
                    lane.cost = cost;
                    lane.steps[index] = (lane.steps[index] * 1.5).min(0.2);
                } else {
                    lane.steps[index] = (lane.steps[index] * 0.9).max(1e-5);
                }
            }
            // Shortcut: waypoints first..=last put evenly on the straight leg between their
            // outer neighbours (what the improved GA gets by deleting waypoints).
            let first = search.below(waypoints);
            let last = (first + 1 + search.below(waypoints - first)).min(waypoints) - 1;
            let (before, after) = (
                waypoint(self.scenario, &lane.x, first as isize - 1),
                waypoint(self.scenario, &lane.x, last as isize + 1),
            );
            let mut candidate = lane.x.clone();
            let span = (last - first + 2) as f64;
            for (offset, k) in (first..=last).enumerate() {
                let t = (offset + 1) as f64 / span;
                for axis in 0..3 {
                    candidate[3 * k + axis] = before[axis] + t * (after[axis] - before[axis]);
                }
            }
            search.clamp(&mut candidate);
            let cost = search.evaluate(&candidate);
            if cost < lane.cost {
                lane.x = candidate;
                lane.cost = cost;
            }
            // Merge a waypoint into a neighbour: costs counted per leg (the threat terms of
            // seed 000 and SPSO) fall when a track near a threat has fewer legs there.
            let index = search.below(waypoints);
            let other = if index + 1 < waypoints && (index == 0 || search.uniform() < 0.5) {
                index + 1
            } else {
                index.saturating_sub(1)
            };
            if other != index {
                let mut candidate = lane.x.clone();
                for axis in 0..3 {
                    candidate[3 * index + axis] = lane.x[3 * other + axis];
                }
                let cost = search.evaluate(&candidate);
                if cost < lane.cost {
                    lane.x = candidate;
                    lane.cost = cost;
                }
            }
        }
    }
}
