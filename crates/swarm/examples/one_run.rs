//! One run of every algorithm on one Table 1 function at the paper's settings.
//!
//! `cargo run --release -p swarm --example one_run -- f1 [seed]`

use swarm::algorithms::Algorithm;
use swarm::functions::{self, FunctionProblem};
use swarm::{Runner, Termination};

fn main() {
    let key = std::env::args().nth(1).unwrap_or_else(|| "f1".into());
    let seed = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let function = functions::by_key(&key).expect("a Table 1 key, f1 … f9");
    let problem = FunctionProblem::new(function, 50).expect("dimension 50");
    let runner = Runner::new(
        Termination::iterations(300).and_evaluations(500 * 301),
        seed,
    )
    .unwrap();
    let only = std::env::args().nth(3);
    for algorithm in Algorithm::ALL.iter().copied() {
        if only.as_deref().is_some_and(|o| o != algorithm.key()) {
            continue;
        }
        let outcome = runner.run(&mut algorithm.build(500), &problem, 0);
        println!(
            "{:<9} {:>14.6e}  evaluations {:>7}  {:>6.3} s",
            algorithm.label(),
            outcome.best_cost,
            outcome.evaluations,
            outcome.elapsed.as_secs_f64()
        );
        if std::env::var("HISTORY").is_ok() {
            for record in outcome.history.iter().step_by(25) {
                println!("   {:>4} {:.6e}", record.iteration, record.best_cost);
            }
        }
    }
}
