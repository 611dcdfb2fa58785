//! `track` and the track tables of `repro`: point-to-point tracks.

use super::*;

pub(super) fn bad_argument(flag: &str, value: &str, why: impl Into<String>) -> Failure {
    InputError::new(
        "arguments",
        Fault::InvalidValue {
            what: flag.into(),
            value: value.into(),
            why: why.into(),
        },
    )
    .into()
}

/// What `agripath track` was asked.
pub(super) struct TrackRequest<'a> {
    pub(super) scenario_path: &'a Path,
    pub(super) task: Option<&'a str>,
    pub(super) algorithms: &'a str,
    pub(super) runs: Option<u64>,
    pub(super) seed: u64,
    pub(super) encoding: Option<&'a str>,
    pub(super) evaluations: Option<u64>,
    pub(super) limits: agripath::track::SafetyLimits,
    pub(super) allow_unsafe: bool,
    pub(super) out: &'a Path,
}

pub(super) fn track(request: TrackRequest) -> Result<(), Failure> {
    use agripath::track::files::{self, PlannerRuns};
    use agripath::track::{plan, Encoding, Planner, TrackScenario, TrackSettings};
    let planners = request
        .algorithms
        .split(',')
        .map(|name| Planner::parse(name).map_err(|why| bad_argument("--algorithm", name, why)))
        .collect::<Result<Vec<_>, _>>()?;
    let encoding = match request.encoding {
        None => None,
        Some(text) => Some(Encoding::parse(text).ok_or_else(|| {
            bad_argument(
                "--encoding",
                text,
                "expected cartesian, cylindrical or spherical",
            )
        })?),
    };
    if request.evaluations == Some(0) {
        return Err(bad_argument("--evaluations", "0", "must be at least 1"));
    }
    let scenario = TrackScenario::read(request.scenario_path, request.task)?
        .with_limits(request.limits)
        .map_err(|fault| InputError::new(request.scenario_path, fault))?;
    let runs = request.runs.or(scenario.paper_runs).unwrap_or(5);
    if runs == 0 || runs > 1000 {
        return Err(bad_argument(
            "--runs",
            &runs.to_string(),
            "must be 1..=1000",
        ));
    }
    let bar = progress_bar(runs * planners.len() as u64, "runs");
    let mut results = Vec::new();
    for planner in planners {
        let settings = TrackSettings {
            planner,
            encoding,
            runs,
            seed: request.seed,
            evaluations: request.evaluations,
        };
        let runs = plan(&scenario, &settings, &|| bar.inc(1))
            .map_err(|fault| InputError::new(request.scenario_path, fault))?;
        results.push(PlannerRuns {
            planner,
            encoding: planner.encoding(&scenario, encoding),
            runs,
        });
    }
    bar.finish_and_clear();
    let files = files::files(&scenario, &results, request.seed, request.allow_unsafe)
        .map_err(Failure::Output)?;
    let written = write_folder(request.out, &files)?;
    emit!("{}", files::table(&scenario, &results));
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
    if request.allow_unsafe {
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
    let runs = runs.unwrap_or(10);
    if runs == 0 || runs > 1000 {
        return Err(bad_argument(
            "--runs",
            &runs.to_string(),
            "must be 1..=1000",
        ));
    }
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
