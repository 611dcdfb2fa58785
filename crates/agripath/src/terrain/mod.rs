//! Terrain models behind one trait: flat ground, the analytic terrains of the seeds, and
//! rasters read from GeoTIFF, ESRI ASCII grids and XYZ point clouds.
//!
//! Every query answers a height above sea level in metres at a planning-frame position, or
//! says why it cannot ([`TerrainError`]): asking outside a DEM is an error, never a silent 0.

pub mod ascii_grid;
pub mod composite;
pub mod flat;
pub mod frame;
pub mod gdal_metadata;
pub mod geotiff;
pub mod grid;
pub mod hillshade;
pub mod nearness;
pub mod plateaus;
pub mod prj;
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

    /// Where the surface bends along the straight segment `from`–`to`: fractions of it in
    /// (0, 1), ascending. Between two bends the surface along the segment is smooth (on a
    /// raster, bilinear between cell centres: a quadratic along a line). A check that samples
    /// a leg only every metre steps over a step in the ground one cell wide; sampled at the
    /// bends and at each piece's extremes ([`profile_places`]) it sees a raster as modelled.
    /// The default: none, for the analytic models (flat ground; seed 000's composite hills,
    /// whose crests and ripples of a few metres the 1 m samples read to about 0.1 m).
    fn bends_along(&self, _from: (f64, f64), _to: (f64, f64)) -> Vec<f64> {
        Vec::new()
    }

    /// The lattice the surface is bilinear on, `(origin, step)`: a raster's cell centres.
    /// `None` for the analytic models ([`nearness`] then samples them).
    fn lattice(&self) -> Option<((f64, f64), (f64, f64))> {
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

/// Most lines of one axis a segment's bends are taken from: beyond (a leg 200 km along one
/// axis of a 1 m grid; the fields lie within 200 km of the supply point at most), that axis's
/// bends are left out and the leg is sampled every [`profile_places`]'s spacing only.
pub const MAX_BENDS: usize = 200_000;

/// Where the straight segment `from`–`to` crosses the lines of a lattice with nodes at
/// `origin + (i·step.0, j·step.1)`, as fractions of it strictly inside, ascending: where
/// bilinear interpolation between those nodes bends along the segment.
pub fn lattice_bends(
    from: (f64, f64),
    to: (f64, f64),
    origin: (f64, f64),
    step: (f64, f64),
) -> Vec<f64> {
    let mut bends = Vec::new();
    grid_line_crossings(from, to, 0, origin.0, step.0, &mut bends);
    grid_line_crossings(from, to, 1, origin.1, step.1, &mut bends);
    bends.sort_by(f64::total_cmp);
    bends.dedup();
    bends
}

/// The fractions of the straight segment `from`–`to` where the lines `origin + k·step`
/// (x = … for `axis` 0, y = … for 1) cross it, strictly inside; appended to `bends`.
/// Nothing when there would be more than [`MAX_BENDS`].
fn grid_line_crossings(
    from: (f64, f64),
    to: (f64, f64),
    axis: usize,
    origin: f64,
    step: f64,
    bends: &mut Vec<f64>,
) {
    let (start, end) = if axis == 0 {
        (from.0, to.0)
    } else {
        (from.1, to.1)
    };
    let span = end - start;
    if !(span.abs() > 1e-12 && step > 0.0 && step.is_finite()) {
        return;
    }
    let (low, high) = (start.min(end), start.max(end));
    let first = ((low - origin) / step).floor() + 1.0;
    let last = ((high - origin) / step).ceil() - 1.0;
    if !(first.is_finite() && last.is_finite()) || last - first > MAX_BENDS as f64 {
        return;
    }
    let mut line = first;
    while line <= last {
        let t = (origin + line * step - start) / span;
        if t > 0.0 && t < 1.0 {
            bends.push(t);
        }
        line += 1.0;
    }
}

/// The places to sample a profile of the straight segment `from`–`to` at, as fractions of it
/// in ascending order: both ends, at most `spacing_m` apart (its length `length_m`), every
/// bend of the surface ([`Terrain::bends_along`]), and, between two bends, where each of
/// `values(t)` (the ground, or the height above it) is highest or lowest, found as the vertex
/// of the quadratic through the piece's ends and middle (exact on a raster for a leg whose
/// altitude changes linearly). Where `values` has no answer the piece gets no extreme (the
/// caller's own samples report the fault).
pub fn profile_places(
    terrain: &dyn Terrain,
    from: (f64, f64),
    to: (f64, f64),
    length_m: f64,
    spacing_m: f64,
    values: impl Fn(f64) -> Option<Vec<f64>>,
) -> Vec<f64> {
    let mut places: Vec<f64> = crate::geometry::leg_samples(length_m, spacing_m).collect();
    // A leg within one cell bends nowhere but may still peak between two samples.
    let bends = terrain.bends_along(from, to);
    let bounds: Vec<f64> = std::iter::once(0.0)
        .chain(bends.iter().copied())
        .chain(std::iter::once(1.0))
        .collect();
    // Each bound is asked once, shared by the pieces either side of it.
    let at_bounds: Vec<Option<Vec<f64>>> = bounds.iter().map(|&t| values(t)).collect();
    for (index, piece) in bounds.windows(2).enumerate() {
        let (a, b) = (piece[0], piece[1]);
        let (Some(at_a), Some(at_b)) = (&at_bounds[index], &at_bounds[index + 1]) else {
            continue;
        };
        let Some(at_middle) = values((a + b) / 2.0) else {
            continue;
        };
        for ((&first, &middle), &last) in at_a.iter().zip(&at_middle).zip(at_b) {
            // f(s) = first + s·(−3·first + 4·middle − last) + s²·(2·first − 4·middle + 2·last)
            let linear = -3.0 * first + 4.0 * middle - last;
            let square = 2.0 * first - 4.0 * middle + 2.0 * last;
            if square.abs() > 1e-12 {
                let vertex = -linear / (2.0 * square);
                if vertex > 0.0 && vertex < 1.0 {
                    places.push(a + vertex * (b - a));
                }
            }
        }
    }
    places.extend(bends);
    places.sort_by(f64::total_cmp);
    places.dedup_by(|later, earlier| *later - *earlier < 1e-12);
    places
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Highest and lowest of the ground and of a leg's height above it (its altitude going
    /// linearly from `altitudes.0` to `altitudes.1`) over the places `places` of the segment.
    fn extremes(
        terrain: &dyn Terrain,
        from: (f64, f64),
        to: (f64, f64),
        altitudes: (f64, f64),
        places: impl IntoIterator<Item = f64>,
    ) -> [f64; 4] {
        let mut found = [
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
        ];
        for t in places {
            let (x, y) = (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
            let ground = terrain.height_m(x, y).unwrap();
            let above = altitudes.0 + t * (altitudes.1 - altitudes.0) - ground;
            found = [
                found[0].max(ground),
                found[1].min(ground),
                found[2].max(above),
                found[3].min(above),
            ];
        }
        found
    }

    /// `profile_places` of the segment against 20,000 even samples of it: no extreme of the
    /// ground or of the height above it lies beyond what the places find by more than `slack`.
    fn places_find_the_extremes(
        terrain: &dyn Terrain,
        from: (f64, f64),
        to: (f64, f64),
        altitudes: (f64, f64),
        slack: f64,
    ) -> Result<(), TestCaseError> {
        let length = (to.0 - from.0).hypot(to.1 - from.1);
        let places = profile_places(terrain, from, to, length, 1.0, |t| {
            let (x, y) = (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
            let ground = terrain.height_m(x, y).ok()?;
            Some(vec![
                ground,
                altitudes.0 + t * (altitudes.1 - altitudes.0) - ground,
            ])
        });
        prop_assert!(places.windows(2).all(|pair| pair[0] < pair[1]));
        prop_assert!(places[0] == 0.0 && places[places.len() - 1] == 1.0);
        let found = extremes(terrain, from, to, altitudes, places);
        let fine = extremes(
            terrain,
            from,
            to,
            altitudes,
            (0..=20_000).map(|k| k as f64 / 20_000.0),
        );
        for (index, (&found, &fine)) in found.iter().zip(&fine).enumerate() {
            // Even indices are highest, odd lowest.
            let missed = if index % 2 == 0 {
                fine - found
            } else {
                found - fine
            };
            prop_assert!(
                missed <= slack,
                "extreme {index}: found {found}, fine sampling {fine}"
            );
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// A raster with a cliff one cell wide (decision 0028): every extreme is found, to
        /// rounding (bilinear is a quadratic along a line between the cell-centre lines).
        #[test]
        fn profile_places_find_a_rasters_extremes(
            heights in proptest::collection::vec(0.0f32..30.0, 36),
            cliff in 0.0f32..20.0,
            from in (0.0f64..24.0, 0.0f64..24.0),
            to in (0.0f64..24.0, 0.0f64..24.0),
            altitudes in (0.0f64..60.0, 0.0f64..60.0),
        ) {
            let mut heights = heights;
            for (index, height) in heights.iter_mut().enumerate() {
                if index / 6 >= 3 {
                    *height += cliff;
                }
            }
            let grid = Grid {
                columns: 6,
                rows: 6,
                first_center_x: 2.0,
                first_center_y: 22.0,
                cell_x: 4.0,
                cell_y: 4.0,
                heights,
                epsg: None,
                source: "test grid".into(),
            };
            places_find_the_extremes(&grid, from, to, altitudes, 1e-6)?;
        }

        /// A plateau's top edge, foot and the ramp between (the ramp is not a quadratic along a
        /// line: its extremes are found to a centimetre, within the preflight's 2 cm of slack
        /// for rounding).
        #[test]
        fn profile_places_find_a_plateaus_extremes(
            from in (-60.0f64..60.0, -60.0f64..60.0),
            to in (-60.0f64..60.0, -60.0f64..60.0),
            altitudes in (0.0f64..30.0, 0.0f64..30.0),
            ramp in 0.0f64..8.0,
        ) {
            let terrain = Plateaus::new(
                0.0,
                vec![Plateau { center: [5.0, -3.0], radius_m: 20.0, height_m: 6.0, edge_ramp_m: ramp }],
            )
            .unwrap();
            places_find_the_extremes(&terrain, from, to, altitudes, 0.01)?;
        }
    }
}
