//! End-to-end tests of the `agripath` program as users run it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn data(relative: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
}

fn agripath(arguments: &[&str], directory: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agripath"))
        .args(arguments)
        .current_dir(directory)
        .output()
        .unwrap()
}

fn scratch(name: &str) -> PathBuf {
    let folder = std::env::temp_dir().join(format!("agripath-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    std::fs::create_dir_all(&folder).unwrap();
    folder
}

fn stdout(output: &Output) -> String {
    assert!(
        output.status.success(),
        "status {:?}: {}",
        output.status.code(),
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout.clone()).unwrap()
}

#[test]
fn demo_writes_its_folder_and_is_byte_identical_when_run_again() {
    let folder = scratch("demo");
    let text = stdout(&agripath(&["demo"], &folder));
    assert!(text.contains("S4"), "{text}");
    let out = folder.join("agripath-demo");
    let first: Vec<Vec<u8>> = ["summary.json", "summary.txt", "terrain.png"]
        .iter()
        .map(|name| std::fs::read(out.join(name)).unwrap())
        .collect();
    let summary: serde_json::Value = serde_json::from_slice(&first[0]).unwrap();
    assert_eq!(summary["fields"].as_array().unwrap().len(), 5);
    stdout(&agripath(&["demo", "--out", "again"], &folder));
    for (index, name) in ["summary.json", "summary.txt", "terrain.png"]
        .iter()
        .enumerate()
    {
        assert_eq!(
            std::fs::read(folder.join("again").join(name)).unwrap(),
            first[index],
            "{name}"
        );
    }
    // Nothing but the two output folders: no staging left behind.
    let mut entries: Vec<String> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    entries.sort();
    assert_eq!(entries, ["again", "agripath-demo"]);
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn every_shared_data_file_validates() {
    let folder = scratch("validate");
    let mut count = 0;
    for entry in std::fs::read_dir(data("")).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".geojson") || name.ends_with(".kml") || name.ends_with(".kmz") {
            let text = stdout(&agripath(
                &["validate", "--fields", path.to_str().unwrap()],
                &folder,
            ));
            assert!(text.ends_with("valid\n"), "{name}: {text}");
            count += 1;
        }
    }
    assert!(count >= 11, "{count} field files");
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn validate_json_reports_fields_terrain_and_vehicle() {
    let folder = scratch("json");
    let scenario = data("scenarios/christmas_island.toml");
    let text = stdout(&agripath(
        &["validate", scenario.to_str().unwrap(), "--json"],
        &folder,
    ));
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(summary["fields"][0]["name"], "Plantation A");
    assert_eq!(summary["fields"][0]["holes"], 1);
    assert_eq!(summary["obstacles"], 1);
    assert_eq!(summary["swath_width_m"], 6.5);
    assert!(summary["coordinate_system"]
        .as_str()
        .unwrap()
        .contains("EPSG:32748"));
    let [low, high] = [
        summary["fields"][0]["terrain_range_m"][0].as_f64().unwrap(),
        summary["fields"][0]["terrain_range_m"][1].as_f64().unwrap(),
    ];
    assert!(low > 100.0 && high < 250.0 && high > low, "{low}..{high}");
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn terrain_sample_answers_stored_values_and_analytic_heights() {
    let folder = scratch("sample");
    let grid = data("test/grid_small.asc");
    let text = stdout(&agripath(
        &[
            "terrain",
            "sample",
            grid.to_str().unwrap(),
            "1005",
            "1025",
            "1035",
            "1005",
            "1010",
            "1020",
        ],
        &folder,
    ));
    let heights: Vec<f64> = text
        .lines()
        .map(|line| line.split_whitespace().nth(2).unwrap().parse().unwrap())
        .collect();
    // Northern row first: (1005, 1025) is row 0 column 0; (1035, 1005) is row 2 column 3;
    // (1010, 1020) is halfway between rows 0-1 and columns 0-1: (1 + 2 + 5 + 6) / 4.
    assert_eq!(heights, [1.0, 12.0, 3.5]);
    let text = stdout(&agripath(
        &["terrain", "sample", "seed000", "0", "0"],
        &folder,
    ));
    let origin: f64 = text.split_whitespace().nth(2).unwrap().parse().unwrap();
    // At the origin the hills' flanks (mostly the one at (500, 500)) top z1 = sin 10 + 1.1.
    use agripath::terrain::Terrain;
    let expected = agripath::terrain::Composite::seed000()
        .height_m(0.0, 0.0)
        .unwrap();
    assert!(expected > 10f64.sin() + 1.1);
    assert!((origin - expected).abs() < 1e-12, "{origin} vs {expected}");
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn hillshade_writes_a_png_of_the_requested_size() {
    let folder = scratch("hillshade");
    let text = stdout(&agripath(
        &[
            "terrain",
            "hillshade",
            "seed000",
            "--out",
            "hills.png",
            "--size",
            "200",
        ],
        &folder,
    ));
    assert!(text.contains("200 × 200"), "{text}");
    let bytes = std::fs::read(folder.join("hills.png")).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // IHDR width and height.
    assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 200);
    assert_eq!(u32::from_be_bytes(bytes[20..24].try_into().unwrap()), 200);
    std::fs::remove_dir_all(&folder).unwrap();
}

#[test]
fn help_and_version_exit_0_and_usage_errors_exit_2() {
    let folder = scratch("help");
    assert!(stdout(&agripath(&["--help"], &folder)).contains("demo"));
    assert!(stdout(&agripath(&["--version"], &folder)).starts_with("agripath "));
    assert_eq!(agripath(&["frobnicate"], &folder).status.code(), Some(2));
    assert_eq!(
        agripath(&["validate", "--crs", "utm"], &folder)
            .status
            .code(),
        Some(2)
    );
    std::fs::remove_dir_all(&folder).unwrap();
}
