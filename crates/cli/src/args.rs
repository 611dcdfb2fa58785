//! Command-line grammar (clap derive). Values are checked here only for shape; meaning is
//! checked by the library, once.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "agripath",
    version,
    about = "Mission planning for agricultural UAVs over real terrain",
    long_about = "Mission planning for agricultural UAVs over real terrain.\n\nExit status: 0 done, 2 bad input (nothing written), 1 could not write outputs."
)]
pub struct Arguments {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run the embedded default (seed 001's five-field farm) and write ./agripath-demo/.
    Demo {
        /// Output folder.
        #[arg(long, default_value = "agripath-demo")]
        out: PathBuf,
    },
    /// Read a scenario (or fields, terrain and vehicle) and say what was read or what is wrong.
    Validate {
        #[command(flatten)]
        inputs: Inputs,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Look at a terrain model: its extent and heights, samples, a hillshade picture.
    Terrain {
        #[command(subcommand)]
        action: TerrainAction,
    },
}

/// Where a scenario comes from: a scenario file, or its parts as flags (flags override it).
#[derive(Debug, Args)]
pub struct Inputs {
    /// Scenario TOML file tying fields, terrain and vehicle together.
    pub scenario: Option<PathBuf>,
    /// Field file: GeoJSON (.geojson/.json), KML or KMZ.
    #[arg(long)]
    pub fields: Option<PathBuf>,
    /// Terrain: a DEM file (.tif, .asc, .xyz/.csv) or flat, flat:HEIGHT, seed000, seed002.
    #[arg(long)]
    pub terrain: Option<String>,
    /// Vehicle TOML file.
    #[arg(long)]
    pub vehicle: Option<PathBuf>,
    /// Read field coordinates as metres in a local frame ("local"), whatever the file says.
    #[arg(long, value_parser = ["local"])]
    pub crs: Option<String>,
    /// Swath width, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub swath_width: Option<f64>,
    /// Spray height above the terrain, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub spray_height: Option<f64>,
    /// Safe transfer height h, metres (overrides the vehicle).
    #[arg(long, allow_negative_numbers = true)]
    pub safe_height: Option<f64>,
}

#[derive(Debug, Subcommand)]
pub enum TerrainAction {
    /// Size, cell, coordinate system, extent and height range of a terrain.
    Info {
        /// A DEM file (.tif, .asc, .xyz/.csv) or flat, flat:HEIGHT, seed000, seed002.
        terrain: String,
        /// Cell size for gridding an XYZ point cloud, metres.
        #[arg(long)]
        cell: Option<f64>,
        #[arg(long)]
        json: bool,
    },
    /// Heights at points given in the terrain's own coordinates: X Y [X Y ...].
    Sample {
        terrain: String,
        /// Pairs of coordinates.
        #[arg(required = true, num_args = 2.., allow_negative_numbers = true)]
        coordinates: Vec<f64>,
        #[arg(long)]
        cell: Option<f64>,
    },
    /// A hillshade picture (PNG, north up) of the terrain.
    Hillshade {
        terrain: String,
        /// Output PNG file.
        #[arg(long)]
        out: PathBuf,
        /// Longer side of the picture, pixels.
        #[arg(long, default_value_t = 1024)]
        size: usize,
        /// Vertical exaggeration.
        #[arg(long, default_value_t = 1.0)]
        exaggeration: f64,
        /// Area to draw, for unbounded terrains: MIN_X,MIN_Y,MAX_X,MAX_Y.
        #[arg(
            long,
            value_delimiter = ',',
            num_args = 4,
            allow_negative_numbers = true
        )]
        extent: Option<Vec<f64>>,
        #[arg(long)]
        cell: Option<f64>,
    },
}
