//! swarm: domain-free swarm and evolutionary optimizers.
//!
//! Nothing here knows about UAVs, fields or terrain, so a researcher can use it on any
//! objective:
//!
//! ```
//! use swarm::{algorithms::IbaFcs, Bounds, FnProblem, Runner, Termination};
//!
//! let problem = FnProblem::new(Bounds::cube(10, -5.0, 5.0).unwrap(), |x: &[f64]| {
//!     x.iter().map(|v| v * v).sum::<f64>()
//! });
//! let runner = Runner::new(Termination::iterations(100), 42).unwrap();
//! let outcome = runner.run(&mut IbaFcs::default(), &problem, 0);
//! assert!(outcome.best_cost < 1e-6);
//! ```
//!
//! - [`Problem`]: what is minimised, over a solution type it declares (a real vector, a
//!   permutation, a grid route, …); [`BoxProblem`] / [`Bounds`]: the continuous case, a box;
//! - [`Optimizer`]: an algorithm writes only `start` and `step` (one file each in
//!   [`algorithms`], equations in its doc comment), for box problems or for any problem
//!   ([`algorithms::RandomSearch`]);
//! - [`Runner`]: the one loop: termination by iterations, evaluations, target or time;
//!   evaluation counting; convergence history; one seeded stream per run (contract
//!   decision 10, docs/contract.md); parallel runs equal to serial ones;
//! - [`functions`]: seed 000 Table 1, with the official CEC 2005 data;
//! - [`conformance`]: the checks every optimizer passes;
//! - [`readings`]: the open choices of seed 000's algorithms, as named settings;
//! - [`statistics`]: best, worst, mean and deviation of runs, for every table.

#![warn(missing_docs)]

pub mod algorithms;
pub mod conformance;
pub mod functions;
pub mod problem;
pub mod random;
pub mod readings;
pub mod runner;
pub mod statistics;
pub mod termination;

pub use algorithms::Algorithm;
pub use problem::{as_solution, Bounds, BoundsError, BoxProblem, FnProblem, Problem, SolutionOf};
pub use random::{below, run_stream, uniform, RunStream};
pub use readings::Readings;
pub use runner::{
    Continuous, ContinuousOptimizer, Observer, Optimizer, Outcome, Record, Runner, Search,
    StopReason, Termination, TerminationError,
};
