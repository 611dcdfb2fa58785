//! Seed 001's improved ant colony for ordering swaths with their entry ends (§3, eqs. 2-13).
//!
//! Each ant m of batch t builds a route R^m(t) (eq. 2) and records the entry end of every
//! swath, O^m(t) (eq. 3). From swath i (left by its exit end), swath j is entered by end A_j
//! or B_j with probabilities (eqs. 4-5)
//!
//!   p_iAj = τ_ij^α η_iAj^β / Σ_k∈V τ_ik^α (η_iAk^β + η_iBk^β),   p_iBj likewise,
//!
//! where η is 1/d of the end actually reached from the end i is left by (eqs. 11-12; their
//! indices are swapped in print, MISSION.md decision 3), and d is eq. (8)'s transfer cost
//! (eqs. 6-10). After each batch the pheromone evaporates and every ant deposits Q/l_m on the
//! pairs it flew (ant-cycle model, eq. 13). Parameters as the seed: α = 1, β = 5, ρ = 0.1,
//! Q = 100, 50 ants, 100 or 200 batches.
//!
//! Deviations from the paper, all where it is silent: the initial pheromone is 1 on every
//! pair; a fixed start point is node 0 of the pheromone matrix (so the first choice learns
//! too); with a free start each ant starts at a random swath and end (the seed's option ②) and
//! its tour is closed; d = 0 uses d = 1e-6 m; the best tour of all batches is returned.

use serde::Serialize;
use swarm::random::{below, uniform};

use super::tour::{OrderingProblem, Start, Step};

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AntColonySettings {
    pub ants: usize,
    pub batches: usize,
    pub alpha: f64,
    pub beta: f64,
    pub evaporation: f64,
    pub deposit: f64,
    pub initial_pheromone: f64,
    pub seed: u64,
}

impl Default for AntColonySettings {
    /// Seed 001 §5 (the real farm): T = 200 batches, M = 50, α = 1, β = 5, ρ = 0.1, Q = 100.
    fn default() -> Self {
        Self {
            ants: 50,
            batches: 200,
            alpha: 1.0,
            beta: 5.0,
            evaporation: 0.1,
            deposit: 100.0,
            initial_pheromone: 1.0,
            seed: 1,
        }
    }
}

/// Smallest distance used in η = 1/d.
const TINY_DISTANCE_M: f64 = 1e-6;

/// Runs the colony; returns the best tour and the best cost after each batch.
pub fn ant_colony(
    problem: &OrderingProblem,
    settings: &AntColonySettings,
) -> (Vec<Step>, Vec<f64>) {
    let passes = problem.passes();
    if passes == 0 {
        return (Vec::new(), Vec::new());
    }
    let ends = 2 * passes;
    // Eqs. (6)-(10): every end to every end; row `ends` is the fixed start point.
    let mut distance = vec![0.0; (ends + 1) * ends];
    for from in 0..ends {
        for to in 0..ends {
            if from / 2 != to / 2 {
                distance[from * ends + to] = problem.cost(from, to);
            }
        }
    }
    for to in 0..ends {
        distance[ends * ends + to] = problem.cost_from_start(to);
    }
    // η^β precomputed per end pair.
    let visibility: Vec<f64> = distance
        .iter()
        .map(|d| (1.0 / d.max(TINY_DISTANCE_M)).powf(settings.beta))
        .collect();
    // Pheromone between passes; node `passes` is the start point.
    let nodes = passes + 1;
    let mut pheromone = vec![settings.initial_pheromone; nodes * nodes];
    let mut stream = swarm::run_stream(settings.seed, 0);
    let mut best: Option<(f64, Vec<Step>)> = None;
    let mut history = Vec::with_capacity(settings.batches);
    let mut weights = vec![0.0; ends];
    for _ in 0..settings.batches {
        let mut batch: Vec<(f64, Vec<Step>)> = Vec::with_capacity(settings.ants);
        for _ in 0..settings.ants {
            let mut visited = vec![false; passes];
            let mut tour: Vec<Step> = Vec::with_capacity(passes);
            if problem.start == Start::Free {
                let pass = below(&mut stream, passes);
                let step = Step {
                    pass,
                    reversed: below(&mut stream, 2) == 1,
                };
                visited[pass] = true;
                tour.push(step);
            }
            while tour.len() < passes {
                let (from_node, from_end) = match tour.last() {
                    Some(step) => (step.pass, step.exit()),
                    None => (passes, ends),
                };
                let mut total = 0.0;
                for pass in 0..passes {
                    for side in 0..2 {
                        let end = 2 * pass + side;
                        weights[end] = if visited[pass] {
                            0.0
                        } else {
                            let trail = pheromone[from_node * nodes + pass];
                            let trail = if settings.alpha == 1.0 {
                                trail
                            } else {
                                trail.powf(settings.alpha)
                            };
                            trail * visibility[from_end * ends + end]
                        };
                        total += weights[end];
                    }
                }
                // Roulette wheel over (pass, entry end).
                let mut target = total * uniform(&mut stream);
                let mut chosen = None;
                for (end, weight) in weights.iter().enumerate() {
                    if *weight > 0.0 {
                        chosen = Some(end);
                        if target < *weight {
                            break;
                        }
                        target -= weight;
                    }
                }
                let end = chosen.expect("an unvisited pass remains");
                visited[end / 2] = true;
                tour.push(Step {
                    pass: end / 2,
                    reversed: end % 2 == 1,
                });
            }
            let cost = problem.tour_cost(&tour);
            batch.push((cost, tour));
        }
        // Eq. (13): evaporate, then deposit Q / l_m on every pair each ant flew.
        for value in &mut pheromone {
            *value *= 1.0 - settings.evaporation;
        }
        for (cost, tour) in &batch {
            let deposit = settings.deposit / cost.max(TINY_DISTANCE_M);
            if let (Start::Fixed(_), Some(first)) = (problem.start, tour.first()) {
                pheromone[passes * nodes + first.pass] += deposit;
            }
            for pair in tour.windows(2) {
                pheromone[pair[0].pass * nodes + pair[1].pass] += deposit;
            }
            if problem.start == Start::Free {
                pheromone[tour[tour.len() - 1].pass * nodes + tour[0].pass] += deposit;
            }
        }
        for (cost, tour) in batch {
            if best.as_ref().is_none_or(|(best_cost, _)| cost < *best_cost) {
                best = Some((cost, tour));
            }
        }
        history.push(
            best.as_ref()
                .map(|(cost, _)| *cost)
                .unwrap_or(f64::INFINITY),
        );
    }
    (best.map(|(_, tour)| tour).unwrap_or_default(), history)
}
