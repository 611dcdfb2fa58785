//! IBA-FCS: the improved bat algorithm with a frequency-conversion strategy, adaptive local
//! search and mutation (seed 000 §2, eqs. 8-15).
//!
//! At progress k = t / t_max (the Runner's `progress()`):
//! - (9)  f1 = α_b·(1 − e^{−|F_avg − F_min|}) + γ_b·(1 − k) + f_min,   f2 = S_F − f1
//! - (11) ω_b = ω_max − k·(ω_max − ω_min);  μ = μ_max − k·(μ_max − μ_min) (linear, §2.5)
//! - (14) A = f1 / f_max,  (15) R = f2 / f_max, with the §2.5 controls A ≥ A_min, R ≤ R_max
//! - (8)  v_i = ω_b·v_i + f1·r1·(h_i − x_i) + f2·r2·(x_* − x_i),  r1, r2 ~ U(0.5, 1.5)
//! - (10) x_i = x_i + μ·v_i
//! - local search (§2.2): β_i ~ U[0, R_max]; if β_i < R:
//!   (12) x_i = x_* + δ·V·A·g(k), δ ~ U[−1, 1] per coordinate, V = box width / population,
//!   (13) g(k) = a_g·exp(−Σ_j b_j k^j) with J = 2, a_g = 2.1766, b = (−2.0886, 27.3349)
//! - mutation (§2.3): a bat that did not search locally is reset to a random point when
//!   β1 < A and β2 > ρ (β1, β2 ~ U[0, 1]).
//! - (§2.4 step 5) every bat moves to its new point; its personal best h_i and the global
//!   best x_* are kept by cost.
//!
//! Parameters (`Default`): `../shared/data/seed000_orchard.json`, i.e. §2.5.
//!
//! Decisions where the seed is silent (docs/decisions/0007-swarm-engine.md): r1, r2 and δ are
//! drawn per coordinate; A_min and R_max bound A and R of eqs. (14)-(15) (the seed lists them
//! as "the remaining control parameters" and says A must not fall to 0 so that mutation
//! continues late); ρ, not given, is 0.99 (decision 0007: of 0.9, 0.99 and 1, the best on Table 1 in a 4-run trial); F_avg is the mean cost of the bats' current points
//! and F_min the global best cost; a reset bat restarts with zero velocity.
//!
//! Readings (`IbaFcsReadings`, issue 20, decision 0020): β_i ~ U[0, R_max] as §2.2 writes
//! (P(local search) = 1 once R reaches R_max, so §2.3's mutation then never fires) or
//! U[0, 1]; the velocity kept or zeroed after an eq.-(12) jump; δ a vector (the text) or one
//! number; every move accepted (§2.4 step 5) or only no-worse ones; no velocity limit or ± a
//! share of the box width; positions clamped, reflected or redrawn.

use super::bat::index_of_smallest;
use crate::readings::{
    limit_velocity, Acceptance, IbaFcsReadings, JumpVelocity, LocalSearchDraw, Readings,
};
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `iba-fcs`, in tables "IBA-FCS": `population` agents.
pub const ALGORITHM: super::Algorithm =
    super::Algorithm::with_readings("iba-fcs", "IBA-FCS", |population, readings| {
        Box::new(IbaFcs::new(IbaFcsParameters {
            population,
            readings: readings.iba_fcs,
            ..Default::default()
        }))
    });

/// IBA-FCS's parameters; `Default` is seed 000 §2.5.
#[derive(Debug, Clone, PartialEq)]
pub struct IbaFcsParameters {
    /// Number of bats (at least 1).
    pub population: usize,
    /// ω_max of eq. (11), the inertia weight at the start of the run.
    pub omega_max: f64,
    /// ω_min of eq. (11), the inertia weight at the end of the run.
    pub omega_min: f64,
    /// α_b of eq. (9), the weight of the cost spread |F_avg − F_min| in f1.
    pub alpha_b: f64,
    /// γ_b of eq. (9), the weight of the remaining progress 1 − k in f1.
    pub gamma_b: f64,
    /// S_F = f1 + f2.
    pub frequency_sum: f64,
    /// f_min of eq. (9), the floor added to f1.
    pub frequency_min: f64,
    /// f_max of eqs. (14)-(15), dividing f1 and f2 into A and R.
    pub frequency_max: f64,
    /// μ_max, the position step factor μ of eq. (10) at the start of the run.
    pub mu_max: f64,
    /// μ_min, the position step factor μ of eq. (10) at the end of the run.
    pub mu_min: f64,
    /// A_min, the floor of the loudness A of eq. (14).
    pub loudness_min: f64,
    /// R_max, the cap of the pulse rate R of eq. (15) and the upper end of β_i.
    pub pulse_rate_max: f64,
    /// g(k) = a_g·exp(−Σ_j b_j k^j), eq. (13).
    pub step_scale: f64,
    /// b_1, b_2, … of eq. (13): b_j multiplies k^j (J is the length).
    pub step_exponents: Vec<f64>,
    /// ρ of §2.3: a mutating bat is reset when β2 > ρ.
    pub mutation_threshold: f64,
    /// The open choices of the text (default: decision 0007's).
    pub readings: IbaFcsReadings,
}

impl Default for IbaFcsParameters {
    fn default() -> Self {
        Self {
            population: 500,
            omega_max: 0.9,
            omega_min: 0.1,
            alpha_b: 1.0,
            gamma_b: 1.5,
            frequency_sum: 3.0,
            frequency_min: 0.5,
            frequency_max: 2.5,
            mu_max: 0.7,
            mu_min: 0.3,
            loudness_min: 0.3,
            pulse_rate_max: 0.7,
            step_scale: 2.1766,
            step_exponents: vec![-2.0886, 27.3349],
            mutation_threshold: 0.99,
            readings: Readings::ENGINE.iba_fcs,
        }
    }
}

impl IbaFcsParameters {
    /// g(k) of eq. (13).
    pub fn step_decay(&self, k: f64) -> f64 {
        let exponent: f64 = self
            .step_exponents
            .iter()
            .enumerate()
            .map(|(j, b)| b * k.powi(j as i32 + 1))
            .sum();
        self.step_scale * (-exponent).exp()
    }
}

/// The improved bat algorithm IBA-FCS.
#[derive(Debug, Clone, Default)]
pub struct IbaFcs {
    parameters: IbaFcsParameters,
    positions: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
    costs: Vec<f64>,
    personal_best: Vec<Vec<f64>>,
    personal_best_cost: Vec<f64>,
    best: Vec<f64>,
    best_cost: f64,
}

impl IbaFcs {
    /// IBA-FCS with the given parameters; the bats are drawn when the run starts.
    pub fn new(parameters: IbaFcsParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }
}

impl<'p> Optimizer<Continuous<'p>> for IbaFcs {
    fn name(&self) -> &'static str {
        "IBA-FCS"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let population = self.parameters.population.max(1);
        self.positions = (0..population).map(|_| search.random_position()).collect();
        self.velocities = vec![vec![0.0; search.dimension()]; population];
        self.costs = self.positions.iter().map(|x| search.evaluate(x)).collect();
        self.personal_best = self.positions.clone();
        self.personal_best_cost = self.costs.clone();
        let best = index_of_smallest(&self.costs);
        self.best = self.positions[best].clone();
        self.best_cost = self.costs[best];
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        let k = search.progress();
        let finite: Vec<f64> = self
            .costs
            .iter()
            .copied()
            .filter(|c| c.is_finite())
            .collect();
        let average = finite.iter().sum::<f64>() / finite.len().max(1) as f64;
        let spread = if finite.is_empty() {
            0.0
        } else {
            (average - self.best_cost).abs()
        };
        let f1 = p.alpha_b * (1.0 - (-spread).exp()) + p.gamma_b * (1.0 - k) + p.frequency_min; // eq. (9)
        let f2 = p.frequency_sum - f1;
        let omega = p.omega_max - k * (p.omega_max - p.omega_min); // eq. (11)
        let mu = p.mu_max - k * (p.mu_max - p.mu_min);
        let loudness = (f1 / p.frequency_max).max(p.loudness_min); // eq. (14)
        let pulse_rate = (f2 / p.frequency_max).min(p.pulse_rate_max); // eq. (15)
        let local_step = loudness * p.step_decay(k); // A·g(k) of eq. (12)
        let population = self.positions.len() as f64;
        let dimension = search.dimension();
        let readings = p.readings;

        let mut candidate = vec![0.0; dimension];
        for bat in 0..self.positions.len() {
            let velocity = &mut self.velocities[bat];
            let (position, personal) = (&self.positions[bat], &self.personal_best[bat]);
            for d in 0..dimension {
                let r1 = search.uniform_in(0.5, 1.5);
                let r2 = search.uniform_in(0.5, 1.5);
                let value = omega * velocity[d]
                    + f1 * r1 * (personal[d] - position[d])
                    + f2 * r2 * (self.best[d] - position[d]); // eq. (8)
                velocity[d] =
                    limit_velocity(readings.velocity_limit, value, search.bounds().width(d));
                candidate[d] = position[d] + mu * velocity[d]; // eq. (10)
            }
            let beta = match readings.local_search {
                LocalSearchDraw::UpToPulseRateCap => search.uniform_in(0.0, p.pulse_rate_max),
                LocalSearchDraw::UpToOne => search.uniform(),
            };
            if beta < pulse_rate {
                readings.jump.fill(search, &mut candidate, -1.0, 1.0); // δ of eq. (12)
                for (d, value) in candidate.iter_mut().enumerate() {
                    let width = search.bounds().width(d) / population; // V of eq. (12)
                    *value = self.best[d] + *value * width * local_step;
                }
                if readings.jump_velocity == JumpVelocity::Zero {
                    velocity.fill(0.0);
                }
            } else if search.uniform() < loudness && search.uniform() > p.mutation_threshold {
                candidate = search.random_position();
                velocity.fill(0.0);
            }
            readings
                .boundary
                .apply(search, &mut candidate, Some(velocity));
            let cost = search.evaluate(&candidate);
            if readings.acceptance == Acceptance::EveryMove || cost <= self.costs[bat] {
                self.positions[bat].copy_from_slice(&candidate);
                self.costs[bat] = cost;
            }
            if cost < self.personal_best_cost[bat] {
                self.personal_best[bat].copy_from_slice(&candidate);
                self.personal_best_cost[bat] = cost;
            }
            if cost < self.best_cost {
                self.best.copy_from_slice(&candidate);
                self.best_cost = cost;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_decay_follows_eq_13() {
        let parameters = IbaFcsParameters::default();
        assert!((parameters.step_decay(0.0) - 2.1766).abs() < 1e-12);
        let at_half = 2.1766 * (-(-2.0886 * 0.5 + 27.3349 * 0.25_f64)).exp();
        assert!((parameters.step_decay(0.5) - at_half).abs() < 1e-15);
        assert!(parameters.step_decay(1.0) < 1e-10);
    }
}
