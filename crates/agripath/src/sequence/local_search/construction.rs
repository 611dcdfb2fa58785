//! Step 1 of `best`: the constructions the local search starts from: a field-by-field
//! boustrophedon (by nearest fields on large farms), the exact order of whole field blocks
//! up to ten fields, and block relocation above (see the parent module).

use super::super::tour::{End, OrderingProblem, Step};
use super::blocks::{BlockSearch, Blocks, Placed};

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
pub(super) fn boustrophedon_by_grid(problem: &OrderingProblem, groups: &[Vec<usize>]) -> Vec<Step> {
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
pub(super) fn block_steps(passes: &[usize], variant: usize) -> Vec<Step> {
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

    /// The passes of blocks flown in `order`.
    fn steps(&self, order: &[Placed]) -> Vec<Step> {
        order
            .iter()
            .flat_map(|&(field, variant)| self.0[field][variant].0.iter().copied())
            .collect()
    }
}

impl Blocks for FieldBlocks {
    fn count(&self) -> usize {
        self.0.len()
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

    /// Backwards, the lines run the other way (bit 0) and the first pass flown is the old
    /// last one, flown the other way (bit 1 from the old last pass's direction).
    fn backwards(&self, (field, variant): Placed) -> Placed {
        let passes = self.0[field][variant].0.len();
        let last_reversed = (variant & 2 == 2) ^ passes.is_multiple_of(2);
        (field, (variant ^ 1) | (usize::from(!last_reversed) << 1))
    }
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
    let (closed, home) = (problem.start.is_closed(), problem.start.returns_home());
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
            } else if home {
                total += problem.cost_from_start(exit(state / 4, state % 4));
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
    let (entry, exit) = (|p: Placed| blocks.entry(p), |p: Placed| blocks.exit(p));
    // Nearest-first chain as the start.
    let mut order: Vec<Placed> = Vec::with_capacity(count);
    let mut left: Vec<usize> = (0..count).collect();
    while !left.is_empty() {
        let (slot, choice) = left
            .iter()
            .enumerate()
            .flat_map(|(slot, &field)| (0..4).map(move |variant| (slot, (field, variant))))
            .min_by(|a, b| {
                let cost = |choice: Placed| match order.last() {
                    Some(&last) => problem.cost(exit(last), entry(choice)),
                    None => problem.cost_from_start(entry(choice)),
                };
                cost(a.1).total_cmp(&cost(b.1))
            })
            .expect("a field is left");
        left.remove(slot);
        order.push(choice);
    }
    let search = BlockSearch::new(problem, &blocks);
    let start_cost = search.total(&order);
    let mut stream = swarm::run_stream(seed, 1);
    // A block-level descent costs O(F²) per round: fewer kicks on farms of many fields.
    let kicks = BLOCK_KICKS.min(500_000 / (count * count));
    let (order, best) = search.iterate(order, reversals, kicks, &mut stream);
    debug_assert!(best <= start_cost + 1e-6);
    Some(blocks.steps(&order))
}
