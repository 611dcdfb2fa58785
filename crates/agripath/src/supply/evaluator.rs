//! The default supply point evaluator: the route's order kept fixed, the point scored by the
//! exact split of that route into sorties from it (docs/decisions/0016-supply-point.md).
//!
//! For a supply point P and the route planned without a start point (points p_0 … p_n), the
//! plan's non-spray time is
//!
//! C(P) = E*(P) + (‖p_0, P‖ + H_0 + 2h) / v_off + (‖p_n, P‖ + H_n + 2h) / v_off
//!
//! with E*(P) seed 003's objective (eq. 2: turns and transfers along the route, then per
//! return its round trip and max(T_e, T_p), eq. 5) at the `exact` split's optimal breaks
//! for P, and the last two terms the first leg out and the last leg home, which E leaves out
//! because they are the same for every split from one P ([`plan_cost_s`]). C is infinite
//! where no split flies from P on one tank and battery per sortie.
//!
//! The surrogate near a point A keeps A's breaks B and re-costs them from P:
//! C_B(P) = E_B(P) + the two legs, O(sorties) instead of O(points × points per sortie). It
//! equals C at A, and C(P) ≤ C_B(P) wherever B is flyable from P (the exact split can only do
//! better), so a point the surrogate improves on is one the split improves on at least as
//! much; where B is not flyable from P it is infinite.

use geo::Coord;

use super::{SupplyCost, Surrogate};
use crate::sortie::route::{RoutePoint, WorkRoute};
use crate::sortie::{plan_sorties, SortieModel, SortiePlan, SortiePlanner};

/// The non-spray seconds of `plan` flown from and back to `model.supply`: E (eq. 2) plus the
/// first leg out and the last leg home.
pub fn plan_cost_s(route: &WorkRoute, model: &SortieModel, plan: &SortiePlan) -> f64 {
    let legs_m = match (route.points().first(), route.points().last()) {
        (Some(first), Some(last)) => model.leg_m(first) + model.leg_m(last),
        _ => 0.0,
    };
    plan.objective_s() + legs_m / model.transit_mps
}

/// The default evaluator: a fixed route, split exactly from each point scored.
pub struct FixedRouteSplit<'a> {
    route: &'a WorkRoute,
    /// The vehicle's sortie model; its supply point is replaced by the point scored.
    model: SortieModel,
    /// Whether the plan is split into sorties (`false`: one flight, no returns).
    split: bool,
    /// Terrain height at (x, y), `None` where the terrain model has no answer.
    ground: &'a dyn Fn(f64, f64) -> Option<f64>,
}

impl<'a> FixedRouteSplit<'a> {
    /// The evaluator of `route` with `model`'s vehicle figures (its supply point is ignored);
    /// `split`: whether the plan has sorties; `ground`: the terrain height.
    pub fn new(
        route: &'a WorkRoute,
        model: SortieModel,
        split: bool,
        ground: &'a dyn Fn(f64, f64) -> Option<f64>,
    ) -> Self {
        Self {
            route,
            model,
            split,
            ground,
        }
    }

    /// The model with its supply point at `point`, or `None` where the terrain has no height.
    fn model_at(&self, point: Coord<f64>) -> Option<SortieModel> {
        let ground_m = (self.ground)(point.x, point.y)?;
        Some(SortieModel {
            supply: RoutePoint {
                x: point.x,
                y: point.y,
                ground_m,
            },
            ..self.model.clone()
        })
    }

    /// The split from `point` with its cost, or `None` where none flies.
    fn split_at(&self, point: Coord<f64>) -> Option<(SortieModel, SortiePlan)> {
        let model = self.model_at(point)?;
        let plan = if self.split {
            plan_sorties(self.route, &model, SortiePlanner::Exact, 0).ok()?
        } else {
            model.evaluate(self.route, SortiePlanner::Exact, Vec::new())
        };
        Some((model, plan))
    }

    /// The surrogate of the split `plan` (found from some point): its breaks kept, re-costed
    /// from `point`. E_B(P) = D_u / v_u + Σ max(T_e, T_p) + Σ_b 2 (‖P_b, P‖ + H_b + 2h) / v_off:
    /// the first two sums do not depend on P (the refills depend on the sorties' spray), so
    /// they are taken from `plan`; infinite where a sortie is not flyable from `point`.
    fn cost_with_breaks_s(&self, point: Coord<f64>, plan: &SortiePlan) -> f64 {
        let Some(model) = self.model_at(point) else {
            return f64::INFINITY;
        };
        if self.split
            && !plan
                .sorties
                .iter()
                .all(|sortie| model.feasible(self.route, sortie.first, sortie.last))
        {
            return f64::INFINITY;
        }
        let points = self.route.points();
        let round_trips_m: f64 = plan
            .breaks
            .iter()
            .map(|&at| 2.0 * model.leg_m(&points[at]))
            .sum();
        let fixed_s = plan.turn_time_s + plan.service_s;
        let legs_m = match (points.first(), points.last()) {
            (Some(first), Some(last)) => model.leg_m(first) + model.leg_m(last),
            _ => 0.0,
        };
        fixed_s + (round_trips_m + legs_m) / model.transit_mps
    }
}

impl SupplyCost for FixedRouteSplit<'_> {
    fn cost_s(&self, point: Coord<f64>) -> f64 {
        self.split_at(point).map_or(f64::INFINITY, |(model, plan)| {
            plan_cost_s(self.route, &model, &plan)
        })
    }

    fn cost_and_surrogate(&self, around: Coord<f64>) -> (f64, Surrogate<'_>) {
        match self.split_at(around) {
            Some((model, plan)) => (
                plan_cost_s(self.route, &model, &plan),
                Box::new(move |point| self.cost_with_breaks_s(point, &plan)),
            ),
            None => (f64::INFINITY, Box::new(|point| self.cost_s(point))),
        }
    }

    fn describe(&self) -> &'static str {
        if self.split {
            "the route planned without a start point, split exactly into sorties from the point, plus the first leg out and the last leg home"
        } else {
            "the route planned without a start point, flown in one flight from the point and back"
        }
    }
}
