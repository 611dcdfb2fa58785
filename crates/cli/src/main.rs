//! The `agripath` program: arguments → validated request → library calls → exit code.
//!
//! Exit status: 0 done; 2 bad input (one line naming the file and the fault, nothing
//! written); 3 the plan is not safe to fly (one line per failed preflight check, no mission
//! file written); 1 a failure writing outputs.

mod args;
mod commands;
mod view;

use std::process::ExitCode;

use clap::Parser;

/// Why a command stopped.
pub enum Failure {
    /// The user's input is wrong: exit 2.
    Input(agripath::InputError),
    /// Something outside the input failed (a disk full, a folder not writable): exit 1.
    Output(String),
    /// The mission as written does not fly safely: exit 3, one line per failure.
    Unsafe(Vec<String>),
}

impl From<agripath::InputError> for Failure {
    fn from(error: agripath::InputError) -> Self {
        Self::Input(error)
    }
}

fn main() -> ExitCode {
    let arguments = match args::Arguments::try_parse() {
        Ok(arguments) => arguments,
        Err(error) => {
            // Help and version go to stdout with status 0; usage errors are bad input.
            let code = if error.use_stderr() { 2 } else { 0 };
            let _ = error.print();
            return ExitCode::from(code);
        }
    };
    match commands::run(arguments) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Input(error)) => {
            eprintln!("agripath: error: {error}");
            ExitCode::from(2)
        }
        Err(Failure::Output(message)) => {
            eprintln!("agripath: error: {message}");
            ExitCode::from(1)
        }
        Err(Failure::Unsafe(lines)) => {
            for line in lines {
                eprintln!("agripath: unsafe: {line}");
            }
            eprintln!("agripath: error: not safe to fly as planned: no mission file was written (--allow-unsafe writes them)");
            ExitCode::from(3)
        }
    }
}
