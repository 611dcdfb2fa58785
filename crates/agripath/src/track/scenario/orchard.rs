//! Seed 000's orchard (`seed000_orchard.json`): the composite terrain, tasks I-III and the
//! paper's IBA-FCS settings, which must be the ones the planners run.

use std::sync::Arc;

use serde_json::Value;

use super::composite::composite_over;
use super::json::*;
use super::{validated, AltitudeReference, Georeference, GroundTruth, SafetyLimits, TrackScenario};
use crate::error::Fault;
use crate::terrain::Composite;
use crate::track::cost::{CostModel, Seed000Cost};

pub(super) fn read(value: &Value, task: &str) -> Result<TrackScenario, Fault> {
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
        Ok(_) => Some(count(value, "algorithms.runs", 0.0, 1000.0)?.max(1) as u64),
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
        free_waypoints: count(value, "free_waypoints", 1.0, 100.0)?,
        cost: CostModel::Seed000(Seed000Cost::default()),
        population: count(value, "algorithms.population", 2.0, 1.0e5)?,
        iterations: count(value, "algorithms.iterations", 1.0, 1.0e6)?,
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
        clearance_ground: std::sync::OnceLock::new(),
    })
}
