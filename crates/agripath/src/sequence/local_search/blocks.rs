//! The search over whole blocks of passes, shared by the block relocation of the
//! constructions (a field's boustrophedon is a block, `construction.rs`) and the run search
//! (a run of a field's passes is a block, `runs.rs`).
//!
//! A block is placed in one of its four variants; the tour is the blocks in order, and its
//! cost is eq. (8)'s transfers between each block's exit and the next one's entry, the start
//! legs that `Start` counts, and each placed variant's own transfers inside it. Moves, while
//! they gain (at most 50 rounds):
//!
//! - Or-opt: one block to the best other gap, in any of its variants;
//! - 2-opt on blocks (when asked for): a stretch of blocks flown backwards, each block in its
//!   backwards variant; eq. (8) is symmetric, so the inside costs do not change.
//!
//! Then double-bridge kicks on the block order, each followed by the moves again, kept when
//! the tour gets cheaper.

use super::super::tour::{End, OrderingProblem};
use super::double_bridge;

/// A block and one of its four variants.
pub(super) type Placed = (usize, usize);

/// What the block search needs to know of the blocks it orders.
pub(super) trait Blocks {
    /// How many blocks there are (numbered from 0).
    fn count(&self) -> usize;
    /// The end the placed block is entered by.
    fn entry(&self, placed: Placed) -> End;
    /// The end the placed block is left by.
    fn exit(&self, placed: Placed) -> End;
    /// The cost of the transfers inside the placed block.
    fn inside(&self, placed: Placed) -> f64;
    /// The same block flown backwards: its passes in reverse order, each the other way (the
    /// entry and the exit swap).
    fn backwards(&self, placed: Placed) -> Placed;
}

/// The block search over `blocks` for `problem`'s start.
pub(super) struct BlockSearch<'a, 'p, B> {
    problem: &'a OrderingProblem<'p>,
    blocks: &'a B,
    closed: bool,
    home: bool,
    /// Without the problem's cost matrix (above 2,000 ends) a cost is computed, not looked
    /// up: the costs between every placed block's exit and every other's entry, computed once
    /// here (the same values), when there are at most [`LINK_TABLE_BLOCKS`] blocks.
    links: Option<Vec<f64>>,
}

/// Most blocks whose links are tabled: 4 variants each, (4 × 300)² costs, 11.5 MB.
const LINK_TABLE_BLOCKS: usize = 300;

impl<'a, 'p, B: Blocks> BlockSearch<'a, 'p, B> {
    pub(super) fn new(problem: &'a OrderingProblem<'p>, blocks: &'a B) -> Self {
        let count = blocks.count();
        let links = (!problem.has_cost_matrix() && count <= LINK_TABLE_BLOCKS).then(|| {
            let placed = |index: usize| (index / 4, index % 4);
            // In series: the block searches already run side by side (the constructions).
            (0..4 * count)
                .flat_map(|from| {
                    let exit = blocks.exit(placed(from));
                    (0..4 * count).map(move |to| problem.cost(exit, blocks.entry(placed(to))))
                })
                .collect()
        });
        Self {
            problem,
            blocks,
            closed: problem.start.is_closed(),
            home: problem.start.returns_home(),
            links,
        }
    }

    /// The link from one block to the next; `None` is the start point or a free end of the
    /// path (whose start cost is 0: `cost_from_start` of a start with no point).
    fn link(&self, from: Option<Placed>, to: Option<Placed>) -> f64 {
        let blocks = self.blocks;
        match (from, to) {
            (Some(a), Some(b)) => match &self.links {
                Some(links) => links[(4 * a.0 + a.1) * 4 * blocks.count() + 4 * b.0 + b.1],
                None => self.problem.cost(blocks.exit(a), blocks.entry(b)),
            },
            (None, Some(b)) if !self.closed => self.problem.cost_from_start(blocks.entry(b)),
            (Some(a), None) if self.home => self.problem.cost_from_start(blocks.exit(a)),
            _ => 0.0,
        }
    }

    /// The blocks on either side of a gap in `order` (a closed tour wraps around).
    fn around(&self, order: &[Placed], gap: usize) -> (Option<Placed>, Option<Placed>) {
        let n = order.len();
        let before = match gap {
            0 if self.closed && n > 0 => Some(order[n - 1]),
            0 => None,
            _ => Some(order[gap - 1]),
        };
        let after = if gap < n {
            Some(order[gap])
        } else if self.closed && n > 0 {
            Some(order[0])
        } else {
            None
        };
        (before, after)
    }

    /// The tour cost of the blocks flown in `order`.
    pub(super) fn total(&self, order: &[Placed]) -> f64 {
        let inside: f64 = order.iter().map(|&placed| self.blocks.inside(placed)).sum();
        let between: f64 = (0..=order.len())
            .filter(|&gap| !(self.closed && gap == order.len()))
            .map(|gap| {
                let (before, after) = self.around(order, gap);
                self.link(before, after)
            })
            .sum();
        inside + between
    }

    /// Or-opt of blocks and, with `reversals`, 2-opt on blocks, while they gain.
    pub(super) fn improve(&self, order: &mut Vec<Placed>, reversals: bool) {
        let count = order.len();
        for _ in 0..50 {
            let mut improved = false;
            for from in 0..count {
                improved |= self.relocate(order, from);
            }
            for i in 0..if reversals { count } else { 0 } {
                for j in i + 1..count {
                    if self.closed && i == 0 && j == count - 1 {
                        continue;
                    }
                    let (before, _) = self.around(order, i);
                    let (_, after) = self.around(order, j + 1);
                    let backwards = |placed: Placed| self.blocks.backwards(placed);
                    let old = self.link(before, Some(order[i])) + self.link(Some(order[j]), after);
                    let new = self.link(before, Some(backwards(order[j])))
                        + self.link(Some(backwards(order[i])), after);
                    if new < old - 1e-9 {
                        order[i..=j].reverse();
                        for placed in &mut order[i..=j] {
                            *placed = backwards(*placed);
                        }
                        improved = true;
                    }
                }
            }
            if !improved {
                break;
            }
        }
    }

    /// Moves the block at `from` to the best other gap in its best variant, if that gains.
    fn relocate(&self, order: &mut Vec<Placed>, from: usize) -> bool {
        let moving = order[from];
        let (before, _) = self.around(order, from);
        let (_, after) = self.around(order, from + 1);
        let removal = self.link(before, Some(moving)) + self.link(Some(moving), after)
            - self.link(before, after);
        let mut without = order.clone();
        without.remove(from);
        let mut choice: Option<(f64, usize, Placed)> = None;
        for to in 0..=without.len() {
            if self.closed && to == 0 {
                continue; // the same gap as the last
            }
            let (left, right) = self.around(&without, to);
            let base = self.link(left, right);
            for variant in 0..4 {
                let candidate = (moving.0, variant);
                let added = self.link(left, Some(candidate)) + self.link(Some(candidate), right)
                    - base
                    + self.blocks.inside(candidate)
                    - self.blocks.inside(moving);
                let gain = removal - added;
                if gain > 1e-9 && choice.is_none_or(|(best, ..)| gain > best) {
                    choice = Some((gain, to, candidate));
                }
            }
        }
        let Some((_, to, candidate)) = choice else {
            return false;
        };
        without.insert(to, candidate);
        *order = without;
        true
    }

    /// [`Self::improve`], then up to `kicks` double-bridge kicks from `stream`, each improved
    /// and kept when the tour gets cheaper: the best order found and its cost.
    pub(super) fn iterate(
        &self,
        mut order: Vec<Placed>,
        reversals: bool,
        kicks: usize,
        stream: &mut swarm::RunStream,
    ) -> (Vec<Placed>, f64) {
        self.improve(&mut order, reversals);
        let mut best = self.total(&order);
        for _ in 0..kicks {
            let Some(mut kicked) = double_bridge(&order, stream) else {
                continue;
            };
            self.improve(&mut kicked, reversals);
            let cost = self.total(&kicked);
            if cost < best - 1e-9 {
                best = cost;
                order = kicked;
            }
        }
        (order, best)
    }
}
