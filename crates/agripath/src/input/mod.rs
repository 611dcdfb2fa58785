//! Reading what operators have: field files (GeoJSON, KML, KMZ) into a validated [`Farm`].
//!
//! Each format parser only turns its syntax into [`RawFeature`]s in the file's own
//! coordinates; [`farm::build`] then does everything once for all formats: choose the frame,
//! project, clean rings, validate, apply the size limits.

pub mod farm;
pub mod geojson;
pub mod kml;
pub mod kmz;

use std::path::Path;

use crate::error::{Fault, InputError};
use crate::files::extension_of;
use crate::model::Farm;

pub use farm::{RawFeature, RawGeometry};

/// How the coordinates of a field file are to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum CoordinateChoice {
    /// As the file says: GeoJSON is lon/lat unless it carries `"crs": "local"`; KML is lon/lat.
    #[default]
    FromFile,
    /// Metres in a local frame whatever the file says (`--crs local`).
    Local,
}

/// Reads a field file of any supported kind, chosen by its extension.
pub fn read_farm(path: &Path, choice: CoordinateChoice) -> Result<Farm, InputError> {
    let extension = extension_of(path);
    match extension.as_str() {
        "geojson" | "json" => geojson::read(path, choice),
        "kml" => kml::read_kml(path, choice),
        "kmz" => kmz::read_kmz(path, choice),
        other => Err(InputError::new(
            path,
            Fault::UnknownExtension {
                extension: other.to_string(),
                role: "fields",
                expected: ".geojson, .json, .kml or .kmz",
            },
        )),
    }
}
