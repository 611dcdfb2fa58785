#![no_main]
//! Any text as an XYZ point cloud, gridded as `terrain info --cell 5` would.
use agripath::terrain::xyz;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(points) = xyz::parse_points(text) {
        let _ = xyz::grid_points(&points, Some(5.0));
        let _ = xyz::grid_points(&points, None);
    }
});
