//! A point-to-point track problem: terrain, start, goal, threat cylinders, a height band and
//! the number of free waypoints, with the cost model that scores a track over it.
//!
//! Three scenario files are read (their format is detected from their keys):
//! - seed 000's orchard (`seed000_orchard.json`): the composite terrain, tasks I-III;
//! - seed 002's survey space (`seed002_field_survey.json`);
//! - SPSO's public scenario (`spso/scenario.json` beside `ChrismasTerrain.tif`).
//!
//! Units are the scenario's own: metres for the seeds, and for SPSO its code's units (one
//! DEM pixel = one unit horizontally, heights in metres), so its costs compare with its runs.

use std::path::Path;

use serde_json::Value;

use super::cost::{CostModel, Seed000Cost, Seed002Cost, SpsoCost};
use super::height_map::HeightMap;
use crate::error::{Fault, InputError};
use crate::geometry::{from_utm, UtmZone};
use crate::terrain::Composite;

/// Seed 000's orchard, embedded so that `agripath repro` needs no files.
pub const ORCHARD_JSON: &str = include_str!("../../../../data/seed000_orchard.json");
/// Seed 002's survey space.
pub const SURVEY_JSON: &str = include_str!("../../../../data/seed002_field_survey.json");
/// SPSO's public scenario and its DEM (Christmas Island, 5 m pixels; BSD-style licence in
/// `data/spso/LICENSE-SPSO.txt`).
pub const SPSO_JSON: &str = include_str!("../../../../data/spso/scenario.json");
pub const SPSO_DEM: &[u8] = include_bytes!("../../../../data/spso/ChrismasTerrain.tif");

/// A vertical cylinder the track must not enter (2D: centre and radius).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Threat {
    pub x: f64,
    pub y: f64,
    pub radius: f64,
}

/// What a waypoint's z means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AltitudeReference {
    /// Height above the terrain (SPSO's nodes).
    AboveGround,
    /// Height above sea level (seeds 000 and 002: "z relative to sea level").
    SeaLevel,
}

/// Where the scenario's plane lies on Earth, for mission files.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Georeference {
    /// Metres east and north of a longitude/latitude.
    Local { lon: f64, lat: f64 },
    /// UTM metres of a zone: the scenario was given in longitude/latitude, and its outputs
    /// go back to longitude/latitude.
    Utm { zone: UtmZone },
    /// SPSO's pixel units on a UTM raster: x = column + 1, y = row + 1 from the top-left
    /// pixel, whose corner is at (easting, northing).
    Pixels {
        zone: UtmZone,
        easting: f64,
        northing: f64,
        pixel_m: f64,
    },
}

/// One track problem.
#[derive(Debug, Clone)]
pub struct TrackScenario {
    pub name: String,
    pub terrain: HeightMap,
    /// Waypoints stay in [min_x, max_x] × [min_y, max_y].
    pub area: (f64, f64, f64, f64),
    /// Waypoint altitudes stay in [low, high], in `altitude_reference`.
    pub altitude_bounds: (f64, f64),
    pub altitude_reference: AltitudeReference,
    /// Start and goal: x, y and z in `altitude_reference`.
    pub start: [f64; 3],
    pub goal: [f64; 3],
    pub threats: Vec<Threat>,
    /// Height above ground the track should keep, when the scenario has a band.
    pub height_band: Option<(f64, f64)>,
    pub free_waypoints: usize,
    pub cost: CostModel,
    /// Population and iterations the scenario's paper uses.
    pub population: usize,
    pub iterations: usize,
    pub georeference: Georeference,
    /// Horizontal unit in metres (1 for the seeds, 5 for SPSO's pixels).
    pub unit_m: f64,
}

impl TrackScenario {
    /// Altitude above sea level of a point given in `altitude_reference`.
    pub fn sea_level(&self, point: [f64; 3]) -> [f64; 3] {
        match self.altitude_reference {
            AltitudeReference::SeaLevel => point,
            AltitudeReference::AboveGround => [
                point[0],
                point[1],
                point[2] + self.terrain.height(point[0], point[1]),
            ],
        }
    }

    /// Longitude, latitude of a planar point.
    pub fn lon_lat(&self, x: f64, y: f64) -> (f64, f64) {
        match self.georeference {
            Georeference::Local { lon, lat } => {
                let zone = UtmZone::containing(lon, lat);
                let (easting, northing) = crate::geometry::to_utm(lon, lat, zone);
                from_utm(easting + x, northing + y, zone)
            }
            Georeference::Utm { zone } => from_utm(x, y, zone),
            Georeference::Pixels {
                zone,
                easting,
                northing,
                pixel_m,
            } => from_utm(
                easting + (x - 0.5) * pixel_m,
                northing - (y - 0.5) * pixel_m,
                zone,
            ),
        }
    }

    /// A planar point as the scenario's input gave it: longitude/latitude for a scenario in
    /// lon/lat, the scenario's own x, y otherwise.
    pub fn to_input(&self, x: f64, y: f64) -> (f64, f64) {
        match self.georeference {
            Georeference::Utm { .. } => self.lon_lat(x, y),
            _ => (x, y),
        }
    }

    /// Whether outputs are in the scenario's local frame (not longitude/latitude).
    pub fn is_local(&self) -> bool {
        !matches!(self.georeference, Georeference::Utm { .. })
    }

    /// The straight start-goal distance (horizontal), in the scenario's units.
    pub fn start_goal_distance(&self) -> f64 {
        (self.goal[0] - self.start[0]).hypot(self.goal[1] - self.start[1])
    }

    /// Reads a scenario file; `task` picks one of seed 000's tasks ("I", "II", "III").
    pub fn read(path: &Path, task: Option<&str>) -> Result<Self, InputError> {
        let text = std::fs::read_to_string(path)
            .map_err(|error| InputError::new(path, Fault::Unreadable(error.to_string())))?;
        if text.trim().is_empty() {
            return Err(InputError::new(path, Fault::Empty));
        }
        if crate::input::extension_of(path) == "toml" {
            return super::operator::read(path, &text);
        }
        let value: Value = serde_json::from_str(&text)
            .map_err(|error| InputError::new(path, Fault::Json(error.to_string())))?;
        let directory = path.parent().unwrap_or(Path::new("."));
        Self::from_value(&value, task, &|name| {
            let dem = directory.join(name);
            std::fs::read(&dem)
                .map_err(|error| InputError::new(&dem, Fault::Unreadable(error.to_string())))
        })
        .map_err(|error| match error {
            Loaded::Input(error) => error,
            Loaded::Fault(fault) => InputError::new(path, fault),
        })
    }

    fn from_value(
        value: &Value,
        task: Option<&str>,
        read_dem: &dyn Fn(&str) -> Result<Vec<u8>, InputError>,
    ) -> Result<Self, Loaded> {
        if value.get("tasks").is_some() {
            Ok(orchard(value, task.unwrap_or("I"))?)
        } else if value.get("ga").is_some() {
            Ok(survey(value)?)
        } else if value.get("threat_cylinders_x_y_z_r").is_some() {
            let name = text(value, "dem.file")?;
            let bytes = read_dem(&name).map_err(Loaded::Input)?;
            Ok(spso(value, &bytes)?)
        } else {
            Err(Loaded::Fault(Fault::Structure(
                "not a track scenario: expected seed 000's \"tasks\", seed 002's \"ga\" or SPSO's \"threat_cylinders_x_y_z_r\""
                    .into(),
            )))
        }
    }

    /// Seed 000's task "I", "II" or "III" (embedded).
    pub fn seed000(task: &str) -> Result<Self, Fault> {
        orchard(&embedded(ORCHARD_JSON), task)
    }

    /// Seed 002's survey space (embedded).
    pub fn seed002() -> Result<Self, Fault> {
        survey(&embedded(SURVEY_JSON))
    }

    /// SPSO's public scenario (embedded, with its DEM).
    pub fn spso() -> Result<Self, Fault> {
        spso(&embedded(SPSO_JSON), SPSO_DEM)
    }
}

/// Why an embedded or read scenario failed: a fault in the file, or another file's error.
enum Loaded {
    Fault(Fault),
    Input(InputError),
}

impl From<Fault> for Loaded {
    fn from(fault: Fault) -> Self {
        Loaded::Fault(fault)
    }
}

fn embedded(text: &str) -> Value {
    serde_json::from_str(text).expect("embedded scenario is valid JSON")
}

/// The value at a dotted path.
fn lookup<'a>(value: &'a Value, path: &str) -> Result<&'a Value, Fault> {
    path.split('.').try_fold(value, |inner, key| {
        inner
            .get(key)
            .ok_or_else(|| Fault::Structure(format!("missing key '{path}'")))
    })
}

fn text(value: &Value, path: &str) -> Result<String, Fault> {
    lookup(value, path)?
        .as_str()
        .map(str::to_owned)
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be a string")))
}

fn number(value: &Value, path: &str) -> Result<f64, Fault> {
    let number = lookup(value, path)?
        .as_f64()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be a number")))?;
    if number.is_finite() {
        Ok(number)
    } else {
        Err(Fault::NonFinite)
    }
}

fn numbers(value: &Value, path: &str) -> Result<Vec<f64>, Fault> {
    let array = lookup(value, path)?
        .as_array()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be an array of numbers")))?;
    array
        .iter()
        .map(|item| {
            item.as_f64()
                .filter(|number| number.is_finite())
                .ok_or_else(|| Fault::Structure(format!("'{path}' must hold finite numbers")))
        })
        .collect()
}

fn point(value: &Value, path: &str) -> Result<[f64; 3], Fault> {
    let values = numbers(value, path)?;
    <[f64; 3]>::try_from(values.as_slice())
        .map_err(|_| Fault::Structure(format!("'{path}' must be [x, y, z]")))
}

fn threats(rows: &Value, path: &str, width: usize) -> Result<Vec<Threat>, Fault> {
    let rows = rows
        .as_array()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be an array of cylinders")))?;
    rows.iter()
        .enumerate()
        .map(|(index, row)| {
            let values: Option<Vec<f64>> = row
                .as_array()
                .map(|items| items.iter().filter_map(Value::as_f64).collect());
            match values {
                Some(values) if values.len() == width && values.iter().all(|v| v.is_finite()) => {
                    let radius = values[width - 1];
                    if radius <= 0.0 {
                        return Err(Fault::InvalidValue {
                            what: format!("{path}[{index}] radius"),
                            value: radius.to_string(),
                            why: "a threat cylinder needs a positive radius".into(),
                        });
                    }
                    Ok(Threat {
                        x: values[0],
                        y: values[1],
                        radius,
                    })
                }
                _ => Err(Fault::Structure(format!(
                    "'{path}[{index}]' must hold {width} finite numbers"
                ))),
            }
        })
        .collect()
}

/// Checks that start and goal lie in the area and the band makes sense.
pub(super) fn validated(scenario: TrackScenario) -> Result<TrackScenario, Fault> {
    let (min_x, min_y, max_x, max_y) = scenario.area;
    for (what, point) in [("start", scenario.start), ("goal", scenario.goal)] {
        if !(min_x..=max_x).contains(&point[0]) || !(min_y..=max_y).contains(&point[1]) {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: format!("({}, {})", point[0], point[1]),
                why: format!("outside the planning area [{min_x}, {max_x}] × [{min_y}, {max_y}]"),
            });
        }
    }
    if let Some((low, high)) = scenario.height_band {
        if low.partial_cmp(&high) != Some(std::cmp::Ordering::Less) {
            return Err(Fault::InvalidValue {
                what: "height band".into(),
                value: format!("[{low}, {high}]"),
                why: "needs lower < upper".into(),
            });
        }
    }
    if !(max_x - min_x > 0.0
        && max_y - min_y > 0.0
        && scenario.altitude_bounds.1 > scenario.altitude_bounds.0)
    {
        return Err(Fault::InvalidValue {
            what: "planning space".into(),
            value: format!(
                "[{min_x}, {max_x}] × [{min_y}, {max_y}] × {:?}",
                scenario.altitude_bounds
            ),
            why: "needs a positive width, depth and height".into(),
        });
    }
    if !(2..=100_000).contains(&scenario.population)
        || !(1..=1_000_000).contains(&scenario.iterations)
    {
        return Err(Fault::InvalidValue {
            what: "population / iterations".into(),
            value: format!("{} / {}", scenario.population, scenario.iterations),
            why: "need a population of 2..=100000 and 1..=1000000 iterations".into(),
        });
    }
    if scenario.free_waypoints == 0 || scenario.free_waypoints > 100 {
        return Err(Fault::InvalidValue {
            what: "free waypoints".into(),
            value: scenario.free_waypoints.to_string(),
            why: "must be 1..=100".into(),
        });
    }
    Ok(scenario)
}

fn orchard(value: &Value, task: &str) -> Result<TrackScenario, Fault> {
    let tasks = lookup(value, "tasks")?
        .as_array()
        .ok_or_else(|| Fault::Structure("'tasks' must be an array".into()))?;
    let chosen = tasks
        .iter()
        .find(|item| item.get("name").and_then(Value::as_str) == Some(task))
        .ok_or_else(|| Fault::InvalidValue {
            what: "task".into(),
            value: task.into(),
            why: "the orchard has tasks I, II and III".into(),
        })?;
    let band = numbers(value, "height_band_agl_m")?;
    let extent = numbers(value, "terrain.extent_m")?;
    if band.len() != 2 || extent.len() != 3 {
        return Err(Fault::Structure(
            "'height_band_agl_m' needs [low, high] and 'terrain.extent_m' [x, y, z]".into(),
        ));
    }
    let terrain = Composite::seed000();
    let map = HeightMap::sample(&terrain, (0.0, 0.0, extent[0], extent[1]), 1.0)?;
    validated(TrackScenario {
        name: format!("seed 000 task {task}"),
        terrain: map,
        area: (0.0, 0.0, extent[0], extent[1]),
        altitude_bounds: (0.0, extent[2]),
        altitude_reference: AltitudeReference::SeaLevel,
        start: point(chosen, "start")?,
        goal: point(chosen, "goal")?,
        threats: threats(
            lookup(chosen, "threat_cylinders_x_y_r")?,
            "threat_cylinders_x_y_r",
            3,
        )?,
        height_band: Some((band[0], band[1])),
        free_waypoints: number(value, "free_waypoints")? as usize,
        cost: CostModel::Seed000(Seed000Cost::default()),
        population: number(value, "algorithms.population")? as usize,
        iterations: number(value, "algorithms.iterations")? as usize,
        // Guangzhou, the mango orchard of seed 000 §5.3.
        georeference: Georeference::Local {
            lon: 113.36,
            lat: 23.16,
        },
        unit_m: 1.0,
    })
}

fn survey(value: &Value) -> Result<TrackScenario, Fault> {
    let extent = numbers(value, "extent_m")?;
    if extent.len() != 3 {
        return Err(Fault::Structure("'extent_m' needs [x, y, z]".into()));
    }
    let terrain = Composite::seed002();
    let map = HeightMap::sample(&terrain, (0.0, 0.0, extent[0], extent[1]), 1.0)?;
    validated(TrackScenario {
        name: "seed 002 field survey".into(),
        terrain: map,
        area: (0.0, 0.0, extent[0], extent[1]),
        altitude_bounds: (number(value, "min_altitude_m")?, extent[2]),
        altitude_reference: AltitudeReference::SeaLevel,
        start: point(value, "start")?,
        goal: point(value, "goal")?,
        threats: Vec::new(),
        height_band: None,
        free_waypoints: number(value, "ga.chromosome_length")? as usize,
        cost: CostModel::Seed002(Seed002Cost),
        population: number(value, "ga.population")? as usize,
        iterations: number(value, "ga.generations")? as usize,
        // Xi'an, Shaanxi: seed 002's university.
        georeference: Georeference::Local {
            lon: 108.95,
            lat: 34.27,
        },
        unit_m: 1.0,
    })
}

fn spso(value: &Value, dem: &[u8]) -> Result<TrackScenario, Fault> {
    let grid = crate::terrain::geotiff::decode(dem)?;
    let map = HeightMap::from_grid_in_pixel_units(&grid);
    let band = numbers(value, "altitude_band_agl")?;
    if band.len() != 2 {
        return Err(Fault::Structure(
            "'altitude_band_agl' needs [low, high]".into(),
        ));
    }
    let settings = lookup(value, "pso_reference_settings")?;
    // The raster's top-left corner: the centre of pixel (0, 0) minus half a pixel.
    let zone = UtmZone {
        number: 48,
        south: true,
    };
    validated(TrackScenario {
        name: "SPSO public scenario (Christmas Island)".into(),
        area: (1.0, 1.0, grid.columns as f64, grid.rows as f64),
        terrain: map,
        altitude_bounds: (band[0], band[1]),
        altitude_reference: AltitudeReference::AboveGround,
        start: point(value, "start_xyz_agl")?,
        goal: point(value, "goal_xyz_agl")?,
        threats: threats(
            lookup(value, "threat_cylinders_x_y_z_r")?,
            "threat_cylinders_x_y_z_r",
            4,
        )?,
        height_band: Some((band[0], band[1])),
        free_waypoints: number(value, "free_nodes")? as usize,
        cost: CostModel::Spso(SpsoCost::default()),
        population: number(settings, "population")? as usize,
        iterations: number(settings, "iterations")? as usize,
        georeference: Georeference::Pixels {
            zone,
            easting: grid.first_center_x - 0.5 * grid.cell_x,
            northing: grid.first_center_y + 0.5 * grid.cell_y,
            pixel_m: grid.cell_x,
        },
        unit_m: grid.cell_x,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_scenarios_load() {
        for task in ["I", "II", "III"] {
            let scenario = TrackScenario::seed000(task).unwrap();
            assert_eq!(scenario.free_waypoints, 12);
            assert_eq!((scenario.population, scenario.iterations), (500, 300));
        }
        assert_eq!(TrackScenario::seed000("I").unwrap().threats.len(), 8);
        assert_eq!(TrackScenario::seed000("III").unwrap().threats.len(), 12);
        assert!(TrackScenario::seed000("IV").is_err());
        let survey = TrackScenario::seed002().unwrap();
        assert_eq!(
            (survey.population, survey.iterations, survey.free_waypoints),
            (50, 30, 9)
        );
        let spso = TrackScenario::spso().unwrap();
        assert_eq!(spso.area, (1.0, 1.0, 1045.0, 879.0));
        assert_eq!(spso.threats.len(), 6);
        assert_eq!((spso.population, spso.iterations), (500, 200));
    }

    #[test]
    fn spso_pixels_follow_matlab_row_order() {
        // H(y, x) in the reference is row y (from the top), column x, both from 1.
        let spso = TrackScenario::spso().unwrap();
        let grid = crate::terrain::geotiff::decode(SPSO_DEM).unwrap();
        for &(x, y) in &[(1usize, 1usize), (200, 100), (800, 800), (1045, 879)] {
            let expected = f64::from(grid.cell(y - 1, x - 1).max(0.0));
            assert_eq!(spso.terrain.height(x as f64, y as f64), expected);
        }
        // Pixel (1, 1) lies at the raster's north-west corner on Christmas Island.
        let (lon, lat) = spso.lon_lat(1.0, 1.0);
        assert!(
            (105.5..105.8).contains(&lon) && (-10.6..-10.3).contains(&lat),
            "{lon} {lat}"
        );
    }
}
