//! Benchmarks users run from the command line (`agripath bench …`).

pub mod farms;
pub mod functions;
