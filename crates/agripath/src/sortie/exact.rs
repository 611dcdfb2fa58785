//! `exact` (ours): the break points that minimise seed 003's E for the given route, exactly.
//!
//! E's terms depend on the breaks only through each return's round trip and the service
//! before the next sortie, so the best split is a shortest path over the route's points: with
//! cost(0) = 0,
//!
//! cost(j) = min over i < j with (i..=j) flyable on one tank and battery of
//!           cost(i) + [i > 0]·(max(T_e, T_p(spray(i, j))) + 2 (‖P_i, P0‖ + H_i) / v_off),
//!
//! and the answer is cost(last point). Spray metres and route time only grow along the route,
//! so the first i that one tank and battery can reach moves forward with j (two pointers):
//! the work is O(points × points per sortie), a few million steps for a 10,000-point route.
//! Ties go to the earliest break, so the result is deterministic. Every return point must be
//! a route point: routes carry points every cell (grid) or every draping step (plans).

use super::route::WorkRoute;
use super::SortieModel;
use crate::error::Fault;

/// The optimal break points.
pub fn breaks(route: &WorkRoute, model: &SortieModel) -> Result<Vec<usize>, Fault> {
    let count = route.len();
    let mut cost = vec![f64::INFINITY; count];
    let mut previous = vec![usize::MAX; count];
    cost[0] = 0.0;
    let mut lowest = 0;
    for j in 1..count {
        // Below `lowest`, a sortie to j already sprays more than a tank or flies longer than
        // the battery along the route alone.
        while lowest < j
            && (model
                .spray_per_tank_m
                .is_some_and(|tank| route.spray_between(lowest, j) > tank + 1e-6)
                || route.flight_between(lowest, j) > model.endurance_s + 1e-6)
        {
            lowest += 1;
        }
        for i in lowest..j {
            if !cost[i].is_finite() || !model.feasible(route, i, j) {
                continue;
            }
            let step = if i == 0 {
                0.0
            } else {
                model.return_cost_s(route, i, j)
            };
            if cost[i] + step < cost[j] {
                cost[j] = cost[i] + step;
                previous[j] = i;
            }
        }
    }
    let last = count - 1;
    if !cost[last].is_finite() {
        return Err(Fault::Structure(
            "the route cannot be split into sorties that one tank and one battery fly".into(),
        ));
    }
    let mut breaks = Vec::new();
    let mut at = previous[last];
    while at != 0 && at != usize::MAX {
        breaks.push(at);
        at = previous[at];
    }
    breaks.reverse();
    Ok(breaks)
}
