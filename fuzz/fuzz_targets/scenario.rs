#![no_main]
//! Any text as a scenario TOML file (written to a temporary file, as the CLI reads it; the
//! paths it names are relative to the repository's data folder, so real fields and DEMs load).
use std::path::PathBuf;

use agripath::scenario::{Scenario, VehicleOverrides};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/scenarios"))
        .join(format!(".fuzz-{}.toml", std::process::id()));
    if std::fs::write(&path, text).is_ok() {
        let _ = Scenario::from_file(&path, VehicleOverrides::default(), false);
        let _ = std::fs::remove_file(&path);
    }
});
