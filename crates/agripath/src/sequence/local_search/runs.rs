//! Run search, a step of `best` (issue 19 item 4): the order and the corners of whole runs.
//!
//! A local optimum of the pass-level moves (2-opt with end flips, Or-opt of 1-3 passes) flies
//! each cell of a field (the swaths on one side of a hole, or a whole convex field) as a run:
//! consecutive passes of one field joined by transfers that stay in the field (eq. 8 without
//! its 2h). What is left is the order of the runs and the corner each is entered by, and
//! there the pass-level moves are weak: moving a run of twenty passes is not a move of 1-3
//! passes, and entering it by another corner flips every pass in it. Here the tour is cut
//! into its runs, and the runs are ordered as the field blocks are in
//! [`super::construction`], on four variants each:
//!
//! - 0: as flown; 1: backwards (the passes in reverse order, each flown the other way);
//! - 2: every pass flown the other way, same order; 3: both.
//!
//! Moves, while they gain: a run to any other gap in any variant (Or-opt), a stretch of runs
//! flown backwards (2-opt on runs); then double-bridge kicks on the run order, kept when the
//! tour gets cheaper (the block search of `blocks.rs`, shared with the constructions). Costs are eq. (8)'s between the runs' end passes, plus each variant's
//! own transfers inside the run (variant 2 and 3 may cost more inside: the ends of a
//! boustrophedon's turns swap sides).

use super::super::tour::{End, OrderingProblem, Step};
use super::blocks::{BlockSearch, Blocks, Placed};

/// Kicks of the run-order search; fewer on tours of many runs (a round is O(R²)).
const RUN_KICKS: usize = 150;

/// The runs of a tour, each in its four variants with the cost inside it.
struct Runs(Vec<[(Vec<Step>, f64); 4]>);

impl Runs {
    fn steps(&self, (run, variant): Placed) -> &[Step] {
        &self.0[run][variant].0
    }
}

impl Blocks for Runs {
    fn count(&self) -> usize {
        self.0.len()
    }

    fn entry(&self, placed: Placed) -> End {
        self.steps(placed)[0].entry()
    }

    fn exit(&self, placed: Placed) -> End {
        self.steps(placed)[self.steps(placed).len() - 1].exit()
    }

    fn inside(&self, (run, variant): Placed) -> f64 {
        self.0[run][variant].1
    }

    /// Variant 1 is variant 0 backwards, 3 is 2 backwards.
    fn backwards(&self, (run, variant): Placed) -> Placed {
        (run, variant ^ 1)
    }
}

/// Cuts `tour` into runs: a new run starts where the field changes or the transfer climbs.
fn cut_into_runs(problem: &OrderingProblem, tour: &[Step], group_of: &[usize]) -> Vec<Vec<Step>> {
    let mut runs: Vec<Vec<Step>> = Vec::new();
    for (index, step) in tour.iter().enumerate() {
        let joined = index > 0 && {
            let previous = tour[index - 1];
            group_of[previous.pass] == group_of[step.pass]
                && !problem.climbs(previous.exit(), step.entry())
        };
        match runs.last_mut() {
            Some(run) if joined => run.push(*step),
            _ => runs.push(vec![*step]),
        }
    }
    runs
}

/// The four variants of a run, with the transfers inside each.
fn variants(problem: &OrderingProblem, run: &[Step]) -> [(Vec<Step>, f64); 4] {
    let inside = |steps: &[Step]| -> f64 {
        steps
            .windows(2)
            .map(|pair| problem.cost(pair[0].exit(), pair[1].entry()))
            .sum()
    };
    let backwards =
        |steps: &[Step]| -> Vec<Step> { steps.iter().rev().map(|step| step.flipped()).collect() };
    let flipped: Vec<Step> = run.iter().map(|step| step.flipped()).collect();
    [
        run.to_vec(),
        backwards(run),
        flipped.clone(),
        backwards(&flipped),
    ]
    .map(|steps| {
        let cost = inside(&steps);
        (steps, cost)
    })
}

/// The tour with its runs reordered and re-cornered by the run-order search, never costlier
/// than `tour` (the order as flown is the search's start).
pub(super) fn run_search(
    problem: &OrderingProblem,
    tour: &[Step],
    group_of: &[usize],
    seed: u64,
) -> Vec<Step> {
    let runs = Runs(
        cut_into_runs(problem, tour, group_of)
            .iter()
            .map(|run| variants(problem, run))
            .collect(),
    );
    let count = runs.0.len();
    if count < 3 {
        return tour.to_vec();
    }
    let search = BlockSearch::new(problem, &runs);
    let order: Vec<Placed> = (0..count).map(|run| (run, 0)).collect();
    let flown = search.total(&order);
    let mut stream = swarm::run_stream(seed, 2);
    let kicks = RUN_KICKS.min(400_000 / (count * count));
    let (order, best) = search.iterate(order, true, kicks, &mut stream);
    if best >= flown - 1e-9 {
        return tour.to_vec();
    }
    order
        .iter()
        .flat_map(|&placed| runs.steps(placed).iter().copied())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::drape::GroundPoint;
    use crate::sequence::tour::{is_permutation, Start};
    use crate::sequence::TransferModel;

    /// Three fields of four parallel passes, flown field by field in a poor order and from
    /// poor corners: the run search reorders the runs, and is never worse.
    #[test]
    fn run_search_keeps_the_passes_and_never_costs_more() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let mut ends = Vec::new();
        let mut group_of = Vec::new();
        for (field, offset) in [(0, 0.0), (1, 900.0), (2, 300.0)] {
            for line in 0..4 {
                let x = offset + 5.0 * line as f64;
                group_of.push(field);
                let ground = |y: f64| GroundPoint {
                    x,
                    y,
                    ground_m: 0.0,
                };
                ends.push([ground(2000.0), ground(2100.0)]);
            }
        }
        for start in [Start::Open, Start::Closed] {
            let problem = OrderingProblem::new(ends.clone(), start, &model);
            // Fields 0, 1, 2 in a zigzag each, the first pass of each field flown upwards.
            let tour: Vec<Step> = (0..12)
                .map(|pass| Step {
                    pass,
                    reversed: pass % 2 == 1,
                })
                .collect();
            let searched = run_search(&problem, &tour, &group_of, 1);
            assert!(is_permutation(&searched, 12));
            assert!(problem.tour_cost(&searched) <= problem.tour_cost(&tour) + 1e-9);
            if start == Start::Open {
                // West to east (0, 2, 1) or east to west: field 2 in the middle.
                let fields: Vec<usize> = searched.iter().map(|s| group_of[s.pass]).collect();
                assert_eq!(fields[4..8], [2, 2, 2, 2], "{fields:?}");
                assert!(problem.tour_cost(&searched) < problem.tour_cost(&tour) - 100.0);
            }
        }
    }
}
