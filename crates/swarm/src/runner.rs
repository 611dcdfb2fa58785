//! The one loop that drives every optimizer.
//!
//! Algorithms only write their `start` and `step`; the Runner owns termination, evaluation
//! counting, the best-so-far, the convergence history and the random stream, so every
//! algorithm is measured the same way (DESIGN.md principle 2).
//!
//! An evaluation budget is honoured exactly: once it is spent, `Search::evaluate` returns
//! `f64::INFINITY` without calling the problem, every algorithm treats that as "worse", and
//! the Runner stops after the step. No algorithm needs budget code of its own.

use std::time::{Duration, Instant};

use rayon::prelude::*;
use thiserror::Error;

use crate::problem::Problem;
use crate::random::{self, RunStream};

/// When a run stops: at whichever configured limit comes first. At least one budget
/// (iterations, evaluations or time) is required; a target alone might never be reached.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Termination {
    pub max_iterations: Option<usize>,
    pub max_evaluations: Option<u64>,
    /// Stop as soon as the best cost is at or below this value.
    pub target_cost: Option<f64>,
    /// Wall-clock limit. Results then depend on the machine: not reproducible from the seed.
    pub time_limit: Option<Duration>,
}

/// Why a termination was refused.
#[derive(Debug, Error, PartialEq)]
pub enum TerminationError {
    #[error("a run needs a budget: iterations, evaluations or a time limit")]
    NoBudget,
    #[error("a budget of zero iterations or evaluations runs nothing")]
    ZeroBudget,
}

impl Termination {
    /// Stop after `iterations` steps.
    pub fn iterations(iterations: usize) -> Self {
        Self {
            max_iterations: Some(iterations),
            ..Self::default()
        }
    }

    /// Stop once `evaluations` costs have been computed.
    pub fn evaluations(evaluations: u64) -> Self {
        Self {
            max_evaluations: Some(evaluations),
            ..Self::default()
        }
    }

    /// Also stop at `evaluations` (whichever limit comes first).
    pub fn and_evaluations(mut self, evaluations: u64) -> Self {
        self.max_evaluations = Some(evaluations);
        self
    }

    /// Also stop when the best cost reaches `target`.
    pub fn and_target(mut self, target: f64) -> Self {
        self.target_cost = Some(target);
        self
    }

    pub fn validate(&self) -> Result<(), TerminationError> {
        if self.max_iterations.is_none()
            && self.max_evaluations.is_none()
            && self.time_limit.is_none()
        {
            return Err(TerminationError::NoBudget);
        }
        if self.max_iterations == Some(0) || self.max_evaluations == Some(0) {
            return Err(TerminationError::ZeroBudget);
        }
        Ok(())
    }
}

/// An optimizer: it sets up its population in `start` and improves it in `step`.
///
/// Parameters live in the implementing value (`Default` = its paper's settings); the
/// state it keeps between steps is its own. Everything else comes from `Search`.
pub trait Optimizer: Send {
    fn name(&self) -> &'static str;
    /// Builds and evaluates the initial population.
    fn start(&mut self, search: &mut Search);
    /// One iteration (generation).
    fn step(&mut self, search: &mut Search);
}

/// What an optimizer sees of a run: the problem, the run's random stream, the budget used
/// so far and the best point found so far.
pub struct Search<'a> {
    problem: &'a dyn Problem,
    termination: &'a Termination,
    stream: RunStream,
    started: Instant,
    iteration: usize,
    evaluations: u64,
    best_cost: f64,
    best_position: Vec<f64>,
    converged: bool,
}

impl<'a> Search<'a> {
    fn new(problem: &'a dyn Problem, termination: &'a Termination, stream: RunStream) -> Self {
        Self {
            problem,
            termination,
            stream,
            started: Instant::now(),
            iteration: 0,
            evaluations: 0,
            best_cost: f64::INFINITY,
            best_position: problem.bounds().lower().to_vec(),
            converged: false,
        }
    }

    pub fn bounds(&self) -> &crate::Bounds {
        self.problem.bounds()
    }

    pub fn dimension(&self) -> usize {
        self.problem.bounds().dimension()
    }

    /// The cost of `x`, counted; `f64::INFINITY` once the evaluation budget is spent.
    /// NaN costs count as `f64::INFINITY` so that comparisons stay total.
    pub fn evaluate(&mut self, x: &[f64]) -> f64 {
        if self
            .termination
            .max_evaluations
            .is_some_and(|budget| self.evaluations >= budget)
        {
            return f64::INFINITY;
        }
        self.evaluations += 1;
        let cost = self.problem.evaluate(x);
        let cost = if cost.is_nan() { f64::INFINITY } else { cost };
        if cost < self.best_cost {
            self.best_cost = cost;
            self.best_position.clear();
            self.best_position.extend_from_slice(x);
        }
        cost
    }

    /// The current iteration: 0 during `start`, then 1, 2, …
    pub fn iteration(&self) -> usize {
        self.iteration
    }

    /// Ends the run after this step: the optimizer knows it can gain nothing more (a local
    /// search whose every step size has shrunk away, say). The run's outcome says so.
    pub fn declare_converged(&mut self) {
        self.converged = true;
    }

    pub fn evaluations(&self) -> u64 {
        self.evaluations
    }

    /// How much of the budget is used, in [0, 1]: the largest of iteration / max
    /// iterations, evaluations / max evaluations and elapsed / time limit. Algorithms use
    /// it wherever their paper writes t / t_max, so they behave the same under any budget.
    pub fn progress(&self) -> f64 {
        let mut used: f64 = 0.0;
        if let Some(iterations) = self.termination.max_iterations {
            used = used.max(self.iteration as f64 / iterations as f64);
        }
        if let Some(evaluations) = self.termination.max_evaluations {
            used = used.max(self.evaluations as f64 / evaluations as f64);
        }
        if let Some(limit) = self.termination.time_limit {
            used = used.max(self.started.elapsed().as_secs_f64() / limit.as_secs_f64());
        }
        used.min(1.0)
    }

    /// The best cost evaluated so far in this run.
    pub fn best_cost(&self) -> f64 {
        self.best_cost
    }

    pub fn best_position(&self) -> &[f64] {
        &self.best_position
    }

    /// The run's random stream, for draws not covered by the helpers below.
    pub fn stream(&mut self) -> &mut RunStream {
        &mut self.stream
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        random::uniform(&mut self.stream)
    }

    /// Uniform in [low, high).
    pub fn uniform_in(&mut self, low: f64, high: f64) -> f64 {
        random::uniform_in(&mut self.stream, low, high)
    }

    /// Standard normal.
    pub fn normal(&mut self) -> f64 {
        random::normal(&mut self.stream)
    }

    /// Uniform in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        random::below(&mut self.stream, n)
    }

    /// A uniform point of the search box.
    pub fn random_position(&mut self) -> Vec<f64> {
        let bounds = self.problem.bounds();
        (0..bounds.dimension())
            .map(|d| random::uniform_in(&mut self.stream, bounds.lower()[d], bounds.upper()[d]))
            .collect()
    }

    /// Moves `x` into the search box (the nearest point).
    pub fn clamp(&self, x: &mut [f64]) {
        self.problem.bounds().clamp(x);
    }

    fn stop_reason(&self) -> Option<StopReason> {
        if self.converged {
            return Some(StopReason::Converged);
        }
        let termination = self.termination;
        if termination
            .target_cost
            .is_some_and(|target| self.best_cost <= target)
        {
            return Some(StopReason::Target);
        }
        if termination
            .max_evaluations
            .is_some_and(|budget| self.evaluations >= budget)
        {
            return Some(StopReason::Evaluations);
        }
        if termination
            .max_iterations
            .is_some_and(|budget| self.iteration >= budget)
        {
            return Some(StopReason::Iterations);
        }
        if termination
            .time_limit
            .is_some_and(|limit| self.started.elapsed() >= limit)
        {
            return Some(StopReason::Time);
        }
        None
    }
}

/// Which limit ended a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    Iterations,
    Evaluations,
    Target,
    Time,
    /// The optimizer declared itself converged ([`Search::declare_converged`]).
    Converged,
}

/// One point of the convergence history: the best cost after an iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record {
    pub iteration: usize,
    pub evaluations: u64,
    pub best_cost: f64,
}

/// Watches a run as it goes (progress display, custom logging).
pub trait Observer {
    fn observe(&mut self, record: &Record);
}

/// The result of one run.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub algorithm: &'static str,
    pub run: u64,
    pub best_cost: f64,
    pub best_position: Vec<f64>,
    pub evaluations: u64,
    pub iterations: usize,
    pub elapsed: Duration,
    pub stopped_by: StopReason,
    /// The best cost after the start (iteration 0) and after every iteration.
    pub history: Vec<Record>,
}

/// Runs optimizers under one termination rule and one seed.
#[derive(Debug, Clone)]
pub struct Runner {
    termination: Termination,
    seed: u64,
}

impl Runner {
    pub fn new(termination: Termination, seed: u64) -> Result<Self, TerminationError> {
        termination.validate()?;
        Ok(Self { termination, seed })
    }

    pub fn termination(&self) -> &Termination {
        &self.termination
    }

    /// Run number `run` (its own random stream, MISSION.md decision 10).
    pub fn run(&self, optimizer: &mut dyn Optimizer, problem: &dyn Problem, run: u64) -> Outcome {
        self.run_observed(optimizer, problem, run, &mut ())
    }

    /// `run`, telling `observer` the best cost after every iteration.
    pub fn run_observed(
        &self,
        optimizer: &mut dyn Optimizer,
        problem: &dyn Problem,
        run: u64,
        observer: &mut dyn Observer,
    ) -> Outcome {
        let mut search = Search::new(
            problem,
            &self.termination,
            random::run_stream(self.seed, run),
        );
        let mut history = Vec::new();
        let mut record = |search: &Search| {
            let point = Record {
                iteration: search.iteration,
                evaluations: search.evaluations,
                best_cost: search.best_cost,
            };
            observer.observe(&point);
            history.push(point);
        };
        optimizer.start(&mut search);
        record(&search);
        let stopped_by = loop {
            if let Some(reason) = search.stop_reason() {
                break reason;
            }
            search.iteration += 1;
            let evaluations_before = search.evaluations;
            optimizer.step(&mut search);
            record(&search);
            if search.converged {
                break StopReason::Converged;
            }
            let only_evaluations_stop =
                self.termination.max_iterations.is_none() && self.termination.time_limit.is_none();
            if search.evaluations == evaluations_before && only_evaluations_stop {
                // A step that evaluates nothing would never reach the evaluation budget.
                break StopReason::Evaluations;
            }
        };
        Outcome {
            algorithm: optimizer.name(),
            run,
            best_cost: search.best_cost,
            best_position: search.best_position,
            evaluations: search.evaluations,
            iterations: search.iteration,
            elapsed: search.started.elapsed(),
            stopped_by,
            history,
        }
    }

    /// Runs `0..runs` in parallel, each with a fresh optimizer from `make`; the outcomes are
    /// in run order and equal, number for number, to running them one after another.
    /// `finished` is called once per run as it completes (for a progress display).
    pub fn run_many<O, Make>(
        &self,
        make: Make,
        problem: &dyn Problem,
        runs: u64,
        finished: &(dyn Fn(&Outcome) + Sync),
    ) -> Vec<Outcome>
    where
        O: Optimizer,
        Make: Fn() -> O + Sync,
    {
        (0..runs)
            .into_par_iter()
            .map(|run| {
                let mut optimizer = make();
                let outcome = self.run(&mut optimizer, problem, run);
                finished(&outcome);
                outcome
            })
            .collect()
    }
}

impl Observer for () {
    fn observe(&mut self, _record: &Record) {}
}

impl Optimizer for Box<dyn Optimizer + '_> {
    fn name(&self) -> &'static str {
        self.as_ref().name()
    }

    fn start(&mut self, search: &mut Search) {
        self.as_mut().start(search);
    }

    fn step(&mut self, search: &mut Search) {
        self.as_mut().step(search);
    }
}
