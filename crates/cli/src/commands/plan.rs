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
    // The library's stages, and its counts of fields laid out and sorties flown, as they come.
    let shown = spinner.clone();
    agripath::progress::set_sink(Some(Box::new(move |stage: &str| {
        shown.set_message(stage.to_string());
    })));
    let result = agripath::pipeline::plan_mission(&scenario, &settings)
        .map_err(|fault| agripath::request::plan::planning_error(&scenario, &settings, fault))
        .and_then(|mission| outcome(&scenario, &mission, files, &scenario.farm.source));
    agripath::progress::set_sink(None);
    spinner.finish_and_clear();
    finish(Some(out), result?)
}
