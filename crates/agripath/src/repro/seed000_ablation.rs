//! `agripath repro seed000-table2 --ablation`: seed 000 Table 2 under each reading of the
//! text's open choices (`swarm::readings::NAMES`), beside the paper's numbers.
//!
//! The `paper` reading runs all five algorithms; every other reading changes one or two of
//! them, and only those are run again (the others' cells are the `paper` reading's, which
//! they equal by construction: same seed, same settings). Per reading the table gives the
//! changed algorithms' mean / std / best per function, IBA-FCS's rank among the five, the
//! number of functions whose full ranking of the five is the paper's, and IBA-FCS's mean as
//! a ratio to the paper's where the paper's is not ~0 (|mean| > 1e-6).

use std::fmt::Write;

use swarm::readings::NAMES;
use swarm::{Algorithm, Readings};

use super::super::bench::functions::{scientific, FunctionBench, FunctionTable};
use super::seed000_table2::{paper_mean, ranking, ranking_matches};
use crate::error::Fault;

/// Whether `readings` change `algorithm` compared with `base`.
fn changes(readings: &Readings, base: &Readings, algorithm: Algorithm) -> bool {
    if algorithm == Algorithm::BAT {
        readings.bat != base.bat
    } else if algorithm == Algorithm::IBA_FCS {
        readings.iba_fcs != base.iba_fcs
    } else if algorithm == Algorithm::PARTICLE_SWARM {
        readings.particle_swarm != base.particle_swarm
    } else if algorithm == Algorithm::GENETIC {
        readings.genetic != base.genetic
    } else {
        false
    }
}

/// One reading's table: the `paper` reading's cells with the changed algorithms' replaced.
pub struct ReadingTable {
    /// The reading's name.
    pub name: String,
    /// What it changes.
    pub description: String,
    /// The algorithms it changes (empty for `paper`).
    pub changed: Vec<Algorithm>,
    /// All five algorithms' cells under this reading.
    pub table: FunctionTable,
}

/// The runs the ablation makes in all, for a progress bar.
pub fn total_runs<S: AsRef<str>>(settings: &FunctionBench, names: &[S]) -> u64 {
    let per_algorithm = settings.runs * settings.functions.len() as u64;
    let mut total = per_algorithm * Algorithm::SEED_000.len() as u64;
    for name in names
        .iter()
        .map(AsRef::as_ref)
        .filter(|name| *name != "paper")
    {
        if let Ok(readings) = Readings::named(name) {
            let changed = Algorithm::SEED_000
                .iter()
                .filter(|&&a| changes(&readings, &Readings::PAPER, a))
                .count();
            total += per_algorithm * changed as u64;
        }
    }
    total
}

/// Runs seed 000's five algorithms under `paper` and then each of `names` (readings as
/// [`Readings::named`] knows them), with `settings`' dimension, population, iterations,
/// runs and seed.
pub fn run<S: AsRef<str>>(
    settings: &FunctionBench,
    names: &[S],
    tick: &(dyn Fn() + Sync),
) -> Result<Vec<ReadingTable>, Fault> {
    let names: Vec<&str> = names
        .iter()
        .map(AsRef::as_ref)
        .filter(|name| *name != "paper")
        .collect();
    let readings: Vec<Readings> = names
        .iter()
        .map(|name| {
            Readings::named(name).map_err(|why| Fault::InvalidValue {
                what: "--variant".into(),
                value: name.to_string(),
                why,
            })
        })
        .collect::<Result<_, _>>()?;
    let mut base_settings = settings.clone();
    base_settings.algorithms = Algorithm::SEED_000.to_vec();
    base_settings.readings = Readings::PAPER;
    let base = base_settings.run(tick)?;
    let mut tables = vec![ReadingTable {
        name: "paper".into(),
        description: describe("paper"),
        changed: Vec::new(),
        table: base.clone(),
    }];
    for (&name, readings) in names.iter().zip(readings) {
        let changed: Vec<Algorithm> = Algorithm::SEED_000
            .iter()
            .copied()
            .filter(|&a| changes(&readings, &Readings::PAPER, a))
            .collect();
        let mut reading_settings = base_settings.clone();
        reading_settings.algorithms = changed.clone();
        reading_settings.readings = readings;
        let rerun = reading_settings.run(tick)?;
        let mut table = base.clone();
        table.settings.readings = readings;
        for cell in &mut table.cells {
            if let Some(new) = rerun
                .cells
                .iter()
                .find(|c| c.function.key == cell.function.key && c.algorithm == cell.algorithm)
            {
                *cell = new.clone();
            }
        }
        table.wall_seconds = rerun.wall_seconds;
        tables.push(ReadingTable {
            name: name.into(),
            description: describe(name),
            changed,
            table,
        });
    }
    Ok(tables)
}

fn describe(name: &str) -> String {
    name.split('+')
        .map(|part| {
            NAMES
                .iter()
                .find(|(known, _)| *known == part)
                .map(|(_, what)| what.to_string())
                .unwrap_or_else(|| part.to_string())
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// IBA-FCS's rank (1 = best mean) among the five on `function`.
fn iba_rank(table: &FunctionTable, function: &str) -> usize {
    ranking(table, function)
        .iter()
        .position(|&a| a == Algorithm::IBA_FCS)
        .map_or(0, |index| index + 1)
}

/// IBA-FCS's mean over the paper's, as "×ratio", or the mean itself where the paper's is ~0.
fn iba_ratio(table: &FunctionTable, function: &str) -> String {
    let ours = table
        .cell(function, Algorithm::IBA_FCS)
        .map_or(f64::NAN, |cell| cell.statistics.mean);
    match paper_mean(function, Algorithm::IBA_FCS) {
        Some(paper) if paper.abs() > 1e-6 => format!("×{:.3}", ours / paper),
        _ => format!("{} (paper ~0)", scientific(ours)),
    }
}

/// The ablation as Markdown: a summary row per reading, then per reading the changed
/// algorithms' mean / std / best beside the paper's mean.
pub fn markdown(tables: &[ReadingTable]) -> String {
    let mut text = String::new();
    let Some(first) = tables.first() else {
        return text;
    };
    let settings = &first.table.settings;
    let _ = writeln!(
        text,
        "Seed 000 Table 2 by reading. {}.\n",
        settings.describe()
    );
    text.push_str("| reading | IBA-FCS first on | ranking as the paper's on |");
    for function in &settings.functions {
        let _ = write!(text, " {} |", function.key);
    }
    text.push_str("\n|---|---:|---:|");
    for _ in &settings.functions {
        text.push_str("---|");
    }
    text.push('\n');
    for reading in tables {
        let firsts = settings
            .functions
            .iter()
            .filter(|f| iba_rank(&reading.table, f.key) == 1)
            .count();
        let _ = write!(
            text,
            "| {} | {firsts} / {} | {} / {} |",
            reading.name,
            settings.functions.len(),
            ranking_matches(&reading.table),
            settings.functions.len()
        );
        for function in &settings.functions {
            let _ = write!(
                text,
                " {} {} |",
                rank_word(iba_rank(&reading.table, function.key)),
                iba_ratio(&reading.table, function.key)
            );
        }
        text.push('\n');
    }
    text.push_str(
        "\nPer function: IBA-FCS's rank among the five by mean, and its mean as a ratio to the \
         paper's (or the mean where the paper's is ~0).\n",
    );
    for reading in tables {
        let shown: Vec<Algorithm> = if reading.changed.is_empty() {
            Algorithm::SEED_000.to_vec()
        } else {
            reading.changed.clone()
        };
        let _ = writeln!(text, "\n### {}\n\n{}.\n", reading.name, reading.description);
        text.push_str("| function |");
        for algorithm in &shown {
            let _ = write!(
                text,
                " {0} mean / std / best | {0} paper mean |",
                algorithm.label()
            );
        }
        text.push_str(" ranking (ours) |\n|---|");
        for _ in &shown {
            text.push_str("---|---:|");
        }
        text.push_str("---|\n");
        for function in &settings.functions {
            let _ = write!(text, "| {} |", function.key);
            for &algorithm in &shown {
                let (ours, paper) = (
                    reading.table.cell(function.key, algorithm),
                    paper_mean(function.key, algorithm),
                );
                let ours = ours.map_or(String::new(), |cell| {
                    let s = cell.statistics;
                    format!(
                        "{} / {} / {}",
                        scientific(s.mean),
                        scientific(s.standard_deviation),
                        scientific(s.best)
                    )
                });
                let paper = paper.map_or(String::new(), scientific);
                let _ = write!(text, " {ours} | {paper} |");
            }
            let order: Vec<&str> = ranking(&reading.table, function.key)
                .iter()
                .map(|a| a.label())
                .collect();
            let _ = writeln!(text, " {} |", order.join(" < "));
        }
    }
    text
}

fn rank_word(rank: usize) -> &'static str {
    ["?", "1st", "2nd", "3rd", "4th", "5th"]
        .get(rank)
        .copied()
        .unwrap_or("?")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> FunctionBench {
        let mut settings = FunctionBench::table_2();
        settings.dimension = 10;
        settings.population = 20;
        settings.iterations = 10;
        settings.runs = 2;
        settings.functions = vec![swarm::functions::by_key("f1").unwrap()];
        settings
    }

    #[test]
    fn a_reading_reruns_only_what_it_changes_and_the_rest_is_the_papers() {
        let names = ["paper", "iba-greedy", "engine"];
        let tables = run(&small(), &names, &|| {}).unwrap();
        assert_eq!(tables.len(), 3);
        assert_eq!(tables[1].changed, vec![Algorithm::IBA_FCS]);
        assert_eq!(
            tables[2].changed,
            vec![Algorithm::PARTICLE_SWARM, Algorithm::BAT]
        );
        for algorithm in [
            Algorithm::GENETIC,
            Algorithm::BAT,
            Algorithm::PARTICLE_SWARM,
        ] {
            let paper = tables[0].table.cell("f1", algorithm).unwrap();
            let greedy = tables[1].table.cell("f1", algorithm).unwrap();
            assert_eq!(paper.finals, greedy.finals);
        }
        let paper = tables[0].table.cell("f1", Algorithm::IBA_FCS).unwrap();
        let greedy = tables[1].table.cell("f1", Algorithm::IBA_FCS).unwrap();
        assert_ne!(paper.finals, greedy.finals);
        assert_eq!(total_runs(&small(), &names), 2 * (5 + 1 + 2));
        let text = markdown(&tables);
        assert!(text.contains("| iba-greedy |") && text.contains("### engine"));
    }

    #[test]
    fn an_unknown_reading_is_refused() {
        assert!(run(&small(), &["iba-nonsense"], &|| {}).is_err());
    }
}
