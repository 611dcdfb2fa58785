//! One file per algorithm, each opening with its equations and its deviations.

pub mod ant_colony;
pub mod bat;
pub mod genetic;
pub mod gravitational_search;
pub mod iba_fcs;
pub mod ilssiwba;
pub mod lshade;
pub mod particle_swarm;
pub mod random_search;

use std::fmt;
use std::str::FromStr;

pub use ant_colony::{AntColony, AntColonyParameters};
pub use bat::{Bat, BatParameters};
pub use genetic::{Genetic, GeneticParameters};
pub use gravitational_search::{GravitationalSearch, GravitationalSearchParameters};
pub use iba_fcs::{IbaFcs, IbaFcsParameters};
pub use ilssiwba::{Ilssiwba, IlssiwbaParameters};
pub use lshade::{Lshade, LshadeParameters};
pub use particle_swarm::{ParticleSwarm, ParticleSwarmParameters};
pub use random_search::RandomSearch;

use crate::readings::Readings;
use crate::runner::ContinuousOptimizer;

/// The optimizers, registered in one place: adding one is its file plus one line here.
/// `--algorithm all` and the conformance suite take every one of them.
pub const ALL: &[Algorithm] = &[
    particle_swarm::ALGORITHM,
    genetic::ALGORITHM,
    bat::ALGORITHM,
    ilssiwba::ALGORITHM,
    iba_fcs::ALGORITHM,
    gravitational_search::ALGORITHM,
    ant_colony::ALGORITHM,
    lshade::ALGORITHM,
];

/// Baselines: known by name, left out of `all` (they are what the optimizers must beat).
pub const BASELINES: &[Algorithm] = &[random_search::ALGORITHM];

/// An algorithm by name, for configuration files and the command line, with the builder
/// that makes it with its paper's parameters. Each algorithm's file declares its own
/// `ALGORITHM`.
#[derive(Clone, Copy)]
pub struct Algorithm {
    key: &'static str,
    label: &'static str,
    build: Builder,
}

/// How an algorithm is made: from a population size, or also from the readings of its
/// paper's open choices ([`Readings`]).
#[derive(Clone, Copy)]
enum Builder {
    Plain(fn(usize) -> Box<ContinuousOptimizer<'static>>),
    Read(fn(usize, &Readings) -> Box<ContinuousOptimizer<'static>>),
}

impl Algorithm {
    /// An algorithm called `key` on the command line and `label` in tables, made by `build`
    /// from a population size.
    pub const fn new(
        key: &'static str,
        label: &'static str,
        build: fn(usize) -> Box<ContinuousOptimizer<'static>>,
    ) -> Self {
        Self {
            key,
            label,
            build: Builder::Plain(build),
        }
    }

    /// An algorithm whose builder also takes the [`Readings`] of its open choices.
    pub const fn with_readings(
        key: &'static str,
        label: &'static str,
        build: fn(usize, &Readings) -> Box<ContinuousOptimizer<'static>>,
    ) -> Self {
        Self {
            key,
            label,
            build: Builder::Read(build),
        }
    }

    /// Every registered optimizer ([`ALL`]), in table order.
    pub const ALL: &'static [Algorithm] = ALL;

    /// The five algorithms of seed 000's Table 2, in its column order.
    pub const SEED_000: [Algorithm; 5] = [
        particle_swarm::ALGORITHM,
        genetic::ALGORITHM,
        bat::ALGORITHM,
        ilssiwba::ALGORITHM,
        iba_fcs::ALGORITHM,
    ];

    /// PSO.
    pub const PARTICLE_SWARM: Algorithm = particle_swarm::ALGORITHM;
    /// GA.
    pub const GENETIC: Algorithm = genetic::ALGORITHM;
    /// BA.
    pub const BAT: Algorithm = bat::ALGORITHM;
    /// ILSSIWBA.
    pub const ILSSIWBA: Algorithm = ilssiwba::ALGORITHM;
    /// IBA-FCS, seed 000's algorithm.
    pub const IBA_FCS: Algorithm = iba_fcs::ALGORITHM;
    /// GSA.
    pub const GRAVITATIONAL_SEARCH: Algorithm = gravitational_search::ALGORITHM;
    /// ACO_R.
    pub const ANT_COLONY: Algorithm = ant_colony::ALGORITHM;
    /// L-SHADE.
    pub const LSHADE: Algorithm = lshade::ALGORITHM;
    /// The random-search baseline.
    pub const RANDOM_SEARCH: Algorithm = random_search::ALGORITHM;

    /// The name used on the command line.
    pub fn key(self) -> &'static str {
        self.key
    }

    /// The name used in tables (as the papers write it).
    pub fn label(self) -> &'static str {
        self.label
    }

    /// The algorithm with its paper's parameters and `population` agents (evaluations per
    /// iteration). ACO_R keeps its archive of 50 and sends `population` ants; L-SHADE keeps
    /// its own initial population of 18·D, which it shrinks over the budget.
    /// The open choices are decision 0007's ([`Readings::ENGINE`]).
    pub fn build(self, population: usize) -> Box<ContinuousOptimizer<'static>> {
        self.build_read(population, &Readings::ENGINE)
    }

    /// The algorithm with `population` agents and the given readings of its paper's open
    /// choices (an algorithm without readings ignores them).
    pub fn build_read(
        self,
        population: usize,
        readings: &Readings,
    ) -> Box<ContinuousOptimizer<'static>> {
        match self.build {
            Builder::Plain(build) => build(population),
            Builder::Read(build) => build(population, readings),
        }
    }

    /// Whether [`Readings`] change this algorithm.
    pub fn has_readings(self) -> bool {
        matches!(self.build, Builder::Read(_))
    }
}

impl PartialEq for Algorithm {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}

impl Eq for Algorithm {}

impl std::hash::Hash for Algorithm {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.key.hash(state);
    }
}

impl fmt::Debug for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.label)
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

impl FromStr for Algorithm {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let wanted = text.trim().to_ascii_lowercase().replace('_', "-");
        ALL.iter()
            .chain(BASELINES)
            .copied()
            .find(|a| {
                a.key() == wanted || a.label().to_ascii_lowercase().replace('_', "-") == wanted
            })
            .ok_or_else(|| {
                let names: Vec<&str> = ALL.iter().chain(BASELINES).map(|a| a.key()).collect();
                format!("unknown algorithm '{text}' (known: {})", names.join(", "))
            })
    }
}
