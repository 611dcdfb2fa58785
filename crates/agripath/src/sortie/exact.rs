//! `exact` (ours): the break points that minimise seed 003's E for the given route, exactly.
//!
//! E's terms depend on the breaks only through each return's round trip and the service
//! before the next sortie, so the best split is a shortest path over the route's points: with
//! cost(0) = 0,
//!
//! cost(j) = min over i < j with (i..=j) flyable on one tank and battery of
//!           cost(i) + \[i > 0\]·(max(T_e, T_p(spray(i, j))) + 2 (‖P_i, P0‖ + H_i) / v_off),
//!
//! and the answer is cost(last point). Spray metres and route time only grow along the route,
//! so the first i that one tank and battery can reach moves forward with j (two pointers):
//! the work is O(points × points per sortie), a few million steps for a 10,000-point route.
//! Ties go to the earliest break, so the result is deterministic. Every return point must be
//! a route point: routes carry points every cell (grid) or every draping step (plans).

use super::route::WorkRoute;
use super::{SortieModel, TOLERANCE};
use crate::error::Fault;

/// The optimal break points.
pub fn breaks(route: &WorkRoute, model: &SortieModel) -> Result<Vec<usize>, Fault> {
    let count = route.len();
    let spray = route.spray_prefix();
    let flight = route.flight_prefix();
    let tank = model.spray_per_tank_m.unwrap_or(f64::INFINITY) + TOLERANCE;
    let endurance = model.usable_s() + TOLERANCE;
    // Per point: the one-way return in seconds.
    let leg_s: Vec<f64> = route
        .points()
        .iter()
        .map(|point| model.leg_m(point) / model.transit_mps)
        .collect();
    let mut cost = vec![f64::INFINITY; count];
    // cost(i) plus the round trip from i: what a return at i costs before its service.
    let mut base = vec![f64::INFINITY; count];
    let mut previous = vec![usize::MAX; count];
    cost[0] = 0.0;
    base[0] = 0.0;
    let mut lowest = 0;
    for j in 1..count {
        // Below `lowest`, a sortie to j already sprays more than a tank or flies longer than
        // the battery along the route alone; both only grow as j moves on.
        while lowest < j
            && (spray[j] - spray[lowest] > tank || flight[j] - flight[lowest] > endurance)
        {
            lowest += 1;
        }
        let (mut best, mut from) = (f64::INFINITY, usize::MAX);
        for i in lowest..j {
            if !base[i].is_finite() || leg_s[i] + flight[j] - flight[i] + leg_s[j] > endurance {
                continue;
            }
            // max(T_e, T_p) of eq. (5) for the sortie i..=j.
            let step = if i == 0 {
                0.0
            } else {
                model.service_s(spray[j] - spray[i])
            };
            if base[i] + step < best {
                best = base[i] + step;
                from = i;
            }
        }
        cost[j] = best;
        previous[j] = from;
        base[j] = best + 2.0 * leg_s[j];
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
