//! Speed of the sortie planners: the exact split of a 10,000-point route (goal ≤ 50 ms), and
//! the seed 003 strip end to end.
//!
//! `cargo run --release -p agripath --example bench_sorties`

use std::time::Instant;

use agripath::repro::seed003_table4::{strip_route, StripSlope};
use agripath::sortie::route::{RoutePoint, Segment, Speeds, WorkRoute};
use agripath::sortie::{exact, plan_sorties, SortieModel, SortiePlanner};

/// A boustrophedon of 50 columns × 200 points, 5 m apart (1 km columns), gently rolling.
fn long_route() -> WorkRoute {
    let mut points = Vec::new();
    let mut segments = Vec::new();
    for column in 0..50 {
        for k in 0..200 {
            let along = 5.0 * k as f64;
            let y = if column % 2 == 0 {
                along
            } else {
                995.0 - along
            };
            if !points.is_empty() {
                segments.push(if k == 0 {
                    Segment::Turn
                } else {
                    Segment::Spray
                });
            }
            let x = 2.5 + 5.0 * column as f64;
            points.push(RoutePoint {
                x,
                y,
                ground_m: 2.0 * (x / 80.0).sin() + 1.5 * (y / 130.0).cos(),
            });
        }
    }
    let speeds = Speeds {
        spray_mps: 3.0,
        turn_mps: 3.0,
        transit_mps: 6.0,
        climb_mps: 3.0,
        descent_mps: 3.0,
        transfer_climb_s: 0.0,
    };
    WorkRoute::new(points, segments, None, speeds)
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() {
    let route = long_route();
    let (_, strip_model) = strip_route(&StripSlope).expect("the embedded strip");
    let model = SortieModel {
        supply: RoutePoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        },
        ..strip_model
    };
    let mut times = Vec::new();
    let mut returns = 0;
    for _ in 0..21 {
        let started = Instant::now();
        returns = exact::returns(&route, &model)
            .expect("a split exists")
            .len();
        times.push(started.elapsed().as_secs_f64() * 1e3);
    }
    println!(
        "exact split of a {}-point route ({:.0} m sprayed, {} returns): median {:.1} ms over 21 runs (goal ≤ 50 ms)",
        route.len(),
        route.total_spray_m(),
        returns,
        median(times)
    );
    for planner in SortiePlanner::ALL {
        let started = Instant::now();
        let plan = plan_sorties(&route, &model, planner, 1).expect("a split exists");
        println!(
            "  {:<9} {:>7.1} ms  {} returns, {:.1} min returning",
            planner.key(),
            started.elapsed().as_secs_f64() * 1e3,
            plan.returns(),
            plan.return_time_s / 60.0
        );
    }
    let started = Instant::now();
    let (grid_route, model) = strip_route(&StripSlope).expect("the embedded strip");
    let grid_ms = started.elapsed().as_secs_f64() * 1e3;
    for planner in SortiePlanner::ALL {
        let started = Instant::now();
        plan_sorties(&grid_route.route, &model, planner, 1).expect("a split exists");
        println!(
            "strip ({} cells, grid and motion rule {:.1} ms): {:<9} {:.1} ms",
            grid_route.cells.len(),
            grid_ms,
            planner.key(),
            started.elapsed().as_secs_f64() * 1e3
        );
    }
}
