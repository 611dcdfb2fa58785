//! `simple`: seed 003's simple plan. Return points lie on the supply side of the field: at the
//! end of a swath flown towards the supply point, the last such end the tank and battery allow
//! (seed 003 §2.2 places them "on the field boundary where the supply point is, within what
//! the tank allows"). Where no swath end fits in a sortie, the drone returns where it runs
//! out, as `unplanned` does.

use super::route::WorkRoute;
use super::unplanned::run_out;
use super::SortieModel;
use crate::error::Fault;

/// The ends of swaths flown towards the supply point (their last point nearer to it than
/// their first), in route order: where a drone finishing a swath is on the supply side.
pub fn supply_side_ends(route: &WorkRoute, model: &SortieModel) -> Vec<usize> {
    let points = route.points();
    route
        .spray_run_starts()
        .iter()
        .zip(route.spray_run_ends())
        .filter(|&(&start, end)| model.leg_m(&points[end]) < model.leg_m(&points[start]))
        .map(|(_, end)| end)
        .collect()
}

/// The break points of the simple plan.
pub fn breaks(route: &WorkRoute, model: &SortieModel) -> Result<Vec<usize>, Fault> {
    let candidates = supply_side_ends(route, model);
    let end = route.len() - 1;
    let mut breaks = Vec::new();
    let mut first = 0;
    loop {
        let limit = run_out(route, model, first);
        if limit == end {
            return Ok(breaks);
        }
        if limit == first {
            return Err(Fault::Structure(format!(
                "no sortie can leave route point {first}: one step is beyond one tank or battery"
            )));
        }
        // The last supply-side end in (first, limit] that one tank and battery fly.
        let upto = candidates.partition_point(|&c| c <= limit);
        let chosen = candidates[..upto]
            .iter()
            .rev()
            .take_while(|&&c| c > first)
            .find(|&&c| model.feasible(route, first, c))
            .copied()
            .unwrap_or(limit);
        breaks.push(chosen);
        first = chosen;
    }
}
