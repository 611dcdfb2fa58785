#![no_main]
//! Any text as a KML field file.
use std::path::Path;

use agripath::input::{kml, CoordinateChoice};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = kml::parse(Path::new("fuzz.kml"), text, CoordinateChoice::FromFile);
});
