//! `agripath bench functions`: optimizers × test functions × independent runs, summarised as
//! seed 000 Table 2 is (best, worst, mean, standard deviation, time), with mean convergence
//! curves.
//!
//! Every algorithm gets the same evaluation budget, population × (iterations + 1): the
//! initial population plus `iterations` generations of a population-sized algorithm. The
//! algorithms that spend evaluations differently (GA keeps its elite without re-evaluating
//! it, ILSSIWBA's local search, L-SHADE's shrinking population) run as many iterations as
//! the budget allows. Runs are independent seeded streams, run in parallel; the numbers equal
//! those of serial runs.

use std::fmt::Write;
use std::time::Instant;

use swarm::functions::{FunctionProblem, TestFunction};
use swarm::{Algorithm, Outcome, Runner, Termination};

use crate::error::Fault;
use crate::plot::line_chart::{self, Chart, Series};

/// Points on each convergence curve.
const CURVE_POINTS: usize = 100;

/// What to run.
#[derive(Debug, Clone)]
pub struct FunctionBench {
    /// D, the number of coordinates of every function.
    pub dimension: usize,
    /// Agents per algorithm (at least 2); also sets the evaluation budget.
    pub population: usize,
    /// Iterations a population-sized algorithm runs (at least 1); sets the budget.
    pub iterations: usize,
    /// Independent runs per algorithm and function (at least 1).
    pub runs: u64,
    /// The algorithms compared, one table column each.
    pub algorithms: Vec<Algorithm>,
    /// The test functions, one group of table rows each.
    pub functions: Vec<&'static TestFunction>,
    /// The base seed; run r draws from its own stream derived from it.
    pub seed: u64,
    /// The readings of the algorithms' open choices (issue 20); `bench functions` keeps
    /// decision 0007's, `repro seed000-table2` takes `--variant`.
    pub readings: swarm::Readings,
    /// Whether the table carries each cell's mean wall-clock time per run (Table 2 has a time
    /// row). Off, the table and its files depend on the settings alone and repeat byte for
    /// byte; on, the time rows change from one run to the next.
    pub with_times: bool,
}

/// Most numbers (population × dimension) a bench's population may hold: 160 MB a copy.
pub const MOST_POPULATION_NUMBERS: usize = 20_000_000;

impl FunctionBench {
    /// Seed 000 §2.5: D = 50, population 500, 300 iterations, 50 runs, its five algorithms
    /// on its nine functions.
    pub fn table_2() -> Self {
        Self {
            dimension: 50,
            population: 500,
            iterations: 300,
            runs: 50,
            algorithms: Algorithm::SEED_000.to_vec(),
            functions: swarm::functions::TABLE_1.iter().collect(),
            seed: 1,
            readings: swarm::Readings::ENGINE,
            with_times: true,
        }
    }

    /// The evaluations every algorithm may spend in one run.
    pub fn evaluation_budget(&self) -> u64 {
        self.population as u64 * (self.iterations as u64 + 1)
    }

    /// The settings in one line.
    pub fn describe(&self) -> String {
        format!(
            "D = {}, population {}, {} iterations ({} evaluations per run), {} runs, seed {}",
            self.dimension,
            self.population,
            self.iterations,
            self.evaluation_budget(),
            self.runs,
            self.seed
        )
    }

    /// The head of a Markdown table with a column per algorithm.
    pub fn table_header(&self) -> String {
        let mut text = String::from("| function | statistic |");
        for algorithm in &self.algorithms {
            let _ = write!(text, " {} |", algorithm.label());
        }
        text.push_str("\n|---|---|");
        for _ in &self.algorithms {
            text.push_str("---:|");
        }
        text.push('\n');
        text
    }

    /// Runs in total (for a progress display).
    pub fn total_runs(&self) -> u64 {
        self.runs * (self.algorithms.len() * self.functions.len()) as u64
    }

    /// Checks the settings before anything runs.
    pub fn validate(&self) -> Result<(), Fault> {
        let invalid = |what: &str, value: String, why: &str| Fault::InvalidValue {
            what: what.into(),
            value,
            why: why.into(),
        };
        if self.population < 2 {
            return Err(invalid(
                "--pop",
                self.population.to_string(),
                "needs at least 2",
            ));
        }
        if self.iterations == 0 {
            return Err(invalid("--iters", "0".into(), "needs at least 1"));
        }
        if self.runs == 0 {
            return Err(invalid("--runs", "0".into(), "needs at least 1"));
        }
        if self.algorithms.is_empty() || self.functions.is_empty() {
            return Err(invalid(
                "--algorithms/--functions",
                "(none)".into(),
                "name at least one",
            ));
        }
        if self.evaluation_budget() > 10_000_000_000 {
            return Err(invalid(
                "--pop × --iters",
                self.evaluation_budget().to_string(),
                "more than 1e10 evaluations per run",
            ));
        }
        // Each optimizer keeps a few copies of its population (positions, velocities or
        // offspring, bests), and runs go in parallel, one per core.
        if self.population.saturating_mul(self.dimension) > MOST_POPULATION_NUMBERS {
            return Err(invalid(
                "--pop × --dim",
                format!("{} × {}", self.population, self.dimension),
                &format!(
                    "more than {MOST_POPULATION_NUMBERS} numbers in a population (160 MB a copy; the optimizers keep several)"
                ),
            ));
        }
        for function in &self.functions {
            function.check_dimension(self.dimension).map_err(|error| {
                invalid("--dim", self.dimension.to_string(), &error.to_string())
            })?;
        }
        Ok(())
    }

    /// Runs everything; `finished` is called after each run (from any thread).
    pub fn run(&self, finished: &(dyn Fn() + Sync)) -> Result<FunctionTable, Fault> {
        self.validate()?;
        let started = Instant::now();
        let runner = Runner::new(
            Termination::evaluations(self.evaluation_budget()),
            self.seed,
        )
        .expect("a positive evaluation budget");
        let mut cells = Vec::new();
        for &function in &self.functions {
            let problem =
                FunctionProblem::new(function, self.dimension).expect("dimensions were validated");
            for &algorithm in &self.algorithms {
                let outcomes = runner.run_many(
                    || algorithm.build_read(self.population, &self.readings),
                    &problem,
                    self.runs,
                    &|_| finished(),
                );
                cells.push(Cell::new(
                    function,
                    algorithm,
                    &outcomes,
                    self.evaluation_budget(),
                ));
            }
        }
        Ok(FunctionTable {
            settings: self.clone(),
            cells,
            wall_seconds: started.elapsed().as_secs_f64(),
        })
    }
}

/// Best, worst, mean and sample standard deviation of the final costs, and the mean time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Statistics {
    /// The lowest final cost.
    pub best: f64,
    /// The highest final cost.
    pub worst: f64,
    /// The mean final cost.
    pub mean: f64,
    /// The sample standard deviation of the final costs (0 for a single run).
    pub standard_deviation: f64,
    /// The mean wall-clock time of a run, in seconds.
    pub mean_seconds: f64,
    /// The mean number of evaluations a run spent.
    pub mean_evaluations: f64,
}

/// One function × one algorithm.
#[derive(Debug, Clone)]
pub struct Cell {
    /// The test function.
    pub function: &'static TestFunction,
    /// The algorithm.
    pub algorithm: Algorithm,
    /// The statistics over the runs.
    pub statistics: Statistics,
    /// Every run's final best cost, in run order.
    pub finals: Vec<f64>,
    /// Mean best cost over the runs against evaluations spent.
    pub convergence: Vec<(f64, f64)>,
    /// The runs' lower quartile, median and upper quartile of the best cost against
    /// evaluations spent: (evaluations, q1, median, q3).
    pub quartiles: Vec<(f64, f64, f64, f64)>,
}

impl Cell {
    fn new(
        function: &'static TestFunction,
        algorithm: Algorithm,
        outcomes: &[Outcome],
        budget: u64,
    ) -> Self {
        let finals: Vec<f64> = outcomes.iter().map(|o| o.best_cost).collect();
        let count = finals.len() as f64;
        let spread = swarm::statistics::Spread::of(&finals);
        let statistics = Statistics {
            best: spread.best,
            worst: spread.worst,
            mean: spread.mean,
            standard_deviation: spread.standard_deviation,
            mean_seconds: outcomes
                .iter()
                .map(|o| o.elapsed.as_secs_f64())
                .sum::<f64>()
                / count,
            mean_evaluations: outcomes.iter().map(|o| o.evaluations as f64).sum::<f64>() / count,
        };
        Self {
            function,
            algorithm,
            statistics,
            finals,
            convergence: curve(outcomes, budget, |values| {
                values.iter().sum::<f64>() / values.len() as f64
            }),
            quartiles: curve(outcomes, budget, |values| values.to_vec())
                .into_iter()
                .map(|(x, values)| {
                    let q = |p| swarm::statistics::quantile(&values, p);
                    (x, q(0.25), q(0.5), q(0.75))
                })
                .collect(),
        }
    }
}

/// `summary` over runs of the best cost after `budget·i/CURVE_POINTS` evaluations (where
/// every run has a record by then).
fn curve<T>(outcomes: &[Outcome], budget: u64, summary: impl Fn(&[f64]) -> T) -> Vec<(f64, T)> {
    let mut curve = Vec::with_capacity(CURVE_POINTS + 1);
    for step in 0..=CURVE_POINTS {
        let spent = budget * step as u64 / CURVE_POINTS as u64;
        let values: Vec<f64> = outcomes
            .iter()
            .filter_map(|outcome| {
                outcome
                    .history
                    .iter()
                    .take_while(|record| record.evaluations <= spent)
                    .last()
                    .map(|record| record.best_cost)
            })
            .collect();
        if values.len() == outcomes.len() && !values.is_empty() {
            curve.push((spent as f64, summary(&values)));
        }
    }
    curve
}

/// How one row of the table shows a cell's statistics.
type ShowStatistic = fn(&Statistics) -> String;

/// The results of a bench run.
#[derive(Debug, Clone)]
pub struct FunctionTable {
    /// The settings the bench ran with.
    pub settings: FunctionBench,
    /// One cell per function × algorithm, functions in order, algorithms within.
    pub cells: Vec<Cell>,
    /// Wall-clock time of the whole bench, in seconds.
    pub wall_seconds: f64,
}

/// A number as Table 2 prints it: four significant decimals, exponent form.
pub fn scientific(value: f64) -> String {
    if value == 0.0 {
        "0".into()
    } else {
        format!("{value:.5e}")
    }
}

/// The log-scale axis of a convergence plot on `function`: the gap of a value to the optimum,
/// or to `lowest` (the lowest value seen) where that is lower (f5's −150 is not proven), kept
/// above a floor so that a log scale can draw zero; and the axis label saying which.
pub(crate) fn gap_axis(function: &TestFunction, lowest: f64) -> (impl Fn(f64) -> f64, String) {
    let floor = 1e-30_f64.max(lowest.abs() * 1e-15);
    let label = if lowest < function.optimum {
        format!("best − ({lowest:.6}) (lowest seen)")
    } else if function.optimum_known {
        format!("best − f* (f* = {})", function.optimum)
    } else {
        // A run that has converged still shows its distance to a minimum nobody reaches.
        format!(
            "best − f* (f* = {}, Table 1's; no known point reaches it)",
            function.optimum
        )
    };
    // A gap of exactly 0 (a run at the optimum, to the last bit) sits on the floor: say so.
    let label = format!("{label}; 0 drawn at {floor:.0e}");
    (move |y: f64| (y - lowest).max(floor), label)
}

impl FunctionTable {
    /// The cell of the function with key `function` and `algorithm`, if it ran.
    pub fn cell(&self, function: &str, algorithm: Algorithm) -> Option<&Cell> {
        self.cells
            .iter()
            .find(|cell| cell.function.key == function && cell.algorithm == algorithm)
    }

    /// Table 2's layout: a row per function and statistic, a column per algorithm.
    pub fn markdown(&self) -> String {
        let settings = &self.settings;
        let mut text = format!("{}\n\n", settings.describe());
        text.push_str(&settings.table_header());
        for function in &settings.functions {
            let rows: [(&str, ShowStatistic); 5] = [
                ("best", |s| scientific(s.best)),
                ("worst", |s| scientific(s.worst)),
                ("mean", |s| scientific(s.mean)),
                ("std", |s| scientific(s.standard_deviation)),
                ("time (s)", |s| format!("{:.3}", s.mean_seconds)),
            ];
            let shown = if settings.with_times { 5 } else { 4 };
            for (index, (label, show)) in rows[..shown].iter().enumerate() {
                let name = if index == 0 { function.key } else { "" };
                let _ = write!(text, "| {name} | {label} |");
                for &algorithm in &settings.algorithms {
                    let value = self
                        .cell(function.key, algorithm)
                        .map(|cell| show(&cell.statistics))
                        .unwrap_or_default();
                    let _ = write!(text, " {value} |");
                }
                text.push('\n');
            }
        }
        text
    }

    /// One line per function × algorithm; the mean time column only `with_times`.
    pub fn csv(&self) -> String {
        let time_column = if self.settings.with_times {
            "mean_time_s,"
        } else {
            ""
        };
        let mut text = format!(
            "function,algorithm,dimension,runs,evaluation_budget,best,worst,mean,std,{time_column}mean_evaluations\n",
        );
        for cell in &self.cells {
            let s = &cell.statistics;
            let time = if self.settings.with_times {
                format!("{:.6},", s.mean_seconds)
            } else {
                String::new()
            };
            let _ = writeln!(
                text,
                "{},{},{},{},{},{:e},{:e},{:e},{:e},{time}{:.1}",
                cell.function.key,
                cell.algorithm.label(),
                self.settings.dimension,
                self.settings.runs,
                self.settings.evaluation_budget(),
                s.best,
                s.worst,
                s.mean,
                s.standard_deviation,
                s.mean_evaluations
            );
        }
        text
    }

    /// The mean convergence curves of every algorithm on `function`, as the gap to the
    /// optimum (or to the lowest value seen, where that is lower: f5's −150 is not proven) on
    /// a log scale.
    pub fn convergence_svg(&self, function: &TestFunction) -> String {
        let cells: Vec<&Cell> = self
            .cells
            .iter()
            .filter(|cell| cell.function.key == function.key)
            .collect();
        let lowest = cells
            .iter()
            .flat_map(|cell| cell.convergence.iter().map(|&(_, y)| y))
            .fold(function.optimum, f64::min);
        let (gap, y_label) = gap_axis(function, lowest);
        let series: Vec<Series> = cells
            .iter()
            .map(|cell| Series {
                name: cell.algorithm.label().to_string(),
                points: cell.convergence.iter().map(|&(x, y)| (x, gap(y))).collect(),
            })
            .collect();
        let title = format!(
            "{} {}, D = {}: mean best of {} runs",
            function.key, function.name, self.settings.dimension, self.settings.runs
        );
        line_chart::render(
            &Chart {
                title: &title,
                x_label: "evaluations",
                y_label: &y_label,
                log_y: true,
            },
            &series,
        )
    }

    /// The files `bench functions --out DIR` writes.
    pub fn files(&self) -> Vec<(String, Vec<u8>)> {
        let mut files = vec![
            ("table.md".to_string(), self.markdown().into_bytes()),
            ("table.csv".to_string(), self.csv().into_bytes()),
        ];
        for function in &self.settings.functions {
            files.push((
                format!("convergence_{}.svg", function.key),
                self.convergence_svg(function).into_bytes(),
            ));
        }
        files
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> FunctionBench {
        FunctionBench {
            dimension: 10,
            population: 20,
            iterations: 30,
            runs: 3,
            algorithms: vec![Algorithm::IBA_FCS, Algorithm::PARTICLE_SWARM],
            functions: vec![
                swarm::functions::by_key("f1").unwrap(),
                swarm::functions::by_key("f7").unwrap(),
            ],
            seed: 5,
            readings: swarm::Readings::ENGINE,
            with_times: false,
        }
    }

    #[test]
    fn statistics_order_and_the_table_lists_every_cell() {
        let table = small().run(&|| {}).unwrap();
        assert_eq!(table.cells.len(), 4);
        for cell in &table.cells {
            let s = cell.statistics;
            assert!(s.best <= s.mean && s.mean <= s.worst, "{s:?}");
            assert!(s.mean_evaluations <= 20.0 * 31.0);
            assert!(cell
                .convergence
                .windows(2)
                .all(|w| w[1].1 <= w[0].1 + 1e-9 * w[0].1.abs()));
        }
        let markdown = table.markdown();
        assert_eq!(markdown.matches("| f1 |").count(), 1);
        assert!(markdown.contains("IBA-FCS") && markdown.contains("PSO"));
        assert_eq!(table.csv().lines().count(), 5);
        assert_eq!(table.files().len(), 4);
    }

    #[test]
    fn the_same_seed_gives_the_same_table() {
        let first = small().run(&|| {}).unwrap();
        let second = small().run(&|| {}).unwrap();
        assert!(!first.cells.is_empty());
        assert_eq!(first.cells.len(), second.cells.len());
        for (a, b) in first.cells.iter().zip(&second.cells) {
            assert_eq!(a.finals, b.finals);
        }
    }

    #[test]
    fn bad_settings_are_refused_before_running() {
        let mut settings = small();
        settings.dimension = 20;
        settings.functions = vec![swarm::functions::by_key("f3").unwrap()];
        assert!(settings.validate().is_err());
        let mut settings = small();
        settings.runs = 0;
        assert!(settings.validate().is_err());
    }
}
