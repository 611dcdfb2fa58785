//! Seed 001's improved ant colony for ordering swaths with their entry ends (§3, eqs. 2-13).
//!
//! Each ant m of batch t builds a route R^m(t) (eq. 2) and records the entry end of every
//! swath, O^m(t) (eq. 3). From swath i (left by its exit end), swath j is entered by end A_j
//! or B_j with probabilities (eqs. 4-5)
//!
//!   p_iAj = τ_ij^α η_iAj^β / Σ_k∈V τ_ik^α (η_iAk^β + η_iBk^β),   p_iBj likewise,
//!
//! where η is 1/d of the end actually reached from the end i is left by (eqs. 11-12; their
//! indices are swapped in print, contract decision 3, docs/contract.md), and d is eq. (8)'s transfer cost
//! (eqs. 6-10). After each batch the pheromone evaporates and every ant deposits Q/l_m on the
//! pairs it flew (ant-cycle model, eq. 13). Parameters as the seed: α = 1, β = 5, ρ = 0.1,
//! Q = 100, 50 ants, 100 or 200 batches.
//!
//! Deviations from the paper, all where it is silent: the initial pheromone is 1 on every
//! pair; a start point is node 0 of the pheromone matrix (so the first choice learns too);
//! with none each ant starts at a random swath and end (the seed's option ②), and its tour
//! is closed (`Start::Closed`, as the seed's) or not (`Start::Open`); a start point the flight
//! comes back to (`Start::Fixed`) has the pair home deposited too; d = 0 uses d = 1e-6 m; the best tour of all batches is returned (the
//! Runner's best).

use serde::Serialize;
use swarm::{Optimizer, Runner, Search, Termination};

use super::tour::{OrderingProblem, Start, Step};

/// The colony's settings; `Default` is seed 001 §5's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AntColonySettings {
    /// M, ants per batch (at least 1).
    pub ants: usize,
    /// T, batches flown (at least 1).
    pub batches: usize,
    /// α, the weight of the pheromone τ in eqs. (4)-(5).
    pub alpha: f64,
    /// β, the weight of the visibility η = 1/d in eqs. (4)-(5).
    pub beta: f64,
    /// ρ, the share of the pheromone that evaporates after each batch, 0..1 (eq. 13).
    pub evaporation: f64,
    /// Q: an ant deposits Q / l_m on every pair it flew, l_m its tour's cost in metres (eq. 13).
    pub deposit: f64,
    /// The pheromone on every pair before the first batch.
    pub initial_pheromone: f64,
    /// The Runner's seed; the colony is its run 0.
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

/// Runs the colony through `swarm`'s Runner (one batch per iteration, `settings.batches`
/// iterations, run 0 of `settings.seed`); returns the best tour and the best cost after each
/// batch. At least one ant and one batch are flown.
pub fn ant_colony(
    problem: &OrderingProblem,
    settings: &AntColonySettings,
) -> (Vec<Step>, Vec<f64>) {
    if problem.passes() == 0 {
        return (Vec::new(), Vec::new());
    }
    let runner = Runner::new(
        Termination::iterations(settings.batches.max(1)),
        settings.seed,
    )
    .expect("a budget of at least one batch");
    let mut colony = SwathAntColony::new(*settings);
    let outcome = runner.run_problem(&mut colony, problem, 0, &mut ());
    let history = outcome.history[1..]
        .iter()
        .map(|record| record.best_cost)
        .collect();
    (outcome.best_solution, history)
}

/// The colony as an optimizer of [`OrderingProblem`]: `start` builds eqs. (6)-(12)'s tables and
/// the pheromone; each `step` is one batch of ants and eq. (13)'s update.
#[derive(Debug, Clone)]
pub struct SwathAntColony {
    settings: AntColonySettings,
    passes: usize,
    /// η^β between every pair of ends; row `2·passes` is the fixed start point.
    visibility: Vec<f64>,
    /// τ between passes; node `passes` is the start point.
    pheromone: Vec<f64>,
    weights: Vec<f64>,
}

impl SwathAntColony {
    /// A colony with `settings` (its seed is the Runner's, not this value's).
    pub fn new(settings: AntColonySettings) -> Self {
        Self {
            settings,
            passes: 0,
            visibility: Vec::new(),
            pheromone: Vec::new(),
            weights: Vec::new(),
        }
    }

    /// One ant's tour, eqs. (2)-(5).
    fn walk(&mut self, free_start: bool, search: &mut Search<OrderingProblem<'_>>) -> Vec<Step> {
        let (passes, settings) = (self.passes, &self.settings);
        let ends = 2 * passes;
        let nodes = passes + 1;
        let mut visited = vec![false; passes];
        let mut tour: Vec<Step> = Vec::with_capacity(passes);
        if free_start {
            let pass = search.below(passes);
            let step = Step {
                pass,
                reversed: search.below(2) == 1,
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
            for (pass, &flown) in visited.iter().enumerate() {
                for side in 0..2 {
                    let end = 2 * pass + side;
                    self.weights[end] = if flown {
                        0.0
                    } else {
                        let trail = self.pheromone[from_node * nodes + pass];
                        let trail = if settings.alpha == 1.0 {
                            trail
                        } else {
                            trail.powf(settings.alpha)
                        };
                        trail * self.visibility[from_end * ends + end]
                    };
                    total += self.weights[end];
                }
            }
            // Roulette wheel over (pass, entry end).
            let mut target = total * search.uniform();
            let mut chosen = None;
            for (end, weight) in self.weights.iter().enumerate() {
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
        tour
    }
}

impl<'a> Optimizer<OrderingProblem<'a>> for SwathAntColony {
    fn name(&self) -> &'static str {
        "ant colony (seed 001)"
    }

    fn start(&mut self, search: &mut Search<OrderingProblem<'a>>) {
        let problem = search.problem();
        let passes = problem.passes();
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
        self.visibility = distance
            .iter()
            .map(|d| (1.0 / d.max(TINY_DISTANCE_M)).powf(self.settings.beta))
            .collect();
        let nodes = passes + 1;
        self.pheromone = vec![self.settings.initial_pheromone; nodes * nodes];
        self.weights = vec![0.0; ends];
        self.passes = passes;
    }

    fn step(&mut self, search: &mut Search<OrderingProblem<'a>>) {
        let start = search.problem().start;
        let (passes, nodes) = (self.passes, self.passes + 1);
        let mut batch: Vec<(f64, Vec<Step>)> = Vec::with_capacity(self.settings.ants);
        for _ in 0..self.settings.ants.max(1) {
            let tour = self.walk(start.free_first(), search);
            let cost = search.evaluate(&tour);
            batch.push((cost, tour));
        }
        // Eq. (13): evaporate, then deposit Q / l_m on every pair each ant flew.
        for value in &mut self.pheromone {
            *value *= 1.0 - self.settings.evaporation;
        }
        for (cost, tour) in &batch {
            let deposit = self.settings.deposit / cost.max(TINY_DISTANCE_M);
            if let (Some(_), Some(first)) = (start.point(), tour.first()) {
                self.pheromone[passes * nodes + first.pass] += deposit;
            }
            if let (true, Some(last)) = (start.returns_home(), tour.last()) {
                self.pheromone[last.pass * nodes + passes] += deposit;
            }
            for pair in tour.windows(2) {
                self.pheromone[pair[0].pass * nodes + pair[1].pass] += deposit;
            }
            if start == Start::Closed {
                self.pheromone[tour[tour.len() - 1].pass * nodes + tour[0].pass] += deposit;
            }
        }
    }
}
