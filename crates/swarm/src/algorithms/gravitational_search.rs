//! Gravitational search algorithm (GSA): Rashedi, Nezamabadi-pour and Saryazdi, "GSA: a
//! gravitational search algorithm", Information Sciences 179 (2009) 2232-2248 (Rashedi 2009, docs/references.md), as the
//! authors' MATLAB code computes it (equation numbers of the paper).
//!
//! At iteration t of T (k = t / T, the Runner's progress), for minimisation:
//! - (14)-(15) masses  m_i = (cost_i − worst) / (best − worst),  M_i = m_i / Σ_j m_j
//!   (all costs equal: every m_i = 1)
//! - (28) gravitational constant  G = G0·exp(−α·k),  G0 = 100, α = 20
//! - Kbest: the K heaviest agents attract, K = round(N·(p_final + (1 − k)·(100 − p_final)) / 100)
//!   shrinking linearly from N to p_final = 2 % of N (elitist check)
//! - (7), (9)-(10) acceleration  a_i^d = G·Σ_{j ∈ Kbest, j ≠ i} rand_j^d·M_j·(x_j^d − x_i^d) / (R_ij + ε),
//!   R_ij = ‖x_i − x_j‖₂ (R power 1), ε = 2.2e-16 (MATLAB's eps)
//! - (11)-(12) v_i^d = rand_i^d·v_i^d + a_i^d,  x_i^d = x_i^d + v_i^d
//! - a coordinate that leaves the box is drawn again uniformly in it (the code's space_bound).
//!
//! Used on its own (the bench) and by seed 003's sortie planner (one search per number of
//! returns).

use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `gsa`, in tables "GSA": `population` agents.
pub const ALGORITHM: super::Algorithm = super::Algorithm::new("gsa", "GSA", |population| {
    Box::new(GravitationalSearch::new(GravitationalSearchParameters {
        population,
        ..Default::default()
    }))
});

/// GSA's parameters; `Default` is Rashedi 2009's (population: 50 in the demo, 500 here to
/// match the other benchmarks; set it per use).
#[derive(Debug, Clone, PartialEq)]
pub struct GravitationalSearchParameters {
    /// Number of agents N (at least 1).
    pub population: usize,
    /// G0 of eq. (28).
    pub initial_gravity: f64,
    /// α of eq. (28).
    pub gravity_decay: f64,
    /// The share of agents that still attract at the end, in percent.
    pub final_attractors_percent: f64,
}

impl Default for GravitationalSearchParameters {
    fn default() -> Self {
        Self {
            population: 500,
            initial_gravity: 100.0,
            gravity_decay: 20.0,
            final_attractors_percent: 2.0,
        }
    }
}

/// The gravitational search algorithm.
#[derive(Debug, Clone, Default)]
pub struct GravitationalSearch {
    parameters: GravitationalSearchParameters,
    positions: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
    costs: Vec<f64>,
}

impl GravitationalSearch {
    /// GSA with the given parameters; the agents are drawn when the run starts.
    pub fn new(parameters: GravitationalSearchParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }

    /// Normalised masses M_i of eqs. (14)-(15).
    fn masses(&self) -> Vec<f64> {
        let best = self.costs.iter().copied().fold(f64::INFINITY, f64::min);
        let worst = self
            .costs
            .iter()
            .copied()
            .filter(|c| c.is_finite())
            .fold(f64::NEG_INFINITY, f64::max);
        let raw: Vec<f64> = self
            .costs
            .iter()
            .map(|&cost| {
                if worst <= best {
                    1.0
                } else if cost.is_finite() {
                    (cost - worst) / (best - worst)
                } else {
                    0.0
                }
            })
            .collect();
        let total: f64 = raw.iter().sum();
        raw.iter()
            .map(|m| m / total.max(f64::MIN_POSITIVE))
            .collect()
    }
}

impl<'p> Optimizer<Continuous<'p>> for GravitationalSearch {
    fn name(&self) -> &'static str {
        "GSA"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let population = self.parameters.population.max(1);
        self.positions = (0..population).map(|_| search.random_position()).collect();
        self.velocities = vec![vec![0.0; search.dimension()]; population];
        self.costs = self.positions.iter().map(|x| search.evaluate(x)).collect();
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        let k = search.progress();
        let population = self.positions.len();
        let dimension = search.dimension();
        let masses = self.masses();
        let gravity = p.initial_gravity * (-p.gravity_decay * k).exp(); // eq. (28)
        let share = p.final_attractors_percent + (1.0 - k) * (100.0 - p.final_attractors_percent);
        let attractors =
            ((population as f64 * share / 100.0).round() as usize).clamp(1, population);
        let mut order: Vec<usize> = (0..population).collect();
        order.sort_by(|&a, &b| self.costs[a].total_cmp(&self.costs[b]).then(a.cmp(&b)));
        order.truncate(attractors);

        let mut acceleration = vec![0.0; dimension];
        let mut moved = self.positions.clone();
        for (agent, next) in moved.iter_mut().enumerate() {
            acceleration.fill(0.0);
            let position = &self.positions[agent];
            for &other in &order {
                if other == agent {
                    continue;
                }
                let attractor = &self.positions[other];
                let distance = position
                    .iter()
                    .zip(attractor)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>()
                    .sqrt();
                let pull = masses[other] / (distance + f64::EPSILON);
                for d in 0..dimension {
                    acceleration[d] += search.uniform() * pull * (attractor[d] - position[d]);
                }
            }
            let velocity = &mut self.velocities[agent];
            for d in 0..dimension {
                velocity[d] = search.uniform() * velocity[d] + gravity * acceleration[d]; // eq. (11)
                next[d] += velocity[d]; // eq. (12)
                let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
                if !(low..=high).contains(&next[d]) {
                    next[d] = search.uniform_in(low, high);
                }
            }
        }
        self.positions = moved;
        self.costs = self.positions.iter().map(|x| search.evaluate(x)).collect();
    }
}
