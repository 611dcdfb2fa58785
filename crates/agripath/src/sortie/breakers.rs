//! The sortie planners behind one signature ([`BreakRoute`]), and the registry that picks
//! one by [`SortiePlanner`].

use super::route::WorkRoute;
use super::{exact, gsa, simple, unplanned, Return, SortieModel, SortiePlanner};
use crate::error::Fault;

/// A way to split a route into sorties: the one signature every sortie planner has. The
/// result is the returns to the supply point, in route order.
pub trait BreakRoute {
    /// Where the vehicle returns and resumes; `seed` drives the stochastic planners.
    fn returns(
        &self,
        route: &WorkRoute,
        model: &SortieModel,
        seed: u64,
    ) -> Result<Vec<Return>, Fault>;
}

/// The seed's planners: they break the route at points and resume where they broke off.
struct Planned(fn(&WorkRoute, &SortieModel) -> Result<Vec<usize>, Fault>);

/// Returns that resume where they broke off.
fn resuming_in_place(breaks: Vec<usize>) -> Vec<Return> {
    breaks
        .into_iter()
        .map(|at| Return { at, resume: at })
        .collect()
}

impl BreakRoute for Planned {
    fn returns(
        &self,
        route: &WorkRoute,
        model: &SortieModel,
        _seed: u64,
    ) -> Result<Vec<Return>, Fault> {
        (self.0)(route, model).map(resuming_in_place)
    }
}

impl BreakRoute for gsa::GsaSettings {
    fn returns(
        &self,
        route: &WorkRoute,
        model: &SortieModel,
        seed: u64,
    ) -> Result<Vec<Return>, Fault> {
        Ok(resuming_in_place(
            gsa::search(route, model, self, seed)?.breaks,
        ))
    }
}

/// Ours: the optimal returns, skipping the turn or transfer after a return where that pays.
struct Exact;

impl BreakRoute for Exact {
    fn returns(
        &self,
        route: &WorkRoute,
        model: &SortieModel,
        _seed: u64,
    ) -> Result<Vec<Return>, Fault> {
        exact::returns(route, model)
    }
}

impl SortiePlanner {
    /// The planner itself: the registry of [`BreakRoute`] implementations.
    pub fn breaker(self) -> Box<dyn BreakRoute> {
        match self {
            SortiePlanner::Unplanned => Box::new(Planned(unplanned::breaks)),
            SortiePlanner::Simple => Box::new(Planned(simple::breaks)),
            SortiePlanner::Gsa => Box::new(gsa::GsaSettings::default()),
            // The joint planner reorders the route first (the pipeline's job); its returns
            // on the route it keeps are the exact split's.
            SortiePlanner::Exact | SortiePlanner::Joint => Box::new(Exact),
        }
    }
}
