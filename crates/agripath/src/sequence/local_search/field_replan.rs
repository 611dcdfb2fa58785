//! Each field's stretch of a tour ordered again as a problem of its own (decision 0018,
//! seventh step).
//!
//! The iterated local search of `best` ends, on some farms, with a field flown in cells that a
//! better route flies in another order and from other corners (a notched field crossed at
//! its notch instead of at its top): moving there changes dozens of short transfers inside
//! the field at once, which no kick of the whole tour makes and its descent undoes. Here the
//! tour is cut into its *field stretches*, maximal runs of consecutive passes of one field,
//! and each stretch of at least [`MIN_PASSES`] passes (but not the whole tour) is ordered
//! again by `best`'s steps 1-3 (constructions, descent, kicks) on its passes only, with the
//! kick budget the caller gives:
//!
//! - between the pass end flown before it and the one flown after it, the stretch is the
//!   closed tour through a connector pass between those two ends ([`PartBounds::Between`]),
//!   whose transfers are exactly those the stretch adds to the tour;
//! - at a free end of the tour (the first stretch of an open path, the last of an open path
//!   or of `Start::From`), it is a path from its one neighbour with a free other end
//!   ([`PartBounds::From`]), flown backwards when the free end is the tour's first;
//! - a stretch next to a start point, or at a closed tour's seam, is left as it is (the
//!   caller, `best_tour`, re-plans open paths only: on closed tours and round trips it was
//!   measured no better, decision 0018's seventh step).
//!
//! This is one pass of POPMUSIC's idea (Taillard and Voß 2002, docs/references.md: parts of a
//! solution optimised as problems of their own), with a field's stretch as the part; it does
//! not loop over the parts until none improves (measured no better on the farms of decision
//! 0018, whose second pass found nothing the first had not).
//!
//! A part's passes are one group in the stretch's order as flown, so the boustrophedon
//! construction among the part's starts replays that order with alternating directions; the
//! field's scan-line order instead was tried and moved single farms both ways (a review's
//! measurement), so the flown order is kept.
//!
//! The stretches are ordered independently, on the machine's cores, each against the tour as
//! the search left it; they are then put back first to last, each only when the whole tour
//! gets cheaper (a neighbour put back before it may have moved the end it was ordered from),
//! so the tour never gets dearer. Costs come from the whole problem's matrix
//! ([`OrderingProblem::part`]); without one (above 2,000 ends) the tour is left as it is.

use super::{
    block_local_search, exact_field_order, group_of, iterated, kick_budget, LocalSearchSettings,
};
use crate::sequence::tour::{OrderingProblem, PartBounds, Step};

/// On an open path, the share of the kick budget (in eighths) the whole path's chain gets;
/// each field stretch then gets the budget / [`STRETCH_KICKS_DIVISOR`] (with the default 400:
/// 250 on the path, 100 per stretch). Measured in decision 0018's seventh step: the same open
/// paths within 1.01 × LKH as 400 + 100, in 10-25 % less time.
const OPEN_PATH_KICKS_EIGHTHS: usize = 5;
const STRETCH_KICKS_DIVISOR: usize = 4;

/// Rounds of stretch re-planning on the chain of whole field blocks: the second re-plans each
/// field against neighbours that the first has moved (seed 001's farm, decision 0018's eighth
/// step, measured with a quarter of the kicks per stretch: 1,686.8 m after one round,
/// 1,342.2 m after two, nothing more after three).
const FIELD_BLOCK_ROUNDS: usize = 2;
/// Each stretch of the chain of field blocks gets the budget / this many kicks (50 of the
/// default 400): the same paths on the 14 instances of decision 0018 as with 100, in 9-17 %
/// less time on one core.
const FIELD_BLOCK_KICKS_DIVISOR: usize = 8;

/// The kick budgets of [`open_path`]'s steps, from the caller's.
struct ChainSettings {
    /// The whole path's steps 1-3.
    whole: LocalSearchSettings,
    /// Each stretch of the whole path's chain.
    stretch: LocalSearchSettings,
    /// Each stretch of the chain of field blocks.
    block_stretch: LocalSearchSettings,
}

impl ChainSettings {
    fn of(settings: &LocalSearchSettings) -> Self {
        let share = |kicks: usize| LocalSearchSettings {
            kicks: kicks.max(1),
            ..*settings
        };
        Self {
            whole: share(settings.kicks * OPEN_PATH_KICKS_EIGHTHS / 8),
            stretch: share(settings.kicks / STRETCH_KICKS_DIVISOR),
            block_stretch: share(settings.kicks / FIELD_BLOCK_KICKS_DIVISOR),
        }
    }
}

/// The open path over `groups` (the passes by field), when [`may_replan`]: two chains, run on
/// the machine's cores, and the cheaper path kept (the first on a tie):
///
/// 1. *The whole path*: steps 1-3 with 5/8 of the kicks, then its field stretches re-planned
///    (decision 0018's seventh step).
/// 2. *Whole field blocks*: the fields flown one after the other, each as one boustrophedon
///    block, in the exact best order and corners (or by block relocation above ten fields),
///    then every field's stretch re-planned between its neighbours (with an eighth of the
///    kicks), [`FIELD_BLOCK_ROUNDS`] times (decision 0018's eighth step). The whole path's
///    kicks leave a field split in two stretches around a smaller one where flying each field
///    once, in other cells and corners, is cheaper (seed 001's farm: 1,448.2 m against LKH-3's 1,377.7 m); getting there moves
///    several fields at once, which the kicks' descents undo. This chain never splits a field,
///    and the re-plans find each field's path for the neighbours it actually has.
pub fn open_path(
    problem: &OrderingProblem,
    groups: &[Vec<usize>],
    settings: &LocalSearchSettings,
) -> Vec<Step> {
    let n = problem.passes();
    let ChainSettings {
        whole,
        stretch,
        block_stretch,
    } = ChainSettings::of(settings);
    let field_of = group_of(groups, n);
    let chains = [false, true];
    let tours = crate::parallel::map_in_order(&chains, |&field_blocks| {
        if field_blocks {
            let blocks = exact_field_order(problem, groups)
                .or_else(|| block_local_search(problem, groups, true, settings.seed))?;
            Some((0..FIELD_BLOCK_ROUNDS).fold(blocks, |tour, _| {
                replan_field_stretches(problem, &field_of, tour, &block_stretch)
            }))
        } else {
            let tour = iterated(problem, groups, &whole, kick_budget(&whole, n));
            Some(replan_field_stretches(problem, &field_of, tour, &stretch))
        }
    });
    tours
        .into_iter()
        .flatten()
        .map(|tour| (problem.tour_cost(&tour), tour))
        .reduce(|kept, other| if other.0 < kept.0 - 1e-9 { other } else { kept })
        .map(|(_, tour)| tour)
        .expect("the whole path's chain always gives a tour")
}

/// Passes a stretch needs to be ordered again (shorter ones the tour's own moves reach).
pub const MIN_PASSES: usize = 8;

/// Whether an open path over `groups` (the passes by field) can have a stretch re-planned: a
/// cost matrix to read the parts' costs from, two fields or more, and a field of at least
/// [`MIN_PASSES`] passes.
pub fn may_replan(problem: &OrderingProblem, groups: &[Vec<usize>]) -> bool {
    problem.has_cost_matrix()
        && groups.iter().filter(|members| !members.is_empty()).count() >= 2
        && groups.iter().any(|members| members.len() >= MIN_PASSES)
}

/// `tour` with each of its field stretches ordered again where that makes it cheaper
/// (`field_of[pass]` is the pass's field).
pub fn replan_field_stretches(
    problem: &OrderingProblem,
    field_of: &[usize],
    tour: Vec<Step>,
    settings: &LocalSearchSettings,
) -> Vec<Step> {
    let n = tour.len();
    let stretches = field_stretches(&tour, field_of);
    if !problem.has_cost_matrix() || stretches.len() < 2 {
        return tour;
    }
    let worth: Vec<(usize, usize)> = stretches
        .into_iter()
        .filter(|&(first, last)| last + 1 - first >= MIN_PASSES)
        .collect();
    let ordered = crate::parallel::map_in_order(&worth, |&(first, last)| {
        reorder(problem, &tour, first, last, settings)
    });
    let mut tour = tour;
    let mut cost = problem.tour_cost(&tour);
    for (&(first, last), stretch) in worth.iter().zip(ordered) {
        let Some(stretch) = stretch else { continue };
        let kept = tour[first..=last].to_vec();
        tour[first..=last].copy_from_slice(&stretch);
        let changed = problem.tour_cost(&tour);
        if changed < cost - 1e-9 {
            cost = changed;
        } else {
            tour[first..=last].copy_from_slice(&kept);
        }
    }
    debug_assert_eq!(tour.len(), n);
    tour
}

/// The maximal runs `(first, last)` of consecutive positions of `tour` in one field.
pub fn field_stretches(tour: &[Step], field_of: &[usize]) -> Vec<(usize, usize)> {
    let mut stretches = Vec::new();
    let mut first = 0;
    for position in 1..=tour.len() {
        let ends_here =
            position == tour.len() || field_of[tour[position].pass] != field_of[tour[first].pass];
        if ends_here {
            stretches.push((first, position - 1));
            first = position;
        }
    }
    stretches
}

/// Positions `first..=last` of `tour` ordered again between their neighbours: the stretch's
/// passes in their new order, or `None` when the stretch has no neighbour (the whole tour).
fn reorder(
    problem: &OrderingProblem,
    tour: &[Step],
    first: usize,
    last: usize,
    settings: &LocalSearchSettings,
) -> Option<Vec<Step>> {
    let n = tour.len();
    let passes: Vec<usize> = tour[first..=last].iter().map(|step| step.pass).collect();
    // The ends flown just before and after the stretch.
    let before = (first > 0).then(|| tour[first - 1].exit());
    let after = (last + 1 < n).then(|| tour[last + 1].entry());
    order_between(problem, &passes, before, after, settings)
}

/// `passes` ordered by steps 1-3 to be flown between the end `before` and the end `after`
/// (`None`: the tour's own end there), in flight order; `None` when an end is the start
/// point or a closed tour's seam, or there is no cost matrix.
fn order_between(
    problem: &OrderingProblem,
    passes: &[usize],
    before: Option<usize>,
    after: Option<usize>,
    settings: &LocalSearchSettings,
) -> Option<Vec<Step>> {
    // The start point has no end of its own, so a stretch next to it is bounded by a free
    // end only when the start is free.
    let seam = problem.start.is_closed();
    let fixed_first = !problem.start.free_first() || seam;
    let fixed_last = problem.start.returns_home() || seam;
    let bounds = match (before, after) {
        (Some(before), Some(after)) => PartBounds::Between { before, after },
        (None, Some(after)) if !fixed_first => PartBounds::From(after),
        (Some(before), None) if !fixed_last => PartBounds::From(before),
        // Next to the start point, or on a closed tour's seam: left as it is.
        _ => return None,
    };
    let part = problem.part(passes, bounds)?;
    let count = passes.len();
    // The stretch's passes are one field; the connector is a field of its own.
    let mut groups = vec![(0..count).collect::<Vec<usize>>()];
    if part.passes() > count {
        groups.push(vec![count]);
    }
    // Steps 1-3 alone: a part is never re-planned in its turn.
    let solved = iterated(
        &part,
        &groups,
        settings,
        kick_budget(settings, part.passes()),
    );
    in_flight_order(&solved, passes, bounds, before.is_none())
}

/// A part's tour `solved` (its passes numbered as in [`OrderingProblem::part`]: pass i is
/// `passes[i]`, the connector last) as the stretch it stands for, in flight order between
/// `before` and `after`, in the whole problem's pass numbers. `path_into_after`: the part is
/// a path from `after` (the stretch begins the tour), so it is the stretch flown backwards.
fn in_flight_order(
    solved: &[Step],
    passes: &[usize],
    bounds: PartBounds,
    path_into_after: bool,
) -> Option<Vec<Step>> {
    let count = passes.len();
    let ordered: Vec<Step> = match bounds {
        PartBounds::Between { .. } => {
            // The cycle read from the connector's exit (`before`) round to its entry
            // (`after`); flown the other way round when the connector is.
            let connector = solved.iter().position(|step| step.pass == count)?;
            let mut cycle: Vec<Step> = solved[connector + 1..].to_vec();
            cycle.extend_from_slice(&solved[..connector]);
            if solved[connector].reversed {
                backwards(&cycle)
            } else {
                cycle
            }
        }
        PartBounds::From(_) if path_into_after => backwards(solved),
        PartBounds::From(_) => solved.to_vec(),
    };
    Some(
        ordered
            .into_iter()
            .map(|step| Step {
                pass: passes[step.pass],
                reversed: step.reversed,
            })
            .collect(),
    )
}

/// `steps` flown backwards: the last first, each the other way.
fn backwards(steps: &[Step]) -> Vec<Step> {
    steps.iter().rev().map(|step| step.flipped()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::drape::GroundPoint;
    use crate::sequence::tour::{is_permutation, Start};
    use crate::sequence::TransferModel;
    use proptest::prelude::*;

    fn ground(x: f64, y: f64) -> GroundPoint {
        GroundPoint {
            x,
            y,
            ground_m: 0.0,
        }
    }

    /// Three fields of ten parallel passes 5 m apart, 300 m from each other along a line
    /// (south of the demo farm, outside its fields, so eq. 8 is the straight line plus 2h):
    /// pass p is in field p / 10.
    fn three_fields() -> (Vec<[GroundPoint; 2]>, Vec<usize>) {
        let mut ends = Vec::new();
        let mut field_of = Vec::new();
        for field in 0..3 {
            for line in 0..10 {
                let x = 300.0 * field as f64 + 5.0 * line as f64;
                ends.push([ground(x, -2000.0), ground(x, -1900.0)]);
                field_of.push(field);
            }
        }
        (ends, field_of)
    }

    fn steps(passes: impl IntoIterator<Item = (usize, bool)>) -> Vec<Step> {
        passes
            .into_iter()
            .map(|(pass, reversed)| Step { pass, reversed })
            .collect()
    }

    #[test]
    fn the_stretches_are_the_maximal_runs_of_one_field() {
        let field_of = [0, 0, 1, 1, 2];
        let tour = steps([(0, false), (2, false), (3, true), (1, false), (4, false)]);
        assert_eq!(
            field_stretches(&tour, &field_of),
            [(0, 0), (1, 2), (3, 3), (4, 4)]
        );
        assert_eq!(field_stretches(&tour[..0], &field_of), []);
    }

    /// A part between two ends costs, through its connector, exactly what its stretch adds to
    /// the tour: the transfer in, the transfers inside, the transfer out; a part from an end
    /// costs the transfer from that end and those inside.
    #[test]
    fn a_part_costs_what_its_stretch_adds_to_the_tour() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let (ends, _) = three_fields();
        let problem = OrderingProblem::new(ends, Start::Open, &model);
        let tour = swarm::Problem::random_solution(&problem, &mut swarm::run_stream(3, 0));
        let (first, last) = (10, 19);
        let stretch = &tour[first..=last];
        let passes: Vec<usize> = stretch.iter().map(|step| step.pass).collect();
        let (before, after) = (tour[first - 1].exit(), tour[last + 1].entry());
        let inside: f64 = stretch
            .windows(2)
            .map(|pair| problem.cost(pair[0].exit(), pair[1].entry()))
            .sum();
        let added = problem.cost(before, stretch[0].entry())
            + inside
            + problem.cost(stretch[9].exit(), after);
        let between = problem
            .part(&passes, PartBounds::Between { before, after })
            .unwrap();
        let mut cycle: Vec<Step> = (0..10)
            .map(|index| Step {
                pass: index,
                reversed: stretch[index].reversed,
            })
            .collect();
        cycle.push(Step {
            pass: 10,
            reversed: false,
        });
        assert!((between.tour_cost(&cycle) - added).abs() < 1e-9);
        let from = problem.part(&passes, PartBounds::From(before)).unwrap();
        let path = &cycle[..10];
        let expected = problem.cost(before, stretch[0].entry()) + inside;
        assert!((from.tour_cost(path) - expected).abs() < 1e-9);
        assert_eq!(from.point(0), problem.point(2 * passes[0]));
    }

    /// The middle field flown in a scrambled order between two well-flown ones: it comes back
    /// flown as one boustrophedon, every field still in its place.
    #[test]
    fn a_scrambled_field_is_ordered_again() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let (ends, field_of) = three_fields();
        let problem = OrderingProblem::new(ends, Start::Open, &model);
        let sweep = |field: usize| (0..10).map(move |line| (10 * field + line, line % 2 == 1));
        let scrambled = [3, 8, 1, 6, 0, 9, 4, 2, 7, 5].map(|line| (10 + line, line % 3 == 0));
        let tour = steps(sweep(0).chain(scrambled).chain(sweep(2)));
        let replanned = replan_field_stretches(
            &problem,
            &field_of,
            tour.clone(),
            &LocalSearchSettings::default(),
        );
        assert!(is_permutation(&replanned, 30));
        // Each field is still flown in one stretch, in the same place.
        for (position, step) in replanned.iter().enumerate() {
            assert_eq!(field_of[step.pass], position / 10);
        }
        let transfers_inside: f64 = replanned[10..20]
            .windows(2)
            .map(|pair| problem.cost(pair[0].exit(), pair[1].entry()))
            .sum();
        // Nine steps across the field, a boustrophedon: each 5 m + 2h (20 m) = 25 m (the points
        // lie outside the demo farm's fields, so every transfer climbs).
        assert!(
            (transfers_inside - 9.0 * 25.0).abs() < 1e-6,
            "{transfers_inside}"
        );
        assert!(problem.tour_cost(&replanned) < problem.tour_cost(&tour) - 100.0);
    }

    /// The open path keeps every pass once and is never dearer than the whole path's chain
    /// alone (the chain of field blocks only replaces it when cheaper).
    #[test]
    fn the_open_path_is_the_cheaper_chain() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let (ends, field_of) = three_fields();
        let problem = OrderingProblem::new(ends, Start::Open, &model);
        let groups: Vec<Vec<usize>> = (0..3).map(|f| (10 * f..10 * f + 10).collect()).collect();
        assert!(field_of.iter().enumerate().all(|(pass, &f)| pass / 10 == f));
        let settings = LocalSearchSettings::default();
        let path = open_path(&problem, &groups, &settings);
        assert!(is_permutation(&path, 30));
        let ChainSettings { whole, stretch, .. } = ChainSettings::of(&settings);
        let alone = replan_field_stretches(
            &problem,
            &field_of,
            iterated(&problem, &groups, &whole, kick_budget(&whole, 30)),
            &stretch,
        );
        assert!(problem.tour_cost(&path) <= problem.tour_cost(&alone) + 1e-9);
    }

    /// A random tour of [`three_fields`]: each field's passes in a random order and cut into
    /// one to three runs at random places, the runs in a random order (so a field may be
    /// flown in several stretches, of any length from 1 to 10).
    fn scattered_tour(problem: &OrderingProblem, field_of: &[usize], seed: u64) -> Vec<Step> {
        let mut stream = swarm::run_stream(seed, 0);
        let tour = swarm::Problem::random_solution(problem, &mut stream);
        let mut runs: Vec<Vec<Step>> = Vec::new();
        for field in 0..3 {
            let members: Vec<Step> = tour
                .iter()
                .filter(|step| field_of[step.pass] == field)
                .copied()
                .collect();
            let mut cuts = [swarm::below(&mut stream, 11), swarm::below(&mut stream, 11)];
            cuts.sort_unstable();
            for run in [
                &members[..cuts[0]],
                &members[cuts[0]..cuts[1]],
                &members[cuts[1]..],
            ] {
                if !run.is_empty() {
                    runs.push(run.to_vec());
                }
            }
        }
        for index in (1..runs.len()).rev() {
            runs.swap(index, swarm::below(&mut stream, index + 1));
        }
        runs.concat()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]
        /// Whatever the tour and the start, the re-plan returns every pass once and never a
        /// dearer tour; a stretch next to a start point stays where it is.
        #[test]
        fn the_replan_keeps_every_pass_and_never_costs_more(
            seed in 0u64..1000,
            start in 0usize..4,
        ) {
            let farm = crate::demo::scenario().unwrap().farm;
            let model = TransferModel::new(&farm, 10.0);
            let (ends, field_of) = three_fields();
            let point = ground(450.0, -2100.0);
            let starts = [Start::Open, Start::Closed, Start::From(point), Start::Fixed(point)];
            let start = starts[start];
            let problem = OrderingProblem::new(ends, start, &model);
            let tour = scattered_tour(&problem, &field_of, seed);
            let settings = LocalSearchSettings { kicks: 20, seed, restarts: 0 };
            let replanned = replan_field_stretches(&problem, &field_of, tour.clone(), &settings);
            prop_assert!(is_permutation(&replanned, 30));
            prop_assert!(problem.tour_cost(&replanned) <= problem.tour_cost(&tour) + 1e-9);
            let (_, first_last) = field_stretches(&tour, &field_of)[0];
            if start.point().is_some() || start.is_closed() {
                prop_assert_eq!(&replanned[..=first_last], &tour[..=first_last]);
            }
        }

        /// Any tour of a part, read back as its stretch, costs on the whole problem (from the
        /// end before it to the end after it, or from the one end it has) exactly what it
        /// costs in the part: for a stretch between two others (the connector either way
        /// round), at the head of an open path and at its tail.
        #[test]
        fn a_part_tour_read_back_costs_the_same_in_the_tour(seed in 0u64..1000, span in 0usize..3) {
            let farm = crate::demo::scenario().unwrap().farm;
            let model = TransferModel::new(&farm, 10.0);
            let (ends, _) = three_fields();
            let problem = OrderingProblem::new(ends, Start::Open, &model);
            let mut stream = swarm::run_stream(seed, 1);
            let tour = swarm::Problem::random_solution(&problem, &mut stream);
            let (first, last) = [(0, 11), (7, 20), (19, 29)][span];
            let passes: Vec<usize> = tour[first..=last].iter().map(|step| step.pass).collect();
            let before = (first > 0).then(|| tour[first - 1].exit());
            let after = (last < 29).then(|| tour[last + 1].entry());
            let bounds = match (before, after) {
                (Some(before), Some(after)) => PartBounds::Between { before, after },
                (None, Some(after)) => PartBounds::From(after),
                (Some(before), None) => PartBounds::From(before),
                (None, None) => unreachable!(),
            };
            let part = problem.part(&passes, bounds).unwrap();
            for _ in 0..4 {
                let solved = swarm::Problem::random_solution(&part, &mut stream);
                let stretch = in_flight_order(&solved, &passes, bounds, before.is_none()).unwrap();
                let mut sorted: Vec<usize> = stretch.iter().map(|step| step.pass).collect();
                sorted.sort_unstable();
                let mut expected = passes.clone();
                expected.sort_unstable();
                prop_assert_eq!(sorted, expected);
                let inside: f64 = stretch
                    .windows(2)
                    .map(|pair| problem.cost(pair[0].exit(), pair[1].entry()))
                    .sum();
                let into = before.map_or(0.0, |end| problem.cost(end, stretch[0].entry()));
                let last_exit = stretch[stretch.len() - 1].exit();
                let out = after.map_or(0.0, |end| problem.cost(last_exit, end));
                prop_assert!((into + inside + out - part.tour_cost(&solved)).abs() < 1e-9);
            }
        }
    }
}
