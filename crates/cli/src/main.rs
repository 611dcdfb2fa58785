//! The `agripath` program: arguments → validated request → library calls → exit code.
//!
//! Exit status: 0 done; 2 bad input (one line naming the file and the fault, nothing
//! written); 3 the plan is not safe to fly (one line per failed preflight check, no mission
//! file written); 1 a failure writing outputs.

mod args;
mod commands;

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

use agripath::request::Failure;

/// Clap's message in one line: its first paragraph (the fault and, for missing arguments, the
/// indented list of them), without its `error:` prefix.
fn usage_error_line(text: &str) -> String {
    let paragraph: Vec<&str> = text
        .lines()
        .take_while(|line| !line.trim().is_empty())
        .map(str::trim)
        .collect();
    let mut line = paragraph
        .join(" ")
        .trim_start_matches("error:")
        .trim()
        .to_string();
    if let Some(tip) = text
        .lines()
        .map(str::trim)
        .find(|line| line.starts_with("tip:"))
    {
        line.push_str("; ");
        line.push_str(tip);
    }
    line
}

/// `--iters -5` reads -5 as the option's value, so the option's own check names it ("invalid
/// value '-5' for '--iters'"), not as an unknown flag '-5'.
fn negative_numbers_as_values(command: clap::Command) -> clap::Command {
    command
        .allow_negative_numbers(true)
        .mut_subcommands(negative_numbers_as_values)
}

fn main() -> ExitCode {
    let command = negative_numbers_as_values(args::Arguments::command());
    let parsed = command
        .try_get_matches()
        .and_then(|matches| args::Arguments::from_arg_matches(&matches));
    let arguments = match parsed {
        Ok(arguments) => arguments,
        Err(error) => {
            // Help and version go to stdout with status 0; usage errors are bad input, one
            // line like every other.
            if !error.use_stderr() {
                let _ = error.print();
                return ExitCode::SUCCESS;
            }
            eprintln!(
                "agripath: error: arguments: {} (see agripath --help)",
                usage_error_line(&error.render().to_string())
            );
            return ExitCode::from(2);
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
        Err(Failure::Unsafe(flight)) => {
            for line in flight.lines {
                eprintln!("agripath: unsafe: {line}");
            }
            eprintln!("agripath: error: {}", flight.closing);
            ExitCode::from(3)
        }
    }
}
