//! Bat algorithm (BA): Yang, "A New Metaheuristic Bat-Inspired Algorithm", NICSO 2010
//! (Studies in Computational Intelligence 284:65-74; Yang 2010, docs/references.md), in the form seed 000 §1 writes it.
//!
//! For bat i at iteration t (seed 000 numbering):
//! - (3) frequency   f_i = f_min + (f_max − f_min)·β,  β ~ U[0, 1]
//! - (2) velocity    v_i^t = v_i^{t−1} + (x_i^{t−1} − x_*)·f_i
//! - (1) position    x_i^t = x_i^{t−1} + v_i^t
//! - (4) local walk  if rand > R_i: x = x_* + ε·Ā^t, ε ~ U[−1, 1] per coordinate, Ā the mean loudness
//! - acceptance (Yang): the new point replaces the bat if it is no worse and rand < A_i; then
//!   (5) A_i ← α·A_i and (6) R_i ← R_max·(1 − exp(−γ·t)).
//!
//! Parameters are those seed 000 gives for its BA baseline: f ∈ [−2, 0], A_i^0 ~ U(1, 2),
//! R_i^0 ~ U(0, 0.5), R_max = 0.9, α = γ = 0.9. With f ≤ 0, eq. (2) pulls every bat towards
//! x_* (the frequency range of Yang's demo code, whose sign slip the seed's settings keep).
//!
//! Deviations, stated: the global best moves whenever a bat finds a better point, accepted
//! or not (as in Yang's pseudo-code); t in eq. (6) is the iteration number.
//!
//! Readings (`BatReadings`, issue 20): β of eq. (3) per coordinate (the text's "random
//! vector") or one per bat (Yang's code, decision 0007); ε of eq. (4) one number (the text's
//! "random number") or per coordinate (Yang's code); no velocity limit or ± a share of the box
//! width; positions clamped (Yang's demo clamps the old position instead: not copied),
//! reflected or redrawn after (1) and (4).

use crate::readings::{limit_velocity, BatReadings, Boundary, Draw, Readings};
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `ba`, in tables "BA": `population` agents.
pub const ALGORITHM: super::Algorithm =
    super::Algorithm::with_readings("ba", "BA", |population, readings| {
        Box::new(Bat::new(BatParameters {
            population,
            readings: readings.bat,
            ..Default::default()
        }))
    });

/// BA's parameters; `Default` is seed 000's baseline setting.
#[derive(Debug, Clone, PartialEq)]
pub struct BatParameters {
    /// Number of bats (at least 1).
    pub population: usize,
    /// f_min of eq. (3).
    pub frequency_min: f64,
    /// f_max of eq. (3).
    pub frequency_max: f64,
    /// Range (low, high) from which each bat's initial loudness A_i^0 is drawn uniformly.
    pub initial_loudness: (f64, f64),
    /// Range (low, high) from which each bat's initial pulse rate R_i^0 is drawn uniformly.
    pub initial_pulse_rate: (f64, f64),
    /// R_max of eq. (6), the pulse rate approached as t grows.
    pub pulse_rate_max: f64,
    /// Loudness decay α of eq. (5).
    pub alpha: f64,
    /// Pulse-rate growth γ of eq. (6).
    pub gamma: f64,
    /// The open choices of the text (default: decision 0007's).
    pub readings: BatReadings,
}

impl Default for BatParameters {
    fn default() -> Self {
        Self {
            population: 500,
            frequency_min: -2.0,
            frequency_max: 0.0,
            initial_loudness: (1.0, 2.0),
            initial_pulse_rate: (0.0, 0.5),
            pulse_rate_max: 0.9,
            alpha: 0.9,
            gamma: 0.9,
            readings: Readings::ENGINE.bat,
        }
    }
}

/// A colony of bats: what BA and ILSSIWBA keep between iterations.
#[derive(Debug, Clone, Default)]
pub(crate) struct Colony {
    pub positions: Vec<Vec<f64>>,
    pub velocities: Vec<Vec<f64>>,
    pub costs: Vec<f64>,
    pub loudness: Vec<f64>,
    pub pulse_rate: Vec<f64>,
    pub best: Vec<f64>,
    pub best_cost: f64,
}

impl Colony {
    /// `population` bats at random, still, evaluated, with loudness and pulse rate drawn
    /// uniformly from the given ranges.
    pub fn new(
        search: &mut Search<Continuous<'_>>,
        population: usize,
        (loud_low, loud_high): (f64, f64),
        (rate_low, rate_high): (f64, f64),
    ) -> Self {
        let population = population.max(1);
        let positions: Vec<Vec<f64>> = (0..population).map(|_| search.random_position()).collect();
        let velocities = vec![vec![0.0; search.dimension()]; population];
        let costs: Vec<f64> = positions.iter().map(|x| search.evaluate(x)).collect();
        let loudness = (0..population)
            .map(|_| search.uniform_in(loud_low, loud_high))
            .collect();
        let pulse_rate = (0..population)
            .map(|_| search.uniform_in(rate_low, rate_high))
            .collect();
        let best = index_of_smallest(&costs);
        Self {
            best: positions[best].clone(),
            best_cost: costs[best],
            positions,
            velocities,
            costs,
            loudness,
            pulse_rate,
        }
    }

    fn mean_loudness(&self) -> f64 {
        self.loudness.iter().sum::<f64>() / self.loudness.len() as f64
    }

    /// The local walk of eq. (4) around the best, in place of `candidate`; `mean_loudness`
    /// is Ā^t, taken at the start of the iteration; ε is drawn as `walk` says.
    fn walk_near_best(
        &self,
        candidate: &mut [f64],
        mean_loudness: f64,
        walk: Draw,
        search: &mut Search<Continuous<'_>>,
    ) {
        walk.fill(search, candidate, -1.0, 1.0);
        for (value, best) in candidate.iter_mut().zip(&self.best) {
            *value = best + *value * mean_loudness;
        }
    }

    /// One BA iteration over every bat: `velocity` updates a bat's velocity (its own draws
    /// and rule: eq. 2 for BA, the inertia-weighted form for ILSSIWBA), the bat flies to
    /// x + v (eq. 1) or walks near the best when rand > R_i (eq. 4), and the new point is
    /// accepted when no worse and rand < A_i (Yang), after which `accepted` updates the bat's
    /// loudness and pulse rate. `walk` draws ε of eq. (4); `boundary` brings points back
    /// into the box.
    pub fn fly(
        &mut self,
        search: &mut Search<Continuous<'_>>,
        (walk, boundary): (Draw, Boundary),
        mut velocity: impl FnMut(&mut Search<Continuous<'_>>, &mut [f64], &[f64], &[f64]),
        mut accepted: impl FnMut(&mut f64, &mut f64),
    ) {
        let mean_loudness = self.mean_loudness();
        let mut candidate = vec![0.0; search.dimension()];
        for bat in 0..self.positions.len() {
            velocity(
                search,
                &mut self.velocities[bat],
                &self.positions[bat],
                &self.best,
            );
            for (d, value) in candidate.iter_mut().enumerate() {
                *value = self.positions[bat][d] + self.velocities[bat][d]; // eq. (1)
            }
            if search.uniform() > self.pulse_rate[bat] {
                self.walk_near_best(&mut candidate, mean_loudness, walk, search);
                // eq. (4)
            }
            boundary.apply(search, &mut candidate, Some(&mut self.velocities[bat]));
            let cost = search.evaluate(&candidate);
            if cost <= self.costs[bat] && search.uniform() < self.loudness[bat] {
                self.positions[bat].copy_from_slice(&candidate);
                self.costs[bat] = cost;
                accepted(&mut self.loudness[bat], &mut self.pulse_rate[bat]);
            }
            self.offer_best(&candidate, cost);
        }
    }

    /// Keeps `candidate` as the best when it is better.
    pub fn offer_best(&mut self, candidate: &[f64], cost: f64) {
        if cost < self.best_cost {
            self.best.copy_from_slice(candidate);
            self.best_cost = cost;
        }
    }
}

/// The bat algorithm.
#[derive(Debug, Clone, Default)]
pub struct Bat {
    parameters: BatParameters,
    colony: Colony,
}

impl Bat {
    /// BA with the given parameters; the colony is drawn when the run starts.
    pub fn new(parameters: BatParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }
}

impl<'p> Optimizer<Continuous<'p>> for Bat {
    fn name(&self) -> &'static str {
        "BA"
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
        let p = &self.parameters;
        let t = search.iteration() as f64;
        let readings = p.readings;
        let mut frequencies = vec![0.0; search.dimension()];
        self.colony.fly(
            search,
            (readings.walk, readings.boundary),
            |search, velocity, position, best| {
                let (low, high) = (p.frequency_min, p.frequency_max);
                readings.frequency.fill(search, &mut frequencies, low, high); // eq. (3)
                for d in 0..velocity.len() {
                    let value = velocity[d] + (position[d] - best[d]) * frequencies[d]; // eq. (2)
                    velocity[d] =
                        limit_velocity(readings.velocity_limit, value, search.bounds().width(d));
                }
            },
            |loudness, pulse_rate| {
                *loudness *= p.alpha; // eq. (5)
                *pulse_rate = p.pulse_rate_max * (1.0 - (-p.gamma * t).exp()); // eq. (6)
            },
        );
    }
}

/// The index of the smallest cost (the first on ties).
pub(crate) fn index_of_smallest(costs: &[f64]) -> usize {
    let mut best = 0;
    for (index, &cost) in costs.iter().enumerate() {
        if cost < costs[best] {
            best = index;
        }
    }
    best
}
