//! L-SHADE: success-history adaptive differential evolution with linear population size
//! reduction (Tanabe and Fukunaga, "Improving the search performance of SHADE using linear
//! population size reduction", IEEE CEC 2014, pp. 1658-1665; Tanabe & Fukunaga 2014, docs/references.md). The strong modern baseline
//! that users of such tools compare against (CEC 2014 winner); not in the seeds.
//!
//! Per generation, for each target x_i (algorithm 1 of the paper):
//! - pick a memory slot r: CR_i ~ N(M_CR\[r\], 0.1) clipped to [0, 1] (0 when M_CR\[r\] is the
//!   terminal value ⊥), F_i ~ Cauchy(M_F\[r\], 0.1) drawn again while ≤ 0, cut to 1
//! - current-to-pbest/1: v = x_i + F_i·(x_pbest − x_i) + F_i·(x_r1 − x_r2), pbest among the
//!   best max(2, round(p·N)) (p = 0.11), r1 from the population, r2 from population ∪ archive
//! - a coordinate out of the box goes half way between the parent and the violated bound
//! - binomial crossover with one guaranteed coordinate; the trial replaces x_i when no worse;
//!   strictly better trials record (CR_i, F_i, |Δf|) and send x_i to the archive
//!   (size ≤ r_arc·N, r_arc = 2.6, random removal)
//! - memory update (eqs. 7-9): weighted Lehmer means of the successful F and CR, weights |Δf|
//!   (M_CR becomes ⊥ once the best successful CR is 0), slot index cycling over H = 6
//! - (10) population size N = round(N_init + (N_min − N_init)·k), N_init = 18·D, N_min = 4,
//!   k the Runner's progress (NFE / MAX_NFE in the paper): the worst leave.
//!
//! `population`, when set, replaces N_init = 18·D.

use crate::random::cauchy;
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `lshade`, in tables "L-SHADE": `population` agents.
pub const ALGORITHM: super::Algorithm = super::Algorithm::new("lshade", "L-SHADE", |population| {
    {
        // L-SHADE keeps its own initial population of 18·D, which it shrinks.
        let _ = population;
        Box::new(Lshade::new(LshadeParameters::default()))
    }
});

/// L-SHADE's parameters; `Default` is the paper's.
#[derive(Debug, Clone, PartialEq)]
pub struct LshadeParameters {
    /// N_init; `None` = 18·D.
    pub population: Option<usize>,
    /// N_min, the population size at the end of the run (never below 4).
    pub minimum_population: usize,
    /// H, the number of memory slots for M_CR and M_F (at least 1).
    pub memory_size: usize,
    /// r_arc: the archive holds at most round(r_arc·N) solutions.
    pub archive_rate: f64,
    /// p: pbest is drawn among the best max(2, round(p·N)).
    pub best_share: f64,
}

impl Default for LshadeParameters {
    fn default() -> Self {
        Self {
            population: None,
            minimum_population: 4,
            memory_size: 6,
            archive_rate: 2.6,
            best_share: 0.11,
        }
    }
}

/// L-SHADE.
#[derive(Debug, Clone, Default)]
pub struct Lshade {
    parameters: LshadeParameters,
    initial_population: usize,
    individuals: Vec<Vec<f64>>,
    costs: Vec<f64>,
    archive: Vec<Vec<f64>>,
    /// M_CR; `None` is the terminal value ⊥.
    memory_crossover: Vec<Option<f64>>,
    memory_scale: Vec<f64>,
    memory_slot: usize,
}

impl Lshade {
    /// L-SHADE with the given parameters; the population is drawn when the run starts.
    pub fn new(parameters: LshadeParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }
}

/// Σ w·s² / Σ w·s, the weighted Lehmer mean of eq. (7).
fn lehmer_mean(values: &[f64], weights: &[f64]) -> f64 {
    let numerator: f64 = values.iter().zip(weights).map(|(s, w)| w * s * s).sum();
    let denominator: f64 = values.iter().zip(weights).map(|(s, w)| w * s).sum();
    if denominator > 0.0 {
        numerator / denominator
    } else {
        0.0
    }
}

impl<'p> Optimizer<Continuous<'p>> for Lshade {
    fn name(&self) -> &'static str {
        "L-SHADE"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        self.initial_population = p
            .population
            .unwrap_or(18 * search.dimension())
            .max(p.minimum_population)
            .max(4);
        self.individuals = (0..self.initial_population)
            .map(|_| search.random_position())
            .collect();
        self.costs = self
            .individuals
            .iter()
            .map(|x| search.evaluate(x))
            .collect();
        self.archive.clear();
        self.memory_crossover = vec![Some(0.5); p.memory_size.max(1)];
        self.memory_scale = vec![0.5; p.memory_size.max(1)];
        self.memory_slot = 0;
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let size = self.individuals.len();
        let dimension = search.dimension();
        let mut ranked: Vec<usize> = (0..size).collect();
        ranked.sort_by(|&a, &b| self.costs[a].total_cmp(&self.costs[b]).then(a.cmp(&b)));
        let best_count =
            ((self.parameters.best_share * size as f64).round() as usize).clamp(2, size);

        let mut trials = Vec::with_capacity(size);
        let mut settings = Vec::with_capacity(size);
        for target in 0..size {
            let slot = search.below(self.memory_scale.len());
            let crossover = match self.memory_crossover[slot] {
                None => 0.0,
                Some(mean) => (mean + 0.1 * search.normal()).clamp(0.0, 1.0),
            };
            let scale = loop {
                let draw = self.memory_scale[slot] + 0.1 * cauchy(search.stream());
                if draw > 0.0 {
                    break draw.min(1.0);
                }
            };
            let pbest = ranked[search.below(best_count)];
            let first = loop {
                let pick = search.below(size);
                if pick != target {
                    break pick;
                }
            };
            let second = loop {
                let pick = search.below(size + self.archive.len());
                if pick != target && pick != first {
                    break pick;
                }
            };
            let x = &self.individuals[target];
            let donor = if second < size {
                &self.individuals[second]
            } else {
                &self.archive[second - size]
            };
            let forced = search.below(dimension);
            let mut trial = x.clone();
            for d in 0..dimension {
                if d == forced || search.uniform() < crossover {
                    let mut value = x[d]
                        + scale * (self.individuals[pbest][d] - x[d])
                        + scale * (self.individuals[first][d] - donor[d]);
                    let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
                    if value < low {
                        value = (low + x[d]) / 2.0;
                    } else if value > high {
                        value = (high + x[d]) / 2.0;
                    }
                    trial[d] = value;
                }
            }
            trials.push(trial);
            settings.push((crossover, scale));
        }

        let (mut good_crossover, mut good_scale, mut improvements) = (vec![], vec![], vec![]);
        for (target, trial) in trials.into_iter().enumerate() {
            let cost = search.evaluate(&trial);
            if cost <= self.costs[target] {
                if cost < self.costs[target] {
                    good_crossover.push(settings[target].0);
                    good_scale.push(settings[target].1);
                    improvements.push(self.costs[target] - cost);
                    self.archive
                        .push(std::mem::replace(&mut self.individuals[target], trial));
                } else {
                    self.individuals[target] = trial;
                }
                self.costs[target] = cost;
            }
        }
        if !improvements.is_empty() {
            let slot = self.memory_slot;
            let total: f64 = improvements.iter().sum();
            let weights: Vec<f64> = improvements
                .iter()
                .map(|d| d / total.max(f64::MIN_POSITIVE))
                .collect();
            let best_crossover = good_crossover.iter().copied().fold(0.0, f64::max);
            self.memory_crossover[slot] = match self.memory_crossover[slot] {
                Some(_) if best_crossover > 0.0 => Some(lehmer_mean(&good_crossover, &weights)),
                _ => None,
            };
            self.memory_scale[slot] = lehmer_mean(&good_scale, &weights);
            self.memory_slot = (slot + 1) % self.memory_scale.len();
        }

        // eq. (10): linear population size reduction, the worst leave.
        let k = search.progress();
        let p = &self.parameters;
        let minimum = p.minimum_population.max(4) as f64;
        let next_size = ((self.initial_population as f64
            + (minimum - self.initial_population as f64) * k)
            .round() as usize)
            .clamp(p.minimum_population.max(4), size);
        if next_size < size {
            let mut order: Vec<usize> = (0..size).collect();
            order.sort_by(|&a, &b| self.costs[a].total_cmp(&self.costs[b]).then(a.cmp(&b)));
            order.truncate(next_size);
            order.sort_unstable();
            self.individuals = order.iter().map(|&i| self.individuals[i].clone()).collect();
            self.costs = order.iter().map(|&i| self.costs[i]).collect();
        }
        let archive_limit = (p.archive_rate * self.individuals.len() as f64).round() as usize;
        while self.archive.len() > archive_limit {
            let leaving = search.below(self.archive.len());
            self.archive.swap_remove(leaving);
        }
    }
}
