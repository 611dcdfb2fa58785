//! Greedy ordering, seed 001's baseline (§4.2.1, refs. 23-25): from the start, always fly to
//! the nearest unvisited pass end (by eq. 8's cost), enter there and leave by the other end.
//! With no start point (a closed tour or an open path), every pass end is tried as the first
//! entry and the cheapest tour by the problem's objective kept, as the seed does to find its
//! A71 and A73. With a start point that the flight comes back to, the leg home is counted in
//! the objective but not in the choice of the next pass (the seed's rule is unchanged).

use super::tour::{OrderingProblem, Start, Step};

/// Greedy from a given first step (`None`: from the fixed start point).
fn greedy_from(problem: &OrderingProblem, first: Option<Step>) -> Vec<Step> {
    let passes = problem.passes();
    let mut visited = vec![false; passes];
    let mut tour = Vec::with_capacity(passes);
    if let Some(step) = first {
        visited[step.pass] = true;
        tour.push(step);
    }
    while tour.len() < passes {
        let mut best: Option<(f64, Step)> = None;
        for pass in (0..passes).filter(|&pass| !visited[pass]) {
            for reversed in [false, true] {
                let step = Step { pass, reversed };
                let cost = match tour.last() {
                    Some(previous) => problem.cost(previous.exit(), step.entry()),
                    None => problem.cost_from_start(step.entry()),
                };
                // Strictly lower wins: ties keep the lower pass index and forward direction.
                if best.is_none_or(|(best_cost, _)| cost < best_cost) {
                    best = Some((cost, step));
                }
            }
        }
        let (_, step) = best.expect("an unvisited pass remains");
        visited[step.pass] = true;
        tour.push(step);
    }
    tour
}

/// Seed 001's greedy sequencer.
pub fn greedy(problem: &OrderingProblem) -> Vec<Step> {
    greedy_with_starts(problem, usize::MAX)
}

/// Greedy; with no start point, from at most `first_entries` pass ends spread over the
/// passes (all of them for the seed's baseline).
pub fn greedy_with_starts(problem: &OrderingProblem, first_entries: usize) -> Vec<Step> {
    match problem.start {
        Start::Fixed(_) | Start::From(_) => greedy_from(problem, None),
        Start::Closed | Start::Open => {
            let mut best: Option<(f64, Vec<Step>)> = None;
            let ends = 2 * problem.passes();
            let stride = ends.div_ceil(first_entries.min(ends).max(1));
            for end in (0..ends).step_by(stride) {
                let (pass, reversed) = (end / 2, end % 2 == 1);
                {
                    let tour = greedy_from(problem, Some(Step { pass, reversed }));
                    let cost = problem.tour_cost(&tour);
                    if best.as_ref().is_none_or(|(best_cost, _)| cost < *best_cost) {
                        best = Some((cost, tour));
                    }
                }
            }
            best.map(|(_, tour)| tour).unwrap_or_default()
        }
    }
}
