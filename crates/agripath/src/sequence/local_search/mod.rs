//! `best`: our ordering for near-optimal tours in little time (not from the seeds).
//!
//! 1. Constructions, each improved by 2 and the cheapest kept: seed 001's greedy (on instances
//!    small enough for its O(n²) scan); a field-by-field boustrophedon — fields chained
//!    nearest-first, each field's swaths in scan-line order, alternating, from whichever corner
//!    is nearest; and the best order and corner of whole field blocks — exact (Held-Karp over
//!    fields × 4 corners) up to 10 fields, by block relocation above.
//! 2. Local search to a local optimum of two neighbourhoods on oriented passes, both driven by
//!    lists of the K nearest pass ends (so a sweep is O(n·K), not O(n²)):
//!    - 2-opt with end flips: reversing a stretch of the tour flies each of its passes the
//!      other way; only the two transfers at its edges change (eq. 8 is symmetric);
//!    - Or-opt: a chain of 1-3 consecutive passes, a field's whole block, or a longer chain
//!      whose removal joins two near ends (or-3opt), moved next to a neighbouring end, either
//!      way round.
//!    - The neighbour lists hold the 10 cheapest ends by eq. (8) and the 6 cheapest in other
//!      fields (by planar distance above 2,000 ends, where the costs are not precomputed).
//!    - On a path with a free end (`Start::Open`, and the last pass of `Start::From`), the
//!      free end is the dummy node of an open path at zero cost from every end: the head or
//!      the tail flown backwards, and a chain moved to the very start or end, are tried from
//!      every position.
//!    - Then the run search (`runs.rs`): the tour cut into runs (a field's passes joined by
//!      transfers that stay in it), the runs reordered and re-cornered as whole blocks, and
//!      the pass-level search again where they now meet.
//! 3. Iterated local search: a seeded double-bridge kick, then 1-2 again; a kick is kept only
//!    when the tour gets cheaper. On an open path (`Start::Open`) a kick may also cut before
//!    the first or after the last pass, and its descent also makes Or-3opt moves
//!    (`three_opt.rs`: Lin-Kernighan's sequential 3-opt step over the near-end lists). A kick works in place on the incumbent: the three new
//!    transfers are costed, only the passes at the cuts are queued, the moves report their
//!    gains (no re-costing of the tour unless it gained), and a kick that does not gain is
//!    undone by copying the incumbent back (the same tours as kicks on a copy on the 14
//!    benchmark instances of decision 0018, with no allocation per kick). The number of
//!    kicks is the budget: the iterations of `swarm`'s Runner, which drives
//!    [`IteratedLocalSearch`] like every other search.
//! 4. On an open path (`Start::Open`) only, two chains run side by side and the cheaper path
//!    is kept (`field_replan::open_path`): step 3 with 5/8 of the kicks, then each field's
//!    stretch of the path (its consecutive passes of one field, at least 8) ordered again by
//!    1-3 as a problem of its own between the pass ends flown before and after it, with a
//!    quarter of the kicks, and put back where the path gets cheaper (`field_replan.rs`); and
//!    the fields flown once each, as whole blocks in the exact best order, with every field's
//!    stretch ordered again that way twice. The kicks of the whole path spread over every
//!    field and undo themselves; spent on one field's passes they find a field flown from
//!    other corners, in another order of its cells, that the whole path's moves do not reach.
//!    And a path that has split a field around a smaller one does not find its way back to
//!    flying each field once, which the second chain never leaves.

use swarm::{Optimizer, Runner, Termination};

mod blocks;
mod construction;
mod field_replan;
mod lin_kernighan;
mod moves;
mod runs;
mod three_opt;

pub use construction::{block_local_search, boustrophedon, exact_field_order, LARGE_FARM_FIELDS};

use super::greedy::greedy_with_starts;
use super::tour::{End, OrderingProblem, Start, Step};
#[cfg(test)]
use construction::{block_steps, boustrophedon_by_grid};
use moves::Search;
pub use moves::{cheapest_ends, nearest_ends};

/// Positions examined after a kick before giving up on it.
const KICK_MOVES: usize = 400;

/// Nearest ends in other fields kept per end.
const OTHER_FIELD_NEIGHBOURS: usize = 6;

/// Nearest ends kept per end.
const NEIGHBOURS: usize = 10;
/// Greedy construction is O(n²) cost evaluations per start; above this it is skipped.
const GREEDY_LIMIT: usize = 1000;

/// `best`'s settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LocalSearchSettings {
    /// Double-bridge kicks of the iterated local search.
    pub kicks: usize,
    /// Seed of the kicks (run 0 of this seed).
    pub seed: u64,
    /// Closed tours only: independent chained Lin-Kernighan runs (2.5 × `kicks` kicks each)
    /// from the boustrophedon, beside the iterated search; the cheapest tour is kept. 0: the
    /// iterated search alone (what the supply search scores its candidates along, for speed).
    pub restarts: usize,
}

impl Default for LocalSearchSettings {
    fn default() -> Self {
        Self {
            kicks: 400,
            seed: 1,
            restarts: 8,
        }
    }
}

/// Kicks actually made: the budget, scaled down on big instances so that a kick's local
/// search (O(n·K) per sweep) keeps the whole run near linear.
fn kick_budget(settings: &LocalSearchSettings, passes: usize) -> usize {
    if passes > LOCAL_KICKS_ABOVE {
        // Local kicks cost O(KICK_MOVES) each whatever the size: the full budget, twice.
        return 2 * settings.kicks.max(1);
    }
    settings.kicks.min(100_000 / passes.max(1)).max(1)
}

/// Above this many passes the kicks are local double bridges (three cuts within
/// `LOCAL_KICK_SPAN` positions): a random double bridge on a long tour joins far-apart
/// stretches, which the local search then mostly undoes.
const LOCAL_KICKS_ABOVE: usize = 1000;
const LOCAL_KICK_SPAN: usize = 60;

/// The three cuts of a double-bridge kick on `n` items, in increasing order: anywhere within
/// 1..n, or within `LOCAL_KICK_SPAN` positions on long tours. On a path with a free first
/// end (`free_first`) a cut may also fall at 0, before the first pass, and with a free last
/// end (`free_last`) at n, after the last: the kick then changes where the path begins or
/// ends (the open path's dummy node is moved as any other node is in a kick on a cycle).
/// `None` when two cuts coincide (the caller skips that kick).
fn bridge_cuts(
    n: usize,
    free_first: bool,
    free_last: bool,
    stream: &mut swarm::RunStream,
) -> Option<[usize; 3]> {
    let mut cuts: [usize; 3] = if n > LOCAL_KICKS_ABOVE {
        let first = 1 + swarm::below(stream, n - 1 - LOCAL_KICK_SPAN);
        [
            first,
            first + 1 + swarm::below(stream, LOCAL_KICK_SPAN),
            first + 1 + swarm::below(stream, LOCAL_KICK_SPAN),
        ]
    } else {
        let lowest = usize::from(!free_first);
        let highest = n - 1 + usize::from(free_last);
        [0; 3].map(|_| lowest + swarm::below(stream, highest + 1 - lowest))
    };
    cuts.sort_unstable();
    (cuts[0] < cuts[1] && cuts[1] < cuts[2]).then_some(cuts)
}

/// A double-bridge kick: cut `items` at three random places and swap the middle two parts.
/// `None` when two cuts coincide (the caller skips that kick).
fn double_bridge<T: Copy>(items: &[T], stream: &mut swarm::RunStream) -> Option<Vec<T>> {
    let [a, b, c] = bridge_cuts(items.len(), false, false, stream)?;
    let mut kicked = items.to_vec();
    kicked[a..c].rotate_left(b - a);
    Some(kicked)
}

/// The constructions of step 1, each a start of the local search.
#[derive(Clone, Copy)]
enum Construction {
    Boustrophedon,
    ExactFieldOrder,
    /// Block relocation alone and with block reversals end in different local optima; both
    /// are kept as starts and the local search decides.
    BlockRelocation,
    BlockRelocationWithReversals,
    /// Seed 001's greedy, on instances of at most `GREEDY_LIMIT` passes.
    Greedy,
}

impl Construction {
    /// Its tour, when it applies to the problem.
    fn build(
        self,
        problem: &OrderingProblem,
        groups: &[Vec<usize>],
        seed: u64,
    ) -> Option<Vec<Step>> {
        match self {
            Self::Boustrophedon => Some(boustrophedon(problem, groups)),
            Self::ExactFieldOrder => exact_field_order(problem, groups),
            Self::BlockRelocation => block_local_search(problem, groups, false, seed),
            Self::BlockRelocationWithReversals => block_local_search(problem, groups, true, seed),
            Self::Greedy => {
                (problem.passes() <= GREEDY_LIMIT).then(|| greedy_with_starts(problem, 8))
            }
        }
    }
}

/// Our sequencer: construction, local search, iterated kicks, on `swarm`'s Runner (one kick
/// per iteration, run 0 of `settings.seed`); returns the Runner's best tour.
pub fn best_tour(
    problem: &OrderingProblem,
    groups: &[Vec<usize>],
    settings: &LocalSearchSettings,
) -> Vec<Step> {
    let n = problem.passes();
    if n <= 1 {
        return (0..n)
            .map(|pass| Step {
                pass,
                reversed: false,
            })
            .collect();
    }
    // Only an open path whose stretches can be re-planned splits its budget: a farm of one
    // field, of no field of `MIN_PASSES` passes, or without the cost matrix (above 1,000
    // passes) keeps every kick for the whole path (a review measured 5/8 of the kicks alone
    // 0.3-0.9 % dearer on farms of 1,000-2,400 passes).
    if problem.start == Start::Closed && settings.restarts > 0 && problem.has_cost_matrix() {
        return closed_tour(problem, groups, settings);
    }
    if problem.start != Start::Open || !field_replan::may_replan(problem, groups) {
        return iterated(problem, groups, settings, kick_budget(settings, n));
    }
    // An open path: two chains, the cheaper kept (step 4 of the module's doc).
    field_replan::open_path(problem, groups, settings)
}

/// A closed tour: the iterated search's, or the cheapest of `settings.restarts` chained
/// Lin-Kernighan runs from the boustrophedon, whichever is cheaper (decision 0018, twelfth
/// step: the seed 001 farm 1,737.0 m alone, 1,654.0 m with the runs, LKH-3 1,653.8 m).
fn closed_tour(
    problem: &OrderingProblem,
    groups: &[Vec<usize>],
    settings: &LocalSearchSettings,
) -> Vec<Step> {
    let n = problem.passes();
    let searched = iterated(problem, groups, settings, kick_budget(settings, n));
    // The near ends 2-opt and Or-opt use.
    let neighbours = near_ends(problem, &group_of(groups, n), groups.len());
    let restarted = lin_kernighan::restarted(
        problem,
        &neighbours,
        &boustrophedon(problem, groups),
        settings.restarts,
        settings.kicks * 5 / 2,
        settings.seed,
    );
    if problem.tour_cost(&restarted) < problem.tour_cost(&searched) - 1e-9 {
        restarted
    } else {
        searched
    }
}

/// Each end's near ends: the cheapest ends of any other pass, and the cheapest in other
/// fields (`group_of` each pass's, of `groups` fields). Without the latter a field's own swath
/// ends (a swath width apart) fill the list and moves between fields are never tried.
fn near_ends(problem: &OrderingProblem, group_of: &[usize], groups: usize) -> Vec<Vec<End>> {
    let mut neighbours = cheapest_ends(problem, NEIGHBOURS, |end, other| other / 2 != end / 2);
    if groups > 1 {
        let across = cheapest_ends(problem, OTHER_FIELD_NEIGHBOURS, |end, other| {
            group_of[other / 2] != group_of[end / 2]
        });
        for (list, extra) in neighbours.iter_mut().zip(across) {
            for end in extra {
                if !list.contains(&end) {
                    list.push(end);
                }
            }
        }
    }
    neighbours
}

/// Each of `n` passes' group (its field) in `groups`.
fn group_of(groups: &[Vec<usize>], n: usize) -> Vec<usize> {
    let mut group_of = vec![0; n];
    for (group, members) in groups.iter().enumerate() {
        for &pass in members {
            group_of[pass] = group;
        }
    }
    group_of
}

/// Steps 1-3 on `problem` with `kicks` kicks.
fn iterated(
    problem: &OrderingProblem,
    groups: &[Vec<usize>],
    settings: &LocalSearchSettings,
    kicks: usize,
) -> Vec<Step> {
    let runner = Runner::new(Termination::iterations(kicks), settings.seed)
        .expect("a kick budget of at least one");
    let mut search = IteratedLocalSearch::new(groups, settings.seed);
    runner
        .run_problem(&mut search, problem, 0, &mut ())
        .best_solution
}

/// Steps 1-3 as an optimizer of [`OrderingProblem`]: `start` builds the constructions and
/// descends from each; every `step` is one double-bridge kick and its local search, kept
/// when the tour gets cheaper by more than a nanometre (so float noise does not count).
/// The Runner costs the constructions and the kicks kept (its evaluation count); the local
/// search costs its moves by their gains, as 2-opt does.
pub struct IteratedLocalSearch<'g> {
    groups: &'g [Vec<usize>],
    /// The seed of the block relocation's own kicks (a construction, inside `start`).
    seed: u64,
    neighbours: Vec<Vec<End>>,
    group_of: Vec<usize>,
    /// The incumbent as the kicks work on it, kept between kicks so that a kick allocates
    /// nothing and costs only its local search: a kick that does not gain is undone by
    /// copying `saved` back.
    incumbent: Workspace,
}

/// The buffers of the kick loop (see [`IteratedLocalSearch`]).
#[derive(Default)]
struct Workspace {
    tour: Vec<Step>,
    position: Vec<usize>,
    queue: Vec<usize>,
    queued: Vec<bool>,
    gaps_costed: moves::GapMarks,
    saved: Vec<Step>,
}

impl<'g> IteratedLocalSearch<'g> {
    /// The search over passes grouped by field in `groups`.
    pub fn new(groups: &'g [Vec<usize>], seed: u64) -> Self {
        Self {
            groups,
            seed,
            neighbours: Vec::new(),
            group_of: Vec::new(),
            incumbent: Workspace::default(),
        }
    }

    /// The local search over `tour` (`position` its passes' places, kept up to date).
    fn search<'s, 'p>(
        &'s self,
        problem: &'s OrderingProblem<'p>,
        tour: Vec<Step>,
        position: Vec<usize>,
    ) -> Search<'s, 'p> {
        Search {
            problem,
            tour,
            position,
            neighbours: &self.neighbours,
            groups: &self.group_of,
            closed: problem.start.is_closed(),
            from_start: !problem.start.free_first(),
            home: problem.start.returns_home(),
            // Or-3opt in the descents from the constructions led to worse optima (decision
            // 0018, fourth step): `step` turns it on for the kicks of open paths only.
            three_opt: false,
            queue: Vec::new(),
            queued: Vec::new(),
            gaps_costed: moves::GapMarks::default(),
        }
    }

    /// Local search from `tour` around `active` passes, at most `budget` positions.
    fn descend(
        &self,
        problem: &OrderingProblem,
        tour: Vec<Step>,
        active: impl IntoIterator<Item = usize>,
        budget: usize,
    ) -> Vec<Step> {
        let n = tour.len();
        let mut search = self.search(problem, tour, vec![0; n]);
        search.reindex();
        search.descend(active, budget);
        search.tour
    }
}

impl<'a> Optimizer<OrderingProblem<'a>> for IteratedLocalSearch<'_> {
    fn name(&self) -> &'static str {
        "iterated local search (ours)"
    }

    fn start(&mut self, run: &mut swarm::Search<OrderingProblem<'a>>) {
        let problem = run.problem();
        let (n, groups, seed) = (problem.passes(), self.groups, self.seed);
        // The constructions, and then each one's descents, are independent: they run on the
        // machine's cores and are evaluated in this order, so the tours and the run's stream
        // are the same on any number of cores.
        let constructions = [
            Construction::Boustrophedon,
            Construction::ExactFieldOrder,
            Construction::BlockRelocation,
            Construction::BlockRelocationWithReversals,
            Construction::Greedy,
        ];
        let starts: Vec<Vec<Step>> =
            crate::parallel::map_in_order(&constructions, |construction| {
                construction.build(problem, groups, seed)
            })
            .into_iter()
            .flatten()
            .collect();
        self.group_of = group_of(groups, n);
        self.neighbours = near_ends(problem, &self.group_of, groups.len());
        self.incumbent = Workspace::default();
        // Each start's run search draws its kicks' seed from this run's stream, in order.
        let seeded: Vec<(Vec<Step>, u64)> = starts
            .into_iter()
            .map(|start| (start, swarm::below(run.stream(), 1 << 30) as u64))
            .collect();
        let this = &*self;
        let tours = crate::parallel::map_in_order(&seeded, |(start, seed)| {
            let tour = this.descend(problem, start.clone(), 0..n, 50 * n + 10_000);
            // Then the order and corners of its runs, and the pass-level moves again where
            // the runs now meet (runs.rs).
            let reordered = runs::run_search(problem, &tour, &this.group_of, *seed);
            if reordered == tour {
                tour
            } else {
                this.descend(problem, reordered, 0..n, 50 * n + 10_000)
            }
        });
        for tour in tours {
            run.evaluate(&tour);
        }
        if n < 8 {
            // Too few passes for a double bridge's three cuts.
            run.declare_converged();
        }
    }

    fn step(&mut self, run: &mut swarm::Search<OrderingProblem<'a>>) {
        let problem = run.problem();
        let n = problem.passes();
        let open = problem.start == Start::Open;
        let Some([a, b, c]) = bridge_cuts(n, open, open, run.stream()) else {
            return;
        };
        // The incumbent is the Runner's best: only kicks that beat it reach the Runner.
        let mut workspace = std::mem::take(&mut self.incumbent);
        let fresh = workspace.tour.is_empty();
        if fresh {
            workspace.tour = run.best_solution().to_vec();
            workspace.position = vec![0; n];
        }
        let mut search = self.search(problem, workspace.tour, workspace.position);
        // Or-3opt, and cuts at the free ends, on open paths only: the other starts were not
        // helped by them (decision 0018, fourth step) and keep their routes.
        search.three_opt = open;
        (search.queue, search.queued) = (workspace.queue, workspace.queued);
        search.gaps_costed = workspace.gaps_costed;
        if fresh {
            search.reindex();
        }
        workspace.saved.clone_from(&search.tour);
        let kick = search.double_bridge(a, b, c);
        // The passes at the first and the last cut, at positions b - 1 and b of the kicked
        // tour, and the tour's two ends, as the kicks woke them when they were made on a copy.
        // The middle join of the kicked tour is at a + c - b, not b; waking it instead was
        // measured (decision 0018) and is no better over seeds 1-3, and this keeps every
        // route as it was.
        let touched = [
            0,
            a.saturating_sub(1),
            a,
            b - 1,
            b,
            c - 1,
            c.min(n - 1),
            n - 1,
        ]
        .map(|i| search.tour[i.min(n - 1)].pass);
        let gained = search.descend(touched, KICK_MOVES);
        // Only a kick kept is handed to the Runner: a closed tour and its rotation cost the
        // same up to float noise but fly different open routes, so the Runner's best must
        // stay the incumbent, not a tour a nanometre cheaper by summation order.
        let kept =
            kick - gained < -1e-9 && problem.tour_cost(&search.tour) < run.best_cost() - 1e-9;
        if kept {
            run.evaluate(&search.tour);
        } else {
            search.tour.copy_from_slice(&workspace.saved);
            search.reindex();
        }
        self.incumbent = Workspace {
            tour: search.tour,
            position: search.position,
            queue: search.queue,
            queued: search.queued,
            gaps_costed: search.gaps_costed,
            saved: workspace.saved,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::drape::GroundPoint;
    use crate::sequence::tour::is_permutation;
    use crate::sequence::TransferModel;

    /// Three "fields" of three parallel passes each, far apart on a line.
    #[test]
    fn exact_field_order_is_a_permutation_no_worse_than_the_chained_boustrophedon() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let mut ends = Vec::new();
        let mut groups = vec![Vec::new(); 3];
        for (field, offset) in [(0, 0.0), (1, 900.0), (2, 300.0)] {
            for line in 0..3 {
                let x = offset + 5.0 * line as f64;
                groups[field].push(ends.len());
                ends.push([
                    GroundPoint {
                        x,
                        y: 2000.0,
                        ground_m: 0.0,
                    },
                    GroundPoint {
                        x,
                        y: 2100.0,
                        ground_m: 0.0,
                    },
                ]);
            }
        }
        let west = GroundPoint {
            x: -50.0,
            y: 2000.0,
            ground_m: 0.0,
        };
        for start in [
            Start::Closed,
            Start::Open,
            Start::From(west),
            Start::Fixed(west),
        ] {
            let problem = OrderingProblem::new(ends.clone(), start, &model);
            let exact = exact_field_order(&problem, &groups).unwrap();
            assert!(is_permutation(&exact, 9));
            let chained = boustrophedon(&problem, &groups);
            assert!(problem.tour_cost(&exact) <= problem.tour_cost(&chained) + 1e-9);
            // From the west the best order visits the fields west to east: 0, 2, 1.
            if let Start::From(_) = start {
                let order: Vec<usize> = exact.iter().map(|step| step.pass / 3).collect();
                assert_eq!(order, [0, 0, 0, 2, 2, 2, 1, 1, 1]);
            }
        }
    }

    /// Without the cost matrix (farms above 2,000 ends) the block search reads its links from
    /// a table of its own: the same links, so the same order as with the matrix.
    #[test]
    fn the_block_search_orders_alike_with_and_without_the_cost_matrix() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let (mut ends, mut groups) = (Vec::new(), Vec::new());
        for field in 0..40_usize {
            let (column, row) = ((field * 7) % 9, field / 9);
            let mut group = Vec::new();
            for line in 0..3 {
                let x = 3000.0 + 70.0 * column as f64 + 5.0 * line as f64;
                let y = 2000.0 + 90.0 * row as f64 + (field % 4) as f64 * 7.0;
                group.push(ends.len());
                ends.push([y, y + 30.0 + (field % 5) as f64].map(|y| GroundPoint {
                    x,
                    y,
                    ground_m: 0.0,
                }));
            }
            groups.push(group);
        }
        for start in [Start::Closed, Start::Open] {
            let problem = OrderingProblem::new(ends.clone(), start, &model);
            let with_matrix = block_local_search(&problem, &groups, true, 3).unwrap();
            let problem = problem.without_cost_matrix();
            assert!(!problem.has_cost_matrix());
            let without = block_local_search(&problem, &groups, true, 3).unwrap();
            assert_eq!(with_matrix, without);
        }
    }

    /// A farm of more fields than the exact constructions take: the grid construction flies
    /// each field once as a block, and stays within a few per cent of the all-pairs one.
    #[test]
    fn the_grid_construction_on_a_large_farm_is_a_permutation_close_to_the_exact_one() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        let mut ends = Vec::new();
        let mut groups = Vec::new();
        let side = 34; // 1,156 fields of two passes
        for row in 0..side {
            for column in 0..side {
                let mut group = Vec::new();
                for line in 0..2 {
                    let x = 3000.0 + 60.0 * column as f64 + 5.0 * line as f64 + (row % 3) as f64;
                    let y = 2000.0 + 60.0 * row as f64;
                    group.push(ends.len());
                    ends.push([
                        GroundPoint {
                            x,
                            y,
                            ground_m: 0.0,
                        },
                        GroundPoint {
                            x,
                            y: y + 40.0,
                            ground_m: 0.0,
                        },
                    ]);
                }
                groups.push(group);
            }
        }
        assert!(groups.len() > LARGE_FARM_FIELDS);
        let problem = OrderingProblem::new(ends, Start::Closed, &model);
        let grid = boustrophedon_by_grid(&problem, &groups);
        assert!(is_permutation(&grid, 2 * side * side));
        for pair in grid.chunks(2) {
            assert_eq!(
                pair[0].pass / 2,
                pair[1].pass / 2,
                "each field flown as one block"
            );
        }
        // The all-pairs construction, called directly.
        let mut all_pairs = Vec::new();
        let mut remaining: Vec<usize> = (0..groups.len()).collect();
        while !remaining.is_empty() {
            let (slot, steps) = remaining
                .iter()
                .enumerate()
                .flat_map(|(slot, &g)| [0, 2, 1, 3].map(|v| (slot, block_steps(&groups[g], v))))
                .min_by(|a, b| {
                    let cost = |steps: &Vec<Step>| match all_pairs.last() {
                        Some(last) => problem.cost(Step::exit(last), steps[0].entry()),
                        None => problem.cost_from_start(steps[0].entry()),
                    };
                    cost(&a.1).total_cmp(&cost(&b.1))
                })
                .unwrap();
            remaining.remove(slot);
            all_pairs.extend(steps);
        }
        let (ours, exact) = (problem.tour_cost(&grid), problem.tour_cost(&all_pairs));
        assert!(
            ours <= 1.05 * exact,
            "grid {ours} against all pairs {exact}"
        );
    }
}
