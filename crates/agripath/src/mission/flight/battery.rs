//! The sortie model the split plans with, charged for what the mission files fly beyond
//! seed 003's eq. 2: the climbs and descents of the out- and home-legs at climb and descent
//! speed, and the landing as ArduCopter flies it, over the terrain between the supply point
//! and the route (decisions 0012, 0034).
//!
//! Eq. 2 times each leg between a route point P and the supply point S as
//! (‖P, S‖ + |H_P − H_S| + 2h) / v_off. A mission flies it as this module's writer does: up
//! from S's ground to the cruise altitude, max ground under the leg and within 2 m of its
//! ends G + c (c = spray height + max(h, 5 m)), level at transit speed, down to P's spray
//! height, at climb speed w, and the same way back. Per sortie the two legs climb and descend
//!
//!   V = 4c − 2·spray height + e(first) + e(last),  e(P) = 2·G(P) − H_S − H_P ≥ |H_P − H_S|,
//!
//! so the battery reserve a sortie keeps beyond eq. 2's time is
//!
//!   V₀ / w − 2 · 2h / v_off   (V₀ = 4c − 2·spray height, the flat ground's; the 2h of both legs
//!                              eq. 2 already charges at transit speed)
//!   + 2 · max_P (e(P) / w − |H_P − H_S| / v_off)   (the terrain's, over the route's points).
//!
//! With a descent speed w↓ other than the climb speed w↑ (the vehicle's `descent_speed_mps`),
//! V₀ / w is the climbs (2c − spray height) / w↑, the descent to the first point
//! (c − spray height) / w↓ and the landing from c as ArduCopter flies it
//! ([`Vehicle::landing_s`]: the last 10 m at `land_speed_mps` when given); the terrain's e(P)
//! is the out-leg's climb G − H_S and descent G − H_P, or the home leg's climb G − H_P and
//! descent G − H_S, each at its speed, the dearer of the two legs taken for both.
//!
//! plus the share of the endurance the vehicle file says to land with
//! (`battery_reserve_percent`). The second term is the worst leg's, taken for both legs of every sortie: a bound, not the
//! sortie's own figure, so sorties over rough ground keep a little more battery than they
//! fly. On the flat it is 0. (The first term was V₀ / w − V₀ / v_off until 2026-12-05: right
//! when the legs' 2h equals the climb, 12 s short for a survey flown at 60 m, whose sorties
//! then flew 101.4 % of the battery as written; the preflight refused them.)

use crate::coverage::drape::GroundPoint;
use crate::error::Fault;
use crate::model::Vehicle;
use crate::sortie::route::RoutePoint;
use crate::sortie::SortieModel;
use crate::terrain::Terrain;

use super::{highest_ground, highest_ground_near, TRANSIT_CORRIDOR_M};

/// The sortie model of `vehicle` from `supply` on flat ground: eq. 2's legs with 2h, and the
/// battery reserve for the climbs at climb speed (the module's first term).
pub fn sortie_model(vehicle: &Vehicle, supply: RoutePoint) -> SortieModel {
    // Returns fly at the safe height, as transfers that leave the field do (decision 0008).
    let mut model = SortieModel::new(vehicle, supply, 2.0 * vehicle.safe_height_m);
    let (cruise_m, spray_m) = (vehicle.cruise_height_m(), vehicle.spray_height_m);
    // Up from the supply point and from the last point, down to the first point, and the
    // landing (4c − 2·spray height in all).
    let vertical_s = vehicle.vertical_s(2.0 * cruise_m - spray_m)
        + vehicle.vertical_s(spray_m - cruise_m)
        + vehicle.landing_s(cruise_m);
    let charged_m = 2.0 * model.return_climb_m;
    let reserve_s = vertical_s - charged_m / vehicle.transit_speed_mps;
    // No cap: a reserve the battery cannot hold leaves no usable time, and the split says
    // which route point cannot be reached (an input error), rather than plan sorties that
    // fly over the battery as written.
    // The share the operator lands with is held back from every sortie as well.
    let landing_s = vehicle.battery_endurance_s - vehicle.usable_battery_s();
    model.battery_reserve_s = reserve_s.max(0.0) + landing_s;
    model
}

/// The sortie model of `vehicle` from `supply` over `terrain`, for a route through `points`:
/// [`sortie_model`] with the terrain's term of the module's doc added to the reserve.
pub fn sortie_model_over(
    vehicle: &Vehicle,
    supply: RoutePoint,
    terrain: &dyn Terrain,
    points: impl IntoIterator<Item = GroundPoint>,
) -> Result<SortieModel, Fault> {
    let mut model = sortie_model(vehicle, supply);
    let points: Vec<GroundPoint> = points.into_iter().collect();
    // The writer clears the corridor beside each leg too (a mast is climbed over). Read in
    // full for every point it cost Christmas Island's plan 0.8 s, so the model reads the
    // corridor round both ends, where the supply point's own neighbourhood (trial 8's mast
    // and pylon) is shared by every leg, and the leg's own line between; a mast beside the
    // middle of a leg is left to the re-plan that holds back what the files overrun
    // (decision 0012).
    let around = |x: f64, y: f64| highest_ground_near(terrain, (x, y), (x, y), TRANSIT_CORRIDOR_M);
    let around_supply = around(supply.x, supply.y)?;
    // Each point's leg sampled every metre as the writer samples it: thousands of terrain
    // queries per point, so the points are shared among the machine's cores.
    let extras = crate::parallel::try_map_in_order(&points, |_, point| {
        let highest = highest_ground(terrain, (supply.x, supply.y), (point.x, point.y))?
            .max(around_supply)
            .max(around(point.x, point.y)?)
            .max(supply.ground_m)
            .max(point.ground_m);
        // Out: up G − H_S, down G − H_P; home: up G − H_P, down G − H_S (e(P) in all).
        let (from_supply_m, from_point_m) = (highest - supply.ground_m, highest - point.ground_m);
        let out_s = vehicle.vertical_s(from_supply_m) + vehicle.vertical_s(-from_point_m);
        let home_s = vehicle.vertical_s(from_point_m) + vehicle.vertical_s(-from_supply_m);
        let charged_m = (point.ground_m - supply.ground_m).abs();
        Ok::<f64, Fault>(out_s.max(home_s) - charged_m / vehicle.transit_speed_mps)
    })?;
    let worst_s = extras.into_iter().fold(0.0, f64::max);
    model.battery_reserve_s += (2.0 * worst_s).max(0.0);
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::TerrainError;
    use crate::terrain::{Extent, Flat};

    /// A ridge 30 m high at x = 100 (40 m wide at its foot), the ground beyond x = 150 at 10 m.
    struct Ridge;

    impl Terrain for Ridge {
        fn height_m(&self, x: f64, _y: f64) -> Result<f64, TerrainError> {
            let ridge = 30.0 * (1.0 - ((x - 100.0) / 20.0).abs()).max(0.0);
            Ok(ridge + if x > 150.0 { 10.0 } else { 0.0 })
        }

        fn extent(&self) -> Option<Extent> {
            None
        }

        fn describe(&self) -> String {
            "a ridge".into()
        }
    }

    #[test]
    fn the_reserve_pays_for_the_climbs_eq_2_does_not_charge() {
        let vehicle = crate::model::Vehicle::default();
        let supply = RoutePoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        };
        let model = sortie_model(&vehicle, supply);
        // Climbed and descended at climb speed, minus what eq. 2's two legs charge (2h each).
        let cruise = vehicle.spray_height_m + vehicle.safe_height_m.max(5.0);
        let climbed = 4.0 * cruise - 2.0 * vehicle.spray_height_m;
        let expected = climbed / vehicle.climb_speed_mps
            - 4.0 * vehicle.safe_height_m / vehicle.transit_speed_mps;
        assert!((model.battery_reserve_s - expected).abs() < 1e-9);
        // A survey at 60 m: the legs charge 2 × 2h = 80 m, the drone climbs 200 m.
        let survey = Vehicle {
            spray_height_m: 60.0,
            safe_height_m: 20.0,
            climb_speed_mps: 4.0,
            transit_speed_mps: 10.0,
            battery_endurance_s: 600.0,
            ..vehicle
        };
        assert!((sortie_model(&survey, supply).battery_reserve_s - 42.0).abs() < 1e-9);
        // Landing with a fifth of a 600 s battery holds back 120 s more.
        let careful = Vehicle {
            battery_reserve_percent: 20.0,
            ..survey.clone()
        };
        assert!((sortie_model(&careful, supply).battery_reserve_s - 162.0).abs() < 1e-9);
    }

    /// ArduCopter's defaults (climb 2.5 m/s, `WPNAV_SPEED_DN` 1.5 m/s, `LAND_SPEED` 0.5 m/s
    /// below `LAND_ALT_LOW` 10 m): the descents and the landing are charged at them (fifth
    /// trial: a landing charged at the climb speed ate into the battery reserve).
    #[test]
    fn descents_and_the_landing_are_charged_at_their_own_speeds() {
        let arducopter = Vehicle {
            climb_speed_mps: 2.5,
            descent_speed_mps: Some(1.5),
            land_speed_mps: Some(0.5),
            ..Vehicle::default()
        };
        // Cruise c = 2 + 18 = 20 m: 10 m at 1.5 m/s, then 10 m at 0.5 m/s.
        assert!((arducopter.landing_s(20.0) - (10.0 / 1.5 + 20.0)).abs() < 1e-12);
        assert!((arducopter.landing_s(6.0) - 12.0).abs() < 1e-12);
        assert!((arducopter.vertical_s(-3.0) - 2.0).abs() < 1e-12);
        assert!((arducopter.vertical_s(5.0) - 2.0).abs() < 1e-12);
        let supply = RoutePoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        };
        let reserve = sortie_model(&arducopter, supply).battery_reserve_s;
        let expected = (2.0 * 20.0 - 2.0) / 2.5 + (20.0 - 2.0) / 1.5 + (10.0 / 1.5 + 20.0)
            - 4.0 * 18.0 / arducopter.transit_speed_mps;
        assert!((reserve - expected).abs() < 1e-9, "{reserve} {expected}");
        // 23.5 s more per sortie than with every metre at the climb speed.
        let symmetric = Vehicle {
            descent_speed_mps: None,
            land_speed_mps: None,
            ..arducopter.clone()
        };
        let more = reserve - sortie_model(&symmetric, supply).battery_reserve_s;
        assert!(
            (more - (12.0 + 26.0 + 2.0 / 3.0 - 38.0 / 2.5)).abs() < 1e-9,
            "{more}"
        );
    }

    #[test]
    fn a_hill_between_the_supply_point_and_the_route_adds_its_climbs() {
        let vehicle = crate::model::Vehicle::default();
        let supply = RoutePoint {
            x: 0.0,
            y: 0.0,
            ground_m: 0.0,
        };
        let point = GroundPoint {
            x: 200.0,
            y: 0.0,
            ground_m: 10.0,
        };
        let flat = sortie_model(&vehicle, supply).battery_reserve_s;
        let over = sortie_model_over(&vehicle, supply, &Ridge, [point])
            .unwrap()
            .battery_reserve_s;
        // e = 2·30 − 0 − 10 = 50 m at climb speed, less the 10 m eq. 2 charges, both legs.
        let expected = 2.0 * (50.0 / vehicle.climb_speed_mps - 10.0 / vehicle.transit_speed_mps);
        assert!(
            (over - flat - expected).abs() < 1e-6,
            "{over} {flat} {expected}"
        );
        // On the flat, nothing is added.
        let plain = Flat::new(0.0);
        let level = GroundPoint {
            ground_m: 0.0,
            ..point
        };
        let same = sortie_model_over(&vehicle, supply, &plain, [level])
            .unwrap()
            .battery_reserve_s;
        assert!((same - flat).abs() < 1e-12);
    }
}
