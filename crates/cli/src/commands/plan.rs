//! `demo`, `plan`, `check` and `validate`: a coverage plan, its folder, its preflight.

use super::*;

pub(super) fn demo(out: &Path) -> Result<(), Failure> {
    let scenario = agripath::demo::scenario()?;
    // The seed's Table 8 start C1 (0, 0): a corner of S1.
    let mut settings = PlanSettings {
        start: Some([0.0, 0.0]),
        ..PlanSettings::default()
    };
    settings.mission.altitude =
        AltitudeReference::resolve(None, &scenario.terrain_spec, scenario.terrain_stated)
            .map_err(|fault| InputError::new(agripath::demo::FARM_LABEL, fault))?;
    let mission = plan_mission(&scenario, &settings)
        .map_err(|fault| InputError::new(agripath::demo::FARM_LABEL, fault))?;
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
    let mut rendered = render(scenario, mission).map_err(|fault| InputError::new(source, fault))?;
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
    let given = inputs.scenario.is_some() || inputs.fields.is_some();
    let scenario = if given {
        load_scenario(inputs)?
    } else {
        agripath::demo::scenario()?
    };
    let world = agripath::preflight::World {
        farm: &scenario.farm,
        terrain: scenario.terrain.as_ref(),
        vehicle: &scenario.vehicle,
    };
    let verdict = agripath::preflight::check_folder(&world, folder)
        .map_err(|fault| InputError::new(folder, fault))?;
    emitln!("{}", verdict.summary());
    for check in &verdict.checks {
        emitln!(
            "  {:<20} {:>5}  {} {} (limit {} {})",
            check.name,
            if check.passed { "ok" } else { "FAIL" },
            check.figure,
            check.unit,
            check.rule,
            check.limit
        );
    }
    if verdict.safe {
        Ok(())
    } else {
        Err(Failure::Unsafe(verdict.failures))
    }
}

/// The files written, in one short line: mission files per sortie are counted, not listed.
pub(super) fn files_summary(files: &[(String, Vec<u8>)]) -> String {
    let sorties = files
        .iter()
        .filter(|(name, _)| name.ends_with(".plan"))
        .count();
    let mut names: Vec<&str> = files
        .iter()
        .map(|(name, _)| name.as_str())
        .filter(|name| !name.starts_with("sortie_"))
        .collect();
    let per_sortie = format!("sortie_NN.plan and .waypoints for {sorties} sortie(s)");
    if sorties > 0 {
        names.push(&per_sortie);
    }
    names.join(", ")
}

pub(super) fn plan(
    inputs: &Inputs,
    coverage: &CoverageArgs,
    order: &OrderArgs,
    mission_args: &MissionArgs,
    out: &Path,
) -> Result<(), Failure> {
    let mut mission_settings = mission_settings(mission_args)?;
    let scenario = load_scenario(inputs)?;
    let requested = match mission_args.altitude.as_deref() {
        Some(key) => Some(key.parse::<AltitudeReference>().map_err(|why| {
            InputError::new(
                "--altitude",
                Fault::InvalidValue {
                    what: "--altitude".into(),
                    value: key.into(),
                    why,
                },
            )
        })?),
        None => None,
    };
    mission_settings.altitude =
        AltitudeReference::resolve(requested, &scenario.terrain_spec, scenario.terrain_stated)
            .map_err(|fault| InputError::new("--altitude", fault))?;
    let start = match &order.start {
        Some(values) if values.len() == 2 && values.iter().all(|value| value.is_finite()) => {
            let (x, y) = scenario
                .farm
                .coordinate_system
                .to_plan(values[0], values[1]);
            Some([x, y])
        }
        Some(values) => {
            return Err(InputError::new(
                "--start",
                Fault::InvalidValue {
                    what: "--start".into(),
                    value: format!("{values:?}"),
                    why: "expected two finite numbers X,Y".into(),
                },
            )
            .into())
        }
        None => None,
    };
    let settings = PlanSettings {
        coverage: coverage_settings(coverage)?,
        sequencer: sequencer(order)?,
        start,
        sorties: SortieSettings {
            planner: match order.sorties.as_str() {
                "none" => None,
                name => Some(name.parse().expect("clap allows only known planners")),
            },
            seed: order.seed,
        },
        mission: mission_settings,
    };
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
    let scenario = load_scenario(inputs)?;
    let summary = ScenarioSummary::of(&scenario);
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
