//! Seed 001 Table 7: heading, swath count and swath length per field of the real farm
//! (w = 5 m, a = 20 m, ω_N = ω_L = 0.5, the seed's layout without edge passes), beside the
//! paper's figures; the same farm at w = 6.5 m (a DJI T16's swath); and, for each, the
//! coverage of the seed's layout against ours with one edge pass.

use serde::Serialize;
use serde_json::Value;

use crate::coverage::{plan_coverage, CoverageSettings};
use crate::error::Fault;
use crate::scenario::Scenario;

/// One field of Table 7: the paper's figures beside ours.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// The field's name.
    pub field: String,
    /// The paper's heading, degrees (`None` where it gives none).
    pub paper_heading_deg: Option<f64>,
    /// The paper's swath count.
    pub paper_swaths: Option<u64>,
    /// The paper's swath length, metres.
    pub paper_length_m: Option<f64>,
    /// Our swaths and length at the paper's heading.
    pub at_paper_heading: Option<(usize, f64)>,
    /// Our best heading of the 1° scan, degrees.
    pub heading_deg: f64,
    /// Our swath count at that heading.
    pub swaths: usize,
    /// Our draped swath length at that heading, metres.
    pub length_m: f64,
    /// The 0.1° refinement of our E, when it lowers E.
    pub refined_heading_deg: f64,
    /// Draped swath length at the refined heading, metres.
    pub refined_length_m: f64,
    /// Coverage of the seed's layout and of ours (one edge pass, refined heading).
    pub seed_layout_covered: f64,
    /// Covered fraction of ours (one edge pass, refined heading), 0..1.
    pub default_covered: f64,
    /// Area sprayed more than once by ours, m².
    pub default_overlap_m2: f64,
}

/// Table 7 at one swath width.
#[derive(Debug, Clone, Serialize)]
pub struct Table {
    /// The swath width the table was computed at, metres.
    pub swath_width_m: f64,
    /// One row per field, in the farm's order.
    pub rows: Vec<Row>,
}

/// Recomputes Table 7 for the scenario's farm at `swath_width_m`. Paper figures come from the
/// field file's `reference_*` properties (`data/seed001_farm.geojson`); pass `Value::Null`
/// where the paper has none (other swath widths).
pub fn table7(scenario: &Scenario, references: &Value, swath_width_m: f64) -> Result<Table, Fault> {
    let vehicle = crate::model::Vehicle {
        swath_width_m,
        ..scenario.vehicle.clone()
    };
    let seed = CoverageSettings {
        headland_passes: 0,
        ..CoverageSettings::default()
    };
    let ours = CoverageSettings::default();
    let seed_plan = plan_coverage(&scenario.farm, scenario.terrain.as_ref(), &vehicle, &seed)?;
    let our_plan = plan_coverage(&scenario.farm, scenario.terrain.as_ref(), &vehicle, &ours)?;
    let rows = seed_plan
        .fields
        .iter()
        .zip(&our_plan.fields)
        .map(|(seed_field, our_field)| {
            let reference = references
                .get("features")
                .and_then(Value::as_array)
                .and_then(|features| {
                    features
                        .iter()
                        .find(|feature| feature["properties"]["name"] == seed_field.name.as_str())
                })
                .map(|feature| &feature["properties"]);
            let number = |key: &str| reference.and_then(|properties| properties[key].as_f64());
            // The integer heading's swaths and length are the seed's answer.
            let integer = seed_field
                .heading_samples
                .iter()
                .find(|sample| sample.heading_deg == seed_field.heading.integer_heading_deg)
                .copied()
                .expect("the integer heading was scanned");
            let at_paper_heading = number("reference_heading_deg").and_then(|paper| {
                seed_field
                    .heading_samples
                    .iter()
                    .find(|sample| sample.heading_deg == paper)
                    .map(|sample| (sample.swaths, sample.length_m))
            });
            Row {
                at_paper_heading,
                field: seed_field.name.clone(),
                paper_heading_deg: number("reference_heading_deg"),
                paper_swaths: reference
                    .and_then(|properties| properties["reference_swaths"].as_u64()),
                paper_length_m: number("reference_length_m"),
                heading_deg: integer.heading_deg,
                swaths: integer.swaths,
                length_m: integer.length_m,
                refined_heading_deg: seed_field.heading.heading_deg,
                refined_length_m: seed_field.heading.length_m,
                seed_layout_covered: seed_field.measure.covered_fraction,
                default_covered: our_field.measure.covered_fraction,
                default_overlap_m2: our_field.measure.overlap_m2,
            }
        })
        .collect();
    Ok(Table {
        swath_width_m,
        rows,
    })
}

impl Table {
    /// The table as aligned text, for the terminal.
    pub fn to_text(&self) -> String {
        let optional = |value: Option<f64>, width: usize, decimals: usize| match value {
            Some(value) => format!("{value:>width$.decimals$}"),
            None => format!("{:>width$}", "—"),
        };
        let mut text = format!(
            "w = {} m, a = 20 m, ω_N = ω_L = 0.5, seed layout (no edge passes); columns: the paper's heading, N and L | ours at the paper's heading | ours\n",
            self.swath_width_m
        );
        text.push_str(&format!(
            "{:<6}| {:>6} {:>6} {:>8} | {:>6} {:>8} | {:>6} {:>6} {:>8} {:>7} | {:>7} {:>8} | {:>8} {:>8} {:>10}\n",
            "field", "paper°", "N", "L m", "N", "L m", "ours°", "N", "L m", "ΔL", "0.1°", "L m", "seed cov", "our cov", "overlap m²"
        ));
        for row in &self.rows {
            let delta = row
                .paper_length_m
                .map(|paper| format!("{:+.2}%", 100.0 * (row.length_m - paper) / paper))
                .unwrap_or_else(|| "—".into());
            text.push_str(&format!(
                "{:<6}| {} {} {} | {} {} | {:>6.0} {:>6} {:>8.1} {:>7} | {:>7.1} {:>8.1} | {:>7.2}% {:>7.2}% {:>10.1}\n",
                row.field,
                optional(row.paper_heading_deg, 6, 0),
                optional(row.paper_swaths.map(|n| n as f64), 6, 0),
                optional(row.paper_length_m, 8, 0),
                optional(row.at_paper_heading.map(|(n, _)| n as f64), 6, 0),
                optional(row.at_paper_heading.map(|(_, length)| length), 8, 1),
                row.heading_deg,
                row.swaths,
                row.length_m,
                delta,
                row.refined_heading_deg,
                row.refined_length_m,
                100.0 * row.seed_layout_covered,
                100.0 * row.default_covered,
                row.default_overlap_m2
            ));
        }
        text
    }
}
