//! The joint search: local search on the giant tour with every move scored through the
//! split (Prins 2004), then seeded kicks (iterated local search), on `swarm`'s Runner.
//!
//! Moves, on oriented passes, generated from lists of the nearest pass ends as the ordering
//! search does ([`crate::sequence::local_search`]): flipping one pass; 2-opt reversals (a
//! stretch flown backwards, each of its passes the other way); relocating a chain of 1-3
//! passes next to a near end, either way round. Splitting a tour costs far more than costing
//! its transfers, so at each position the moves are ranked by their change in transfer
//! metres and only the `SCORED_PER_POSITION` best are scored through the split: a move that
//! lengthens the transfers can still pay (a sortie that now ends near the supply point),
//! which is why they are not discarded outright. The first move that lowers the split's
//! cost is made, and the passes around it are looked at again.
//!
//! From several start tours ([`super::starts`]) the local search races: each start descends
//! for the same number of splits, and only the cheapest descent goes on to its local optimum
//! (one full descent costs most of the budget, and the search stalls in the local optimum of
//! its start, so the budget is better spent choosing the start than finishing every descent).
//!
//! Each Runner iteration is one kick: a double bridge within `KICK_SPAN` positions of the
//! incumbent (the Runner's best), then the local search around its cuts. The budget is the
//! Runner's evaluation count.

use swarm::{below, Optimizer, Search};

use super::{petals, JointProblem};
use crate::sequence::local_search::nearest_ends;
use crate::sequence::tour::{End, Step};

/// Moves scored through the split at each position.
const SCORED_PER_POSITION: usize = 16;
/// Nearest ends of other passes per end.
const NEIGHBOURS: usize = 8;
/// Positions a kick's three cuts lie within.
const KICK_SPAN: usize = 30;

/// A change of the tour.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Move {
    /// Fly positions `from..=to` backwards.
    Reverse { from: usize, to: usize },
    /// Move positions `from..=to` to before position `gap` of the tour as it was (`gap` not
    /// in `from..=to + 1`), turned round when `flip`.
    Relocate {
        from: usize,
        to: usize,
        gap: usize,
        flip: bool,
    },
}

/// The joint search's state: its start tours, how far each races, and the neighbour lists.
pub struct JointSearch {
    starts: Vec<Vec<Step>>,
    race_evaluations: u64,
    neighbours: Vec<Vec<End>>,
    /// Whether the petal moves ([`super::petals`]) are tried on the incumbent.
    petals: bool,
    /// The incumbent cost at which a round of petal moves last found nothing (not tried
    /// again until the incumbent changes).
    petals_failed_at: f64,
}

impl JointSearch {
    /// The search starting from `start`.
    pub fn new(start: Vec<Step>) -> Self {
        Self::racing(vec![start], 0)
    }

    /// The search from several start tours (the first is the preferred one on ties): each
    /// descends for `race_evaluations` splits, the cheapest descent then goes on to its
    /// local optimum, and the kicks start from the best tour found. With one start the race
    /// is skipped.
    pub fn racing(starts: Vec<Vec<Step>>, race_evaluations: u64) -> Self {
        assert!(!starts.is_empty(), "the joint search needs a start tour");
        Self {
            starts,
            race_evaluations,
            neighbours: Vec::new(),
            petals: false,
            petals_failed_at: f64::NAN,
        }
    }

    /// The same search, trying the petal moves ([`super::petals`]) on every sortie of the
    /// incumbent before each kick while they pay.
    pub fn with_petals(mut self) -> Self {
        self.petals = true;
        self
    }

    /// One round of petal moves on the incumbent: every sortie's candidates scored through
    /// the split, the first that pays made and descended around. Whether one paid.
    fn petal_round(&self, run: &mut Search<JointProblem<'_>>) -> bool {
        let incumbent = run.best_solution().to_vec();
        let cost = run.best_cost();
        let problem = run.problem();
        for (first, last) in problem.sorties(&incumbent) {
            if last <= first {
                continue;
            }
            for candidate in petals::candidates(problem.ordering, &incumbent, first, last) {
                if run.progress() >= 1.0 {
                    return false;
                }
                let candidate_cost = run.evaluate(&candidate);
                if candidate_cost < cost - 1e-9 {
                    let touched: Vec<usize> = candidate[first..=last]
                        .iter()
                        .map(|step| step.pass)
                        .collect();
                    Descent::new(candidate, candidate_cost, touched).run(
                        run,
                        &self.neighbours,
                        u64::MAX,
                    );
                    return true;
                }
            }
        }
        false
    }
}

/// The tour with `change` made.
fn apply(tour: &[Step], change: Move) -> Vec<Step> {
    let mut changed = tour.to_vec();
    match change {
        Move::Reverse { from, to } => {
            changed[from..=to].reverse();
            changed[from..=to]
                .iter_mut()
                .for_each(|step| *step = step.flipped());
        }
        Move::Relocate {
            from,
            to,
            gap,
            flip,
        } => {
            let mut chain: Vec<Step> = changed.drain(from..=to).collect();
            if flip {
                chain.reverse();
                chain.iter_mut().for_each(|step| *step = step.flipped());
            }
            let at = if gap > to { gap - chain.len() } else { gap };
            changed.splice(at..at, chain);
        }
    }
    changed
}

struct Moves<'t, 'p> {
    tour: &'t [Step],
    position: &'t [usize],
    problem: &'t JointProblem<'p>,
    neighbours: &'t [Vec<End>],
}

impl Moves<'_, '_> {
    /// Eq. (8) from end `from` to end `to`; 0 where either is off the tour's ends.
    fn edge(&self, from: Option<End>, to: Option<End>) -> f64 {
        match (from, to) {
            (Some(from), Some(to)) => self.problem.ordering.cost(from, to),
            _ => 0.0,
        }
    }

    fn exit_before(&self, position: usize) -> Option<End> {
        position
            .checked_sub(1)
            .map(|before| self.tour[before].exit())
    }

    fn entry_after(&self, position: usize) -> Option<End> {
        self.tour.get(position + 1).map(Step::entry)
    }

    /// Change in transfer metres of `change`.
    fn delta(&self, change: Move) -> f64 {
        let tour = self.tour;
        match change {
            Move::Reverse { from, to } => {
                let (before, after) = (self.exit_before(from), self.entry_after(to));
                self.edge(before, Some(tour[to].exit()))
                    + self.edge(Some(tour[from].entry()), after)
                    - self.edge(before, Some(tour[from].entry()))
                    - self.edge(Some(tour[to].exit()), after)
            }
            Move::Relocate {
                from,
                to,
                gap,
                flip,
            } => {
                let (before, after) = (self.exit_before(from), self.entry_after(to));
                let (entry, exit) = (tour[from].entry(), tour[to].exit());
                let removed = self.edge(before, Some(entry)) + self.edge(Some(exit), after)
                    - self.edge(before, after);
                let left = gap.checked_sub(1).map(|k| tour[k].exit());
                let right = tour.get(gap).map(Step::entry);
                let (first, last) = if flip { (exit, entry) } else { (entry, exit) };
                let added = self.edge(left, Some(first)) + self.edge(Some(last), right)
                    - self.edge(left, right);
                added - removed
            }
        }
    }

    /// The moves around position `p`.
    fn around(&self, p: usize) -> Vec<Move> {
        let n = self.tour.len();
        let mut moves = vec![Move::Reverse { from: p, to: p }];
        for q in [p, p + 1].into_iter().filter(|&q| q < n) {
            // Reversals that join the flight before q to a near exit, or a near entry to q.
            if let Some(before) = self.exit_before(q) {
                for &end in &self.neighbours[before] {
                    let other = self.position[end / 2];
                    if other > q && self.tour[other].exit() == end {
                        moves.push(Move::Reverse { from: q, to: other });
                    }
                }
            }
            for &end in &self.neighbours[self.tour[q].entry()] {
                let other = self.position[end / 2];
                if other + 1 < q && self.tour[other].entry() == end {
                    moves.push(Move::Reverse {
                        from: other,
                        to: q - 1,
                    });
                }
            }
        }
        for length in 1..=3usize {
            let to = p + length - 1;
            if to >= n || length >= n {
                break;
            }
            let ends = [self.tour[p].entry(), self.tour[to].exit()];
            for end in ends {
                for &near in &self.neighbours[end] {
                    let other = self.position[near / 2];
                    for gap in [other, other + 1] {
                        if (p..=to + 1).contains(&gap) || gap > n {
                            continue;
                        }
                        for flip in [false, true] {
                            moves.push(Move::Relocate {
                                from: p,
                                to,
                                gap,
                                flip,
                            });
                        }
                    }
                }
            }
        }
        moves
    }
}

/// A local search in progress: its tour, and the passes still to look at (a stack).
struct Descent {
    tour: Vec<Step>,
    cost: f64,
    position: Vec<usize>,
    queue: Vec<usize>,
    queued: Vec<bool>,
}

impl Descent {
    /// The local search from `tour` (of split cost `cost`) around the passes `active`.
    fn new(tour: Vec<Step>, cost: f64, active: impl IntoIterator<Item = usize>) -> Self {
        let n = tour.len();
        let mut descent = Self {
            tour,
            cost,
            position: vec![0; n],
            queue: Vec::new(),
            queued: vec![false; n],
        };
        descent.reindex();
        for pass in active {
            descent.push(pass);
        }
        descent
    }

    fn reindex(&mut self) {
        for (index, step) in self.tour.iter().enumerate() {
            self.position[step.pass] = index;
        }
    }

    fn push(&mut self, pass: usize) {
        if !std::mem::replace(&mut self.queued[pass], true) {
            self.queue.push(pass);
        }
    }

    /// Whether the tour is a local optimum of the moves.
    fn is_done(&self) -> bool {
        self.queue.is_empty()
    }

    /// Looks at the queued passes until none is left, the run's budget is spent or the run
    /// has made `until` evaluations (a pass is looked at in full: up to
    /// `SCORED_PER_POSITION` more).
    fn run(&mut self, run: &mut Search<JointProblem<'_>>, neighbours: &[Vec<End>], until: u64) {
        let n = self.tour.len();
        // The candidates differ from this tour from their first changed position on: their
        // splits resume there.
        run.problem().pin(&self.tour);
        while let Some(pass) = self.queue.pop() {
            if run.progress() >= 1.0 || run.evaluations() >= until {
                self.queue.push(pass);
                return;
            }
            self.queued[pass] = false;
            let p = self.position[pass];
            let moves = Moves {
                tour: &self.tour,
                position: &self.position,
                problem: run.problem(),
                neighbours,
            };
            let mut ranked: Vec<(f64, Move)> = moves
                .around(p)
                .into_iter()
                .map(|change| (moves.delta(change), change))
                .collect();
            ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
            ranked.dedup_by(|a, b| a.1 == b.1);
            // The first that lowers the cost is made: the candidates are scored side by
            // side on the cores, and counted as if one after another.
            let candidates: Vec<Vec<Step>> = ranked
                .iter()
                .take(SCORED_PER_POSITION)
                .map(|&(_, change)| apply(&self.tour, change))
                .collect();
            let better = self.cost - 1e-9;
            let at_once = run.problem().caches();
            if let Some((index, candidate_cost)) =
                run.evaluate_until(&candidates, at_once, |cost| cost < better)
            {
                let change = ranked[index].1;
                let candidate = candidates
                    .into_iter()
                    .nth(index)
                    .expect("a scored candidate");
                let (low, high) = match change {
                    Move::Reverse { from, to } => (from, to),
                    Move::Relocate { from, to, gap, .. } => (from.min(gap), to.max(gap)),
                };
                self.tour = candidate;
                self.cost = candidate_cost;
                run.problem().pin(&self.tour);
                self.reindex();
                for index in [
                    low.saturating_sub(1),
                    low,
                    high.min(n - 1),
                    (high + 1).min(n - 1),
                ] {
                    self.push(self.tour[index].pass);
                }
                self.push(pass);
            }
        }
    }
}

/// The cheapest descent of the race (the earliest on ties).
fn cheapest(descents: Vec<Descent>) -> Descent {
    descents
        .into_iter()
        .reduce(|kept, descent| {
            if descent.cost < kept.cost {
                descent
            } else {
                kept
            }
        })
        .expect("at least one start")
}

impl<'a> Optimizer<JointProblem<'a>> for JointSearch {
    fn name(&self) -> &'static str {
        "joint order and returns (ours)"
    }

    fn start(&mut self, run: &mut Search<JointProblem<'a>>) {
        let problem = run.problem();
        self.neighbours = nearest_ends(problem.ordering, NEIGHBOURS, |end, other| {
            other / 2 != end / 2
        });
        let starts = std::mem::take(&mut self.starts);
        let n = starts[0].len();
        let neighbours = &self.neighbours;
        let race = self.race_evaluations;
        let racing = starts.len() > 1;
        // A start's descent overruns its share of the race by at most one position's
        // candidates; while that fits each branch's share of the budget, the race runs on
        // the cores and ends as it would here, start after start (`branch_out`).
        let fits_in_branches = run.remaining_evaluations().is_none_or(|left| {
            race + SCORED_PER_POSITION as u64 <= left / starts.len().max(1) as u64
        });
        let mut leader = if racing && fits_in_branches {
            // Each start on a core of its own with its own split buffers.
            let copies: Vec<JointProblem<'a>> = starts.iter().map(|_| problem.fork()).collect();
            let problems: Vec<&JointProblem<'a>> = copies.iter().collect();
            let descents = run.branch_out(&problems, u64::MAX, |k, branch| {
                let start = &starts[k];
                let cost = branch.evaluate(start);
                let mut descent = Descent::new(start.clone(), cost, 0..n);
                let until = branch.evaluations() + race;
                descent.run(branch, neighbours, until);
                descent
            });
            cheapest(descents)
        } else {
            // Here, start after start (one start, or a budget too small to share out).
            let mut descents = Vec::new();
            for start in starts {
                let cost = run.evaluate(&start);
                let mut descent = Descent::new(start, cost, 0..n);
                let until = if racing {
                    run.evaluations() + race
                } else {
                    u64::MAX
                };
                descent.run(run, neighbours, until);
                descents.push(descent);
            }
            cheapest(descents)
        };
        if !leader.is_done() {
            leader.run(run, neighbours, u64::MAX);
        }
        if n < 8 {
            run.declare_converged();
        }
    }

    fn step(&mut self, run: &mut Search<JointProblem<'a>>) {
        if self.petals && run.best_cost() != self.petals_failed_at {
            if self.petal_round(run) {
                return;
            }
            self.petals_failed_at = run.best_cost();
        }
        let incumbent = run.best_solution().to_vec();
        let n = incumbent.len();
        let span = KICK_SPAN.min(n - 2);
        // Three distinct cuts (a step that evaluates nothing would end the run).
        let mut tries = 0;
        let (a, b, c) = loop {
            tries += 1;
            if tries > 100 {
                run.evaluate(&incumbent);
                return;
            }
            let first = 1 + below(run.stream(), n - 1 - span);
            let mut cuts: Vec<usize> = (0..3)
                .map(|k| {
                    if k == 0 {
                        first
                    } else {
                        first + 1 + below(run.stream(), span)
                    }
                })
                .collect();
            cuts.sort_unstable();
            cuts.dedup();
            if let [a, b, c] = cuts[..] {
                break (a, b, c);
            }
        };
        let c = c.min(n);
        let mut kicked = Vec::with_capacity(n);
        kicked.extend_from_slice(&incumbent[..a]);
        kicked.extend_from_slice(&incumbent[b..c]);
        kicked.extend_from_slice(&incumbent[a..b]);
        kicked.extend_from_slice(&incumbent[c..]);
        let touched: Vec<usize> = [a - 1, a, b - 1, b.min(n - 1), c - 1, c.min(n - 1)]
            .iter()
            .map(|&index| kicked[index].pass)
            .collect();
        let cost = run.evaluate(&kicked);
        Descent::new(kicked, cost, touched).run(run, &self.neighbours, u64::MAX);
    }
}
