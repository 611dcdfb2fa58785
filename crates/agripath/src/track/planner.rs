//! The planners by name, and independent seeded runs of one planner on one scenario.
//!
//! Every planner runs on the swarm engine's one loop under the same evaluation budget (the
//! scenario's [`TrackScenario::evaluation_budget`]); runs are independent streams run in
//! parallel, equal number for number to serial runs. Each returned track is checked by
//! [`super::safety::check`].

use std::time::Duration;

use swarm::algorithms::{ParticleSwarm, ParticleSwarmParameters};
use swarm::{Algorithm, ContinuousOptimizer, Record, Runner, Termination};

use super::bspline;
use super::cost::CostBreakdown;
use super::encoding::Encoding;
use super::flown;
use super::improved_genetic::{ImprovedGenetic, ImprovedGeneticParameters};
use super::problem::TrackProblem;
use super::refine::LatticeRefine;
use super::safety::{self, Verdict};
use super::scenario::TrackScenario;
use crate::error::Fault;

/// A track planner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Planner {
    /// An algorithm of the swarm engine on the scenario's encoding.
    Swarm(Algorithm),
    /// SPSO: PSO with its code's settings on the spherical encoding.
    Spso,
    /// Seed 002's improved GA, then cubic B-spline smoothing.
    ImprovedGenetic,
    /// Ours: lattice corridors refined waypoint by waypoint.
    Lattice,
}

impl Planner {
    /// The planner's name on the command line and in file names.
    pub fn key(self) -> &'static str {
        match self {
            Planner::Swarm(algorithm) => algorithm.key(),
            Planner::Spso => "spso",
            Planner::ImprovedGenetic => "improved-ga",
            Planner::Lattice => "lattice",
        }
    }

    /// The planner's name for tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            Planner::Swarm(algorithm) => algorithm.label(),
            Planner::Spso => "SPSO",
            Planner::ImprovedGenetic => "improved GA",
            Planner::Lattice => "lattice+refine (ours)",
        }
    }

    /// The planner's colour in every picture (its place in [`Planner::all`], colour-blind-safe
    /// Okabe-Ito and Tol colours).
    pub fn colour(self) -> &'static str {
        const PALETTE: [&str; 12] = [
            "#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#882255", "#DDCC77", "#999933",
            "#44AA99", "#AA4499", "#000000", "#D55E00",
        ];
        let index = Planner::all()
            .iter()
            .position(|planner| *planner == self)
            .unwrap_or(0);
        PALETTE[index % PALETTE.len()]
    }

    /// Every planner: the swarm engine's algorithms, then SPSO, the improved GA and ours.
    pub fn all() -> Vec<Planner> {
        let mut all: Vec<Planner> = Algorithm::ALL.iter().copied().map(Planner::Swarm).collect();
        all.extend([Planner::Spso, Planner::ImprovedGenetic, Planner::Lattice]);
        all
    }

    /// The planner named `text` (case-insensitive; `ours` is the lattice); errs with the known names.
    pub fn parse(text: &str) -> Result<Planner, String> {
        let wanted = text.trim().to_ascii_lowercase();
        if let Some(planner) = [Planner::Spso, Planner::ImprovedGenetic, Planner::Lattice]
            .into_iter()
            .find(|p| p.key() == wanted)
        {
            return Ok(planner);
        }
        if wanted == "ours" {
            return Ok(Planner::Lattice);
        }
        wanted
            .parse::<Algorithm>()
            .map(Planner::Swarm)
            .map_err(|_| {
                let names: Vec<&str> = Planner::all().iter().map(|p| p.key()).collect();
                format!("unknown planner '{text}' (known: {})", names.join(", "))
            })
    }

    /// The encoding the planner searches, given the one asked for (swarm algorithms only).
    pub fn encoding(self, scenario: &TrackScenario, asked: Option<Encoding>) -> Encoding {
        match self {
            Planner::Spso => Encoding::Spherical,
            Planner::ImprovedGenetic | Planner::Lattice => Encoding::Cartesian,
            Planner::Swarm(_) => asked.unwrap_or(scenario.default_encoding()),
        }
    }
}

/// What to run.
#[derive(Debug, Clone)]
pub struct TrackSettings {
    /// The planner to run.
    pub planner: Planner,
    /// For the swarm algorithms; `None`: the scenario's paper's encoding.
    pub encoding: Option<Encoding>,
    /// Number of independent runs.
    pub runs: u64,
    /// Seed of the runs: run k draws from stream k of this seed.
    pub seed: u64,
    /// `None`: the scenario's budget.
    pub evaluations: Option<u64>,
}

/// A track smoothed by B-spline, with its own cost and check.
#[derive(Debug, Clone)]
pub struct Smoothed {
    /// The smoothed track: start, waypoints and goal, altitudes above sea level.
    pub points: Vec<[f64; 3]>,
    /// Each planned leg was split in this many before smoothing (1: the paper's spline).
    pub splits: usize,
    /// The smoothed track's cost.
    pub cost: CostBreakdown,
    /// The smoothed track's safety check.
    pub verdict: Verdict,
}

/// One run's result.
#[derive(Debug, Clone)]
pub struct TrackRun {
    /// Number of the run, from 0.
    pub run: u64,
    /// Start, waypoints and goal, altitudes above sea level.
    pub points: Vec<[f64; 3]>,
    /// The planned track's cost.
    pub cost: CostBreakdown,
    /// The planned track's safety check.
    pub verdict: Verdict,
    /// Cost evaluations spent.
    pub evaluations: u64,
    /// Wall time of the run.
    pub elapsed: Duration,
    /// The best cost after each iteration.
    pub history: Vec<Record>,
    /// The improved GA's smoothed track (its cost is the run's `final_cost`).
    pub smoothed: Option<Smoothed>,
}

impl TrackRun {
    /// The cost of the track the planner hands over: the smoothed one when smoothing kept it
    /// safe, else the planned one.
    pub fn final_cost(&self) -> f64 {
        match &self.smoothed {
            Some(smoothed) if smoothed.verdict.is_safe() => smoothed.cost.total,
            _ => self.cost.total,
        }
    }

    /// The points of the track the planner hands over: the smoothed one when smoothing kept it safe, else the planned one.
    pub fn final_points(&self) -> &[[f64; 3]] {
        match &self.smoothed {
            Some(smoothed) if smoothed.verdict.is_safe() => &smoothed.points,
            _ => &self.points,
        }
    }

    /// Whether the track the planner hands over is safe.
    pub fn is_safe(&self) -> bool {
        match &self.smoothed {
            Some(smoothed) if smoothed.verdict.is_safe() => true,
            _ => self.verdict.is_safe(),
        }
    }
}

impl TrackScenario {
    /// Evaluations every planner may spend: population × (iterations + 1), and for seed
    /// 002 population × (1 + iterations × 3), what its improved GA spends with three
    /// mutation tries per child (decision 0011).
    pub fn evaluation_budget(&self) -> u64 {
        let (population, iterations) = (self.population as u64, self.iterations as u64);
        match self.cost {
            super::cost::CostModel::Seed002(_) => population * (1 + 3 * iterations),
            _ => population * (iterations + 1),
        }
    }

    /// The encoding of the scenario's paper: cylindrical for seed 000, spherical for SPSO,
    /// Cartesian for seed 002.
    pub fn default_encoding(&self) -> Encoding {
        match self.cost {
            super::cost::CostModel::Seed000(_) => Encoding::Cylindrical,
            super::cost::CostModel::Spso(_) => Encoding::Spherical,
            super::cost::CostModel::Seed002(_) => Encoding::Cartesian,
        }
    }
}

/// Runs `settings.runs` independent runs; `finished` is called as each ends.
pub fn plan(
    scenario: &TrackScenario,
    settings: &TrackSettings,
    finished: &(dyn Fn() + Sync),
) -> Result<Vec<TrackRun>, Fault> {
    if settings.runs == 0 {
        return Err(Fault::InvalidValue {
            what: "--runs".into(),
            value: "0".into(),
            why: "at least one run".into(),
        });
    }
    let budget = settings
        .evaluations
        .unwrap_or_else(|| scenario.evaluation_budget());
    let runner = Runner::new(Termination::evaluations(budget), settings.seed).map_err(|error| {
        Fault::InvalidValue {
            what: "evaluations".into(),
            value: budget.to_string(),
            why: error.to_string(),
        }
    })?;
    let encoding = settings.planner.encoding(scenario, settings.encoding);
    let genetic = ImprovedGeneticParameters {
        population: scenario.population,
        initial_length: scenario.free_waypoints,
        max_length: 2 * scenario.free_waypoints,
        ..Default::default()
    };
    let problem = match settings.planner {
        Planner::ImprovedGenetic => {
            TrackProblem::with_waypoints(scenario, encoding, genetic.max_length)
        }
        _ => TrackProblem::new(scenario, encoding),
    };
    let population = scenario.population;
    let make = || -> Box<ContinuousOptimizer<'_>> {
        match settings.planner {
            Planner::Swarm(algorithm) => algorithm.build(population),
            Planner::Spso => Box::new(ParticleSwarm::new(ParticleSwarmParameters::spso(
                population,
            ))),
            Planner::ImprovedGenetic => Box::new(ImprovedGenetic::new(scenario, genetic.clone())),
            Planner::Lattice => Box::new(LatticeRefine::new(scenario)),
        }
    };
    let outcomes = runner.run_many(make, &problem, settings.runs, &|_| finished());
    Ok(outcomes
        .into_iter()
        .map(|outcome| {
            let mut points = problem.track(&outcome.best_solution);
            if settings.planner == Planner::ImprovedGenetic {
                // Drop the padding: waypoints parked at the goal.
                let goal = scenario.sea_level(scenario.cruise_goal);
                points.dedup_by(|a, b| a == b && *a == goal);
            }
            let cost = scenario.evaluate(&points);
            // The track as its mission file flies it (`flown`), not the planner's polyline.
            let verdict = safety::check(scenario, &flown::as_flown(scenario, &points));
            let smoothed = (settings.planner == Planner::ImprovedGenetic)
                .then(|| smooth_safely(scenario, &points));
            TrackRun {
                run: outcome.run,
                points,
                cost,
                verdict,
                evaluations: outcome.evaluations,
                elapsed: outcome.elapsed,
                history: outcome.history,
                smoothed,
            }
        })
        .collect())
}

/// Seed 002's smoothing, re-checked. The spline through the planned points can cut under a
/// hill the polyline clears, or overshoot the space's ceiling at a corner. Then (ours, decision
/// 0011) the spline is drawn through the polyline with each leg split in 2, 4 and 8, which hugs
/// it ever closer, until the smoothed track is safe; altitudes above sea level are held within
/// the space's floor and ceiling. The last try is returned, safe or not.
fn smooth_safely(scenario: &TrackScenario, track: &[[f64; 3]]) -> Smoothed {
    // The cruise is smoothed; the vertical legs stay as they are.
    let (points, _) = scenario.cruise_of(track);
    let mut tried = None;
    for splits in [1usize, 2, 4, 8] {
        let mut dense = Vec::with_capacity(points.len() * splits);
        for pair in points.windows(2) {
            for part in 0..splits {
                let t = part as f64 / splits as f64;
                dense.push(
                    [0, 1, 2].map(|axis| pair[0][axis] + t * (pair[1][axis] - pair[0][axis])),
                );
            }
        }
        dense.extend(points.last());
        let mut curve = bspline::smooth(&dense);
        if scenario.altitude_reference == super::scenario::AltitudeReference::SeaLevel {
            let (low, high) = scenario.altitude_bounds;
            for point in &mut curve {
                point[2] = point[2].clamp(low, high);
            }
        }
        let curve = scenario.whole_track(&curve);
        let smoothed = Smoothed {
            cost: scenario.evaluate(&curve),
            verdict: safety::check(scenario, &flown::as_flown(scenario, &curve)),
            points: curve,
            splits,
        };
        if smoothed.verdict.is_safe() {
            return smoothed;
        }
        tried = Some(smoothed);
    }
    tried.expect("at least one try")
}

/// Best, worst, mean and standard deviation of the runs' final costs, and how many are safe.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunStatistics {
    /// Lowest final cost.
    pub best: f64,
    /// Highest final cost.
    pub worst: f64,
    /// Mean final cost.
    pub mean: f64,
    /// Sample standard deviation of the final costs.
    pub standard_deviation: f64,
    /// Runs whose handed-over track is safe.
    pub safe_runs: usize,
    /// Number of runs.
    pub runs: usize,
    /// Mean wall time per run, seconds.
    pub mean_seconds: f64,
}

impl RunStatistics {
    /// "best | worst | mean | std | safe/runs | s/run" for Markdown tables.
    pub fn cells(&self, decimals: usize) -> String {
        format!(
            "{:.decimals$} | {:.decimals$} | {:.decimals$} | {:.decimals$} | {}/{} | {:.2}",
            self.best,
            self.worst,
            self.mean,
            self.standard_deviation,
            self.safe_runs,
            self.runs,
            self.mean_seconds
        )
    }
}

/// The statistics of `runs` (final costs, as [`TrackRun::final_cost`] gives them).
pub fn statistics(runs: &[TrackRun]) -> RunStatistics {
    let costs: Vec<f64> = runs.iter().map(TrackRun::final_cost).collect();
    let spread = swarm::statistics::Spread::of(&costs);
    let count = costs.len().max(1) as f64;
    RunStatistics {
        best: spread.best,
        worst: spread.worst,
        mean: spread.mean,
        standard_deviation: spread.standard_deviation,
        safe_runs: runs.iter().filter(|run| run.is_safe()).count(),
        runs: runs.len(),
        mean_seconds: runs
            .iter()
            .map(|run| run.elapsed.as_secs_f64())
            .sum::<f64>()
            / count,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenarios() -> Vec<TrackScenario> {
        vec![
            TrackScenario::seed000("I").unwrap(),
            TrackScenario::seed000("II").unwrap(),
            TrackScenario::seed000("III").unwrap(),
            TrackScenario::seed002().unwrap(),
            TrackScenario::spso().unwrap(),
        ]
    }

    fn settings(planner: Planner, evaluations: u64) -> TrackSettings {
        TrackSettings {
            planner,
            encoding: None,
            runs: 2,
            seed: 7,
            evaluations: Some(evaluations),
        }
    }

    #[test]
    fn every_returned_track_carries_its_own_safety_check_and_ours_is_safe_everywhere() {
        for scenario in scenarios() {
            for planner in [
                Planner::Lattice,
                Planner::Swarm(Algorithm::IBA_FCS),
                Planner::ImprovedGenetic,
            ] {
                let runs = plan(&scenario, &settings(planner, 4000), &|| {}).unwrap();
                for run in &runs {
                    assert_eq!(
                        run.verdict,
                        safety::check(&scenario, &flown::as_flown(&scenario, &run.points))
                    );
                    assert_eq!(
                        run.points.first(),
                        Some(&scenario.sea_level(scenario.start))
                    );
                    assert_eq!(run.points.last(), Some(&scenario.sea_level(scenario.goal)));
                    if planner == Planner::Lattice {
                        assert!(
                            run.is_safe(),
                            "{}: {:?}",
                            scenario.name,
                            run.verdict.violations
                        );
                    }
                    if let Some(smoothed) = &run.smoothed {
                        assert_eq!(
                            smoothed.verdict,
                            safety::check(&scenario, &flown::as_flown(&scenario, &smoothed.points))
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn runs_repeat_with_their_seed_and_differ_between_runs() {
        let scenario = TrackScenario::seed000("I").unwrap();
        let first = plan(
            &scenario,
            &settings(Planner::Swarm(Algorithm::BAT), 3000),
            &|| {},
        )
        .unwrap();
        let again = plan(
            &scenario,
            &settings(Planner::Swarm(Algorithm::BAT), 3000),
            &|| {},
        )
        .unwrap();
        assert_eq!(first[0].points, again[0].points);
        assert_eq!(first[1].cost, again[1].cost);
        assert_ne!(first[0].points, first[1].points);
    }

    #[test]
    fn planners_parse_by_key_and_reject_unknown_names() {
        for planner in Planner::all() {
            assert_eq!(Planner::parse(planner.key()), Ok(planner));
        }
        assert_eq!(Planner::parse("ours"), Ok(Planner::Lattice));
        assert!(Planner::parse("dijkstra")
            .unwrap_err()
            .contains("unknown planner"));
    }
}
