#![no_main]
//! Any bytes as a GeoTIFF DEM.
use agripath::terrain::geotiff;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = geotiff::decode(bytes);
});
