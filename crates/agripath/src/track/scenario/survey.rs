//! Seed 002's survey space (`seed002_field_survey.json`): the composite terrain and the
//! improved GA's settings, which must be the ones the planner runs.

use std::sync::Arc;

use serde_json::Value;

use super::composite::composite_over;
use super::json::*;
use super::{validated, AltitudeReference, Georeference, GroundTruth, SafetyLimits, TrackScenario};
use crate::error::Fault;
use crate::terrain::Composite;
use crate::track::cost::{CostModel, Seed002Cost};

pub(super) fn read(value: &Value) -> Result<TrackScenario, Fault> {
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
    let paper = crate::track::improved_genetic::ImprovedGeneticParameters::default();
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
        free_waypoints: count(value, "ga.chromosome_length", 1.0, 100.0)?,
        cost: CostModel::Seed002(Seed002Cost),
        population: count(value, "ga.population", 2.0, 1.0e5)?,
        iterations: count(value, "ga.generations", 1.0, 1.0e6)?,
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
        clearance_ground: std::sync::OnceLock::new(),
    })
}
