//! `demo` and `plan`: a coverage plan, its folder, its preflight.

use std::path::Path;

use agripath::request::plan::{outcome, plan_demo};
use agripath::request::Failure;

use super::finish;
use crate::args::{CoverageArgs, Inputs, MissionArgs, OrderArgs};

pub(super) fn demo(out: &Path) -> Result<(), Failure> {
    let (scenario, mission) = plan_demo()?;
    let source = Path::new(agripath::demo::FARM_LABEL);
    finish(Some(out), outcome(&scenario, &mission, false, source)?)
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
    let mission = agripath::pipeline::plan_mission(&scenario, &settings)
        .map_err(|fault| agripath::InputError::new(&scenario.farm.source, fault))?;
    spinner.set_message("writing mission files, checking them as flown, maps");
    let source = &scenario.farm.source;
    let result = outcome(&scenario, &mission, mission_args.allow_unsafe, source)
        .map_err(Failure::from)
        .and_then(|outcome| finish(Some(out), outcome));
    spinner.finish_and_clear();
    result
}
