//! Quick look: one planner on one scenario, statistics of a few runs.
//! `cargo run --release -p agripath --example track_trial -- SCENARIO PLANNER RUNS [ENCODING]`
//! SCENARIO: I, II, III, spso, seed002. With TRACK_PRINT set, the best run's waypoints are printed.
use agripath::track::{plan, statistics, Encoding, Planner, TrackScenario, TrackSettings};

fn main() {
    let arguments: Vec<String> = std::env::args().collect();
    let scenario = match arguments[1].as_str() {
        "spso" => TrackScenario::spso().unwrap(),
        "seed002" => TrackScenario::seed002().unwrap(),
        task => TrackScenario::seed000(task).unwrap(),
    };
    let planner = Planner::parse(&arguments[2]).unwrap();
    let runs: u64 = arguments[3].parse().unwrap();
    let encoding = arguments.get(4).and_then(|e| Encoding::parse(e));
    let settings = TrackSettings {
        planner,
        encoding,
        runs,
        seed: 1,
        evaluations: None,
    };
    let results = plan(&scenario, &settings, &|| {}).unwrap();
    let s = statistics(&results);
    println!(
        "{} {}: best {:.1} worst {:.1} mean {:.1} std {:.1} safe {}/{} {:.2} s/run",
        scenario.name,
        planner.label(),
        s.best,
        s.worst,
        s.mean,
        s.standard_deviation,
        s.safe_runs,
        s.runs,
        s.mean_seconds
    );
    let best = results
        .iter()
        .min_by(|a, b| a.final_cost().total_cmp(&b.final_cost()))
        .unwrap();
    println!(
        "  terms {:?} violations {:?}",
        best.cost.terms, best.verdict.violations
    );
    if std::env::var_os("TRACK_PRINT").is_some() {
        for p in &best.points {
            println!("  {:.1} {:.1} {:.1}", p[0], p[1], p[2]);
        }
    }
}
