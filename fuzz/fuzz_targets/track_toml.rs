#![no_main]
//! Any text as a track scenario .toml file (written beside the shipped ones, so the DEM paths
//! they name resolve to the real Christmas Island DEM).
use std::path::PathBuf;

use agripath::track::TrackScenario;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let path = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/tracks"))
        .join(format!(".fuzz-{}.toml", std::process::id()));
    if std::fs::write(&path, text).is_ok() {
        let _ = TrackScenario::read(&path, Some("II"));
        let _ = std::fs::remove_file(&path);
    }
});
