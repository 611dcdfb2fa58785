//! Ordering benchmark (issues 4 and 19): time of each sequencer on seed 001's instance (130
//! swaths, Table 7's layout) from C1; `best`'s open path and closed tour, with their times,
//! on the seed 001 farm and on 12 irregular farms of 100-250 swaths
//! (`agripath::bench::farms::irregular_farm`); and `best` on random farms up to 5,000
//! swaths, on the machine's cores (`RAYON_NUM_THREADS=1` for one). With `--export DIR` it
//! also writes each open/closed instance (the full cost matrix between pass ends) and our
//! costs as JSON, for `benches/ordering_vs_lkh.py`, which runs this and prints ours / LKH.
//! `--lkh-only` skips the first and last parts; `--open-only` also skips the closed tours
//! (and writes nothing). Run:
//!
//! ```sh
//! cargo run --release -p agripath --example bench_sequence [-- --export DIR] [--lkh-only] [--open-only] [--kicks N] [--seed N] [--restarts N]
//! ```
//!
//! `--kicks N` and `--seed N` run `best` with N kicks or seed N instead of the defaults (to
//! measure quality against time, and its spread over seeds, without a rebuild).

use std::time::Instant;

use agripath::coverage::drape::GroundPoint;
use agripath::coverage::{plan_coverage, CoveragePlan, CoverageSettings};
use agripath::model::{Farm, Field, Vehicle};
use agripath::sequence::ant_colony::AntColonySettings;
use agripath::sequence::local_search::LocalSearchSettings;
use agripath::sequence::tour::Start;
use agripath::sequence::{ordering_problem, passes_of, route, Pass, Sequencer, TransferModel};
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
    Farm::local("random", polygons)
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

/// One instance for LKH: the eq. (8) matrix between pass ends (node 2p is pass p's first end,
/// 2p + 1 its last) and our open-path and closed-tour costs with their times.
struct Instance<'a> {
    name: &'a str,
    plan: &'a CoveragePlan,
    model: &'a TransferModel<'a>,
    open: Measured,
    closed: Measured,
}

/// A tour's cost, its median time in milliseconds, and its ends in flight order.
struct Measured(f64, f64, Vec<usize>);

fn export(folder: &str, instance: &Instance) {
    let passes = passes_of(instance.plan);
    let nodes: Vec<GroundPoint> = passes
        .iter()
        .flat_map(|(_, points)| [points[0], points[points.len() - 1]])
        .collect();
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
                        (instance.model.cost(*from, *to) * 100.0).round() / 100.0
                    }
                })
                .collect()
        })
        .collect();
    // Each pass's field and each end's position, to draw and compare tours by field.
    let fields: Vec<usize> = passes
        .iter()
        .map(|(pass, _)| match pass {
            Pass::Edge { field, .. } | Pass::Swath { field, .. } => *field,
        })
        .collect();
    let points: Vec<[f64; 2]> = nodes
        .iter()
        .map(|node| {
            [
                (node.x * 100.0).round() / 100.0,
                (node.y * 100.0).round() / 100.0,
            ]
        })
        .collect();
    let value = serde_json::json!({
        "name": instance.name,
        "passes": passes.len(),
        "matrix": matrix,
        "fields": fields,
        "points": points,
        "open_m": instance.open.0,
        "open_ms": instance.open.1,
        "open_ends": instance.open.2,
        "closed_m": instance.closed.0,
        "closed_ms": instance.closed.1,
        "closed_ends": instance.closed.2,
    });
    std::fs::create_dir_all(folder).unwrap();
    std::fs::write(
        format!("{folder}/{}.json", instance.name),
        value.to_string(),
    )
    .unwrap();
}

/// `best`'s settings: the default, or `--kicks N` kicks, `--seed N` and `--restarts N`
/// (chained-LK runs on closed tours).
fn best_settings() -> LocalSearchSettings {
    let arguments: Vec<String> = std::env::args().collect();
    let kicks = arguments
        .iter()
        .skip_while(|arg| *arg != "--kicks")
        .nth(1)
        .map(|value| value.parse().expect("--kicks takes a whole number"));
    let seed = arguments
        .iter()
        .skip_while(|arg| *arg != "--seed")
        .nth(1)
        .map(|value| value.parse().expect("--seed takes a whole number"));
    let default = LocalSearchSettings::default();
    let restarts = arguments
        .iter()
        .skip_while(|arg| *arg != "--restarts")
        .nth(1)
        .map(|value| value.parse().expect("--restarts takes a whole number"));
    LocalSearchSettings {
        kicks: kicks.unwrap_or(default.kicks),
        seed: seed.unwrap_or(default.seed),
        restarts: restarts.unwrap_or(default.restarts),
    }
}

/// `best` on `plan` from `start`: the problem built (its cost matrix) and ordered, median of
/// 3 runs.
fn measure(plan: &CoveragePlan, model: &TransferModel, start: Start) -> Measured {
    let best = Sequencer::Best(best_settings());
    let mut tour = Vec::new();
    let (ms, cost) = median_ms(3, || {
        let (problem, groups) = ordering_problem(plan, model, start);
        tour = best.sequencer().order(&problem, &groups);
        problem.tour_cost(&tour)
    });
    let ends = tour.iter().flat_map(|step| [step.entry(), step.exit()]);
    if std::env::var_os("BENCH_MATRIX").is_some() {
        let (matrix_ms, _) = median_ms(3, || {
            let (problem, _) = ordering_problem(plan, model, start);
            problem.cost(0, 1)
        });
        eprintln!("    of which the cost matrix: {matrix_ms:.1} ms");
    }
    Measured(cost, ms, ends.collect())
}

/// `best`'s open path and closed tour on `plan`, printed and exported.
fn open_and_closed(name: &str, plan: &CoveragePlan, model: &TransferModel, folder: Option<&str>) {
    let open = measure(plan, model, Start::Open);
    if std::env::args().any(|arg| arg == "--open-only") {
        println!(
            "  {name:<14} {:>5} passes: open {:>9.1} m {:>7.1} ms",
            passes_of(plan).len(),
            open.0,
            open.1
        );
        return;
    }
    let closed = measure(plan, model, Start::Closed);
    println!(
        "  {name:<14} {:>5} passes: open {:>9.1} m {:>7.1} ms   closed {:>9.1} m {:>7.1} ms",
        passes_of(plan).len(),
        open.0,
        open.1,
        closed.0,
        closed.1
    );
    if let Some(folder) = folder {
        export(
            folder,
            &Instance {
                name,
                plan,
                model,
                open,
                closed,
            },
        );
    }
}

/// Swath targets of the irregular farms against LKH: 100-250, cycling.
const LKH_TARGETS: [usize; 4] = [110, 150, 190, 230];
/// Irregular farms against LKH.
const LKH_FARMS: u64 = 12;

fn main() {
    let arguments: Vec<String> = std::env::args().collect();
    let export_to = arguments
        .iter()
        .skip_while(|arg| *arg != "--export")
        .nth(1)
        .cloned();
    let lkh_only = arguments.iter().any(|arg| arg == "--lkh-only");
    let scenario = agripath::demo::scenario().unwrap();
    let plan = agripath::repro::seed001_table8::instance(&scenario).unwrap();
    let model = TransferModel::new(&scenario.farm, 18.0);
    let start = Start::From(GroundPoint {
        x: 0.0,
        y: 0.0,
        ground_m: 0.0,
    });
    let swaths: usize = plan.fields.iter().map(|f| f.swaths.len()).sum();
    if !lkh_only {
        println!("seed 001 farm, {swaths} swaths from C1 (median of 5 runs):");
        for (label, sequencer) in [
            ("greedy", Sequencer::Greedy),
            (
                "aco (200 × 50)",
                Sequencer::AntColony(AntColonySettings::default()),
            ),
            ("best", Sequencer::Best(best_settings())),
        ] {
            let (ms, cost) = median_ms(5, || route(&plan, &model, start, &sequencer).tour_cost_m);
            println!("  {label:<16} {ms:>9.1} ms   tour {cost:.1} m");
        }
    }
    println!("best, open path and closed tour (median of 3 runs):");
    open_and_closed("seed001_t7", &plan, &model, export_to.as_deref());
    // The seed 001 farm as planned by default (headland passes, the layout's own headings).
    let default_plan = plan_coverage(
        &scenario.farm,
        scenario.terrain.as_ref(),
        &scenario.vehicle,
        &CoverageSettings::default(),
    )
    .unwrap();
    let default_model = TransferModel::new(&scenario.farm, scenario.vehicle.safe_height_m);
    open_and_closed(
        "seed001_farm",
        &default_plan,
        &default_model,
        export_to.as_deref(),
    );
    for seed in 1..=LKH_FARMS {
        let target = LKH_TARGETS[(seed as usize - 1) % LKH_TARGETS.len()];
        let farm = agripath::bench::farms::irregular_farm(seed, target, 5.0);
        let plan = layout(&farm);
        let model = TransferModel::new(&farm, 18.0);
        let name = format!("irregular_{seed:02}");
        open_and_closed(&name, &plan, &model, export_to.as_deref());
    }
    if lkh_only {
        return;
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
        let best = Sequencer::Best(best_settings());
        let (ms, cost) = median_ms(3, || route(&plan, &model, Start::Open, &best).tour_cost_m);
        println!("  {fields:>3} fields, {count:>5} swaths: {ms:>9.1} ms   open path {cost:.1} m");
    }
}
