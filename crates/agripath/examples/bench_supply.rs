//! The supply point (issue 19 item 2): on the Christmas Island farm (KML, no marker), the seed
//! 001 farm (its GeoJSON, default vehicle) and random irregular farms of about 200 swaths,
//! the `auto` point's non-spray time against the old rule (the first point of the route
//! planned without a start point), both by the same evaluator, the same measure on the route
//! as planned from the point, and the time the choice adds to `plan` (the median default plan
//! against the median plan given the chosen point, which skips the search and the route
//! planned without a start), with its two parts timed alone. Run:
//!
//! ```sh
//! cargo run --release -p agripath --example bench_supply [-- RUNS]
//! ```

use std::path::{Path, PathBuf};
use std::time::Instant;

use agripath::coverage::plan_coverage;
use agripath::input::CoordinateChoice;
use agripath::pipeline::{plan_mission, supply_point};
use agripath::scenario::{Scenario, ScenarioParts, VehicleOverrides};
use agripath::sequence::tour::Start;
use agripath::sequence::{route, TransferModel};
use agripath::settings::PlanSettings;

fn parts(fields: PathBuf) -> ScenarioParts {
    ScenarioParts {
        name: None,
        fields,
        coordinates: CoordinateChoice::FromFile,
        terrain: None,
        terrain_base: PathBuf::new(),
        vehicle_file: None,
        vehicle_table: None,
        overrides: VehicleOverrides::default(),
        allow_overlap: false,
    }
}

fn median_ms(runs: usize, mut work: impl FnMut()) -> f64 {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let started = Instant::now();
            work();
            started.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[runs / 2]
}

/// One row of the table, and what the totals need of it.
fn row(name: &str, scenario: &Scenario, runs: usize) -> Row {
    let settings = PlanSettings::default();
    let mission = plan_mission(scenario, &settings).expect("a plan");
    let supply = mission.report.supply.clone().expect("a supply point");
    let auto = supply.auto.clone().expect("the auto rule");
    let cost = supply.cost_s.expect("a cost");
    let given = PlanSettings {
        start: Some(supply.at.point_m),
        ..settings
    };
    let auto_ms = median_ms(runs, || {
        plan_mission(scenario, &settings).expect("a plan");
    });
    // The two parts of the added time: the route planned without a start point, and the
    // search on it.
    let coverage = plan_coverage(
        &scenario.farm,
        scenario.terrain.as_ref(),
        &scenario.vehicle,
        &settings.coverage,
    )
    .expect("a layout");
    let transfers = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
    // The route the supply search plans: the closed tour by the iterated search alone, as
    // `pipeline::supply_point` plans it.
    let sequencer = settings.sequencer.without_restarts();
    let route_ms = median_ms(runs, || {
        route(&coverage, &transfers, Start::Closed, &sequencer);
    });
    let choice_ms = median_ms(runs, || {
        supply_point(scenario, &settings, &coverage, &transfers, None).expect("a point");
    });
    let given_ms = median_ms(runs, || {
        plan_mission(scenario, &given).expect("a plan");
    });
    let place = match supply.at.lon_lat {
        Some([lon, lat]) => format!("{lon:.6}, {lat:.6}"),
        None => format!("{:.1}, {:.1}", supply.at.point_m[0], supply.at.point_m[1]),
    };
    // A cost of `null` in the report: the plan cannot be flown from that point.
    let seconds = |cost: Option<f64>| cost.unwrap_or(f64::INFINITY);
    let saved = |saving: Option<f64>, percent: Option<f64>| match saving.zip(percent) {
        Some((saving, percent)) => format!("{saving:.0} ({percent:.1} %)"),
        None => "out of reach".to_string(),
    };
    // Where no vehicle can stand at the first point: the nearest place one can.
    let (moved, moved_saving) = match &auto.first_point_moved {
        Some(moved) => (
            format!("{:.0}", seconds(moved.scored.cost_s)),
            saved(moved.saving_s, moved.saving_percent),
        ),
        None => ("stands".to_string(), "-".to_string()),
    };
    let old = seconds(auto.first_point.cost_s);
    let old_as_followed = auto
        .first_point_moved
        .as_ref()
        .map_or(old, |moved| seconds(moved.scored.cost_s));
    println!(
        "| {name} | {} | {} | {place} | {cost:.0} | {old:.0} | {} | {moved} | {moved_saving} | {:.0} | {} | {auto_ms:.0} | {given_ms:.0} | {:.0} | {route_ms:.0} | {:.0} |",
        mission.report.sorties,
        mission.report.fields.iter().map(|field| field.swaths).sum::<usize>(),
        saved(auto.saving_s, auto.saving_percent),
        supply.planned_cost_s,
        auto.evaluations,
        auto_ms - given_ms,
        choice_ms - route_ms,
    );
    Row {
        cost,
        old,
        old_as_followed,
        added_ms: auto_ms - given_ms,
    }
}

/// What the totals need of a row.
struct Row {
    cost: f64,
    old: f64,
    old_as_followed: f64,
    added_ms: f64,
}

fn main() {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|text| text.parse().ok())
        .unwrap_or(5);
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
    println!("| farm | sorties | swaths | chosen point | cost s | first-point rule s | saving s (%) | first point moved to stand s | saving s (%) | as planned s | evaluations | plan ms | plan given the point ms | added ms | of which route without a start ms | of which search ms |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut rows = Vec::new();
    for (name, file) in [
        ("Christmas Island (KML)", "christmas_island_fields.kml"),
        ("seed 001 farm", "seed001_farm.geojson"),
    ] {
        let scenario = Scenario::load(parts(data.join(file))).expect("the data file");
        rows.push((false, row(name, &scenario, runs)));
    }
    for seed in 1..=12u64 {
        let farm = agripath::bench::farms::irregular_farm(seed, 200, 5.0);
        let scenario =
            Scenario::with_farm(farm, parts(PathBuf::from("random"))).expect("a random farm");
        rows.push((true, row(&format!("irregular {seed}"), &scenario, runs)));
    }
    let irregular: Vec<&Row> = rows
        .iter()
        .filter(|(random, _)| *random)
        .map(|(_, row)| row)
        .collect();
    let total = |of: fn(&Row) -> f64| irregular.iter().map(|row| of(row)).sum::<f64>();
    let (cost, old, followed) = (
        total(|row| row.cost),
        total(|row| row.old),
        total(|row| row.old_as_followed),
    );
    let mut added: Vec<f64> = irregular.iter().map(|row| row.added_ms).collect();
    added.sort_by(f64::total_cmp);
    let wins = |of: fn(&Row) -> f64| {
        rows.iter()
            .filter(|(_, row)| row.cost <= of(row) + 0.5)
            .count()
    };
    println!(
        "\nauto no dearer than the first point on {} of {} farms, than the first point moved to where a vehicle can stand on {} of {}",
        wins(|row| row.old),
        rows.len(),
        wins(|row| row.old_as_followed),
        rows.len()
    );
    println!(
        "irregular farms: auto {cost:.0} s against {old:.0} s by the first-point rule in all ({:.1} % saved), {followed:.0} s with it moved to stand ({:.1} % saved); added time median {:.0} ms, most {:.0} ms",
        100.0 * (old - cost) / old,
        100.0 * (followed - cost) / followed,
        added[added.len() / 2],
        added[added.len() - 1]
    );
}
