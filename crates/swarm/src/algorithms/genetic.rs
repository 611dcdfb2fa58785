//! Real-coded genetic algorithm (GA) with seed 000's rates: crossover rate in (0.4, 1),
//! mutation rate in (0, 0.5) (Michalewicz, "Genetic Algorithms + Data Structures = Evolution
//! Programs", 1996, for the operators).
//!
//! One generation:
//! - elitism: the best individual is copied unchanged;
//! - selection: binary tournaments;
//! - crossover with probability p_c: arithmetic (whole) crossover,
//!   c1 = λ·a + (1 − λ)·b, c2 = (1 − λ)·a + λ·b with λ ~ U[0, 1] per pair;
//! - mutation: with probability p_m an individual is mutated; each of its genes then mutates
//!   with probability `gene_mutation` by non-uniform mutation,
//!   x' = x + (u − x)·(1 − r^{(1 − k)^b}) or x' = x − (x − l)·(1 − r^{(1 − k)^b}), b = 5,
//!   r ~ U[0, 1], k the Runner's progress.
//!
//! The seed gives the rates as ranges (`GeneticReadings`, issue 20): by default they fall
//! linearly over the run, p_c from 1 to 0.4 and p_m from 0.5 to 0.01 (explore early, keep
//! good genes late; decision 0007); the other readings keep the middle of each range or draw
//! the rates from the ranges once per generation.

use crate::readings::{GeneticReadings, RateSchedule, Readings};
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `ga`, in tables "GA": `population` agents.
pub const ALGORITHM: super::Algorithm =
    super::Algorithm::with_readings("ga", "GA", |population, readings| {
        Box::new(Genetic::new(GeneticParameters {
            population,
            readings: readings.genetic,
            ..Default::default()
        }))
    });

/// The GA's parameters; `Default` is seed 000's ranges.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneticParameters {
    /// Number of individuals (at least 2).
    pub population: usize,
    /// Crossover rate p_c at the start of the run.
    pub crossover_start: f64,
    /// Crossover rate p_c at the end of the run (linear in between).
    pub crossover_end: f64,
    /// Mutation rate p_m at the start of the run.
    pub mutation_start: f64,
    /// Mutation rate p_m at the end of the run (linear in between).
    pub mutation_end: f64,
    /// The chance that each gene of a mutating individual changes.
    pub gene_mutation: f64,
    /// b of the non-uniform mutation.
    pub mutation_shape: f64,
    /// How the rates move within their ranges (default: decision 0007's).
    pub readings: GeneticReadings,
}

impl Default for GeneticParameters {
    fn default() -> Self {
        Self {
            population: 500,
            crossover_start: 1.0,
            crossover_end: 0.4,
            mutation_start: 0.5,
            mutation_end: 0.01,
            gene_mutation: 0.1,
            mutation_shape: 5.0,
            readings: Readings::ENGINE.genetic,
        }
    }
}

/// A generational real-coded GA with elitism.
#[derive(Debug, Clone, Default)]
pub struct Genetic {
    parameters: GeneticParameters,
    individuals: Vec<Vec<f64>>,
    costs: Vec<f64>,
}

impl Genetic {
    /// A GA with the given parameters; the population is drawn when the run starts.
    pub fn new(parameters: GeneticParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }

    fn tournament(&self, search: &mut Search<Continuous<'_>>) -> usize {
        let a = search.below(self.individuals.len());
        let b = search.below(self.individuals.len());
        if self.costs[b] < self.costs[a] {
            b
        } else {
            a
        }
    }

    fn mutate(&self, child: &mut [f64], search: &mut Search<Continuous<'_>>) {
        let k = search.progress();
        let shape = (1.0 - k).powf(self.parameters.mutation_shape);
        for (d, gene) in child.iter_mut().enumerate() {
            if search.uniform() >= self.parameters.gene_mutation {
                continue;
            }
            let change = 1.0 - search.uniform().powf(shape);
            let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
            if search.uniform() < 0.5 {
                *gene += (high - *gene) * change;
            } else {
                *gene -= (*gene - low) * change;
            }
        }
    }
}

impl<'p> Optimizer<Continuous<'p>> for Genetic {
    fn name(&self) -> &'static str {
        "GA"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let population = self.parameters.population.max(2);
        self.individuals = (0..population).map(|_| search.random_position()).collect();
        self.costs = self
            .individuals
            .iter()
            .map(|x| search.evaluate(x))
            .collect();
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        let k = search.progress();
        let (crossover, mutation) = match p.readings.rates {
            RateSchedule::Falling => (
                p.crossover_start + k * (p.crossover_end - p.crossover_start),
                p.mutation_start + k * (p.mutation_end - p.mutation_start),
            ),
            // The seed's ranges themselves, (0.4, 1) and (0, 0.5), not the schedule's ends.
            RateSchedule::Middle => (0.7, 0.25),
            RateSchedule::DrawnEachGeneration => {
                (search.uniform_in(0.4, 1.0), search.uniform_in(0.0, 0.5))
            }
        };
        let elite = super::bat::index_of_smallest(&self.costs);
        let mut next = vec![self.individuals[elite].clone()];
        let mut next_costs = vec![self.costs[elite]];
        while next.len() < self.individuals.len() {
            let mut first = self.individuals[self.tournament(search)].clone();
            let mut second = self.individuals[self.tournament(search)].clone();
            if search.uniform() < crossover {
                let lambda = search.uniform();
                for (a, b) in first.iter_mut().zip(second.iter_mut()) {
                    let (x, y) = (*a, *b);
                    *a = lambda * x + (1.0 - lambda) * y;
                    *b = (1.0 - lambda) * x + lambda * y;
                }
            }
            for mut child in [first, second] {
                if next.len() == self.individuals.len() {
                    break;
                }
                if search.uniform() < mutation {
                    self.mutate(&mut child, search);
                }
                search.clamp(&mut child);
                next_costs.push(search.evaluate(&child));
                next.push(child);
            }
        }
        self.individuals = next;
        self.costs = next_costs;
    }
}
