//! The end-to-end suites of the `agripath` program, one module each, linked as one test
//! binary: five suites in one link instead of five (issue 18, build cost). The hostile-input
//! suite (`tests/bad_input.rs`) stays a binary of its own, because it reads the peak memory
//! of its own child processes (`getrusage(RUSAGE_CHILDREN)`), which other suites' children
//! running beside it would raise.

mod common;

mod cli;
mod open_path;
mod operator;
mod spray_once;
mod supply;
