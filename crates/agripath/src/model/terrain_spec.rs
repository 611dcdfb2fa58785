//! Which terrain a plan is to use, as written down (a scenario's `[terrain]`, a field file's
//! `terrain` member, `--terrain`): a description only. `terrain::TerrainSpec::load` turns it
//! into a height model; this module knows nothing of rasters.

use std::path::PathBuf;

use serde::Deserialize;

use crate::error::{Fault, InputError};

/// Which terrain to use, as written in a scenario file, a field file's `terrain` member or
/// a `--terrain` argument. `load` (in the terrain module) turns it into a height model.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum TerrainSpec {
    /// Level ground at `height_m`.
    Flat {
        /// Ground height above sea level, metres (default 0).
        #[serde(default)]
        height_m: f64,
    },
    /// The composite terrain of seeds 000/002 (`preset` = `seed000` or `seed002`).
    Composite {
        /// The preset's name (default `seed000`).
        #[serde(default = "default_preset")]
        preset: String,
    },
    /// Level ground with circular plateaus (seed 001's S4).
    #[serde(alias = "flat_with_plateaus")]
    Plateaus {
        /// Height of the ground around the plateaus above sea level, metres (default 0).
        #[serde(default)]
        base_m: f64,
        /// The plateaus standing on that ground.
        plateaus: Vec<Plateau>,
        /// Spacing of the paper's DEM (informational; the model is analytic).
        #[serde(default)]
        dem_spacing_m: Option<f64>,
        /// Free text describing the terrain (informational).
        #[serde(default)]
        note: Option<String>,
    },
    /// A DEM file: GeoTIFF (.tif/.tiff), ESRI ASCII grid (.asc) or XYZ points (.xyz/.csv).
    File {
        /// Path of the DEM file; a relative path is taken from the base folder given to `load`.
        path: PathBuf,
        /// Cell size for gridding an XYZ point cloud, metres (estimated when absent).
        #[serde(default)]
        cell_m: Option<f64>,
    },
}

fn default_preset() -> String {
    "seed000".to_string()
}

impl TerrainSpec {
    /// Reads a `--terrain` argument: a DEM path, or `flat`, `flat:HEIGHT`, `seed000`, `seed002`.
    pub fn from_argument(argument: &str) -> Result<Self, InputError> {
        let fail = |why: &str| {
            InputError::new(
                "--terrain",
                Fault::InvalidValue {
                    what: "--terrain".into(),
                    value: argument.into(),
                    why: why.into(),
                },
            )
        };
        match argument {
            "flat" => Ok(Self::Flat { height_m: 0.0 }),
            "seed000" | "seed002" => Ok(Self::Composite {
                preset: argument.to_string(),
            }),
            _ if argument.starts_with("flat:") => {
                let height_m: f64 = argument[5..]
                    .parse()
                    .map_err(|_| fail("flat:HEIGHT needs a number of metres"))?;
                let (lowest, highest) = crate::limits::TERRAIN_HEIGHT_RANGE_M;
                if !(lowest..=highest).contains(&height_m) {
                    return Err(fail(&format!(
                        "the height must lie within {lowest}..={highest} m"
                    )));
                }
                Ok(Self::Flat { height_m })
            }
            _ => Ok(Self::File {
                path: PathBuf::from(argument),
                cell_m: None,
            }),
        }
    }

    /// The `terrain` member of a field file. A member of kind `note` only describes the
    /// ground in words (seed 003's strip): there is no model in it, so `None`.
    pub fn from_embedded(value: &serde_json::Value) -> Result<Option<Self>, Fault> {
        if value.get("kind").and_then(|kind| kind.as_str()) == Some("note") {
            return Ok(None);
        }
        serde_json::from_value(value.clone())
            .map(Some)
            .map_err(|error| Fault::Structure(error.to_string()))
    }
}

/// A circular plateau of seed 001's S4: a flat top with a sloping rim.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plateau {
    /// Centre [x, y], metres.
    pub center: [f64; 2],
    /// Radius of the flat top, metres.
    pub radius_m: f64,
    /// Height of the top above the base, metres.
    pub height_m: f64,
    /// Width of the sloping rim outside the top, metres.
    #[serde(default)]
    pub edge_ramp_m: f64,
}
