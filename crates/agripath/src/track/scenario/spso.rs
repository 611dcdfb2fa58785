//! SPSO's public scenario (`spso/scenario.json` beside `ChrismasTerrain.tif`): the DEM in
//! pixel units, threat cylinders, the height band above the ground and SPSO's settings.

use serde_json::Value;

use super::json::*;
use super::{validated, AltitudeReference, Georeference, GroundTruth, SafetyLimits, TrackScenario};
use crate::error::Fault;
use crate::geometry::UtmZone;
use crate::track::cost::{CostModel, SpsoCost};
use crate::track::height_map::HeightMap;

pub(super) fn read(value: &Value, dem: &[u8]) -> Result<TrackScenario, Fault> {
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
        free_waypoints: count(value, "free_nodes", 1.0, 100.0)?,
        cost: CostModel::Spso(model),
        population: count(settings, "population", 2.0, 1.0e5)?,
        iterations: count(settings, "iterations", 1.0, 1.0e6)?,
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
        clearance_ground: std::sync::OnceLock::new(),
    })
}
