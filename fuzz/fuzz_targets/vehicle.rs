#![no_main]
//! Any text as a vehicle TOML file.
use agripath::model::Vehicle;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let _ = Vehicle::from_toml(text);
});
