//! Placing a DEM in the planning frame of a farm.
//!
//! A farm read in lon/lat is planned in its UTM zone; a DEM may come in that zone, another
//! UTM zone, or in lon/lat. Queries are converted to the DEM's own coordinates, so no
//! resampling (and no loss) happens. A farm in local metres uses the DEM's coordinates as they
//! are: the fields must be drawn in the DEM's frame.

use super::{Extent, Grid, Terrain};
use crate::error::{Fault, TerrainError};
use crate::geometry::{from_utm, to_utm, UtmZone};
use crate::model::CoordinateSystem;

/// The DEM's coordinate system as far as planning needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
enum DemCoordinates {
    Utm(UtmZone),
    LonLat,
}

/// EPSG codes whose coordinates are UTM easting/northing: WGS84 (326zz, 327zz), and the
/// national grids that are UTM on GRS80 (ETRS89 258zz, NAD83 269zz, GDA94/MGA 283zz,
/// GDA2020 78xx), whose axes differ from WGS84 UTM by well under the DEM's pixel.
fn dem_coordinates(epsg: u32) -> Option<DemCoordinates> {
    let zone = |number: u32, south: bool| {
        Some(DemCoordinates::Utm(UtmZone {
            number: number as u8,
            south,
        }))
    };
    match epsg {
        4326 | 4258 | 4269 | 4283 | 7844 => Some(DemCoordinates::LonLat),
        32601..=32660 => zone(epsg - 32600, false),
        32701..=32760 => zone(epsg - 32700, true),
        25801..=25860 => zone(epsg - 25800, false),
        26901..=26923 => zone(epsg - 26900, false),
        28348..=28358 => zone(epsg - 28300, true),
        7846..=7859 => zone(epsg - 7800, true),
        _ => None,
    }
}

/// Whether a DEM in EPSG `epsg` can be placed under the fields (its coordinates are UTM or
/// lon/lat on a datum `dem_coordinates` reads).
pub fn placeable(epsg: u32) -> bool {
    dem_coordinates(epsg).is_some()
}

/// The corners and edge midpoints of `extent` (in `dem`'s coordinates) as lon/lat: the
/// outline of a DEM is curved in another frame, and these eight points bound it closely
/// enough to say where to look.
fn outline_lon_lat(dem: DemCoordinates, extent: Extent) -> impl Iterator<Item = (f64, f64)> {
    const AT: [(f64, f64); 8] = [
        (0.0, 0.0),
        (0.5, 0.0),
        (1.0, 0.0),
        (0.0, 0.5),
        (1.0, 0.5),
        (0.0, 1.0),
        (0.5, 1.0),
        (1.0, 1.0),
    ];
    AT.into_iter().map(move |(fx, fy)| {
        let x = extent.min_x + fx * extent.width();
        let y = extent.min_y + fy * extent.height();
        match dem {
            DemCoordinates::LonLat => (x, y),
            DemCoordinates::Utm(zone) => from_utm(x, y, zone),
        }
    })
}

/// The bounding box of `points`, `None` when there are none.
fn bounding_box(points: impl Iterator<Item = (f64, f64)>) -> Option<Extent> {
    points.fold(None, |extent: Option<Extent>, (x, y)| {
        Some(match extent {
            None => Extent {
                min_x: x,
                min_y: y,
                max_x: x,
                max_y: y,
            },
            Some(e) => Extent {
                min_x: e.min_x.min(x),
                min_y: e.min_y.min(y),
                max_x: e.max_x.max(x),
                max_y: e.max_y.max(y),
            },
        })
    })
}

/// The lon/lat box `[west, south, east, north]` of an extent given in EPSG `epsg`'s
/// coordinates (a UTM grid or lon/lat), from its corners and edge midpoints; `None` for a
/// coordinate system agripath does not place.
pub fn lon_lat_box(epsg: u32, extent: Extent) -> Option<[f64; 4]> {
    let dem = dem_coordinates(epsg)?;
    let e = bounding_box(outline_lon_lat(dem, extent))?;
    Some([e.min_x, e.min_y, e.max_x, e.max_y])
}

/// A lon/lat point in EPSG `epsg`'s coordinates; `None` for a system agripath does not place.
pub fn from_lon_lat(epsg: u32, lon: f64, lat: f64) -> Option<(f64, f64)> {
    Some(match dem_coordinates(epsg)? {
        DemCoordinates::LonLat => (lon, lat),
        DemCoordinates::Utm(zone) => to_utm(lon, lat, zone),
    })
}

/// A longitude read a turn round (±360°) where that lands inside the columns of a lon/lat
/// DEM's `extent` and it is outside them: a DEM may run past ±180° (179.99..180.01 across the
/// antimeridian), and −179.999° is its 180.001°.
pub fn wrap_into(lon: f64, extent: Extent) -> f64 {
    if lon < extent.min_x && lon + 360.0 <= extent.max_x {
        lon + 360.0
    } else if lon > extent.max_x && lon - 360.0 >= extent.min_x {
        lon - 360.0
    } else {
        lon
    }
}

/// Whether EPSG `epsg`'s coordinates are degrees of longitude and latitude.
pub fn is_lon_lat(epsg: u32) -> bool {
    dem_coordinates(epsg) == Some(DemCoordinates::LonLat)
}

/// A DEM queried through a change of coordinates.
struct Reprojected {
    grid: Grid,
    plan_zone: UtmZone,
    dem: DemCoordinates,
}

/// Longest piece of a leg carried into a reprojected DEM's coordinates as a straight line.
const BEND_PIECE_M: f64 = 200.0;

impl Reprojected {
    /// A place of the plan's frame in the DEM's coordinates. A lon/lat DEM may run past
    /// ±180° (179.99..180.01 across the antimeridian): a longitude outside its columns is
    /// read a turn round where that lands inside them (until 2026-12-07 a field at −179.998°
    /// over such a DEM was refused as not covered: the fourth trial).
    fn to_dem(&self, x: f64, y: f64) -> (f64, f64) {
        let (lon, lat) = from_utm(x, y, self.plan_zone);
        match self.dem {
            DemCoordinates::LonLat => (wrap_into(lon, self.grid.outer_extent()), lat),
            DemCoordinates::Utm(zone) => to_utm(lon, lat, zone),
        }
    }
}

impl Terrain for Reprojected {
    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        let (dem_x, dem_y) = self.to_dem(x, y);
        // The fault at the plan's place, of the same kind: a gap inside the DEM is no data,
        // not outside it (its message names the DEM's extent).
        self.grid
            .height_m(dem_x, dem_y)
            .map_err(|error| match error {
                TerrainError::NoData { .. } => TerrainError::NoData { x, y },
                TerrainError::Outside { .. } => TerrainError::Outside { x, y },
            })
    }

    fn extent(&self) -> Option<Extent> {
        let zone = self.plan_zone;
        bounding_box(
            outline_lon_lat(self.dem, self.grid.outer_extent())
                .map(|(lon, lat)| to_utm(lon, lat, zone)),
        )
    }

    /// The DEM's lines through its cell centres, crossed by the segment carried into the DEM's
    /// coordinates piece by piece, [`BEND_PIECE_M`] at most: the projection is not affine over
    /// a long leg (the test below: a 3 km leg over a lon/lat DEM carried whole missed its
    /// lowest ground by 2 cm).
    fn bends_along(&self, from: (f64, f64), to: (f64, f64)) -> Vec<f64> {
        let to_dem = |(x, y): (f64, f64)| self.to_dem(x, y);
        let length = (to.0 - from.0).hypot(to.1 - from.1);
        let pieces = (length / BEND_PIECE_M).ceil().max(1.0) as usize;
        let along = |t: f64| (from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
        let mut bends = Vec::new();
        for piece in 0..pieces {
            let (start, end) = (
                piece as f64 / pieces as f64,
                (piece + 1) as f64 / pieces as f64,
            );
            bends.extend(
                self.grid
                    .bends_along(to_dem(along(start)), to_dem(along(end)))
                    .into_iter()
                    .map(|t| start + t * (end - start)),
            );
        }
        bends
    }

    fn describe(&self) -> String {
        format!(
            "{} (sampled from UTM zone {}{})",
            self.grid.source,
            self.plan_zone.number,
            if self.plan_zone.south { "S" } else { "N" }
        )
    }

    /// The DEM's range over the cells within the box that holds `within` carried into the
    /// DEM's coordinates (its outline sampled: the box of a rotated, curved rectangle), a
    /// little wider than `within`, never narrower. Until 2026-12-07 this was the whole DEM's
    /// range, so `validate` gave every field the same (the fourth trial).
    fn height_range_m(&self, within: Extent) -> Option<(f64, f64)> {
        let to_dem = |x: f64, y: f64| self.to_dem(x, y);
        let steps = 16;
        let outline = (0..=steps).flat_map(|k| {
            let t = f64::from(k) / f64::from(steps);
            let (x, y) = (
                within.min_x + t * within.width(),
                within.min_y + t * within.height(),
            );
            [
                to_dem(x, within.min_y),
                to_dem(x, within.max_y),
                to_dem(within.min_x, y),
                to_dem(within.max_x, y),
            ]
        });
        // A cell more each way: heights read between the box's outer centres blend the
        // centres just beyond it.
        let inner = bounding_box(outline)?;
        let (cell_x, cell_y) = (self.grid.cell_x.abs(), self.grid.cell_y.abs());
        self.grid.height_range_m(Extent {
            min_x: inner.min_x - cell_x,
            min_y: inner.min_y - cell_y,
            max_x: inner.max_x + cell_x,
            max_y: inner.max_y + cell_y,
        })
    }
}

/// The DEM as a terrain in the farm's planning frame.
pub fn place(grid: Grid, frame: CoordinateSystem) -> Result<Box<dyn Terrain>, Fault> {
    let CoordinateSystem::Utm(plan_zone) = frame else {
        return Ok(Box::new(grid));
    };
    let Some(epsg) = grid.epsg else {
        return Err(Fault::Structure(
            "the DEM has no coordinate system (no EPSG code) and the fields are in lon/lat: use a georeferenced GeoTIFF, or local fields drawn in the DEM's frame".into(),
        ));
    };
    match dem_coordinates(epsg) {
        Some(DemCoordinates::Utm(zone)) if zone == plan_zone => Ok(Box::new(grid)),
        Some(dem) => Ok(Box::new(Reprojected {
            grid,
            plan_zone,
            dem,
        })),
        None => Err(Fault::Structure(format!(
            "the DEM's coordinate system EPSG:{epsg} is not supported: reproject it to UTM or WGS84 lon/lat (for example with gdalwarp -t_srs EPSG:{})",
            plan_zone.epsg()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{to_utm, UtmZone};

    /// A 200 × 200 lon/lat DEM of 0.0003° cells near 126.6°E, 45.8°N, heights by row and column.
    fn lon_lat_grid(source: &str, height: impl Fn(usize, usize) -> f32) -> Grid {
        let (columns, rows) = (200, 200);
        Grid {
            columns,
            rows,
            first_center_x: 126.60,
            first_center_y: 45.78,
            cell_x: 0.0003,
            cell_y: 0.0003,
            heights: (0..rows * columns)
                .map(|index| height(index / columns, index % columns))
                .collect(),
            epsg: Some(4326),
            source: source.into(),
        }
    }

    /// A lon/lat DEM under fields planned in UTM, rough (cells 0, 8 or 16 m apart), with a step of 30 m between two rows of
    /// cells: along a leg 3 km long, the places `profile_places` samples find the highest and
    /// lowest ground that 30,000 even samples find, to a centimetre (the leg is carried into
    /// lon/lat in pieces of 200 m; whole, its chord strays 20 cm from the leg).
    #[test]
    fn bends_of_a_long_leg_over_a_lon_lat_dem_are_found() {
        let grid = lon_lat_grid("lon/lat step", |row, column| {
            (if row < 100 { 30.0 } else { 0.0 }) + 8.0 * ((row * 7 + column * 13) % 3) as f32
        });
        let zone = UtmZone::containing(126.63, 45.75);
        let terrain = place(grid, CoordinateSystem::Utm(zone)).unwrap();
        let from = to_utm(126.605, 45.735, zone);
        let to = to_utm(126.640, 45.761, zone);
        let length = (to.0 - from.0).hypot(to.1 - from.1);
        assert!(length > 3000.0, "{length}");
        let ground = |t: f64| {
            terrain
                .height_m(from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1))
                .unwrap()
        };
        let places = crate::terrain::profile_places(terrain.as_ref(), from, to, length, 1.0, |t| {
            Some(vec![ground(t)])
        });
        let range = |places: &mut dyn Iterator<Item = f64>| {
            places.fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), t| {
                (low.min(ground(t)), high.max(ground(t)))
            })
        };
        let found = range(&mut places.into_iter());
        let fine = range(&mut (0..=30_000).map(|k| f64::from(k) / 30_000.0));
        assert!(
            found.0 <= fine.0 + 0.01 && found.1 >= fine.1 - 0.01,
            "{found:?} {fine:?}"
        );
    }

    /// A field's height range over a lon/lat DEM is the range under the field, not the whole
    /// DEM's (the fourth trial's `validate` gave every field −40..140 m): it holds every
    /// height sampled over the field, and is far narrower than the DEM's.
    #[test]
    fn the_range_over_a_reprojected_dem_is_the_ground_under_the_extent() {
        let grid = lon_lat_grid("lon/lat ramp", |row, column| (row + column) as f32);
        let whole = grid.stored_range().unwrap();
        let zone = UtmZone::containing(126.63, 45.75);
        let terrain = place(grid, CoordinateSystem::Utm(zone)).unwrap();
        let centre = terrain.extent().unwrap();
        let (x, y) = (
            0.5 * (centre.min_x + centre.max_x),
            0.5 * (centre.min_y + centre.max_y),
        );
        let field = Extent {
            min_x: x - 100.0,
            min_y: y - 100.0,
            max_x: x + 100.0,
            max_y: y + 100.0,
        };
        let (low, high) = terrain.height_range_m(field).unwrap();
        assert!(
            high - low < 0.1 * (whole.1 - whole.0),
            "{low}..{high} of {whole:?}"
        );
        for k in 0..=20 {
            for j in 0..=20 {
                let (px, py) = (
                    field.min_x + 10.0 * f64::from(k),
                    field.min_y + 10.0 * f64::from(j),
                );
                let height = terrain.height_m(px, py).unwrap();
                assert!(
                    (low..=high).contains(&height),
                    "{height} outside {low}..{high}"
                );
            }
        }
    }

    /// A lon/lat DEM across the antimeridian (columns 179.99..180.01): a place at −179.998°
    /// is read at its column 180.002°, east of the one at 179.998°.
    #[test]
    fn a_lon_lat_dem_across_the_antimeridian_covers_both_sides() {
        let (columns, rows) = (100, 100);
        let grid = Grid {
            columns,
            rows,
            first_center_x: 179.99 + 0.0001,
            first_center_y: -16.79 - 0.0001,
            cell_x: 0.0002,
            cell_y: 0.0002,
            heights: (0..rows * columns)
                .map(|index| (index % columns) as f32)
                .collect(),
            epsg: Some(4326),
            source: "across 180".into(),
        };
        let zone = UtmZone::containing(179.999, -16.8);
        let terrain = place(grid, CoordinateSystem::Utm(zone)).unwrap();
        let west = to_utm(179.998, -16.8, zone);
        let east = to_utm(-179.998, -16.8, zone);
        let (west, east) = (
            terrain.height_m(west.0, west.1).unwrap(),
            terrain.height_m(east.0, east.1).unwrap(),
        );
        // Columns are 0.0002° apart: 179.998° is column 39.5, 180.002° column 59.5.
        assert!(
            (west - 39.5).abs() < 0.01 && (east - 59.5).abs() < 0.01,
            "{west} {east}"
        );
        let extent = Extent {
            min_x: 179.99,
            min_y: -16.81,
            max_x: 180.01,
            max_y: -16.79,
        };
        assert_eq!(wrap_into(-179.998, extent), -179.998 + 360.0);
        assert_eq!(wrap_into(179.995, extent), 179.995);
        assert_eq!(wrap_into(-170.0, extent), -170.0);
    }
}
