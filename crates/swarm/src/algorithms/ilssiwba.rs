//! ILSSIWBA: bat algorithm with iterated local search and a stochastic inertia weight
//! (Gan, Cao, Wu, Chen 2018, Expert Systems with Applications 104:202-212; docs/references.md), as contract
//! decision 9 (docs/contract.md) fixes it: only its parameters are in seed 000, so it is built from its idea.
//!
//! For bat i at iteration t:
//! - frequency       f_i = f_min + (f_max − f_min)·β, β ~ U[0, 1], f ∈ [−2, 2]
//! - inertia (SIW)   w_i = μ_min + (μ_max − μ_min)·U(0, 1) + σ·N(0, 1), μ ∈ [0.4, 0.9], σ = 0.2
//! - velocity        v_i = w_i·v_i + (x_i − x_*)·f_i;  x_i' = x_i + v_i
//! - local walk      if rand > r_i: x_i' = x_* + ε·Ā, ε ~ U[−1, 1] per coordinate (BA eq. 4)
//! - acceptance      no worse and rand < A_i; then A_i ← max(α·A_i, A_x) (loudness floor
//!   A_x = 0.6) and r_i ← r_x·(1 − exp(−γ·t)) (pulse-rate cap r_x = 0.7), α = γ = 0.9
//! - iterated local search (ILS), once per iteration: kick x_* by a Gaussian of scale
//!   s = 0.05·(1 − k)·width + 1e-9·width, then `local_search_evaluations − 1` steps of a
//!   (1+1) hill climb from the kicked point whose step halves on failure; the result replaces
//!   x_* when better. k is the Runner's progress (t / t_max).
//!
//! The ILS spends `local_search_evaluations` (default 10) evaluations per iteration on top of
//! the population's: under an evaluation budget ILSSIWBA simply runs fewer iterations.
//! Initial loudness U(1, 2) and pulse rate U(0, 0.5) as in the BA baseline. Positions are
//! clamped to the box.

use super::bat::Colony;
use crate::readings::{Boundary, Draw};
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `ilssiwba`, in tables "ILSSIWBA": `population` agents.
pub const ALGORITHM: super::Algorithm =
    super::Algorithm::new("ilssiwba", "ILSSIWBA", |population| {
        Box::new(Ilssiwba::new(IlssiwbaParameters {
            population,
            ..Default::default()
        }))
    });

/// ILSSIWBA's parameters; `Default` is seed 000 §2.5 plus the documented ILS budget.
#[derive(Debug, Clone, PartialEq)]
pub struct IlssiwbaParameters {
    /// Number of bats (at least 1).
    pub population: usize,
    /// f_min, the lower end of the frequency range.
    pub frequency_min: f64,
    /// f_max, the upper end of the frequency range.
    pub frequency_max: f64,
    /// μ_min, the lower end of the uniform part of the inertia weight.
    pub inertia_mean_min: f64,
    /// μ_max, the upper end of the uniform part of the inertia weight.
    pub inertia_mean_max: f64,
    /// σ, the standard deviation of the Gaussian part of the inertia weight.
    pub inertia_deviation: f64,
    /// r_x, the pulse rate approached as t grows.
    pub pulse_rate_cap: f64,
    /// A_x, the loudness below which α no longer lowers A_i.
    pub loudness_floor: f64,
    /// Range (low, high) from which each bat's initial loudness is drawn uniformly.
    pub initial_loudness: (f64, f64),
    /// Range (low, high) from which each bat's initial pulse rate is drawn uniformly.
    pub initial_pulse_rate: (f64, f64),
    /// Loudness decay α.
    pub alpha: f64,
    /// Pulse-rate growth γ.
    pub gamma: f64,
    /// Evaluations the iterated local search spends per iteration (0: no ILS).
    pub local_search_evaluations: usize,
}

impl Default for IlssiwbaParameters {
    fn default() -> Self {
        Self {
            population: 500,
            frequency_min: -2.0,
            frequency_max: 2.0,
            inertia_mean_min: 0.4,
            inertia_mean_max: 0.9,
            inertia_deviation: 0.2,
            pulse_rate_cap: 0.7,
            loudness_floor: 0.6,
            initial_loudness: (1.0, 2.0),
            initial_pulse_rate: (0.0, 0.5),
            alpha: 0.9,
            gamma: 0.9,
            local_search_evaluations: 10,
        }
    }
}

/// The ILSSIWBA bat algorithm.
#[derive(Debug, Clone, Default)]
pub struct Ilssiwba {
    parameters: IlssiwbaParameters,
    colony: Colony,
}

impl Ilssiwba {
    /// ILSSIWBA with the given parameters; the colony is drawn when the run starts.
    pub fn new(parameters: IlssiwbaParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }

    /// The iterated local search around the global best.
    fn iterated_local_search(&mut self, search: &mut Search<Continuous<'_>>) {
        let evaluations = self.parameters.local_search_evaluations;
        if evaluations == 0 {
            return;
        }
        let dimension = search.dimension();
        let k = search.progress();
        let scale: Vec<f64> = (0..dimension)
            .map(|d| search.bounds().width(d) * (0.05 * (1.0 - k) + 1e-9))
            .collect();
        let mut current: Vec<f64> = (0..dimension)
            .map(|d| self.colony.best[d] + scale[d] * search.normal())
            .collect();
        search.clamp(&mut current);
        let mut current_cost = search.evaluate(&current);
        let mut step = 0.5;
        let mut trial = vec![0.0; dimension];
        for _ in 1..evaluations {
            for d in 0..dimension {
                trial[d] = current[d] + step * scale[d] * search.normal();
            }
            search.clamp(&mut trial);
            let cost = search.evaluate(&trial);
            if cost < current_cost {
                current.copy_from_slice(&trial);
                current_cost = cost;
            } else {
                step *= 0.5;
            }
        }
        self.colony.offer_best(&current, current_cost);
    }
}

impl<'p> Optimizer<Continuous<'p>> for Ilssiwba {
    fn name(&self) -> &'static str {
        "ILSSIWBA"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        self.colony = Colony::new(
            search,
            p.population,
            p.initial_loudness,
            p.initial_pulse_rate,
        );
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = self.parameters.clone();
        let t = search.iteration() as f64;
        self.colony.fly(
            search,
            (Draw::PerCoordinate, Boundary::Clamp),
            |search, velocity, position, best| {
                let frequency = search.uniform_in(p.frequency_min, p.frequency_max);
                let inertia = search.uniform_in(p.inertia_mean_min, p.inertia_mean_max)
                    + p.inertia_deviation * search.normal(); // stochastic inertia weight
                for d in 0..velocity.len() {
                    velocity[d] = inertia * velocity[d] + (position[d] - best[d]) * frequency;
                }
            },
            |loudness, pulse_rate| {
                *loudness = (*loudness * p.alpha).max(p.loudness_floor);
                *pulse_rate = p.pulse_rate_cap * (1.0 - (-p.gamma * t).exp());
            },
        );
        self.iterated_local_search(search);
    }
}
