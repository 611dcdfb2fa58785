//! Speed of the track planners, one run at a time on one thread:
//! `cargo run --release -p agripath --example bench_tracks`
//!
//! The goal: one IBA-FCS run (population 500, 300 iterations = 150,500 evaluations,
//! 12 free waypoints) in at most 1 s. Prints the median of 5 runs per planner and task.
use std::time::Instant;

use agripath::track::{plan, Planner, TrackScenario, TrackSettings};
use swarm::Algorithm;

fn main() {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global()
        .unwrap();
    for task in ["I", "II", "III"] {
        let scenario = TrackScenario::seed000(task).unwrap();
        for planner in [
            Planner::Swarm(Algorithm::IbaFcs),
            Planner::Swarm(Algorithm::Bat),
            Planner::Lattice,
        ] {
            let mut seconds: Vec<f64> = (0..5)
                .map(|run| {
                    let settings = TrackSettings {
                        planner,
                        encoding: None,
                        runs: 1,
                        seed: run,
                        evaluations: None,
                    };
                    let started = Instant::now();
                    let runs = plan(&scenario, &settings, &|| {}).unwrap();
                    assert_eq!(runs[0].evaluations, 150_500);
                    started.elapsed().as_secs_f64()
                })
                .collect();
            seconds.sort_by(f64::total_cmp);
            println!("task {task:<3} {:<22} median {:.3} s per run (150,500 evaluations; min {:.3}, max {:.3})", planner.label(), seconds[2], seconds[0], seconds[4]);
        }
    }
}
