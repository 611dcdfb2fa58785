//! What the preflight check adds to a plan: the demo (seed 001 farm, 9 sorties) and the
//! Christmas Island plantation over the real DEM (36 sorties); median of 11 runs each of
//! planning (`plan_mission`, the report's `runtime_s`), rendering every file, and the
//! preflight alone on the mission files rendered.
//!
//! `cargo run --release -p agripath --example bench_preflight`

use std::path::Path;
use std::time::Instant;

use agripath::mission::flight::AltitudeReference;
use agripath::pipeline::{plan_mission, preflight_settings, render};
use agripath::preflight::{check, World};
use agripath::scenario::Scenario;
use agripath::scenario::VehicleOverrides;
use agripath::settings::PlanSettings;

fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

fn bench(name: &str, scenario: &Scenario, settings: &PlanSettings) {
    let mut planning = Vec::new();
    let mut rendering = Vec::new();
    let mut preflight = Vec::new();
    for _ in 0..11 {
        let started = Instant::now();
        let mission = plan_mission(scenario, settings).expect("plans");
        planning.push(started.elapsed().as_secs_f64() * 1e3);
        let started = Instant::now();
        let rendered = render(scenario, &mission).expect("renders");
        rendering.push(started.elapsed().as_secs_f64() * 1e3);
        assert!(rendered.verdict.safe);
        let world = World {
            farm: &scenario.farm,
            terrain: scenario.terrain.as_ref(),
            vehicle: &scenario.vehicle,
        };
        let mission_settings = preflight_settings(&mission);
        let started = Instant::now();
        let verdict = check(&world, &mission_settings, &rendered.files);
        preflight.push(started.elapsed().as_secs_f64() * 1e3);
        assert!(verdict.safe);
    }
    let (planning, rendering, preflight) = (median(planning), median(rendering), median(preflight));
    println!(
        "{name}: planning {planning:.1} ms, rendering every file {rendering:.1} ms (preflight included), preflight {preflight:.1} ms = {:.0} % of planning, {:.0} % of plan + render",
        100.0 * preflight / planning,
        100.0 * preflight / (planning + rendering)
    );
}

fn main() {
    let demo = agripath::demo::scenario().expect("the embedded farm");
    let mut settings = PlanSettings {
        start: Some([0.0, 0.0]),
        ..PlanSettings::default()
    };
    settings.mission.altitude = AltitudeReference::Relative;
    bench("demo", &demo, &settings);
    let island = Scenario::from_file(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/scenarios/christmas_island.toml"),
        VehicleOverrides::default(),
        false,
    )
    .expect("the island scenario");
    settings.start = None;
    settings.mission.altitude = AltitudeReference::SeaLevel;
    bench("island", &island, &settings);
}
