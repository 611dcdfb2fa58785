//! `exact` (ours): the returns that minimise seed 003's E for the given route, exactly.
//!
//! A return leaves the route at point P_n for the supply point P0 and resumes at Q_n: at P_n
//! itself, or, where the segment after P_n is a turn or a transfer, at the next point, and
//! then that segment is not flown (the drone flies from P0 straight to the next pass). E's
//! terms depend on the returns only through their legs, the service before each sortie and
//! the segments skipped, so the best split is a shortest path over the route's points. With
//! start(0) = 0, and for each point j the best sortie ending there,
//!
//! end(j)  = min over s < j with (s..=j) flyable on one tank and battery of
//!           start(s) + \[s > 0\]·max(T_e, T_p(spray(s, j))),
//! start(j)     ← end(j) + 2 (‖P_j, P0‖ + H_j) / v_off                          (resume at j),
//! start(j + 1) ← end(j) + (leg(P_j) + leg(P_{j+1})) / v_off − t(segment j)     (skip it),
//!
//! and the answer is end(last point). Spray metres and route time only grow along the route,
//! so the first s that one tank and battery can reach moves forward with j (two pointers):
//! the work is O(points × points per sortie), a few million steps for a 10,000-point route.
//! Ties go to the earliest return, so the result is deterministic. Every return point must be
//! a route point: routes carry points every cell (grid) or every draping step (plans).

use super::route::WorkRoute;
use super::{Return, SortieModel, TOLERANCE};
use crate::error::Fault;

/// The optimal returns.
pub fn returns(route: &WorkRoute, model: &SortieModel) -> Result<Vec<Return>, Fault> {
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
    // start[s]: the least cost of everything before point s with a sortie starting at s, its
    // out-leg included; via[s]: the return point it came from.
    let mut start = vec![f64::INFINITY; count + 1];
    let mut via = vec![usize::MAX; count + 1];
    // from[j]: where the best sortie ending at j starts.
    let mut from = vec![usize::MAX; count];
    start[0] = 0.0;
    let mut lowest = 0;
    let last = count - 1;
    let mut answer = f64::INFINITY;
    for j in 1..count {
        // Below `lowest`, a sortie to j already sprays more than a tank or flies longer than
        // the battery along the route alone; both only grow as j moves on.
        while lowest < j
            && (spray[j] - spray[lowest] > tank || flight[j] - flight[lowest] > endurance)
        {
            lowest += 1;
        }
        let (mut best, mut best_from) = (f64::INFINITY, usize::MAX);
        for s in lowest..j {
            if !start[s].is_finite() || leg_s[s] + flight[j] - flight[s] + leg_s[j] > endurance {
                continue;
            }
            // max(T_e, T_p) of eq. (5) for the sortie s..=j.
            let service = if s == 0 {
                0.0
            } else {
                model.service_s(spray[j] - spray[s])
            };
            if start[s] + service < best {
                best = start[s] + service;
                best_from = s;
            }
        }
        from[j] = best_from;
        if j == last {
            answer = best;
            break;
        }
        if !best.is_finite() {
            continue;
        }
        if SortieModel::may_skip(route, j) {
            let skipped = best + leg_s[j] + leg_s[j + 1] - (flight[j + 1] - flight[j]);
            if skipped < start[j + 1] {
                start[j + 1] = skipped;
                via[j + 1] = j;
            }
        }
        let in_place = best + 2.0 * leg_s[j];
        if in_place < start[j] {
            start[j] = in_place;
            via[j] = j;
        }
    }
    if !answer.is_finite() {
        return Err(Fault::Structure(
            "the route cannot be split into sorties that one tank and one battery fly".into(),
        ));
    }
    let mut returns = Vec::new();
    let mut sortie_start = from[last];
    while sortie_start != 0 {
        let at = via[sortie_start];
        returns.push(Return {
            at,
            resume: sortie_start,
        });
        sortie_start = from[at];
    }
    returns.reverse();
    Ok(returns)
}
