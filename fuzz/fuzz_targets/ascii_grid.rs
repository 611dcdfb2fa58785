#![no_main]
//! Any text as an ESRI ASCII grid DEM.
use agripath::terrain::ascii_grid;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = ascii_grid::parse(text);
});
