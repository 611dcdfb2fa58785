//! Missions in the formats other programs load. One file per format.

pub mod plan_geojson;
