//! `demo` and `plan`: a coverage plan, its folder, its preflight.

use std::path::Path;

use agripath::request::plan::{outcome, plan_demo, FolderChoice};
use agripath::request::Failure;

use super::finish;
use agripath::request::plan::PlanOptions;
use agripath::request::ScenarioInputs;

pub(super) fn demo(out: &Path, files: FolderChoice) -> Result<(), Failure> {
    let (scenario, mission) = plan_demo()?;
    let source = Path::new(agripath::demo::FARM_LABEL);
    finish(Some(out), outcome(&scenario, &mission, files, source)?)
}

pub(super) fn plan(
    inputs: &ScenarioInputs,
    options: &PlanOptions,
    files: FolderChoice,
    out: &Path,
) -> Result<(), Failure> {
    let (scenario, settings) = options.load(inputs)?;
    // A spinner for big farms (heading scans, ordering, sorties, mission files).
    let spinner = indicatif::ProgressBar::new_spinner();
    spinner.set_message(format!("planning {} field(s)", scenario.farm.fields.len()));
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let mission = agripath::pipeline::plan_mission(&scenario, &settings)
        .map_err(|fault| agripath::request::plan::planning_error(&scenario, &settings, fault))?;
    spinner.set_message("writing mission files, checking them as flown, maps");
    let source = &scenario.farm.source;
    let result = outcome(&scenario, &mission, files, source)
        .map_err(Failure::from)
        .and_then(|outcome| finish(Some(out), outcome));
    spinner.finish_and_clear();
    result
}
