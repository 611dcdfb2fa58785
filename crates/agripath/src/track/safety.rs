//! Is a track safe to fly? Checked on the geometry, whatever the cost model said.
//!
//! A track is safe when every segment, sampled at every half terrain cell, stays above the
//! terrain (bilinear between DEM cells), no segment passes within a threat cylinder (2D
//! distance from the axis to the segment), and every waypoint lies in the planning area
//! (and, for altitudes above sea level, between the space's floor and ceiling).
//! Height-band excursions are reported but do not make a track unsafe: the band is a
//! preference of the cost models, the ground and the threats are not.

use super::cost::point_segment_distance;
use super::scenario::TrackScenario;

/// What the check found.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// Lowest height above the terrain along the track (scenario units of height: metres).
    pub lowest_clearance_m: f64,
    /// Smallest 2D distance from a threat cylinder's wall (negative: inside), if any threats.
    pub threat_margin: Option<f64>,
    /// Human-readable violations; empty when the track is safe.
    pub violations: Vec<String>,
    /// Waypoints outside the height band (reported, not a violation).
    pub outside_band: usize,
}

impl Verdict {
    pub fn is_safe(&self) -> bool {
        self.violations.is_empty()
    }
}

/// Checks a track given with altitudes above sea level.
pub fn check(scenario: &TrackScenario, points: &[[f64; 3]]) -> Verdict {
    let mut violations = Vec::new();
    let mut lowest_clearance_m = f64::INFINITY;
    let mut threat_margin: Option<f64> = None;
    for (index, pair) in points.windows(2).enumerate() {
        let clearance = scenario.terrain.lowest_clearance(pair[0], pair[1]);
        lowest_clearance_m = lowest_clearance_m.min(clearance);
        if clearance <= 0.0 {
            violations.push(format!(
                "segment {index} goes {:.1} m under the terrain",
                -clearance
            ));
        }
        for (threat_index, threat) in scenario.threats.iter().enumerate() {
            let margin =
                point_segment_distance(threat.x, threat.y, pair[0], pair[1]) - threat.radius;
            threat_margin = Some(threat_margin.map_or(margin, |m| m.min(margin)));
            if margin <= 0.0 {
                violations.push(format!(
                    "segment {index} enters threat cylinder {threat_index} by {:.1}",
                    -margin
                ));
            }
        }
    }
    let (min_x, min_y, max_x, max_y) = scenario.area;
    let (low, high) = scenario.altitude_bounds;
    for (index, point) in points.iter().enumerate() {
        if !(min_x..=max_x).contains(&point[0]) || !(min_y..=max_y).contains(&point[1]) {
            violations.push(format!("waypoint {index} lies outside the planning area"));
        }
        // Above sea level, the altitude bounds are the space's floor and ceiling.
        let sea_level = scenario.altitude_reference == super::scenario::AltitudeReference::SeaLevel;
        if sea_level && !(low - 1e-9..=high + 1e-9).contains(&point[2]) {
            violations.push(format!(
                "waypoint {index} at {:.1} m is outside the space's altitudes [{low}, {high}]",
                point[2]
            ));
        }
    }
    let outside_band = match scenario.height_band {
        Some((low, high)) => points
            .iter()
            .filter(|p| {
                let above = p[2] - scenario.terrain.height(p[0], p[1]);
                !(low..=high).contains(&above)
            })
            .count(),
        None => 0,
    };
    Verdict {
        lowest_clearance_m,
        threat_margin,
        violations,
        outside_band,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_track_through_a_threat_or_a_hill_is_unsafe() {
        let scenario = TrackScenario::seed000("I").unwrap();
        let threat = scenario.threats[0];
        let through = [
            [threat.x - 100.0, threat.y, 300.0],
            [threat.x + 100.0, threat.y, 300.0],
        ];
        let verdict = check(&scenario, &through);
        assert!(!verdict.is_safe());
        assert!(verdict.violations[0].contains("threat cylinder 0"));
        // Under the terrain near the highest hill (350, 650).
        let under = [[300.0, 650.0, 50.0], [400.0, 650.0, 50.0]];
        assert!(check(&scenario, &under)
            .violations
            .iter()
            .any(|v| v.contains("under the terrain")));
        // High above everything, away from threats.
        let safe = [[0.0, 1000.0, 390.0], [10.0, 990.0, 390.0]];
        assert!(check(&scenario, &safe).is_safe());
    }
}

#[cfg(test)]
mod properties {
    use proptest::prelude::*;

    use super::*;
    use crate::terrain::{Composite, Terrain};

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Against brute force on the formula itself: a leg that dips more than the raster's
        /// interpolation error under the terrain, or into a cylinder, is always reported, and a
        /// leg clear of both by a margin never is.
        #[test]
        fn the_check_agrees_with_dense_sampling_of_the_exact_terrain(
            ax in 0.0..1000.0f64, ay in 0.0..1000.0f64, az in 0.0..160.0f64,
            bx in 0.0..1000.0f64, by in 0.0..1000.0f64, bz in 0.0..160.0f64,
        ) {
            let scenario = TrackScenario::seed000("III").unwrap();
            let exact = Composite::seed000();
            let (a, b) = ([ax, ay, az], [bx, by, bz]);
            let mut lowest: f64 = f64::INFINITY;
            let mut threat_margin: f64 = f64::INFINITY;
            for step in 0..=4000 {
                let t = step as f64 / 4000.0;
                let (x, y, z) = (ax + t * (bx - ax), ay + t * (by - ay), az + t * (bz - az));
                lowest = lowest.min(z - exact.height_m(x, y).unwrap());
                for threat in &scenario.threats {
                    threat_margin = threat_margin.min((x - threat.x).hypot(y - threat.y) - threat.radius);
                }
            }
            let verdict = check(&scenario, &[a, b]);
            let says_under = verdict.violations.iter().any(|v| v.contains("under the terrain"));
            let says_threat = verdict.violations.iter().any(|v| v.contains("threat cylinder"));
            if lowest < -0.3 { prop_assert!(says_under, "lowest {lowest}"); }
            if lowest > 0.3 { prop_assert!(!says_under, "lowest {lowest}"); }
            if threat_margin < -0.5 { prop_assert!(says_threat); }
            if threat_margin > 0.5 { prop_assert!(!says_threat); }
        }
    }
}
