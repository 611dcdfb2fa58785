//! What an operator reads (issue 21): the mission sheet, bearings, terrain in lon/lat.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common;
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

/// The first and last positions of every swath in a plan folder's `plan.geojson`.
fn swath_ends(folder: &Path) -> Vec<([f64; 2], [f64; 2])> {
    let plan: serde_json::Value =
        serde_json::from_slice(&std::fs::read(folder.join("plan.geojson")).unwrap()).unwrap();
    let position = |p: &serde_json::Value| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()];
    plan["features"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|feature| feature["properties"]["kind"] == "swath")
        .map(|feature| {
            let line = feature["geometry"]["coordinates"].as_array().unwrap();
            (position(&line[0]), position(&line[line.len() - 1]))
        })
        .collect()
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

/// The centres of the sortie numbers' circles on plan.svg, px.
fn sortie_number_centres(map: &str) -> Vec<(f64, f64)> {
    let start = map
        .find("<g id=\"sortie-numbers\"")
        .expect("a sortie-numbers layer");
    let layer = &map[start..];
    let layer = &layer[..layer.find("</g>").unwrap()];
    layer
        .split("<circle cx=\"")
        .skip(1)
        .map(|circle| {
            let (x, rest) = circle.split_once("\" cy=\"").unwrap();
            let y = rest.split('"').next().unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
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
        if sorties > 1 {
            let numbers = sortie_number_centres(&map);
            assert_eq!(numbers.len(), sorties, "{scenario:?}: sortie numbers");
            for (index, one) in numbers.iter().enumerate() {
                for other in &numbers[..index] {
                    let apart = (one.0 - other.0).hypot(one.1 - other.1);
                    // Circles of radius 8 px: closer than 16 px they overlap.
                    assert!(
                        apart >= 16.0,
                        "{scenario:?}: sortie numbers {apart:.1} px apart"
                    );
                }
            }
        }
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
            // (the only one with a rate) over the horizontal distance the preflight flew
            // from `sortie_NN.plan` with the pump on, the distance ArduPilot's sprayer doses
            // by (decision 0030). The report's litres are the plan's, draped over the
            // terrain: never fewer.
            assert_eq!(report["vehicle"], "DJI T16-class sprayer", "{scenario:?}");
            let rate = application_rate(&data("vehicles/dji_t16.toml"));
            let swath = report["swath_width_m"].as_f64().unwrap();
            let flown = report["preflight"]["sorties"].as_array().unwrap();
            assert_eq!(flown.len(), sorties);
            for (row, sortie) in row_litres.iter().zip(flown) {
                let spray_m = sortie["spray_m"].as_f64().unwrap()
                    - sortie["pump_stopped_m"].as_f64().unwrap();
                let as_flown = rate / 10_000.0 * swath * spray_m;
                assert!(
                    (*row - as_flown).abs() <= 0.05,
                    "{scenario:?}: sheet {row} L, flown from the file {as_flown:.2} L"
                );
            }
            assert!(
                litres <= total + 0.05 * sorties as f64
                    && litres >= total * 20f64.to_radians().cos(),
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
    let mut swaths = 0;
    for (first, last) in swath_ends(&folder.join("bearing")) {
        let (dx, dy) = (last[0] - first[0], last[1] - first[1]);
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
            text.contains("Placemark 2 (farm road): a LineString is not planned"),
            "{text}"
        );
        assert!(
            text.contains("Placemark 1 (North): the boundary was not closed"),
            "{text}"
        );
        let _ = std::fs::remove_dir_all(&folder);
    }
}

#[test]
fn a_battery_share_to_land_with_is_left_unflown_in_every_file() {
    let folder = scratch("landing-share");
    let careful = t16_with(
        &folder,
        "careful.toml",
        &[("battery_reserve_percent", "35")],
    );
    let out = folder.join("out");
    let output = plan_island_fields(&careful, &out, &[]);
    assert_eq!(output.status.code(), Some(0), "{output:?}");
    // Lon/lat fields with no DEM: the summary says the check was over flat ground.
    let printed = String::from_utf8_lossy(&output.stdout);
    assert!(
        printed.contains("warning: no terrain model: flat ground at 0 m assumed: the missions were planned and checked over it"),
        "{printed}"
    );
    assert!(printed.contains("(usable 65%)"), "{printed}");
    // The coverage line names the ground missed as flown, the area report.json counts.
    assert!(printed.contains(" m² missed as flown"), "{printed}");
    // The sheet taken to the field carries the flat-ground warning too.
    let sheet = std::fs::read_to_string(out.join("sheet.html")).unwrap();
    assert!(
        sheet.contains("<dt>Warning</dt><dd><strong>no terrain model"),
        "the sheet has no terrain warning"
    );
    let report = report(&out);
    assert_eq!(report["preflight"]["safe"], true);
    // The files, flown, leave 35 % of the 600 s battery: the preflight's own figures.
    let flown = report["preflight"]["sorties"].as_array().unwrap();
    assert!(flown.len() > 1);
    for sortie in flown {
        let share = sortie["battery_fraction"].as_f64().unwrap();
        assert!(share <= 0.65 * 1.001, "{sortie}");
    }
    assert!(report["battery_reserve_s"].as_f64().unwrap() >= 0.35 * 600.0);
    // Held back by the split itself, not by a re-plan after the preflight found overruns.
    assert_eq!(report["battery_replan_s"].as_f64(), Some(0.0));
    // A share that leaves too little to reach the far end: the error names what the
    // endurance and the share leave.
    let greedy = t16_with(&folder, "greedy.toml", &[("battery_reserve_percent", "90")]);
    let output = plan_island_fields(
        &greedy,
        &folder.join("none"),
        &["--supply", "105.6216,-10.4953"],
    );
    assert_eq!(output.status.code(), Some(2));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains(
            "greedy.toml: battery_endurance_s = 600 less battery_reserve_percent = 90 leaves 60 s, too little for this farm"
        ),
        "{message}"
    );
    // And with the supply point to choose: no point would do, not even where the route
    // begins, so the error names the vehicle file and what the share leaves.
    let output = plan_island_fields(&greedy, &folder.join("none"), &[]);
    assert_eq!(output.status.code(), Some(2));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains(
            "greedy.toml: battery_endurance_s = 600 less battery_reserve_percent = 90 leaves 60 s, too little for this farm"
        ),
        "{message}"
    );
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn a_vehicle_too_weak_for_the_farm_is_blamed_on_its_file_with_a_lon_lat_place() {
    let folder = scratch("weak");
    let weak = t16_with(
        &folder,
        "weak.toml",
        &[
            ("battery_endurance_s", "30.0"),
            ("battery_reserve_percent", "0"),
        ],
    );
    let output = plan_island_fields(
        &weak,
        &folder.join("out"),
        &["--supply", "105.6216,-10.4953"],
    );
    assert_eq!(output.status.code(), Some(2));
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("weak.toml: battery_endurance_s = 30, too little for this farm"),
        "{message}"
    );
    assert!(message.contains("near lon 105.6"), "{message}");
    assert_eq!(message.lines().count(), 1, "{message}");
    // A battery given in minutes: `validate` notes it, and `plan` blames the figure, with
    // the supply point given or to choose (a tenth trial was told to give a nearer --supply).
    let minutes = t16_with(&folder, "minutes.toml", &[("battery_endurance_s", "12.0")]);
    for supply in [&["--supply", "105.6216,-10.4953"][..], &[]] {
        let output = plan_island_fields(&minutes, &folder.join("out"), supply);
        assert_eq!(output.status.code(), Some(2));
        let message = String::from_utf8_lossy(&output.stderr);
        assert!(
            message.contains("minutes.toml: battery_endurance_s = 12 less battery_reserve_percent")
                && message.contains("minutes typed?")
                && !message.contains("--supply"),
            "{message}"
        );
    }
    let fields = data("christmas_island_fields.kml");
    let output = agripath_without_browser(&[
        "validate",
        "--fields",
        fields.to_str().unwrap(),
        "--vehicle",
        minutes.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("note: battery_endurance_s = 12 gives 12 seconds of flight")
            && stdout.ends_with("valid\n"),
        "{stdout}"
    );
    let _ = std::fs::remove_dir_all(&folder);
}

/// The DJI T16-class example vehicle with each `(key, value)` in place of its own line,
/// written to `folder/name`.
fn t16_with(folder: &Path, name: &str, figures: &[(&str, &str)]) -> PathBuf {
    let vehicle = std::fs::read_to_string(data("vehicles/dji_t16.toml")).unwrap();
    let stated: Vec<String> = figures
        .iter()
        .map(|(key, value)| format!("{key} = {value}"))
        .collect();
    let vehicle: Vec<&str> = vehicle
        .lines()
        .filter(|line| {
            let key = line.split('=').next().map(str::trim);
            !figures.iter().any(|(figure, _)| key == Some(figure))
        })
        .chain(stated.iter().map(String::as_str))
        .collect();
    let path = folder.join(name);
    std::fs::write(&path, vehicle.join("\n")).unwrap();
    path
}

/// `agripath plan` of the Christmas Island fields (KML) with `vehicle`, into `out`.
fn plan_island_fields(vehicle: &Path, out: &Path, extra: &[&str]) -> Output {
    let fields = data("christmas_island_fields.kml");
    let mut arguments = vec![
        "plan",
        "--fields",
        fields.to_str().unwrap(),
        "--vehicle",
        vehicle.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    arguments.extend_from_slice(extra);
    agripath_without_browser(&arguments)
}

/// A PNG's size and RGBA pixels.
fn rgba(path: &Path) -> (usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut pixels).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba, "{path:?}");
    (info.width as usize, info.height as usize, pixels)
}

#[test]
fn terrain_png_draws_the_fields_the_supply_point_and_a_legend_on_the_terrain() {
    let folder = scratch("terrain-map");
    let out = folder.join("island");
    let scenario = data("scenarios/christmas_island.toml");
    stdout(&agripath_without_browser(&[
        "plan",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    let (width, height, pixels) = rgba(&out.join("terrain.png"));
    // The hillshade's size: 1024 pixels on the farm box's longer side.
    assert_eq!(width.max(height), 1024, "{width} × {height}");
    let of_colour = |colour: [u8; 3]| {
        pixels
            .chunks(4)
            .enumerate()
            .filter(|(_, pixel)| pixel[..3] == colour && pixel[3] == 255)
            .map(|(index, _)| (index % width, index / width))
            .collect::<Vec<_>>()
    };
    // Field outlines (agripath::plot::terrain_map::FIELD_COLOUR) around most of the picture:
    // the picture is the farm's box with a 5 % margin.
    let field = of_colour([21, 101, 192]);
    assert!(field.len() > 3000, "{} field-outline pixels", field.len());
    let span = |axis: fn(&(usize, usize)) -> usize| {
        field.iter().map(axis).max().unwrap() - field.iter().map(axis).min().unwrap()
    };
    assert!(span(|p| p.0) > width * 3 / 4 && span(|p| p.1) > height * 3 / 4);
    assert!(!of_colour([198, 40, 40]).is_empty(), "the obstacle");
    assert!(!of_colour([255, 235, 59]).is_empty(), "the supply point");
    // The legend's colour ramp, both ends.
    for end in [[74, 140, 84], [245, 242, 236]] {
        assert!(of_colour(end).len() >= 8, "ramp end {end:?}");
    }
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn a_broken_vehicle_toml_is_reported_at_file_line_column_in_one_line() {
    let folder = scratch("broken-toml");
    let broken = folder.join("broken.toml");
    std::fs::write(
        &broken,
        "name = \"broken\"\n# swath below\nswath_width_m = = 6.5\n",
    )
    .unwrap();
    let out = folder.join("out");
    let output = plan_island_fields(&broken, &out, &[]);
    assert_eq!(output.status.code(), Some(2));
    let message = String::from_utf8_lossy(&output.stderr);
    assert_eq!(message.lines().count(), 1, "{message}");
    let expected = format!(
        "agripath: error: {}:3:17: not valid TOML: ",
        broken.display()
    );
    assert!(message.starts_with(&expected), "{message}");
    assert!(!out.exists(), "nothing written");
    let _ = std::fs::remove_dir_all(&folder);
}

/// The mission items of a `.plan`: (command, p1).
fn plan_commands(path: &Path) -> Vec<(u64, f64)> {
    let plan: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    plan["mission"]["items"]
        .as_array()
        .unwrap()
        .iter()
        .map(|item| {
            (
                item["command"].as_u64().unwrap(),
                item["params"][0].as_f64().unwrap_or(f64::NAN),
            )
        })
        .collect()
}

/// Trial 9: a servo sprayer asked of a survey vehicle was silently dropped.
#[test]
fn a_sprayer_asked_of_a_survey_vehicle_is_refused() {
    let folder = scratch("survey-servo");
    let out = folder.join("out");
    let scenario = data("scenarios/christmas_island_survey.toml");
    let output = agripath_without_browser(&[
        "plan",
        scenario.to_str().unwrap(),
        "--sprayer",
        "servo:9:1900:1100",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(output.status.code(), Some(2), "{output:?}");
    let message = String::from_utf8_lossy(&output.stderr);
    assert!(
        message.contains("--sprayer") && message.contains("is a survey vehicle"),
        "{message}"
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&folder);
}

/// Trial 9: `validate` said `valid` for two launch markers, which `plan` refuses without a
/// choice.
#[test]
fn validate_notes_two_launch_points() {
    let folder = scratch("two-launch");
    std::fs::create_dir_all(&folder).unwrap();
    let fields = folder.join("two_launch.geojson");
    std::fs::write(
        &fields,
        r#"{"type":"FeatureCollection","crs":"local","features":[
          {"type":"Feature","properties":{"name":"A"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[100,0],[100,60],[0,60],[0,0]]]}},
          {"type":"Feature","properties":{"kind":"launch","name":"Gate"},"geometry":{"type":"Point","coordinates":[-10,0]}},
          {"type":"Feature","properties":{"kind":"home","name":"Yard"},"geometry":{"type":"Point","coordinates":[110,0]}}]}"#,
    )
    .unwrap();
    let printed = stdout(&agripath_without_browser(&[
        "validate",
        "--fields",
        fields.to_str().unwrap(),
    ]));
    assert!(
        printed
            .contains("note: 2 launch points ('Gate', 'Yard'): keep one, or choose with --start"),
        "{printed}"
    );
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn a_survey_vehicle_triggers_its_camera_on_each_swath_and_has_no_tank() {
    let folder = scratch("survey");
    let out = folder.join("survey");
    let scenario = data("scenarios/christmas_island_survey.toml");
    let printed = stdout(&agripath_without_browser(&[
        "plan",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(printed.contains("survey: camera every 12 m"), "{printed}");
    // Over its DEM, no flat-ground warning.
    assert!(!printed.contains("no terrain model"), "{printed}");
    // The summary speaks of surveying, not spraying.
    assert!(
        printed.contains("survey m") && printed.contains("total: survey "),
        "{printed}"
    );
    assert!(!printed.contains("spray m"), "{printed}");
    assert!(
        !printed.contains("spraying") && printed.contains("min not surveying)"),
        "{printed}"
    );
    let validated = stdout(&agripath_without_browser(&[
        "validate",
        scenario.to_str().unwrap(),
    ]));
    assert!(validated.contains(", survey height 60 m"), "{validated}");
    let report = report(&out);
    assert_eq!(report["preflight"]["safe"], true);
    // 90 m footprint at 70 % side overlap; 60 m along the track at 80 % front overlap.
    assert_eq!(report["swath_width_m"], 27.0);
    let survey = &report["survey"];
    assert_eq!(survey["trigger_distance_m"], 12.0);
    let length =
        report["spray_length_m"].as_f64().unwrap() + report["edge_length_m"].as_f64().unwrap();
    assert_eq!(
        survey["photos_estimate"].as_u64().unwrap(),
        (length / 12.0).round() as u64
    );
    assert!(report["litres"].is_null());
    let sorties = report["sorties"].as_u64().unwrap() as usize;
    for number in 1..=sorties {
        let commands = plan_commands(&out.join(format!("sortie_{number:02}.plan")));
        assert!(
            commands
                .iter()
                .all(|(command, _)| *command != 216 && *command != 183),
            "sortie {number}: a sprayer command in a survey"
        );
        let triggers: Vec<f64> = commands
            .iter()
            .filter(|(command, _)| *command == 206)
            .map(|(_, distance)| *distance)
            .collect();
        assert!(triggers.len() >= 2, "sortie {number}: {triggers:?}");
        // On with the distance at each swath's start, off (0) at its end.
        for pair in triggers.chunks(2) {
            assert_eq!(pair, [12.0, 0.0], "sortie {number}");
        }
        let waypoints =
            std::fs::read_to_string(out.join(format!("sortie_{number:02}.waypoints"))).unwrap();
        let rows_206 = waypoints
            .lines()
            .filter(|line| line.split('\t').nth(3) == Some("206"))
            .count();
        assert_eq!(rows_206, triggers.len(), "sortie {number}: .waypoints");
    }
    let details = report["sortie_details"].as_array().unwrap();
    assert!(details
        .iter()
        .all(|sortie| sortie["tank_percent"].is_null()));
    let sheet = std::fs::read_to_string(out.join("sheet.html")).unwrap();
    assert!(sheet.contains("<th class=\"number\">photos</th>") && !sheet.contains(">litres<"));
    assert!(sheet.contains("survey camera, a photo every 12 m"));
    // Sorties end for the battery alone: a weaker battery, more sorties, still no tank.
    let weak = folder.join("weak_survey.toml");
    let vehicle = std::fs::read_to_string(data("vehicles/survey_camera.toml")).unwrap();
    std::fs::write(
        &weak,
        vehicle.replace(
            "battery_endurance_s = 1500.0",
            "battery_endurance_s = 600.0",
        ),
    )
    .unwrap();
    let terrain = data("spso/ChrismasTerrain.tif");
    let weak_out = folder.join("weak");
    stdout(&agripath_without_browser(&[
        "plan",
        "--fields",
        data("christmas_island_fields.kml").to_str().unwrap(),
        "--terrain",
        terrain.to_str().unwrap(),
        "--vehicle",
        weak.to_str().unwrap(),
        "--out",
        weak_out.to_str().unwrap(),
    ]));
    let weak_report = self::report(&weak_out);
    assert!(weak_report["sorties"].as_u64().unwrap() as usize > sorties);
    let weak_details = weak_report["sortie_details"].as_array().unwrap();
    assert!(weak_details
        .iter()
        .all(|sortie| sortie["tank_percent"].is_null()
            && sortie["battery_percent"].as_f64().unwrap() <= 100.0));
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn a_track_waypoints_file_gives_each_place_once() {
    let folder = scratch("track-once");
    let scenario = data("tracks/christmas_island_track.toml");
    stdout(&agripath_without_browser(&[
        "track",
        scenario.to_str().unwrap(),
        "--algorithm",
        "lattice",
        "--runs",
        "1",
        "--out",
        folder.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(folder.join("lattice.waypoints")).unwrap();
    // Place and altitude of each row after the header: columns 9-11.
    let places: Vec<Vec<&str>> = text
        .lines()
        .skip(1)
        .map(|line| line.split('\t').skip(8).take(3).collect())
        .collect();
    assert!(places.len() >= 5, "{text}");
    // Row 0 is home and row 1 the takeoff above it; after that no row repeats the one before.
    for pair in places[1..].windows(2) {
        assert_ne!(pair[0], pair[1], "a waypoint repeated:\n{text}");
    }
    let _ = std::fs::remove_dir_all(&folder);
}

/// In lon/lat a bearing is a true one: a field in Flevoland, 2.7° east of its UTM zone's
/// central meridian (grid north 2.1° east of true north there), flown at `bearing:90` has
/// swaths that run true east-west on the ground, and the report prints 90°, not the grid's.
#[test]
fn a_bearing_in_lon_lat_is_true_not_the_grids() {
    let folder = scratch("true_bearing");
    std::fs::create_dir_all(&folder).unwrap();
    let field = r#"{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"polder"},"geometry":{"type":"Polygon","coordinates":[[[5.700,52.500],[5.706,52.500],[5.706,52.5025],[5.700,52.5025],[5.700,52.500]]]}}]}"#;
    let fields = folder.join("polder.geojson");
    std::fs::write(&fields, field).unwrap();
    let out = folder.join("plan");
    stdout(&agripath_without_browser(&[
        "plan",
        "--fields",
        fields.to_str().unwrap(),
        "--heading",
        "bearing:90",
        "--out",
        out.to_str().unwrap(),
    ]));
    let report = report(&out);
    let printed = report["fields"][0]["heading_bearing_deg"].as_f64().unwrap();
    assert!((printed - 90.0).abs() < 1e-6, "{printed}");
    let mut swaths = 0;
    for (first, last) in swath_ends(&out) {
        let lon = |p: [f64; 2]| p[0].to_radians();
        let lat = |p: [f64; 2]| p[1].to_radians();
        // The initial azimuth on the sphere, modulo 180° (a line has two directions).
        let delta = lon(last) - lon(first);
        let east = delta.sin() * lat(last).cos();
        let north =
            lat(first).cos() * lat(last).sin() - lat(first).sin() * lat(last).cos() * delta.cos();
        let bearing = east.atan2(north).to_degrees().rem_euclid(180.0);
        assert!(
            (bearing - 90.0).abs() < 0.05,
            "a swath at true bearing {bearing}"
        );
        swaths += 1;
    }
    assert!(swaths > 10, "{swaths} swaths");
    std::fs::remove_dir_all(&folder).unwrap();
}

/// An autopilot that holds fewer mission items than a sortie has: the preflight fails the
/// plan (exit 3, no mission file), naming the sortie and the limit; one that holds them all
/// passes, with the check in `report.json` (a tenth trial: 705-922 items a sortie and no
/// word of it).
#[test]
fn a_sortie_larger_than_the_autopilot_holds_is_not_written() {
    let folder = scratch("mission_size");
    let small = t16_with(&folder, "small.toml", &[("mission_items_max", "30")]);
    let out = folder.join("small_out");
    let output = plan_island_fields(&small, &out, &["--supply", "105.6216,-10.4953"]);
    assert_eq!(output.status.code(), Some(3));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains(
            "mission items, home included, and the autopilot holds 30 (mission_items_max)"
        ),
        "{stderr}"
    );
    assert!(!out.join("sortie_01.plan").exists());
    let large = t16_with(&folder, "large.toml", &[("mission_items_max", "5000")]);
    let out = folder.join("large_out");
    let output = plan_island_fields(&large, &out, &["--supply", "105.6216,-10.4953"]);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let check = report["preflight"]["checks"]
        .as_array()
        .unwrap()
        .iter()
        .find(|check| check["name"] == "mission size")
        .expect("the mission size check");
    assert!(check["figure"].as_f64().unwrap() > 30.0, "{check}");
    assert_eq!(report["vehicle_settings"]["mission_items_max"], 5000);
    let _ = std::fs::remove_dir_all(&folder);
}
