//! Missions in the formats other programs load. One file per format; [`flight`] builds the
//! commands they all write.

pub mod csv;
pub mod flight;
pub mod kml;
pub mod mavlink;
pub mod plan_geojson;
pub mod qgc_plan;
pub mod wpl;

/// The name of a sortie's mission files without their extension (`sortie_01` for the first,
/// sortie index 0): the name `.plan`, `.waypoints`, the preflight and the report give it.
pub fn sortie_file_stem(sortie_index: usize) -> String {
    format!("sortie_{:02}", sortie_index + 1)
}
