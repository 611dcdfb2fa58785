#![no_main]
//! Any text as a GeoJSON field file: an error or a farm, never a panic or a hang.
use std::path::Path;

use agripath::input::{geojson, CoordinateChoice};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    for choice in [CoordinateChoice::FromFile, CoordinateChoice::Local] {
        let _ = geojson::parse(Path::new("fuzz.geojson"), text, choice);
    }
});
