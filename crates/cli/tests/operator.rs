//! What an operator reads (issue 21): the mission sheet, bearings, terrain in lon/lat.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn data(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
}

fn scratch(name: &str) -> PathBuf {
    let folder = std::env::temp_dir().join(format!("agripath-sheet-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

/// Runs agripath with no browser to print with, whatever the machine has.
fn agripath_without_browser(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agripath"))
        .args(arguments)
        .env("AGRIPATH_BROWSER", "none")
        .output()
        .unwrap()
}

fn succeeded(output: &Output) -> String {
    assert!(
        output.status.success(),
        "status {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

fn report(folder: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(folder.join("report.json")).unwrap()).unwrap()
}

/// Sortie rows of the sheet's table: `<tr>` lines whose first cell is a number.
fn sortie_rows(sheet: &str) -> Vec<&str> {
    sheet
        .lines()
        .filter(|line| line.starts_with("<tr><td class=\"number\">"))
        .collect()
}

#[test]
fn the_sheet_lists_every_sortie_and_its_litres_add_up_to_the_report() {
    let folder = scratch("island");
    let out = folder.join("plan");
    let scenario = data("scenarios/christmas_island.toml");
    succeeded(&agripath_without_browser(&[
        "plan",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    let sheet = std::fs::read_to_string(out.join("sheet.html")).unwrap();
    let report = report(&out);
    let sorties = report["sorties"].as_u64().unwrap() as usize;
    assert!(sorties > 1);
    let rows = sortie_rows(&sheet);
    assert_eq!(rows.len(), sorties, "one row per sortie_NN.plan");
    // Litres per row, read back from the page, add up to the report's total.
    let litres: f64 = rows
        .iter()
        .map(|row| {
            let cells: Vec<&str> = row.split("<td class=\"number\">").collect();
            cells[3].split('<').next().unwrap().parse::<f64>().unwrap()
        })
        .sum();
    let total = report["litres"].as_f64().unwrap();
    assert!(
        (litres - total).abs() <= 0.05 * sorties as f64,
        "rows {litres} L, report {total} L"
    );
    // Places in the input's terms: the supply point in lon/lat, the preflight's verdict.
    let supply = &report["supply"]["lon_lat"];
    assert!(sheet.contains(&format!("{:.6}", supply[0].as_f64().unwrap())));
    assert!(
        sheet.contains("SAFE"),
        "the preflight verdict is on the sheet"
    );
    assert!(sheet.contains("<svg"), "the map is inlined");
    assert!(
        !sheet.contains("src=\"http"),
        "nothing fetched from the network"
    );
    assert!(!out.join("sheet.pdf").exists(), "no PDF unless --pdf");
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn pdf_without_a_browser_warns_and_writes_the_rest() {
    let folder = scratch("nobrowser");
    let out = folder.join("demo");
    let text = succeeded(&agripath_without_browser(&[
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
        succeeded(&agripath_without_browser(&[
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
    let text = succeeded(&agripath_without_browser(&[
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
    let text = succeeded(&agripath_without_browser(&[
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
    let by_lon_lat = succeeded(&agripath_without_browser(&[
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
