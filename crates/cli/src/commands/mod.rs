//! One file per command: build the request, call the library, print, write. Shared here:
//! the output helpers and the requests several commands build (scenario, coverage, order,
//! mission settings).

use std::path::{Path, PathBuf};

use agripath::input::CoordinateChoice;
use agripath::output::{write_file_atomically, StagedFolder};
use agripath::scenario::{Scenario, ScenarioParts, VehicleOverrides};
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

mod bench;
mod grid;
mod plan;
mod repro;
mod terrain;
mod track;

use bench::*;
use grid::*;
use plan::*;
use repro::*;
use terrain::*;
use track::*;

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
    let heading = HeadingObjective::parse(
        &arguments.heading,
        [arguments.weights[0], arguments.weights[1]],
    )
    .map_err(|why| {
        InputError::new(
            "--heading",
            Fault::InvalidValue {
                what: "--heading".into(),
                value: arguments.heading.clone(),
                why,
            },
        )
    })?;
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
