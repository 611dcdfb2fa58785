//! `unplanned`: fly on until the tank or the battery runs out, then return from wherever the
//! drone is (seed 003's baseline). The break is the last route point before one more step
//! would empty the tank or leave too little battery to fly back.

use super::route::WorkRoute;
use super::SortieModel;
use crate::error::Fault;

/// Where the drone runs out, flying on from `first`: the last point it can reach and return
/// from.
pub(crate) fn run_out(route: &WorkRoute, model: &SortieModel, first: usize) -> usize {
    let mut last = first;
    while last + 1 < route.len() && model.feasible(route, first, last + 1) {
        last += 1;
    }
    last
}

/// The break points of the unplanned flight.
pub fn breaks(route: &WorkRoute, model: &SortieModel) -> Result<Vec<usize>, Fault> {
    let end = route.len() - 1;
    let mut breaks = Vec::new();
    let mut first = 0;
    loop {
        let last = run_out(route, model, first);
        if last == end {
            return Ok(breaks);
        }
        if last == first {
            return Err(Fault::Structure(format!(
                "no sortie can leave route point {first}: one step is beyond one tank or battery"
            )));
        }
        breaks.push(last);
        first = last;
    }
}
