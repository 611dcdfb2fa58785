//! Typed errors for everything a user hands to agripath.
//!
//! Every fault in an input is an [`InputError`]: the file it came from, where in the file
//! (a feature, a key, a pixel), and the [`Fault`]. Its `Display` is the one line the CLI
//! prints before exiting with status 2.

use std::fmt;
use std::path::{Path, PathBuf};

/// A fault in one input file (or command-line value), with its place.
#[derive(Debug, thiserror::Error)]
pub struct InputError {
    /// The file (or `--flag`) the fault was found in.
    pub file: PathBuf,
    /// Where in the file, when known: "feature 3 (S4)", "row 12", "key vehicle.swath_width_m".
    pub place: Option<String>,
    /// What is wrong.
    pub fault: Fault,
}

impl fmt::Display for InputError {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{}", self.file.display())?;
        if let Some(place) = &self.place {
            write!(formatter, ": {place}")?;
        }
        write!(formatter, ": {}", self.fault)
    }
}

impl InputError {
    pub fn new(file: impl AsRef<Path>, fault: Fault) -> Self {
        Self {
            file: file.as_ref().to_path_buf(),
            place: None,
            fault,
        }
    }

    /// Adds (or prefixes) the place in the file where the fault lies.
    pub fn at(mut self, place: impl Into<String>) -> Self {
        let place = place.into();
        self.place = Some(match self.place.take() {
            Some(inner) => format!("{place}: {inner}"),
            None => place,
        });
        self
    }
}

/// What is wrong with an input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Fault {
    #[error("cannot read the file: {0}")]
    Unreadable(String),
    #[error("the file is empty")]
    Empty,
    #[error("not valid JSON: {0}")]
    Json(String),
    #[error("not valid TOML: {0}")]
    Toml(String),
    #[error("not valid KML: {0}")]
    Kml(String),
    #[error("not a readable GeoTIFF: {0}")]
    Tiff(String),
    #[error("unsupported file type '{0}' (expected .geojson, .json, .kml or .kmz for fields; .tif, .tiff, .asc, .xyz or .csv for terrain)")]
    UnknownExtension(String),
    /// The file parses but its structure is not what the format requires.
    #[error("{0}")]
    Structure(String),
    #[error("coordinate is not a finite number")]
    NonFinite,
    #[error("longitude/latitude ({lon}, {lat}) is out of range (longitudes lie in -180..180, latitudes in -90..90)")]
    OutOfRange { lon: f64, lat: f64 },
    #[error("ring has fewer than 3 distinct points")]
    DegenerateRing,
    #[error("ring is not closed (first and last positions differ)")]
    UnclosedRing,
    #[error("ring has zero area")]
    ZeroArea,
    #[error("boundary intersects itself near ({x:.3}, {y:.3})")]
    SelfIntersection { x: f64, y: f64 },
    #[error("hole {hole} crosses the outer boundary near ({x:.3}, {y:.3})")]
    HoleCrossesShell { hole: usize, x: f64, y: f64 },
    #[error("hole {hole} lies outside the outer boundary")]
    HoleOutsideShell { hole: usize },
    #[error("holes {first} and {second} overlap")]
    HolesOverlap { first: usize, second: usize },
    #[error("no field polygons found")]
    NoFields,
    #[error("{what} = {value} is invalid: {why}")]
    InvalidValue {
        what: String,
        value: String,
        why: String,
    },
    #[error("too large: {0}")]
    TooLarge(String),
    #[error("{0}")]
    Terrain(#[from] TerrainError),
}

/// A number as a message shows it: `1e308` as written, not as 309 digits.
pub fn figure(value: f64) -> String {
    if value != 0.0 && !(1e-3..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        value.to_string()
    }
}

/// A terrain query that cannot be answered.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum TerrainError {
    #[error("point ({x:.2}, {y:.2}) is outside the terrain model")]
    Outside { x: f64, y: f64 },
    #[error("the terrain model has no data at ({x:.2}, {y:.2})")]
    NoData { x: f64, y: f64 },
}
