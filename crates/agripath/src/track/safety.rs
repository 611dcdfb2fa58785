//! Is a track safe to fly? Checked on the geometry against the terrain as given, whatever
//! the cost model said (decision 0013).
//!
//! Every leg of the cruise is sampled at most 1 m apart (horizontally, the mission preflight's
//! spacing and sampling, `geometry::leg_samples`) against the scenario's
//! [`GroundTruth`](super::scenario::GroundTruth): the formula of an analytic terrain, or the
//! DEM bilinear on its own cells, never the planners' raster. A track is safe when
//! - every sample of the cruise is at least [`SafetyLimits::min_clearance_m`] above the
//!   terrain, and every leg that far from it in any direction (beside a cliff the ground
//!   beneath may be far and the face near; `terrain::nearness`, decision 0030) (the takeoff
//!   and landing legs, vertical above the start and the goal, start on the ground and are
//!   exempt: their ground is the start's and the goal's);
//! - every leg stays at least the vehicle's radius from every threat cylinder's wall (the 2D
//!   distance from the axis to the segment, exact);
//! - every waypoint lies in the planning area (and, for altitudes above sea level, between
//!   the space's floor and ceiling).
//!
//! Metres flown outside the height band are reported and do not make a track unsafe: the
//! band is a preference of the cost models, the ground and the threats are not.
//!
//! [`SafetyLimits::min_clearance_m`]: super::scenario::SafetyLimits

use super::cost::point_segment_distance;
use super::height_map::planar_length;
use super::scenario::{AltitudeReference, TrackScenario};
use crate::terrain::nearness::GroundNearness;

/// Horizontal spacing of the verdict's samples, metres: the mission preflight's.
pub const SAMPLE_SPACING_M: f64 = crate::preflight::SAMPLE_M;

/// Distances this far below the minimum are arithmetic, not a shortfall: a level leg at
/// exactly the minimum over flat ground read 1.9999999999999716 m and failed.
const ROUNDING_M: f64 = 1e-9;

/// Farthest the reported lowest clearance looks sideways, metres: a track that keeps more
/// than this above the ground everywhere reports its height above it (the cost of the search
/// grows with the reach, and no operator reads the difference up there).
pub const REPORTED_REACH_M: f64 = 50.0;

/// What the check found.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Least distance from the cruise to the terrain in any direction (a lower bound, within
    /// [`REPORTED_REACH_M`]; beyond it, the least height above the terrain), metres.
    pub lowest_clearance_m: f64,
    /// Where the lowest clearance is, scenario (x, y).
    pub lowest_clearance_at: [f64; 2],
    /// Smallest distance from a threat cylinder's wall (metres; negative: inside), if any.
    pub threat_margin_m: Option<f64>,
    /// Horizontal metres of the cruise flown outside the height band.
    pub outside_band_m: f64,
    /// One line per unsafe leg or waypoint; empty when the track is safe.
    pub violations: Vec<String>,
}

impl Verdict {
    /// Whether the check found no violation.
    pub fn is_safe(&self) -> bool {
        self.violations.is_empty()
    }

    /// The first violation, for one-line reports.
    pub fn worst(&self) -> Option<&str> {
        self.violations.first().map(String::as_str)
    }
}

/// A place as the scenario's input gives it: longitude/latitude or the local x, y.
fn place(scenario: &TrackScenario, x: f64, y: f64) -> String {
    let (a, b) = scenario.to_input(x, y);
    if scenario.is_local() {
        format!("({a:.1}, {b:.1})")
    } else {
        format!("({a:.6}, {b:.6})")
    }
}

/// Checks a whole track (takeoff leg, cruise, landing leg) given with altitudes above sea
/// level.
pub fn check(scenario: &TrackScenario, points: &[[f64; 3]]) -> Verdict {
    let limits = scenario.limits;
    let mut violations = Vec::new();
    let mut lowest_clearance_m = f64::INFINITY;
    let mut lowest_clearance_at = [scenario.start[0], scenario.start[1]];
    let mut threat_margin_m: Option<f64> = None;
    let mut outside_band_m = 0.0;
    let first_cruise_leg = usize::from(scenario.takes_off());
    let cruise_legs = points
        .len()
        .saturating_sub(1 + first_cruise_leg + usize::from(scenario.lands()));
    let spacing = SAMPLE_SPACING_M / scenario.unit_m;
    let mut nearness = GroundNearness::new(
        scenario.true_terrain(),
        |x, y| scenario.true_ground(x, y),
        scenario.unit_m,
        limits.min_clearance_m,
    );
    // Each cruise leg's lower bound of the distance to the ground, from the search within
    // the minimum (the minimum itself where nothing is nearer).
    let mut sideways_at_least = Vec::with_capacity(cruise_legs);
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let leg = index + 1;
        for (threat_index, threat) in scenario.threats.iter().enumerate() {
            let distance = point_segment_distance(threat.x, threat.y, a, b);
            let margin = (distance - threat.radius) * scenario.unit_m;
            threat_margin_m = Some(threat_margin_m.map_or(margin, |m| m.min(margin)));
            if margin < limits.vehicle_radius_m {
                let closest = closest_point(threat.x, threat.y, a, b);
                violations.push(if margin < 0.0 {
                    format!(
                        "leg {leg} enters threat cylinder {} by {:.2} m at {}",
                        threat_index + 1,
                        -margin,
                        place(scenario, closest[0], closest[1])
                    )
                } else {
                    format!(
                        "leg {leg} passes {margin:.2} m from threat cylinder {} at {} (the vehicle's radius is {} m)",
                        threat_index + 1,
                        place(scenario, closest[0], closest[1]),
                        limits.vehicle_radius_m
                    )
                });
            }
        }
        let in_cruise = (first_cruise_leg..first_cruise_leg + cruise_legs).contains(&index);
        if !in_cruise {
            continue;
        }
        let horizontal = planar_length(b[0] - a[0], b[1] - a[1]);
        let at = |t: f64| [0, 1, 2].map(|axis| a[axis] + t * (b[axis] - a[axis]));
        // Every `spacing`, and where the ground bends and peaks between (a raster's lines
        // through its cell centres: a peak one cell wide lies between two samples, and 1 m
        // samples read a 20 m peak on a 1 m lattice as 15.45 m; decision 0028).
        let places = crate::terrain::profile_places(
            scenario.true_terrain(),
            (a[0], a[1]),
            (b[0], b[1]),
            horizontal,
            spacing,
            |t| {
                let p = at(t);
                let ground = scenario.true_ground(p[0], p[1])?;
                Some(vec![ground, p[2] - ground])
            },
        );
        let mut leg_lowest = (f64::INFINITY, [a[0], a[1]]);
        let mut off_model = None;
        for (index, &t) in places.iter().enumerate() {
            let p = at(t);
            let Some(ground) = scenario.true_ground(p[0], p[1]) else {
                off_model.get_or_insert([p[0], p[1]]);
                continue;
            };
            let clearance = p[2] - ground;
            if clearance < leg_lowest.0 {
                leg_lowest = (clearance, [p[0], p[1]]);
            }
            if let Some((low, high)) = scenario.height_band {
                // The stretch to the next place counts as this place's.
                if let Some(&next) = places.get(index + 1) {
                    if !(low..=high).contains(&clearance) {
                        outside_band_m += horizontal * (next - t) * scenario.unit_m;
                    }
                }
            }
        }
        if let Some([x, y]) = off_model {
            violations.push(format!(
                "leg {leg} leaves the terrain model at {}",
                place(scenario, x, y)
            ));
        }
        let (clearance, [x, y]) = leg_lowest;
        // Sideways too: beside a cliff the ground beneath may be far and the face near.
        let short = limits.min_clearance_m - ROUNDING_M;
        let vertical_fails = clearance < short;
        let (mut lowest, mut lowest_at) = (clearance, [x, y]);
        let sideways = nearness.leg(a, b);
        // Nothing within the minimum: the minimum is a lower bound of the distance.
        sideways_at_least.push(sideways.map_or(limits.min_clearance_m, |near| near.distance_m));
        if let Some(near) = sideways {
            if near.distance_m < clearance {
                if !vertical_fails && near.distance_m < short {
                    violations.push(format!(
                        "leg {leg} passes {} m from the terrain beside it at {} ({:.2} m above the ground beneath; minimum {} m in any direction)",
                        short_of(near.distance_m, limits.min_clearance_m),
                        place(scenario, near.at[0], near.at[1]),
                        clearance,
                        limits.min_clearance_m
                    ));
                }
                (lowest, lowest_at) = (near.distance_m, near.at);
            }
        }
        if lowest < lowest_clearance_m {
            lowest_clearance_m = lowest;
            lowest_clearance_at = lowest_at;
        }
        if vertical_fails {
            violations.push(if clearance < 0.0 {
                format!(
                    "leg {leg} goes {:.2} m under the terrain at {}",
                    -clearance,
                    place(scenario, x, y)
                )
            } else {
                format!(
                    "leg {leg} passes {} m above the terrain at {} (minimum {} m)",
                    short_of(clearance, limits.min_clearance_m),
                    place(scenario, x, y),
                    limits.min_clearance_m
                )
            });
        }
    }
    // The figure reported is the least distance in any direction, as `--min-clearance` is
    // defined: the pass above looked sideways only within the minimum (enough for the
    // verdict), so where the track keeps more, look again within what it keeps. A search
    // that far bounds coarsely (its smallest squares are a 32nd of its reach): where it
    // finds ground nearer than the track's least height, that leg is bounded again within
    // twice what it found, and the figure is the best of the lower bounds (a safe track
    // beside a cliff read 1.25 m from a 50 m search against a 2 m minimum).
    if lowest_clearance_m.is_finite() && lowest_clearance_m > limits.min_clearance_m {
        let near_within = |reach_m: f64| {
            GroundNearness::new(
                scenario.true_terrain(),
                |x, y| scenario.true_ground(x, y),
                scenario.unit_m,
                reach_m,
            )
        };
        let mut wide = near_within(lowest_clearance_m.min(REPORTED_REACH_M));
        let cruise = &points[first_cruise_leg..first_cruise_leg + cruise_legs + 1];
        for (pair, &at_least) in cruise.windows(2).zip(&sideways_at_least) {
            let Some(coarse) = wide.leg(pair[0], pair[1]) else {
                continue;
            };
            if coarse.distance_m >= lowest_clearance_m {
                continue;
            }
            let close_reach_m = (2.0 * coarse.distance_m).max(limits.min_clearance_m);
            let close = near_within(close_reach_m).leg(pair[0], pair[1]);
            let (bound, at) = close.map_or((close_reach_m, coarse.at), |near| {
                (near.distance_m, near.at)
            });
            let distance = bound.max(coarse.distance_m).max(at_least);
            if distance < lowest_clearance_m {
                (lowest_clearance_m, lowest_clearance_at) = (distance, at);
            }
        }
    }
    let (min_x, min_y, max_x, max_y) = scenario.area;
    let (low, high) = scenario.altitude_bounds;
    let sea_level = scenario.altitude_reference == AltitudeReference::SeaLevel;
    for (index, point) in points.iter().enumerate() {
        if !(min_x..=max_x).contains(&point[0]) || !(min_y..=max_y).contains(&point[1]) {
            violations.push(format!("waypoint {index} lies outside the planning area"));
        }
        // Above sea level, the altitude bounds are the space's floor and ceiling.
        if sea_level && !(low - 1e-9..=high + 1e-9).contains(&point[2]) {
            violations.push(format!(
                "waypoint {index} at {:.1} m is outside the space's altitudes [{low}, {high}]",
                point[2]
            ));
        }
    }
    Verdict {
        lowest_clearance_m,
        lowest_clearance_at,
        threat_margin_m,
        outside_band_m,
        violations,
    }
}

/// A distance short of `minimum`, with the decimals that show it short: 1.9985 m reads
/// "1.998", not "2.00", beside a minimum of 2 m.
fn short_of(distance_m: f64, minimum_m: f64) -> String {
    (2..=9)
        .map(|decimals| format!("{distance_m:.decimals$}"))
        .find(|text| text.parse::<f64>().is_ok_and(|shown| shown < minimum_m))
        .unwrap_or_else(|| format!("{distance_m}"))
}

/// The point of the segment a → b nearest (x, y), horizontally.
fn closest_point(x: f64, y: f64, a: [f64; 3], b: [f64; 3]) -> [f64; 2] {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length_squared = dx * dx + dy * dy;
    let t = if length_squared > 0.0 {
        (((x - a[0]) * dx + (y - a[1]) * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [a[0] + t * dx, a[1] + t * dy]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shortfall_reads_short() {
        assert_eq!(short_of(1.9985, 2.0), "1.998");
        assert_eq!(short_of(1.5, 2.0), "1.50");
        assert_eq!(short_of(9.99, 10.0), "9.99");
    }

    /// A scenario over a cliff: 5 m cells, 200 m west of x = 195, 400 m from x = 200 (a
    /// 200 m face 5 m across), from `start` to `goal` (local metres, height above ground).
    fn over_a_cliff(start: [f64; 3], goal: [f64; 3]) -> Result<TrackScenario, crate::InputError> {
        let folder = std::env::temp_dir().join(format!(
            "agripath-cliff-{}-{}",
            std::process::id(),
            start[0]
        ));
        std::fs::create_dir_all(&folder).unwrap();
        let mut grid = String::from(
            "ncols 81\nnrows 41\nxllcorner -2.5\nyllcorner -2.5\ncellsize 5\nNODATA_value -9999\n",
        );
        for _ in 0..41 {
            let row: Vec<&str> = (0..81)
                .map(|column| if column < 40 { "200" } else { "400" })
                .collect();
            grid.push_str(&row.join(" "));
            grid.push('\n');
        }
        std::fs::write(folder.join("cliff.asc"), grid).unwrap();
        let toml = format!(
            "name = \"cliff\"\ncrs = \"local\"\nterrain = {{ kind = \"file\", path = \"cliff.asc\" }}\nstart = {start:?}\ngoal = {goal:?}\nheight_band_m = [2, 300]\nfree_waypoints = 4\nmargin_m = 5\n"
        );
        let path = folder.join("cliff.toml");
        std::fs::write(&path, toml).unwrap();
        let scenario = TrackScenario::read(&path, None);
        std::fs::remove_dir_all(&folder).unwrap();
        scenario
    }

    /// A leg 92 m above the ground beneath and 2.3 m from a cliff's face: safe at a 2 m
    /// minimum, and the figure reported must say so (a 50 m search alone bounded it at 1.25 m).
    #[test]
    fn a_safe_leg_beside_a_cliff_reports_its_clearance_in_any_direction_no_less_than_the_minimum() {
        let mut scenario = over_a_cliff([20.0, 100.0, 95.0], [190.0, 60.0, 95.0]).unwrap();
        scenario.start = scenario.cruise_start;
        scenario.goal = scenario.cruise_goal;
        let leg = [[100.0, 100.0, 292.0], [195.0, 100.0, 292.0]];
        let verdict = check(&scenario, &leg);
        assert!(verdict.is_safe(), "{:?}", verdict.violations);
        assert!(
            (2.0..2.4).contains(&verdict.lowest_clearance_m),
            "reported {} m",
            verdict.lowest_clearance_m
        );
        // Level at exactly the minimum over the flat ground: arithmetic, not a shortfall.
        let level = [[30.0, 80.0, 202.0], [150.0, 80.0, 202.0]];
        let verdict = check(&scenario, &level);
        assert!(verdict.is_safe(), "{:?}", verdict.violations);
    }

    /// A start on the ground 1 m from the foot of the face: lifting hardly moves it away from
    /// the face, so it is refused with the distance left, not flown from short of the minimum.
    #[test]
    fn a_start_at_the_foot_of_a_cliff_is_refused_not_flown_short_of_the_minimum() {
        let message = over_a_cliff([194.0, 100.0, 0.0], [20.0, 60.0, 0.0])
            .map(|_| ())
            .expect_err("refused")
            .to_string();
        assert!(message.contains("start"), "{message}");
        assert!(message.contains("too steep to climb clear of"), "{message}");
        // Ten metres out, one lift clears it.
        assert!(over_a_cliff([185.0, 100.0, 0.0], [20.0, 60.0, 0.0]).is_ok());
    }

    /// Task `task` with the start and goal moved to the cruise's ends: no vertical legs, so
    /// a hand-made track is all cruise.
    pub(super) fn cruise_only(task: &str) -> TrackScenario {
        let mut scenario = TrackScenario::seed000(task).unwrap();
        scenario.start = scenario.cruise_start;
        scenario.goal = scenario.cruise_goal;
        scenario
    }

    #[test]
    fn a_track_through_a_threat_or_a_hill_or_too_close_is_unsafe() {
        let scenario = cruise_only("I");
        let threat = scenario.threats[0];
        let through = [
            [threat.x - 100.0, threat.y, 300.0],
            [threat.x + 100.0, threat.y, 300.0],
        ];
        let verdict = check(&scenario, &through);
        assert!(!verdict.is_safe());
        assert!(verdict.violations[0].contains("enters threat cylinder 1"));
        // Half a metre from the wall: inside the vehicle's 1 m radius.
        let y = threat.y + threat.radius + 0.5;
        let grazing = [[threat.x - 100.0, y, 300.0], [threat.x + 100.0, y, 300.0]];
        let verdict = check(&scenario, &grazing);
        assert!(verdict.violations[0].contains("passes 0.50 m from threat cylinder 1"));
        assert!((verdict.threat_margin_m.unwrap() - 0.5).abs() < 1e-9);
        // Under the terrain near the highest hill (350, 650).
        let under = [[300.0, 650.0, 50.0], [400.0, 650.0, 50.0]];
        assert!(check(&scenario, &under)
            .violations
            .iter()
            .any(|v| v.contains("under the terrain")));
        // High above everything, away from threats.
        let safe = [[0.0, 1000.0, 390.0], [10.0, 990.0, 390.0]];
        let verdict = check(&scenario, &safe);
        assert!(verdict.is_safe(), "{:?}", verdict.violations);
        // 390 m above sea level is above the band's 300 m ceiling over that ground.
        assert!((verdict.outside_band_m - 200f64.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn a_track_one_metre_above_the_ground_breaks_the_two_metre_minimum() {
        let scenario = cruise_only("II");
        let ground = |x: f64, y: f64| scenario.true_ground(x, y).unwrap();
        let (a, b) = ([20.0, 20.0], [60.0, 20.0]);
        let low = [
            [a[0], a[1], ground(a[0], a[1]) + 1.0],
            [b[0], b[1], ground(b[0], b[1]) + 1.0],
        ];
        let verdict = check(&scenario, &low);
        assert!(
            verdict
                .violations
                .iter()
                .any(|v| v.contains("above the terrain") && v.contains("minimum 2 m")),
            "{:?}",
            verdict.violations
        );
        // Every sampled metre below the band's 100 m floor counts as outside it.
        assert!(
            (verdict.outside_band_m - 40.0).abs() < 1.01,
            "{}",
            verdict.outside_band_m
        );
        let relaxed = scenario
            .clone()
            .with_limits(super::super::scenario::SafetyLimits {
                min_clearance_m: 0.5,
                vehicle_radius_m: 1.0,
            })
            .unwrap();
        assert!(check(&relaxed, &low).is_safe());
    }

    #[test]
    fn the_vertical_legs_at_a_start_on_the_ground_are_exempt_from_the_clearance() {
        let mut scenario = TrackScenario::seed000("III").unwrap();
        scenario.start[2] = scenario
            .true_ground(scenario.start[0], scenario.start[1])
            .unwrap();
        let scenario = super::super::scenario::validated(scenario).unwrap();
        assert!(scenario.takes_off());
        let above = scenario.cruise_start[2]
            - scenario
                .true_ground(scenario.start[0], scenario.start[1])
                .unwrap();
        assert!(
            (above - 100.0).abs() < 1e-9,
            "climbs to the band's floor: {above}"
        );
        let cruise = [
            scenario.cruise_start,
            [500.0, 200.0, 390.0],
            scenario.sea_level(scenario.cruise_goal),
        ];
        let track = scenario.whole_track(&cruise);
        assert_eq!(
            track.len(),
            cruise.len() + usize::from(scenario.lands()) + 1
        );
        let verdict = check(&scenario, &track);
        assert!(
            !verdict.violations.iter().any(|v| v.contains("terrain")),
            "{:?}",
            verdict.violations
        );
    }
}

#[cfg(test)]
mod properties {
    use proptest::prelude::*;

    use super::*;
    use crate::terrain::{Composite, Terrain};

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Against brute force on the formula itself, sampled every 0.25 m: a leg that comes
        /// closer to the terrain than the minimum (by more than the terrain's change between
        /// 1 m samples) or to a threat's wall than the vehicle's radius is always reported, and
        /// a leg clear of both by that margin never is. Clear of the terrain in any direction
        /// (decision 0030): the ground within 2.2 m of each sample, every 0.2 m, wherever the
        /// sample is less than 4 m above the ground beneath (the hills are nowhere steeper than
        /// 1 in 1, so higher samples are more than 2.8 m from any ground).
        #[test]
        fn the_check_agrees_with_dense_sampling_of_the_exact_terrain(
            ax in 0.0..1000.0f64, ay in 0.0..1000.0f64, az in 0.0..160.0f64,
            bx in 0.0..1000.0f64, by in 0.0..1000.0f64, bz in 0.0..160.0f64,
        ) {
            let scenario = super::tests::cruise_only("III");
            let exact = Composite::seed000();
            let (a, b) = ([ax, ay, az], [bx, by, bz]);
            let length = (bx - ax).hypot(by - ay);
            let steps = ((length / 0.25).ceil() as usize).max(1);
            let mut lowest: f64 = f64::INFINITY;
            let mut nearest: f64 = f64::INFINITY;
            let mut threat_margin: f64 = f64::INFINITY;
            for step in 0..=steps {
                let t = step as f64 / steps as f64;
                let (x, y, z) = (ax + t * (bx - ax), ay + t * (by - ay), az + t * (bz - az));
                let beneath = z - exact.height_m(x, y).unwrap();
                lowest = lowest.min(beneath);
                nearest = nearest.min(beneath);
                if beneath < 4.0 {
                    for i in -11..=11 {
                        for j in -11..=11 {
                            let (dx, dy) = (f64::from(i) * 0.2, f64::from(j) * 0.2);
                            if let Ok(ground) = exact.height_m(x + dx, y + dy) {
                                nearest = nearest.min(dx.hypot(dy).hypot((z - ground).max(0.0)));
                            }
                        }
                    }
                }
                for threat in &scenario.threats {
                    threat_margin = threat_margin.min((x - threat.x).hypot(y - threat.y) - threat.radius);
                }
            }
            let verdict = check(&scenario, &[a, b]);
            let says_low = verdict.violations.iter().any(|v| v.contains("terrain"));
            let says_threat = verdict.violations.iter().any(|v| v.contains("threat cylinder"));
            if lowest < 2.0 - 0.2 { prop_assert!(says_low, "lowest {lowest}"); }
            if nearest > 2.0 + 0.25 { prop_assert!(!says_low, "lowest {lowest}, nearest {nearest}"); }
            if threat_margin < 1.0 - 0.01 { prop_assert!(says_threat); }
            if threat_margin > 1.0 + 0.01 { prop_assert!(!says_threat); }
        }
    }
}
