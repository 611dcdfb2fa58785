//! Ordering benchmark (issue 4): time of each sequencer on seed 001's instance (130 swaths,
//! Table 7's layout) and of `best` on random farms up to 5,000 swaths, one core. With
//! `--export DIR` it also writes each instance (pass ends, start, full cost matrix when
//! small enough) and our tour cost as JSON, for `benches/ordering_vs_lkh.py`. Run:
//!
//! ```sh
//! cargo run --release -p agripath --example bench_sequence [-- --export DIR]
//! ```

use std::time::Instant;

use agripath::coverage::drape::GroundPoint;
use agripath::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
use agripath::model::{CoordinateSystem, Farm, Field, Vehicle};
use agripath::sequence::ant_colony::AntColonySettings;
use agripath::sequence::local_search::LocalSearchSettings;
use agripath::sequence::{passes_of, route, Sequencer, TransferModel};
use agripath::terrain::Flat;
use geo::{Coord, LineString, Polygon};
use swarm::random::{run_stream, uniform};

/// A farm of `fields` random rotated rectangles scattered over a square, sized for about
/// `swaths` swaths of 5 m in all.
fn random_farm(fields: usize, swaths: usize, seed: u64) -> Farm {
    let mut stream = run_stream(seed, 0);
    let per_field = (swaths as f64 / fields as f64).max(1.0);
    let side = (fields as f64).sqrt().ceil() as usize;
    // Far enough apart that no two fields overlap, whatever their rotation: the widest field
    // is 1.2 × per_field × 5 m wide and 2.5 times as long.
    let spacing = per_field * 5.0 * 1.2 * (1.0f64 + 2.5 * 2.5).sqrt() + 60.0;
    let polygons = (0..fields)
        .map(|index| {
            let width = per_field * 5.0 * (0.8 + 0.4 * uniform(&mut stream));
            let length = width * (1.5 + uniform(&mut stream));
            let angle = std::f64::consts::PI * uniform(&mut stream);
            let centre = (
                (index % side) as f64 * spacing + 30.0 * uniform(&mut stream),
                (index / side) as f64 * spacing + 30.0 * uniform(&mut stream),
            );
            let corner = |u: f64, v: f64| Coord {
                x: centre.0 + u * angle.cos() - v * angle.sin(),
                y: centre.1 + u * angle.sin() + v * angle.cos(),
            };
            let (h, w) = (length / 2.0, width / 2.0);
            let ring = vec![
                corner(-h, -w),
                corner(h, -w),
                corner(h, w),
                corner(-h, w),
                corner(-h, -w),
            ];
            Field::new(
                format!("F{index}"),
                Polygon::new(LineString::new(ring), vec![]),
            )
        })
        .collect();
    Farm {
        source: "random".into(),
        coordinate_system: CoordinateSystem::Local,
        fields: polygons,
        obstacles: vec![],
        markers: vec![],
        access: vec![],
        embedded_terrain: None,
        stated_swath_width_m: None,
        notes: Vec::new(),
    }
}

fn layout(farm: &Farm) -> CoveragePlan {
    let settings = CoverageSettings {
        headland_passes: 0,
        ..CoverageSettings::default()
    };
    plan_coverage(farm, &Flat::new(0.0), &Vehicle::default(), &settings).unwrap()
}

fn median_ms(runs: usize, mut work: impl FnMut() -> f64) -> (f64, f64) {
    let mut cost = 0.0;
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let started = Instant::now();
            cost = work();
            started.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (times[runs / 2], cost)
}

fn export(
    folder: &str,
    name: &str,
    plan: &CoveragePlan,
    model: &TransferModel,
    start: Option<GroundPoint>,
    best: f64,
) {
    let passes = passes_of(plan);
    let ends: Vec<[GroundPoint; 2]> = passes
        .iter()
        .map(|(_, points)| [points[0], points[points.len() - 1]])
        .collect();
    let nodes: Vec<GroundPoint> = ends.iter().flatten().copied().collect();
    let matrix: Vec<Vec<f64>> = nodes
        .iter()
        .map(|from| {
            nodes
                .iter()
                .map(|to| {
                    if from == to {
                        0.0
                    } else {
                        // Centimetres are all LKH sees; fewer digits keep the file small.
                        (model.cost(*from, *to) * 100.0).round() / 100.0
                    }
                })
                .collect()
        })
        .collect();
    let from_start: Option<Vec<f64>> =
        start.map(|start| nodes.iter().map(|to| model.cost(start, *to)).collect());
    let value = serde_json::json!({
        "name": name,
        "passes": passes.len(),
        "start_costs": from_start,
        "matrix": matrix,
        "best_tour_cost_m": best,
    });
    std::fs::create_dir_all(folder).unwrap();
    std::fs::write(format!("{folder}/{name}.json"), value.to_string()).unwrap();
}

fn main() {
    let export_to = std::env::args().skip_while(|arg| arg != "--export").nth(1);
    let scenario = agripath::demo::scenario().unwrap();
    let plan = agripath::repro::seed001_table8::instance(&scenario).unwrap();
    let model = TransferModel::new(&scenario.farm, 18.0);
    let start = Some(GroundPoint {
        x: 0.0,
        y: 0.0,
        ground_m: 0.0,
    });
    let swaths: usize = plan.fields.iter().map(|f| f.swaths.len()).sum();
    println!("seed 001 farm, {swaths} swaths from C1 (median of 5 runs, one core):");
    for (label, sequencer) in [
        ("greedy", Sequencer::Greedy),
        (
            "aco (200 × 50)",
            Sequencer::AntColony(AntColonySettings::default()),
        ),
        ("best", Sequencer::Best(LocalSearchSettings::default())),
    ] {
        let (ms, cost) = median_ms(5, || route(&plan, &model, start, &sequencer).tour_cost_m);
        println!("  {label:<16} {ms:>9.1} ms   tour {cost:.1} m");
        if label == "best" {
            if let Some(folder) = &export_to {
                export(folder, "seed001_c1", &plan, &model, start, cost);
            }
        }
    }
    println!("random farms, best (median of 3 runs):");
    for (fields, target) in [
        (5, 50),
        (10, 200),
        (20, 500),
        (40, 1000),
        (50, 2000),
        (100, 5000),
    ] {
        let farm = random_farm(fields, target, fields as u64);
        let plan = layout(&farm);
        let count: usize = plan.fields.iter().map(|f| f.swaths.len()).sum();
        let model = TransferModel::new(&farm, 18.0);
        let best = Sequencer::Best(LocalSearchSettings::default());
        let (ms, cost) = median_ms(3, || route(&plan, &model, None, &best).tour_cost_m);
        println!("  {fields:>3} fields, {count:>5} swaths: {ms:>9.1} ms   closed tour {cost:.1} m");
        if let (Some(folder), true) = (&export_to, count <= 2100) {
            export(
                folder,
                &format!("random_{count}"),
                &plan,
                &model,
                None,
                cost,
            );
        }
    }
}
