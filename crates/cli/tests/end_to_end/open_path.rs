//! End to end (issue 19 item 1, decision 0018): with `--sorties none` and no launch point
//! the flight is an open path, optimised as one; with a launch point it starts and ends there.

use std::path::{Path, PathBuf};

use crate::common;
use common::agripath;

fn scratch(name: &str) -> PathBuf {
    common::scratch("open", name)
}

fn planned(folder: &Path, arguments: &[&str], out: &str) -> serde_json::Value {
    let mut all = vec!["plan", "--fields", "farm.geojson", "--out", out];
    all.extend_from_slice(arguments);
    let output = agripath(&all, folder);
    assert!(
        output.status.success(),
        "status {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&std::fs::read(folder.join(out).join("report.json")).unwrap()).unwrap()
}

/// Three small fields on a line, in local metres (one tank, one battery): an open path flies
/// them west to east once.
fn write_farm(folder: &Path) {
    let field = |name: &str, x0: f64| {
        let x1 = x0 + 40.0;
        format!(
            r#"{{"type":"Feature","properties":{{"name":"{name}"}},"geometry":{{"type":"Polygon","coordinates":[[[{x0},0],[{x1},0],[{x1},30],[{x0},30],[{x0},0]]]}}}}"#
        )
    };
    let text = format!(
        r#"{{"type":"FeatureCollection","crs":"local","features":[{},{},{}]}}"#,
        field("west", 0.0),
        field("middle", 200.0),
        field("east", 400.0),
    );
    std::fs::write(folder.join("farm.geojson"), text).unwrap();
}

#[test]
fn without_sorties_or_a_launch_point_the_flight_is_an_open_path() {
    let folder = scratch("none");
    write_farm(&folder);
    let open = planned(&folder, &["--sorties", "none"], "open");
    assert!(open["start"].is_null(), "{}", open["start"]);
    assert!(open["supply"].is_null(), "{}", open["supply"]);
    // What the sequencer minimised is what is flown: no closing leg, no leg home.
    let (tour, flown) = (
        open["tour_cost_m"].as_f64().unwrap(),
        open["transfer_length_m"].as_f64().unwrap(),
    );
    assert!((tour - flown).abs() < 0.01, "tour {tour} flown {flown}");
    // Three fields 160 m apart: the open path crosses between them twice and never back
    // (each crossing climbs).
    assert_eq!(open["climbing_transfers"].as_u64(), Some(2), "{open}");
    // From a launch point 50 m west of the farm, the flight comes back to it: the leg out
    // and the leg home are flown and counted, so it is longer than the open path.
    let fixed = planned(&folder, &["--sorties", "none", "--start=-50,15"], "fixed");
    assert_eq!(fixed["start"], serde_json::json!([-50.0, 15.0]));
    let (tour, flown) = (
        fixed["tour_cost_m"].as_f64().unwrap(),
        fixed["transfer_length_m"].as_f64().unwrap(),
    );
    assert!((tour - flown).abs() < 0.01, "tour {tour} flown {flown}");
    assert!(flown > open["transfer_length_m"].as_f64().unwrap() + 100.0);
    std::fs::remove_dir_all(&folder).unwrap();
}

/// A third trial's small squares (decision 0030): the edge pass began and ended at a corner,
/// both ends of its spray strip square, so that corner was never sprayed (a 20 m square
/// 97.92 % covered as flown and refused by its own preflight, after "100.00 % as planned").
/// The pass now begins in the middle of a side.
#[test]
fn a_small_square_field_is_sprayed_to_its_corners() {
    let folder = scratch("small-square");
    std::fs::write(
        folder.join("square.geojson"),
        r#"{"type":"FeatureCollection","crs":"local","features":[{"type":"Feature","properties":{"name":"square"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[20,0],[20,20],[0,20],[0,0]]]}}]}"#,
    )
    .unwrap();
    let vehicle = common::data("vehicles/dji_t16.toml");
    let output = agripath(
        &[
            "plan",
            "--fields",
            "square.geojson",
            "--vehicle",
            vehicle.to_str().unwrap(),
            "--out",
            "out",
        ],
        &folder,
    );
    assert!(
        output.status.success(),
        "status {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(folder.join("out/report.json")).unwrap()).unwrap();
    let field = &report["preflight"]["fields"][0];
    assert!(
        field["covered_fraction"].as_f64().unwrap() > 0.9999,
        "{field}"
    );
    assert!(field["missed_m2"].as_f64().unwrap() < 0.01, "{field}");
}
