//! Quality against budget for the joint optimiser of order and returns (issue 19's "curve of
//! quality against time budget"). For the seed 001 farm and random irregular farms (the farms
//! and supply points of `bench_joint`), builds the joint problem as the pipeline does, then
//! runs the joint search at several budgets (evaluations through the split per pass) from
//! several sets of start tours (`sortie::joint::starts`), and writes each run's non-spray
//! seconds and wall time to `DIR/joint_budget_curve.csv`, with a chart of the mean cost
//! above each farm's best (over all runs, per cent) against the mean wall time each budget
//! took, `DIR/joint_budget_curve.svg`. Run:
//!
//! ```sh
//! cargo run --release -p agripath --example joint_budget_curve -- \
//!     [--farms 3] [--per-pass 2,4,8,12,16,24,32,48] [--starts F,FB,FBRS,FC,FBCD] \
//!     [--race-share 0.5] [--out DIR]
//! ```
//!
//! A set of starts is a word of letters, raced in that order: F the sequencer's order from the
//! supply point (`Start::Fixed`), B it flown backwards, R its cheapest rotation, S that
//! backwards, C the sequencer's closed tour (`Start::Closed`, a second sequencer run, timed
//! and printed) cut at the supply point, D that backwards, O the sequencer's open path
//! (`Start::Open`, another sequencer run, timed and printed), Q that backwards, V a peer's
//! sorties (PyVRP's, from the `--results` file of `benches/joint_vs_pyvrp.py` given as
//! `--peer FILE`) flown one after the other; a P anywhere in the word turns the petal moves on
//! (`sortie::joint::petals`).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use agripath::bench::farms::{irregular_farm, supply_south_of, ROUTING_SWATH_TARGETS};
use agripath::coverage::drape::GroundPoint;
use agripath::coverage::{plan_coverage, CoverageSettings};
use agripath::pipeline::sortie_model;
use agripath::plot::line_chart::{self, Chart, Series};
use agripath::scenario::{Scenario, ScenarioParts};
use agripath::sequence::tour::Start;
use agripath::sequence::tour::Step;
use agripath::sequence::{ordering_problem, Sequencer, TransferModel};
use agripath::sortie::joint::starts::{backwards, cheapest_rotation, cut_at_supply, rotated};
use agripath::sortie::joint::{search_from, JointProblem, JointSettings};
use agripath::sortie::route::Speeds;

struct Options {
    farms: usize,
    per_pass: Vec<u64>,
    starts: Vec<String>,
    race_share: f64,
    out: PathBuf,
    peer: Option<serde_json::Value>,
}

fn usage() -> ! {
    eprintln!(
        "usage: joint_budget_curve [--farms N] [--per-pass LIST] [--starts LIST] \
         [--race-share X] [--out DIR] [--peer FILE]"
    );
    std::process::exit(2)
}

fn list<T: std::str::FromStr>(value: &str) -> Vec<T> {
    value
        .split(',')
        .map(|item| item.trim().parse().unwrap_or_else(|_| usage()))
        .collect()
}

fn options() -> Options {
    let mut options = Options {
        farms: 3,
        per_pass: vec![2, 4, 8, 12, 16, 24, 32, 48],
        starts: ["F", "FB", "FBRS", "FC", "FBCD"].map(String::from).to_vec(),
        race_share: JointSettings::default().race_share,
        out: PathBuf::from("."),
        peer: None,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().unwrap_or_else(|| usage());
        match flag.as_str() {
            "--farms" => options.farms = value.parse().unwrap_or_else(|_| usage()),
            "--per-pass" => options.per_pass = list(&value),
            "--starts" => options.starts = value.split(',').map(String::from).collect(),
            "--race-share" => options.race_share = value.parse().unwrap_or_else(|_| usage()),
            "--out" => options.out = PathBuf::from(value),
            "--peer" => {
                let text = std::fs::read_to_string(&value).unwrap_or_else(|_| usage());
                options.peer = Some(serde_json::from_str(&text).unwrap_or_else(|_| usage()));
            }
            _ => usage(),
        }
    }
    options
}

/// The seed 001 farm (supply at its launch point) and the first `count` random farms of
/// `bench_joint` (supply 30 m south of the middle of the farm's south side).
fn farms(count: usize) -> Vec<(String, Scenario, [f64; 2])> {
    let mut farms = vec![(
        "seed001".to_string(),
        agripath::demo::scenario().expect("the embedded demo farm"),
        [0.0, 0.0],
    )];
    for seed in 1..=count as u64 {
        let target = ROUTING_SWATH_TARGETS[(seed as usize - 1) % ROUTING_SWATH_TARGETS.len()];
        let farm = irregular_farm(seed, target, 5.0);
        let supply = supply_south_of(&farm);
        let scenario =
            Scenario::with_farm(farm, ScenarioParts::default()).expect("a random farm is valid");
        farms.push((format!("random_s{seed}_{target}"), scenario, supply));
    }
    farms
}

/// The peer's sorties for farm `name`, flown one after the other, as a giant tour.
fn peer_tour(peer: Option<&serde_json::Value>, name: &str) -> Vec<Step> {
    let farms = peer.and_then(|peer| peer["farms"].as_array());
    let row = farms
        .and_then(|farms| {
            // `bench_joint` names a random farm by the swaths it got, this example by the
            // swaths it asked for: match on the seed.
            let seed = |name: &str| {
                name.rsplit_once('_')
                    .map_or(name, |(seed, _)| seed)
                    .to_string()
            };
            farms
                .iter()
                .find(|row| row["name"].as_str().map(seed) == Some(seed(name)))
        })
        .unwrap_or_else(|| {
            eprintln!("start V needs --peer FILE with the routes of {name}");
            std::process::exit(2)
        });
    let routes = row["pyvrp"]["routes"].as_array().unwrap_or_else(|| {
        eprintln!("the peer file has no routes for {name} (re-run joint_vs_pyvrp.py)");
        std::process::exit(2)
    });
    routes
        .iter()
        .flat_map(|route| route.as_array().into_iter().flatten())
        .map(|step| Step {
            pass: step[0].as_u64().expect("a pass number") as usize,
            reversed: step[1].as_bool().expect("a direction"),
        })
        .collect()
}

/// One run of the search: farm, starts, evaluations per pass, cost, seconds.
struct Row {
    farm: usize,
    starts: String,
    per_pass: u64,
    cost_s: f64,
    runtime_s: f64,
}

fn main() {
    let options = options();
    std::fs::create_dir_all(&options.out).expect("the output folder can be made");
    let mut rows: Vec<Row> = Vec::new();
    let mut names = Vec::new();
    println!(
        "{:<16} {:>6} {:>6} {:>8} {:>11} {:>9}",
        "farm", "passes", "starts", "per pass", "non-spray", "runtime"
    );
    for (index, (name, scenario, supply)) in farms(options.farms).into_iter().enumerate() {
        let vehicle = &scenario.vehicle;
        let coverage = plan_coverage(
            &scenario.farm,
            scenario.terrain.as_ref(),
            vehicle,
            &CoverageSettings::default(),
        )
        .expect("a coverage plan");
        let transfers = TransferModel::new(&scenario.farm, vehicle.safe_height_m);
        let supply = GroundPoint {
            x: supply[0],
            y: supply[1],
            ground_m: scenario
                .terrain
                .height_m(supply[0], supply[1])
                .expect("the supply point is on the terrain"),
        };
        let (problem, groups) = ordering_problem(&coverage, &transfers, Start::Fixed(supply));
        let started = Instant::now();
        let order = Sequencer::default().sequencer().order(&problem, &groups);
        let sequenced_s = started.elapsed().as_secs_f64();
        let needs_closed = options.starts.iter().any(|word| word.contains(['C', 'D']));
        let closed = needs_closed.then(|| {
            let started = Instant::now();
            let (free, free_groups) = ordering_problem(&coverage, &transfers, Start::Closed);
            let tour = Sequencer::default().sequencer().order(&free, &free_groups);
            println!(
                "{name}: the closed tour (its own ordering problem and sequencer run) in {:.3} s",
                started.elapsed().as_secs_f64()
            );
            cut_at_supply(&problem, &tour)
        });
        let needs_open = options.starts.iter().any(|word| word.contains(['O', 'Q']));
        let open = needs_open.then(|| {
            let started = Instant::now();
            let (free, free_groups) = ordering_problem(&coverage, &transfers, Start::Open);
            let path = Sequencer::default().sequencer().order(&free, &free_groups);
            println!(
                "{name}: the open path (its own ordering problem and sequencer run) in {:.3} s",
                started.elapsed().as_secs_f64()
            );
            path
        });
        let start = |letter: char| -> Vec<Step> {
            let turned = || {
                cheapest_rotation(&problem, &order)
                    .map_or(order.clone(), |(k, _)| rotated(&order, k))
            };
            match letter {
                'F' => order.clone(),
                'B' => backwards(&order),
                'R' => turned(),
                'S' => backwards(&turned()),
                'C' => closed.clone().expect("the closed tour"),
                'D' => backwards(closed.as_ref().expect("the closed tour")),
                'O' => open.clone().expect("the open path"),
                'Q' => backwards(open.as_ref().expect("the open path")),
                'V' => {
                    let tour = peer_tour(options.peer.as_ref(), &name);
                    if let Err(fault) = agripath::sequence::tour::check_order(&tour, order.len()) {
                        eprintln!(
                            "{name}: the peer's sorties are not a tour of these passes: {fault}"
                        );
                        std::process::exit(2)
                    }
                    tour
                }
                _ => usage(),
            }
        };
        let model = sortie_model(vehicle, supply.into());
        let joint = JointProblem::of_coverage(&problem, &coverage, &model, Speeds::of(vehicle));
        // What a split from the first position costs: the order and the order backwards
        // (which differ at the first position, so nothing is resumed) in turn, the rate the
        // search would score at without resuming.
        let timed = Instant::now();
        let full_splits = 200;
        let turned = backwards(&order);
        for split in 0..full_splits {
            let tour = if split % 2 == 0 { &order } else { &turned };
            std::hint::black_box(swarm::Problem::evaluate(&joint, std::hint::black_box(tour)));
        }
        let full_rate = full_splits as f64 / timed.elapsed().as_secs_f64();
        println!(
            "{name}: {} passes, {} route points, the sequencer's order in {sequenced_s:.3} s, \
             {full_rate:.0} full splits/s",
            order.len(),
            joint.points()
        );
        for word in &options.starts {
            let tours: Vec<Vec<Step>> = word.chars().filter(|&c| c != 'P').map(start).collect();
            let costs: Vec<String> = word
                .chars()
                .filter(|&c| c != 'P')
                .zip(&tours)
                .map(|(letter, tour)| format!("{letter} {:.1} s", joint.full_split_cost(tour)))
                .collect();
            println!("{name}: the starts' splits: {}", costs.join(", "));
            for &per_pass in &options.per_pass {
                let settings = JointSettings {
                    evaluations_per_pass: per_pass,
                    race_share: options.race_share,
                    petals: word.contains('P'),
                    ..JointSettings::default()
                };
                let labelled_before = joint.points_labelled();
                let started = Instant::now();
                let outcome = search_from(
                    &joint,
                    tours.clone(),
                    &settings,
                    settings.budget(&joint, joint.split_steps(&tours[0])),
                );
                let runtime_s = started.elapsed().as_secs_f64();
                // Splits per second, and the share of a full split's points each laid out
                // (the split resumes at the first changed position).
                let labelled = (joint.points_labelled() - labelled_before) as f64;
                println!(
                    "{:<16} {:>6} {:>6} {:>8} {:>9.1} s {:>7.3} s {:>6} iterations {:>7.0} splits/s {:>5.3} of the points each",
                    name,
                    order.len(),
                    word,
                    per_pass,
                    outcome.cost,
                    runtime_s,
                    outcome.iterations,
                    outcome.evaluations as f64 / runtime_s,
                    labelled / (outcome.evaluations as f64 * joint.points() as f64)
                );
                rows.push(Row {
                    farm: index,
                    starts: word.clone(),
                    per_pass,
                    cost_s: outcome.cost,
                    runtime_s,
                });
            }
        }
        names.push(name);
    }
    let best: Vec<f64> = (0..names.len())
        .map(|farm| {
            rows.iter()
                .filter(|row| row.farm == farm)
                .map(|row| row.cost_s)
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let mut csv = String::from("farm,starts,evaluations_per_pass,non_spray_s,relative,runtime_s\n");
    for row in &rows {
        writeln!(
            csv,
            "{},{},{},{:.3},{:.5},{:.4}",
            names[row.farm],
            row.starts,
            row.per_pass,
            row.cost_s,
            row.cost_s / best[row.farm],
            row.runtime_s
        )
        .expect("writing to a string");
    }
    let series: Vec<Series> = options
        .starts
        .iter()
        .map(|starts| Series {
            name: format!("starts {starts}"),
            points: options
                .per_pass
                .iter()
                .map(|&per_pass| {
                    let chosen: Vec<&Row> = rows
                        .iter()
                        .filter(|row| &row.starts == starts && row.per_pass == per_pass)
                        .collect();
                    let count = chosen.len() as f64;
                    let mean = chosen
                        .iter()
                        .map(|row| row.cost_s / best[row.farm])
                        .sum::<f64>()
                        / count;
                    let runtime = chosen.iter().map(|row| row.runtime_s).sum::<f64>() / count;
                    // Against the time the search took (the issue's "time budget"); per cent
                    // above the best, whose ticks read better than ratios.
                    (runtime, 100.0 * (mean - 1.0))
                })
                .collect(),
        })
        .collect();
    println!("\nmean cost above the farm's best (mean runtime):");
    for series in &series {
        let cells: Vec<String> = options
            .per_pass
            .iter()
            .zip(&series.points)
            .map(|(per_pass, &(runtime, mean))| {
                format!("{per_pass}: +{mean:.2} % ({runtime:.3} s)")
            })
            .collect();
        println!("  {:<9} {}", series.name, cells.join("  "));
    }
    let title = format!(
        "Joint optimiser: quality against budget ({} farms)",
        names.len()
    );
    let svg = line_chart::render(
        &Chart {
            title: &title,
            x_label: "wall time of the joint search, s (mean over the farms)",
            y_label: "non-spray time above the best found, %",
            log_y: false,
        },
        &series,
    );
    std::fs::write(options.out.join("joint_budget_curve.csv"), csv).expect("the CSV is written");
    std::fs::write(options.out.join("joint_budget_curve.svg"), svg).expect("the SVG is written");
}
