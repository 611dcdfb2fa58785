//! Speed of seed 004's grid coverage: per field, our constructive method (goal ≤ 10 ms), the
//! baseline, and one HPSO run at its documented budget (goal ≤ 1 s).
//!
//! `cargo run --release -p agripath --example bench_grid_cover`

use std::path::Path;
use std::time::Instant;

use agripath::grid_cover::hybrid_pso::{self, HpsoSettings};
use agripath::grid_cover::{boustrophedon, fewest_turns, PointGrid};
use agripath::input::{geojson, CoordinateChoice};
use agripath::repro::seed004::FIELDS;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    for (name, text) in FIELDS {
        let farm = geojson::parse(Path::new(name), text, CoordinateChoice::FromFile)
            .expect("embedded field");
        let started = Instant::now();
        let grid = PointGrid::new(&farm, 0, 5.0).expect("a grid");
        let grid_ms = started.elapsed().as_secs_f64() * 1e3;
        let mut ours = Vec::new();
        let mut turns = 0;
        for _ in 0..7 {
            let started = Instant::now();
            let route = fewest_turns::plan(&grid);
            ours.push(started.elapsed().as_secs_f64() * 1e3);
            turns = route.measure(&grid).turns;
        }
        let started = Instant::now();
        let baseline = boustrophedon::plan(&grid).measure(&grid).turns;
        let baseline_ms = started.elapsed().as_secs_f64() * 1e3;
        let started = Instant::now();
        let (route, _) = hybrid_pso::plan(&grid, &HpsoSettings::default());
        let hpso_ms = started.elapsed().as_secs_f64() * 1e3;
        println!(
            "{name:<9} grid {grid_ms:5.1} ms | ours {turns} turns, median {:6.1} ms over 7 | baseline {baseline} turns {baseline_ms:5.1} ms | HPSO {} turns {hpso_ms:6.0} ms",
            median(ours),
            route.measure(&grid).turns
        );
    }
}
