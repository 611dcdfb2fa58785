//! Choosing each field's swath heading (seed 001 §2.2, eq. 1).
//!
//! E(θ) = ω_N · (N − N_min)/(N_max − N_min) + ω_L · (L − L_min)/(L_max − L_min)   (1)
//!
//! N is the number of swaths and L = Σ L_i their total draped (3D) length at heading θ; the
//! minima and maxima are over the headings tried, 0..179° in 1° steps. Contract decision 2 (docs/contract.md):
//! a term whose max equals its min is 0; ties go to the smaller heading. Then, our addition,
//! a local refinement tries θ* ± 0.1..0.9° and keeps a heading only if it lowers E (with the
//! same normalisation); both the integer and the refined heading are reported.
//!
//! `dose` (the command line's default, decision 0019): E as above, then, of the headings
//! whose E is within [`DOSE_TOLERANCE`] of the least, the one whose swath ends, cut against
//! the edge band, spray least twice ([`near_best_headings`] lists them; the cut is measured in
//! `coverage::cover_field`). Square swath ends leave a triangle of w²·|cot δ|/2 against a band
//! at angle δ, sprayed twice or missed; E counts swaths and length, not the slant of their
//! ends. `auto` stays E alone (the seed's, for the tables).

use serde::Serialize;

/// What a heading is chosen for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "objective", rename_all = "snake_case")]
pub enum HeadingObjective {
    /// Seed 001's E with weights ω_N (swath count) and ω_L (length).
    Seed {
        /// ω_N, the weight of the swath-count term; 0 or more.
        count_weight: f64,
        /// ω_L, the weight of the length term; 0 or more (not both 0).
        length_weight: f64,
    },
    /// Seed 001's E, then the least double dose among the headings whose E is within
    /// [`DOSE_TOLERANCE`] of the least (module docs); E alone where there is no edge band to
    /// cut against.
    LeastDose {
        /// ω_N, as in [`HeadingObjective::Seed`].
        count_weight: f64,
        /// ω_L, as in [`HeadingObjective::Seed`].
        length_weight: f64,
    },
    /// Fewest swaths (each one is a headland U-turn, so also fewest turns); ties: shorter.
    Swaths,
    /// Shortest total draped length.
    Length,
    /// A compass bearing of the swaths given by the user (`bearing:DEG`), degrees clockwise
    /// from true north: each field flies it, turned into its own frame by the grid
    /// convergence there ([`HeadingObjective::for_field`]).
    Bearing {
        /// Degrees clockwise from true north, modulo 180°.
        bearing_deg: f64,
    },
    /// A heading given by the user, degrees.
    Fixed {
        /// Degrees from east, counter-clockwise ([`HeadingObjective::parse`] takes it modulo 180°).
        heading_deg: f64,
    },
}

impl HeadingObjective {
    /// Reads `dose` (E, then the least double dose), `auto` (seed 001's E with these weights
    /// ω_N, ω_L), `swaths` (alias `turns`),
    /// `length`, a heading in degrees from east, counter-clockwise (the seed's angle), or
    /// `bearing:DEG`, a compass bearing (0° = north, clockwise); both taken modulo 180°.
    pub fn parse(spec: &str, weights: [f64; 2]) -> Result<Self, String> {
        if let Some(bearing) = spec.strip_prefix("bearing:") {
            return match bearing.parse::<f64>() {
                Ok(bearing_deg) if bearing_deg.is_finite() => Ok(Self::Bearing {
                    bearing_deg: bearing_deg.rem_euclid(180.0),
                }),
                _ => Err("expected bearing:DEG, a compass bearing in degrees".into()),
            };
        }
        Ok(match spec {
            "auto" => Self::Seed {
                count_weight: weights[0],
                length_weight: weights[1],
            },
            "dose" => Self::LeastDose {
                count_weight: weights[0],
                length_weight: weights[1],
            },
            "swaths" | "turns" => Self::Swaths,
            "length" => Self::Length,
            degrees => match degrees.parse::<f64>() {
                Ok(heading_deg) if heading_deg.is_finite() => Self::Fixed {
                    heading_deg: heading_deg.rem_euclid(180.0),
                },
                _ => {
                    return Err(
                        "expected dose, auto, swaths, length, degrees from east or bearing:DEG"
                            .into(),
                    )
                }
            },
        })
    }
}

impl HeadingObjective {
    /// The objective for a field whose frame's north lies `grid_north_bearing_deg` clockwise
    /// of true north: a compass bearing becomes the fixed heading in that frame; the rest are
    /// the same in any frame.
    pub fn for_field(self, grid_north_bearing_deg: f64) -> Self {
        match self {
            Self::Bearing { bearing_deg } => Self::Fixed {
                heading_deg: crate::geometry::heading_of_bearing_deg(
                    bearing_deg - grid_north_bearing_deg,
                ),
            },
            other => other,
        }
    }

    /// Seed 001's E with the paper's weights ω_N = ω_L = 0.5 (`--heading auto`): the tables'.
    pub const SEED: Self = Self::Seed {
        count_weight: 0.5,
        length_weight: 0.5,
    };

    /// The weights ω_N, ω_L of E, for the objectives that use it.
    pub fn seed_weights(&self) -> Option<(f64, f64)> {
        match *self {
            Self::Seed {
                count_weight,
                length_weight,
            }
            | Self::LeastDose {
                count_weight,
                length_weight,
            } => Some((count_weight, length_weight)),
            _ => None,
        }
    }
}

/// The default is the command line's, `dose` with ω_N = ω_L = 0.5.
impl Default for HeadingObjective {
    fn default() -> Self {
        Self::LeastDose {
            count_weight: 0.5,
            length_weight: 0.5,
        }
    }
}

/// How far above the least E (eq. 1, in [0, 1] with both weights 0.5) a heading may be for
/// `dose` to take it for less double dose (measured in decision 0019: 0.1, 0.2, 0.3, 0.5
/// and 1.0 gave 4.24, 4.11, 3.94, 3.77 and 3.72 % of the field sprayed twice, E alone 4.39 %).
pub const DOSE_TOLERANCE: f64 = 0.5;
/// Most headings `dose` cuts and measures, best E first.
pub const DOSE_CANDIDATES: usize = 24;
/// Least difference between two headings `dose` measures, degrees: nearer ones cut alike.
const DOSE_SEPARATION_DEG: f64 = 4.0;

/// What one heading gives.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HeadingSample {
    /// Heading tried, degrees from east, counter-clockwise.
    pub heading_deg: f64,
    /// Number of interior swaths at that heading (seed 001's N).
    pub swaths: usize,
    /// Total draped length of those swaths, metres (seed 001's L).
    pub length_m: f64,
}

/// The chosen heading and how it was found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeadingChoice {
    /// The chosen heading, degrees from east, counter-clockwise, in 0..180.
    pub heading_deg: f64,
    /// Best of the 1° scan (the seed's answer).
    pub integer_heading_deg: f64,
    /// E at the integer heading and at the chosen one (both 0 for fixed headings).
    pub integer_objective: f64,
    /// The objective at the chosen heading.
    pub objective: f64,
    /// Number of interior swaths at the chosen heading.
    pub swaths: usize,
    /// Total draped swath length at the chosen heading, metres.
    pub length_m: f64,
}

/// Normalisation of eq. (1) over a scan.
struct Normalisation {
    count: (f64, f64),
    length: (f64, f64),
}

impl Normalisation {
    fn of(samples: &[HeadingSample]) -> Self {
        let fold = |values: &mut dyn Iterator<Item = f64>| {
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
                (low.min(v), high.max(v))
            })
        };
        Self {
            count: fold(&mut samples.iter().map(|sample| sample.swaths as f64)),
            length: fold(&mut samples.iter().map(|sample| sample.length_m)),
        }
    }

    fn term((low, high): (f64, f64), value: f64) -> f64 {
        if high > low {
            (value - low) / (high - low)
        } else {
            0.0
        }
    }
}

fn score(
    objective: HeadingObjective,
    normalisation: &Normalisation,
    sample: &HeadingSample,
) -> f64 {
    match objective {
        HeadingObjective::Seed {
            count_weight,
            length_weight,
        }
        | HeadingObjective::LeastDose {
            count_weight,
            length_weight,
        } => {
            count_weight * Normalisation::term(normalisation.count, sample.swaths as f64)
                + length_weight * Normalisation::term(normalisation.length, sample.length_m)
        }
        // Count first; the length term (in [0, 1)) only breaks ties.
        HeadingObjective::Swaths => {
            sample.swaths as f64 + 0.5 * Normalisation::term(normalisation.length, sample.length_m)
        }
        HeadingObjective::Length => Normalisation::term(normalisation.length, sample.length_m),
        HeadingObjective::Fixed { .. } | HeadingObjective::Bearing { .. } => 0.0,
    }
}

/// Picks the heading. `evaluate(θ)` gives the swaths and length at θ degrees.
pub fn choose_heading<E>(
    objective: HeadingObjective,
    refine: bool,
    mut evaluate: impl FnMut(f64) -> Result<HeadingSample, E>,
) -> Result<(HeadingChoice, Vec<HeadingSample>), E> {
    if let HeadingObjective::Fixed { heading_deg } = objective {
        let sample = evaluate(heading_deg)?;
        return Ok((
            HeadingChoice {
                heading_deg,
                integer_heading_deg: heading_deg,
                integer_objective: 0.0,
                objective: 0.0,
                swaths: sample.swaths,
                length_m: sample.length_m,
            },
            vec![sample],
        ));
    }
    let samples = (0..180)
        .map(|degree| evaluate(f64::from(degree)))
        .collect::<Result<Vec<_>, _>>()?;
    let normalisation = Normalisation::of(&samples);
    // Strictly lower wins, so ties keep the smaller heading.
    let mut best = (samples[0], score(objective, &normalisation, &samples[0]));
    for sample in &samples[1..] {
        let value = score(objective, &normalisation, sample);
        if value < best.1 {
            best = (*sample, value);
        }
    }
    let integer = best;
    if refine {
        for tenth in (-9..=9).filter(|tenth| *tenth != 0) {
            let heading = (integer.0.heading_deg + f64::from(tenth) / 10.0).rem_euclid(180.0);
            let sample = evaluate(heading)?;
            let value = score(objective, &normalisation, &sample);
            if value < best.1 - 1e-12 {
                best = (sample, value);
            }
        }
    }
    Ok((
        HeadingChoice {
            heading_deg: best.0.heading_deg,
            integer_heading_deg: integer.0.heading_deg,
            integer_objective: integer.1,
            objective: best.1,
            swaths: best.0.swaths,
            length_m: best.0.length_m,
        },
        samples,
    ))
}

/// `dose`'s candidates: `choice` (the heading E picked), then the 1° headings of `samples`
/// whose E is at most `tolerance` above it, best E first (ties: the smaller heading), each at
/// least `DOSE_SEPARATION_DEG` from those before it, at most `most` in all.
pub fn near_best_headings(
    objective: HeadingObjective,
    choice: &HeadingChoice,
    samples: &[HeadingSample],
    tolerance: f64,
    most: usize,
) -> Vec<HeadingChoice> {
    let normalisation = Normalisation::of(samples);
    let mut ranked: Vec<(f64, &HeadingSample)> = samples
        .iter()
        .map(|sample| (score(objective, &normalisation, sample), sample))
        .filter(|(value, _)| *value <= choice.integer_objective + tolerance)
        .collect();
    ranked.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then(a.1.heading_deg.total_cmp(&b.1.heading_deg))
    });
    let apart = |a: f64, b: f64| {
        let difference = (a - b).rem_euclid(180.0);
        difference.min(180.0 - difference) >= DOSE_SEPARATION_DEG
    };
    let mut chosen = vec![choice.clone()];
    for (value, sample) in ranked {
        if chosen.len() >= most {
            break;
        }
        if chosen
            .iter()
            .all(|kept| apart(kept.heading_deg, sample.heading_deg))
        {
            chosen.push(HeadingChoice {
                heading_deg: sample.heading_deg,
                integer_heading_deg: sample.heading_deg,
                integer_objective: value,
                objective: value,
                swaths: sample.swaths,
                length_m: sample.length_m,
            });
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalised_e_with_ties_to_the_smaller_heading() {
        // Swaths fewest at 30..=40; length shortest at 35.
        let evaluate = |heading: f64| -> Result<HeadingSample, ()> {
            Ok(HeadingSample {
                heading_deg: heading,
                swaths: if (30.0..=40.0).contains(&heading) {
                    10
                } else {
                    12
                },
                length_m: 1000.0 + (heading - 35.0).abs(),
            })
        };
        let (choice, samples) =
            choose_heading(HeadingObjective::default(), false, evaluate).unwrap();
        assert_eq!(samples.len(), 180);
        assert_eq!(choice.heading_deg, 35.0);
        assert_eq!(choice.objective, 0.0);
        // Equal E everywhere: the smallest heading.
        let flat = |heading: f64| -> Result<HeadingSample, ()> {
            Ok(HeadingSample {
                heading_deg: heading,
                swaths: 5,
                length_m: 100.0,
            })
        };
        let (choice, _) = choose_heading(HeadingObjective::default(), true, flat).unwrap();
        assert_eq!(choice.heading_deg, 0.0);
    }

    #[test]
    fn refinement_keeps_only_improvements() {
        let evaluate = |heading: f64| -> Result<HeadingSample, ()> {
            Ok(HeadingSample {
                heading_deg: heading,
                swaths: 10,
                length_m: 1000.0 + (heading - 35.3).abs(),
            })
        };
        let (choice, _) = choose_heading(HeadingObjective::Length, true, evaluate).unwrap();
        assert_eq!(choice.integer_heading_deg, 35.0);
        assert!((choice.heading_deg - 35.3).abs() < 1e-9);
        assert!(choice.objective < choice.integer_objective);
    }
}
