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

/// ArduPilot's sprayer stops its pump below this ground speed (`SPRAY_SPEED_MIN`, default
/// 100 cm/s, `AC_Sprayer`) once it has been below it for [`SPRAYER_SHUT_OFF_DELAY_S`]: a
/// spray leg held back below it by a climb for longer goes unsprayed.
pub const SPRAYER_SPEED_MIN_MPS: f64 = 1.0;

/// How long ArduPilot's sprayer keeps pumping below `SPRAY_SPEED_MIN`, seconds
/// (`AC_SPRAYER_DEFAULT_SHUT_OFF_DELAY`, 1,000 ms).
pub const SPRAYER_SHUT_OFF_DELAY_S: f64 = 1.0;

/// ArduPilot's pump through one spray run (`AC_Sprayer`): off when `DO_SPRAYER` switches the
/// sprayer on until the vehicle is at `SPRAY_SPEED_MIN` (after 100 ms, not modelled), then on
/// until it has been under that speed for [`SPRAYER_SHUT_OFF_DELAY_S`]. A new run starts
/// it afresh ([`Pump::default`]).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Pump {
    pumping: bool,
    slow_s: f64,
}

/// The check's tally, before any leg.
pub(super) fn tally() -> Tally {
    Tally::new(
        "spray speed",
        "≤",
        MAX_SPRAY_SPEED_SHARE,
        "share off the spray speed",
    )
}

/// Records spray leg `leg` of sortie `sortie` (`horizontal` metres, `rise` metres up) flown by
/// `vehicle` with its pump switched by `sprayer`. Returns
/// whether ArduPilot's pump is off on this leg (`pump`: its state through the run): its strip
/// is then not sprayed, which the coverage as flown counts (a bank a few metres high leaves a
/// short gap; a face climbed for a swath's length fails the coverage). A leg on which the pump
/// stops counts whole: the second it keeps pumping is not credited.
pub(super) fn record(
    tally: &mut Tally,
    leg: &Leg,
    (horizontal, rise): (f64, f64),
    vehicle: &Vehicle,
    sprayer: SprayerCommand,
    sortie: usize,
    pump: &mut Pump,
) -> bool {
    // Over ground steeper than the vehicle climbs at the commanded speed, the climb (or
    // descent) holds it back along the leg (the autopilot keeps its vertical speed limit). A
    // pump on a servo output runs at one flow, so the slower crossing doses more; ArduPilot's
    // sprayer (DO_SPRAYER) pumps in proportion to ground speed, and a camera triggers by
    // distance, so theirs does not change.
    // But below SPRAY_SPEED_MIN for longer than its shut-off delay ArduPilot's pump stops:
    // over ground that steep (a third trial's swaths up a 78° face, crossed at 0.61 m/s) the
    // strip goes unsprayed.
    let held_back_mps = horizontal / (horizontal / leg.speed_mps).max(vehicle.vertical_s(rise));
    let (vertical, vertical_mps) = if rise >= 0.0 {
        (rise, vehicle.climb_speed_mps)
    } else {
        (-rise, vehicle.descent_mps())
    };
    let constant_flow = matches!(sprayer, SprayerCommand::Servo { .. }) && vehicle.camera.is_none();
    let do_sprayer = matches!(sprayer, SprayerCommand::DoSprayer) && vehicle.camera.is_none();
    let pump_stops = if !do_sprayer {
        false
    } else if held_back_mps >= SPRAYER_SPEED_MIN_MPS {
        *pump = Pump {
            pumping: true,
            slow_s: 0.0,
        };
        false
    } else if pump.pumping {
        pump.slow_s += horizontal / held_back_mps;
        pump.pumping = pump.slow_s <= SPRAYER_SHUT_OFF_DELAY_S;
        !pump.pumping
    } else {
        // A run that starts slow, or a pump already stopped: nothing until speed is back.
        true
    };
    let over_ground_mps = if constant_flow {
        held_back_mps
    } else {
        leg.speed_mps
    };
    let off = (over_ground_mps / vehicle.spray_speed_mps - 1.0).abs();
    let middle = ((leg.from.x + leg.to.x) / 2.0, (leg.from.y + leg.to.y) / 2.0);
    tally.record_at(middle, off, off > MAX_SPRAY_SPEED_SHARE, || {
        if over_ground_mps < leg.speed_mps * (1.0 - 1e-9) {
            format!(
                "sortie {sortie}, item {}: the ground {} {:.1} m over {:.1} m, more than the vehicle's {} speed ({} m/s) lets it follow at {:.1} m/s: it crosses at {:.1} m/s and the dose would be {:.0}% of the rate (terrain too steep to spray along; spray across the slope, or a vehicle that climbs faster)",
                leg.item,
                if rise >= 0.0 { "climbs" } else { "falls" },
                vertical,
                horizontal,
                if rise >= 0.0 { "climb" } else { "descent" },
                vertical_mps,
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
    pump_stops
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preflight::flown::{Height, Motion, Place};

    /// A spray leg `horizontal` metres east that climbs `climb` metres, at 5 m/s.
    fn leg(horizontal: f64, climb: f64) -> (Leg, (f64, f64)) {
        let place = |x: f64, z: f64| Place {
            x,
            y: 0.0,
            height: Height::SeaLevel(z),
        };
        let leg = Leg {
            item: 1,
            from: place(0.0, 0.0),
            to: place(horizontal, climb),
            spraying: true,
            speed_mps: 5.0,
            motion: Motion::Flight,
        };
        (leg, (horizontal, climb))
    }

    /// `AC_Sprayer`'s pump through runs of legs, at the default vehicle's 2 m/s climb: a
    /// 3 m climb over 1 m is crossed at 0.67 m/s (under SPRAY_SPEED_MIN), each such leg in
    /// 1.5 s; a level leg at 5 m/s. Returns whether the pump is off on each leg.
    fn run(legs: &[(f64, f64)], sprayer: SprayerCommand) -> Vec<bool> {
        let vehicle = Vehicle::default();
        let mut tally = tally();
        let mut pump = Pump::default();
        legs.iter()
            .map(|&(horizontal, climb)| {
                let (leg, figures) = leg(horizontal, climb);
                record(&mut tally, &leg, figures, &vehicle, sprayer, 1, &mut pump)
            })
            .collect()
    }

    #[test]
    fn the_pump_follows_ardupilots_sprayer_through_a_run() {
        let (level, steep, short_steep) = ((5.0, 0.0), (1.0, 3.0), (0.5, 1.5));
        let sprayer = SprayerCommand::DoSprayer;
        // Up to speed, then under it for 0.75 s: still pumping; for 1.5 s more: stopped;
        // back to speed: pumping again.
        assert_eq!(
            run(&[level, short_steep, steep, level], sprayer),
            [false, false, true, false]
        );
        // A run that starts slow never started its pump.
        assert_eq!(run(&[short_steep, level], sprayer), [true, false]);
        // A servo pump runs at one flow whatever the speed (its overdose is the check's).
        assert_eq!(
            run(
                &[level, steep, steep],
                SprayerCommand::Servo {
                    channel: 9,
                    on_pwm: 1900,
                    off_pwm: 1100
                }
            ),
            [false, false, false]
        );
    }
}
