//! Return-aware moves: each sortie of the current split re-flown as a petal, out and back to
//! the supply point (ours, after what PyVRP's solutions do on the seed 001 farm: longer
//! transfers, sorties that end near the supply point; issue 19).
//!
//! A sortie cut from a tour optimised for transfers flies its passes side by side away from
//! the supply point and ends where the tank runs dry, far from it; its return is long. The
//! same passes flown out on every other one and back on the ones between,
//!
//! c_1, c_3, c_5, …, c_6, c_4, c_2   (the interleave of c_1 … c_m),
//!
//! end next to where they began, at the price of transfers twice as wide. For a fixed
//! sequence of passes p_1 … p_m the directions are chosen exactly by dynamic programming
//! over the two directions of each pass, with the legs to the supply point at both ends:
//!
//! F_1(r) = L(in(p_1, r)),  F_i(r) = min_{r'} F_{i−1}(r') + c(out(p_{i−1}, r'), in(p_i, r)),
//! cost = min_r F_m(r) + L(out(p_m, r)),
//!
//! with c eq. (8) and L the leg to the supply point (metres). Each sortie gives five
//! candidates, scored through the split by the search: its passes re-directed, and the
//! interleaves from its first, its second, its last and its last but one pass (a petal
//! should start and end at the pass nearest the supply point, which may be either end).

use crate::sequence::tour::{OrderingProblem, Step};

/// The passes of `steps` in the same order, each flown in the direction that minimises the
/// transfers between them plus the legs from the supply point to the first and from the last.
pub fn directed(problem: &OrderingProblem, steps: &[Step]) -> Vec<Step> {
    let Some(first) = steps.first() else {
        return Vec::new();
    };
    let flown = |pass: usize, reversed: bool| Step { pass, reversed };
    // best[i][r]: least metres to have flown steps[..=i] with steps[i] in direction r;
    // came[i][r]: the direction of steps[i − 1] on that way.
    let mut best = vec![[0.0f64; 2]; steps.len()];
    let mut came = vec![[false; 2]; steps.len()];
    for r in [false, true] {
        best[0][usize::from(r)] = problem.cost_from_start(flown(first.pass, r).entry());
    }
    for i in 1..steps.len() {
        for r in [false, true] {
            let entry = flown(steps[i].pass, r).entry();
            let (cost, from) = [false, true]
                .into_iter()
                .map(|before| {
                    let exit = flown(steps[i - 1].pass, before).exit();
                    (
                        best[i - 1][usize::from(before)] + problem.cost(exit, entry),
                        before,
                    )
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .expect("two directions");
            best[i][usize::from(r)] = cost;
            came[i][usize::from(r)] = from;
        }
    }
    let last = steps.len() - 1;
    let mut direction = [false, true]
        .into_iter()
        .min_by(|&a, &b| {
            let home = |r: bool| {
                best[last][usize::from(r)]
                    + problem.cost_from_start(flown(steps[last].pass, r).exit())
            };
            home(a).total_cmp(&home(b))
        })
        .expect("two directions");
    let mut chosen = vec![*first; steps.len()];
    for i in (0..steps.len()).rev() {
        chosen[i] = flown(steps[i].pass, direction);
        direction = came[i][usize::from(direction)];
    }
    chosen
}

/// The interleave of `steps` from `offset` (0 or 1): every other pass from `steps[offset]`
/// out, the ones between back.
pub fn interleaved(steps: &[Step], offset: usize) -> Vec<Step> {
    let out = steps.iter().skip(offset).step_by(2);
    let back: Vec<Step> = steps
        .iter()
        .enumerate()
        .filter(|(index, _)| index % 2 != offset % 2)
        .map(|(_, step)| *step)
        .collect();
    out.copied().chain(back.into_iter().rev()).collect()
}

/// The candidates for the sortie flying tour positions `first..=last`: the tour with that
/// stretch re-directed, and interleaved from its first, second, last and last but one pass
/// (each re-directed); those equal to the tour are left out.
pub fn candidates(
    problem: &OrderingProblem,
    tour: &[Step],
    first: usize,
    last: usize,
) -> Vec<Vec<Step>> {
    let stretch = &tour[first..=last];
    let mut found: Vec<Vec<Step>> = Vec::new();
    let orders = [
        stretch.to_vec(),
        interleaved(stretch, 0),
        interleaved(stretch, 1),
    ];
    for order in orders {
        let mut candidate = tour.to_vec();
        candidate.splice(first..=last, directed(problem, &order));
        if candidate != tour && !found.contains(&candidate) {
            found.push(candidate);
        }
    }
    found
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
    fn the_directions_are_the_cheapest_and_the_interleave_comes_back() {
        let farm = crate::demo::scenario().unwrap().farm;
        let model = TransferModel::new(&farm, 10.0);
        // Six parallel swaths 5 m apart, 100 m long, running away from the supply point.
        let ends: Vec<[GroundPoint; 2]> = (0..6)
            .map(|k| {
                let x = 600.0 + 5.0 * k as f64;
                [point(x, 300.0), point(x, 400.0)]
            })
            .collect();
        let problem = OrderingProblem::new(ends, Start::Fixed(point(600.0, 0.0)), &model);
        let steps: Vec<Step> = (0..6)
            .map(|pass| Step {
                pass,
                reversed: false,
            })
            .collect();
        let directed_steps = directed(&problem, &steps);
        let cost = |tour: &[Step]| problem.tour_cost(tour);
        // Brute force over all 2^6 directions.
        let brute = (0..64u32)
            .map(|mask| {
                let tour: Vec<Step> = (0..6)
                    .map(|pass| Step {
                        pass,
                        reversed: mask & (1 << pass) != 0,
                    })
                    .collect();
                cost(&tour)
            })
            .fold(f64::INFINITY, f64::min);
        assert!((cost(&directed_steps) - brute).abs() < 1e-9);
        let petal = interleaved(&steps, 0);
        let order: Vec<usize> = petal.iter().map(|step| step.pass).collect();
        assert_eq!(order, vec![0, 2, 4, 5, 3, 1]);
        assert_eq!(check_order(&petal, 6), Ok(()));
        let from_second: Vec<usize> = interleaved(&steps, 1).iter().map(|s| s.pass).collect();
        assert_eq!(from_second, vec![1, 3, 5, 4, 2, 0]);
        // Out and back, the petal ends next to where it began.
        let petal = directed(&problem, &petal);
        let (start, end) = (
            problem.point(petal[0].entry()),
            problem.point(petal[5].exit()),
        );
        assert!(start.y == 300.0 && end.y == 300.0, "{start:?} {end:?}");
        for candidate in candidates(&problem, &steps, 0, 5) {
            assert_eq!(check_order(&candidate, 6), Ok(()));
        }
    }
}
