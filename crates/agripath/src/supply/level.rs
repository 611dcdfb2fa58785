//! Level ground for the supply point (decision 0029): the drone takes off and lands there and
//! the truck parks there, so `auto` keeps to ground no steeper than [`MAX_SLOPE`] where such
//! ground serves the route, and says so where it does not.
//!
//! The slope is the terrain's gradient by central differences [`STEP_M`] either way (on a
//! raster, the bilinear surface's slope across the point); a place without a height is not
//! level.

use geo::Coord;

use super::{SupplyCost, Surrogate};

/// Steepest ground the supply point may stand on, rise over run: 10 % (5.7°). Multirotor
/// makers ask for level ground to take off and land on, and a refill truck parked across a
/// steeper slope is not level either; the plan map's relief shading starts to show about there.
pub const MAX_SLOPE: f64 = 0.10;

/// Half the span of the central differences, metres.
pub const STEP_M: f64 = 2.0;

/// The ground's slope at `point` (rise over run), from heights `ground(x, y)`; `None` where a
/// height is missing.
pub fn slope_at(ground: &dyn Fn(f64, f64) -> Option<f64>, point: Coord<f64>) -> Option<f64> {
    let (x, y) = (point.x, point.y);
    let east = ground(x + STEP_M, y)? - ground(x - STEP_M, y)?;
    let north = ground(x, y + STEP_M)? - ground(x, y - STEP_M)?;
    Some(east.hypot(north) / (2.0 * STEP_M))
}

/// An evaluator that refuses (an infinite cost) every point on ground steeper than
/// [`MAX_SLOPE`], and otherwise asks `inner`.
pub struct OnLevelGround<'a> {
    /// The evaluator asked on level ground.
    pub inner: &'a dyn SupplyCost,
    /// The terrain's height at (x, y).
    pub ground: &'a dyn Fn(f64, f64) -> Option<f64>,
}

impl OnLevelGround<'_> {
    fn level(&self, point: Coord<f64>) -> bool {
        slope_at(self.ground, point).is_some_and(|slope| slope <= MAX_SLOPE)
    }
}

impl SupplyCost for OnLevelGround<'_> {
    fn cost_s(&self, point: Coord<f64>) -> f64 {
        if self.level(point) {
            self.inner.cost_s(point)
        } else {
            f64::INFINITY
        }
    }

    fn cost_and_surrogate(&self, around: Coord<f64>) -> (f64, Surrogate<'_>) {
        let (cost, surrogate) = self.inner.cost_and_surrogate(around);
        let cost = if self.level(around) {
            cost
        } else {
            f64::INFINITY
        };
        (
            cost,
            Box::new(move |point| {
                if self.level(point) {
                    surrogate(point)
                } else {
                    f64::INFINITY
                }
            }),
        )
    }

    fn describe(&self) -> &'static str {
        self.inner.describe()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_is_the_gradient_and_steep_ground_is_refused() {
        // A plane rising 15 % to the east and 20 % to the north: 25 % in all.
        let plane = |x: f64, y: f64| Some(0.15 * x + 0.2 * y);
        let slope = slope_at(&plane, Coord { x: 3.0, y: -7.0 }).unwrap();
        assert!((slope - 0.25).abs() < 1e-12);
        let cost = |_: Coord<f64>| 42.0;
        let steep = OnLevelGround {
            inner: &cost,
            ground: &plane,
        };
        assert!(steep.cost_s(Coord { x: 0.0, y: 0.0 }).is_infinite());
        let gentle = |x: f64, _: f64| Some(0.05 * x);
        let level = OnLevelGround {
            inner: &cost,
            ground: &gentle,
        };
        assert_eq!(level.cost_s(Coord { x: 0.0, y: 0.0 }), 42.0);
        let (at, surrogate) = level.cost_and_surrogate(Coord { x: 0.0, y: 0.0 });
        assert_eq!((at, surrogate(Coord { x: 5.0, y: 5.0 })), (42.0, 42.0));
        // No height: not level.
        let nowhere = |_: f64, _: f64| None;
        let unknown = OnLevelGround {
            inner: &cost,
            ground: &nowhere,
        };
        assert!(unknown.cost_s(Coord { x: 0.0, y: 0.0 }).is_infinite());
    }
}
