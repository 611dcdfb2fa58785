//! The checks every track scenario ends with, whatever file it came from: start and goal in
//! the area, above the terrain and outside every threat, a band that makes sense, and the
//! cruise's ends placed at the band's floor (a vertical leg reaches them).

use super::{AltitudeReference, TrackScenario};
use crate::error::Fault;
use crate::terrain::nearness::GroundNearness;

/// Checks that start and goal lie in the area, above the terrain and outside every threat,
/// that the band makes sense, and places the cruise's ends.
pub(in crate::track) fn validated(mut scenario: TrackScenario) -> Result<TrackScenario, Fault> {
    let (min_x, min_y, max_x, max_y) = scenario.area;
    if !(max_x - min_x > 0.0
        && max_y - min_y > 0.0
        && scenario.altitude_bounds.1 > scenario.altitude_bounds.0)
    {
        return Err(Fault::InvalidValue {
            what: "planning space".into(),
            value: format!(
                "[{min_x}, {max_x}] × [{min_y}, {max_y}] × {:?}",
                scenario.altitude_bounds
            ),
            why: "needs a positive width, depth and height".into(),
        });
    }
    if let Some((low, high)) = scenario.height_band {
        if low.partial_cmp(&high) != Some(std::cmp::Ordering::Less) || low < 0.0 {
            return Err(Fault::InvalidValue {
                what: "height band".into(),
                value: format!("[{low}, {high}]"),
                why: "needs 0 ≤ lower < upper".into(),
            });
        }
    }
    if !(2..=100_000).contains(&scenario.population)
        || !(1..=1_000_000).contains(&scenario.iterations)
    {
        return Err(Fault::InvalidValue {
            what: "population / iterations".into(),
            value: format!("{} / {}", scenario.population, scenario.iterations),
            why: "need a population of 2..=100000 and 1..=1000000 iterations".into(),
        });
    }
    if scenario.free_waypoints == 0 || scenario.free_waypoints > 100 {
        return Err(Fault::InvalidValue {
            what: "free waypoints".into(),
            value: scenario.free_waypoints.to_string(),
            why: "must be 1..=100".into(),
        });
    }
    if scenario.threats.len() > 1000 {
        return Err(Fault::InvalidValue {
            what: "threat cylinders".into(),
            value: scenario.threats.len().to_string(),
            why: "at most 1000".into(),
        });
    }
    // Within a metre of each other there is no track to plan (and the length term, which
    // divides by the start-goal distance, would be meaningless).
    let apart_m = (0..3)
        .map(|axis| (scenario.goal[axis] - scenario.start[axis]).powi(2))
        .sum::<f64>()
        .sqrt()
        * scenario.unit_m;
    if apart_m.is_nan() || apart_m < 1.0 {
        return Err(Fault::InvalidValue {
            what: "start and goal".into(),
            value: format!("{:?} and {:?}", scenario.start, scenario.goal),
            why: format!(
                "they are {apart_m:.2} m apart: a track needs two places at least 1 m apart"
            ),
        });
    }
    let radius_units = scenario.limits.vehicle_radius_m / scenario.unit_m;
    let floor = scenario
        .height_band
        .map_or(0.0, |(low, _)| low)
        .max(scenario.limits.min_clearance_m);
    let mut ends = [scenario.start, scenario.goal];
    // Places as the scenario's input gave them: lon/lat for a lon/lat scenario, not the
    // planning frame's UTM metres (the fourth trial read its goal back in metres it never
    // wrote).
    let input_place = |x: f64, y: f64| {
        let (a, b) = scenario.to_input(x, y);
        if scenario.is_local() {
            format!("({a}, {b})")
        } else {
            format!("(lon {a:.7}, lat {b:.7})")
        }
    };
    let area = if scenario.is_local() {
        format!("[{min_x}, {max_x}] × [{min_y}, {max_y}] (the box round the start, goal and threats grown by the margin, cut to the terrain model: a start or goal outside it lies off the terrain model)")
    } else {
        format!(
            "from {} to {} (the box round the start, goal and threats grown by margin_m, cut to the terrain model: a start or goal outside it lies off the terrain model)",
            input_place(min_x, min_y),
            input_place(max_x, max_y)
        )
    };
    for (what, point) in ["start", "goal"].into_iter().zip(ends.iter_mut()) {
        let place = input_place(point[0], point[1]);
        if !(min_x..=max_x).contains(&point[0]) || !(min_y..=max_y).contains(&point[1]) {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!("outside the planning area {area}"),
            });
        }
        if let Some((index, threat)) = scenario.threats.iter().enumerate().find(|(_, threat)| {
            (point[0] - threat.x).hypot(point[1] - threat.y) < threat.radius + radius_units
        }) {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!(
                    "inside threat cylinder {} (centre {}, radius {} m, plus the vehicle's {} m)",
                    index + 1,
                    input_place(threat.x, threat.y),
                    threat.radius * scenario.unit_m,
                    scenario.limits.vehicle_radius_m
                ),
            });
        }
        let ground = scenario.terrain.height(point[0], point[1]);
        let above = match scenario.altitude_reference {
            AltitudeReference::AboveGround => point[2],
            AltitudeReference::SeaLevel => {
                let truth = scenario.true_ground(point[0], point[1]).unwrap_or(ground);
                point[2] - truth
            }
        };
        if above < -1e-6 {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: format!("{} at {} m", input_place(point[0], point[1]), point[2]),
                why: format!("{:.2} m under the terrain", -above),
            });
        }
        if above < floor {
            // A vertical leg to the floor: sea-level altitudes over the true ground.
            point[2] = match scenario.altitude_reference {
                AltitudeReference::AboveGround => floor,
                AltitudeReference::SeaLevel => point[2] + (floor - above),
            };
            point[2] += slope_lift_m(&scenario, *point).map_err(|distance_m| {
                Fault::InvalidValue {
                    what: what.into(),
                    value: place.clone(),
                    why: format!(
                        "it lies at the foot of a slope or face too steep to climb clear of: {LIFT_STEPS} lifts leave the ground {distance_m:.2} m away (minimum {} m in any direction); move it away from the face",
                        scenario.limits.min_clearance_m
                    ),
                }
            })?;
        }
        let (_, high) = scenario.altitude_bounds;
        if scenario.altitude_reference == AltitudeReference::SeaLevel && point[2] > high {
            return Err(Fault::InvalidValue {
                what: what.into(),
                value: place,
                why: format!(
                    "the cruise's start above it ({:.1} m: the band's floor, or higher beside a slope) is above the space's ceiling ({high} m)",
                    point[2]
                ),
            });
        }
    }
    [scenario.cruise_start, scenario.cruise_goal] = ends;
    // Made again, for these limits, when the costs first ask for it.
    scenario.clearance_ground = std::sync::OnceLock::new();
    Ok(scenario)
}

/// Lifts [`slope_lift_m`] tries before it gives up.
const LIFT_STEPS: usize = 16;

/// How much higher than `point` (the top of a takeoff climb or of a landing's descent) the
/// cruise must begin for the ground to be `--min-clearance` away in any direction, as the
/// safety check measures it ([`GroundNearness`]'s bound). On a slope the ground beside is
/// nearer than the ground beneath: a sixth trial's climb to 2 m above a 2 % slope ended
/// 1.998 m from it, and every planner's track then failed the check at its first leg.
///
/// Each lift adds the shortfall. On a slope at angle θ the next shortfall is about the last
/// one times (1 − cos θ): gentle slopes are clear after one lift. At the foot of a steep face
/// a lift hardly moves the point away from it; after [`LIFT_STEPS`] lifts the point is
/// refused with the distance still left (`Err`), not flown from short of the minimum.
fn slope_lift_m(scenario: &TrackScenario, point: [f64; 3]) -> Result<f64, f64> {
    let minimum = scenario.limits.min_clearance_m;
    if minimum <= 0.0 {
        return Ok(0.0);
    }
    let mut nearness = GroundNearness::new(
        scenario.true_terrain(),
        |x, y| scenario.true_ground(x, y),
        scenario.unit_m,
        minimum,
    );
    let [x, y, z] = scenario.sea_level(point);
    let mut lift = 0.0;
    for _ in 0..LIFT_STEPS {
        let top = [x, y, z + lift];
        match nearness.leg(top, top) {
            Some(near) if near.distance_m < minimum => lift += minimum - near.distance_m + 1e-3,
            _ => return Ok(lift),
        }
    }
    let top = [x, y, z + lift];
    match nearness.leg(top, top) {
        Some(near) if near.distance_m < minimum => Err(near.distance_m),
        _ => Ok(lift),
    }
}
