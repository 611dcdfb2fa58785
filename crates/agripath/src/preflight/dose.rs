//! The preflight's `spray speed` check: the dose per hectare is the flow over the ground
//! speed, so a spray leg crossed faster or slower than the vehicle's spray speed under- or
//! over-doses the crop however well it covers it (a speed item edited in a ground station,
//! decision 0027; a climb the vehicle cannot make at speed, decision 0028).

use super::flown::Leg;
use super::verdict::Tally;
use crate::mission::flight::SprayerCommand;
use crate::model::Vehicle;

/// Most a spray leg's speed over the ground may differ from the vehicle's spray speed, as a
/// share of it: the dose then stays within ±10 % of the rate, the tolerance sprayer inspections
/// (ISO 16122) hold a nozzle's flow to.
pub const MAX_SPRAY_SPEED_SHARE: f64 = 0.10;

/// The check's tally, before any leg.
pub(super) fn tally() -> Tally {
    Tally::new(
        "spray speed",
        "≤",
        MAX_SPRAY_SPEED_SHARE,
        "share off the spray speed",
    )
}

/// Records spray leg `leg` of sortie `sortie` (`horizontal` and `vertical` metres) flown by
/// `vehicle` with its pump switched by `sprayer`.
pub(super) fn record(
    tally: &mut Tally,
    leg: &Leg,
    (horizontal, vertical): (f64, f64),
    vehicle: &Vehicle,
    sprayer: SprayerCommand,
    sortie: usize,
) {
    // Over ground steeper than the vehicle climbs at the commanded speed, the climb (or
    // descent) holds it back along the leg (the autopilot keeps its vertical speed limit). A
    // pump on a servo output runs at one flow, so the slower crossing doses more; ArduPilot's
    // sprayer (DO_SPRAYER) pumps in proportion to ground speed, and a camera triggers by
    // distance, so theirs does not change.
    let constant_flow = matches!(sprayer, SprayerCommand::Servo { .. }) && vehicle.camera.is_none();
    let over_ground_mps = if constant_flow {
        horizontal / (horizontal / leg.speed_mps).max(vertical / vehicle.climb_speed_mps)
    } else {
        leg.speed_mps
    };
    let off = (over_ground_mps / vehicle.spray_speed_mps - 1.0).abs();
    let middle = ((leg.from.x + leg.to.x) / 2.0, (leg.from.y + leg.to.y) / 2.0);
    tally.record_at(middle, off, off > MAX_SPRAY_SPEED_SHARE, || {
        if over_ground_mps < leg.speed_mps * (1.0 - 1e-9) {
            format!(
                "sortie {sortie}, item {}: the ground climbs or falls {:.1} m over {:.1} m, more than the vehicle's climb speed ({} m/s) lets it follow at {:.1} m/s: it crosses at {:.1} m/s and the dose would be {:.0}% of the rate (terrain too steep to spray along; spray across the slope, or a vehicle that climbs faster)",
                leg.item,
                vertical,
                horizontal,
                vehicle.climb_speed_mps,
                leg.speed_mps,
                over_ground_mps,
                100.0 * vehicle.spray_speed_mps / over_ground_mps
            )
        } else {
            format!(
                "sortie {sortie}, item {}: spraying at {:.1} m/s, not the vehicle's {} m/s (± {:.0}%): the dose would be {:.0}% of the rate",
                leg.item,
                leg.speed_mps,
                vehicle.spray_speed_mps,
                100.0 * MAX_SPRAY_SPEED_SHARE,
                100.0 * vehicle.spray_speed_mps / leg.speed_mps
            )
        }
    });
}
