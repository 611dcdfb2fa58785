//! A table of the papers as asked for (`agripath repro TABLE`): the table's key, runs and
//! seed, checked into a [`ReproJob`] whose outcome is the text printed and the folder.

use super::{Failure, Outcome};
use crate::bench::functions::FunctionBench;
use crate::repro::{printed, seed000_table2, tracks};
use crate::InputError;

/// How the scenarios of the track tables are named in errors.
const TRACK_LABEL: &str = "embedded track scenario";

/// A checked request for one table.
pub struct ReproJob {
    table: Table,
    seed: u64,
}

/// The tables, by what they need to run.
enum Table {
    /// Seed 000 Table 2: a function bench.
    Functions(FunctionBench),
    /// Seed 000 Table 2 under several readings (`--ablation`): the bench and the names.
    Ablation(FunctionBench, Vec<String>),
    /// A track table (its key) with its runs per planner.
    Tracks(&'static str, u64),
    /// Seed 001 Table 8: the ant colony's runs per start (seeds `seed`, `seed + 1`, …).
    Table8(u64),
    /// A table computed without runs to count (its key).
    Other(&'static str),
}

/// The keys of the tables, as `agripath repro` takes them.
pub const TABLES: [&str; 9] = [
    "seed000-table2",
    "seed003-table4",
    "seed004",
    "seed001-table7",
    "seed000-table4",
    "seed000-table5",
    "seed002",
    "spso",
    "seed001-table8",
];

impl ReproJob {
    /// Checks the runs for `key` (one of [`TABLES`]): `runs` defaults to the paper's.
    pub fn new(key: &str, runs: Option<u64>, seed: u64) -> Result<Self, InputError> {
        let key = TABLES
            .iter()
            .copied()
            .find(|table| *table == key)
            .ok_or_else(|| {
                super::bad_value("TABLE", key, format!("expected {}", TABLES.join(", ")))
            })?;
        let table = match key {
            "seed000-table2" => {
                let settings =
                    seed000_table2::settings(runs.unwrap_or(50), seed, swarm::Readings::PAPER);
                super::bench::check(&settings)?;
                Table::Functions(settings)
            }
            "seed000-table4" | "seed000-table5" | "seed002" | "spso" => {
                Table::Tracks(key, super::track::check_runs(runs.unwrap_or(10))?)
            }
            "seed001-table8" => {
                let runs = super::track::check_runs(runs.unwrap_or(1))?;
                if seed.checked_add(runs - 1).is_none() {
                    return Err(super::bad_value(
                        "--seed",
                        seed.to_string(),
                        format!(
                            "{runs} runs from it go past the largest seed ({})",
                            u64::MAX
                        ),
                    ));
                }
                Table::Table8(runs)
            }
            other => {
                if let Some(runs) = runs {
                    return Err(super::bad_value(
                        "--runs",
                        runs.to_string(),
                        format!("{other} is computed once: it has no runs to count"),
                    ));
                }
                Table::Other(other)
            }
        };
        Ok(Self { table, seed })
    }

    /// Seed 000 Table 2 under the readings called `variant` (`paper` by default, decision
    /// 0020), or with `ablation` under `paper` and each reading of a comma-separated
    /// `variant` (every named reading when `variant` is `paper`); other tables refuse both.
    pub fn with_readings(mut self, variant: &str, ablation: bool) -> Result<Self, InputError> {
        let Table::Functions(settings) = &mut self.table else {
            if ablation || variant != "paper" {
                return Err(super::bad_value(
                    "--variant/--ablation",
                    variant,
                    "only seed000-table2 has readings".to_string(),
                ));
            }
            return Ok(self);
        };
        let names: Vec<&str> = if ablation && variant == "paper" {
            swarm::readings::NAMES
                .iter()
                .map(|(name, _)| *name)
                .collect()
        } else {
            variant.split(',').map(str::trim).collect()
        };
        for name in &names {
            swarm::Readings::named(name)
                .map_err(|why| super::bad_value("--variant", *name, why))?;
        }
        if ablation {
            let mut bench = settings.clone();
            bench.algorithms = swarm::Algorithm::SEED_000.to_vec();
            let names = names.iter().map(|name| name.to_string()).collect();
            self.table = Table::Ablation(bench, names);
        } else if names.len() > 1 {
            return Err(super::bad_value(
                "--variant",
                variant,
                "several readings (',') need --ablation; join changes with '+'".to_string(),
            ));
        } else {
            settings.readings = swarm::Readings::named(variant)
                .map_err(|why| super::bad_value("--variant", variant, why))?;
        }
        Ok(self)
    }

    /// The runs to make and what they are called, for a progress bar; `None` when the table
    /// has no runs to count.
    pub fn progress(&self) -> Option<(u64, &'static str)> {
        match &self.table {
            Table::Functions(settings) => Some((settings.total_runs(), "bench")),
            Table::Ablation(settings, names) => Some((
                crate::repro::seed000_ablation::total_runs(settings, names),
                "runs",
            )),
            Table::Tracks(key, runs) => Some((tracks::total_runs(key, *runs), "runs")),
            Table::Table8(_) | Table::Other(_) => None,
        }
    }

    /// Computes the table, `tick` after each counted run; its folder's files only when
    /// `with_files` (an `--out` folder is given), as they take time to draw.
    pub fn run(&self, with_files: bool, tick: &(dyn Fn() + Sync)) -> Result<Outcome, Failure> {
        let seed = self.seed;
        match &self.table {
            Table::Functions(settings) => {
                let table = super::bench::run(settings, tick)?;
                let comparison = seed000_table2::comparison(&table);
                let mut files = Vec::new();
                if with_files {
                    files = table.files();
                    let statistics = seed000_table2::statistics_files(&table).map_err(|why| {
                        InputError::new("convergence plots", crate::error::Fault::Structure(why))
                    })?;
                    files.extend(statistics);
                }
                files.push(("comparison.md".into(), comparison.clone().into_bytes()));
                let contents = "comparison.md, table.md, table.csv, statistics.md, \
                    convergence_*.svg, convergence_median_*.svg/.png";
                Ok(Outcome::with_folder(comparison, files, contents))
            }
            Table::Ablation(settings, names) => {
                let tables = crate::repro::seed000_ablation::run(settings, names, tick)
                    .map_err(|fault| InputError::new("arguments", fault))?;
                let text = crate::repro::seed000_ablation::markdown(&tables);
                let files = vec![("ablation.md".into(), text.clone().into_bytes())];
                Ok(Outcome::with_folder(text, files, "ablation.md"))
            }
            Table::Tracks(key, runs) => track_table(key, *runs, seed, with_files, tick),
            Table::Other(key @ "seed003-table4") => {
                Ok(printed_table(key, printed::seed003_table4(seed)?))
            }
            Table::Other("seed004") => {
                let settings = crate::grid_cover::hybrid_pso::HpsoSettings {
                    seed,
                    ..Default::default()
                };
                let (rows, table, text) = printed::seed004(&settings)?;
                let mut files: Vec<(String, Vec<u8>)> =
                    vec![("seed004.txt".into(), table.into_bytes())];
                if with_files {
                    for row in &rows {
                        let map = crate::repro::seed004::map_svg(row);
                        files.push((format!("{}.svg", row.name), map.into_bytes()));
                    }
                }
                Ok(Outcome::with_folder(
                    text,
                    files,
                    "seed004.txt and a map per field",
                ))
            }
            Table::Table8(runs) => Ok(printed_table(
                "seed001-table8",
                printed::seed001_table8(*runs, seed)?,
            )),
            Table::Other(key) => Ok(printed_table(key, printed::seed001_table7()?)),
        }
    }
}

/// A table that is only text: printed, and with `--out` written as `KEY.txt`.
fn printed_table(key: &str, text: String) -> Outcome {
    let name = format!("{key}.txt");
    let files = vec![(name.clone(), text.clone().into_bytes())];
    Outcome::with_folder(text, files, &name)
}

/// A track table: its text and, with `with_files`, each case's track files (numbered when
/// the table has several cases) beside `table.md`.
fn track_table(
    key: &str,
    runs: u64,
    seed: u64,
    with_files: bool,
    tick: &(dyn Fn() + Sync),
) -> Result<Outcome, Failure> {
    let input = |fault| InputError::new(TRACK_LABEL, fault);
    let (text, cases) = match key {
        "seed000-table4" => tracks::seed000_table4(runs, seed, tick).map_err(input)?,
        other => {
            let (text, scenario, results) = match other {
                "seed000-table5" => tracks::seed000_table5(runs, seed, tick),
                "seed002" => tracks::seed002(runs, seed, tick),
                _ => tracks::spso(runs, seed, tick),
            }
            .map_err(input)?;
            (text, vec![(scenario, results)])
        }
    };
    let mut files: Vec<(String, Vec<u8>)> = vec![("table.md".into(), text.clone().into_bytes())];
    for (index, (scenario, results)) in cases.iter().enumerate().filter(|_| with_files) {
        let suffix = if cases.len() > 1 {
            format!("_{}", index + 1)
        } else {
            String::new()
        };
        for (name, bytes) in
            crate::track::files::files(scenario, results, seed, false).map_err(Failure::Output)?
        {
            if name == "table.md" {
                continue;
            }
            let (stem, extension) = name.rsplit_once('.').unwrap_or((&name, ""));
            files.push((format!("{stem}{suffix}.{extension}"), bytes));
        }
    }
    let contents = "table.md, track, report, top views, profiles, convergence";
    Ok(Outcome::with_folder(text, files, contents))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--runs` counts Table 8's colony runs and `--seed` seeds the first (the sixth trial
    /// found `--seed` taken as the count and `--runs` ignored); a table computed once
    /// refuses `--runs`.
    #[test]
    fn table8_takes_runs_and_seed_apart_and_a_table_computed_once_refuses_runs() {
        let job = ReproJob::new("seed001-table8", Some(3), 7).unwrap();
        assert!(matches!(job.table, Table::Table8(3)) && job.seed == 7);
        let default = ReproJob::new("seed001-table8", None, 7).unwrap();
        assert!(matches!(default.table, Table::Table8(1)));
        for (runs, seed) in [(0, 1), (1001, 1), (2, u64::MAX)] {
            assert!(ReproJob::new("seed001-table8", Some(runs), seed).is_err());
        }
        assert!(ReproJob::new("seed001-table8", Some(1), u64::MAX).is_ok());
        for key in ["seed001-table7", "seed003-table4", "seed004"] {
            let error = ReproJob::new(key, Some(5), 1).err().expect("refused");
            assert!(error.to_string().contains("no runs to count"), "{error}");
            assert!(ReproJob::new(key, None, 1).is_ok());
        }
    }
}
