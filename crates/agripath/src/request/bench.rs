//! A function bench as asked for: seed 000's Table 2 settings with the dimension, population,
//! iterations, runs and seed given, and the algorithms and functions named.

use super::{named_list, Outcome};
use crate::bench::functions::{FunctionBench, FunctionTable};
use crate::InputError;

/// The options of `agripath bench functions`, as given.
/// With the `cli` feature, also the command line's grammar of `bench functions`.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct FunctionBenchOptions {
    /// Dimension of every function.
    #[cfg_attr(
        feature = "cli",
        arg(long = "dim", value_name = "DIM", default_value_t = 50)
    )]
    pub dimension: usize,
    /// Population (agents per iteration).
    #[cfg_attr(
        feature = "cli",
        arg(long = "pop", value_name = "POP", default_value_t = 500)
    )]
    pub population: usize,
    /// Iterations; every algorithm gets pop × (iters + 1) evaluations.
    #[cfg_attr(
        feature = "cli",
        arg(long = "iters", value_name = "ITERS", default_value_t = 300)
    )]
    pub iterations: usize,
    /// Independent runs per algorithm and function.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 50))]
    pub runs: u64,
    /// Algorithms, comma-separated: pso, ga, ba, ilssiwba, iba-fcs, gsa, aco-r, lshade, random
    /// (uniform random search, a baseline; default: the five of seed 000).
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ','))]
    pub algorithms: Vec<String>,
    /// Functions, comma-separated: f1 … f9 (default: all nine).
    #[cfg_attr(feature = "cli", arg(long, value_delimiter = ','))]
    pub functions: Vec<String>,
    /// Seed of the random streams.
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 1))]
    pub seed: u64,
    /// Also print and write the mean wall-clock time of a run per cell and the bench's wall
    /// time (Table 2's time row); these change from run to run, the rest repeats byte for byte.
    #[cfg_attr(feature = "cli", arg(long))]
    pub times: bool,
}

impl FunctionBenchOptions {
    /// The bench to run, its algorithms and functions found by name and its settings checked.
    pub fn settings(&self) -> Result<FunctionBench, InputError> {
        let mut settings = FunctionBench::table_2();
        settings.with_times = self.times;
        (
            settings.dimension,
            settings.population,
            settings.iterations,
            settings.runs,
            settings.seed,
        ) = (
            self.dimension,
            self.population,
            self.iterations,
            self.runs,
            self.seed,
        );
        if !self.algorithms.is_empty() {
            let names: Vec<&str> = self.algorithms.iter().map(String::as_str).collect();
            settings.algorithms =
                named_list("--algorithms", &names, str::parse::<swarm::Algorithm>)?;
        }
        if !self.functions.is_empty() {
            let names: Vec<&str> = self.functions.iter().map(String::as_str).collect();
            let keyed = named_list("--functions", &names, |key| {
                swarm::functions::by_key(key).map(ByKey)
            })?;
            settings.functions = keyed.into_iter().map(|ByKey(function)| function).collect();
        }
        settings
            .validate()
            .map_err(|fault| InputError::new("arguments", fault))?;
        Ok(settings)
    }
}

/// A test function told apart from others by its key (`F1` and `f1` are one).
struct ByKey(&'static swarm::functions::TestFunction);

impl PartialEq for ByKey {
    fn eq(&self, other: &Self) -> bool {
        self.0.key == other.0.key
    }
}

/// Refuses a function bench that cannot run, before any run starts.
pub fn check(settings: &FunctionBench) -> Result<(), InputError> {
    settings
        .validate()
        .map_err(|fault| InputError::new("arguments", fault))
}

/// Runs a checked function bench; `tick` after each run.
pub fn run(
    settings: &FunctionBench,
    tick: &(dyn Fn() + Sync),
) -> Result<FunctionTable, InputError> {
    settings
        .run(tick)
        .map_err(|fault| InputError::new("arguments", fault))
}

/// The outcome of `agripath bench functions`: the table (with `--times`, its wall time) and
/// the folder of table.md, table.csv and the convergence plots.
pub fn outcome(table: &FunctionTable) -> Outcome {
    let mut text = table.markdown();
    if table.settings.with_times {
        text.push_str(&format!("wall time {:.1} s\n", table.wall_seconds));
    }
    Outcome::with_folder(
        text,
        table.files(),
        "table.md, table.csv, convergence_*.svg",
    )
}
