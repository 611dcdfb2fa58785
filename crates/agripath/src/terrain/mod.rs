//! Terrain models behind one trait: flat ground, the analytic terrains of the seeds, and
//! rasters read from GeoTIFF, ESRI ASCII grids and XYZ point clouds.
//!
//! Every query answers a height above sea level in metres at a planning-frame position, or
//! says why it cannot ([`TerrainError`]): asking outside a DEM is an error, never a silent 0.

pub mod ascii_grid;
pub mod composite;
pub mod flat;
pub mod frame;
pub mod geotiff;
pub mod grid;
pub mod hillshade;
pub mod plateaus;
pub mod xyz;

use std::path::Path;

use crate::error::{Fault, InputError, TerrainError};
use crate::model::CoordinateSystem;

pub use crate::model::terrain_spec::TerrainSpec;
pub use composite::Composite;
pub use flat::Flat;
pub use grid::Grid;
pub use plateaus::{Plateau, Plateaus};

/// A rectangle of the plane, metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// Smallest x (the west edge), metres.
    pub min_x: f64,
    /// Smallest y (the south edge), metres.
    pub min_y: f64,
    /// Largest x (the east edge), metres.
    pub max_x: f64,
    /// Largest y (the north edge), metres.
    pub max_y: f64,
}

impl Extent {
    /// East-west size, metres.
    pub fn width(&self) -> f64 {
        self.max_x - self.min_x
    }

    /// North-south size, metres.
    pub fn height(&self) -> f64 {
        self.max_y - self.min_y
    }

    /// Whether (x, y) lies inside or on the edge.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        x >= self.min_x && x <= self.max_x && y >= self.min_y && y <= self.max_y
    }
}

/// A height field.
pub trait Terrain: Send + Sync {
    /// Height above sea level at (x, y), metres.
    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError>;

    /// Where the model has answers; `None` for models defined everywhere.
    fn extent(&self) -> Option<Extent>;

    /// One line for people: what was read.
    fn describe(&self) -> String;

    /// The EPSG code of the model's own coordinates, when its file states one.
    fn epsg(&self) -> Option<u32> {
        None
    }

    /// Lowest and highest height over `within`, metres. The default samples a 257 × 257
    /// lattice; rasters override it with their exact range.
    fn height_range_m(&self, within: Extent) -> Option<(f64, f64)> {
        let steps = 256;
        let mut range: Option<(f64, f64)> = None;
        for row in 0..=steps {
            for column in 0..=steps {
                let x = within.min_x + within.width() * column as f64 / steps as f64;
                let y = within.min_y + within.height() * row as f64 / steps as f64;
                if let Ok(height) = self.height_m(x, y) {
                    range = Some(match range {
                        Some((low, high)) => (low.min(height), high.max(height)),
                        None => (height, height),
                    });
                }
            }
        }
        range
    }
}

impl TerrainSpec {
    /// Loads the terrain. Relative paths are taken from `base`; `frame` is the planning frame
    /// of the farm, so that a DEM in another projection is sampled where the fields are.
    pub fn load(
        &self,
        base: &Path,
        frame: CoordinateSystem,
    ) -> Result<Box<dyn Terrain>, InputError> {
        match self {
            Self::Flat { height_m } => {
                if !height_m.is_finite() {
                    return Err(InputError::new(base, Fault::NonFinite).at("terrain height_m"));
                }
                plausible_height(*height_m, "terrain height_m")
                    .map_err(|fault| InputError::new(base, fault))?;
                Ok(Box::new(Flat::new(*height_m)))
            }
            Self::Composite { preset } => match preset.as_str() {
                "seed000" => Ok(Box::new(Composite::seed000())),
                "seed002" => Ok(Box::new(Composite::seed002())),
                other => Err(InputError::new(
                    base,
                    Fault::InvalidValue {
                        what: "terrain preset".into(),
                        value: other.into(),
                        why: "known presets are seed000 and seed002".into(),
                    },
                )),
            },
            Self::Plateaus {
                base_m, plateaus, ..
            } => {
                plausible_height(*base_m, "terrain base_m")
                    .and_then(|()| {
                        plateaus.iter().try_for_each(|plateau| {
                            plausible_height(base_m + plateau.height_m, "a plateau's top")
                        })
                    })
                    .map_err(|fault| InputError::new(base, fault).at("terrain"))?;
                Plateaus::new(*base_m, plateaus.clone())
                    .map(|terrain| Box::new(terrain) as Box<dyn Terrain>)
                    .map_err(|fault| InputError::new(base, fault).at("terrain"))
            }
            Self::File { path, cell_m } => {
                let path = if path.is_absolute() {
                    path.clone()
                } else {
                    base.join(path)
                };
                let grid = load_grid(&path, *cell_m)?;
                frame::place(grid, frame).map_err(|fault| InputError::new(&path, fault))
            }
        }
    }
}

/// A height an analytic terrain may have: within the range rasters are held to.
fn plausible_height(height_m: f64, what: &str) -> Result<(), Fault> {
    let (lowest, highest) = crate::limits::TERRAIN_HEIGHT_RANGE_M;
    if (lowest..=highest).contains(&height_m) {
        Ok(())
    } else {
        Err(Fault::InvalidValue {
            what: what.into(),
            value: format!("{} m", crate::error::figure(height_m)),
            why: format!("terrain lies within {lowest}..={highest} m"),
        })
    }
}

/// Reads a DEM file into a grid, choosing the reader by extension.
pub fn load_grid(path: &Path, cell_m: Option<f64>) -> Result<Grid, InputError> {
    let extension = crate::files::extension_of(path);
    let grid = match extension.as_str() {
        "tif" | "tiff" => geotiff::read(path),
        "asc" => ascii_grid::read(path),
        "xyz" | "csv" | "txt" => xyz::read(path, cell_m),
        other => Err(InputError::new(
            path,
            Fault::UnknownExtension {
                extension: other.to_string(),
                role: "terrain",
                expected: ".tif, .tiff, .asc, .xyz, .csv or .txt",
            },
        )),
    }?;
    grid.check_plausible()
        .map_err(|fault| InputError::new(path, fault))?;
    Ok(grid)
}
