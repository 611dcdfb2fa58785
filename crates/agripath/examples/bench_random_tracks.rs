//! Safety of the track planners on 20 random scenarios nobody drew (issue 16): seed 000's
//! formula with other hills, 6-14 threats across the corridor, start and goal on the ground,
//! band 30-150 m. For each scenario: our lattice planner (1 run at seed 000's budget of
//! 500 × 301 evaluations, and 1 run at a fifth of it) and IBA-FCS (1 run, seed 000's budget),
//! each track's verdict (1 m sampling of the formula, 2 m minimum clearance, 1 m vehicle
//! radius) and time.
//!
//! `cargo run --release -p agripath --example bench_random_tracks [SCENARIOS]`
use std::time::Instant;

use agripath::track::{plan, random_scenario, Planner, TrackScenario, TrackSettings};
use swarm::Algorithm;

fn main() {
    let count: u64 = std::env::args()
        .nth(1)
        .map_or(20, |text| text.parse().expect("a number of scenarios"));
    let directory =
        std::env::temp_dir().join(format!("agripath-bench-random-{}", std::process::id()));
    std::fs::create_dir_all(&directory).expect("a scratch folder");
    println!("| scenario | threats | planner | safe | lowest clearance m | threat margin m | outside band m | cost | s |");
    println!("|---:|---:|---|---|---:|---:|---:|---:|---:|");
    let mut safe = [0usize; 3];
    let mut slowest = [0.0f64; 3];
    for seed in 0..count {
        let path = directory.join(format!("random_{seed}.json"));
        std::fs::write(&path, random_scenario::json(seed).to_string()).expect("writable");
        let scenario =
            TrackScenario::read(&path, Some("R")).expect("the generator writes valid scenarios");
        let budget = scenario.evaluation_budget();
        let trials = [
            (Planner::Lattice, budget),
            (Planner::Lattice, budget / 5),
            (Planner::Swarm(Algorithm::IBA_FCS), budget),
        ];
        for (index, (planner, evaluations)) in trials.into_iter().enumerate() {
            let settings = TrackSettings {
                planner,
                encoding: None,
                runs: 1,
                seed,
                evaluations: Some(evaluations),
            };
            let started = Instant::now();
            let runs = plan(&scenario, &settings, &|| {}).expect("plans");
            let seconds = started.elapsed().as_secs_f64();
            let run = &runs[0];
            let verdict = &run.verdict;
            safe[index] += usize::from(run.is_safe());
            slowest[index] = slowest[index].max(seconds);
            println!(
                "| {seed} | {} | {} ({evaluations}) | {} | {:.1} | {:.1} | {:.0} | {:.1} | {:.2} |",
                scenario.threats.len(),
                planner.label(),
                if run.is_safe() { "yes" } else { "**no**" },
                verdict.lowest_clearance_m,
                verdict.threat_margin_m.unwrap_or(f64::NAN),
                verdict.outside_band_m,
                run.final_cost(),
                seconds
            );
            if !run.is_safe() {
                eprintln!(
                    "scenario {seed}, {}: {}",
                    planner.label(),
                    verdict.violations.join("; ")
                );
            }
        }
    }
    println!(
        "\nsafe: lattice {}/{count} (slowest {:.2} s), lattice at a fifth {}/{count} (slowest {:.2} s), IBA-FCS {}/{count} (slowest {:.2} s)",
        safe[0], slowest[0], safe[1], slowest[1], safe[2], slowest[2]
    );
    let _ = std::fs::remove_dir_all(&directory);
}
