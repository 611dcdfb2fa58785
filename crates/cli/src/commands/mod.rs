//! One file per command: build the request, call the library, print, write. Shared here:
//! the output helpers and the requests several commands build (scenario, coverage, order,
//! mission settings).

use std::path::{Path, PathBuf};

use agripath::bench::functions::{FunctionBench, FunctionTable};
use agripath::output::{write_file_atomically, StagedFolder};
use agripath::pipeline::plan_mission;
use agripath::scenario::Scenario;
use agripath::{Fault, InputError};

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
        } => track(
            &agripath::request::track::TrackRequest {
                scenario_path: scenario,
                task,
                algorithms: algorithm,
                runs,
                seed,
                encoding,
                evaluations,
                limits: agripath::track::SafetyLimits {
                    min_clearance_m: min_clearance,
                    vehicle_radius_m: vehicle_radius,
                },
            },
            allow_unsafe,
            &out,
        ),
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

fn view(folder: &Path, port: u16, open: bool) -> Result<(), Failure> {
    agripath::view::check_folder(folder)?;
    agripath::view::serve(folder, port, |url| {
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
