//! Golden files for every mission exporter: a small two-field farm on a gentle slope, with a
//! tank that forces two sorties, planned and rendered; each exported file must equal the one
//! checked in under `tests/golden/` byte for byte. After a deliberate change, regenerate with
//! `UPDATE_GOLDEN=1 cargo test -p agripath --test golden_exporters` and review the diff.

use std::path::{Path, PathBuf};

use agripath::input::{geojson, CoordinateChoice};
use agripath::mission::qgc_plan::check_plan;
use agripath::pipeline::{plan_mission, render};
use agripath::scenario::Scenario;
use agripath::scenario::ScenarioParts;
use agripath::settings::PlanSettings;
use agripath::terrain::TerrainSpec;

const FARM: &str = r#"{"type": "FeatureCollection", "crs": "local", "features": [
  {"type": "Feature", "properties": {"name": "north"}, "geometry": {"type": "Polygon",
   "coordinates": [[[100, 100], [160, 100], [160, 140], [100, 140], [100, 100]]]}},
  {"type": "Feature", "properties": {"name": "east"}, "geometry": {"type": "Polygon",
   "coordinates": [[[190, 90], [230, 90], [230, 130], [190, 130], [190, 90]]]}},
  {"type": "Feature", "properties": {"kind": "obstacle", "name": "pole"}, "geometry": {"type": "Polygon",
   "coordinates": [[[120, 115], [126, 115], [126, 121], [120, 121], [120, 115]]]}},
  {"type": "Feature", "properties": {"kind": "launch"}, "geometry": {"type": "Point", "coordinates": [95, 95]}}
]}"#;

const VEHICLE: &str = r#"
name = "golden sprayer"
swath_width_m = 5.0
spray_height_m = 2.5
safe_height_m = 10.0
spray_speed_mps = 4.0
turn_speed_mps = 3.0
transit_speed_mps = 8.0
climb_speed_mps = 2.0
tank_spray_time_s = 150.0
battery_endurance_s = 900.0
battery_swap_s = 60.0
refill_base_s = 20.0
refill_max_s = 90.0
"#;

fn golden() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn rendered() -> Vec<(String, Vec<u8>)> {
    let farm = geojson::parse(
        Path::new("golden.geojson"),
        FARM,
        CoordinateChoice::FromFile,
    )
    .unwrap();
    let vehicle: toml::Table = toml::from_str(VEHICLE).unwrap();
    let scenario = Scenario::with_farm(
        farm,
        ScenarioParts {
            name: Some("golden farm".into()),
            terrain: Some(TerrainSpec::Composite {
                preset: "seed002".into(),
            }),
            vehicle_table: Some(vehicle),
            ..ScenarioParts::default()
        },
    )
    .unwrap();
    let mission = plan_mission(&scenario, &PlanSettings::default()).unwrap();
    assert!(mission.report.sorties >= 2, "the tank must force a return");
    let rendered = render(&scenario, &mission).unwrap();
    assert!(
        rendered.verdict.safe,
        "the golden plan flies safely as written: {:?}",
        rendered.verdict.failures
    );
    rendered.files
}

#[test]
fn every_exporter_matches_its_golden_file() {
    let files = rendered();
    let exporters = [
        "plan.geojson",
        "sortie_01.plan",
        "sortie_01.waypoints",
        "sortie_02.plan",
        "sortie_02.waypoints",
        "mission.kml",
        "waypoints.csv",
    ];
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    for name in exporters {
        let (_, bytes) = files
            .iter()
            .find(|(file, _)| file == name)
            .unwrap_or_else(|| panic!("{name} not written"));
        let path = golden().join(name);
        if update {
            std::fs::write(&path, bytes).unwrap();
            continue;
        }
        let expected = std::fs::read(&path)
            .unwrap_or_else(|_| panic!("{} missing: run with UPDATE_GOLDEN=1", path.display()));
        assert!(
            expected == *bytes,
            "{name} differs from {} (UPDATE_GOLDEN=1 to accept a deliberate change)",
            path.display()
        );
    }
}

/// The track exporters: ours on seed 000's task I with a small budget (deterministic by seed).
#[test]
fn track_exporters_match_their_golden_files() {
    use agripath::track::files::{geojson, mission, PlannerRuns};
    use agripath::track::{plan, Planner, TrackScenario, TrackSettings};
    let scenario = TrackScenario::seed000("I").unwrap();
    let settings = TrackSettings {
        planner: Planner::Lattice,
        encoding: None,
        runs: 1,
        seed: 1,
        evaluations: Some(3000),
    };
    let runs = plan(&scenario, &settings, &|| {}).unwrap();
    let results = [PlannerRuns {
        planner: Planner::Lattice,
        encoding: agripath::track::Encoding::Cartesian,
        runs,
    }];
    let files = [
        ("track.geojson", geojson(&scenario, &results)),
        (
            "track.waypoints",
            mission(&scenario, results[0].best().final_points()),
        ),
    ];
    for (name, text) in files {
        let path = golden().join(name);
        if std::env::var_os("UPDATE_GOLDEN").is_some() {
            std::fs::write(&path, &text).unwrap();
            continue;
        }
        let expected = std::fs::read_to_string(&path)
            .unwrap_or_else(|_| panic!("{} missing: run with UPDATE_GOLDEN=1", path.display()));
        assert!(
            expected == text,
            "{name} differs from {} (UPDATE_GOLDEN=1 to accept a deliberate change)",
            path.display()
        );
    }
}

#[test]
fn every_plan_file_passes_the_qgroundcontrol_loader_rules() {
    for (name, bytes) in rendered() {
        if name.ends_with(".plan") {
            let faults = check_plan(std::str::from_utf8(&bytes).unwrap());
            assert!(faults.is_empty(), "{name}: {faults:?}");
        }
    }
    // The checker itself catches what QGC refuses.
    let broken = r#"{"fileType": "Plan", "version": 1, "groundStation": "x", "mission": {"version": 2, "firmwareType": 3,
        "plannedHomePosition": [0, 0, 0], "items": [{"type": "SimpleItem", "command": 16, "frame": 0,
        "autoContinue": true, "params": [0, 0, 0, null, 1, 2], "Altitude": 3}]}}"#;
    let faults = check_plan(broken);
    assert_eq!(faults.len(), 2, "{faults:?}");
}

#[test]
fn sprayer_commands_pair_up_and_missions_end_landing_at_home() {
    for (name, bytes) in rendered() {
        if !name.ends_with(".waypoints") {
            continue;
        }
        let text = String::from_utf8(bytes).unwrap();
        let rows: Vec<Vec<&str>> = text
            .lines()
            .skip(1)
            .map(|line| line.split('\t').collect())
            .collect();
        assert!(rows.iter().all(|row| row.len() == 12), "{name}: 12 columns");
        let sprayer: Vec<&str> = rows
            .iter()
            .filter(|row| row[3] == "216")
            .map(|row| row[4])
            .collect();
        assert!(!sprayer.is_empty());
        for pair in sprayer.chunks(2) {
            assert_eq!(pair, ["1.000", "0.000"], "{name}: on, then off");
        }
        assert_eq!(rows[1][3], "22", "{name}: takes off first");
        let last = rows.last().unwrap();
        assert_eq!(last[3], "21", "{name}: lands last");
        assert_eq!(
            (last[8], last[9]),
            (rows[0][8], rows[0][9]),
            "{name}: lands at home"
        );
    }
}
