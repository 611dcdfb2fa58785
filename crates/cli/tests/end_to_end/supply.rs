//! End-to-end tests of the supply point (issue 19 item 2): `plan` without a launch marker
//! chooses one (`auto`), `--supply X,Y` takes the one given, `--supply auto:N` lists N, a
//! marker keeps today's rule, access features hold the point, bad values exit 2.

use std::path::{Path, PathBuf};

use crate::common;
use common::{agripath, stdout};

fn scratch(name: &str) -> PathBuf {
    common::scratch("supply", name)
}

fn report(folder: &Path, out: &str) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(folder.join(out).join("report.json")).unwrap()).unwrap()
}

fn rectangle(x0: f64, y0: f64, width: f64, height: f64) -> String {
    format!(
        "[[[{x0},{y0}],[{x1},{y0}],[{x1},{y1}],[{x0},{y1}],[{x0},{y0}]]]",
        x1 = x0 + width,
        y1 = y0 + height
    )
}

/// Two fields 300 m apart in local metres (about 10 km of swaths: several tanks), and
/// `extra` features.
fn farm_file(folder: &Path, name: &str, extra: &str) -> String {
    let field = |name: &str, rings: String| {
        format!(
            r#"{{"type":"Feature","properties":{{"name":"{name}"}},"geometry":{{"type":"Polygon","coordinates":{rings}}}}}"#
        )
    };
    let text = format!(
        r#"{{"type":"FeatureCollection","crs":"local","features":[{},{}{extra}]}}"#,
        field("west", rectangle(0.0, 0.0, 160.0, 150.0)),
        field("east", rectangle(460.0, 0.0, 160.0, 150.0)),
    );
    std::fs::write(folder.join(name), text).unwrap();
    name.to_string()
}

fn inside_a_field(x: f64, y: f64) -> bool {
    (0.0..=150.0).contains(&y) && ((0.0..=160.0).contains(&x) || (460.0..=620.0).contains(&x))
}

#[test]
fn without_a_marker_the_point_is_chosen_and_saves_against_the_first_point_rule() {
    let folder = scratch("auto");
    let fields = farm_file(&folder, "farm.geojson", "");
    let text = stdout(&agripath(
        &["plan", "--fields", &fields, "--out", "out"],
        &folder,
    ));
    assert!(text.contains("supply point (auto)"), "{text}");
    let report = report(&folder, "out");
    let supply = &report["supply"];
    assert_eq!(supply["rule"], "auto", "{supply}");
    assert!(report["sorties"].as_u64().unwrap() > 1);
    let [x, y] = [0, 1].map(|k| supply["point_m"][k].as_f64().unwrap());
    assert!(!inside_a_field(x, y), "{supply}");
    assert!(supply["lon_lat"].is_null(), "local metres: no lon/lat");
    let auto = &supply["auto"];
    assert!(auto["saving_s"].as_f64().unwrap() >= 0.0, "{supply}");
    let cost = supply["cost_s"].as_f64().unwrap();
    let old = auto["first_point"]["cost_s"].as_f64().unwrap();
    assert!(
        (old - cost - auto["saving_s"].as_f64().unwrap()).abs() < 0.01,
        "{supply}"
    );
    // The route begins on the crop: the old rule as an operator could follow it is the
    // nearest place a vehicle can stand, never cheaper than the choice.
    assert_eq!(auto["first_point_stands"], false, "{supply}");
    let moved = &auto["first_point_moved"];
    let [moved_x, moved_y] = [0, 1].map(|k| moved["point_m"][k].as_f64().unwrap());
    assert!(!inside_a_field(moved_x, moved_y), "{supply}");
    assert!(moved["saving_s"].as_f64().unwrap() >= 0.0, "{supply}");
    assert!(
        (moved["cost_s"].as_f64().unwrap() - cost - moved["saving_s"].as_f64().unwrap()).abs()
            < 0.01,
        "{supply}"
    );
    assert!(text.contains("from the nearest place one can"), "{text}");
    assert_eq!(auto["margin_m"], 5.0);
    assert_eq!(auto["reach_m"], 200.0);
    // The flight starts and ends there.
    assert!((report["start"][0].as_f64().unwrap() - x).abs() < 1e-5);
    assert!((report["start"][1].as_f64().unwrap() - y).abs() < 1e-5);
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn a_point_given_is_used_and_auto_n_lists_candidates_best_first() {
    let folder = scratch("given");
    let fields = farm_file(&folder, "farm.geojson", "");
    stdout(&agripath(
        &[
            "plan", "--fields", &fields, "--supply", "310,-20", "--out", "given",
        ],
        &folder,
    ));
    let given = report(&folder, "given");
    assert_eq!(given["supply"]["rule"], "given");
    assert_eq!(
        given["supply"]["point_m"],
        serde_json::json!([310.0, -20.0])
    );
    assert_eq!(given["start"], serde_json::json!([310.0, -20.0]));
    assert!(given["supply"]["auto"].is_null() && given["supply"]["cost_s"].is_null());
    stdout(&agripath(
        &[
            "plan", "--fields", &fields, "--supply", "auto:3", "--out", "listed",
        ],
        &folder,
    ));
    let listed = report(&folder, "listed");
    let candidates = listed["supply"]["auto"]["candidates"].as_array().unwrap();
    assert!((2..=3).contains(&candidates.len()), "{candidates:?}");
    let costs: Vec<f64> = candidates
        .iter()
        .map(|candidate| candidate["cost_s"].as_f64().unwrap())
        .collect();
    assert!(costs.windows(2).all(|pair| pair[0] <= pair[1]), "{costs:?}");
    assert_eq!(candidates[0]["point_m"], listed["supply"]["point_m"]);
    // The others are on the map and in plan.geojson as options 2, 3, … with their costs.
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(folder.join("listed/plan.geojson")).unwrap())
            .unwrap();
    let options: Vec<&serde_json::Value> = plan["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|feature| feature["properties"]["kind"] == "supply_option")
        .collect();
    assert_eq!(options.len(), candidates.len() - 1);
    for (option, candidate) in options.iter().zip(&candidates[1..]) {
        assert_eq!(option["properties"]["cost_s"], candidate["cost_s"]);
        let at = &option["geometry"]["coordinates"];
        for axis in 0..2 {
            let given = candidate["point_m"][axis].as_f64().unwrap();
            assert!(
                (at[axis].as_f64().unwrap() - given).abs() < 1e-3,
                "{at} {candidate}"
            );
        }
    }
    assert_eq!(options[0]["properties"]["rank"], 2);
    let map = std::fs::read_to_string(folder.join("listed/plan.svg")).unwrap();
    assert!(
        map.contains(">option 2</text>"),
        "the map names the second place"
    );
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn a_marker_keeps_its_rule_and_access_features_hold_the_point() {
    let folder = scratch("marker");
    let marker = r#",{"type":"Feature","properties":{"kind":"launch","name":"truck"},"geometry":{"type":"Point","coordinates":[-20,75]}}"#;
    let fields = farm_file(&folder, "marked.geojson", marker);
    stdout(&agripath(
        &["plan", "--fields", &fields, "--out", "marked"],
        &folder,
    ));
    let marked = report(&folder, "marked");
    assert_eq!(marked["supply"]["rule"], "marker");
    assert_eq!(marked["start"], serde_json::json!([-20.0, 75.0]));
    let road = r#",{"type":"Feature","properties":{"kind":"access","name":"farm road"},"geometry":{"type":"LineString","coordinates":[[-40,-30],[700,-30]]}}"#;
    let fields = farm_file(&folder, "road.geojson", road);
    stdout(&agripath(
        &["plan", "--fields", &fields, "--out", "road"],
        &folder,
    ));
    let on_road = report(&folder, "road");
    let supply = &on_road["supply"];
    assert_eq!(supply["rule"], "auto");
    assert_eq!(supply["auto"]["on_access"], true);
    assert!(
        (supply["point_m"][1].as_f64().unwrap() + 30.0).abs() < 0.5,
        "{supply}"
    );
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn a_bad_supply_value_exits_2_with_one_line_naming_the_fault() {
    let folder = scratch("bad");
    let fields = farm_file(&folder, "farm.geojson", "");
    for (arguments, fault) in [
        (vec!["--supply", "nowhere"], "expected auto, auto:N"),
        (vec!["--supply", "auto:0"], "'0' is not a count"),
        (vec!["--supply", "1,inf"], "not two finite numbers"),
        (
            vec!["--supply", "auto", "--start", "0,-20"],
            "give one of --start and --supply",
        ),
    ] {
        let mut all = vec!["plan", "--fields", fields.as_str(), "--out", "out"];
        all.extend(arguments.iter().copied());
        let output = agripath(&all, &folder);
        assert_eq!(output.status.code(), Some(2), "{arguments:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains("--supply") && stderr.contains(fault),
            "{arguments:?}: {stderr}"
        );
        assert!(!folder.join("out").exists(), "nothing written");
    }
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn a_point_given_where_no_vehicle_stands_is_flown_from_with_a_warning() {
    let folder = scratch("unstood");
    let fields = farm_file(&folder, "farm.geojson", "");
    for (point, why) in [
        ("80,75", "inside field 'west', on the crop"),
        ("310,-1000", "1011 m from the nearest field"),
    ] {
        let text = stdout(&agripath(
            &[
                "plan", "--fields", &fields, "--supply", point, "--out", "out",
            ],
            &folder,
        ));
        assert!(
            text.contains("warning: a vehicle cannot stand at the supply point")
                && text.contains(why),
            "{point}: {text}"
        );
        let warning = report(&folder, "out")["supply"]["warning"].clone();
        assert!(warning.as_str().unwrap().contains(why), "{warning}");
    }
    // Where auto would stand: no warning.
    stdout(&agripath(
        &[
            "plan", "--fields", &fields, "--supply", "310,-20", "--out", "out",
        ],
        &folder,
    ));
    assert!(report(&folder, "out")["supply"]["warning"].is_null());
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn a_point_given_too_far_or_with_lon_and_lat_swapped_blames_the_flag() {
    let folder = scratch("typo");
    let fields = farm_file(&folder, "farm.geojson", "");
    // 20 km away: no sortie reaches the fields and comes back; the point is at fault, not the
    // vehicle.
    let output = agripath(
        &[
            "plan",
            "--fields",
            &fields,
            "--supply",
            "310,-20000",
            "--out",
            "out",
        ],
        &folder,
    );
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("--supply") && stderr.contains("km from the nearest field"),
        "{stderr}"
    );
    assert!(!stderr.contains("battery_endurance_s"), "{stderr}");
    // A lon/lat farm with the supply point typed latitude first.
    let lon_lat = r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"paddy"},"geometry":{"type":"Polygon","coordinates":[[[110.3,25.2],[110.302,25.2],[110.302,25.2015],[110.3,25.2015],[110.3,25.2]]]}}]}"#;
    std::fs::write(folder.join("lonlat.geojson"), lon_lat).unwrap();
    let output = agripath(
        &[
            "plan",
            "--fields",
            "lonlat.geojson",
            "--supply",
            "25.1995,110.301",
            "--out",
            "out",
        ],
        &folder,
    );
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("--supply = 25.1995,110.301")
            && stderr.contains("did you give the longitude second?"),
        "{stderr}"
    );
    assert!(!folder.join("out").exists(), "nothing written");
    std::fs::remove_dir_all(&folder).unwrap();
}

/// An ESRI ASCII grid under the farm of [`farm_file`] (x -200..800, y -200..400, 10 m cells)
/// rising `east` per metre to the east everywhere, with `ridges`: blocks 6 m high and 20 m
/// wide every 40 m between the fields (x 170..450), whose sides slope 60 % between cell centres.
fn tilted_grid(folder: &Path, name: &str, east: f64, ridges: bool) -> String {
    let (columns, rows, cell, x0, y0) = (100, 60, 10.0, -200.0, -200.0);
    let mut text = format!(
        "ncols {columns}\nnrows {rows}\nxllcorner {x0}\nyllcorner {y0}\ncellsize {cell}\nNODATA_value -9999\n"
    );
    for _ in 0..rows {
        let row: Vec<String> = (0..columns)
            .map(|column| {
                let x = x0 + (f64::from(column) + 0.5) * cell;
                let ridge =
                    ridges && (170.0..=450.0).contains(&x) && ((x - 170.0) / 20.0) as i64 % 2 == 0;
                format!("{:.3}", 100.0 + east * x + if ridge { 6.0 } else { 0.0 })
            })
            .collect();
        text += &(row.join(" ") + "\n");
    }
    std::fs::write(folder.join(name), text).unwrap();
    name.to_string()
}

/// Decision 0029: `auto` stands on level ground where such ground serves the route; on a
/// hillside with none, it stands anyway and the summary warns with the slope.
#[test]
fn auto_keeps_to_level_ground_and_warns_on_a_hillside() {
    let folder = scratch("level");
    let fields = farm_file(&folder, "farm.geojson", "");
    // The slope by the program's own `terrain sample`, 2 m either way (decision 0029's rule).
    let slope_at = |grid: &str, x: f64, y: f64| {
        let mut arguments = vec!["terrain".to_string(), "sample".into(), grid.into()];
        for (dx, dy) in [(2.0, 0.0), (-2.0, 0.0), (0.0, 2.0), (0.0, -2.0)] {
            arguments.extend([(x + dx).to_string(), (y + dy).to_string()]);
        }
        let arguments: Vec<&str> = arguments.iter().map(String::as_str).collect();
        let heights: Vec<f64> = stdout(&agripath(&arguments, &folder))
            .lines()
            .map(|line| line.split_whitespace().last().unwrap().parse().unwrap())
            .collect();
        ((heights[0] - heights[1]) / 4.0).hypot((heights[2] - heights[3]) / 4.0)
    };
    let plan_over = |grid: &str, out: &str| {
        stdout(&agripath(
            &["plan", "--fields", &fields, "--terrain", grid, "--out", out],
            &folder,
        ))
    };
    // Ridges between the fields, where the choice stood before (165.0, 92.1: a 30 % slope by
    // this measure); level ground between them and beyond.
    let banked = tilted_grid(&folder, "banked.asc", 0.0, true);
    let text = plan_over(&banked, "banked");
    assert!(!text.contains("warning: a vehicle cannot stand"), "{text}");
    let supply = &report(&folder, "banked")["supply"];
    let [x, y] = [0, 1].map(|k| supply["point_m"][k].as_f64().unwrap());
    assert!(slope_at(&banked, x, y) <= 0.10 + 1e-9, "{supply}");
    // A hillside of 20 % everywhere.
    let hillside = tilted_grid(&folder, "hillside.asc", 0.2, false);
    let text = plan_over(&hillside, "hillside");
    assert!(
        text.contains(
            "warning: a vehicle cannot stand at the supply point: its ground slopes 20.0%"
        ),
        "{text}"
    );
    let report = report(&folder, "hillside");
    assert!(report["supply"]["warning"]
        .as_str()
        .unwrap()
        .contains("no level place (at most 10%"));
    let auto = &report["supply"]["auto"];
    assert!(
        auto["first_point"]["cost_s"].as_f64().unwrap().is_finite(),
        "{auto}"
    );
    std::fs::remove_dir_all(&folder).unwrap();
}

/// A supply point given inside an obstacle: exit 2, one line blaming `--supply`, not the field
/// file (fifth trial), and nothing written.
#[test]
fn a_point_given_inside_an_obstacle_is_blamed_on_the_flag() {
    let folder = scratch("in_obstacle");
    let obstacle = format!(
        r#",{{"type":"Feature","properties":{{"name":"shed","kind":"obstacle"}},"geometry":{{"type":"Polygon","coordinates":{}}}}}"#,
        rectangle(250.0, 50.0, 60.0, 50.0)
    );
    let fields = farm_file(&folder, "farm.geojson", &obstacle);
    let output = agripath(
        &[
            "plan", "--fields", &fields, "--out", "out", "--supply", "275,75",
        ],
        &folder,
    );
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("--supply/--start: no transit between (275.0, 75.0)")
            && stderr.contains("inside an obstacle"),
        "{stderr}"
    );
    assert!(!folder.join("out").exists(), "nothing written");
    std::fs::remove_dir_all(&folder).unwrap();
}
