//! One file per algorithm, each opening with its equations and its deviations.

pub mod ant_colony;
pub mod bat;
pub mod genetic;
pub mod gravitational_search;
pub mod iba_fcs;
pub mod ilssiwba;
pub mod lshade;
pub mod particle_swarm;

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

use crate::runner::Optimizer;

/// The algorithms by name, for configuration files and the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Algorithm {
    ParticleSwarm,
    Genetic,
    Bat,
    Ilssiwba,
    IbaFcs,
    GravitationalSearch,
    AntColony,
    Lshade,
}

impl Algorithm {
    pub const ALL: [Algorithm; 8] = [
        Algorithm::ParticleSwarm,
        Algorithm::Genetic,
        Algorithm::Bat,
        Algorithm::Ilssiwba,
        Algorithm::IbaFcs,
        Algorithm::GravitationalSearch,
        Algorithm::AntColony,
        Algorithm::Lshade,
    ];

    /// The five algorithms of seed 000's Table 2, in its column order.
    pub const SEED_000: [Algorithm; 5] = [
        Algorithm::ParticleSwarm,
        Algorithm::Genetic,
        Algorithm::Bat,
        Algorithm::Ilssiwba,
        Algorithm::IbaFcs,
    ];

    /// The name used on the command line.
    pub fn key(self) -> &'static str {
        match self {
            Algorithm::ParticleSwarm => "pso",
            Algorithm::Genetic => "ga",
            Algorithm::Bat => "ba",
            Algorithm::Ilssiwba => "ilssiwba",
            Algorithm::IbaFcs => "iba-fcs",
            Algorithm::GravitationalSearch => "gsa",
            Algorithm::AntColony => "aco-r",
            Algorithm::Lshade => "lshade",
        }
    }

    /// The name used in tables (as the papers write it).
    pub fn label(self) -> &'static str {
        match self {
            Algorithm::ParticleSwarm => "PSO",
            Algorithm::Genetic => "GA",
            Algorithm::Bat => "BA",
            Algorithm::Ilssiwba => "ILSSIWBA",
            Algorithm::IbaFcs => "IBA-FCS",
            Algorithm::GravitationalSearch => "GSA",
            Algorithm::AntColony => "ACO_R",
            Algorithm::Lshade => "L-SHADE",
        }
    }

    /// The algorithm with its paper's parameters and `population` agents (evaluations per
    /// iteration). ACO_R keeps its archive of 50 and sends `population` ants; L-SHADE keeps
    /// its own initial population of 18·D, which it shrinks over the budget.
    pub fn build(self, population: usize) -> Box<dyn Optimizer> {
        match self {
            Algorithm::ParticleSwarm => Box::new(ParticleSwarm::new(ParticleSwarmParameters {
                population,
                ..Default::default()
            })),
            Algorithm::Genetic => Box::new(Genetic::new(GeneticParameters {
                population,
                ..Default::default()
            })),
            Algorithm::Bat => Box::new(Bat::new(BatParameters {
                population,
                ..Default::default()
            })),
            Algorithm::Ilssiwba => Box::new(Ilssiwba::new(IlssiwbaParameters {
                population,
                ..Default::default()
            })),
            Algorithm::IbaFcs => Box::new(IbaFcs::new(IbaFcsParameters {
                population,
                ..Default::default()
            })),
            Algorithm::GravitationalSearch => {
                Box::new(GravitationalSearch::new(GravitationalSearchParameters {
                    population,
                    ..Default::default()
                }))
            }
            Algorithm::AntColony => Box::new(AntColony::new(AntColonyParameters {
                ants: population,
                ..Default::default()
            })),
            Algorithm::Lshade => Box::new(Lshade::new(LshadeParameters::default())),
        }
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
        Algorithm::ALL
            .into_iter()
            .find(|a| {
                a.key() == wanted || a.label().to_ascii_lowercase().replace('_', "-") == wanted
            })
            .ok_or_else(|| {
                let names: Vec<&str> = Algorithm::ALL.iter().map(|a| a.key()).collect();
                format!("unknown algorithm '{text}' (known: {})", names.join(", "))
            })
    }
}
