//! Seed 004's HPSO under larger budgets than its 40 particles × 1,000 iterations (the open
//! choice "iterations" of issue 20): does the turn count approach the paper's 27-46?
//!
//! cargo run --release -p agripath --example seed004_hpso_budget -- PARTICLES ITERATIONS [SEED]
//!
//! Prints the repro seed004 table (HPSO, baseline, ours, the paper) at that budget.

use agripath::grid_cover::hybrid_pso::HpsoSettings;

fn main() {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let number = |index: usize, default: usize| {
        arguments
            .get(index)
            .and_then(|text| text.parse().ok())
            .unwrap_or(default)
    };
    let settings = HpsoSettings {
        particles: number(0, 40),
        iterations: number(1, 1_000),
        seed: number(2, 1) as u64,
        ..Default::default()
    };
    let started = std::time::Instant::now();
    match agripath::repro::printed::seed004(&settings) {
        Ok((_, table, _)) => println!(
            "{} particles × {} iterations, seed {} ({:.1} s)\n{table}",
            settings.particles,
            settings.iterations,
            settings.seed,
            started.elapsed().as_secs_f64()
        ),
        Err(error) => {
            eprintln!("{error}");
            std::process::exit(2);
        }
    }
}
