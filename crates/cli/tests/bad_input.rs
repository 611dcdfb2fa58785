//! The bad-input corpus (`data/test/bad/`): every case exits with status 2, prints exactly one
//! line naming the file (or flag) and the fault, never panics, and writes nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn data(relative: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(relative)
        .display()
        .to_string()
}

fn bad(name: &str) -> String {
    data(&format!("test/bad/{name}"))
}

/// (arguments, the file or flag the message must name, a fragment of the fault).
fn corpus() -> Vec<(Vec<String>, String, &'static str)> {
    let fields = |name: &str| vec!["validate".to_string(), "--fields".into(), bad(name)];
    let local_fields = |name: &str| {
        vec![
            "validate".to_string(),
            "--fields".into(),
            bad(name),
            "--crs".into(),
            "local".into(),
        ]
    };
    let terrain_info = |name: &str| vec!["terrain".to_string(), "info".into(), bad(name)];
    let vehicle = |name: &str| {
        vec![
            "validate".to_string(),
            "--fields".into(),
            data("seed001_farm.geojson"),
            "--vehicle".into(),
            bad(name),
        ]
    };
    let scenario = |name: &str| vec!["validate".to_string(), bad(name)];
    let farm_with = |flags: &[&str]| {
        let mut arguments = vec![
            "validate".to_string(),
            "--fields".into(),
            data("seed001_farm.geojson"),
        ];
        arguments.extend(flags.iter().map(|flag| flag.to_string()));
        arguments
    };
    vec![
        (fields("empty.geojson"), bad("empty.geojson"), "empty"),
        (
            fields("whitespace.geojson"),
            bad("whitespace.geojson"),
            "empty",
        ),
        (
            fields("truncated.geojson"),
            bad("truncated.geojson"),
            "not valid JSON",
        ),
        (fields("binary.geojson"), bad("binary.geojson"), "not UTF-8"),
        (
            fields("wrong_type.geojson"),
            bad("wrong_type.geojson"),
            "not an array",
        ),
        (
            fields("string_number.geojson"),
            bad("string_number.geojson"),
            "not a number",
        ),
        (
            fields("self_intersecting.geojson"),
            bad("self_intersecting.geojson"),
            "feature 0 (bowtie): boundary intersects itself near (5.000, 5.000)",
        ),
        (
            fields("hole_outside.geojson"),
            bad("hole_outside.geojson"),
            "hole 1 lies outside",
        ),
        (
            fields("hole_crossing.geojson"),
            bad("hole_crossing.geojson"),
            "hole 1 crosses the outer boundary",
        ),
        (
            fields("holes_overlap.geojson"),
            bad("holes_overlap.geojson"),
            "overlap",
        ),
        (
            fields("lonlat_out_of_range.geojson"),
            bad("lonlat_out_of_range.geojson"),
            "out of range",
        ),
        (
            fields("linestring.geojson"),
            bad("linestring.geojson"),
            "'LineString' cannot be a field",
        ),
        (
            fields("unclosed.geojson"),
            bad("unclosed.geojson"),
            "not closed",
        ),
        (
            fields("degenerate.geojson"),
            bad("degenerate.geojson"),
            "fewer than 3 distinct points",
        ),
        (
            fields("collinear.geojson"),
            bad("collinear.geojson"),
            "zero area",
        ),
        (
            fields("infinite.geojson"),
            bad("infinite.geojson"),
            "number out of range",
        ),
        (
            fields("unknown_kind.geojson"),
            bad("unknown_kind.geojson"),
            "kind is 'pond'",
        ),
        (
            fields("no_fields.geojson"),
            bad("no_fields.geojson"),
            "no field polygons",
        ),
        (
            fields("too_wide.geojson"),
            bad("too_wide.geojson"),
            "span 300 km",
        ),
        (
            fields("farm_too_spread.geojson"),
            bad("farm_too_spread.geojson"),
            "limit 200 km",
        ),
        (
            fields("bad_crs.geojson"),
            bad("bad_crs.geojson"),
            "EPSG:3857",
        ),
        (
            fields("fields.shp"),
            bad("fields.shp"),
            "unsupported file type 'shp'",
        ),
        (
            fields("does_not_exist.geojson"),
            bad("does_not_exist.geojson"),
            "no such file",
        ),
        (fields("truncated.kml"), bad("truncated.kml"), "truncated"),
        (
            fields("not_kml.kml"),
            bad("not_kml.kml"),
            "not a KML document",
        ),
        (
            fields("bad_coordinates.kml"),
            bad("bad_coordinates.kml"),
            "'a,b' is not 'lon,lat[,alt]'",
        ),
        (
            fields("mismatched.kml"),
            bad("mismatched.kml"),
            "not valid KML",
        ),
        (
            fields("not_zip.kmz"),
            bad("not_zip.kmz"),
            "not a KMZ (zip) archive",
        ),
        (
            fields("no_kml_inside.kmz"),
            bad("no_kml_inside.kmz"),
            "holds no .kml",
        ),
        (
            local_fields("local_too_big.geojson"),
            bad("local_too_big.geojson"),
            "is this lon/lat?",
        ),
        (
            terrain_info("truncated.asc"),
            bad("truncated.asc"),
            "truncated",
        ),
        (
            terrain_info("nan.asc"),
            bad("nan.asc"),
            "row 1, column 2: coordinate is not a finite number",
        ),
        (
            terrain_info("no_cellsize.asc"),
            bad("no_cellsize.asc"),
            "no 'cellsize'",
        ),
        (
            terrain_info("text.tif"),
            bad("text.tif"),
            "not a readable GeoTIFF",
        ),
        (
            terrain_info("truncated.tif"),
            bad("truncated.tif"),
            "not a readable GeoTIFF",
        ),
        (
            terrain_info("short_line.xyz"),
            bad("short_line.xyz"),
            "line 3: expected 'x y z'",
        ),
        (
            terrain_info("collinear.xyz"),
            bad("collinear.xyz"),
            "span no area",
        ),
        (
            vec![
                "terrain".into(),
                "info".into(),
                data("test/geotiff/rotated.tif"),
            ],
            data("test/geotiff/rotated.tif"),
            "rotated",
        ),
        (
            vehicle("vehicle_negative_swath.toml"),
            bad("vehicle_negative_swath.toml"),
            "swath_width_m = -5 is invalid",
        ),
        (
            vehicle("vehicle_unknown_key.toml"),
            bad("vehicle_unknown_key.toml"),
            "line 1, column 1: unknown field `swath_widht_m`",
        ),
        (
            vehicle("vehicle_nan.toml"),
            bad("vehicle_nan.toml"),
            "spray_speed_mps = NaN",
        ),
        (
            vehicle("vehicle_wrong_type.toml"),
            bad("vehicle_wrong_type.toml"),
            "line 1, column 17: invalid type",
        ),
        (
            vehicle("vehicle_tank_without_rate.toml"),
            bad("vehicle_tank_without_rate.toml"),
            "go together",
        ),
        (
            scenario("scenario_syntax.toml"),
            bad("scenario_syntax.toml"),
            "not valid TOML",
        ),
        (
            scenario("scenario_missing_fields.toml"),
            data("test/bad/does_not_exist.geojson"),
            "no such file",
        ),
        (
            scenario("scenario_unknown_key.toml"),
            bad("scenario_unknown_key.toml"),
            "unknown field `speed`",
        ),
        (
            scenario("scenario_bad_terrain.toml"),
            bad("scenario_bad_terrain.toml"),
            "unknown variant `volcano`",
        ),
        (
            scenario("scenario_dem_not_covering.toml"),
            data("test/bad/../geotiff/float32_strips_none.tif"),
            "field 'S1': the terrain model does not cover the field",
        ),
        (
            scenario("scenario_lonlat_fields_dem_without_crs.toml"),
            data("test/bad/../grid_small.asc"),
            "does not cover the field",
        ),
        (
            farm_with(&["--swath-width", "0"]),
            "--swath-width".into(),
            "swath_width_m = 0 is invalid",
        ),
        (
            farm_with(&["--safe-height", "1e308"]),
            "--safe-height".into(),
            "safe_height_m = 1e308 is invalid: a vehicle's safe_height_m lies in 0..=500",
        ),
        (
            farm_with(&["--spray-height", "1e308"]),
            "--spray-height".into(),
            "spray_height_m = 1e308 is invalid",
        ),
        (
            farm_with(&["--swath-width", "0.001"]),
            "--swath-width".into(),
            "lies in 0.5..=200",
        ),
        (
            farm_with(&["--swath-width", "-5"]),
            "--swath-width".into(),
            "must be a finite number above 0",
        ),
        (
            farm_with(&["--swath-width", "NaN"]),
            "--swath-width".into(),
            "NaN",
        ),
        (
            farm_with(&["--spray-height", "inf"]),
            "--spray-height".into(),
            "inf",
        ),
        (
            farm_with(&["--terrain", "flat:abc"]),
            "--terrain".into(),
            "flat:HEIGHT needs a number",
        ),
        (
            farm_with(&["--terrain", "seed000"]),
            "seed001_farm.geojson".into(),
            "outside the terrain model",
        ),
        (
            vec![
                "terrain".into(),
                "sample".into(),
                data("test/grid_small.asc"),
                "0".into(),
                "0".into(),
            ],
            data("test/grid_small.asc"),
            "outside the terrain model",
        ),
        (
            vec![
                "terrain".into(),
                "hillshade".into(),
                "flat".into(),
                "--out".into(),
                "never.png".into(),
            ],
            "flat".into(),
            "unbounded",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--algorithms", "pso,nope"]),
            "--algorithms".into(),
            "unknown algorithm 'nope'",
        ),
        (
            bench_with(&["--runs", "1", "--functions", "f3", "--dim", "30"]),
            "--dim".into(),
            "only 50",
        ),
        (
            bench_with(&["--runs", "0", "--dim", "5"]),
            "--runs".into(),
            "needs at least 1",
        ),
        (
            bench_with(&["--runs", "1", "--dim", "5", "--functions", "f10"]),
            "--functions".into(),
            "unknown function",
        ),
        (
            track_with(
                &data("seed000_orchard.json"),
                &["--algorithm", "lattice,nope"],
            ),
            "--algorithm".into(),
            "unknown planner 'nope'",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--task", "IV"]),
            data("seed000_orchard.json"),
            "the scenario has tasks I, II, III",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--encoding", "polar"]),
            "--encoding".into(),
            "cartesian, cylindrical or spherical",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--runs", "0"]),
            "--runs".into(),
            "1..=1000",
        ),
        (
            track_with(&data("seed001_farm.geojson"), &[]),
            data("seed001_farm.geojson"),
            "not a track scenario",
        ),
        (
            track_with(&bad("track_negative_radius.json"), &[]),
            bad("track_negative_radius.json"),
            "positive radius",
        ),
        (
            track_with(&bad("track_start_outside.json"), &[]),
            bad("track_start_outside.json"),
            "outside the planning area",
        ),
        (
            track_with(&bad("track_start_in_threat.json"), &[]),
            bad("track_start_in_threat.json"),
            "start = (505, 500) is invalid: inside threat cylinder 0",
        ),
        (
            track_with(&bad("track_goal_under_terrain.json"), &[]),
            bad("track_goal_under_terrain.json"),
            "m under the terrain",
        ),
        (
            track_with(&bad("track_unknown_key.json"), &[]),
            bad("track_unknown_key.json"),
            "unknown key 'terrain.hils'",
        ),
        (
            track_with(&data("seed000_orchard.json"), &["--min-clearance", "5000"]),
            data("seed000_orchard.json"),
            "--min-clearance",
        ),
        (
            track_with(&bad("track_spso_missing_dem.json"), &[]),
            bad("missing.tif"),
            "cannot read",
        ),
        (
            track_with(&bad("track_outside_dem.toml"), &[]),
            bad("track_outside_dem.toml"),
            "does not cover",
        ),
        (
            track_with(&bad("track_bad_band.toml"), &[]),
            bad("track_bad_band.toml"),
            "lower < upper",
        ),
        (
            track_with(&bad("empty.geojson"), &[]),
            bad("empty.geojson"),
            "empty",
        ),
    ]
}

/// `track` with a tiny budget, writing to `out` (which must never appear).
fn track_with(scenario: &str, extra: &[&str]) -> Vec<String> {
    let mut arguments: Vec<String> = vec!["track".into(), scenario.into()];
    if !extra.contains(&"--runs") {
        arguments.extend(["--runs".to_string(), "1".into()]);
    }
    arguments.extend([
        "--evaluations".to_string(),
        "200".into(),
        "--out".into(),
        "out".into(),
    ]);
    arguments.extend(extra.iter().map(|s| s.to_string()));
    arguments
}

/// `bench functions` with a tiny budget and extra arguments.
fn bench_with(extra: &[&str]) -> Vec<String> {
    let mut arguments: Vec<String> = ["bench", "functions", "--pop", "4", "--iters", "2"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    arguments.extend(extra.iter().map(|s| s.to_string()));
    arguments
}

#[test]
fn every_bad_input_exits_2_with_one_line_naming_the_file_and_writes_nothing() {
    let workdir = std::env::temp_dir().join(format!("agripath-bad-input-{}", std::process::id()));
    std::fs::create_dir_all(&workdir).unwrap();
    let cases = corpus();
    assert!(cases.len() >= 40, "the corpus has {} cases", cases.len());
    let mut failures = Vec::new();
    for (arguments, file, fragment) in &cases {
        let output = Command::new(env!("CARGO_BIN_EXE_agripath"))
            .args(arguments)
            .current_dir(&workdir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        let ok = output.status.code() == Some(2)
            && stderr.lines().count() == 1
            && stderr.starts_with("agripath: error: ")
            && stderr.contains(file.as_str())
            && stderr.contains(fragment)
            && !stderr.contains("panicked");
        if !ok {
            failures.push(format!(
                "{arguments:?}\n  status {:?}, expected to name {file} and say '{fragment}'\n  stderr: {stderr}",
                output.status.code()
            ));
        }
    }
    let left: Vec<PathBuf> = std::fs::read_dir(&workdir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    std::fs::remove_dir_all(&workdir).unwrap();
    assert!(left.is_empty(), "bad input left files behind: {left:?}");
    assert!(
        failures.is_empty(),
        "{} of {} cases failed:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}
