//! Particle swarm optimisation (PSO): Kennedy and Eberhart 1995, with the inertia weight of
//! Shi and Eberhart 1998 (docs/references.md), in seed 000's setting (c1 = c2 = 2, w = 0.729).
//!
//! - v_i = w·v_i + c1·r1·(p_i − x_i) + c2·r2·(g − x_i),  r1, r2 ~ U[0, 1] per coordinate
//! - x_i = x_i + v_i
//! - p_i and g: the personal and global best points, kept by cost.
//!
//! Readings (`ParticleSwarmReadings`, issue 20): seed 000 names no velocity limit; decision
//! 0007 limits each velocity coordinate to ± the box width (with c1 = c2 = 2 and w = 0.729 the
//! swarm sits at the edge of divergence, and without a limit velocities can overflow), and
//! the ablation also tries ± 0.2 and 0.1 of it; positions are clamped or reflected.
//!
//! [`ParticleSwarmParameters::spso`] is the PSO of SPSO's code (Phung & Ha 2021, from
//! Yarpiz): w = 1 damped by 0.98 after every iteration, c1 = c2 = 1.5, velocities within
//! ± half the box width, and a coordinate that leaves the box is clamped with its velocity
//! reversed ("mirrored").

use super::bat::index_of_smallest;
use crate::readings::{limit_velocity, Boundary, Readings, VelocityLimit};
use crate::runner::{Continuous, Optimizer, Search};

/// On the command line `pso`, in tables "PSO": `population` agents.
pub const ALGORITHM: super::Algorithm =
    super::Algorithm::with_readings("pso", "PSO", |population, readings| {
        Box::new(ParticleSwarm::new(ParticleSwarmParameters {
            population,
            velocity_limit: readings.particle_swarm.velocity_limit,
            boundary: readings.particle_swarm.boundary,
            ..Default::default()
        }))
    });

/// PSO's parameters; `Default` is seed 000's setting.
#[derive(Debug, Clone, PartialEq)]
pub struct ParticleSwarmParameters {
    /// Number of particles (at least 1).
    pub population: usize,
    /// Inertia weight w at the start of the run.
    pub inertia: f64,
    /// c1, the pull towards the particle's own best p_i.
    pub cognitive: f64,
    /// c2, the pull towards the global best g.
    pub social: f64,
    /// Velocity limit as a share of the box width (`None`: no limit).
    pub velocity_limit: VelocityLimit,
    /// What happens to a coordinate that leaves the box (after the mirror below).
    pub boundary: Boundary,
    /// w is multiplied by this after every iteration (1: constant).
    pub inertia_damping: f64,
    /// Reverse a velocity coordinate whose position left the box.
    pub mirror_velocity: bool,
}

impl ParticleSwarmParameters {
    /// SPSO's PSO settings (its `SPSO_MAIN.m`), for `population` particles.
    pub fn spso(population: usize) -> Self {
        Self {
            population,
            inertia: 1.0,
            cognitive: 1.5,
            social: 1.5,
            velocity_limit: Some(0.5),
            boundary: Boundary::Clamp,
            inertia_damping: 0.98,
            mirror_velocity: true,
        }
    }
}

impl Default for ParticleSwarmParameters {
    fn default() -> Self {
        Self {
            population: 500,
            inertia: 0.729,
            cognitive: 2.0,
            social: 2.0,
            velocity_limit: Readings::ENGINE.particle_swarm.velocity_limit,
            boundary: Readings::ENGINE.particle_swarm.boundary,
            inertia_damping: 1.0,
            mirror_velocity: false,
        }
    }
}

/// Global-best particle swarm optimisation.
#[derive(Debug, Clone, Default)]
pub struct ParticleSwarm {
    parameters: ParticleSwarmParameters,
    positions: Vec<Vec<f64>>,
    velocities: Vec<Vec<f64>>,
    personal_best: Vec<Vec<f64>>,
    personal_best_cost: Vec<f64>,
    best: Vec<f64>,
    best_cost: f64,
    inertia: f64,
}

impl ParticleSwarm {
    /// PSO with the given parameters; the swarm is drawn when the run starts.
    pub fn new(parameters: ParticleSwarmParameters) -> Self {
        Self {
            parameters,
            ..Self::default()
        }
    }
}

impl<'p> Optimizer<Continuous<'p>> for ParticleSwarm {
    fn name(&self) -> &'static str {
        "PSO"
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        let population = self.parameters.population.max(1);
        self.positions = (0..population).map(|_| search.random_position()).collect();
        self.velocities = vec![vec![0.0; search.dimension()]; population];
        self.personal_best = self.positions.clone();
        self.personal_best_cost = self.positions.iter().map(|x| search.evaluate(x)).collect();
        let best = index_of_smallest(&self.personal_best_cost);
        self.best = self.positions[best].clone();
        self.best_cost = self.personal_best_cost[best];
        self.inertia = self.parameters.inertia;
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        let p = &self.parameters;
        let dimension = search.dimension();
        for particle in 0..self.positions.len() {
            let position = &mut self.positions[particle];
            let velocity = &mut self.velocities[particle];
            let personal = &self.personal_best[particle];
            for d in 0..dimension {
                let (r1, r2) = (search.uniform(), search.uniform());
                let value = self.inertia * velocity[d]
                    + p.cognitive * r1 * (personal[d] - position[d])
                    + p.social * r2 * (self.best[d] - position[d]);
                velocity[d] = limit_velocity(p.velocity_limit, value, search.bounds().width(d));
                position[d] += velocity[d];
                let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
                if p.mirror_velocity && !(low..=high).contains(&position[d]) {
                    velocity[d] = -velocity[d];
                }
            }
            p.boundary.apply(search, position, Some(velocity));
            let cost = search.evaluate(position);
            if cost < self.personal_best_cost[particle] {
                self.personal_best[particle].copy_from_slice(position);
                self.personal_best_cost[particle] = cost;
                if cost < self.best_cost {
                    self.best.copy_from_slice(position);
                    self.best_cost = cost;
                }
            }
        }
        self.inertia *= p.inertia_damping;
    }
}
