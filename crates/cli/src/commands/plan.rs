//! `demo`, `plan`, `check` and `validate`: a coverage plan, its folder, its preflight.

use super::*;
use agripath::request::plan::{files_summary, plan_demo};

pub(super) fn demo(out: &Path) -> Result<(), Failure> {
    let (scenario, mission) = plan_demo()?;
    write_plan(
        out,
        &scenario,
        &mission,
        false,
        Path::new(agripath::demo::FARM_LABEL),
    )
}

/// Renders a plan, flies its mission files in the preflight check, and writes the folder:
/// every file when safe (or `allow_unsafe`), else all but the mission files, and exit 3.
pub(super) fn write_plan(
    out: &Path,
    scenario: &Scenario,
    mission: &agripath::pipeline::PlannedMission,
    allow_unsafe: bool,
    source: &Path,
) -> Result<(), Failure> {
    let mut rendered = agripath::pipeline::render(scenario, mission)
        .map_err(|fault| InputError::new(source, fault))?;
    rendered.keep_files_to_write(allow_unsafe);
    let files = &rendered.files;
    let written = write_folder(out, files)?;
    emit!("{}", rendered.report.to_text());
    emitln!("wrote {}/: {}", written.display(), files_summary(files));
    if rendered.verdict.safe {
        return Ok(());
    }
    if allow_unsafe {
        emitln!("warning: the mission files were written although the preflight failed (--allow-unsafe)");
        return Ok(());
    }
    Err(Failure::Unsafe(rendered.verdict.failures.clone()))
}

/// `agripath check DIR`: the preflight on a plan folder as it is now.
pub(super) fn check(folder: &Path, inputs: &Inputs) -> Result<(), Failure> {
    let verdict = agripath::request::check_folder(&inputs.request(), folder)?;
    emit!("{}", verdict.to_text());
    if verdict.safe {
        Ok(())
    } else {
        Err(Failure::Unsafe(verdict.failures))
    }
}

pub(super) fn plan(
    inputs: &Inputs,
    coverage: &CoverageArgs,
    order: &OrderArgs,
    mission_args: &MissionArgs,
    out: &Path,
) -> Result<(), Failure> {
    let options = crate::args::plan_options(coverage, order, mission_args);
    let (scenario, settings) = options.load(&inputs.request())?;
    // A spinner for big farms (heading scans, ordering, sorties, mission files).
    let spinner = indicatif::ProgressBar::new_spinner();
    spinner.set_message(format!("planning {} field(s)", scenario.farm.fields.len()));
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let mission = plan_mission(&scenario, &settings)
        .map_err(|fault| InputError::new(&scenario.farm.source, fault))?;
    spinner.set_message("writing mission files, checking them as flown, maps");
    let result = write_plan(
        out,
        &scenario,
        &mission,
        mission_args.allow_unsafe,
        &scenario.farm.source,
    );
    spinner.finish_and_clear();
    result
}

pub(super) fn validate(inputs: &Inputs, json: bool) -> Result<(), Failure> {
    let scenario = inputs.request().load()?;
    let summary = agripath::summary::ScenarioSummary::of(&scenario);
    if json {
        emitln!(
            "{}",
            serde_json::to_string_pretty(&summary).expect("a summary serialises")
        );
    } else {
        emit!("{}", summary.to_text());
        emitln!("valid");
    }
    Ok(())
}
