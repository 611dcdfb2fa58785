#![no_main]
//! Any bytes as a KMZ (zip) field file.
use std::path::Path;

use agripath::input::{kml, CoordinateChoice};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = kml::parse_kmz(Path::new("fuzz.kmz"), bytes.to_vec(), CoordinateChoice::FromFile);
});
