//! `track`, `bench` and `repro`: the commands with many runs, behind a progress bar.

use std::path::Path;

use agripath::request::repro::ReproJob;
use agripath::request::{self, Failure};

use super::{finish, progress_bar};
use crate::args::{BenchAction, ReproTable};

/// `agripath track`: every planner's runs, the folder, the verdict.
pub(super) fn track(
    request: &request::track::TrackRequest,
    allow_unsafe: bool,
    out: &Path,
) -> Result<(), Failure> {
    let job = request.prepare()?;
    let bar = progress_bar(job.total_runs(), "runs");
    let results = job.run(&|| bar.inc(1))?;
    bar.finish_and_clear();
    finish(Some(out), job.outcome(&results, allow_unsafe)?)
}

pub(super) fn bench(action: BenchAction) -> Result<(), Failure> {
    let BenchAction::Functions { options, out } = action;
    let settings = options.settings()?;
    request::bench::check(&settings)?;
    let bar = progress_bar(settings.total_runs(), "bench");
    let table = request::bench::run(&settings, &|| bar.inc(1))?;
    bar.finish_and_clear();
    finish(out.as_deref(), request::bench::outcome(&table))
}

/// `agripath repro TABLE`: the table on stdout; with `--out`, its files.
pub(super) fn repro(
    table: ReproTable,
    (runs, seed): (Option<u64>, u64),
    (variant, ablation): (&str, bool),
    out: Option<&Path>,
) -> Result<(), Failure> {
    let key = clap::ValueEnum::to_possible_value(&table).expect("every table has a name");
    let job = ReproJob::new(key.get_name(), runs, seed)?.with_readings(variant, ablation)?;
    let bar = job
        .progress()
        .map(|(total, what)| progress_bar(total, what));
    let outcome = job.run(out.is_some(), &|| {
        if let Some(bar) = &bar {
            bar.inc(1);
        }
    })?;
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    finish(out, outcome)
}
