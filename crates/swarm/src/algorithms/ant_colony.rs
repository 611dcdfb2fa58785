//! Continuous ant colony optimisation (ACO_R): Socha and Dorigo, "Ant colony optimization for
//! continuous domains", European Journal of Operational Research 185 (2008) 1155-1173
//! (Socha & Dorigo 2008, docs/references.md)
//! (equation numbers of the paper). Seed 002 compares its GA against an ACO; this is the
//! continuous member of the family for the same encodings.
//!
//! An archive of the k best solutions, sorted by cost, defines a Gaussian mixture:
//! - (8) weight of rank l (1-based)  ω_l = exp(−(l − 1)² / (2 q² k²)) / (q k √(2π))
//! - each ant picks a guide l with probability ω_l / Σ ω (roulette), then for every coordinate
//! - (9) σ_l^i = ξ·Σ_{e=1}^{k} |s_e^i − s_l^i| / (k − 1), and samples x^i ~ N(s_l^i, σ_l^i)
//! - the m new solutions join the archive and the k best stay.
//!
//! Defaults k = 50, q = 1e-4, ξ = 0.85 (the paper's setting for its benchmark functions).
//! `ants` is m; the paper uses m = 2, the benches give it the population size so that every
//! algorithm spends the same evaluations per iteration. Samples outside the box are clamped.

use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `aco-r`, in tables "ACO_R": `population` agents.
pub const ALGORITHM: super::Algorithm = super::Algorithm::new("aco-r", "ACO_R", |population| {
    Box::new(AntColony::new(AntColonyParameters {
        ants: population,
        ..Default::default()
    }))
});

/// ACO_R's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct AntColonyParameters {
    /// k: how many solutions the archive keeps (at least 2).
    pub archive: usize,
    /// m: new solutions sampled per iteration (at least 1).
    pub ants: usize,
    /// q: how strongly the best-ranked solutions guide (small = greedy).
    pub locality: f64,
    /// ξ: the spread of the Gaussians relative to the archive's (like an evaporation rate).
    pub spread: f64,
}

impl Default for AntColonyParameters {
    fn default() -> Self {
        Self {
            archive: 50,
            ants: 2,
            locality: 1e-4,
            spread: 0.85,
        }
    }
}

/// ACO_R, the continuous ant colony.
#[derive(Debug, Clone, Default)]
pub struct AntColony {
    parameters: AntColonyParameters,
    /// Archive solutions sorted by cost.
    archive: Vec<(f64, Vec<f64>)>,
    cumulative_weights: Vec<f64>,
}

impl AntColony {
    /// ACO_R with the given parameters; the archive is drawn when the run starts.
    pub fn new(parameters: AntColonyParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }

    fn pick_guide(&self, search: &mut Search<Continuous<'_>>) -> usize {
        let total = *self.cumulative_weights.last().unwrap_or(&1.0);
        let draw = search.uniform() * total;
        self.cumulative_weights
            .partition_point(|&weight| weight <= draw)
            .min(self.archive.len() - 1)
    }
}

impl<'p> Optimizer<Continuous<'p>> for AntColony {
    fn name(&self) -> &'static str {
        "ACO_R"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let size = self.parameters.archive.max(2);
        self.archive = (0..size)
            .map(|_| {
                let x = search.random_position();
                (search.evaluate(&x), x)
            })
            .collect();
        self.archive.sort_by(|a, b| a.0.total_cmp(&b.0));
        let qk = self.parameters.locality * size as f64;
        let mut running = 0.0;
        self.cumulative_weights = (0..size)
            .map(|rank| {
                // eq. (8); the common factor 1/(q k √(2π)) cancels in the roulette.
                running += (-(rank as f64).powi(2) / (2.0 * qk * qk)).exp();
                running
            })
            .collect();
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let dimension = search.dimension();
        let size = self.archive.len();
        let mut spreads: Vec<Option<Vec<f64>>> = vec![None; size];
        let mut newcomers = Vec::with_capacity(self.parameters.ants);
        for _ in 0..self.parameters.ants.max(1) {
            let guide = self.pick_guide(search);
            let spread = spreads[guide].get_or_insert_with(|| {
                (0..dimension)
                    .map(|i| {
                        let centre = self.archive[guide].1[i];
                        let total: f64 = self
                            .archive
                            .iter()
                            .map(|(_, s)| (s[i] - centre).abs())
                            .sum();
                        self.parameters.spread * total / (size - 1) as f64 // eq. (9)
                    })
                    .collect()
            });
            let mut x: Vec<f64> = (0..dimension)
                .map(|i| self.archive[guide].1[i] + spread[i] * search.normal())
                .collect();
            search.clamp(&mut x);
            newcomers.push((search.evaluate(&x), x));
        }
        self.archive.extend(newcomers);
        self.archive.sort_by(|a, b| a.0.total_cmp(&b.0));
        self.archive.truncate(size);
    }
}
