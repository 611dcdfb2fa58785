//! Point-to-point safe 3D tracks over terrain and threat cylinders (seeds 000 and 002, and
//! SPSO's public benchmark): scenarios, cost models as values, encodings, the planners on the
//! swarm engine, our lattice planner, B-spline smoothing and the safety check.
//!
//! Flow: a [`TrackScenario`] and an [`Encoding`] make a [`TrackProblem`] (a box and a cost
//! for the swarm engine); [`planner::plan`] runs a [`Planner`] on it and checks each track
//! with [`safety::check`].

pub mod bspline;
pub mod cost;
pub mod encoding;
pub mod files;
pub mod flown;
pub mod height_map;
pub mod improved_genetic;
pub mod lattice;
pub mod operator;
pub mod picture;
pub mod planner;
pub mod problem;
pub mod random_scenario;
pub mod refine;
pub mod safety;
pub mod scenario;

pub use cost::{CostBreakdown, CostModel};
pub use encoding::Encoding;
pub use planner::{plan, statistics, Planner, RunStatistics, TrackRun, TrackSettings};
pub use problem::TrackProblem;
pub use scenario::{SafetyLimits, Threat, TrackScenario};
