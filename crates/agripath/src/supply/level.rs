//! Level ground for the supply point (decision 0029): the drone takes off and lands there and
//! the truck parks there, so `auto` keeps to ground no steeper than [`MAX_SLOPE`] where such
//! ground serves the route, and says so where it does not.
//!
//! The slope is the terrain's gradient by central differences [`STEP_M`] either way (on a
//! raster, the bilinear surface's slope across the point); a place without a height is not
//! level. Central differences do not see what is narrower than their span, centred on the
//! point (trial 8, decision 0036: a ditch one cell wide, the crest of a wall, the foot of a
//! mast read as level), so the ground is also read on rings round the point out to
//! [`STAND_RADIUS_M`]: nowhere within it may it rise or fall from the point's height by more
//! than [`MAX_SLOPE`] of the distance and [`BUMP_M`].

use geo::Coord;

use super::{SupplyCost, Surrogate};

/// Steepest ground the supply point may stand on, rise over run: 10 % (5.7°). Multirotor
/// makers ask for level ground to take off and land on, and a refill truck parked across a
/// steeper slope is not level either; the plan map's relief shading starts to show about there.
pub const MAX_SLOPE: f64 = 0.10;

/// Half the span of the central differences, metres.
pub const STEP_M: f64 = 2.0;

/// Radius round the supply point whose ground must be level, metres: the footprint of a
/// spraying drone (a DJI T16 is 2.5 m across its arms) and the reach of the central
/// differences.
pub const STAND_RADIUS_M: f64 = STEP_M;

/// Unevenness allowed within [`STAND_RADIUS_M`] beyond the slope, metres (a kerb, a DEM's
/// noise).
pub const BUMP_M: f64 = 0.1;

/// Radii of the rings the ground is read on, metres.
const RING_RADII_M: [f64; 6] = [0.25, 0.5, 0.75, 1.0, 1.5, STAND_RADIUS_M];

/// Directions read on each ring: on the outer ring, 0.79 m apart, so a feature one 1 m cell
/// wide (whose bilinear surface is 2 m wide) is met. On a raster finer than 0.4 m a feature
/// one cell wide can fall between two directions; the takeoff column's floor in the
/// preflight (decision 0036) still holds a face beside the point.
const RING_DIRECTIONS: usize = 16;

/// Why `point` is not level enough to stand on (module doc), or `None` when it is.
pub fn unlevel(ground: &dyn Fn(f64, f64) -> Option<f64>, point: Coord<f64>) -> Option<String> {
    let Some(slope) = slope_at(ground, point) else {
        return Some("the terrain has no height there".into());
    };
    if slope > MAX_SLOPE {
        return Some(format!("its ground slopes {:.1}%", 100.0 * slope));
    }
    let Some(here) = ground(point.x, point.y) else {
        return Some("the terrain has no height there".into());
    };
    let mut worst: Option<(f64, f64)> = None;
    for radius in RING_RADII_M {
        for direction in 0..RING_DIRECTIONS {
            let angle = std::f64::consts::TAU * direction as f64 / RING_DIRECTIONS as f64;
            let (x, y) = (
                point.x + radius * angle.cos(),
                point.y + radius * angle.sin(),
            );
            let Some(height) = ground(x, y) else {
                return Some("the terrain has no height beside it".into());
            };
            let step = (height - here).abs();
            let excess = step - (MAX_SLOPE * radius + BUMP_M);
            if excess > 0.0 && worst.is_none_or(|(worst, _)| excess > worst) {
                worst = Some((excess, height - here));
            }
        }
    }
    worst.map(|(_, rise)| {
        format!(
            "the ground {} {:.1} m within {STAND_RADIUS_M} m of it (a ditch, a wall, a mast or a bank)",
            if rise > 0.0 { "rises" } else { "falls" },
            rise.abs()
        )
    })
}

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
        unlevel(self.ground, point).is_none()
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

    /// A 1 m raster's one-cell features, read bilinearly as a DEM is: level ground 1 m either
    /// side of each by central differences, refused by the rings (trial 8's ditch, wall and
    /// mast beside a road).
    #[test]
    fn narrow_ditches_walls_and_masts_are_not_level_ground() {
        // Heights at the centres of 1 m cells (x, y integers + 0.5), bilinear between.
        let bilinear = |cell: fn(i64, i64) -> f64| {
            move |x: f64, y: f64| {
                let (u, v) = (x - 0.5, y - 0.5);
                let (i, j) = (u.floor(), v.floor());
                let (s, t) = (u - i, v - j);
                let (i, j) = (i as i64, j as i64);
                Some(
                    cell(i, j) * (1.0 - s) * (1.0 - t)
                        + cell(i + 1, j) * s * (1.0 - t)
                        + cell(i, j + 1) * (1.0 - s) * t
                        + cell(i + 1, j + 1) * s * t,
                )
            }
        };
        let ditch = bilinear(|_, j| if j == 0 { 97.0 } else { 100.0 });
        let wall = bilinear(|_, j| if j == 0 { 130.0 } else { 100.0 });
        let mast = bilinear(|i, j| if (i, j) == (3, 0) { 140.0 } else { 100.0 });
        let flat = bilinear(|_, _| 100.0);
        // The ditch's bottom and the wall's crest, and 1.25 m from the mast's centre, where
        // its bilinear surface ends: the central differences read them as level.
        let on_line = Coord { x: 0.5, y: 0.5 };
        let by_mast = Coord { x: 3.75, y: 1.5 };
        for (ground, point) in [
            (&ditch as &dyn Fn(f64, f64) -> Option<f64>, on_line),
            (&wall, on_line),
            (&mast, by_mast),
        ] {
            assert!(slope_at(ground, point).unwrap() <= MAX_SLOPE);
            let why = unlevel(ground, point).expect("not level");
            assert!(why.contains("within 2 m"), "{why}");
        }
        assert_eq!(unlevel(&flat, on_line), None);
        // A plane at the steepest slope allowed stays level; 4 m from the mast too.
        let plane = |x: f64, y: f64| Some(100.0 + 0.099 * x + 0.0 * y);
        assert_eq!(unlevel(&plane, on_line), None);
        assert_eq!(unlevel(&mast, Coord { x: 3.5, y: 4.5 }), None);
    }
}
