//! Track scenarios as operators write them: a TOML file with a DEM, start and goal in
//! longitude/latitude (or local metres), heights above the ground, and no-fly cylinders.
//!
//! ```toml
//! name = "ridge crossing"
//! crs = "lonlat"                      # or "local": metres, with the DEM in the same frame
//! terrain = { kind = "file", path = "ChrismasTerrain.tif" }
//! start = [105.6168, -10.4768, 40]    # lon, lat, height above the ground (m)
//! goal = [105.6507, -10.5030, 40]
//! height_band_m = [30, 120]           # the band to keep above the ground
//! free_waypoints = 10
//! margin_m = 300                      # planning area: start, goal and threats, plus this
//! threats = [[105.6333, -10.4904, 250]]   # lon, lat, radius (m)
//! # origin = [126.63, 45.75]         # with crs = "local": where (0, 0) goes in the files
//! ```
//!
//! The track is planned in the UTM zone of the start (metres), on the DEM sampled every 2 m
//! (coarser for areas above 4 million samples), with seed 000's cost F and waypoints at heights
//! above the ground inside the band; outputs go back to longitude/latitude.

use std::path::Path;

use serde::Deserialize;

use super::cost::{CostModel, Seed000Cost};
use super::height_map::HeightMap;
use super::scenario::{
    validated, AltitudeReference, Georeference, GroundTruth, SafetyLimits, Threat, TrackScenario,
};
use crate::error::{Fault, InputError};
use crate::geometry::UtmZone;
use crate::model::CoordinateSystem;
use crate::terrain::TerrainSpec;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct OperatorScenario {
    name: Option<String>,
    #[serde(default = "lonlat")]
    crs: String,
    terrain: TerrainSpec,
    start: [f64; 3],
    goal: [f64; 3],
    height_band_m: [f64; 2],
    #[serde(default = "ten")]
    free_waypoints: usize,
    #[serde(default = "margin")]
    margin_m: f64,
    #[serde(default)]
    threats: Vec<[f64; 3]>,
    #[serde(default = "population")]
    population: usize,
    #[serde(default = "iterations")]
    iterations: usize,
    /// With `crs = "local"`: the longitude and latitude local (0, 0) is placed at in the
    /// mission files (default 126.63, 45.75, as `plan --origin`).
    origin: Option<[f64; 2]>,
}

fn lonlat() -> String {
    "lonlat".into()
}
fn ten() -> usize {
    10
}
fn margin() -> f64 {
    300.0
}
fn population() -> usize {
    500
}
fn iterations() -> usize {
    300
}

/// Parses an operator's track scenario (`path` names it in messages) and builds the planning scenario; errs on bad TOML, an invalid value or a DEM that cannot be read.
pub fn read(path: &Path, text: &str) -> Result<TrackScenario, InputError> {
    let fail = |fault: Fault| InputError::new(path, fault);
    let parsed: OperatorScenario =
        toml::from_str(text).map_err(|error| InputError::toml(path, &error, text))?;
    let numbers = parsed
        .start
        .iter()
        .chain(&parsed.goal)
        .chain(&parsed.height_band_m)
        .chain(parsed.threats.iter().flatten())
        .chain([&parsed.margin_m]);
    for value in numbers {
        if !value.is_finite() {
            return Err(fail(Fault::NonFinite));
        }
    }
    let [low, high] = parsed.height_band_m;
    if !(low >= 0.0 && low < high) {
        return Err(fail(Fault::InvalidValue {
            what: "height_band_m".into(),
            value: format!("[{low}, {high}]"),
            why: "needs 0 ≤ lower < upper (metres above the ground)".into(),
        }));
    }
    if parsed.margin_m < 0.0 || parsed.population < 2 || parsed.iterations == 0 {
        return Err(fail(Fault::InvalidValue {
            what: "margin_m / population / iterations".into(),
            value: format!(
                "{} / {} / {}",
                parsed.margin_m, parsed.population, parsed.iterations
            ),
            why: "need margin ≥ 0, population ≥ 2 and iterations ≥ 1".into(),
        }));
    }
    if parsed.crs == "lonlat" && parsed.origin.is_some() {
        return Err(fail(Fault::InvalidValue {
            what: "origin".into(),
            value: format!("{:?}", parsed.origin.unwrap_or_default()),
            why: "it places local metres (crs = \"local\"); lon/lat points are placed already"
                .into(),
        }));
    }
    let (frame, georeference) = match parsed.crs.as_str() {
        "lonlat" => {
            let [lon, lat, _] = parsed.start;
            if !(-180.0..=180.0).contains(&lon) || !(-80.0..=84.0).contains(&lat) {
                return Err(fail(Fault::OutOfRange { lon, lat }));
            }
            let zone = UtmZone::containing(lon, lat);
            (CoordinateSystem::Utm(zone), Georeference::Utm { zone })
        }
        "local" => {
            let [lon, lat] = parsed.origin.unwrap_or({
                let (lon, lat) = crate::mission::flight::DEFAULT_LOCAL_ORIGIN;
                [lon, lat]
            });
            if !(-180.0..=180.0).contains(&lon) || !(-80.0..=84.0).contains(&lat) {
                return Err(fail(Fault::InvalidValue {
                    what: "origin".into(),
                    value: format!("[{lon}, {lat}]"),
                    why: "expected [lon, lat] with longitude in -180..180 and latitude in -80..84"
                        .into(),
                }));
            }
            (CoordinateSystem::Local, Georeference::Local { lon, lat })
        }
        other => {
            return Err(fail(Fault::InvalidValue {
                what: "crs".into(),
                value: other.into(),
                why: "expected \"lonlat\" or \"local\"".into(),
            }))
        }
    };
    let planar = |point: [f64; 3]| -> Result<[f64; 3], InputError> {
        if let CoordinateSystem::Utm(_) = frame {
            if !(-180.0..=180.0).contains(&point[0]) || !(-80.0..=84.0).contains(&point[1]) {
                return Err(fail(Fault::OutOfRange {
                    lon: point[0],
                    lat: point[1],
                }));
            }
        }
        let (x, y) = frame.to_plan(point[0], point[1]);
        Ok([x, y, point[2]])
    };
    let start = planar(parsed.start)?;
    let goal = planar(parsed.goal)?;
    let mut threats = Vec::with_capacity(parsed.threats.len());
    for (index, threat) in parsed.threats.iter().enumerate() {
        if threat[2] <= 0.0 {
            return Err(fail(Fault::InvalidValue {
                what: format!("threat {} radius", index + 1),
                value: threat[2].to_string(),
                why: "a threat cylinder needs a positive radius".into(),
            }));
        }
        let centre = planar(*threat)?;
        threats.push(Threat {
            x: centre[0],
            y: centre[1],
            radius: threat[2],
        });
    }
    // The planning area: start, goal and threats with the margin.
    let mut area = (
        start[0].min(goal[0]),
        start[1].min(goal[1]),
        start[0].max(goal[0]),
        start[1].max(goal[1]),
    );
    for threat in &threats {
        area = (
            area.0.min(threat.x - threat.radius),
            area.1.min(threat.y - threat.radius),
            area.2.max(threat.x + threat.radius),
            area.3.max(threat.y + threat.radius),
        );
    }
    let area = (
        area.0 - parsed.margin_m,
        area.1 - parsed.margin_m,
        area.2 + parsed.margin_m,
        area.3 + parsed.margin_m,
    );
    let base = path.parent().unwrap_or(Path::new("."));
    let terrain = parsed.terrain.load(base, frame)?;
    // Clip the area to the DEM (the start and goal must stay inside).
    let area = match terrain.extent() {
        Some(extent) => (
            area.0.max(extent.min_x),
            area.1.max(extent.min_y),
            area.2.min(extent.max_x),
            area.3.min(extent.max_y),
        ),
        None => area,
    };
    if area.2 - area.0 <= 0.0 || area.3 - area.1 <= 0.0 {
        return Err(fail(Fault::InvalidValue {
            what: "start and goal".into(),
            value: format!("{:?} and {:?}", parsed.start, parsed.goal),
            why: "the terrain model does not cover them".into(),
        }));
    }
    let cell = 2.0; // HeightMap::sample coarsens it for large areas
    let map = HeightMap::sample(terrain.as_ref(), area, cell).map_err(|error| {
        // The place in the file's own coordinates (lon/lat), not the planning frame's UTM
        // metres, which the operator never gave (a third trial).
        let (crate::TerrainError::Outside { x, y } | crate::TerrainError::NoData { x, y }) = error;
        let (a, b) = frame.to_input(x, y);
        let place = match frame {
            CoordinateSystem::Utm(_) => format!("lon {a:.6}, lat {b:.6}"),
            CoordinateSystem::Local => format!("({a:.1}, {b:.1})"),
        };
        fail(Fault::InvalidValue {
            what: "planning area".into(),
            value: format!("{:.0} × {:.0} m", area.2 - area.0, area.3 - area.1),
            why: format!(
                "the terrain model has no height at {place}, inside the area (the start and goal's box grown by margin_m = {}): give a smaller margin_m, or a DEM that covers it",
                crate::error::figure(parsed.margin_m)
            ),
        })
    })?;
    validated(TrackScenario {
        name: parsed.name.unwrap_or_else(|| path.display().to_string()),
        terrain: map,
        area,
        altitude_bounds: (low, high),
        altitude_reference: AltitudeReference::AboveGround,
        start,
        goal,
        threats,
        height_band: Some((low, high)),
        free_waypoints: parsed.free_waypoints,
        cost: CostModel::Seed000(Seed000Cost::default()),
        population: parsed.population,
        iterations: parsed.iterations,
        georeference,
        unit_m: 1.0,
        ground_truth: GroundTruth::Model(std::sync::Arc::from(terrain)),
        limits: SafetyLimits::default(),
        cruise_start: [0.0; 3],
        cruise_goal: [0.0; 3],
        paper_runs: None,
        clearance_ground: std::sync::OnceLock::new(),
    })
    .map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_example_over_the_real_dem_reads_in_utm_and_returns_lon_lat() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../data/tracks/christmas_island_track.toml");
        let scenario = TrackScenario::read(&path, None).unwrap();
        assert_eq!(
            scenario.georeference,
            Georeference::Utm {
                zone: UtmZone {
                    number: 48,
                    south: true
                }
            }
        );
        let (lon, lat) = scenario.to_input(scenario.start[0], scenario.start[1]);
        assert!(
            (lon - 105.6168).abs() < 1e-9 && (lat + 10.4768).abs() < 1e-9,
            "{lon} {lat}"
        );
        assert_eq!(scenario.threats.len(), 3);
        assert!(
            scenario.terrain.range().1 > 200.0,
            "the island's plateau is read"
        );
    }
}
