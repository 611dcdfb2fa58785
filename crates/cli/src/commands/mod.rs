//! One function per command: build the request, call the library, print what it returns.
//! Shared here: printing, how every command ends (print, write, verdict) and progress bars.

use std::path::Path;

use agripath::request::plan::FolderChoice;
use agripath::request::{self, terrain, write_folder, Failure, Outcome};
use agripath::{Fault, InputError};

use crate::args::{Arguments, Command, TerrainAction};

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

macro_rules! emitln {
    ($($argument:tt)*) => { emit_text(&(format!($($argument)*) + "\n")) };
}

mod plan;
mod runs;

pub fn run(arguments: Arguments) -> Result<(), Failure> {
    if let Some(out) = arguments.command.output_folder() {
        agripath::output::check_target(out)
            .and_then(|()| {
                agripath::output::check_inputs_outside(out, &arguments.command.input_files())
            })
            .map_err(|error| {
                // A path that cannot be a plan folder is the caller's input (status 2); a
                // folder the machine will not let us write in is not (status 1, as a full
                // disk is).
                if error.kind() == std::io::ErrorKind::InvalidInput {
                    Failure::from(InputError::new(
                        "--out",
                        Fault::Structure(error.to_string()),
                    ))
                } else {
                    Failure::Output(format!("--out: {error}"))
                }
            })?;
    }
    match arguments.command {
        Command::Demo { out, pdf } => plan::demo(
            &out,
            FolderChoice {
                allow_unsafe: false,
                pdf,
            },
        ),
        Command::Plan {
            inputs,
            options,
            allow_unsafe,
            pdf,
            out,
        } => plan::plan(&inputs, &options, FolderChoice { allow_unsafe, pdf }, &out),
        Command::Check { folder, inputs } => finish(None, request::check(&inputs, &folder)?),
        Command::Repro {
            table,
            runs,
            seed,
            variant,
            ablation,
            out,
        } => runs::repro(table, (runs, seed), (&variant, ablation), out.as_deref()),
        Command::Bench { action } => runs::bench(action),
        Command::View { folder, port, open } => view(&folder, port, open),
        Command::Grid { grid, out } => finish(Some(&out), grid.plan()?),
        Command::Track {
            track,
            allow_unsafe,
            out,
        } => runs::track(&track, allow_unsafe, &out),
        Command::Validate { inputs, json } => {
            emit_text(&request::validate(&inputs, json)?);
            Ok(())
        }
        Command::Terrain { action } => {
            emit_text(&match action {
                TerrainAction::Info {
                    terrain,
                    cell,
                    json,
                } => terrain::info(&terrain, cell, json)?,
                TerrainAction::Sample {
                    terrain,
                    coordinates,
                    lonlat,
                    cell,
                } => terrain::sample(&terrain, cell, &coordinates, lonlat)?,
                TerrainAction::Hillshade {
                    terrain,
                    out,
                    size,
                    exaggeration,
                    extent,
                    cell,
                } => terrain::write_hillshade(
                    &terrain,
                    cell,
                    size,
                    exaggeration,
                    extent.as_deref(),
                    &out,
                )?,
            });
            Ok(())
        }
    }
}

/// Ends a command as the library's outcome says: its text, then its folder when `out` is
/// given (the folder's report and what it holds), its warning, and exit 3 on failures.
fn finish(out: Option<&Path>, outcome: Outcome) -> Result<(), Failure> {
    emit_text(&outcome.text);
    if let (Some(out), Some(folder)) = (out, &outcome.folder) {
        let written = write_folder(out, &folder.files)?;
        emit_text(&folder.report);
        emit_text(&folder.wrote_line(&written));
    }
    if let Some(warning) = &outcome.warning {
        emitln!("{warning}");
    }
    outcome.verdict()
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
