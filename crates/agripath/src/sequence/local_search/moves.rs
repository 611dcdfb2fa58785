//! Step 2 of `best`: local search to a local optimum of 2-opt with end flips and Or-opt on
//! oriented passes, driven by lists of the K nearest pass ends (see the parent module).

use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use super::super::tour::{End, OrderingProblem, Step};

/// Marker for the start point in edge costs.
pub(super) const START: End = usize::MAX;

pub(super) struct Search<'a, 'b> {
    pub(super) problem: &'a OrderingProblem<'b>,
    pub(super) tour: Vec<Step>,
    pub(super) position: Vec<usize>,
    pub(super) neighbours: &'a [Vec<End>],
    /// The group (field) of each pass.
    pub(super) groups: &'a [usize],
    /// The tour wraps around (`Start::Closed`).
    pub(super) closed: bool,
    /// The tour begins at the start point (`Start::Fixed`, `Start::From`).
    pub(super) from_start: bool,
    /// The tour ends at the start point (`Start::Fixed`).
    pub(super) home: bool,
    /// Whether the descent also makes Or-3opt moves (`three_opt.rs`); off only to measure
    /// and test what the move adds.
    pub(super) three_opt: bool,
    /// The descent's queue of passes to look at, and which passes are in it (kept between
    /// descents so that a kick allocates nothing).
    pub(super) queue: Vec<usize>,
    pub(super) queued: Vec<bool>,
    /// The gaps one [`Self::best_insertion`] has costed already.
    pub(super) gaps_costed: GapMarks,
}

/// Marks on the gaps of a tour (0..=n) for one call at a time: the near ends of a chain's two
/// ends name many gaps twice (a neighbour at q gives gaps q and q + 1, and so does one at
/// q + 1 for gap q + 1), and a gap costed once is enough (an equal gain never replaces
/// the first, so the moves are the same). Atomics with relaxed order, as plain as cells on
/// one thread: the move is chosen through `&self`, and the kick loop's buffers, which keep
/// them between descents, are shared with the threads of the constructions' descents.
#[derive(Debug, Default)]
pub(super) struct GapMarks {
    call: AtomicU32,
    marks: Vec<AtomicU32>,
}

impl GapMarks {
    /// Marks for `passes` passes at least (kept between descents: a kick allocates nothing).
    fn cover(&mut self, passes: usize) {
        if self.marks.len() <= passes {
            self.marks.resize_with(passes + 1, || AtomicU32::new(0));
        }
    }

    /// Starts a call: no gap is marked.
    fn clear(&self) {
        let call = self.call.load(Relaxed).wrapping_add(1);
        if call == 0 {
            self.marks.iter().for_each(|mark| mark.store(0, Relaxed));
            self.call.store(1, Relaxed);
        } else {
            self.call.store(call, Relaxed);
        }
    }

    /// Marks gap `gap`; whether it was unmarked in this call.
    fn first_time(&self, gap: usize) -> bool {
        let (call, mark) = (self.call.load(Relaxed), &self.marks[gap]);
        // A load and a store, not a swap: no other thread touches these marks meanwhile.
        let first = mark.load(Relaxed) != call;
        mark.store(call, Relaxed);
        first
    }
}

impl Search<'_, '_> {
    /// The cost of a transfer between two ends, either of which may be the start point;
    /// `None` (an open end of the path) costs nothing: that is the open path's dummy node,
    /// at zero cost from every end.
    pub(super) fn edge(&self, from: Option<End>, to: Option<End>) -> f64 {
        match (from, to) {
            (Some(START), Some(START)) => 0.0,
            (Some(START), Some(end)) | (Some(end), Some(START)) => {
                self.problem.cost_from_start(end)
            }
            (Some(from), Some(to)) => self.problem.cost(from, to),
            _ => 0.0,
        }
    }

    /// The end the flight comes from before position `p`.
    pub(super) fn previous(&self, p: usize) -> Option<End> {
        if p > 0 {
            Some(self.tour[p - 1].exit())
        } else if self.closed {
            Some(self.tour[self.tour.len() - 1].exit())
        } else if self.from_start {
            Some(START)
        } else {
            None
        }
    }

    /// The end the flight goes to after position `q`.
    pub(super) fn next(&self, q: usize) -> Option<End> {
        if q + 1 < self.tour.len() {
            Some(self.tour[q + 1].entry())
        } else if self.closed {
            Some(self.tour[0].entry())
        } else if self.home {
            Some(START)
        } else {
            None
        }
    }

    pub(super) fn reindex(&mut self) {
        self.reindex_range(0, self.tour.len());
    }

    /// Positions of the passes at `from..to` (a move changes only the stretch it touched).
    pub(super) fn reindex_range(&mut self, from: usize, to: usize) {
        for (index, step) in self.tour[from..to].iter().enumerate() {
            self.position[step.pass] = from + index;
        }
    }

    /// The cost of the transfer into position `p` (from the start point, the last pass of a
    /// closed tour, or nothing).
    fn transfer_into(&self, p: usize) -> f64 {
        self.edge(self.previous(p), Some(self.tour[p].entry()))
    }

    /// The cost of the transfer at gap `g` (0..=n): into position `g`, or for `g == n` out of
    /// the last pass (to the start point, the first pass of a closed tour, or nothing).
    fn gap_cost(&self, g: usize) -> f64 {
        let n = self.tour.len();
        if g < n {
            self.transfer_into(g)
        } else {
            self.edge(Some(self.tour[n - 1].exit()), self.next(n - 1))
        }
    }

    /// A double bridge in place: the stretches `a..b` and `b..c` (a < b < c ≤ n) swap
    /// places, each flown as it was. Returns the change in tour cost: three transfers change.
    /// With 0 < a and c < n the first and the last pass stay where they are; a = 0 or c = n
    /// (on a path with a free end there) changes the first or the last pass.
    pub(super) fn double_bridge(&mut self, a: usize, b: usize, c: usize) -> f64 {
        let old = self.gap_cost(a) + self.gap_cost(b) + self.gap_cost(c);
        self.tour[a..c].rotate_left(b - a);
        self.reindex_range(a, c);
        let new = self.gap_cost(a) + self.gap_cost(a + c - b) + self.gap_cost(c);
        new - old
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

    pub(super) fn reverse(&mut self, p: usize, q: usize) {
        self.tour[p..=q].reverse();
        for step in &mut self.tour[p..=q] {
            *step = step.flipped();
        }
        self.reindex_range(p, q + 1);
    }

    /// The best 2-opt move at the transfer into position `p`, applied if it improves the
    /// tour. Returns the range reversed and the gain.
    fn two_opt_at(&mut self, p: usize) -> Option<(usize, usize, f64)> {
        // The last of equal gains wins, in the order the candidates are listed.
        let mut best = (self.reversal_gain(p, p), p, p);
        let mut consider = |from: usize, to: usize, this: &Self| {
            let gain = this.reversal_gain(from, to);
            if gain >= best.0 {
                best = (gain, from, to);
            }
        };
        if let Some(before) = self.previous(p).filter(|end| *end != START) {
            for &end in &self.neighbours[before] {
                let q = self.position[end / 2];
                if q > p && self.tour[q].exit() == end {
                    consider(p, q, self);
                }
            }
        }
        for &end in &self.neighbours[self.tour[p].entry()] {
            let q = self.position[end / 2];
            if q < p && self.tour[q].entry() == end {
                consider(q, p - 1, self);
            }
        }
        // A free end of the path (the open path's dummy node, at zero cost from every end):
        // flying the whole head or the whole tail backwards changes one transfer only.
        if self.previous(0).is_none() && p > 0 {
            consider(0, p - 1, self);
        }
        if self.next(self.tour.len() - 1).is_none() {
            consider(p, self.tour.len() - 1, self);
        }
        let (gain, from, to) = best;
        (gain > 1e-9).then(|| {
            self.reverse(from, to);
            (from, to, gain)
        })
    }

    /// The best Or-opt move of a chain of 1-3 passes starting at position `i`, applied if it
    /// improves the tour. Returns the positions the chain now occupies and the gain.
    fn or_opt_at(&mut self, i: usize) -> Option<(usize, usize, f64)> {
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
        let mut consider = |length: usize, this: &Self| {
            let j = i + length - 1;
            if j >= n || length >= n {
                return;
            }
            if let Some((gain, insert_at, reversed)) = this.best_insertion(i, j) {
                if best.is_none_or(|(best_gain, ..)| gain > best_gain) {
                    best = Some((gain, j, insert_at, reversed));
                }
            }
        };
        for length in [1, 2, 3, block_end + 1 - i] {
            consider(length, self);
        }
        if let Some(before) = self.previous(i).filter(|end| *end != START) {
            for &end in &self.neighbours[before] {
                let q = self.position[end / 2];
                if q > i + 3 && self.tour[q].entry() == end && q - i <= n / 2 {
                    consider(q - i, self);
                }
            }
        }
        let (gain, j, insert_at, reversed) = best?;
        if gain <= 1e-9 {
            return None;
        }
        let length = j - i + 1;
        // Moving the chain is a rotation of the stretch between its place and its new one.
        let at = if insert_at > j {
            self.tour[i..insert_at].rotate_left(length);
            self.reindex_range(i, insert_at);
            insert_at - length
        } else {
            self.tour[insert_at..=j].rotate_right(length);
            self.reindex_range(insert_at, j + 1);
            insert_at
        };
        if reversed {
            self.reverse(at, at + length - 1);
        }
        Some((at, at + length - 1, gain))
    }

    /// Best place to move chain i..=j to: (gain, insertion index before removal, reversed).
    fn best_insertion(&self, i: usize, j: usize) -> Option<(f64, usize, bool)> {
        let n = self.tour.len();
        if i == 0 && j == n - 1 {
            return None; // the whole tour: only a reversal, which 2-opt makes
        }
        let (before, after) = (self.previous(i), self.next(j));
        let entry = self.tour[i].entry();
        let exit = self.tour[j].exit();
        let removed = self.edge(before, Some(entry)) + self.edge(Some(exit), after)
            - self.edge(before, after);
        let mut best: Option<(f64, usize, bool)> = None;
        self.gaps_costed.clear();
        let mut consider = |k: usize, this: &Self| {
            // Insert before position k (k == n: at the end). Positions i..=j+1 change nothing.
            if (i..=j + 1).contains(&k) || !this.gaps_costed.first_time(k) {
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
            if this.closed && (k == 0 || (i == 0 && k == n)) {
                // k == 0 is the same gap as k == n; and with the chain first, the gap at n
                // (after the last pass, before the first) is the chain's own place: costed
                // as a gap, it reported gains no move makes (found by the test below).
                return;
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
        // Free ends of the path: the chain may become its new first or last stretch.
        if self.previous(0).is_none() {
            consider(0, self);
        }
        if self.next(n - 1).is_none() {
            consider(n, self);
        }
        best
    }

    /// Local search to a local optimum, looking only around `active` passes and around
    /// every move made (don't-look bits): a kick costs work near its cuts, not a whole sweep.
    /// Returns the sum of the gains of the moves made.
    pub(super) fn descend(
        &mut self,
        active: impl IntoIterator<Item = usize>,
        mut budget: usize,
    ) -> f64 {
        let n = self.tour.len();
        self.gaps_costed.cover(n);
        let (mut queue, mut queued) = (
            std::mem::take(&mut self.queue),
            std::mem::take(&mut self.queued),
        );
        queue.clear();
        queued.clear();
        queued.resize(n, false);
        let wake = |pass: usize, queue: &mut Vec<usize>, queued: &mut Vec<bool>| {
            if !queued[pass] {
                queued[pass] = true;
                queue.push(pass);
            }
        };
        for pass in active {
            wake(pass, &mut queue, &mut queued);
        }
        let mut gained = 0.0;
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
            if changed.is_none() && self.three_opt {
                if let Some((from, middle, to, gain)) = self.three_opt_at(p) {
                    // The join between the two chains is a new transfer too.
                    for position in [middle.saturating_sub(1), middle.min(n - 1)] {
                        let touched = self.tour[position].pass;
                        wake(touched, &mut queue, &mut queued);
                    }
                    changed = Some((from, to, gain));
                }
            }
            if let Some((from, to, gain)) = changed {
                gained += gain;
                for position in [from.saturating_sub(1), from, to, (to + 1).min(n - 1)] {
                    let touched = self.tour[position].pass;
                    wake(touched, &mut queue, &mut queued);
                }
                wake(pass, &mut queue, &mut queued);
            }
        }
        (self.queue, self.queued) = (queue, queued);
        gained
    }
}

/// For every end, its `count` cheapest ends by eq. (8) that `accept(end, other)` lets
/// through, when the problem holds every end-to-end cost (up to 2,000 ends); else the nearest
/// by planar distance ([`nearest_ends`]). Eq. (8) adds 2h to a transfer that climbs out of a
/// field and goes round holes and obstacles, so the planar nearest ends across a hole or a
/// field edge are often not the cheap ones: on the open paths of the irregular farms of
/// `benches/ordering_vs_lkh.py`, lists by cost took the mean ratio to LKH from 1.0185 to 1.0122
/// (decision 0018).
pub fn cheapest_ends(
    problem: &OrderingProblem,
    count: usize,
    accept: impl Fn(End, End) -> bool,
) -> Vec<Vec<End>> {
    if !problem.has_cost_matrix() {
        return nearest_ends(problem, count, accept);
    }
    let ends = 2 * problem.passes();
    let by_cost = |a: &(f64, End), b: &(f64, End)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
    (0..ends)
        .map(|end| {
            let mut found: Vec<(f64, End)> = (0..ends)
                .filter(|&other| other != end && accept(end, other))
                .map(|other| (problem.cost(end, other), other))
                .collect();
            if found.len() > count {
                found.select_nth_unstable_by(count - 1, by_cost);
                found.truncate(count);
            }
            found.sort_by(by_cost);
            found.into_iter().map(|(_, other)| other).collect()
        })
        .collect()
}

/// For every end, its `count` nearest ends that `accept(end, other)` lets through, by planar
/// distance, through a uniform grid.
pub fn nearest_ends(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::drape::GroundPoint;
    use crate::sequence::tour::Start;
    use crate::sequence::TransferModel;

    /// The kick loop keeps or undoes a kick by the figures the search reports, without
    /// re-costing the tour: the in-place double bridge must report the change in tour cost,
    /// and a descent the sum of its gains, for every start; positions stay the tour's.
    #[test]
    fn double_bridge_and_descent_report_their_cost_changes() {
        let scenario = crate::demo::scenario().unwrap();
        let model = TransferModel::new(&scenario.farm, 18.0);
        let ground = |x: f64, y: f64| GroundPoint {
            x,
            y,
            ground_m: 0.0,
        };
        let ends: Vec<[GroundPoint; 2]> = (0..40)
            .map(|k| {
                let x = 23.0 * (k % 9) as f64 - 80.0 + 3.0 * (k / 9) as f64;
                let y = 41.0 * (k % 5) as f64 - 60.0;
                [ground(x, y), ground(x + 7.0, y + 35.0 + (k % 4) as f64)]
            })
            .collect();
        let point = ground(-150.0, 20.0);
        for start in [
            Start::Open,
            Start::Closed,
            Start::From(point),
            Start::Fixed(point),
        ] {
            let problem = OrderingProblem::new(ends.clone(), start, &model);
            let neighbours = cheapest_ends(&problem, 6, |end, other| other / 2 != end / 2);
            let groups = vec![0; 40];
            let tour: Vec<Step> = (0..40)
                .map(|pass| Step {
                    pass: (pass * 7) % 40,
                    reversed: pass % 3 == 0,
                })
                .collect();
            let mut search = Search {
                problem: &problem,
                position: vec![0; 40],
                tour,
                neighbours: &neighbours,
                groups: &groups,
                closed: start.is_closed(),
                from_start: !start.free_first(),
                home: start.returns_home(),
                three_opt: true,
                queue: Vec::new(),
                queued: Vec::new(),
                gaps_costed: GapMarks::default(),
            };
            search.reindex();
            let consistent = |search: &Search| {
                crate::sequence::tour::is_permutation(&search.tour, 40)
                    && (0..40).all(|p| search.position[search.tour[p].pass] == p)
            };
            let before = problem.tour_cost(&search.tour);
            let change = search.double_bridge(5, 17, 31);
            let kicked = problem.tour_cost(&search.tour);
            assert!((kicked - before - change).abs() < 1e-6, "{start:?}");
            assert!(consistent(&search), "{start:?}");
            let gained = search.descend(0..40, 100_000);
            let after = problem.tour_cost(&search.tour);
            assert!(gained > 1.0, "{start:?}: the scrambled tour improves");
            assert!((kicked - after - gained).abs() < 1e-6, "{start:?}");
            assert!(consistent(&search), "{start:?}");
        }
    }

    /// Passes scattered over the demo farm: the lists by cost hold, for every end, exactly
    /// the `count` cheapest accepted ends by eq. (8), cheapest first.
    #[test]
    fn cheapest_ends_are_the_cheapest_accepted_ends_by_eq_8() {
        let scenario = crate::demo::scenario().unwrap();
        let model = TransferModel::new(&scenario.farm, 18.0);
        let ground = |x: f64, y: f64| GroundPoint {
            x,
            y,
            ground_m: 0.0,
        };
        let ends: Vec<[GroundPoint; 2]> = (0..24)
            .map(|k| {
                let x = 37.0 * k as f64 - 120.0;
                let y = 19.0 * (k % 7) as f64;
                [ground(x, y), ground(x + 13.0, y + 90.0)]
            })
            .collect();
        let problem = OrderingProblem::new(ends, Start::Open, &model);
        assert!(problem.has_cost_matrix());
        let accept = |end: End, other: End| other / 2 != end / 2;
        let lists = cheapest_ends(&problem, 5, accept);
        for (end, list) in lists.iter().enumerate() {
            assert_eq!(list.len(), 5);
            let mut expected: Vec<End> = (0..48).filter(|&other| accept(end, other)).collect();
            expected.sort_by(|&a, &b| {
                problem
                    .cost(end, a)
                    .total_cmp(&problem.cost(end, b))
                    .then(a.cmp(&b))
            });
            assert_eq!(list[..], expected[..5], "end {end}");
        }
    }
}
