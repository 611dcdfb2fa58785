//! Missions in the formats other programs load. One file per format; [`flight`] builds the
//! commands they all write.

pub mod csv;
pub mod flight;
pub mod kml;
pub mod mavlink;
pub mod plan_geojson;
pub mod qgc_plan;
pub mod wpl;
