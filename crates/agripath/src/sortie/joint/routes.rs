//! Moves between sorties, costed in route space (ours, after the granular local search of
//! Vidal et al. 2012's HGS and Toth & Vigo 2003's granular neighbourhoods; issue 19).
//!
//! The giant-tour search ([`super::search`]) moves passes within one order and lets the split
//! place the returns; a move that takes a pass from one sortie into another far along the
//! tour shifts every return between them. Here the incumbent is cut into sorties at pass ends
//! (the best such cut, [`whole_pass_sorties`]), and the sorties are changed as routes, each
//! costed on its own: for a sortie r flying oriented passes q_1 … q_m,
//!
//! c(r) = L(in(q_1)) + Σ t(q_i, q_{i+1}) + L(out(q_m)) + service(S_r),
//!
//! with L the leg to the supply point (seconds), t the transfer (seconds, at its speed, as the
//! split charges it), S_r the spray metres and service(S) = max(T_e', t_b + α S) (seed 003
//! eq. 5). A sortie is kept within the tank (S_r ≤ D_max) and the battery (legs + transfers +
//! spray seconds ≤ the usable battery). Every sortie is charged a service (the split charges
//! all but the first; the difference is one service, and it rewards a move that empties a
//! sortie). The moves, around each pass u and each of its nearest passes v: relocate u next to
//! v (before or after, either way round), swap u and v (each either way round), 2-opt* (the
//! tails after u and after v exchanged, or u joined to v with the heads reversed), and 2-opt
//! within a sortie. The first move that lowers the sum is made, until none does.
//!
//! The sorties are then flown one after the other as a giant tour, which the search scores
//! through the split: a return at each sortie's end is one of the splits it weighs, so the
//! tour costs no more than the sorties here (but for the first service), and the split may
//! still do better with returns inside passes.

use super::JointProblem;
use crate::sequence::local_search::nearest_ends;
use crate::sequence::tour::Step;

/// Nearest passes per pass that moves are tried with (from the nearest ends of either end).
const NEIGHBOURS: usize = 8;
/// Slack on the limits, as the split's.
const SLACK: f64 = 1e-6;

/// Routes of whole passes over `problem`, and the passes near each pass.
pub struct RouteSpace<'p, 'a> {
    problem: &'p JointProblem<'a>,
    near: Vec<Vec<usize>>,
}

impl<'p, 'a> RouteSpace<'p, 'a> {
    /// The route space of `problem`.
    pub fn new(problem: &'p JointProblem<'a>) -> Self {
        let ends = nearest_ends(problem.ordering, NEIGHBOURS, |end, other| {
            other / 2 != end / 2
        });
        let near = (0..problem.profiles.len())
            .map(|pass| {
                let mut passes: Vec<usize> = ends[2 * pass]
                    .iter()
                    .chain(&ends[2 * pass + 1])
                    .map(|end| end / 2)
                    .collect();
                passes.sort_unstable();
                passes.dedup();
                passes
            })
            .collect();
        Self { problem, near }
    }

    /// One-way leg seconds to the supply point from `step`'s entry (or exit).
    fn leg_s(&self, step: Step, at_exit: bool) -> f64 {
        let legs = &self.problem.profiles[step.pass].leg_s;
        if step.reversed != at_exit {
            legs[legs.len() - 1]
        } else {
            legs[0]
        }
    }

    /// c(r) of the sortie flying `route`, or `None` where it breaks the tank or the battery.
    pub fn cost(&self, route: &[Step]) -> Option<f64> {
        let (Some(&first), Some(&last)) = (route.first(), route.last()) else {
            return Some(0.0);
        };
        let limits = &self.problem.limits;
        let (mut spray_m, mut spray_s, mut transfers_s) = (0.0, 0.0, 0.0);
        for (index, step) in route.iter().enumerate() {
            let profile = &self.problem.profiles[step.pass];
            spray_m += profile.length();
            spray_s += profile.seconds();
            if index > 0 {
                transfers_s += self.problem.transfer_s(route[index - 1], *step);
            }
        }
        let legs = self.leg_s(first, false) + self.leg_s(last, true);
        let fits = spray_m <= limits.tank_m + SLACK
            && legs + transfers_s + spray_s <= limits.usable_s + SLACK;
        fits.then(|| legs + transfers_s + limits.service_s(spray_m))
    }

    /// The cheapest cut of `tour` into sorties at pass ends (Bellman's split over the
    /// positions, each sortie costed by [`RouteSpace::cost`]), or `None` where a pass alone
    /// does not fit a sortie (only a return inside it can fly it).
    pub fn whole_pass_sorties(&self, tour: &[Step]) -> Option<Vec<Vec<Step>>> {
        let n = tour.len();
        let mut best = vec![f64::INFINITY; n + 1];
        let mut came = vec![0; n + 1];
        best[0] = 0.0;
        for end in 1..=n {
            // Sorties tour[start..end], longest last: stop once one breaks a limit (they
            // only grow).
            for start in (0..end).rev() {
                let Some(cost) = self.cost(&tour[start..end]) else {
                    break;
                };
                if best[start] + cost < best[end] {
                    best[end] = best[start] + cost;
                    came[end] = start;
                }
            }
        }
        if !best[n].is_finite() {
            return None;
        }
        let mut sorties = Vec::new();
        let mut end = n;
        while end > 0 {
            sorties.push(tour[came[end]..end].to_vec());
            end = came[end];
        }
        sorties.reverse();
        Some(sorties)
    }

    /// The sorties after the local search of the moves between and within them, until no
    /// move lowers their total cost.
    pub fn improve(&self, mut sorties: Vec<Vec<Step>>) -> Vec<Vec<Step>> {
        let passes = self.problem.profiles.len();
        let mut costs: Vec<f64> = sorties
            .iter()
            .map(|route| self.cost(route).unwrap_or(f64::INFINITY))
            .collect();
        let mut place = vec![(0usize, 0usize); passes];
        let locate = |sorties: &[Vec<Step>], place: &mut [(usize, usize)]| {
            for (r, route) in sorties.iter().enumerate() {
                for (i, step) in route.iter().enumerate() {
                    place[step.pass] = (r, i);
                }
            }
        };
        locate(&sorties, &mut place);
        let mut improved = true;
        while improved {
            improved = false;
            for u in 0..passes {
                for &v in &self.near[u] {
                    if let Some((changes, _)) = self.best_move(&sorties, &costs, &place, u, v) {
                        for (r, route) in changes {
                            costs[r] = self.cost(&route).unwrap_or(f64::INFINITY);
                            sorties[r] = route;
                        }
                        locate(&sorties, &mut place);
                        improved = true;
                        break;
                    }
                }
            }
        }
        sorties.retain(|route| !route.is_empty());
        sorties
    }

    /// The cheapest of the moves of `u` with `v` that lowers the cost: the new routes (by
    /// sortie index) and the saving.
    fn best_move(
        &self,
        sorties: &[Vec<Step>],
        costs: &[f64],
        place: &[(usize, usize)],
        u: usize,
        v: usize,
    ) -> Option<(Vec<(usize, Vec<Step>)>, f64)> {
        let (ru, iu) = place[u];
        let (rv, iv) = place[v];
        let mut best: Option<(Vec<(usize, Vec<Step>)>, f64)> = None;
        let mut consider = |changes: Vec<(usize, Vec<Step>)>| {
            let before: f64 = changes.iter().map(|(r, _)| costs[*r]).sum();
            let mut after = 0.0;
            for (_, route) in &changes {
                match self.cost(route) {
                    Some(cost) => after += cost,
                    None => return,
                }
            }
            let saving = before - after;
            if saving > 1e-9 && best.as_ref().is_none_or(|(_, kept)| saving > *kept) {
                best = Some((changes, saving));
            }
        };
        let step_u = sorties[ru][iu];
        let step_v = sorties[rv][iv];
        // Relocate u before or after v, either way round.
        for after in [false, true] {
            for turned in [false, true] {
                let moved = if turned { step_u.flipped() } else { step_u };
                let mut from = sorties[ru].clone();
                from.remove(iu);
                if ru == rv {
                    let at = from
                        .iter()
                        .position(|step| step.pass == v)
                        .expect("v in its route");
                    from.insert(at + usize::from(after), moved);
                    consider(vec![(ru, from)]);
                } else {
                    let mut into = sorties[rv].clone();
                    into.insert(iv + usize::from(after), moved);
                    consider(vec![(ru, from), (rv, into)]);
                }
            }
        }
        // Swap u and v, each either way round.
        for (turn_u, turn_v) in [(false, false), (true, false), (false, true), (true, true)] {
            let new_u = if turn_u { step_u.flipped() } else { step_u };
            let new_v = if turn_v { step_v.flipped() } else { step_v };
            if ru == rv {
                let mut route = sorties[ru].clone();
                route[iu] = new_v;
                route[iv] = new_u;
                consider(vec![(ru, route)]);
            } else {
                let mut first = sorties[ru].clone();
                let mut second = sorties[rv].clone();
                first[iu] = new_v;
                second[iv] = new_u;
                consider(vec![(ru, first), (rv, second)]);
            }
        }
        if ru == rv {
            // 2-opt within the sortie: the stretch between u and v flown backwards.
            let (low, high) = (iu.min(iv), iu.max(iv));
            for (from, to) in [(low, high), (low + 1, high), (low, high - 1)] {
                if from < to {
                    let mut route = sorties[ru].clone();
                    reverse(&mut route[from..=to]);
                    consider(vec![(ru, route)]);
                }
            }
        } else {
            let (a, b) = (&sorties[ru], &sorties[rv]);
            // 2-opt*: u's tail and v's tail exchanged (u then what followed v) ...
            let first: Vec<Step> = a[..=iu].iter().chain(&b[iv + 1..]).copied().collect();
            let second: Vec<Step> = b[..=iv].iter().chain(&a[iu + 1..]).copied().collect();
            consider(vec![(ru, first), (rv, second)]);
            // ... or u joined to v: u's head then v's head backwards, and u's tail backwards
            // then v's tail.
            let mut head = b[..=iv].to_vec();
            reverse(&mut head);
            let first: Vec<Step> = a[..=iu].iter().chain(&head).copied().collect();
            let mut tail = a[iu + 1..].to_vec();
            reverse(&mut tail);
            let second: Vec<Step> = tail.iter().chain(&b[iv + 1..]).copied().collect();
            consider(vec![(ru, first), (rv, second)]);
        }
        best
    }

    /// The sorties flown one after the other, in the order of their first passes in `tour`
    /// (so that the giant tour stays close to the tour it came from).
    pub fn giant_tour(sorties: &[Vec<Step>], tour: &[Step]) -> Vec<Step> {
        let mut position = vec![0; tour.len()];
        for (index, step) in tour.iter().enumerate() {
            position[step.pass] = index;
        }
        let mut ordered: Vec<&Vec<Step>> = sorties.iter().filter(|r| !r.is_empty()).collect();
        ordered.sort_by_key(|route| {
            route
                .iter()
                .map(|step| position[step.pass])
                .min()
                .unwrap_or(0)
        });
        ordered.into_iter().flatten().copied().collect()
    }
}

/// `steps` flown backwards: their order reversed, each pass the other way.
fn reverse(steps: &mut [Step]) {
    steps.reverse();
    steps.iter_mut().for_each(|step| *step = step.flipped());
}
