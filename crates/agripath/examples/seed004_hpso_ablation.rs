//! The ablation of seed 004's HPSO over the choices its text leaves open (issue 20; decision
//! 0010): initial population, mutation rate, crossover placement, iterations. Each reading runs
//! on the six fields with each seed; the table gives the best and median turns per field.
//!
//! cargo run --release -p agripath --example seed004_hpso_ablation -- [SEEDS, e.g. 1,2,3]

fn main() {
    let seeds: Vec<u64> = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "1,2,3".into())
        .split(',')
        .filter_map(|text| text.trim().parse().ok())
        .collect();
    if seeds.is_empty() {
        eprintln!("seeds: a comma-separated list of integers, e.g. 1,2,3");
        std::process::exit(2);
    }
    let readings = agripath::repro::seed004::ablation_readings();
    let started = std::time::Instant::now();
    let tick = |reading: &str| eprintln!("[{:6.1} s] {reading}", started.elapsed().as_secs_f64());
    match agripath::repro::seed004::ablation(&readings, &seeds, tick) {
        Ok((rows, paper)) => {
            print!(
                "{}",
                agripath::repro::seed004::ablation_markdown(&rows, &paper, &seeds)
            );
            println!("\n{:.1} s in all", started.elapsed().as_secs_f64());
        }
        Err(error) => {
            eprintln!("{error}");
            std::process::exit(2);
        }
    }
}
