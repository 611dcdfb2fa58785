//! A point-to-point track as asked for: the scenario file, its task, the planners by name,
//! runs, encoding, budget and safety limits, checked into a [`TrackJob`] to run.

use std::path::{Path, PathBuf};

use super::{bad_value, Failure, Outcome};
use crate::track::files::PlannerRuns;
use crate::track::{plan, Encoding, Planner, SafetyLimits, TrackScenario, TrackSettings};
use crate::InputError;

/// What `agripath track` is asked, as given.
/// With the `cli` feature, also the command line's grammar of `track`.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct TrackRequest {
    /// Scenario file: JSON of seed 000, seed 002 or SPSO, or an operator TOML.
    #[cfg_attr(feature = "cli", arg(value_name = "SCENARIO"))]
    pub scenario_path: PathBuf,
    /// Seed 000's task (I, II or III, or a task name of the file).
    #[cfg_attr(feature = "cli", arg(long))]
    pub task: Option<String>,
    /// Planners, comma-separated: lattice (ours), iba-fcs, ba, ilssiwba, pso, spso, ga,
    /// aco-r, gsa, lshade, improved-ga.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "algorithm",
            value_name = "ALGORITHM",
            default_value = "lattice"
        )
    )]
    pub algorithms: String,
    /// Independent runs per planner (default: the scenario's `algorithms.runs`, else 5).
    #[cfg_attr(feature = "cli", arg(long))]
    pub runs: Option<u64>,
    /// Seed of the random streams.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub seed: u64,
    /// Encoding for the swarm algorithms: cartesian, cylindrical or spherical (default:
    /// the scenario paper's).
    #[cfg_attr(feature = "cli", arg(long))]
    pub encoding: Option<String>,
    /// Evaluations per run (default: the scenario paper's population × iterations).
    #[cfg_attr(feature = "cli", arg(long))]
    pub evaluations: Option<u64>,
    /// Clearance above the terrain and distance from threats a safe track keeps.
    #[cfg_attr(feature = "cli", command(flatten))]
    pub limits: SafetyLimits,
}

/// A checked track request: the scenario read, the planners and the runs to do.
pub struct TrackJob {
    /// The scenario, with the request's safety limits.
    pub scenario: TrackScenario,
    /// Planners in the order asked.
    pub planners: Vec<Planner>,
    /// The encoding asked for, if any.
    pub encoding: Option<Encoding>,
    /// Runs per planner.
    pub runs: u64,
    /// Seed of the random streams.
    pub seed: u64,
    /// Evaluations per run, if not the paper's.
    pub evaluations: Option<u64>,
    source: PathBuf,
}

/// Runs per planner or table that a request may ask for.
const RUNS: std::ops::RangeInclusive<u64> = 1..=1000;

/// Refuses a number of runs outside 1..=1000.
pub fn check_runs(runs: u64) -> Result<u64, InputError> {
    if RUNS.contains(&runs) {
        Ok(runs)
    } else {
        Err(bad_value("--runs", runs.to_string(), "must be 1..=1000"))
    }
}

impl TrackRequest {
    /// Checks the options (planners, encoding, budget) and reads the scenario.
    pub fn prepare(&self) -> Result<TrackJob, InputError> {
        let names: Vec<&str> = self.algorithms.split(',').collect();
        let planners = super::named_list("--algorithm", &names, Planner::parse)?;
        let encoding = match self.encoding.as_deref() {
            None => None,
            Some(text) => Some(Encoding::parse(text).ok_or_else(|| {
                bad_value(
                    "--encoding",
                    text,
                    "expected cartesian, cylindrical or spherical",
                )
            })?),
        };
        // The encoding is the swarm algorithms' choice; the others fly their own.
        if let Some(text) = &self.encoding {
            if !planners
                .iter()
                .any(|planner| matches!(planner, Planner::Swarm(_)))
            {
                return Err(bad_value(
                    "--encoding",
                    text.as_str(),
                    format!(
                        "none of the planners asked ({}) takes an encoding: lattice and improved-ga fly Cartesian waypoints, spso spherical",
                        self.algorithms
                    ),
                ));
            }
        }
        if self.evaluations == Some(0) {
            return Err(bad_value("--evaluations", "0", "must be at least 1"));
        }
        self.limits
            .check()
            .map_err(|fault| InputError::new("arguments", fault))?;
        let path = &self.scenario_path;
        let scenario = TrackScenario::read(path, self.task.as_deref())?
            .with_limits(self.limits)
            .map_err(|fault| InputError::new(path, fault))?;
        let runs = check_runs(self.runs.or(scenario.paper_runs).unwrap_or(5))?;
        Ok(TrackJob {
            scenario,
            planners,
            encoding,
            runs,
            seed: self.seed,
            evaluations: self.evaluations,
            source: path.clone(),
        })
    }
}

impl TrackJob {
    /// Runs in all, for a progress bar.
    pub fn total_runs(&self) -> u64 {
        self.runs * self.planners.len() as u64
    }

    /// Every planner's runs, in order; `tick` after each run.
    pub fn run(&self, tick: &(dyn Fn() + Sync)) -> Result<Vec<PlannerRuns>, InputError> {
        let mut results = Vec::new();
        for &planner in &self.planners {
            let settings = TrackSettings {
                planner,
                encoding: self.encoding,
                runs: self.runs,
                seed: self.seed,
                evaluations: self.evaluations,
            };
            let runs = plan(&self.scenario, &settings, tick)
                .map_err(|fault| InputError::new(Path::new(&self.source), fault))?;
            results.push(PlannerRuns {
                planner,
                encoding: planner.encoding(&self.scenario, self.encoding),
                runs,
            });
        }
        Ok(results)
    }

    /// The outcome of `agripath track` for `results`: the folder (a planner's `.waypoints`
    /// only when its track is safe, unless `allow_unsafe`), the table and why tracks are
    /// unsafe; unsafe when no planner's track is safe.
    pub fn outcome(&self, results: &[PlannerRuns], allow_unsafe: bool) -> Result<Outcome, Failure> {
        use crate::track::files;
        let files = files::files(&self.scenario, results, self.seed, allow_unsafe)
            .map_err(Failure::Output)?;
        let mut report = files::table(&self.scenario, results);
        // Local metres have no place on Earth: say where the files put them (decision 0028).
        if let crate::track::scenario::Georeference::Local { lon, lat } = self.scenario.georeference
        {
            let given = if (lon, lat) == crate::mission::flight::DEFAULT_LOCAL_ORIGIN {
                "the default origin, near Harbin, China; `origin = [lon, lat]` in an operator's TOML places them"
            } else {
                "the scenario's origin"
            };
            report += &format!(
                "placed: local (0, 0) at lon {lon:.6}, lat {lat:.6} in the .waypoints ({given})\n"
            );
        }
        let reasons: Vec<String> = results
            .iter()
            .filter_map(PlannerRuns::unsafe_reason)
            .collect();
        for reason in &reasons {
            report += reason;
            report += "\n";
        }
        let names: Vec<&str> = files.iter().map(|(name, _)| name.as_str()).collect();
        let contents = names.join(", ");
        let mut outcome = Outcome::with_folder(String::new(), files, &contents);
        if let Some(folder) = outcome.folder.as_mut() {
            folder.report = report;
        }
        if reasons.len() >= results.len() {
            if allow_unsafe {
                outcome.warning = Some(
                    "warning: the .waypoints of unsafe tracks were written (--allow-unsafe)".into(),
                );
            } else {
                outcome.failures = reasons;
            }
        }
        Ok(outcome)
    }
}
