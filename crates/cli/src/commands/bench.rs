//! `bench functions`: optimizers × functions × runs (seed 000 Table 2).

use super::*;

/// Runs a function bench with a progress bar.
pub(super) fn run_function_bench(settings: &FunctionBench) -> Result<FunctionTable, Failure> {
    settings
        .validate()
        .map_err(|fault| InputError::new("arguments", fault))?;
    let bar = progress_bar(settings.total_runs(), "bench");
    let table = settings
        .run(&|| bar.inc(1))
        .map_err(|fault| InputError::new("arguments", fault))?;
    bar.finish_and_clear();
    Ok(table)
}

pub(super) fn bench(action: BenchAction) -> Result<(), Failure> {
    let BenchAction::Functions {
        dim,
        pop,
        iters,
        runs,
        algorithms,
        functions,
        seed,
        out,
    } = action;
    let invalid = |what: &str, value: &str, why: String| {
        InputError::new(
            "arguments",
            Fault::InvalidValue {
                what: what.into(),
                value: value.into(),
                why,
            },
        )
    };
    let mut settings = FunctionBench::table_2();
    (
        settings.dimension,
        settings.population,
        settings.iterations,
        settings.runs,
        settings.seed,
    ) = (dim, pop, iters, runs, seed);
    if !algorithms.is_empty() {
        settings.algorithms = algorithms
            .iter()
            .map(|name| {
                name.parse::<swarm::Algorithm>()
                    .map_err(|why| invalid("--algorithms", name, why))
            })
            .collect::<Result<_, _>>()?;
    }
    if !functions.is_empty() {
        settings.functions = functions
            .iter()
            .map(|key| {
                swarm::functions::by_key(key)
                    .map_err(|why| invalid("--functions", key, why.to_string()))
            })
            .collect::<Result<_, _>>()?;
    }
    let table = run_function_bench(&settings)?;
    emit!("{}", table.markdown());
    emitln!("wall time {:.1} s", table.wall_seconds);
    if let Some(out) = out {
        let files = table.files();
        let named: Vec<(&str, Vec<u8>)> = files
            .iter()
            .map(|(name, bytes)| (name.as_str(), bytes.clone()))
            .collect();
        let written = write_folder(&out, &named)?;
        emitln!(
            "wrote {}/: table.md, table.csv, convergence_*.svg",
            written.display()
        );
    }
    Ok(())
}
