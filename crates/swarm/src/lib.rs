//! swarm: domain-free swarm and evolutionary optimizers.
//!
//! Nothing here knows about UAVs, fields or terrain, so a researcher can use it on any
//! objective. This crate grows with the swarm-engine issue: the `Problem`/`Optimizer` traits,
//! the one `Runner` loop, and one file per algorithm. What is here now is the randomness
//! every stochastic stage of agripath shares (MISSION.md decision 10).

pub mod random;

pub use random::{below, run_stream, uniform, RunStream};
