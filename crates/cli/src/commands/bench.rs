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
    let settings = agripath::request::bench::FunctionBenchOptions {
        dimension: dim,
        population: pop,
        iterations: iters,
        runs,
        algorithms,
        functions,
        seed,
    }
    .settings()?;
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
