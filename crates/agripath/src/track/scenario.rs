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
//!
//! Every key a file gives is used or refused: the planning keys are read (seed 000's
//! `terrain.coefficients` and `terrain.hills` build its terrain; `start`/`goal` may sit at
//! the top level or per task), the papers' algorithm settings must equal the ones the
//! planners run (else exit 2: they are not settings of a scenario), the documentation keys
//! (`source`, `note`, `reference`, ...) are the papers' own figures kept beside the data, and
//! any other key is an error naming it (decision 0013).
//!
//! A start or goal below the height band's floor (on the ground, say) is reached by a
//! vertical leg: the drone climbs above the start to the floor, flies the cruise (the free
//! waypoints the planners search, between [`TrackScenario::cruise_start`] and
//! [`TrackScenario::cruise_goal`]), and descends at the goal.

use std::path::Path;
use std::sync::Arc;

use serde_json::Value;

use super::cost::{CostModel, Seed000Cost, Seed002Cost, SpsoCost};
use super::height_map::HeightMap;
use crate::error::{Fault, InputError};
use crate::geometry::{from_utm, UtmZone};
use crate::terrain::composite::Hill;
use crate::terrain::{Composite, Extent, Terrain};

/// Cell of the raster the planners read an analytic terrain on. The legs' samples are one
/// cell apart (`HeightMap::leg_excess`); 2 m keeps them under half the shortest period of the
/// composite formula's ripples (2π m) and one IBA-FCS run under a second. The raster is
/// within 0.6 m of the formula (test `the_orchard_raster_follows_its_formula`); the costs see
/// the ground raised by that error ([`TrackScenario::cost_clearance`]) and the verdict reads
/// the formula itself.
pub const ORCHARD_CELL_M: f64 = 2.0;

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
    /// The terrain as given, for the safety verdict (the planners' `terrain` is a raster of it).
    pub ground_truth: GroundTruth,
    /// What the safety verdict requires.
    pub limits: SafetyLimits,
    /// Where the cruise begins and ends (in `altitude_reference`): above the start and the
    /// goal at the band's floor when they are below it, else the start and the goal.
    pub cruise_start: [f64; 3],
    pub cruise_goal: [f64; 3],
    /// Runs the scenario's paper makes (seed 000's `algorithms.runs`), the default of `--runs`.
    pub paper_runs: Option<u64>,
}

/// The terrain a track is checked against: the formula of an analytic terrain, or a DEM on
/// its own cells, never a coarser resample.
#[derive(Clone)]
pub enum GroundTruth {
    /// The height map's bilinear surface (the map holds the DEM's own cells).
    Raster,
    /// A terrain model: a formula, or a DEM read at its cells.
    Model(Arc<dyn Terrain>),
}

impl std::fmt::Debug for GroundTruth {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            GroundTruth::Raster => write!(formatter, "Raster"),
            GroundTruth::Model(model) => write!(formatter, "Model({})", model.describe()),
        }
    }
}

/// What a safe track keeps: clearance above the terrain and distance from threat walls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SafetyLimits {
    /// Least height above the terrain along the cruise (metres); `--min-clearance`.
    pub min_clearance_m: f64,
    /// The vehicle's radius: least distance from a threat cylinder's wall (metres);
    /// `--vehicle-radius`.
    pub vehicle_radius_m: f64,
}

impl Default for SafetyLimits {
    fn default() -> Self {
        Self {
            min_clearance_m: 2.0,
            vehicle_radius_m: 1.0,
        }
    }
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

    /// The leg of the straight track through the free waypoints: the length over which the
    /// costs spread a band excursion measured along legs (one waypoint's worth).
    pub fn reference_leg(&self) -> f64 {
        (self.start_goal_distance() / (self.free_waypoints + 1) as f64).max(1e-9)
    }

    /// The height above the planners' raster that the costs treat as the ground: the
    /// verdict's minimum clearance plus the raster's error (the orchard's raster is within
    /// 0.6 m of its formula; a DEM resampled at 2 m, within a few decimetres of its cells).
    pub fn cost_clearance(&self) -> f64 {
        self.limits.min_clearance_m + 0.6
    }

    /// The height of the terrain as given (the verdict's ground), `None` off the model.
    pub fn true_ground(&self, x: f64, y: f64) -> Option<f64> {
        match &self.ground_truth {
            GroundTruth::Raster => Some(self.terrain.bilinear(x, y)),
            GroundTruth::Model(model) => model.height_m(x, y).ok(),
        }
    }

    /// Whether the track climbs vertically from the start to the cruise.
    pub fn takes_off(&self) -> bool {
        self.cruise_start != self.start
    }

    /// Whether the track descends vertically from the cruise to the goal.
    pub fn lands(&self) -> bool {
        self.cruise_goal != self.goal
    }

    /// The whole track from a cruise (both in sea-level altitudes): the takeoff leg, the
    /// cruise, the landing leg.
    pub fn whole_track(&self, cruise: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut points = Vec::with_capacity(cruise.len() + 2);
        if self.takes_off() {
            points.push(self.sea_level(self.start));
        }
        points.extend_from_slice(cruise);
        if self.lands() {
            points.push(self.sea_level(self.goal));
        }
        points
    }

    /// The cruise of a whole track, and the length of its vertical legs.
    pub fn cruise_of<'p>(&self, points: &'p [[f64; 3]]) -> (&'p [[f64; 3]], f64) {
        let head = usize::from(self.takes_off());
        let tail = usize::from(self.lands());
        if points.len() < head + tail + 2 {
            return (points, 0.0);
        }
        let cruise = &points[head..points.len() - tail];
        let vertical = (self.cruise_start[2] - self.start[2]).abs() * head as f64
            + (self.cruise_goal[2] - self.goal[2]).abs() * tail as f64;
        (cruise, vertical)
    }

    /// The cost of a whole track: the model's cost of the cruise, plus the vertical legs'
    /// length (at the model's length weight; their angles are a takeoff and a landing, not
    /// turns of the cruise).
    pub fn evaluate(&self, points: &[[f64; 3]]) -> super::cost::CostBreakdown {
        let (cruise, vertical) = self.cruise_of(points);
        let mut breakdown = self.cost.evaluate(self, cruise);
        breakdown.terms[0] += vertical;
        breakdown.total += self.cost.length_weight() * vertical;
        breakdown
    }

    /// The same scenario checked with other safety limits (start and goal checked again).
    pub fn with_limits(mut self, limits: SafetyLimits) -> Result<Self, Fault> {
        for (what, value) in [
            ("--min-clearance", limits.min_clearance_m),
            ("--vehicle-radius", limits.vehicle_radius_m),
        ] {
            if !(0.0..=1000.0).contains(&value) {
                return Err(Fault::InvalidValue {
                    what: what.into(),
                    value: value.to_string(),
                    why: "must be 0..=1000 metres".into(),
                });
            }
        }
        self.limits = limits;
        validated(self)
    }

    /// Reads a scenario file; `task` picks one of seed 000's tasks ("I", "II", "III").
    pub fn read(path: &Path, task: Option<&str>) -> Result<Self, InputError> {
        let text = crate::files::read_text(path)?;
        if crate::files::extension_of(path) == "toml" {
            return super::operator::read(path, &text);
        }
        let value: Value = serde_json::from_str(&text)
            .map_err(|error| InputError::new(path, Fault::Json(error.to_string())))?;
        let directory = path.parent().unwrap_or(Path::new("."));
        Self::from_value(&value, task, &|name| {
            let dem = directory.join(name);
            crate::files::read_bytes(&dem)
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

/// Refuses any key of the object at `path` that is not in `known` (`path` "" for the top).
fn only_keys(value: &Value, path: &str, known: &[&str]) -> Result<(), Fault> {
    let Some(object) = value.as_object() else {
        return Err(Fault::Structure(format!(
            "'{}' must be an object",
            if path.is_empty() {
                "the scenario"
            } else {
                path
            }
        )));
    };
    match object.keys().find(|key| !known.contains(&key.as_str())) {
        None => Ok(()),
        Some(key) => {
            let full = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            Err(Fault::Structure(format!(
                "unknown key '{full}' (known here: {})",
                known.join(", ")
            )))
        }
    }
}

/// A paper's algorithm setting given in a scenario must be the one the planner runs.
fn expect_setting(value: &Value, path: &str, expected: f64) -> Result<(), Fault> {
    if lookup(value, path).is_err() {
        return Ok(());
    }
    let given = number(value, path)?;
    if (given - expected).abs() <= 1e-9 * expected.abs().max(1.0) {
        Ok(())
    } else {
        Err(Fault::InvalidValue {
            what: path.into(),
            value: given.to_string(),
            why: format!(
                "the planner runs the paper's {expected}; algorithm settings are not scenario settings"
            ),
        })
    }
}

/// A whole number of at least 0 (and at most `most`).
fn count(value: &Value, path: &str, most: f64) -> Result<usize, Fault> {
    let given = number(value, path)?;
    if given.fract() == 0.0 && (0.0..=most).contains(&given) {
        Ok(given as usize)
    } else {
        Err(Fault::InvalidValue {
            what: path.into(),
            value: given.to_string(),
            why: format!("must be a whole number in 0..={most}"),
        })
    }
}

/// The composite terrain a file describes: its `coefficients` a..g and `hills` when given,
/// else `default`'s, over `extent`.
fn composite(terrain: &Value, default: Composite, extent: Extent) -> Result<Composite, Fault> {
    let kind = match terrain.get("kind") {
        Some(_) => text(terrain, "kind")?,
        None => "composite".into(),
    };
    if kind != "composite" {
        return Err(Fault::InvalidValue {
            what: "terrain.kind".into(),
            value: kind,
            why: "track scenarios in JSON have the composite terrain of seeds 000/002".into(),
        });
    }
    let mut model = Composite { extent, ..default };
    if let Some(coefficients) = terrain.get("coefficients") {
        const NAMES: [&str; 7] = ["a", "b", "c", "d", "e", "f", "g"];
        only_keys(coefficients, "terrain.coefficients", &NAMES)?;
        for (slot, name) in model.coefficients.iter_mut().zip(NAMES) {
            *slot = number(coefficients, name).map_err(|_| {
                Fault::Structure(format!(
                    "'terrain.coefficients.{name}' must be a finite number"
                ))
            })?;
        }
    }
    if let Some(hills) = terrain.get("hills") {
        const NAMES: [&str; 5] = ["h", "x", "y", "xs", "ys"];
        only_keys(hills, "terrain.hills", &NAMES)?;
        let columns = NAMES
            .iter()
            .map(|name| {
                numbers(hills, name).map_err(|_| {
                    Fault::Structure(format!(
                        "'terrain.hills.{name}' must be an array of finite numbers"
                    ))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let length = columns[0].len();
        if columns.iter().any(|column| column.len() != length) || length > 1000 {
            return Err(Fault::Structure(
                "'terrain.hills' needs h, x, y, xs and ys of one length (at most 1000 hills)"
                    .into(),
            ));
        }
        model.hills = (0..length)
            .map(|index| Hill {
                height_m: columns[0][index],
                x_m: columns[1][index],
                y_m: columns[2][index],
                spread_x_m: columns[3][index],
                spread_y_m: columns[4][index],
            })
            .collect();
        if let Some(index) = model.hills.iter().position(|hill| {
            hill.spread_x_m <= 0.0 || hill.spread_y_m <= 0.0 || hill.height_m.abs() > 1.0e4
        }) {
            return Err(Fault::InvalidValue {
                what: format!("terrain.hills[{index}]"),
                value: format!("{:?}", model.hills[index]),
                why: "spreads must be positive and heights within ±10 km".into(),
            });
        }
    }
    if let Some(scale) = terrain.get("height_scale") {
        let scale = scale
            .as_f64()
            .filter(|scale| scale.is_finite() && *scale > 0.0)
            .ok_or_else(|| {
                Fault::Structure("'terrain.height_scale' must be a positive number".into())
            })?;
        model.height_scale = scale;
    }
    Ok(model)
}

/// The file's composite terrain over [0, x] × [0, y] of `extent`, and the planners' raster of
/// it.
fn composite_over(
    value: &Value,
    default: Composite,
    extent: &[f64],
) -> Result<(Composite, HeightMap), Fault> {
    let area = Extent {
        min_x: 0.0,
        min_y: 0.0,
        max_x: extent[0],
        max_y: extent[1],
    };
    let terrain = composite(lookup(value, "terrain")?, default, area)?;
    let map = HeightMap::sample(&terrain, (0.0, 0.0, extent[0], extent[1]), ORCHARD_CELL_M)?;
    Ok((terrain, map))
}

/// Checks that start and goal lie in the area, above the terrain and outside every threat,
/// that the band makes sense, and places the cruise's ends.
pub(super) fn validated(mut scenario: TrackScenario) -> Result<TrackScenario, Fault> {
    let (min_x, min_y, max_x, max_y) = scenario.area;
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
    if let Some((low, high)) = scenario.height_band {
        if low.partial_cmp(&high) != Some(std::cmp::Ordering::Less) || low < 0.0 {
            return Err(Fault::InvalidValue {
                what: "height band".into(),
                value: format!("[{low}, {high}]"),
                why: "needs 0 ≤ lower < upper".into(),
            });
        }
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
    if scenario.threats.len() > 1000 {
        return Err(Fault::InvalidValue {
            what: "threat cylinders".into(),
            value: scenario.threats.len().to_string(),
            why: "at most 1000".into(),
        });
    }
    // Within a metre of each other there is no track to plan (and the length term, which
    // divides by the start-goal distance, would be meaningless).
    let apart_m = (0..3)
        .map(|axis| (scenario.goal[axis] - scenario.start[axis]).powi(2))
        .sum::<f64>()
        .sqrt()
        * scenario.unit_m;
    if apart_m.is_nan() || apart_m < 1.0 {
        return Err(Fault::InvalidValue {
            what: "start and goal".into(),
            value: format!("{:?} and {:?}", scenario.start, scenario.goal),
            why: format!(
                "they are {apart_m:.2} m apart: a track needs two places at least 1 m apart"
            ),
        });
    }
    let radius_units = scenario.limits.vehicle_radius_m / scenario.unit_m;
    let floor = scenario
        .height_band
        .map_or(0.0, |(low, _)| low)
        .max(scenario.limits.min_clearance_m);
    let mut ends = [scenario.start, scenario.goal];
    for (what, point) in ["start", "goal"].into_iter().zip(ends.iter_mut()) {
        let place = format!("({}, {})", point[0], point[1]);
        if !(min_x..=max_x).contains(&point[0]) || !(min_y..=max_y).contains(&point[1]) {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!("outside the planning area [{min_x}, {max_x}] × [{min_y}, {max_y}]"),
            });
        }
        if let Some((index, threat)) = scenario.threats.iter().enumerate().find(|(_, threat)| {
            (point[0] - threat.x).hypot(point[1] - threat.y) < threat.radius + radius_units
        }) {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!(
                    "inside threat cylinder {index} (centre ({}, {}), radius {}, plus the vehicle's {} m)",
                    threat.x, threat.y, threat.radius, scenario.limits.vehicle_radius_m
                ),
            });
        }
        let ground = scenario.terrain.height(point[0], point[1]);
        let above = match scenario.altitude_reference {
            AltitudeReference::AboveGround => point[2],
            AltitudeReference::SeaLevel => {
                let truth = scenario.true_ground(point[0], point[1]).unwrap_or(ground);
                point[2] - truth
            }
        };
        if above < -1e-6 {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: format!("({}, {}, {})", point[0], point[1], point[2]),
                why: format!("{:.2} m under the terrain", -above),
            });
        }
        if above < floor {
            // A vertical leg to the floor: sea-level altitudes over the true ground.
            point[2] = match scenario.altitude_reference {
                AltitudeReference::AboveGround => floor,
                AltitudeReference::SeaLevel => point[2] + (floor - above),
            };
        }
        let (_, high) = scenario.altitude_bounds;
        if scenario.altitude_reference == AltitudeReference::SeaLevel && point[2] > high {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!(
                    "the band's floor above it ({:.1} m) is above the space's ceiling ({high} m)",
                    point[2]
                ),
            });
        }
    }
    [scenario.cruise_start, scenario.cruise_goal] = ends;
    Ok(scenario)
}

/// A task's point: its own `key`, else the scenario's top-level one.
fn task_point(scenario: &Value, task: &Value, key: &str) -> Result<[f64; 3], Fault> {
    if task.get(key).is_some() {
        point(task, key)
    } else if scenario.get(key).is_some() {
        point(scenario, key)
    } else {
        Err(Fault::Structure(format!(
            "missing key '{key}' (in the task or at the top level)"
        )))
    }
}

/// Keys of the papers' own figures and notes, kept beside the data (decision 0013).
const DOCUMENTATION: [&str; 5] = [
    "source",
    "note",
    "threat_note",
    "reference",
    "field_experiment",
];

fn orchard(value: &Value, task: &str) -> Result<TrackScenario, Fault> {
    let top = [
        "name",
        "terrain",
        "height_band_agl_m",
        "free_waypoints",
        "tasks",
        "algorithms",
        "iba_fcs_parameters",
        "start",
        "goal",
    ];
    let known: Vec<&str> = top.iter().chain(&DOCUMENTATION).copied().collect();
    only_keys(value, "", &known)?;
    only_keys(
        lookup(value, "terrain")?,
        "terrain",
        &[
            "kind",
            "formula",
            "coefficients",
            "hills",
            "height_scale",
            "extent_m",
            "decisions",
            "note",
        ],
    )?;
    only_keys(
        lookup(value, "algorithms")?,
        "algorithms",
        &["population", "iterations", "runs"],
    )?;
    if let Some(parameters) = value.get("iba_fcs_parameters") {
        let paper = swarm::algorithms::IbaFcsParameters::default();
        only_keys(
            parameters,
            "iba_fcs_parameters",
            &[
                "omega_max",
                "omega_min",
                "alpha_b",
                "gamma_b",
                "S_F",
                "f_min",
                "f_max",
                "mu_max",
                "mu_min",
                "A_min",
                "R_max",
                "g_k",
            ],
        )?;
        for (key, expected) in [
            ("omega_max", paper.omega_max),
            ("omega_min", paper.omega_min),
            ("alpha_b", paper.alpha_b),
            ("gamma_b", paper.gamma_b),
            ("S_F", paper.frequency_sum),
            ("f_min", paper.frequency_min),
            ("f_max", paper.frequency_max),
            ("mu_max", paper.mu_max),
            ("mu_min", paper.mu_min),
            ("A_min", paper.loudness_min),
            ("R_max", paper.pulse_rate_max),
            ("g_k.a_g", paper.step_scale),
        ] {
            expect_setting(value, &format!("iba_fcs_parameters.{key}"), expected)?;
        }
        if let Some(decay) = parameters.get("g_k") {
            only_keys(decay, "iba_fcs_parameters.g_k", &["a_g", "b"])?;
            if decay.get("b").is_some() && numbers(decay, "b")? != paper.step_exponents {
                return Err(Fault::InvalidValue {
                    what: "iba_fcs_parameters.g_k.b".into(),
                    value: format!("{:?}", numbers(decay, "b")?),
                    why: format!("the planner runs the paper's {:?}; algorithm settings are not scenario settings", paper.step_exponents),
                });
            }
        }
    }
    let tasks = lookup(value, "tasks")?
        .as_array()
        .ok_or_else(|| Fault::Structure("'tasks' must be an array".into()))?;
    for (index, item) in tasks.iter().enumerate() {
        only_keys(
            item,
            &format!("tasks[{index}]"),
            &["name", "start", "goal", "threat_cylinders_x_y_r"],
        )?;
    }
    let chosen = tasks
        .iter()
        .find(|item| item.get("name").and_then(Value::as_str) == Some(task))
        .ok_or_else(|| {
            let names: Vec<&str> = tasks
                .iter()
                .filter_map(|item| item.get("name").and_then(Value::as_str))
                .collect();
            Fault::InvalidValue {
                what: "task".into(),
                value: task.into(),
                why: format!("the scenario has tasks {}", names.join(", ")),
            }
        })?;
    let band = numbers(value, "height_band_agl_m")?;
    let extent = numbers(value, "terrain.extent_m")?;
    if band.len() != 2
        || extent.len() != 3
        || extent.iter().any(|side| *side <= 0.0 || *side > 1.0e5)
    {
        return Err(Fault::Structure(
            "'height_band_agl_m' needs [low, high] and 'terrain.extent_m' [x, y, z] (positive, at most 100 km)".into(),
        ));
    }
    let (terrain, map) = composite_over(value, Composite::seed000(), &extent)?;
    let runs = match lookup(value, "algorithms.runs") {
        Ok(_) => Some(count(value, "algorithms.runs", 1000.0)?.max(1) as u64),
        Err(_) => None,
    };
    validated(TrackScenario {
        name: match value.get("name") {
            Some(_) => format!("{}, task {task}", text(value, "name")?),
            None => format!("seed 000 task {task}"),
        },
        terrain: map,
        area: (0.0, 0.0, extent[0], extent[1]),
        altitude_bounds: (0.0, extent[2]),
        altitude_reference: AltitudeReference::SeaLevel,
        start: task_point(value, chosen, "start")?,
        goal: task_point(value, chosen, "goal")?,
        threats: threats(
            lookup(chosen, "threat_cylinders_x_y_r")?,
            "threat_cylinders_x_y_r",
            3,
        )?,
        height_band: Some((band[0], band[1])),
        free_waypoints: count(value, "free_waypoints", 100.0)?,
        cost: CostModel::Seed000(Seed000Cost::default()),
        population: count(value, "algorithms.population", 1.0e5)?,
        iterations: count(value, "algorithms.iterations", 1.0e6)?,
        // Guangzhou, the mango orchard of seed 000 §5.3.
        georeference: Georeference::Local {
            lon: 113.36,
            lat: 23.16,
        },
        unit_m: 1.0,
        ground_truth: GroundTruth::Model(Arc::new(terrain)),
        limits: SafetyLimits::default(),
        cruise_start: [0.0; 3],
        cruise_goal: [0.0; 3],
        paper_runs: runs,
    })
}

fn survey(value: &Value) -> Result<TrackScenario, Fault> {
    let known: Vec<&str> = [
        "terrain",
        "extent_m",
        "start",
        "goal",
        "min_altitude_m",
        "ga",
        "aco_baseline",
    ]
    .iter()
    .chain(&DOCUMENTATION)
    .copied()
    .collect();
    only_keys(value, "", &known)?;
    only_keys(
        lookup(value, "terrain")?,
        "terrain",
        &[
            "kind",
            "same_formula_as",
            "coefficients",
            "hills",
            "height_scale",
            "note",
        ],
    )?;
    let ga = lookup(value, "ga")?;
    only_keys(
        ga,
        "ga",
        &[
            "population",
            "chromosome_length",
            "generations",
            "p_crossover",
            "p_mutation",
            "tournament_share_alpha",
            "phase_switch_beta",
            "mutation_tries",
        ],
    )?;
    let paper = super::improved_genetic::ImprovedGeneticParameters::default();
    expect_setting(value, "ga.p_crossover", 1.0)?;
    expect_setting(value, "ga.tournament_share_alpha", paper.tournament_share)?;
    expect_setting(value, "ga.phase_switch_beta", paper.phase_switch)?;
    if let Some(rate) = ga.get("p_mutation") {
        if rate.as_str() != Some("1/chromosome_length") {
            return Err(Fault::InvalidValue {
                what: "ga.p_mutation".into(),
                value: rate.to_string(),
                why: "the improved GA mutates at the paper's \"1/chromosome_length\"".into(),
            });
        }
    }
    if ga.get("mutation_tries").is_some()
        && !numbers(ga, "mutation_tries")?.contains(&(paper.tries as f64))
    {
        return Err(Fault::InvalidValue {
            what: "ga.mutation_tries".into(),
            value: ga["mutation_tries"].to_string(),
            why: format!("the improved GA runs the paper's {} tries", paper.tries),
        });
    }
    // The paper's ACO baseline is a discrete ant colony; the table runs ACO_R on the same
    // budget (decision 0011), so these figures are documentation of the paper's setup.
    let extent = numbers(value, "extent_m")?;
    if extent.len() != 3 || extent.iter().any(|side| *side <= 0.0 || *side > 1.0e5) {
        return Err(Fault::Structure(
            "'extent_m' needs [x, y, z] (positive, at most 100 km)".into(),
        ));
    }
    let (terrain, map) = composite_over(value, Composite::seed002(), &extent)?;
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
        free_waypoints: count(value, "ga.chromosome_length", 100.0)?,
        cost: CostModel::Seed002(Seed002Cost),
        population: count(value, "ga.population", 1.0e5)?,
        iterations: count(value, "ga.generations", 1.0e6)?,
        // Xi'an, Shaanxi: seed 002's university.
        georeference: Georeference::Local {
            lon: 108.95,
            lat: 34.27,
        },
        unit_m: 1.0,
        ground_truth: GroundTruth::Model(Arc::new(terrain)),
        limits: SafetyLimits::default(),
        cruise_start: [0.0; 3],
        cruise_goal: [0.0; 3],
        paper_runs: None,
    })
}

fn spso(value: &Value, dem: &[u8]) -> Result<TrackScenario, Fault> {
    let known: Vec<&str> = [
        "dem",
        "threat_cylinders_x_y_z_r",
        "start_xyz_agl",
        "goal_xyz_agl",
        "altitude_band_agl",
        "free_nodes",
        "cost",
        "encoding",
        "pso_reference_settings",
        "reference_results",
    ]
    .iter()
    .chain(&DOCUMENTATION)
    .copied()
    .collect();
    only_keys(value, "", &known)?;
    only_keys(
        lookup(value, "dem")?,
        "dem",
        &[
            "file",
            "size_cols_rows",
            "sample",
            "pixel_m",
            "crs",
            "nodata",
            "model_units",
        ],
    )?;
    let grid = crate::terrain::geotiff::decode(dem)?;
    grid.check_plausible()?;
    if lookup(value, "dem.size_cols_rows").is_ok() {
        let size = numbers(value, "dem.size_cols_rows")?;
        if size != [grid.columns as f64, grid.rows as f64] {
            return Err(Fault::InvalidValue {
                what: "dem.size_cols_rows".into(),
                value: format!("{size:?}"),
                why: format!("the DEM has {} × {} pixels", grid.columns, grid.rows),
            });
        }
    }
    expect_setting(value, "dem.pixel_m", grid.cell_x)?;
    let cost = lookup(value, "cost")?;
    only_keys(
        cost,
        "cost",
        &[
            "weights_length_threat_altitude_smoothness",
            "drone_size_S",
            "danger_band_D",
            "definition",
        ],
    )?;
    let mut model = SpsoCost::default();
    if cost
        .get("weights_length_threat_altitude_smoothness")
        .is_some()
    {
        let weights = numbers(cost, "weights_length_threat_altitude_smoothness")?;
        model.weights = <[f64; 4]>::try_from(weights.as_slice())
            .ok()
            .filter(|weights| weights.iter().all(|w| *w >= 0.0) && weights[0] > 0.0)
            .ok_or_else(|| Fault::Structure("'cost.weights_length_threat_altitude_smoothness' needs 4 weights ≥ 0, the first positive".into()))?;
    }
    if cost.get("drone_size_S").is_some() {
        model.drone_size = number(cost, "drone_size_S")?.max(0.0);
    }
    if cost.get("danger_band_D").is_some() {
        model.danger = number(cost, "danger_band_D")?.max(0.0);
    }
    let settings = lookup(value, "pso_reference_settings")?;
    only_keys(
        settings,
        "pso_reference_settings",
        &[
            "population",
            "iterations",
            "w",
            "w_damping",
            "c1",
            "c2",
            "velocity_clamp",
        ],
    )?;
    let paper = swarm::algorithms::ParticleSwarmParameters::spso(0);
    expect_setting(value, "pso_reference_settings.w", paper.inertia)?;
    expect_setting(
        value,
        "pso_reference_settings.w_damping",
        paper.inertia_damping,
    )?;
    expect_setting(value, "pso_reference_settings.c1", paper.cognitive)?;
    expect_setting(value, "pso_reference_settings.c2", paper.social)?;
    let map = HeightMap::from_grid_in_pixel_units(&grid);
    let band = numbers(value, "altitude_band_agl")?;
    if band.len() != 2 {
        return Err(Fault::Structure(
            "'altitude_band_agl' needs [low, high]".into(),
        ));
    }
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
        // Each row's z is the cylinder's drawn height in the reference; its cost (MyCost.m)
        // treats every cylinder as infinitely tall, and so do we.
        threats: threats(
            lookup(value, "threat_cylinders_x_y_z_r")?,
            "threat_cylinders_x_y_z_r",
            4,
        )?,
        height_band: Some((band[0], band[1])),
        free_waypoints: count(value, "free_nodes", 100.0)?,
        cost: CostModel::Spso(model),
        population: count(settings, "population", 1.0e5)?,
        iterations: count(settings, "iterations", 1.0e6)?,
        georeference: Georeference::Pixels {
            zone,
            easting: grid.first_center_x - 0.5 * grid.cell_x,
            northing: grid.first_center_y + 0.5 * grid.cell_y,
            pixel_m: grid.cell_x,
        },
        unit_m: grid.cell_x,
        ground_truth: GroundTruth::Raster,
        limits: SafetyLimits::default(),
        cruise_start: [0.0; 3],
        cruise_goal: [0.0; 3],
        paper_runs: None,
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
