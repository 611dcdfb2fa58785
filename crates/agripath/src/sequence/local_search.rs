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
//!    - The neighbour lists hold the 10 nearest ends and the 6 nearest ends in other fields.
//! 3. Iterated local search: a seeded double-bridge kick, then 1-2 again; a kick is kept only
//!    when the tour gets cheaper. The number of kicks is the budget: the iterations of
//!    `swarm`'s Runner, which drives [`IteratedLocalSearch`] like every other search.

use swarm::{Optimizer, Runner, Termination};

use super::greedy::greedy_with_starts;
use super::tour::{End, OrderingProblem, Start, Step};

/// Positions examined after a kick before giving up on it.
const KICK_MOVES: usize = 400;

/// Nearest ends in other fields kept per end.
const OTHER_FIELD_NEIGHBOURS: usize = 6;

/// Nearest ends kept per end.
const NEIGHBOURS: usize = 10;
/// Greedy construction is O(n²) cost evaluations per start; above this it is skipped.
const GREEDY_LIMIT: usize = 1000;

#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LocalSearchSettings {
    /// Double-bridge kicks of the iterated local search.
    pub kicks: usize,
    pub seed: u64,
}

impl Default for LocalSearchSettings {
    fn default() -> Self {
        Self {
            kicks: 400,
            seed: 1,
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

/// Marker for the start point in edge costs.
const START: End = usize::MAX;

struct Search<'a, 'b> {
    problem: &'a OrderingProblem<'b>,
    tour: Vec<Step>,
    position: Vec<usize>,
    neighbours: &'a [Vec<End>],
    /// The group (field) of each pass.
    groups: &'a [usize],
    closed: bool,
}

impl Search<'_, '_> {
    fn edge(&self, from: Option<End>, to: Option<End>) -> f64 {
        match (from, to) {
            (Some(START), Some(to)) => self.problem.cost_from_start(to),
            (Some(from), Some(to)) => self.problem.cost(from, to),
            _ => 0.0,
        }
    }

    /// The end the flight comes from before position `p`.
    fn previous(&self, p: usize) -> Option<End> {
        if p > 0 {
            Some(self.tour[p - 1].exit())
        } else if self.closed {
            Some(self.tour[self.tour.len() - 1].exit())
        } else {
            Some(START)
        }
    }

    /// The end the flight goes to after position `q`.
    fn next(&self, q: usize) -> Option<End> {
        if q + 1 < self.tour.len() {
            Some(self.tour[q + 1].entry())
        } else if self.closed {
            Some(self.tour[0].entry())
        } else {
            None
        }
    }

    fn reindex(&mut self) {
        for (index, step) in self.tour.iter().enumerate() {
            self.position[step.pass] = index;
        }
    }

    /// Gain of reversing positions p..=q (positive = cheaper).
    fn reversal_gain(&self, p: usize, q: usize) -> f64 {
        let n = self.tour.len();
        if self.closed && p == 0 && q == n - 1 {
            return 0.0;
        }
        let (before, after) = (self.previous(p), self.next(q));
        let old = self.edge(before, Some(self.tour[p].entry()))
            + self.edge(Some(self.tour[q].exit()), after);
        let new = self.edge(before, Some(self.tour[q].exit()))
            + self.edge(Some(self.tour[p].entry()), after);
        old - new
    }

    fn reverse(&mut self, p: usize, q: usize) {
        self.tour[p..=q].reverse();
        for step in &mut self.tour[p..=q] {
            *step = step.flipped();
        }
        self.reindex();
    }

    /// The best 2-opt move at the transfer into position `p`, applied if it improves the
    /// tour. Returns the range reversed.
    fn two_opt_at(&mut self, p: usize) -> Option<(usize, usize)> {
        let mut candidates: Vec<(usize, usize)> = vec![(p, p)];
        if let Some(before) = self.previous(p).filter(|end| *end != START) {
            for &end in &self.neighbours[before] {
                let q = self.position[end / 2];
                if q > p && self.tour[q].exit() == end {
                    candidates.push((p, q));
                }
            }
        }
        for &end in &self.neighbours[self.tour[p].entry()] {
            let q = self.position[end / 2];
            if q < p && self.tour[q].entry() == end {
                candidates.push((q, p - 1));
            }
        }
        let (gain, from, to) = candidates
            .into_iter()
            .map(|(from, to)| (self.reversal_gain(from, to), from, to))
            .max_by(|a, b| a.0.total_cmp(&b.0))?;
        (gain > 1e-9).then(|| {
            self.reverse(from, to);
            (from, to)
        })
    }

    /// The best Or-opt move of a chain of 1-3 passes starting at position `i`, applied if it
    /// improves the tour. Returns the positions the chain now occupies.
    fn or_opt_at(&mut self, i: usize) -> Option<(usize, usize)> {
        let n = self.tour.len();
        if n < 3 {
            return None;
        }
        let mut best: Option<(f64, usize, usize, bool)> = None;
        // Chains of 1-3 passes, and the whole run of passes of the same field from `i`: moving
        // a field's block (either way round) reorders the fields without undoing their
        // boustrophedon.
        let block_end = (i..n)
            .take_while(|&k| self.groups[self.tour[k].pass] == self.groups[self.tour[i].pass])
            .last()
            .unwrap_or(i);
        // And chains [i, q) whose removal joins the flight before i to a near end at q: the
        // or-3opt segment moves that short chains cannot make.
        let mut lengths: Vec<usize> = (1..=3usize)
            .chain(std::iter::once(block_end + 1 - i))
            .collect();
        if let Some(before) = self.previous(i).filter(|end| *end != START) {
            for &end in &self.neighbours[before] {
                let q = self.position[end / 2];
                if q > i + 3 && self.tour[q].entry() == end && q - i <= n / 2 {
                    lengths.push(q - i);
                }
            }
        }
        for length in lengths {
            let j = i + length - 1;
            if j >= n || (self.closed && length >= n) {
                continue;
            }
            if let Some((gain, insert_at, reversed)) = self.best_insertion(i, j) {
                if best.is_none_or(|(best_gain, ..)| gain > best_gain) {
                    best = Some((gain, j, insert_at, reversed));
                }
            }
        }
        let (gain, j, insert_at, reversed) = best?;
        if gain <= 1e-9 {
            return None;
        }
        let length = j - i + 1;
        let mut chain: Vec<Step> = self.tour.drain(i..=j).collect();
        if reversed {
            chain.reverse();
            chain.iter_mut().for_each(|step| *step = step.flipped());
        }
        // `insert_at` indexes the tour before removal.
        let at = if insert_at > j {
            insert_at - length
        } else {
            insert_at
        };
        self.tour.splice(at..at, chain);
        self.reindex();
        Some((at, at + length - 1))
    }

    /// Best place to move chain i..=j to: (gain, insertion index before removal, reversed).
    fn best_insertion(&self, i: usize, j: usize) -> Option<(f64, usize, bool)> {
        let n = self.tour.len();
        if self.closed && i == 0 && j == n - 1 {
            return None;
        }
        let (before, after) = (self.previous(i), self.next(j));
        let entry = self.tour[i].entry();
        let exit = self.tour[j].exit();
        let removed = self.edge(before, Some(entry)) + self.edge(Some(exit), after)
            - self.edge(before, after);
        let mut best: Option<(f64, usize, bool)> = None;
        let mut consider = |k: usize, this: &Self| {
            // Insert before position k (k == n: at the end). Positions i..=j+1 change nothing.
            if (i..=j + 1).contains(&k) {
                return;
            }
            let left = if k == 0 {
                this.previous(0)
            } else {
                Some(this.tour[k - 1].exit())
            };
            let right = if k < n {
                Some(this.tour[k].entry())
            } else {
                this.next(n - 1)
            };
            if this.closed && k == 0 {
                return; // the same gap as k == n
            }
            let base = this.edge(left, right);
            for (reversed, first, last) in [(false, entry, exit), (true, exit, entry)] {
                let added = this.edge(left, Some(first)) + this.edge(Some(last), right) - base;
                let gain = removed - added;
                if best.is_none_or(|(best_gain, _, _)| gain > best_gain) {
                    best = Some((gain, k, reversed));
                }
            }
        };
        for &end in self.neighbours[entry].iter().chain(&self.neighbours[exit]) {
            let q = self.position[end / 2];
            consider(q, self);
            consider(q + 1, self);
        }
        best
    }

    /// Local search to a local optimum, looking only around `active` passes and around
    /// every move made (don't-look bits): a kick costs work near its cuts, not a whole sweep.
    fn descend(&mut self, active: impl IntoIterator<Item = usize>, mut budget: usize) {
        let n = self.tour.len();
        let mut queued = vec![false; n];
        let mut queue: Vec<usize> = Vec::new();
        let wake = |pass: usize, queue: &mut Vec<usize>, queued: &mut Vec<bool>| {
            if !queued[pass] {
                queued[pass] = true;
                queue.push(pass);
            }
        };
        for pass in active {
            wake(pass, &mut queue, &mut queued);
        }
        while let Some(pass) = queue.pop() {
            queued[pass] = false;
            if budget == 0 {
                break;
            }
            budget -= 1;
            let p = self.position[pass];
            let mut changed = self.two_opt_at(p);
            if changed.is_none() && p + 1 < n {
                changed = self.two_opt_at(p + 1);
            }
            if changed.is_none() {
                changed = self.or_opt_at(p);
            }
            if let Some((from, to)) = changed {
                for position in [from.saturating_sub(1), from, to, (to + 1).min(n - 1)] {
                    let touched = self.tour[position].pass;
                    wake(touched, &mut queue, &mut queued);
                }
                wake(pass, &mut queue, &mut queued);
            }
        }
    }
}

/// For every end, its `count` nearest ends that `accept(end, other)` lets through, by planar
/// distance, through a uniform grid.
fn nearest_ends(
    problem: &OrderingProblem,
    count: usize,
    accept: impl Fn(End, End) -> bool,
) -> Vec<Vec<End>> {
    let ends = 2 * problem.passes();
    let points: Vec<(f64, f64)> = (0..ends)
        .map(|end| {
            let point = problem.point(end);
            (point.x, point.y)
        })
        .collect();
    let (mut min_x, mut min_y, mut max_x, mut max_y) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for &(x, y) in &points {
        min_x = min_x.min(x);
        min_y = min_y.min(y);
        max_x = max_x.max(x);
        max_y = max_y.max(y);
    }
    let span = (max_x - min_x).max(max_y - min_y).max(1e-9);
    let cells_per_side = ((ends as f64 / 4.0).sqrt().ceil() as usize).max(1);
    let cell = span / cells_per_side as f64 * (1.0 + 1e-9);
    let index = |x: f64, y: f64| {
        (
            (((x - min_x) / cell) as usize).min(cells_per_side - 1),
            (((y - min_y) / cell) as usize).min(cells_per_side - 1),
        )
    };
    let mut grid: Vec<Vec<End>> = vec![Vec::new(); cells_per_side * cells_per_side];
    for (end, &(x, y)) in points.iter().enumerate() {
        let (column, row) = index(x, y);
        grid[row * cells_per_side + column].push(end);
    }
    (0..ends)
        .map(|end| {
            let (x, y) = points[end];
            let (column, row) = index(x, y);
            let mut found: Vec<(f64, End)> = Vec::new();
            let mut ring = 0usize;
            loop {
                let low_c = column.saturating_sub(ring);
                let high_c = (column + ring).min(cells_per_side - 1);
                let low_r = row.saturating_sub(ring);
                let high_r = (row + ring).min(cells_per_side - 1);
                for r in low_r..=high_r {
                    for c in low_c..=high_c {
                        if r.abs_diff(row) != ring && c.abs_diff(column) != ring {
                            continue; // inner cells were searched in earlier rings
                        }
                        for &other in &grid[r * cells_per_side + c] {
                            if accept(end, other) {
                                let (ox, oy) = points[other];
                                found.push(((ox - x).hypot(oy - y), other));
                            }
                        }
                    }
                }
                // Only the `count` nearest so far can end in the answer: later rings are farther
                // than everything already searched.
                let by_distance =
                    |a: &(f64, End), b: &(f64, End)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
                if found.len() > count {
                    found.select_nth_unstable_by(count - 1, by_distance);
                    found.truncate(count);
                }
                // Everything within `ring` cells is now known.
                let covered = ring as f64 * cell;
                let complete =
                    found.len() >= count && found.iter().all(|(distance, _)| *distance <= covered);
                let exhausted = low_c == 0
                    && low_r == 0
                    && high_c == cells_per_side - 1
                    && high_r == cells_per_side - 1;
                if complete || exhausted {
                    break;
                }
                ring += 1;
            }
            found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            found.into_iter().map(|(_, other)| other).collect()
        })
        .collect()
}

/// Field-by-field boustrophedon: `groups` lists each field's passes in scan-line order.
pub fn boustrophedon(problem: &OrderingProblem, groups: &[Vec<usize>]) -> Vec<Step> {
    if groups.iter().filter(|group| !group.is_empty()).count() > LARGE_FARM_FIELDS {
        return boustrophedon_by_grid(problem, groups);
    }
    let mut remaining: Vec<usize> = (0..groups.len())
        .filter(|&g| !groups[g].is_empty())
        .collect();
    let mut tour: Vec<Step> = Vec::with_capacity(problem.passes());
    while !remaining.is_empty() {
        // Each field can be flown from either end of its line order, starting either way.
        let mut best: Option<(f64, usize, Vec<Step>)> = None;
        for (slot, &group) in remaining.iter().enumerate() {
            // Variants in the order (forwards, backwards) × (first pass as is, reversed).
            for variant in [0, 2, 1, 3] {
                let steps = block_steps(&groups[group], variant);
                let cost = match tour.last() {
                    Some(previous) => problem.cost(previous.exit(), steps[0].entry()),
                    None => problem.cost_from_start(steps[0].entry()),
                };
                if best
                    .as_ref()
                    .is_none_or(|(best_cost, _, _)| cost < *best_cost)
                {
                    best = Some((cost, slot, steps));
                }
            }
        }
        let (_, slot, steps) = best.expect("a field remains");
        remaining.remove(slot);
        tour.extend(steps);
    }
    tour
}

/// Above this many fields, the constructions that compare every field with every other
/// (O(F²) per step) give way to ones that look only at the nearest fields: a farm of 10,000
/// fields took hours before (docs/limits.md).
pub const LARGE_FARM_FIELDS: usize = 1000;

/// Planar nearest candidates weighed by the real transfer cost in the scalable construction.
const NEAREST_BLOCKS: usize = 16;

/// [`boustrophedon`] for large farms: the next field is the cheapest of the 16 whose entry
/// ends are nearest (planar) to the current exit, found through a uniform grid, instead of
/// the cheapest of all. Same blocks, same variants, O(F · 16) transfer costs.
fn boustrophedon_by_grid(problem: &OrderingProblem, groups: &[Vec<usize>]) -> Vec<Step> {
    // Every (field, variant) entry, placed on a grid.
    let mut candidates: Vec<(usize, usize, End, f64, f64)> = Vec::new();
    let mut first_slot = vec![0; groups.len()];
    for (group, passes) in groups
        .iter()
        .enumerate()
        .filter(|(_, passes)| !passes.is_empty())
    {
        first_slot[group] = candidates.len();
        for variant in [0, 2, 1, 3] {
            let first = if variant & 1 == 1 {
                passes[passes.len() - 1]
            } else {
                passes[0]
            };
            let entry = Step {
                pass: first,
                reversed: variant & 2 == 2,
            }
            .entry();
            let point = problem.point(entry);
            candidates.push((group, variant, entry, point.x, point.y));
        }
    }
    let (min_x, min_y, max_x, max_y) = candidates.iter().fold(
        (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
        |(a, b, c, d), &(_, _, _, x, y)| (a.min(x), b.min(y), c.max(x), d.max(y)),
    );
    let side = ((candidates.len() as f64 / 4.0).sqrt().ceil() as usize).max(1);
    let cell = ((max_x - min_x).max(max_y - min_y) / side as f64).max(1e-9) * (1.0 + 1e-9);
    let index = |x: f64, y: f64| {
        (
            (((x - min_x) / cell).max(0.0) as usize).min(side - 1),
            (((y - min_y) / cell).max(0.0) as usize).min(side - 1),
        )
    };
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); side * side];
    for (slot, &(_, _, _, x, y)) in candidates.iter().enumerate() {
        let (column, row) = index(x, y);
        grid[row * side + column].push(slot);
    }
    let mut used = vec![false; groups.len()];
    let mut left = candidates.len() / 4;
    let mut tour: Vec<Step> = Vec::with_capacity(problem.passes());
    while left > 0 {
        let cost_of = |slot: usize, tour: &[Step]| match tour.last() {
            Some(previous) => problem.cost(previous.exit(), candidates[slot].2),
            None => problem.cost_from_start(candidates[slot].2),
        };
        let chosen = match tour.last() {
            // The first field: the cheapest of all, as in the exact construction.
            None => (0..candidates.len())
                .min_by(|&a, &b| cost_of(a, &tour).total_cmp(&cost_of(b, &tour)))
                .expect("candidates exist"),
            Some(previous) => {
                let here = problem.point(previous.exit());
                let (column, row) = index(here.x, here.y);
                let mut found: Vec<(f64, usize)> = Vec::new();
                let mut ring = 0usize;
                loop {
                    let (low_c, high_c) =
                        (column.saturating_sub(ring), (column + ring).min(side - 1));
                    let (low_r, high_r) = (row.saturating_sub(ring), (row + ring).min(side - 1));
                    for r in low_r..=high_r {
                        for c in low_c..=high_c {
                            if r.abs_diff(row) != ring && c.abs_diff(column) != ring {
                                continue;
                            }
                            for &slot in &grid[r * side + c] {
                                let (_, _, _, x, y) = candidates[slot];
                                found.push(((x - here.x).hypot(y - here.y), slot));
                            }
                        }
                    }
                    let covered = ring as f64 * cell;
                    let enough = found.len() >= NEAREST_BLOCKS
                        && found.iter().filter(|(d, _)| *d <= covered).count() >= NEAREST_BLOCKS;
                    let everywhere =
                        low_c == 0 && low_r == 0 && high_c == side - 1 && high_r == side - 1;
                    if enough || (everywhere && !found.is_empty()) {
                        break;
                    }
                    ring += 1;
                }
                found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                found
                    .iter()
                    .take(NEAREST_BLOCKS)
                    .map(|&(_, slot)| slot)
                    .min_by(|&a, &b| {
                        cost_of(a, &tour)
                            .total_cmp(&cost_of(b, &tour))
                            .then(a.cmp(&b))
                    })
                    .expect("a field is left")
            }
        };
        let (group, variant, ..) = candidates[chosen];
        tour.extend(block_steps(&groups[group], variant));
        used[group] = true;
        left -= 1;
        // Take the field's four entries off the grid.
        for (slot, &(_, _, _, x, y)) in candidates
            .iter()
            .enumerate()
            .skip(first_slot[group])
            .take(4)
        {
            let (column, row) = index(x, y);
            grid[row * side + column].retain(|&s| s != slot);
        }
    }
    debug_assert!(used
        .iter()
        .enumerate()
        .all(|(g, &u)| u || groups[g].is_empty()));
    tour
}

/// Double-bridge kicks of the block-order search.
const BLOCK_KICKS: usize = 300;

/// Most fields for which the exact order of whole field blocks is searched.
const EXACT_FIELD_ORDER_LIMIT: usize = 10;

/// A field's passes flown as one boustrophedon block: `variant` bit 0 runs the lines
/// backwards, bit 1 flies the first pass reversed.
fn block(problem: &OrderingProblem, passes: &[usize], variant: usize) -> (Vec<Step>, f64) {
    let steps = block_steps(passes, variant);
    let internal = steps
        .windows(2)
        .map(|pair| problem.cost(pair[0].exit(), pair[1].entry()))
        .sum();
    (steps, internal)
}

/// The steps of a block (see [`block`]), without its cost.
fn block_steps(passes: &[usize], variant: usize) -> Vec<Step> {
    let mut order = passes.to_vec();
    if variant & 1 == 1 {
        order.reverse();
    }
    order
        .iter()
        .enumerate()
        .map(|(index, &pass)| Step {
            pass,
            reversed: (variant & 2 == 2) ^ (index % 2 == 1),
        })
        .collect()
}

/// Every field's block in each of its four variants, with the cost inside it.
struct FieldBlocks(Vec<Vec<(Vec<Step>, f64)>>);

/// A field and one of its four block variants.
type Placed = (usize, usize);

impl FieldBlocks {
    fn new(problem: &OrderingProblem, fields: &[&Vec<usize>]) -> Self {
        Self(
            fields
                .iter()
                .map(|passes| {
                    (0..4)
                        .map(|variant| block(problem, passes, variant))
                        .collect()
                })
                .collect(),
        )
    }

    fn entry(&self, (field, variant): Placed) -> End {
        self.0[field][variant].0[0].entry()
    }

    fn exit(&self, (field, variant): Placed) -> End {
        self.0[field][variant]
            .0
            .last()
            .expect("a block has passes")
            .exit()
    }

    /// Transfer cost inside the block.
    fn inside(&self, (field, variant): Placed) -> f64 {
        self.0[field][variant].1
    }

    /// The passes of blocks flown in `order`.
    fn steps(&self, order: &[Placed]) -> Vec<Step> {
        order
            .iter()
            .flat_map(|&(field, variant)| self.0[field][variant].0.iter().copied())
            .collect()
    }
}

/// A double-bridge kick: cut `items` at three random places and swap the middle two parts.
/// `None` when two cuts coincide (the caller skips that kick).
fn double_bridge<T: Copy>(
    items: &[T],
    stream: &mut swarm::RunStream,
) -> Option<(Vec<T>, [usize; 3])> {
    let n = items.len();
    let mut cuts: Vec<usize> = if n > LOCAL_KICKS_ABOVE {
        let first = 1 + swarm::below(stream, n - 1 - LOCAL_KICK_SPAN);
        (0..3)
            .map(|k| {
                if k == 0 {
                    first
                } else {
                    first + 1 + swarm::below(stream, LOCAL_KICK_SPAN)
                }
            })
            .collect()
    } else {
        (0..3).map(|_| 1 + swarm::below(stream, n - 1)).collect()
    };
    cuts.sort_unstable();
    cuts.dedup();
    if cuts.len() < 3 {
        return None;
    }
    let (a, b, c) = (cuts[0], cuts[1], cuts[2]);
    let mut kicked = Vec::with_capacity(n);
    kicked.extend_from_slice(&items[..a]);
    kicked.extend_from_slice(&items[b..c]);
    kicked.extend_from_slice(&items[a..b]);
    kicked.extend_from_slice(&items[c..]);
    Some((kicked, [a, b, c]))
}

/// Whole field blocks in the best order and variant (Held-Karp over at most
/// `EXACT_FIELD_ORDER_LIMIT` fields): exact within that family of tours.
pub fn exact_field_order(problem: &OrderingProblem, groups: &[Vec<usize>]) -> Option<Vec<Step>> {
    let fields: Vec<&Vec<usize>> = groups.iter().filter(|group| !group.is_empty()).collect();
    let count = fields.len();
    if count == 0 || count > EXACT_FIELD_ORDER_LIMIT {
        return None;
    }
    let blocks = FieldBlocks::new(problem, &fields);
    let entry = |field: usize, variant: usize| blocks.entry((field, variant));
    let exit = |field: usize, variant: usize| blocks.exit((field, variant));
    let states = count * 4;
    let closed = problem.start == Start::Free;
    let mut best: Option<(f64, Vec<(usize, usize)>)> = None;
    // A closed tour can start anywhere: fix field 0 first, in each of its variants.
    let first_choices: Vec<Option<usize>> = if closed {
        (0..4).map(Some).collect()
    } else {
        vec![None]
    };
    for first in first_choices {
        let mut cost = vec![f64::INFINITY; (1 << count) * states];
        let mut parent = vec![usize::MAX; (1 << count) * states];
        for field in 0..count {
            for variant in 0..4 {
                let allowed = match first {
                    Some(first_variant) => field == 0 && variant == first_variant,
                    None => true,
                };
                if allowed {
                    let start = if closed {
                        0.0
                    } else {
                        problem.cost_from_start(entry(field, variant))
                    };
                    cost[(1 << field) * states + field * 4 + variant] =
                        start + blocks.inside((field, variant));
                }
            }
        }
        for mask in 1usize..(1 << count) {
            for state in 0..states {
                let here = cost[mask * states + state];
                if !here.is_finite() {
                    continue;
                }
                let (field, variant) = (state / 4, state % 4);
                for next in (0..count).filter(|next| mask & (1 << next) == 0) {
                    for (next_variant, (_, internal)) in blocks.0[next].iter().enumerate() {
                        let value = here
                            + problem.cost(exit(field, variant), entry(next, next_variant))
                            + internal;
                        let slot = (mask | (1 << next)) * states + next * 4 + next_variant;
                        if value < cost[slot] {
                            cost[slot] = value;
                            parent[slot] = mask * states + state;
                        }
                    }
                }
            }
        }
        let full = (1 << count) - 1;
        for state in 0..states {
            let mut total = cost[full * states + state];
            if let Some(first_variant) = first {
                total += problem.cost(exit(state / 4, state % 4), entry(0, first_variant));
            }
            if best
                .as_ref()
                .is_none_or(|(best_total, _)| total < *best_total)
            {
                let mut order = Vec::with_capacity(count);
                let mut slot = full * states + state;
                while slot != usize::MAX {
                    let state = slot % states;
                    order.push((state / 4, state % 4));
                    slot = parent[slot];
                }
                order.reverse();
                best = Some((total, order));
            }
        }
    }
    let (_, order) = best?;
    Some(blocks.steps(&order))
}

/// Whole field blocks ordered by local search over (field, corner) pairs, for farms with more
/// fields than the exact order handles: starting from the nearest-first chain, move one block
/// to any other place in any of its four variants, or fly a run of blocks backwards (2-opt),
/// while that shortens the tour.
pub fn block_local_search(
    problem: &OrderingProblem,
    groups: &[Vec<usize>],
    reversals: bool,
    seed: u64,
) -> Option<Vec<Step>> {
    let fields: Vec<&Vec<usize>> = groups.iter().filter(|group| !group.is_empty()).collect();
    let count = fields.len();
    // Small farms: the exact order; very large ones: the block moves cost O(F²) a round and
    // the pass-level search on neighbour lists takes over.
    if count <= EXACT_FIELD_ORDER_LIMIT || count > LARGE_FARM_FIELDS {
        return None;
    }
    let blocks = FieldBlocks::new(problem, &fields);
    let entry = |placed: Placed| blocks.entry(placed);
    let exit = |placed: Placed| blocks.exit(placed);
    let closed = problem.start == Start::Free;
    let total = |order: &[(usize, usize)]| -> f64 {
        let inside: f64 = order.iter().map(|&placed| blocks.inside(placed)).sum();
        let between: f64 = order
            .windows(2)
            .map(|pair| problem.cost(exit(pair[0]), entry(pair[1])))
            .sum();
        let ends = if closed {
            problem.cost(exit(order[order.len() - 1]), entry(order[0]))
        } else {
            problem.cost_from_start(entry(order[0]))
        };
        inside + between + ends
    };
    // Nearest-first chain as the start.
    let mut order: Vec<(usize, usize)> = Vec::with_capacity(count);
    let mut left: Vec<usize> = (0..count).collect();
    while !left.is_empty() {
        let (slot, choice) = left
            .iter()
            .enumerate()
            .flat_map(|(slot, &field)| (0..4).map(move |variant| (slot, (field, variant))))
            .min_by(|a, b| {
                let cost = |choice: (usize, usize)| match order.last() {
                    Some(&last) => problem.cost(exit(last), entry(choice)),
                    None => problem.cost_from_start(entry(choice)),
                };
                cost(a.1).total_cmp(&cost(b.1))
            })
            .expect("a field is left");
        left.remove(slot);
        order.push(choice);
    }
    // Cost of the link from block a to block b (None: the start, or nothing after the end).
    let link = |from: Option<(usize, usize)>, to: Option<(usize, usize)>| -> f64 {
        match (from, to) {
            (Some(a), Some(b)) => problem.cost(exit(a), entry(b)),
            (None, Some(b)) if !closed => problem.cost_from_start(entry(b)),
            _ => 0.0,
        }
    };
    // The blocks on either side of a gap in a sequence (closed tours wrap around).
    type Block = Option<(usize, usize)>;
    let around = |sequence: &[(usize, usize)], gap: usize| -> (Block, Block) {
        let n = sequence.len();
        let before = if gap > 0 {
            Some(sequence[gap - 1])
        } else if closed && n > 0 {
            Some(sequence[n - 1])
        } else {
            None
        };
        let after = if gap < n {
            Some(sequence[gap])
        } else if closed && n > 0 {
            Some(sequence[0])
        } else {
            None
        };
        (before, after)
    };
    let start_cost = total(&order);
    // Move one block (any variant) to the best other gap while that gains; O(F² · 4) a round.
    let improve = |order: &mut Vec<(usize, usize)>| {
        for _ in 0..50 {
            let mut improved = false;
            for from in 0..count {
                let moving = order[from];
                let (before, _) = around(order, from);
                let (_, after) = around(order, from + 1);
                let removal =
                    link(before, Some(moving)) + link(Some(moving), after) - link(before, after);
                let mut without = order.clone();
                without.remove(from);
                let mut choice: Option<(f64, usize, (usize, usize))> = None;
                for to in 0..=without.len() {
                    let (left, right) = around(&without, to);
                    let base = link(left, right);
                    for (variant, (_, internal)) in blocks.0[moving.0].iter().enumerate() {
                        let candidate = (moving.0, variant);
                        let added = link(left, Some(candidate)) + link(Some(candidate), right)
                            - base
                            + internal
                            - blocks.inside(moving);
                        let gain = removal - added;
                        if gain > 1e-9 && choice.is_none_or(|(best_gain, ..)| gain > best_gain) {
                            choice = Some((gain, to, candidate));
                        }
                    }
                }
                if let Some((_, to, candidate)) = choice {
                    without.insert(to, candidate);
                    *order = without;
                    improved = true;
                }
            }
            // 2-opt over blocks: fly a run of blocks in reverse order, each one backwards (its
            // entry and exit swap; its inside cost is unchanged, eq. 8 being symmetric).
            let backwards = |(field, variant): (usize, usize)| {
                let passes = blocks.0[field][variant].0.len();
                let last_reversed = (variant & 2 == 2) ^ passes.is_multiple_of(2);
                (field, (variant ^ 1) | (usize::from(!last_reversed) << 1))
            };
            for i in 0..if reversals { count } else { 0 } {
                for j in i + 1..count {
                    if closed && i == 0 && j == count - 1 {
                        continue;
                    }
                    let (before, _) = around(order, i);
                    let (_, after) = around(order, j + 1);
                    let old = link(before, Some(order[i])) + link(Some(order[j]), after);
                    let new = link(before, Some(backwards(order[j])))
                        + link(Some(backwards(order[i])), after);
                    if new < old - 1e-9 {
                        order[i..=j].reverse();
                        for item in &mut order[i..=j] {
                            *item = backwards(*item);
                        }
                        improved = true;
                    }
                }
            }
            if !improved {
                break;
            }
        }
    };
    improve(&mut order);
    // Iterated: double-bridge kicks on the block order, kept when the tour gets shorter.
    let mut best_cost = total(&order);
    let mut stream = swarm::run_stream(seed, 1);
    // A block-level descent costs O(F²) per round: fewer kicks on farms of many fields.
    let kicks = BLOCK_KICKS.min(500_000 / (count * count));
    for _ in 0..kicks {
        let Some((mut kicked, _)) = double_bridge(&order, &mut stream) else {
            continue;
        };
        improve(&mut kicked);
        let cost = total(&kicked);
        if cost < best_cost - 1e-9 {
            best_cost = cost;
            order = kicked;
        }
    }
    debug_assert!(total(&order) <= start_cost + 1e-6);
    Some(blocks.steps(&order))
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
    let runner = Runner::new(
        Termination::iterations(kick_budget(settings, n)),
        settings.seed,
    )
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
    incumbent: Vec<Step>,
    incumbent_cost: f64,
}

impl<'g> IteratedLocalSearch<'g> {
    /// The search over passes grouped by field in `groups`.
    pub fn new(groups: &'g [Vec<usize>], seed: u64) -> Self {
        Self {
            groups,
            seed,
            neighbours: Vec::new(),
            group_of: Vec::new(),
            incumbent: Vec::new(),
            incumbent_cost: f64::INFINITY,
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
        let mut search = Search {
            problem,
            position: vec![0; tour.len()],
            tour,
            neighbours: &self.neighbours,
            groups: &self.group_of,
            closed: problem.start == Start::Free,
        };
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
        let (n, groups) = (problem.passes(), self.groups);
        let mut starts = vec![boustrophedon(problem, groups)];
        starts.extend(exact_field_order(problem, groups));
        // Block relocation alone and with block reversals end in different local optima; both
        // are kept as starts and the local search decides.
        starts.extend(block_local_search(problem, groups, false, self.seed));
        starts.extend(block_local_search(problem, groups, true, self.seed));
        if n <= GREEDY_LIMIT {
            starts.push(greedy_with_starts(problem, 8));
        }
        self.group_of = vec![0; n];
        for (group, members) in groups.iter().enumerate() {
            for &pass in members {
                self.group_of[pass] = group;
            }
        }
        // Near ends of any other pass, and near ends in other fields: without the latter, a
        // field's own swath ends (a swath width apart) fill the list and moves between fields
        // are never tried.
        let group_of = &self.group_of;
        let mut neighbours = nearest_ends(problem, NEIGHBOURS, |end, other| other / 2 != end / 2);
        if groups.len() > 1 {
            let across = nearest_ends(problem, OTHER_FIELD_NEIGHBOURS, |end, other| {
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
        self.neighbours = neighbours;
        for start in starts {
            let tour = self.descend(problem, start, 0..n, 50 * n + 10_000);
            run.evaluate(&tour);
        }
        self.incumbent = run.best_solution().to_vec();
        self.incumbent_cost = run.best_cost();
        if n < 8 {
            // Too few passes for a double bridge's three cuts.
            run.declare_converged();
        }
    }

    fn step(&mut self, run: &mut swarm::Search<OrderingProblem<'a>>) {
        let problem = run.problem();
        let n = self.incumbent.len();
        let Some((kicked, [a, b, c])) = double_bridge(&self.incumbent, run.stream()) else {
            return;
        };
        let touched: Vec<usize> = [0, a - 1, a, b - 1, b, c - 1, c, n - 1]
            .iter()
            .map(|&i| kicked[i].pass)
            .collect();
        let tour = self.descend(problem, kicked, touched, KICK_MOVES);
        // Only a kick kept is handed to the Runner: a closed tour and its rotation cost the
        // same up to float noise but fly different open routes, so the Runner's best must be
        // the incumbent, not a tour a nanometre cheaper by summation order.
        let cost = problem.tour_cost(&tour);
        if cost < self.incumbent_cost - 1e-9 {
            self.incumbent_cost = run.evaluate(&tour);
            self.incumbent = tour;
        }
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
        for start in [
            Start::Free,
            Start::Fixed(GroundPoint {
                x: -50.0,
                y: 2000.0,
                ground_m: 0.0,
            }),
        ] {
            let problem = OrderingProblem::new(ends.clone(), start, &model);
            let exact = exact_field_order(&problem, &groups).unwrap();
            assert!(is_permutation(&exact, 9));
            let chained = boustrophedon(&problem, &groups);
            assert!(problem.tour_cost(&exact) <= problem.tour_cost(&chained) + 1e-9);
            // From the west the best order visits the fields west to east: 0, 2, 1.
            if let Start::Fixed(_) = start {
                let order: Vec<usize> = exact.iter().map(|step| step.pass / 3).collect();
                assert_eq!(order, [0, 0, 0, 2, 2, 2, 1, 1, 1]);
            }
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
        let problem = OrderingProblem::new(ends, Start::Free, &model);
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
