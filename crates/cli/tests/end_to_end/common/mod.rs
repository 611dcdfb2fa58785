//! Helpers the end-to-end suites share (each suite uses some of them).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A file of the repository's `data/` folder.
pub fn data(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
}

/// An empty scratch folder for test `name` of `suite`, under cargo's `target/tmp`: the next
/// run empties it again, so runs leave one set of folders behind, where `cargo clean` goes.
pub fn scratch(suite: &str, name: &str) -> PathBuf {
    let folder = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("agripath-{suite}-{name}"));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// The standard output of a run that must have succeeded (its stderr in the failure).
pub fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "status {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

/// Runs the program with `arguments` in `directory`.
pub fn agripath(arguments: &[&str], directory: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agripath"))
        .args(arguments)
        .current_dir(directory)
        .output()
        .unwrap()
}
