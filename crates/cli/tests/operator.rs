//! What an operator reads (issue 21): the mission sheet, bearings, terrain in lon/lat.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::{data, stdout};

fn scratch(name: &str) -> PathBuf {
    common::scratch("sheet", name)
}

/// Runs agripath with no browser to print with, whatever the machine has.
fn agripath_without_browser(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agripath"))
        .args(arguments)
        .env("AGRIPATH_BROWSER", "none")
        .output()
        .unwrap()
}

fn report(folder: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(folder.join("report.json")).unwrap()).unwrap()
}

/// `application_rate_l_per_ha` as the vehicle file states it.
fn application_rate(vehicle: &Path) -> f64 {
    let text = std::fs::read_to_string(vehicle).unwrap();
    let line = text
        .lines()
        .find(|line| line.starts_with("application_rate_l_per_ha"))
        .unwrap();
    line.split('=')
        .nth(1)
        .unwrap()
        .split('#')
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

/// Sortie rows of the sheet's table: `<tr>` lines whose first cell is a number.
fn sortie_rows(sheet: &str) -> Vec<&str> {
    sheet
        .lines()
        .filter(|line| line.starts_with("<tr><td class=\"number\">"))
        .collect()
}

/// Every example scenario: one map layer, one viewer sortie and one sheet row per mission
/// file, and the sheet's litres add up to the report's.
#[test]
fn every_example_scenario_has_a_map_layer_and_a_sheet_row_per_sortie() {
    let folder = scratch("scenarios");
    let mut scenarios: Vec<PathBuf> = std::fs::read_dir(data("scenarios"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .collect();
    scenarios.sort();
    assert!(scenarios.len() >= 5, "{scenarios:?}");
    let mut with_litres = 0;
    for scenario in &scenarios {
        let out = folder.join(scenario.file_stem().unwrap());
        stdout(&agripath_without_browser(&[
            "plan",
            scenario.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]));
        let report = report(&out);
        let sorties = report["sorties"].as_u64().unwrap() as usize;
        let files = std::fs::read_dir(&out)
            .unwrap()
            .filter(|entry| {
                let name = entry.as_ref().unwrap().file_name();
                let name = name.to_string_lossy();
                name.starts_with("sortie_") && name.ends_with(".plan")
            })
            .count();
        assert_eq!(files, sorties, "{scenario:?}: mission files");
        let map = std::fs::read_to_string(out.join("plan.svg")).unwrap();
        assert_eq!(
            map.matches("class=\"sortie\"").count(),
            sorties,
            "{scenario:?}: map layers"
        );
        let plan: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("plan.geojson")).unwrap()).unwrap();
        let mut numbers: Vec<u64> = plan["features"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|feature| feature["properties"]["sortie"].as_u64())
            .collect();
        numbers.sort();
        numbers.dedup();
        assert_eq!(numbers.len(), sorties, "{scenario:?}: plan.geojson sorties");
        let sheet = std::fs::read_to_string(out.join("sheet.html")).unwrap();
        let rows = sortie_rows(&sheet);
        assert_eq!(rows.len(), sorties, "{scenario:?}: sheet rows");
        assert!(
            sheet.contains("<svg") && !sheet.contains("src=\"http"),
            "map inlined"
        );
        assert!(
            sheet.contains("SAFE"),
            "{scenario:?}: the preflight verdict"
        );
        if let Some(total) = report["litres"].as_f64() {
            with_litres += 1;
            // Litres per row, read back from the page, add up to the report's total.
            let row_litres: Vec<f64> = rows
                .iter()
                .map(|row| {
                    let cells: Vec<&str> = row.split("<td class=\"number\">").collect();
                    cells[3].split('<').next().unwrap().parse::<f64>().unwrap()
                })
                .collect();
            let litres: f64 = row_litres.iter().sum();
            // And each row is what its mission file sprays: the rate of the vehicle file
            // (the only one with a rate) over the spray distance the preflight flew from
            // `sortie_NN.plan` (horizontal, so within 3 % of the draped length on these
            // slopes).
            assert_eq!(report["vehicle"], "DJI T16-class sprayer", "{scenario:?}");
            let rate = application_rate(&data("vehicles/dji_t16.toml"));
            let swath = report["swath_width_m"].as_f64().unwrap();
            let flown = report["preflight"]["sorties"].as_array().unwrap();
            assert_eq!(flown.len(), sorties);
            for (row, sortie) in row_litres.iter().zip(flown) {
                let spray_m = sortie["spray_m"].as_f64().unwrap();
                let as_flown = rate / 10_000.0 * swath * spray_m;
                assert!(
                    (row - as_flown).abs() <= 0.03 * as_flown + 0.05,
                    "{scenario:?}: sheet {row} L, flown from the file {as_flown:.2} L"
                );
            }
            assert!(
                (litres - total).abs() <= 0.05 * sorties as f64,
                "{scenario:?}: rows {litres} L, report {total} L"
            );
            // The supply point in the input's terms: lon/lat for a lon/lat farm.
            if let Some(lon) = report["supply"]["lon_lat"][0].as_f64() {
                assert!(sheet.contains(&format!("{lon:.6}")), "{scenario:?}");
            }
        }
        assert!(!out.join("sheet.pdf").exists(), "no PDF unless --pdf");
    }
    assert!(with_litres >= 1, "a scenario with an application rate");
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn pdf_without_a_browser_warns_and_writes_the_rest() {
    let folder = scratch("nobrowser");
    let out = folder.join("demo");
    let text = stdout(&agripath_without_browser(&[
        "demo",
        "--pdf",
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(
        text.contains("sheet.pdf not written: no Chromium found"),
        "{text}"
    );
    assert!(out.join("sheet.html").is_file() && !out.join("sheet.pdf").exists());
    assert!(out.join("sortie_01.plan").is_file());
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn headings_are_given_as_compass_bearings_and_taken_as_them() {
    let folder = scratch("bearing");
    let fields = data("seed001_farm.geojson");
    let plan = |heading: &str, name: &str| {
        let out = folder.join(name);
        stdout(&agripath_without_browser(&[
            "plan",
            "--fields",
            fields.to_str().unwrap(),
            "--heading",
            heading,
            "--out",
            out.to_str().unwrap(),
        ]));
        report(&out)
    };
    // East-west swaths: the seed's 0° from east is a bearing of 90°, and bearing:90 is 0°.
    let by_angle = plan("0", "angle");
    let by_bearing = plan("bearing:90", "bearing");
    for report in [&by_angle, &by_bearing] {
        for field in report["fields"].as_array().unwrap() {
            assert_eq!(field["heading_deg"].as_f64(), Some(0.0));
            assert_eq!(field["heading_bearing_deg"].as_f64(), Some(90.0));
        }
    }
    // The swaths as written (plan.geojson, local metres: x east, y north) run east-west.
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(folder.join("bearing/plan.geojson")).unwrap())
            .unwrap();
    let mut swaths = 0;
    for feature in plan["features"].as_array().unwrap() {
        if feature["properties"]["kind"] != "swath" {
            continue;
        }
        let line = feature["geometry"]["coordinates"].as_array().unwrap();
        let (first, last) = (&line[0], &line[line.len() - 1]);
        let dx = last[0].as_f64().unwrap() - first[0].as_f64().unwrap();
        let dy = last[1].as_f64().unwrap() - first[1].as_f64().unwrap();
        let bearing = dx.atan2(dy).to_degrees().rem_euclid(180.0);
        assert!(
            (bearing - 90.0).abs() < 1e-6,
            "a swath at bearing {bearing}"
        );
        swaths += 1;
    }
    assert!(swaths > 10);
    let bad = agripath_without_browser(&[
        "plan",
        "--fields",
        fields.to_str().unwrap(),
        "--heading",
        "bearing:north",
        "--out",
        folder.join("bad").to_str().unwrap(),
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("bearing:DEG"));
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn terrain_info_gives_lon_lat_and_metres_and_sample_takes_lon_lat() {
    // A UTM DEM (GDA94 / MGA zone 48): its extent in metres and in lon/lat.
    let island = data("spso/ChrismasTerrain.tif");
    let text = stdout(&agripath_without_browser(&[
        "terrain",
        "info",
        island.to_str().unwrap(),
    ]));
    assert!(text.contains("(5225.0 × 4395.0 m)"), "{text}");
    assert!(
        text.contains("lon/lat lon 105.609577..105.657403, lat -10.509001..-10.469158"),
        "{text}"
    );
    // A DEM in degrees: its size in metres, not 0.0 × 0.0.
    let degrees = data("test/geotiff/lonlat_4326_float64.tif");
    let text = stdout(&agripath_without_browser(&[
        "terrain",
        "info",
        degrees.to_str().unwrap(),
    ]));
    assert!(
        text.contains(
            "extent lon 8.500000..8.540000, lat 47.300000..47.324000 (about 3019.0 × 2667.2 m)"
        ),
        "{text}"
    );
    // A lon/lat point inside the DEM answers with one of its heights.
    let by_lon_lat = stdout(&agripath_without_browser(&[
        "terrain",
        "sample",
        island.to_str().unwrap(),
        "--lonlat",
        "105.63",
        "-10.49",
    ]));
    let height: f64 = by_lon_lat
        .split_whitespace()
        .nth(2)
        .unwrap()
        .parse()
        .unwrap();
    assert!((48.9..296.1).contains(&height), "{by_lon_lat}");
}

#[test]
fn skipped_and_repaired_features_are_named_not_dropped() {
    let fields = data("test/road_and_open_ring.kml");
    for command in ["validate", "plan"] {
        let folder = scratch(command);
        let mut arguments = vec![command, "--fields", fields.to_str().unwrap()];
        let out = folder.join("out");
        if command == "plan" {
            arguments.extend(["--out", out.to_str().unwrap()]);
        }
        let text = stdout(&agripath_without_browser(&arguments));
        assert!(
            text.contains("Placemark 1 (farm road): a LineString is not planned"),
            "{text}"
        );
        assert!(
            text.contains("Placemark 0 (North): the boundary was not closed"),
            "{text}"
        );
        let _ = std::fs::remove_dir_all(&folder);
    }
}

#[test]
fn a_vehicle_too_weak_for_the_farm_is_blamed_on_its_file_with_a_lon_lat_place() {
    let folder = scratch("weak");
    let weak = folder.join("weak.toml");
    let vehicle = std::fs::read_to_string(data("vehicles/dji_t16.toml")).unwrap();
    let vehicle: String = vehicle
        .lines()
        .map(|line| {
            if line.starts_with("battery_endurance_s") {
                "battery_endurance_s = 30.0".to_string()
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&weak, vehicle).unwrap();
    let fields = data("christmas_island_fields.kml");
    let output = agripath_without_browser(&[
        "plan",
        "--fields",
        fields.to_str().unwrap(),
        "--vehicle",
        weak.to_str().unwrap(),
        "--supply",
        "105.6216,-10.4953",
        "--out",
        folder.join("out").to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(2));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("weak.toml: battery_endurance_s = 30 is invalid"),
        "{message}"
    );
    assert!(message.contains("near lon 105.6"), "{message}");
    assert_eq!(message.lines().count(), 1, "{message}");
    let _ = std::fs::remove_dir_all(&folder);
}
