//! One function per command: build the request, call the library, print, write.

use std::path::{Path, PathBuf};

use agripath::input::CoordinateChoice;
use agripath::output::{write_file_atomically, StagedFolder};
use agripath::scenario::Scenario;
use agripath::scenario::{ScenarioParts, VehicleOverrides};
use agripath::summary::ScenarioSummary;
use agripath::terrain::hillshade::hillshade;
use agripath::terrain::{Extent, Terrain, TerrainSpec};
use agripath::{Fault, InputError};

use agripath::coverage::heading::HeadingObjective;
use agripath::coverage::CoverageSettings;
use agripath::mission::flight::{AltitudeReference, MissionSettings, SprayerCommand};
use agripath::pipeline::{plan_mission, render};
use agripath::sequence::ant_colony::AntColonySettings;
use agripath::sequence::local_search::LocalSearchSettings;
use agripath::sequence::Sequencer;
use agripath::settings::PlanSettings;
use agripath::sortie::SortieSettings;

use agripath::bench::functions::{FunctionBench, FunctionTable};

use crate::args::{
    Arguments, BenchAction, Command, CoverageArgs, Inputs, MissionArgs, OrderArgs, ReproTable,
    TerrainAction,
};
use crate::Failure;

/// Writes to stdout; a closed pipe (`agripath … | head`) ends the program quietly, as Unix
/// tools do, instead of panicking.
pub fn emit_text(text: &str) {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    if let Err(error) = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        if error.kind() == std::io::ErrorKind::BrokenPipe {
            std::process::exit(0);
        }
    }
}

macro_rules! emit {
    ($($argument:tt)*) => { emit_text(&format!($($argument)*)) };
}

macro_rules! emitln {
    () => { emit_text("\n") };
    ($($argument:tt)*) => { emit_text(&(format!($($argument)*) + "\n")) };
}

pub fn run(arguments: Arguments) -> Result<(), Failure> {
    if let Some(out) = arguments.command.output_folder() {
        agripath::output::check_target(out)
            .map_err(|error| InputError::new("--out", Fault::Structure(error.to_string())))?;
    }
    match arguments.command {
        Command::Demo { out } => demo(&out),
        Command::Plan {
            inputs,
            coverage,
            order,
            mission,
            out,
        } => plan(&inputs, &coverage, &order, &mission, &out),
        Command::Check { folder, inputs } => check(&folder, &inputs),
        Command::Repro {
            table,
            runs,
            seed,
            out,
        } => repro(table, runs, seed, out.as_deref()),
        Command::Bench { action } => bench(action),
        Command::View { folder, port, open } => view(&folder, port, open),
        Command::Grid {
            fields,
            field,
            method,
            swath_width,
            crs,
            seed,
            out,
        } => grid(
            &fields,
            field.as_deref(),
            &method,
            swath_width,
            crs.is_some(),
            seed,
            &out,
        ),
        Command::Track {
            scenario,
            task,
            algorithm,
            runs,
            seed,
            encoding,
            evaluations,
            min_clearance,
            vehicle_radius,
            allow_unsafe,
            out,
        } => track(TrackRequest {
            scenario_path: &scenario,
            task: task.as_deref(),
            algorithms: &algorithm,
            runs,
            seed,
            encoding: encoding.as_deref(),
            evaluations,
            limits: agripath::track::SafetyLimits {
                min_clearance_m: min_clearance,
                vehicle_radius_m: vehicle_radius,
            },
            allow_unsafe,
            out: &out,
        }),
        Command::Validate { inputs, json } => validate(&inputs, json),
        Command::Terrain { action } => terrain(action),
    }
}

fn output_failure(path: &Path, error: std::io::Error) -> Failure {
    Failure::Output(format!("{}: cannot write: {error}", path.display()))
}

fn demo(out: &Path) -> Result<(), Failure> {
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
fn write_plan(
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
fn check(folder: &Path, inputs: &Inputs) -> Result<(), Failure> {
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
fn files_summary(files: &[(String, Vec<u8>)]) -> String {
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

/// Writes every file into a staged folder and moves it into place.
fn write_folder<Name: AsRef<str>>(
    out: &Path,
    files: &[(Name, Vec<u8>)],
) -> Result<PathBuf, Failure> {
    let staged = StagedFolder::new(out).map_err(|error| output_failure(out, error))?;
    for (name, bytes) in files {
        staged
            .write(name.as_ref(), bytes)
            .map_err(|error| output_failure(out, error))?;
    }
    staged.commit().map_err(|error| output_failure(out, error))
}

fn coverage_settings(arguments: &CoverageArgs) -> Result<CoverageSettings, InputError> {
    if arguments.weights.len() != 2 {
        return Err(InputError::new(
            "--weights",
            Fault::Structure("expected two weights ω_N,ω_L".into()),
        ));
    }
    let heading = match arguments.heading.as_str() {
        "auto" => HeadingObjective::Seed {
            count_weight: arguments.weights[0],
            length_weight: arguments.weights[1],
        },
        "swaths" | "turns" => HeadingObjective::Swaths,
        "length" => HeadingObjective::Length,
        degrees => match degrees.parse::<f64>() {
            Ok(heading_deg) if heading_deg.is_finite() => HeadingObjective::Fixed {
                heading_deg: heading_deg.rem_euclid(180.0),
            },
            _ => {
                return Err(InputError::new(
                    "--heading",
                    Fault::InvalidValue {
                        what: "--heading".into(),
                        value: degrees.into(),
                        why: "expected auto, swaths, length or a number of degrees".into(),
                    },
                ))
            }
        },
    };
    let settings = CoverageSettings {
        headland_passes: arguments.headland,
        boundary_margin_m: arguments.boundary_margin,
        obstacle_margin_m: arguments.obstacle_margin,
        drape_spacing_m: arguments.drape_spacing,
        heading,
        refine_heading: !arguments.no_refine,
    };
    settings
        .validate()
        .map_err(|fault| InputError::new("arguments", fault))?;
    Ok(settings)
}

fn sequencer(order: &OrderArgs) -> Result<Sequencer, InputError> {
    // Checked whichever sequencer runs: a value no run could use is a mistake to report.
    for (flag, value) in [("--ants", order.ants), ("--batches", order.batches)] {
        if !(1..=100_000).contains(&value) {
            return Err(InputError::new(
                flag,
                Fault::InvalidValue {
                    what: flag.into(),
                    value: value.to_string(),
                    why: "must be 1..=100000".into(),
                },
            ));
        }
    }
    Ok(match order.sequencer.as_str() {
        "greedy" => Sequencer::Greedy,
        "aco" => Sequencer::AntColony(AntColonySettings {
            ants: order.ants,
            batches: order.batches,
            seed: order.seed,
            ..AntColonySettings::default()
        }),
        _ => Sequencer::Best(LocalSearchSettings {
            seed: order.seed,
            ..LocalSearchSettings::default()
        }),
    })
}

fn plan(
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

fn bad_argument(flag: &str, value: &str, why: impl Into<String>) -> Failure {
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
struct TrackRequest<'a> {
    scenario_path: &'a Path,
    task: Option<&'a str>,
    algorithms: &'a str,
    runs: Option<u64>,
    seed: u64,
    encoding: Option<&'a str>,
    evaluations: Option<u64>,
    limits: agripath::track::SafetyLimits,
    allow_unsafe: bool,
    out: &'a Path,
}

fn track(request: TrackRequest) -> Result<(), Failure> {
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

fn grid(
    fields: &Path,
    field: Option<&str>,
    method: &str,
    swath_width: Option<f64>,
    local: bool,
    seed: u64,
    out: &Path,
) -> Result<(), Failure> {
    use agripath::grid_cover::{boustrophedon, fewest_turns, hybrid_pso, PointGrid};
    let choice = if local {
        CoordinateChoice::Local
    } else {
        CoordinateChoice::FromFile
    };
    let farm = agripath::input::read_farm(fields, choice)?;
    let index = match field {
        None => 0,
        Some(name) => farm
            .fields
            .iter()
            .position(|f| f.name == name)
            .ok_or_else(|| {
                InputError::new(fields, Fault::Structure(format!("no field named '{name}'")))
            })?,
    };
    let from_file = std::fs::read_to_string(fields)
        .ok()
        .and_then(|text| serde_json::from_str::<serde_json::Value>(&text).ok())
        .and_then(|json| json["swath_width_m"].as_f64());
    let width = swath_width.or(from_file).unwrap_or(5.0);
    if !(width.is_finite() && width > 0.0) {
        return Err(InputError::new(
            "arguments",
            Fault::InvalidValue {
                what: "--swath-width".into(),
                value: width.to_string(),
                why: "must be a finite number above 0".into(),
            },
        )
        .into());
    }
    let grid =
        PointGrid::new(&farm, index, width).map_err(|fault| InputError::new(fields, fault))?;
    let started = std::time::Instant::now();
    let route = match method {
        "hpso" => {
            let settings = hybrid_pso::HpsoSettings {
                seed,
                ..Default::default()
            };
            hybrid_pso::plan(&grid, &settings).0
        }
        "baseline" => boustrophedon::plan(&grid),
        _ => fewest_turns::plan(&grid),
    };
    let runtime_s = started.elapsed().as_secs_f64();
    // The grid route's preflight: a move that crosses an obstacle is not flown.
    let crossings = route.measure(&grid).crossings;
    if crossings > 0 {
        return Err(Failure::Unsafe(vec![format!(
            "{crossings} move(s) of the {method} route cross an obstacle and no clear way round was found"
        )]));
    }
    let (files, title) =
        agripath::grid_cover::render(&farm, index, &grid, &route, method, runtime_s);
    let written = write_folder(out, &files)?;
    emitln!(
        "{title} ({} points, planned in {:.3} s)",
        grid.points.len(),
        runtime_s
    );
    emitln!(
        "wrote {}/: plan.geojson, report.json, plan.svg",
        written.display()
    );
    Ok(())
}

fn view(folder: &Path, port: u16, open: bool) -> Result<(), Failure> {
    if !folder.join("plan.html").is_file() {
        return Err(InputError::new(
            folder,
            Fault::Structure(
                "no plan.html here: give a folder written by `agripath plan` or `agripath demo`"
                    .into(),
            ),
        )
        .into());
    }
    crate::view::serve(folder, port, |url| {
        emitln!("serving {} at {url} (Ctrl-C to stop)", folder.display());
        if open {
            let opener = if cfg!(target_os = "macos") {
                "open"
            } else {
                "xdg-open"
            };
            if std::process::Command::new(opener).arg(url).spawn().is_err() {
                eprintln!("agripath: could not start {opener}; open {url} yourself");
            }
        }
    })
    .map_err(|error| Failure::Output(format!("cannot serve on 127.0.0.1:{port}: {error}")))
}

/// The mission-file options, checked.
fn mission_settings(arguments: &MissionArgs) -> Result<MissionSettings, InputError> {
    let invalid = |what: &str, value: String, why: &str| {
        InputError::new(
            "arguments",
            Fault::InvalidValue {
                what: what.into(),
                value,
                why: why.into(),
            },
        )
    };
    let mut settings = MissionSettings {
        sprayer: arguments
            .sprayer
            .parse::<SprayerCommand>()
            .map_err(|why| invalid("--sprayer", arguments.sprayer.clone(), &why))?,
        ..MissionSettings::default()
    };
    if !(arguments.terrain_tolerance.is_finite() && arguments.terrain_tolerance > 0.0) {
        return Err(invalid(
            "--terrain-tolerance",
            arguments.terrain_tolerance.to_string(),
            "must be a finite number above 0",
        ));
    }
    settings.terrain_tolerance_m = arguments.terrain_tolerance;
    if let Some(origin) = &arguments.origin {
        let valid = origin.len() == 2
            && (-180.0..=180.0).contains(&origin[0])
            && (-80.0..=84.0).contains(&origin[1]);
        if !valid {
            return Err(invalid(
                "--origin",
                format!("{origin:?}"),
                "expected LON,LAT with longitude in -180..180 and latitude in -80..84",
            ));
        }
        settings.local_origin = (origin[0], origin[1]);
    }
    Ok(settings)
}

/// A progress bar on stderr for `total` steps (hidden when stderr is not a terminal).
fn progress_bar(total: u64, what: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{msg} [{bar:40}] {pos}/{len} runs, {elapsed} (eta {eta})",
        )
        .expect("a valid template")
        .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}

/// Runs a function bench with a progress bar.
fn run_function_bench(settings: &FunctionBench) -> Result<FunctionTable, Failure> {
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

fn bench(action: BenchAction) -> Result<(), Failure> {
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

fn repro(
    table: ReproTable,
    runs: Option<u64>,
    seed: u64,
    out: Option<&Path>,
) -> Result<(), Failure> {
    match table {
        ReproTable::Seed000Table2 => {
            let settings = agripath::repro::seed000_table2::settings(runs.unwrap_or(50), seed);
            let table = run_function_bench(&settings)?;
            let comparison = agripath::repro::seed000_table2::comparison(&table);
            emit!("{comparison}");
            if let Some(out) = out {
                let mut files = table.files();
                files.push(("comparison.md".into(), comparison.into_bytes()));
                let named: Vec<(&str, Vec<u8>)> = files
                    .iter()
                    .map(|(name, bytes)| (name.as_str(), bytes.clone()))
                    .collect();
                let written = write_folder(out, &named)?;
                emitln!(
                    "wrote {}/: comparison.md, table.md, table.csv, convergence_*.svg",
                    written.display()
                );
            }
            Ok(())
        }
        ReproTable::Seed000Table4
        | ReproTable::Seed000Table5
        | ReproTable::Seed002
        | ReproTable::Spso => repro_tracks(table, runs, seed, out),
        ReproTable::Seed003Table4 => {
            use agripath::repro::seed003_table4::{case, to_text, StripSlope};
            use agripath::terrain::Flat;
            emitln!("Seed 003, Tables 4 and 5: sorties on the 700 m × 100 m strip, ours (paper)");
            let sloped = case(&StripSlope, seed)?;
            emitln!();
            emit!("{}", to_text(&sloped));
            let flat = case(&Flat::new(0.0), seed)?;
            emitln!();
            emitln!("The same on flat ground (the paper's 2D case):");
            emit!("{}", to_text(&flat));
            emitln!();
            emitln!("Non-spray time = round trips + max(battery swap, refill) per return (the turns, equal for every");
            emitln!("plan, are left out as in the paper's Table 4). 'exact' is ours: the optimal returns for this route.");
            Ok(())
        }
        ReproTable::Seed004 => {
            use agripath::grid_cover::hybrid_pso::HpsoSettings;
            use agripath::repro::seed004;
            let settings = HpsoSettings {
                seed,
                ..HpsoSettings::default()
            };
            emitln!("Seed 004: turns on the six fields with obstacles (grid of 5 m path points)");
            let rows = seed004::table(&settings)?;
            let text = seed004::to_text(&rows, &settings);
            emit!("{text}");
            emitln!();
            emitln!("'1-direction': the best single-direction boustrophedon, 2 × (runs − 1); 'lower bd': no route of");
            emitln!("axis-parallel legs can turn fewer times (König cover of the points by row and column runs, − 1).");
            emitln!("'!' marks a route that misses a point or crosses an obstacle.");
            if let Some(out) = out {
                let mut files: Vec<(String, Vec<u8>)> =
                    vec![("seed004.txt".into(), text.into_bytes())];
                for row in &rows {
                    files.push((
                        format!("{}.svg", row.name),
                        seed004::map_svg(row).into_bytes(),
                    ));
                }
                let written = write_folder(out, &files)?;
                emitln!(
                    "wrote {}/: seed004.txt and a map per field",
                    written.display()
                );
            }
            Ok(())
        }
        ReproTable::Seed001Table8 => {
            let scenario = agripath::demo::scenario()?;
            emitln!("Seed 001, Table 8: transfer path length (m), paper beside agripath");
            let table = agripath::repro::seed001_table8::table8(&scenario, seed as usize)
                .map_err(|fault| InputError::new(agripath::demo::FARM_LABEL, fault))?;
            emit!("{}", table.to_text());
            Ok(())
        }
        ReproTable::Seed001Table7 => {
            let scenario = agripath::demo::scenario()?;
            let references: serde_json::Value = serde_json::from_str(agripath::demo::FARM_GEOJSON)
                .expect("the embedded farm is JSON");
            emitln!("Seed 001, Table 7: paper beside agripath");
            for (width, paper) in [(5.0, &references), (6.5, &serde_json::Value::Null)] {
                let table = agripath::repro::seed001_table7::table7(&scenario, paper, width)
                    .map_err(|fault| InputError::new(agripath::demo::FARM_LABEL, fault))?;
                emitln!();
                emit!("{}", table.to_text());
            }
            emitln!();
            emitln!("The paper gives figures for w = 5 m only. 'ΔL' is ours against the paper's length; '0.1°'");
            emitln!("is our refinement of E; coverage is of the sprayable area (seed layout vs one edge pass).");
            emitln!("S4 holds the 3 m plateau: at the paper's 87° we find its 47 swaths and its length to 0.03 %,");
            emitln!("but our analytic plateau (5 m rim) drapes 1° to 45 swaths and 7118 m, a lower E (0.064 vs 0.079);");
            emitln!("the paper's 20 m DEM is not published, and L varies by ±1 % between neighbouring headings there.");
            Ok(())
        }
    }
}

fn load_scenario(inputs: &Inputs) -> Result<Scenario, InputError> {
    let overrides = VehicleOverrides {
        swath_width_m: inputs.swath_width,
        spray_height_m: inputs.spray_height,
        safe_height_m: inputs.safe_height,
    };
    let terrain = inputs
        .terrain
        .as_deref()
        .map(TerrainSpec::from_argument)
        .transpose()?;
    let coordinates = match inputs.crs.as_deref() {
        Some("local") => CoordinateChoice::Local,
        _ => CoordinateChoice::FromFile,
    };
    match (&inputs.scenario, &inputs.fields) {
        (Some(path), None) => {
            if inputs.terrain.is_some() || inputs.vehicle.is_some() || inputs.crs.is_some() {
                return Err(InputError::new(
                    path,
                    Fault::Structure(
                        "with a scenario file, set terrain, vehicle and crs in the file (only --swath-width, --spray-height and --safe-height override it)".into(),
                    ),
                ));
            }
            Scenario::from_file(path, overrides, inputs.allow_overlap)
        }
        (None, Some(fields)) => Scenario::load(ScenarioParts {
            name: None,
            fields: fields.clone(),
            coordinates,
            terrain,
            terrain_base: PathBuf::new(),
            vehicle_file: inputs.vehicle.clone(),
            vehicle_table: None,
            overrides,
            allow_overlap: inputs.allow_overlap,
        }),
        (Some(path), Some(_)) => Err(InputError::new(
            path,
            Fault::Structure("give a scenario file or --fields, not both".into()),
        )),
        (None, None) => Err(InputError::new(
            "arguments",
            Fault::Structure("give a scenario file or --fields FILE".into()),
        )),
    }
}

fn validate(inputs: &Inputs, json: bool) -> Result<(), Failure> {
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

fn load_terrain(argument: &str, cell: Option<f64>) -> Result<Box<dyn Terrain>, InputError> {
    let mut spec = TerrainSpec::from_argument(argument)?;
    if let TerrainSpec::File { cell_m, .. } = &mut spec {
        *cell_m = cell;
    }
    spec.load(Path::new(""), agripath::model::CoordinateSystem::Local)
}

fn terrain(action: TerrainAction) -> Result<(), Failure> {
    match action {
        TerrainAction::Info {
            terrain,
            cell,
            json,
        } => {
            let model = load_terrain(&terrain, cell)?;
            let extent = model.extent();
            let range = extent.and_then(|extent| model.height_range_m(extent));
            if json {
                let value = serde_json::json!({
                    "terrain": terrain,
                    "description": model.describe(),
                    "extent": extent.map(|e| [e.min_x, e.min_y, e.max_x, e.max_y]),
                    "height_range_m": range.map(|(low, high)| [low, high]),
                });
                emitln!(
                    "{}",
                    serde_json::to_string_pretty(&value).expect("JSON value")
                );
            } else {
                emitln!("{}", model.describe());
                match extent {
                    Some(e) => emitln!(
                        "extent x {:.3}..{:.3}, y {:.3}..{:.3} ({:.1} × {:.1})",
                        e.min_x,
                        e.max_x,
                        e.min_y,
                        e.max_y,
                        e.width(),
                        e.height()
                    ),
                    None => emitln!("extent unbounded"),
                }
                if let Some((low, high)) = range {
                    emitln!("heights {low:.3}..{high:.3} m");
                }
            }
            Ok(())
        }
        TerrainAction::Sample {
            terrain,
            coordinates,
            cell,
        } => {
            if coordinates.len() % 2 != 0 {
                return Err(InputError::new(
                    "arguments",
                    Fault::Structure("coordinates come in X Y pairs".into()),
                )
                .into());
            }
            let model = load_terrain(&terrain, cell)?;
            let mut lines = Vec::new();
            for pair in coordinates.chunks(2) {
                let height = model
                    .height_m(pair[0], pair[1])
                    .map_err(|error| InputError::new(&terrain, Fault::Terrain(error)))?;
                lines.push(format!("{} {} {}", pair[0], pair[1], height));
            }
            emitln!("{}", lines.join("\n"));
            Ok(())
        }
        TerrainAction::Hillshade {
            terrain,
            out,
            size,
            exaggeration,
            extent,
            cell,
        } => {
            if !(2..=16384).contains(&size) {
                return Err(InputError::new(
                    "--size",
                    Fault::InvalidValue {
                        what: "--size".into(),
                        value: size.to_string(),
                        why: "must be 2..16384 pixels".into(),
                    },
                )
                .into());
            }
            if !(exaggeration.is_finite() && exaggeration > 0.0) {
                return Err(InputError::new(
                    "--exaggeration",
                    Fault::InvalidValue {
                        what: "--exaggeration".into(),
                        value: exaggeration.to_string(),
                        why: "must be a number above 0".into(),
                    },
                )
                .into());
            }
            let model = load_terrain(&terrain, cell)?;
            let area = match (extent, model.extent()) {
                (Some(values), _) if values.len() != 4 => {
                    return Err(InputError::new(
                        "--extent",
                        Fault::Structure("expected MIN_X,MIN_Y,MAX_X,MAX_Y".into()),
                    )
                    .into())
                }
                (Some(values), _) => {
                    let [min_x, min_y, max_x, max_y] = [values[0], values[1], values[2], values[3]];
                    if !(values.iter().all(|v| v.is_finite()) && max_x > min_x && max_y > min_y) {
                        return Err(InputError::new(
                            "--extent",
                            Fault::Structure(
                                "expected MIN_X,MIN_Y,MAX_X,MAX_Y with MAX above MIN".into(),
                            ),
                        )
                        .into());
                    }
                    Extent {
                        min_x,
                        min_y,
                        max_x,
                        max_y,
                    }
                }
                (None, Some(extent)) => extent,
                (None, None) => {
                    return Err(InputError::new(
                        &terrain,
                        Fault::Structure(
                            "this terrain is unbounded: give --extent MIN_X,MIN_Y,MAX_X,MAX_Y"
                                .into(),
                        ),
                    )
                    .into())
                }
            };
            let shaded = hillshade(model.as_ref(), area, size, exaggeration);
            write_file_atomically(&out, &shaded.to_png())
                .map_err(|error| output_failure(&out, error))?;
            emitln!(
                "wrote {} ({} × {} pixels)",
                out.display(),
                shaded.width,
                shaded.height
            );
            Ok(())
        }
    }
}

/// The track tables: text on stdout; with `--out`, the text, top views and convergence curves.
fn repro_tracks(
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
