//! `track` and the track tables of `repro`: point-to-point tracks.

use super::*;

/// `agripath track`: every planner's runs, the folder, the verdict.
pub(super) fn track(
    request: &agripath::request::track::TrackRequest,
    allow_unsafe: bool,
    out: &Path,
) -> Result<(), Failure> {
    use agripath::track::files::{self, PlannerRuns};
    let job = request.prepare()?;
    let bar = progress_bar(job.total_runs(), "runs");
    let results = job.run(&|| bar.inc(1))?;
    bar.finish_and_clear();
    let files =
        files::files(&job.scenario, &results, job.seed, allow_unsafe).map_err(Failure::Output)?;
    let written = write_folder(out, &files)?;
    emit!("{}", files::table(&job.scenario, &results));
    let reasons: Vec<String> = results
        .iter()
        .filter_map(PlannerRuns::unsafe_reason)
        .collect();
    for reason in &reasons {
        emitln!("{reason}");
    }
    let names: Vec<&str> = files.iter().map(|(name, _)| name.as_str()).collect();
    emitln!("wrote {}/: {}", written.display(), names.join(", "));
    if reasons.len() < results.len() {
        return Ok(());
    }
    if allow_unsafe {
        emitln!("warning: the .waypoints of unsafe tracks were written (--allow-unsafe)");
        return Ok(());
    }
    Err(Failure::Unsafe(reasons))
}

/// The track tables: text on stdout; with `--out`, the text, top views and convergence curves.
pub(super) fn repro_tracks(
    table: ReproTable,
    runs: Option<u64>,
    seed: u64,
    out: Option<&Path>,
) -> Result<(), Failure> {
    use agripath::repro::tracks;
    use agripath::track::files;
    let runs = agripath::request::track::check_runs(runs.unwrap_or(10))?;
    let label = "embedded track scenario";
    let key = match table {
        ReproTable::Seed000Table4 => "seed000-table4",
        ReproTable::Seed000Table5 => "seed000-table5",
        ReproTable::Seed002 => "seed002",
        _ => "spso",
    };
    let bar = progress_bar(tracks::total_runs(key, runs), "runs");
    let tick = || bar.inc(1);
    let (text, cases) = match table {
        ReproTable::Seed000Table4 => tracks::seed000_table4(runs, seed, &tick)
            .map_err(|fault| InputError::new(label, fault))?,
        other => {
            let (text, scenario, results) = match other {
                ReproTable::Seed000Table5 => tracks::seed000_table5(runs, seed, &tick),
                ReproTable::Seed002 => tracks::seed002(runs, seed, &tick),
                _ => tracks::spso(runs, seed, &tick),
            }
            .map_err(|fault| InputError::new(label, fault))?;
            (text, vec![(scenario, results)])
        }
    };
    bar.finish_and_clear();
    emit!("{text}");
    if let Some(out) = out {
        let mut written: Vec<(String, Vec<u8>)> = vec![("table.md".into(), text.into_bytes())];
        for (index, (scenario, results)) in cases.iter().enumerate() {
            let suffix = if cases.len() > 1 {
                format!("_{}", index + 1)
            } else {
                String::new()
            };
            for (name, bytes) in
                files::files(scenario, results, seed, false).map_err(Failure::Output)?
            {
                if name == "table.md" {
                    continue;
                }
                let (stem, extension) = name.rsplit_once('.').unwrap_or((&name, ""));
                written.push((format!("{stem}{suffix}.{extension}"), bytes));
            }
        }
        let folder = write_folder(out, &written)?;
        emitln!(
            "wrote {}/: table.md, track, report, top views, profiles, convergence",
            folder.display()
        );
    }
    Ok(())
}
