//! Speed of the track planners, one run at a time on one thread:
//! `cargo run --release -p agripath --example bench_tracks`
//!
//! The goal: one IBA-FCS run (population 500, 300 iterations = 150,500 evaluations,
//! 12 free waypoints) in at most 1 s. Prints the median time of 5 runs per planner and task,
//! with the mean cost; ours also at a fifth of the budget.
use std::time::Instant;

use agripath::track::{plan, Planner, TrackScenario, TrackSettings};
use swarm::Algorithm;

fn main() {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()
        .unwrap();
    let cases = [
        (Planner::Swarm(Algorithm::IBA_FCS), 150_500),
        (Planner::Swarm(Algorithm::BAT), 150_500),
        (Planner::Lattice, 150_500),
        (Planner::Lattice, 30_100),
    ];
    for task in ["I", "II", "III"] {
        let scenario = TrackScenario::seed000(task).unwrap();
        for (planner, evaluations) in cases {
            let mut seconds = Vec::new();
            let mut cost = 0.0;
            let mut used = 0;
            for run in 0..5 {
                let settings = TrackSettings {
                    planner,
                    encoding: None,
                    runs: 1,
                    seed: run,
                    evaluations: Some(evaluations),
                };
                let started = Instant::now();
                let runs = plan(&scenario, &settings, &|| {}).unwrap();
                seconds.push(started.elapsed().as_secs_f64());
                // Ours may declare convergence and hand the rest of the budget back.
                assert!(runs[0].evaluations <= evaluations);
                used += runs[0].evaluations / 5;
                cost += runs[0].final_cost() / 5.0;
            }
            seconds.sort_by(f64::total_cmp);
            println!(
                "task {task:<3} {:<22} {evaluations:>7} evaluations (mean used {used}): median {:.3} s per run (min {:.3}, max {:.3}), mean cost {cost:.1}",
                planner.label(), seconds[2], seconds[0], seconds[4]
            );
        }
    }
}
