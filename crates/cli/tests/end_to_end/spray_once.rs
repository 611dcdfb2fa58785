//! End to end: `--edge-cut` on an irregular lon/lat field with a hole (Christmas Island),
//! measured as flown by the preflight read-back in `report.json` (issue 22, decision 0019),
//! and the ground no swath reaches in `plan.geojson` (decision 0023).

use crate::common;

use std::process::Command;

use common::{data, scratch, stdout};

fn plan(edge_cut: &str) -> (serde_json::Value, serde_json::Value) {
    let out = scratch("spray_once", edge_cut);
    stdout(
        &Command::new(env!("CARGO_BIN_EXE_agripath"))
            .arg("plan")
            .arg("--fields")
            .arg(data("christmas_island_fields.geojson"))
            .args(["--edge-cut", edge_cut])
            // `gap` misses what a square end cannot reach without a double dose: refused.
            .args((edge_cut == "gap").then_some("--allow-unsafe"))
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap(),
    );
    let read = |name: &str| -> serde_json::Value {
        serde_json::from_slice(&std::fs::read(out.join(name)).unwrap()).unwrap()
    };
    (read("report.json"), read("plan.geojson"))
}

/// (double-sprayed, missed, covered fraction) over the farm, as flown.
fn figures(report: &serde_json::Value) -> (f64, f64, f64) {
    let fields = report["preflight"]["fields"].as_array().unwrap();
    let sum = |key: &str| fields.iter().map(|f| f[key].as_f64().unwrap()).sum::<f64>();
    let least = fields
        .iter()
        .map(|f| f["covered_fraction"].as_f64().unwrap())
        .fold(1.0, f64::min);
    (sum("double_sprayed_m2"), sum("missed_m2"), least)
}

#[test]
fn edge_cuts_trade_double_dose_for_missed_ground_as_flown() {
    let (overlap, _) = plan("overlap");
    let (balanced, _) = plan("balanced");
    let (gap, gap_geojson) = plan("gap");
    let (overlap_double, overlap_missed, overlap_covered) = figures(&overlap);
    let (balanced_double, balanced_missed, balanced_covered) = figures(&balanced);
    let (gap_double, gap_missed, _) = figures(&gap);
    assert!(
        gap_double < balanced_double && balanced_double < overlap_double,
        "double {gap_double} {balanced_double} {overlap_double}"
    );
    assert!(
        overlap_missed <= balanced_missed && balanced_missed < gap_missed,
        "missed {overlap_missed} {balanced_missed} {gap_missed}"
    );
    assert!(overlap_covered >= 0.99 && balanced_covered >= 0.99);
    for report in [&overlap, &balanced] {
        assert_eq!(report["preflight"]["safe"], true);
    }
    // The ground left unsprayed that plan.geojson draws (missed and unreachable) is what the
    // preflight counts, less the slivers under 1 cm of mean width the file leaves out
    // (decision 0036: on this farm every unreachable piece is one, 3-7 mm wide along the
    // boundary). Measured on the gap plan, which misses the most: 4,261 of 4,278 m².
    let drawn: f64 = gap_geojson["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["properties"]["kind"] == "unreachable" || f["properties"]["kind"] == "missed")
        .map(|f| f["properties"]["area_m2"].as_f64().unwrap())
        .sum();
    let counted: f64 = gap["preflight"]["fields"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["unreachable_m2"].as_f64().unwrap() + f["missed_m2"].as_f64().unwrap())
        .sum();
    assert!(
        drawn <= counted + 0.5 && drawn >= 0.98 * counted,
        "drawn {drawn} counted {counted}"
    );
}
