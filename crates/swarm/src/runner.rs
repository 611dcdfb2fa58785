//! The one loop that drives every optimizer.
//!
//! Algorithms only write their `start` and `step`; the Runner owns termination, evaluation
//! counting, the best-so-far, the convergence history and the random stream, so every
//! algorithm is measured the same way (DESIGN.md principle 2).
//!
//! The loop is generic over the problem's solution type ([`Problem::Solution`]): the
//! continuous algorithms, the swath-ordering ant colony, the grid routes' hybrid PSO and the
//! routing local search all run here, under the same budgets, observers and seeding.
//!
//! An evaluation budget is honoured exactly: once it is spent, `Search::evaluate` returns
//! `f64::INFINITY` without calling the problem, every algorithm treats that as "worse", and
//! the Runner stops after the step. No algorithm needs budget code of its own.

use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::problem::{as_solution, BoxProblem, Problem, SolutionOf};
use crate::random::{self, RunStream};
pub use crate::termination::{Termination, TerminationError};

/// An optimizer: it sets up its population in `start` and improves it in `step`.
///
/// Parameters live in the implementing value (`Default` = its paper's settings); the
/// state it keeps between steps is its own. Everything else comes from `Search`.
///
/// `P` is the kind of problem it solves: continuous algorithms implement
/// `Optimizer<Continuous<'p>>` for every `'p` (any [`BoxProblem`]); a permutation search
/// implements `Optimizer<ItsProblem>`; a search that needs only [`Problem`]'s methods can
/// implement `Optimizer<P>` for every `P` ([`crate::algorithms::RandomSearch`]).
pub trait Optimizer<P: Problem + ?Sized>: Send {
    /// The name in tables and reports.
    fn name(&self) -> &'static str;
    /// Builds and evaluates the initial population.
    fn start(&mut self, search: &mut Search<P>);
    /// One iteration (generation).
    fn step(&mut self, search: &mut Search<P>);
}

/// Any continuous problem, as a continuous optimizer sees it.
pub type Continuous<'p> = dyn BoxProblem + 'p;

/// A continuous optimizer: one that runs on every [`BoxProblem`], whatever it borrows.
pub type ContinuousOptimizer<'o> = dyn for<'p> Optimizer<Continuous<'p>> + 'o;

/// What an optimizer sees of a run: the problem, the run's random stream, the budget used
/// so far and the best solution found so far.
pub struct Search<'a, P: Problem + ?Sized> {
    problem: &'a P,
    termination: &'a Termination,
    stream: RunStream,
    started: Instant,
    iteration: usize,
    evaluations: u64,
    best_cost: f64,
    best_solution: SolutionOf<P>,
    converged: bool,
    observer: &'a mut dyn Observer<P::Solution>,
    history: Vec<Record>,
}

impl<'a, P: Problem + ?Sized> Search<'a, P> {
    fn new(
        problem: &'a P,
        termination: &'a Termination,
        stream: RunStream,
        observer: &'a mut dyn Observer<P::Solution>,
    ) -> Self {
        Self {
            problem,
            termination,
            observer,
            history: Vec::new(),
            stream,
            started: Instant::now(),
            iteration: 0,
            evaluations: 0,
            best_cost: f64::INFINITY,
            best_solution: problem.first_solution(),
            converged: false,
        }
    }

    /// The problem being solved (for its own tables: distances, grid cells, …).
    pub fn problem(&self) -> &'a P {
        self.problem
    }

    /// The cost of `solution`, counted; `f64::INFINITY` once the evaluation budget is spent.
    /// NaN costs count as `f64::INFINITY` so that comparisons stay total.
    pub fn evaluate(&mut self, solution: &P::Solution) -> f64 {
        if self
            .termination
            .max_evaluations
            .is_some_and(|budget| self.evaluations >= budget)
        {
            return f64::INFINITY;
        }
        let cost = self.problem.evaluate(solution);
        self.count(solution, cost)
    }

    /// Counts an evaluation of `solution` that cost `cost` (NaN as `f64::INFINITY`), tells
    /// the observer and keeps it when strictly cheapest so far.
    fn count(&mut self, solution: &P::Solution, cost: f64) -> f64 {
        self.evaluations += 1;
        let cost = if cost.is_nan() { f64::INFINITY } else { cost };
        self.observer.evaluated(solution, cost);
        if cost < self.best_cost {
            self.best_cost = cost;
            solution.clone_into(&mut self.best_solution);
        }
        cost
    }

    /// What `evaluate` on each of `solutions` in turn gives, stopping at the first whose cost
    /// `accept` takes: that one's index and cost, or `None`. The solutions are costed a batch
    /// at a time on the machine's cores (rayon's pool; at most `at_once` at a time, what the
    /// problem serves at once: one whose evaluations share a cache keeps one per thread, or
    /// none), then counted in order as `evaluate` counts; costs computed past the accepted one
    /// are dropped uncounted. The run is left where the same calls in series leave it, on any
    /// number of cores: a first-improvement search spends the cores on the candidates it
    /// would try next, not on other work.
    pub fn evaluate_until<S>(
        &mut self,
        solutions: &[S],
        at_once: usize,
        accept: impl Fn(f64) -> bool,
    ) -> Option<(usize, f64)>
    where
        S: std::borrow::Borrow<P::Solution> + Sync,
        P: Sync,
    {
        let width = rayon::current_num_threads().min(at_once).max(1);
        let mut next = 0;
        while next < solutions.len() {
            let left = self.remaining_evaluations().unwrap_or(u64::MAX);
            let batch = (solutions.len() - next)
                .min(width)
                .min(usize::try_from(left).unwrap_or(usize::MAX));
            if batch == 0 {
                // The budget is spent: `evaluate` gives infinity from here on, uncounted.
                return solutions[next..]
                    .iter()
                    .position(|_| accept(f64::INFINITY))
                    .map(|offset| (next + offset, f64::INFINITY));
            }
            let problem = self.problem;
            let costs: Vec<f64> = if batch == 1 {
                vec![problem.evaluate(solutions[next].borrow())]
            } else {
                solutions[next..next + batch]
                    .par_iter()
                    .with_max_len(1)
                    .map(|solution| problem.evaluate(solution.borrow()))
                    .collect()
            };
            for (offset, cost) in costs.into_iter().enumerate() {
                let cost = self.count(solutions[next + offset].borrow(), cost);
                if accept(cost) {
                    return Some((next + offset, cost));
                }
            }
            next += batch;
        }
        None
    }

    /// A solution drawn uniformly from the problem's space, from the run's stream.
    pub fn random_solution(&mut self) -> SolutionOf<P> {
        self.problem.random_solution(&mut self.stream)
    }

    /// The best solution evaluated so far in this run.
    pub fn best_solution(&self) -> &P::Solution {
        as_solution::<P>(&self.best_solution)
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

    /// Costs computed so far in this run.
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

    /// Evaluations left in this run's budget (`None` without an evaluation budget).
    pub fn remaining_evaluations(&self) -> Option<u64> {
        self.termination
            .max_evaluations
            .map(|budget| budget.saturating_sub(self.evaluations))
    }

    /// Work beside this run on the machine's cores (rayon's pool): `work(k, branch)` for
    /// each of `problems` (copies of this run's problem, with caches of their own) on a
    /// search of its own: a stream of its own (this run's, long-jumped k + 1 times; this
    /// run's is not advanced), at most `evaluations` and its even share of the evaluations
    /// left (odd ones to the first branches: the budget is honoured exactly), this run's
    /// deadline; no iteration budget or target, `progress` against its share, and a
    /// `declare_converged` in it is not passed on. Then, in branch order, the evaluations are
    /// added to this run's count and each finite best is offered to this run's best
    /// (strictly cheaper only) and told to the observer: work that stays within its share
    /// leaves the run where the same work in series would, on any number of cores.
    pub fn branch_out<R: Send>(
        &mut self,
        problems: &[&P],
        evaluations: u64,
        work: impl Fn(usize, &mut Search<'_, P>) -> R + Sync,
    ) -> Vec<R>
    where
        P: Sync,
        SolutionOf<P>: Send,
    {
        let count = problems.len().max(1) as u64;
        let shares: Vec<u64> = (0..count)
            .map(|k| match self.remaining_evaluations() {
                Some(left) => evaluations.min(left / count + u64::from(k < left % count)),
                None => evaluations,
            })
            .collect();
        let streams: Vec<RunStream> = (0..problems.len())
            .scan(self.stream.clone(), |stream, _| {
                stream.long_jump();
                Some(stream.clone())
            })
            .collect();
        let (started, time_limit) = (self.started, self.termination.time_limit);
        let branches: Vec<(R, u64, f64, SolutionOf<P>)> = problems
            .par_iter()
            .zip(streams)
            .enumerate()
            .map(|(k, (problem, stream))| {
                // A budget cannot be 0: with nothing to spend, its one evaluation is spent.
                let share = shares[k];
                let mut termination = Termination::evaluations(share.max(1));
                termination.time_limit = time_limit;
                let mut quiet = ();
                let mut branch = Search::new(*problem, &termination, stream, &mut quiet);
                branch.started = started;
                let already = u64::from(share == 0);
                branch.evaluations = already;
                let result = work(k, &mut branch);
                let spent = branch.evaluations - already;
                (result, spent, branch.best_cost, branch.best_solution)
            })
            .collect();
        branches
            .into_iter()
            .map(|(result, spent, best_cost, best_solution)| {
                self.evaluations += spent;
                if spent > 0 && best_cost.is_finite() {
                    let best = as_solution::<P>(&best_solution);
                    self.observer.evaluated(best, best_cost);
                    if best_cost < self.best_cost {
                        self.best_cost = best_cost;
                        best.clone_into(&mut self.best_solution);
                    }
                }
                result
            })
            .collect()
    }

    /// Notes the best cost after an iteration, for the history and the observer.
    fn record(&mut self) {
        let point = Record {
            iteration: self.iteration,
            evaluations: self.evaluations,
            best_cost: self.best_cost,
        };
        self.observer.observe(&point);
        self.history.push(point);
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

/// What continuous optimizers see besides: the box.
impl<P: BoxProblem + ?Sized> Search<'_, P> {
    /// The search box.
    pub fn bounds(&self) -> &crate::Bounds {
        self.problem.bounds()
    }

    /// The number of coordinates.
    pub fn dimension(&self) -> usize {
        self.problem.bounds().dimension()
    }

    /// A uniform point of the search box.
    pub fn random_position(&mut self) -> Vec<f64> {
        self.random_solution()
    }

    /// Moves `x` into the search box (the nearest point).
    pub fn clamp(&self, x: &mut [f64]) {
        self.problem.bounds().clamp(x);
    }

    /// The best point evaluated so far in this run.
    pub fn best_position(&self) -> &[f64] {
        self.best_solution()
    }
}

/// Which limit ended a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// The iteration budget was spent.
    Iterations,
    /// The evaluation budget was spent.
    Evaluations,
    /// The target cost was reached.
    Target,
    /// The time limit passed.
    Time,
    /// The optimizer declared itself converged ([`Search::declare_converged`]).
    Converged,
}

/// One point of the convergence history: the best cost after an iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record {
    /// The iteration just finished (0: the start).
    pub iteration: usize,
    /// Costs computed up to then.
    pub evaluations: u64,
    /// The best cost up to then.
    pub best_cost: f64,
}

/// Watches a run as it goes (progress display, custom logging, conformance checks);
/// `Solution` is the problem's solution type.
pub trait Observer<Solution: ?Sized = [f64]> {
    /// Called after the start and after every iteration.
    fn observe(&mut self, record: &Record);
    /// Called for every solution costed, with its cost (by default, nothing); for work
    /// branched out to other cores ([`Search::branch_out`]), for each branch's best only.
    fn evaluated(&mut self, _solution: &Solution, _cost: f64) {}
}

/// The result of one run; `Solution` is the problem's owned solution (`Vec<f64>` for a box).
#[derive(Debug, Clone)]
pub struct Outcome<Solution = Vec<f64>> {
    /// The optimizer's name.
    pub algorithm: &'static str,
    /// The run number (its random stream).
    pub run: u64,
    /// The best cost found.
    pub best_cost: f64,
    /// The solution of that cost.
    pub best_solution: Solution,
    /// Costs computed.
    pub evaluations: u64,
    /// Iterations made after the start.
    pub iterations: usize,
    /// Wall time of the run.
    pub elapsed: Duration,
    /// The limit that ended it.
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
    /// A runner for `termination` (refused without a budget) and the base `seed`.
    pub fn new(termination: Termination, seed: u64) -> Result<Self, TerminationError> {
        termination.validate()?;
        Ok(Self { termination, seed })
    }

    /// When runs stop.
    pub fn termination(&self) -> &Termination {
        &self.termination
    }

    /// Run number `run` of a continuous optimizer (its own random stream, contract
    /// decision 10, docs/contract.md).
    pub fn run(
        &self,
        optimizer: &mut ContinuousOptimizer,
        problem: &dyn BoxProblem,
        run: u64,
    ) -> Outcome {
        self.run_observed(optimizer, problem, run, &mut ())
    }

    /// `run`, telling `observer` the best cost after every iteration.
    pub fn run_observed(
        &self,
        optimizer: &mut ContinuousOptimizer,
        problem: &dyn BoxProblem,
        run: u64,
        observer: &mut dyn Observer,
    ) -> Outcome {
        self.run_problem(optimizer, problem, run, observer)
    }

    /// Run number `run` of any optimizer on any problem: the one loop.
    pub fn run_problem<P: Problem + ?Sized>(
        &self,
        optimizer: &mut dyn Optimizer<P>,
        problem: &P,
        run: u64,
        observer: &mut dyn Observer<P::Solution>,
    ) -> Outcome<SolutionOf<P>> {
        let mut search = Search::new(
            problem,
            &self.termination,
            random::run_stream(self.seed, run),
            observer,
        );
        optimizer.start(&mut search);
        search.record();
        let stopped_by = loop {
            if let Some(reason) = search.stop_reason() {
                break reason;
            }
            search.iteration += 1;
            let evaluations_before = search.evaluations;
            optimizer.step(&mut search);
            search.record();
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
            best_solution: search.best_solution,
            evaluations: search.evaluations,
            iterations: search.iteration,
            elapsed: search.started.elapsed(),
            stopped_by,
            history: search.history,
        }
    }

    /// Runs `0..runs` in parallel, each with a fresh optimizer from `make`; the outcomes are
    /// in run order and equal, number for number, to running them one after another.
    /// `finished` is called once per run as it completes (for a progress display).
    pub fn run_many<O, Make>(
        &self,
        make: Make,
        problem: &dyn BoxProblem,
        runs: u64,
        finished: &(dyn Fn(&Outcome) + Sync),
    ) -> Vec<Outcome>
    where
        O: for<'p> Optimizer<Continuous<'p>>,
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

impl<Solution: ?Sized> Observer<Solution> for () {
    fn observe(&mut self, _record: &Record) {}
}

impl<'p> Optimizer<Continuous<'p>> for Box<ContinuousOptimizer<'_>> {
    fn name(&self) -> &'static str {
        self.as_ref().name()
    }

    fn start(&mut self, search: &mut Search<Continuous<'p>>) {
        self.as_mut().start(search);
    }

    fn step(&mut self, search: &mut Search<Continuous<'p>>) {
        self.as_mut().step(search);
    }
}
