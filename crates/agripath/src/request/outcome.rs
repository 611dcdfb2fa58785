//! What a command ends with, for any program that runs the library's requests: the text to
//! print, the folder to write, a warning, and the preflight failures that stop it. The order
//! is fixed here so that every program prints and writes in the same order as `agripath`.

use std::path::{Path, PathBuf};

use crate::output::StagedFolder;
use crate::InputError;

/// Why a request stopped.
#[derive(Debug)]
pub enum Failure {
    /// The user's input is wrong (`agripath` exits 2).
    Input(InputError),
    /// Something outside the input failed, a disk full or a folder not writable (exit 1).
    Output(String),
    /// The mission as written does not fly safely (exit 3).
    Unsafe(UnsafeFlight),
}

/// A flight that is not safe: one line per failure, then the line that says what became of
/// the files (`plan` wrote none, `check` read them).
#[derive(Debug)]
pub struct UnsafeFlight {
    /// One line per failure.
    pub lines: Vec<String>,
    /// The last line.
    pub closing: &'static str,
}

impl From<InputError> for Failure {
    fn from(error: InputError) -> Self {
        Self::Input(error)
    }
}

/// The last line `agripath plan` prints after the failures of a mission not safe to fly.
pub const UNSAFE_CLOSING: &str =
    "not safe to fly as planned: no mission file was written (--allow-unsafe writes them)";
/// The last line `agripath check` prints after the failures of the files it read.
pub const CHECK_CLOSING: &str =
    "not safe to fly: the mission files fail the preflight (re-plan, or fix them and check again)";

/// A finished request: print `text`, then write `folder` (when the caller was given one),
/// print its report and what it holds, then `warning`; `failures` stop it after all that.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Printed first, before anything is written.
    pub text: String,
    /// The folder the request writes, if it writes one.
    pub folder: Option<FolderFiles>,
    /// Printed last, when the request goes on although the preflight failed.
    pub warning: Option<String>,
    /// The preflight's failures: the request ends unsafe once the rest is done.
    pub failures: Vec<String>,
    /// The line printed after the failures, when not [`UNSAFE_CLOSING`].
    pub closing: Option<&'static str>,
}

/// The files of an output folder and what is printed once they are written.
#[derive(Debug, Default)]
pub struct FolderFiles {
    /// Every file, by name.
    pub files: Vec<(String, Vec<u8>)>,
    /// Printed once the folder is written, before the line saying what it holds.
    pub report: String,
    /// What the folder holds, in a few words, for the line `wrote DIR/: …`.
    pub contents: String,
}

impl Outcome {
    /// Unsafe when there are failures, with the closing line; else done.
    pub fn verdict(&self) -> Result<(), Failure> {
        if self.failures.is_empty() {
            Ok(())
        } else {
            Err(Failure::Unsafe(UnsafeFlight {
                lines: self.failures.clone(),
                closing: self.closing.unwrap_or(UNSAFE_CLOSING),
            }))
        }
    }

    /// An outcome that only prints `text`.
    pub fn text(text: String) -> Self {
        Self {
            text,
            ..Self::default()
        }
    }

    /// An outcome that prints `text` and may write `files`, summed up as `contents`.
    pub fn with_folder(text: String, files: Vec<(String, Vec<u8>)>, contents: &str) -> Self {
        Self {
            text,
            folder: Some(FolderFiles {
                files,
                report: String::new(),
                contents: contents.into(),
            }),
            ..Self::default()
        }
    }
}

impl FolderFiles {
    /// The line printed once the folder is written to `written`.
    pub fn wrote_line(&self, written: &Path) -> String {
        format!("wrote {}/: {}\n", written.display(), self.contents)
    }
}

/// A failure to write `path`, as a [`Failure::Output`].
pub fn output_failure(path: &Path, error: std::io::Error) -> Failure {
    Failure::Output(format!("{}: cannot write: {error}", path.display()))
}

/// Writes every file into a staged folder and moves it into place at `out`, so that a
/// failure leaves any earlier folder there as it was.
pub fn write_folder<Name: AsRef<str>>(
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
