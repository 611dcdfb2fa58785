//! Benchmark of issue 3: the whole seed 001 farm (5 fields, 180 headings plus the 0.1°
//! refinement, draped at a = 20 m) on one core. Run:
//!
//! ```sh
//! cargo run --release -p agripath --example bench_coverage
//! ```
//!
//! Prints the median and the best of 30 runs for the seed layout (Table 7's setting) and for
//! the default plan (one edge pass, coverage measured by polygon overlay, route).

use std::time::Instant;

use agripath::coverage::{plan_coverage, CoverageSettings};
use agripath::pipeline::plan_mission;
use agripath::settings::PlanSettings;

fn time<T>(runs: usize, mut work: impl FnMut() -> T) -> (f64, f64) {
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let started = Instant::now();
            std::hint::black_box(work());
            started.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (times[runs / 2], times[0])
}

fn main() {
    let scenario = agripath::demo::scenario().expect("the embedded farm loads");
    let seed_layout = CoverageSettings {
        headland_passes: 0,
        ..CoverageSettings::default()
    };
    let (median, best) = time(30, || {
        plan_coverage(
            &scenario.farm,
            scenario.terrain.as_ref(),
            &scenario.vehicle,
            &seed_layout,
        )
        .unwrap()
    });
    println!("seed 001 farm, seed layout (5 fields × 180 headings + refinement, a = 20 m): median {median:.1} ms, best {best:.1} ms");
    let default = PlanSettings::default();
    let (median, best) = time(30, || plan_mission(&scenario, &default).unwrap());
    println!("seed 001 farm, default plan (edge passes, coverage overlay, best route, report): median {median:.1} ms, best {best:.1} ms");
}
