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
//!
//! The parts: `json` (values at dotted paths, checked numbers, unknown keys refused),
//! `composite` (the analytic terrain of seeds 000 and 002 as a file gives it), one reader
//! per paper (`orchard`, `survey`, `spso`) and `validate` (start, goal and band
//! checked, the cruise's ends placed), which every reader and the operator TOML end with.

mod composite;
mod json;
mod orchard;
mod spso;
mod survey;
mod validate;

use std::path::Path;
use std::sync::Arc;

use serde_json::Value;

use super::cost::CostModel;
use super::height_map::HeightMap;
use crate::error::{Fault, InputError};
use crate::geometry::{from_utm, UtmZone};
use crate::terrain::Terrain;
use json::{embedded, text, Loaded};

pub(super) use validate::validated;

/// Cell of the raster the planners read an analytic terrain on. The legs' samples are one
/// cell apart (`HeightMap::leg_excess`); 2 m keeps them under half the shortest period of the
/// composite formula's ripples (2π m) and one IBA-FCS run under a second. The raster is
/// within 0.6 m of the formula (test `the_orchard_raster_follows_its_formula`); the costs see
/// the ground raised by that error ([`TrackScenario::cost_clearance`]) and the verdict reads
/// the formula itself.
pub const ORCHARD_CELL_M: f64 = 2.0;

/// Seed 000's orchard, embedded so that `agripath repro` needs no files.
pub const ORCHARD_JSON: &str = include_str!("../../../../../data/seed000_orchard.json");
/// Seed 002's survey space.
pub const SURVEY_JSON: &str = include_str!("../../../../../data/seed002_field_survey.json");
/// SPSO's public scenario and its DEM (Christmas Island, 5 m pixels; BSD-style licence in
/// `data/spso/LICENSE-SPSO.txt`).
pub const SPSO_JSON: &str = include_str!("../../../../../data/spso/scenario.json");
/// SPSO's DEM, the GeoTIFF's bytes.
pub const SPSO_DEM: &[u8] = include_bytes!("../../../../../data/spso/ChrismasTerrain.tif");

/// A vertical cylinder the track must not enter (2D: centre and radius).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Threat {
    /// Centre x, in the scenario's horizontal unit.
    pub x: f64,
    /// Centre y, in the scenario's horizontal unit.
    pub y: f64,
    /// Radius, in the scenario's horizontal unit.
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
    Local {
        /// Longitude of the origin, degrees.
        lon: f64,
        /// Latitude of the origin, degrees.
        lat: f64,
    },
    /// UTM metres of a zone: the scenario was given in longitude/latitude, and its outputs
    /// go back to longitude/latitude.
    Utm {
        /// The UTM zone.
        zone: UtmZone,
    },
    /// SPSO's pixel units on a UTM raster: x = column + 1, y = row + 1 from the top-left
    /// pixel, whose corner is at (easting, northing).
    Pixels {
        /// The raster's UTM zone.
        zone: UtmZone,
        /// Easting of the top-left pixel's outer corner, metres.
        easting: f64,
        /// Northing of the top-left pixel's outer corner, metres.
        northing: f64,
        /// The pixel's size, metres.
        pixel_m: f64,
    },
}

/// One track problem.
#[derive(Debug, Clone)]
pub struct TrackScenario {
    /// The scenario's name.
    pub name: String,
    /// The terrain as the planners sample it (a raster of `ground_truth`).
    pub terrain: HeightMap,
    /// Waypoints stay in [min_x, max_x] × [min_y, max_y].
    pub area: (f64, f64, f64, f64),
    /// Waypoint altitudes stay in [low, high], in `altitude_reference`.
    pub altitude_bounds: (f64, f64),
    /// What the z of the start, goal and waypoints means.
    pub altitude_reference: AltitudeReference,
    /// Start and goal: x, y and z in `altitude_reference`.
    pub start: [f64; 3],
    /// Where the track ends: x, y and z in `altitude_reference`.
    pub goal: [f64; 3],
    /// Cylinders the track must not enter.
    pub threats: Vec<Threat>,
    /// Height above ground the track should keep, when the scenario has a band.
    pub height_band: Option<(f64, f64)>,
    /// Waypoints a planner places between the cruise's start and goal (1 to 100).
    pub free_waypoints: usize,
    /// The cost model tracks are compared by.
    pub cost: CostModel,
    /// Population and iterations the scenario's paper uses.
    pub population: usize,
    /// Iterations the scenario's paper uses (see `population`).
    pub iterations: usize,
    /// Where the scenario's plane lies on Earth.
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
    /// Where the cruise ends (see `cruise_start`).
    pub cruise_goal: [f64; 3],
    /// Runs the scenario's paper makes (seed 000's `algorithms.runs`), the default of `--runs`.
    pub paper_runs: Option<u64>,
    /// The ground the costs keep their clearance from where a slope or a bank is nearer
    /// sideways than the verdict's clearance allows (`terrain` raised,
    /// [`HeightMap::raised_for_clearance`]), made on the costs' first use for the limits the
    /// scenario has then (`validated` empties it): 0.11 s on SPSO's island at 2 m, which a
    /// scenario read and then given its `--min-clearance` made twice. `None` inside where no
    /// slope is steep enough to matter, and the costs read `terrain`.
    pub clearance_ground: std::sync::OnceLock<Option<HeightMap>>,
}

/// Metres the costs keep over the verdict's clearance: the raster's error (the orchard's
/// raster is within 0.6 m of its formula; a DEM resampled at 2 m, within a few decimetres of
/// its cells).
pub const COST_ALLOWANCE_M: f64 = 0.6;

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
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct SafetyLimits {
    /// Least distance from the terrain a safe track keeps along its cruise, in any
    /// direction (straight down and sideways to a slope), metres; at least 0.5 (checked
    /// every 1 m and at the raster's bends against the terrain as given).
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "min-clearance",
            value_name = "MIN_CLEARANCE",
            default_value_t = 2.0
        )
    )]
    pub min_clearance_m: f64,
    /// The vehicle's radius: least distance from a threat cylinder's wall, metres.
    #[cfg_attr(
        feature = "cli",
        arg(
            long = "vehicle-radius",
            value_name = "VEHICLE_RADIUS",
            default_value_t = 1.0
        )
    )]
    pub vehicle_radius_m: f64,
}

impl SafetyLimits {
    /// Refuses limits no track should be flown to, naming the flag that gives each.
    pub fn check(&self) -> Result<(), Fault> {
        // The clearance has `plan`'s floor under it: a track 0.29 m above the ground read
        // safe at `--min-clearance 0` (decision 0030).
        let floor = crate::limits::MIN_GROUND_CLEARANCE_M;
        for (what, value, least) in [
            ("--min-clearance", self.min_clearance_m, floor),
            ("--vehicle-radius", self.vehicle_radius_m, 0.0),
        ] {
            if !(least..=1000.0).contains(&value) {
                return Err(Fault::InvalidValue {
                    what: what.into(),
                    value: value.to_string(),
                    why: format!("must be {least}..=1000 metres"),
                });
            }
        }
        Ok(())
    }
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

    /// The planar point at a longitude and latitude: [`TrackScenario::lon_lat`] inverted
    /// (for reading a written mission back).
    pub fn from_lon_lat(&self, lon: f64, lat: f64) -> (f64, f64) {
        match self.georeference {
            Georeference::Local {
                lon: origin_lon,
                lat: origin_lat,
            } => {
                let zone = UtmZone::containing(origin_lon, origin_lat);
                let (origin_e, origin_n) = crate::geometry::to_utm(origin_lon, origin_lat, zone);
                let (easting, northing) = crate::geometry::to_utm(lon, lat, zone);
                (easting - origin_e, northing - origin_n)
            }
            Georeference::Utm { zone } => crate::geometry::to_utm(lon, lat, zone),
            Georeference::Pixels {
                zone,
                easting,
                northing,
                pixel_m,
            } => {
                let (e, n) = crate::geometry::to_utm(lon, lat, zone);
                (
                    (e - easting) / pixel_m + 0.5,
                    (northing - n) / pixel_m + 0.5,
                )
            }
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
        self.limits.min_clearance_m + COST_ALLOWANCE_M
    }

    /// The ground the costs keep [`TrackScenario::cost_clearance`] from: the terrain raised
    /// where a slope or a bank beside is nearer than the clearance (decision 0032).
    pub fn cost_ground(&self) -> &HeightMap {
        self.raised_ground().unwrap_or(&self.terrain)
    }

    /// The terrain raised for the clearance where a slope matters ([`Self::cost_ground`]),
    /// `None` where none does.
    pub fn raised_ground(&self) -> Option<&HeightMap> {
        self.clearance_ground
            .get_or_init(|| {
                self.terrain.raised_for_clearance(
                    self.unit_m,
                    self.limits.min_clearance_m,
                    COST_ALLOWANCE_M,
                )
            })
            .as_ref()
    }

    /// The ground the flight is checked against, as a terrain (its bends sample a leg).
    pub fn true_terrain(&self) -> &dyn Terrain {
        match &self.ground_truth {
            GroundTruth::Raster => &self.terrain,
            GroundTruth::Model(model) => model.as_ref(),
        }
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
        limits.check()?;
        self.limits = limits;
        validated(self)
    }

    /// Reads a scenario file; `task` picks one of seed 000's tasks ("I", "II", "III").
    pub fn read(path: &Path, task: Option<&str>) -> Result<Self, InputError> {
        let extension = crate::files::extension_of(path);
        if ["asc", "tif", "tiff", "xyz", "csv", "geojson", "kml", "kmz"]
            .contains(&extension.as_str())
        {
            return Err(InputError::new(
                path,
                Fault::Structure(format!(
                    "a .{extension} file is not a track scenario: give a scenario (.toml or .json) that names it{}",
                    if ["geojson", "kml", "kmz"].contains(&extension.as_str()) {
                        " (fields are planned with `agripath plan`)"
                    } else {
                        " as its terrain"
                    }
                )),
            ));
        }
        let text = crate::files::read_text(path)?;
        if extension == "toml" {
            if let Some(task) = task {
                return Err(InputError::new(
                    "arguments",
                    Fault::InvalidValue {
                        what: "--task".into(),
                        value: task.into(),
                        why: format!(
                            "{} is an operator's scenario, one track with no tasks (tasks are those of seed 000's scenarios)",
                            path.display()
                        ),
                    },
                ));
            }
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
            Ok(orchard::read(value, task.unwrap_or("I"))?)
        } else if value.get("ga").is_some() {
            Ok(survey::read(value)?)
        } else if value.get("threat_cylinders_x_y_z_r").is_some() {
            let name = text(value, "dem.file")?;
            let bytes = read_dem(&name).map_err(Loaded::Input)?;
            Ok(spso::read(value, &bytes)?)
        } else {
            Err(Loaded::Fault(Fault::Structure(
                "not a track scenario: expected seed 000's \"tasks\", seed 002's \"ga\" or SPSO's \"threat_cylinders_x_y_z_r\""
                    .into(),
            )))
        }
    }

    /// Seed 000's task "I", "II" or "III" (embedded).
    pub fn seed000(task: &str) -> Result<Self, Fault> {
        orchard::read(&embedded(ORCHARD_JSON), task)
    }

    /// Seed 002's survey space (embedded).
    pub fn seed002() -> Result<Self, Fault> {
        survey::read(&embedded(SURVEY_JSON))
    }

    /// SPSO's public scenario (embedded, with its DEM).
    pub fn spso() -> Result<Self, Fault> {
        spso::read(&embedded(SPSO_JSON), SPSO_DEM)
    }
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
    fn the_papers_terrains_keep_their_costs_and_a_large_clearance_raises_the_ground() {
        // At the default 2 m the orchard's and the survey's slopes stay within the costs'
        // allowance, so their tables are costed as the papers cost them; SPSO's island has
        // cliffs steeper than 40°, where the costs now keep off the face (decision 0032).
        assert!(TrackScenario::seed000("I")
            .unwrap()
            .raised_ground()
            .is_none());
        assert!(TrackScenario::seed002().unwrap().raised_ground().is_none());
        assert!(TrackScenario::spso().unwrap().raised_ground().is_some());
        let limits = |min_clearance_m| SafetyLimits {
            min_clearance_m,
            ..SafetyLimits::default()
        };
        let orchard = TrackScenario::seed000("I").unwrap();
        let high = orchard.with_limits(limits(30.0)).unwrap();
        let raised = high.raised_ground().expect("raised at 30 m");
        // Never below the ground, and above it somewhere.
        let (min_x, min_y, max_x, max_y) = high.area;
        let mut most: f64 = 0.0;
        for i in 0..=40 {
            for j in 0..=40 {
                let x = min_x + (max_x - min_x) * f64::from(i) / 40.0;
                let y = min_y + (max_y - min_y) * f64::from(j) / 40.0;
                let lift = raised.height(x, y) - high.terrain.height(x, y);
                assert!(lift >= -1e-3, "({x}, {y}): {lift}");
                most = most.max(lift);
            }
        }
        assert!(most > 1.0, "{most}");
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
