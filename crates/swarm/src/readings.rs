//! Readings: the places where seed 000's text (and the papers it cites for its baselines)
//! admits more than one implementation, as named settings of each algorithm rather than
//! forks of it (issue 20, docs/decisions/0020-readings-of-seed-000.md).
//!
//! A [`Readings`] value fixes every open choice of BA, IBA-FCS, PSO and the GA at once;
//! [`Readings::named`] knows the named sets the ablation runs:
//!
//! - `paper`: the reading closest to the text of seed 000 (the default of
//!   `repro seed000-table2`);
//! - `engine`: the choices of decision 0007, which every other caller of the engine keeps
//!   (`Algorithm::build`): the tracks of Tables 4-5 are unchanged by this module;
//! - one name per single change from `paper`, each naming the algorithm it changes, and
//!   the combinations the ablation found worth keeping.

use crate::runner::{Continuous, Search};

/// What happens to a coordinate that leaves the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Boundary {
    /// Moved to the nearest bound (the velocity is kept).
    Clamp,
    /// Mirrored at the bound it crossed (folded back as often as needed), and its velocity
    /// reversed.
    Reflect,
    /// Drawn again uniformly between the bounds (the velocity is kept).
    Redraw,
}

impl Boundary {
    /// Brings `position` into the search box; `velocity`, when given, is the agent's
    /// velocity, reversed in a reflected coordinate.
    pub fn apply(
        self,
        search: &mut Search<Continuous<'_>>,
        position: &mut [f64],
        mut velocity: Option<&mut [f64]>,
    ) {
        match self {
            Boundary::Clamp => search.clamp(position),
            Boundary::Reflect => {
                for (d, value) in position.iter_mut().enumerate() {
                    let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
                    if (low..=high).contains(value) {
                        continue;
                    }
                    *value = reflect(*value, low, high);
                    if let Some(velocity) = velocity.as_deref_mut() {
                        velocity[d] = -velocity[d];
                    }
                }
            }
            Boundary::Redraw => {
                for (d, value) in position.iter_mut().enumerate() {
                    let (low, high) = (search.bounds().lower()[d], search.bounds().upper()[d]);
                    if !(low..=high).contains(value) {
                        *value = search.uniform_in(low, high);
                    }
                }
            }
        }
    }
}

/// `value` folded into [low, high] by mirroring at the bounds (period 2·(high − low)).
/// Non-finite values, which have no mirror image, go to the middle.
pub fn reflect(value: f64, low: f64, high: f64) -> f64 {
    let width = high - low;
    if !value.is_finite() || width <= 0.0 {
        return if width <= 0.0 { low } else { low + width / 2.0 };
    }
    let folded = (value - low).rem_euclid(2.0 * width);
    let inside = if folded > width {
        2.0 * width - folded
    } else {
        folded
    };
    (low + inside).clamp(low, high)
}

/// How a random factor the text names is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Draw {
    /// One value per coordinate (a "random vector").
    PerCoordinate,
    /// One value per agent and move, shared by every coordinate (a "random number").
    OnePerAgent,
}

impl Draw {
    /// Fills `values` with uniform draws in [low, high) as this reading says.
    pub fn fill(
        self,
        search: &mut Search<Continuous<'_>>,
        values: &mut [f64],
        low: f64,
        high: f64,
    ) {
        match self {
            Draw::PerCoordinate => {
                for value in values.iter_mut() {
                    *value = search.uniform_in(low, high);
                }
            }
            Draw::OnePerAgent => {
                let shared = search.uniform_in(low, high);
                values.fill(shared);
            }
        }
    }
}

/// Limits each velocity coordinate to ± `fraction` × the box width in that coordinate.
/// `None`: no limit.
pub type VelocityLimit = Option<f64>;

/// Applies a [`VelocityLimit`] to one velocity coordinate in a box of width `width`.
pub fn limit_velocity(limit: VelocityLimit, value: f64, width: f64) -> f64 {
    match limit {
        Some(fraction) => value.clamp(-fraction * width, fraction * width),
        None => value,
    }
}

/// BA's open choices (seed 000 §1, eqs. 1-6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatReadings {
    /// β of eq. (3): the text calls it a "random vector" (随机向量); Yang's code draws one
    /// scalar per bat.
    pub frequency: Draw,
    /// ε of eq. (4): the text calls it a "random number" (随机数); Yang's code draws a vector.
    pub walk: Draw,
    /// Velocity limit (the text gives none).
    pub velocity_limit: VelocityLimit,
    /// Boundary handling (the text gives none).
    pub boundary: Boundary,
}

/// When IBA-FCS's adaptive local search of §2.2 fires.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LocalSearchDraw {
    /// β_i ~ U[0, R_max] and local search when β_i < R (the text): once R reaches its cap
    /// R_max, every bat searches locally and the mutation of §2.3 never fires.
    UpToPulseRateCap,
    /// β_i ~ U[0, 1]: the chance of a local search is R, at most R_max.
    UpToOne,
}

/// What a bat keeps after an eq.-(12) jump near the best.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JumpVelocity {
    /// Its velocity from eq. (8) (the text sets only the position).
    Keep,
    /// Zero: the jump is a restart near the best.
    Zero,
}

/// Which points a bat or particle moves to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Acceptance {
    /// Every new point (§2.4 step 5 read as "update the positions, keep the bests by cost").
    EveryMove,
    /// Only a new point no worse than the agent's current one.
    Greedy,
}

/// IBA-FCS's open choices (seed 000 §2, eqs. 8-15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IbaFcsReadings {
    /// The draw that decides the local search.
    pub local_search: LocalSearchDraw,
    /// The velocity after an eq.-(12) jump.
    pub jump_velocity: JumpVelocity,
    /// δ of eq. (12): "random vector" (随机向量) in the text.
    pub jump: Draw,
    /// Acceptance of a bat's new point.
    pub acceptance: Acceptance,
    /// Velocity limit (the text gives none).
    pub velocity_limit: VelocityLimit,
    /// Boundary handling (the text gives none).
    pub boundary: Boundary,
}

/// PSO's open choices (seed 000 gives c1 = c2 = 2 and w = 0.729 only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleSwarmReadings {
    /// Velocity limit.
    pub velocity_limit: VelocityLimit,
    /// Boundary handling.
    pub boundary: Boundary,
}

/// How the GA uses the rate ranges seed 000 gives (crossover (0.4, 1), mutation (0, 0.5)).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RateSchedule {
    /// From the top of each range to its bottom, linearly over the run (decision 0007).
    Falling,
    /// The middle of each range throughout (p_c = 0.7, p_m = 0.25).
    Middle,
    /// Drawn uniformly from each range once per generation.
    DrawnEachGeneration,
}

/// The GA's open choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GeneticReadings {
    /// How the crossover and mutation rates move within their ranges.
    pub rates: RateSchedule,
}

/// One reading of every open choice of seed 000's five algorithms (ILSSIWBA's own paper
/// was not available: it is built from its idea, decision 0007, and has no readings).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Readings {
    /// BA's.
    pub bat: BatReadings,
    /// IBA-FCS's.
    pub iba_fcs: IbaFcsReadings,
    /// PSO's.
    pub particle_swarm: ParticleSwarmReadings,
    /// The GA's.
    pub genetic: GeneticReadings,
}

/// The names [`Readings::named`] knows, with what each changes, in ablation order.
pub const NAMES: &[(&str, &str)] = &[
    ("paper", "the reading closest to seed 000's text"),
    (
        "engine",
        "decision 0007's choices (the engine's default for every other caller)",
    ),
    (
        "ba-scalar-beta",
        "BA: one β per bat in eq. (3), as Yang's code",
    ),
    (
        "ba-vector-epsilon",
        "BA: ε of eq. (4) per coordinate, as Yang's code",
    ),
    (
        "ba-velocity-limit",
        "BA: velocities within ± 0.2 × the box width",
    ),
    (
        "iba-beta-to-one",
        "IBA-FCS: β_i ~ U[0, 1], so P(local search) stays ≤ R_max",
    ),
    (
        "iba-zero-velocity",
        "IBA-FCS: velocity zeroed after an eq.-(12) jump",
    ),
    (
        "iba-greedy",
        "IBA-FCS: a bat moves only to a point no worse than its own",
    ),
    ("iba-scalar-delta", "IBA-FCS: one δ per jump in eq. (12)"),
    (
        "iba-velocity-limit",
        "IBA-FCS: velocities within ± 0.2 × the box width",
    ),
    ("iba-reflect", "IBA-FCS: positions mirrored at the bounds"),
    ("iba-redraw", "IBA-FCS: out-of-box coordinates drawn again"),
    (
        "pso-velocity-limit-1",
        "PSO: velocities within ± the box width (decision 0007)",
    ),
    (
        "pso-velocity-limit-0.2",
        "PSO: velocities within ± 0.2 × the box width",
    ),
    (
        "pso-velocity-limit-0.1",
        "PSO: velocities within ± 0.1 × the box width",
    ),
    (
        "pso-reflect",
        "PSO: positions mirrored at the bounds, no velocity limit",
    ),
    ("ga-middle-rates", "GA: p_c = 0.7 and p_m = 0.25 throughout"),
    (
        "ga-drawn-rates",
        "GA: p_c and p_m drawn from their ranges each generation",
    ),
];

impl Readings {
    /// The reading closest to seed 000's text: BA's β a vector and ε a number (as §1 words
    /// them), no velocity limits and clamped positions (the text names neither), IBA-FCS's
    /// β_i ~ U[0, R_max] (§2.2), its velocity kept after a jump (the text sets only the
    /// position), δ a vector, every move accepted (§2.4 step 5), the GA's rates falling
    /// through their ranges.
    pub const PAPER: Readings = Readings {
        bat: BatReadings {
            frequency: Draw::PerCoordinate,
            walk: Draw::OnePerAgent,
            velocity_limit: None,
            boundary: Boundary::Clamp,
        },
        iba_fcs: IbaFcsReadings {
            local_search: LocalSearchDraw::UpToPulseRateCap,
            jump_velocity: JumpVelocity::Keep,
            jump: Draw::PerCoordinate,
            acceptance: Acceptance::EveryMove,
            velocity_limit: None,
            boundary: Boundary::Clamp,
        },
        particle_swarm: ParticleSwarmReadings {
            velocity_limit: None,
            boundary: Boundary::Clamp,
        },
        genetic: GeneticReadings {
            rates: RateSchedule::Falling,
        },
    };

    /// Decision 0007's choices, which `Algorithm::build` keeps: BA's β one scalar and ε a
    /// vector (Yang's code), PSO's velocity within ± the box width; the rest as `PAPER`.
    pub const ENGINE: Readings = Readings {
        bat: BatReadings {
            frequency: Draw::OnePerAgent,
            walk: Draw::PerCoordinate,
            ..Self::PAPER.bat
        },
        particle_swarm: ParticleSwarmReadings {
            velocity_limit: Some(1.0),
            boundary: Boundary::Clamp,
        },
        ..Self::PAPER
    };

    /// The readings called `name` (see [`NAMES`]); several can be joined with `+`, each
    /// applied to `paper` in turn (`iba-zero-velocity+pso-velocity-limit-0.2`).
    pub fn named(name: &str) -> Result<Readings, String> {
        let mut readings = Readings::PAPER;
        for part in name.split('+') {
            readings = readings.with(part.trim()).ok_or_else(|| {
                let known: Vec<&str> = NAMES.iter().map(|(name, _)| *name).collect();
                format!(
                    "unknown reading '{part}' (known: {}; join several with '+')",
                    known.join(", ")
                )
            })?;
        }
        Ok(readings)
    }

    /// These readings with the single change called `name`.
    fn with(mut self, name: &str) -> Option<Readings> {
        let (bat, iba, pso) = (&mut self.bat, &mut self.iba_fcs, &mut self.particle_swarm);
        match name {
            "paper" => {}
            "engine" => return Some(Readings::ENGINE),
            "ba-scalar-beta" => bat.frequency = Draw::OnePerAgent,
            "ba-vector-epsilon" => bat.walk = Draw::PerCoordinate,
            "ba-velocity-limit" => bat.velocity_limit = Some(0.2),
            "iba-beta-to-one" => iba.local_search = LocalSearchDraw::UpToOne,
            "iba-zero-velocity" => iba.jump_velocity = JumpVelocity::Zero,
            "iba-greedy" => iba.acceptance = Acceptance::Greedy,
            "iba-scalar-delta" => iba.jump = Draw::OnePerAgent,
            "iba-velocity-limit" => iba.velocity_limit = Some(0.2),
            "iba-reflect" => iba.boundary = Boundary::Reflect,
            "iba-redraw" => iba.boundary = Boundary::Redraw,
            "pso-velocity-limit-1" => pso.velocity_limit = Some(1.0),
            "pso-velocity-limit-0.2" => pso.velocity_limit = Some(0.2),
            "pso-velocity-limit-0.1" => pso.velocity_limit = Some(0.1),
            "pso-reflect" => pso.boundary = Boundary::Reflect,
            "ga-middle-rates" => self.genetic.rates = RateSchedule::Middle,
            "ga-drawn-rates" => self.genetic.rates = RateSchedule::DrawnEachGeneration,
            _ => return None,
        }
        Some(self)
    }
}

impl Default for Readings {
    fn default() -> Self {
        Readings::PAPER
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_folds_back_into_the_box() {
        assert_eq!(reflect(12.0, -10.0, 10.0), 8.0);
        assert_eq!(reflect(-13.0, -10.0, 10.0), -7.0);
        // Beyond a whole width: 35 → 25 past the upper bound folds twice.
        assert_eq!(reflect(35.0, -10.0, 10.0), -5.0);
        assert_eq!(reflect(5.0, -10.0, 10.0), 5.0);
        assert_eq!(reflect(f64::INFINITY, -10.0, 10.0), 0.0);
    }

    #[test]
    fn every_name_is_known_and_changes_something_but_paper() {
        for (name, _) in NAMES {
            let readings = Readings::named(name).unwrap();
            assert_eq!(readings == Readings::PAPER, *name == "paper", "{name}");
        }
        let joined = Readings::named("iba-greedy+pso-velocity-limit-0.2").unwrap();
        assert_eq!(joined.iba_fcs.acceptance, Acceptance::Greedy);
        assert_eq!(joined.particle_swarm.velocity_limit, Some(0.2));
        let error = Readings::named("iba-greed").unwrap_err();
        assert!(error.contains("iba-greed") && error.contains("iba-greedy"));
    }

    #[test]
    fn the_limit_is_a_share_of_the_width() {
        assert_eq!(limit_velocity(Some(0.2), 50.0, 100.0), 20.0);
        assert_eq!(limit_velocity(Some(0.2), -50.0, 100.0), -20.0);
        assert_eq!(limit_velocity(None, 1e300, 100.0), 1e300);
    }
}
