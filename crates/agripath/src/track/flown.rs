//! The track as its mission file flies it: what the safety verdict checks.
//!
//! A planner's track is a polyline; its `.waypoints` file holds fewer places (each once, a
//! smoothed curve thinned to at most [`MOST_CRUISE_WAYPOINTS`]) and ArduPilot's reading of
//! them (NAV_TAKEOFF climbs where the vehicle stands, NAV_WAYPOINT flies straight, NAV_LAND
//! flies to its place at the altitude it has, then descends). Until 2026-12-07 the verdict
//! checked the planner's polyline, and a track whose goal was above the band's floor ended
//! on a NAV_LAND straight from the last cruise waypoint: ArduPilot flew it level, into a cliff
//! below the goal (the fourth trial: 43 m under the ground, reported safe). Now the file
//! always holds a waypoint above the goal, and the verdict checks the places the file holds,
//! flown straight between them; `flown_is_what_the_file_flies` reads the file back through
//! the preflight's model of ArduPilot and compares.

use super::scenario::TrackScenario;

/// Most cruise waypoints a track's mission file holds (a smoothed curve is thinned evenly).
pub const MOST_CRUISE_WAYPOINTS: usize = 100;

/// Track points closer than this, metres, are one waypoint (the files give places to ~0.1 mm
/// and altitudes to 1 mm).
const SAME_PLACE_M: f64 = 0.01;

/// The cruise's places the mission file holds, in order, altitudes above sea level: the
/// cruise's first point (where the takeoff climbs to), its points each once (a lattice path or
/// a smoothed curve may repeat one: a clamped spline's ends, a knot the refinement left in
/// place, which would be a waypoint flown to where the drone already is), evenly thinned to
/// at most [`MOST_CRUISE_WAYPOINTS`], and its last point (above the goal).
pub fn mission_cruise(scenario: &TrackScenario, track: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let (cruise, _) = scenario.cruise_of(track);
    let mut points: Vec<[f64; 3]> = Vec::with_capacity(cruise.len());
    for &point in cruise {
        let repeated = points.last().is_some_and(|last: &[f64; 3]| {
            (0..3).map(|k| (point[k] - last[k]).powi(2)).sum::<f64>() < SAME_PLACE_M * SAME_PLACE_M
        });
        if !repeated {
            points.push(point);
        }
    }
    // The first and the last always, and every stride-th between: at most
    // MOST_CRUISE_WAYPOINTS in all.
    let last = points.len() - 1;
    let stride = if points.len() <= MOST_CRUISE_WAYPOINTS {
        1
    } else {
        last.div_ceil(MOST_CRUISE_WAYPOINTS - 2)
    };
    points
        .iter()
        .enumerate()
        .filter(|&(index, _)| index == 0 || index == last || index % stride == 0)
        .map(|(_, &point)| point)
        .collect()
}

/// The whole track as its mission file flies it (the vertical legs at the start and the goal
/// as the scenario has them): what [`super::safety::check`] is given.
pub fn as_flown(scenario: &TrackScenario, track: &[[f64; 3]]) -> Vec<[f64; 3]> {
    scenario.whole_track(&mission_cruise(scenario, track))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::flight::SprayerCommand;
    use crate::preflight::flown::{fly, Height, Motion, StartSpeeds};
    use crate::preflight::read_back::read_waypoints;

    /// The places `text` (a track's `.waypoints`) flies to in the air, read back through the
    /// preflight's model of ArduPilot, in the scenario's plane, altitudes above sea level.
    fn read_back(scenario: &TrackScenario, text: &str) -> Vec<([f64; 3], Motion)> {
        let file = read_waypoints(text).expect("a waypoints file");
        let (lat, lon, ground) = file.home;
        let home = scenario.from_lon_lat(lon, lat);
        let legs = fly(
            &file.items,
            home,
            ground,
            SprayerCommand::DoSprayer,
            StartSpeeds {
                horizontal_mps: 5.0,
                climb_mps: 2.5,
                descent_mps: 1.5,
            },
            &|lon, lat| scenario.from_lon_lat(lon, lat),
        )
        .expect("flyable");
        legs.iter()
            .map(|leg| {
                let z = match leg.to.height {
                    Height::SeaLevel(z) => z,
                    Height::AboveTerrain(above) => {
                        above + scenario.terrain.height(leg.to.x, leg.to.y)
                    }
                };
                ([leg.to.x, leg.to.y, z], leg.motion)
            })
            .collect()
    }

    #[test]
    fn flown_is_what_the_file_flies() {
        // The orchard's tracks: a straight one, and one with the goal raised above the
        // band's floor, where the file used to end on a NAV_LAND flown level.
        for raise in [0.0, 40.0] {
            let mut scenario = TrackScenario::seed000("I").unwrap();
            scenario.goal[2] += raise;
            let limits = scenario.limits;
            let scenario = scenario.with_limits(limits).unwrap();
            let (a, b) = (scenario.cruise_start, scenario.cruise_goal);
            let cruise: Vec<[f64; 3]> = (0..=300)
                .map(|k| {
                    let t = f64::from(k) / 300.0;
                    let p = [0, 1, 2].map(|axis| a[axis] + t * (b[axis] - a[axis]));
                    scenario.sea_level([p[0], p[1], p[2] + 60.0 * (std::f64::consts::PI * t).sin()])
                })
                .collect();
            let track = scenario.whole_track(&cruise);
            let text = super::super::files::mission(&scenario, &track);
            let read = read_back(&scenario, &text);
            let flown = as_flown(&scenario, &track);
            // Every place the file flies to in the air is a place of the flown track, in
            // order, to the file's rounding; the last leg is a vertical landing.
            let mut airborne: Vec<[f64; 3]> = read
                .iter()
                .filter(|(_, motion)| *motion != Motion::Landing)
                .map(|(place, _)| *place)
                .collect();
            // The NAV_LAND's level leg to above its place: none, as the waypoint before it
            // is there already.
            airborne.dedup_by(|a, b| (0..3).all(|axis| (a[axis] - b[axis]).abs() < 1e-3));
            let (cruise_flown, _) = scenario.cruise_of(&flown);
            // The takeoff's place is above home; then the cruise's places.
            assert_eq!(airborne.len(), cruise_flown.len(), "raise {raise}");
            for (file, ours) in airborne.iter().zip(cruise_flown) {
                for axis in 0..3 {
                    assert!(
                        (file[axis] - ours[axis]).abs() < 0.01,
                        "raise {raise}: {file:?} {ours:?}"
                    );
                }
            }
            let (landing, motion) = read[read.len() - 1];
            assert_eq!(motion, Motion::Landing);
            let above_goal = read[read.len() - 2].0;
            assert!(
                (above_goal[0] - landing[0]).abs() < 1e-6
                    && (above_goal[1] - landing[1]).abs() < 1e-6
            );
            assert!(cruise_flown.len() <= MOST_CRUISE_WAYPOINTS);
        }
    }
}
