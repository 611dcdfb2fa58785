//! Cheap start tours for the joint search: the sequencer's order from the supply point and
//! tours as good in transfers that the split cuts differently, at O(n) each, no sequencer run.
//!
//! The joint search stalls in the local optimum of its start (decision 0017, addendum): more
//! budget from one start does not help, starts with other structure do. A sequencer run per
//! start costs more than the whole search, so the starts are made from the one order T =
//! t_0 … t_{n−1} the pipeline already has, a cycle S → t_0 → … → t_{n−1} → S through the supply
//! point S (`Start::Fixed` counts both legs):
//!
//! 1. T itself;
//! 2. T flown backwards (t_{n−1} … t_0, every pass the other way): eq. (8) is symmetric, so its
//!    transfers cost the same, but the tank and the battery run out at other places, so the
//!    split ends its sorties elsewhere;
//! 3. the cycle cut at the place k where it passes nearest S other than at its ends: the tour
//!    t_k … t_{n−1}, t_0 … t_{k−1}, whose transfers change by
//!
//!    Δ(k) = c(t_{n−1}, t_0) + L(t_k) + L(t_{k−1}) − c(t_{k−1}, t_k) − L(t_0) − L(t_{n−1}),
//!
//!    with c eq. (8) between a pass's exit and the next one's entry and L the leg to S
//!    (k = argmin Δ over 1 ≤ k < n);
//! 4. that rotation flown backwards.
//!
//! A closed tour made without the supply point (`Start::Closed`, as the supply point search
//! makes it) is another start when the caller has one: [`cut_at_supply`] cuts it at its k of
//! least Δ(k), k = 0 included.
//!
//! The pipeline's starts ([`of_paths`]) are not made from `Start::Fixed`'s order: the open path
//! (`Start::Open`, no supply point) and that backwards, after the closed tour cut at the supply
//! point and that backwards when the supply search has made it. The open path is no dearer to
//! make than the order from the supply point (one sequencer run either way), and the search
//! from it ends lower: mean non-spray time above each farm's best over the seed 001 farm and
//! ten random farms, 12 splits per pass, +1.13 % from T and T backwards, +0.25 % from the open
//! path and it backwards, +0.23 % with the closed tour's two first (seed 001: 2,108.1 s →
//! 2,061.1 s; docs/benchmarks.md, decision 0017's addendum of 2026-12-05). The legs to and from
//! the supply point, which the open path does not see, are a few of the dozen or more the
//! split places; its transfers, which the open path minimises, are the rest.

use crate::sequence::tour::{OrderingProblem, Step};

/// Most start tours [`start_tours`] makes.
pub const MOST_STARTS: usize = 4;

/// The tour flown backwards: the last pass first, every pass the other way.
pub fn backwards(tour: &[Step]) -> Vec<Step> {
    tour.iter().rev().map(|step| step.flipped()).collect()
}

/// Δ(k) of the module's doc: the transfer metres that cutting the cycle of `tour` through the
/// supply point at k adds (0 at k = 0).
pub fn rotation_change(problem: &OrderingProblem, tour: &[Step], k: usize) -> f64 {
    if k == 0 || k >= tour.len() {
        return 0.0;
    }
    let leg = |end| problem.cost_from_start(end);
    let (first, last) = (tour[0], tour[tour.len() - 1]);
    let (before, after) = (tour[k - 1], tour[k]);
    problem.cost(last.exit(), first.entry()) - leg(first.entry()) - leg(last.exit())
        + leg(after.entry())
        + leg(before.exit())
        - problem.cost(before.exit(), after.entry())
}

/// The cut k ≥ 1 of the cycle through the supply point that adds the least transfer metres
/// (Δ(k) of the module's doc), with Δ(k); `None` for fewer than two passes.
pub fn cheapest_rotation(problem: &OrderingProblem, tour: &[Step]) -> Option<(usize, f64)> {
    (1..tour.len())
        .map(|k| (k, rotation_change(problem, tour, k)))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
}

/// `tour` from its k-th pass round to its (k − 1)-th.
pub fn rotated(tour: &[Step], k: usize) -> Vec<Step> {
    let mut turned = tour[k..].to_vec();
    turned.extend_from_slice(&tour[..k]);
    turned
}

/// A closed tour (`Start::Closed`'s, no supply point) cut where it passes nearest the supply
/// point of `problem`: the rotation of least Δ(k), k = 0 included.
pub fn cut_at_supply(problem: &OrderingProblem, closed: &[Step]) -> Vec<Step> {
    match cheapest_rotation(problem, closed) {
        Some((k, change)) if change < 0.0 => rotated(closed, k),
        _ => closed.to_vec(),
    }
}

/// The pipeline's start tours, the preferred first: `closed` (the supply search's closed tour,
/// when it made one) cut at the supply point and that backwards, then `open` (the sequencer's
/// open path) and that backwards; tours equal to an earlier one are left out.
pub fn of_paths(
    problem: &OrderingProblem,
    open: &[Step],
    closed: Option<&[Step]>,
) -> Vec<Vec<Step>> {
    let mut candidates = Vec::with_capacity(MOST_STARTS);
    if let Some(closed) = closed {
        let cut = cut_at_supply(problem, closed);
        candidates.push(backwards(&cut));
        candidates.insert(0, cut);
    }
    candidates.push(open.to_vec());
    candidates.push(backwards(open));
    let mut starts: Vec<Vec<Step>> = Vec::with_capacity(candidates.len());
    for candidate in candidates {
        if !starts.contains(&candidate) {
            starts.push(candidate);
        }
    }
    starts
}

/// Up to `count` (at most [`MOST_STARTS`]) start tours from `order`, in the order of the
/// module's doc; tours equal to an earlier one are left out.
pub fn start_tours(problem: &OrderingProblem, order: Vec<Step>, count: usize) -> Vec<Vec<Step>> {
    let count = count.clamp(1, MOST_STARTS);
    let mut candidates = vec![backwards(&order)];
    if let Some((k, _)) = cheapest_rotation(problem, &order) {
        let turned = rotated(&order, k);
        candidates.push(backwards(&turned));
        candidates.insert(1, turned);
    }
    let mut starts = vec![order];
    for candidate in candidates {
        if starts.len() >= count {
            break;
        }
        if !starts.contains(&candidate) {
            starts.push(candidate);
        }
    }
    starts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::drape::GroundPoint;
    use crate::sequence::tour::{check_order, Start};
    use crate::sequence::TransferModel;

    fn point(x: f64, y: f64) -> GroundPoint {
        GroundPoint {
            x,
            y,
            ground_m: 0.0,
        }
    }

    #[test]
    fn the_starts_are_tours_and_the_rotation_costs_what_delta_says() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        // Passes along a line away from the supply point and back, so the cycle passes near
        // the supply point in its middle.
        let ends: Vec<[GroundPoint; 2]> = (0..6)
            .map(|k| {
                let x = 500.0 + 40.0 * (k % 3) as f64;
                let y = if k < 3 { 0.0 } else { 300.0 };
                [point(x, y), point(x, y + 20.0)]
            })
            .collect();
        let problem = OrderingProblem::new(ends, Start::Fixed(point(0.0, 0.0)), &model);
        let order: Vec<Step> = (0..6)
            .map(|pass| Step {
                pass,
                reversed: pass % 2 == 1,
            })
            .collect();
        let starts = start_tours(&problem, order.clone(), MOST_STARTS);
        assert_eq!(starts.len(), 4);
        assert_eq!(starts[0], order);
        for start in &starts {
            assert_eq!(check_order(start, 6), Ok(()));
        }
        let cost = problem.tour_cost(&order);
        assert!((problem.tour_cost(&starts[1]) - cost).abs() < 1e-9);
        let (k, change) = cheapest_rotation(&problem, &order).unwrap();
        let turned = rotated(&order, k);
        assert_eq!(starts[2], turned);
        assert!((problem.tour_cost(&turned) - cost - change).abs() < 1e-6);
        for other in 1..6 {
            let tour = rotated(&order, other);
            assert!(problem.tour_cost(&tour) >= problem.tour_cost(&turned) - 1e-9);
        }
        // A closed tour is cut at its cheapest rotation, the unrotated one included.
        let cut = cut_at_supply(&problem, &turned);
        for other in 0..6 {
            assert!(problem.tour_cost(&cut) <= problem.tour_cost(&rotated(&turned, other)) + 1e-9);
        }
        assert_eq!(start_tours(&problem, order.clone(), 1), vec![order]);
    }
}
