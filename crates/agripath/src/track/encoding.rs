//! How an optimizer's vector becomes a track: three encodings of the free waypoints.
//!
//! - **Cartesian**: (x, y, z) per waypoint, each in the scenario's box.
//! - **Cylindrical** (seed 000 eqs. 27-30): (ρ, θ, z') per waypoint, an increment from the
//!   previous point: x_j = x_{j−1} + ρ cos θ, y_j = y_{j−1} + ρ sin θ, z_j = z_{j−1} + z'.
//!   ρ ∈ [0, L_path], θ ∈ [−π, π], z' ∈ [−Z, Z]. The paper gives neither L_path nor Z
//!   (contract decision 8, docs/contract.md): L_path = 2·|SG| / (n + 1), so that n + 1 legs at half their
//!   longest span reach the goal in a straight line, and Z = (h_max − h_min) / 4.
//! - **Spherical** (SPSO): (r, ψ, φ) per waypoint: x_j = x_{j−1} + r cos ψ cos φ,
//!   y_j = y_{j−1} + r cos ψ sin φ, z_j = z_{j−1} + r sin ψ; r ∈ [0, 2·|SG|/n],
//!   ψ ∈ [−π/4, π/4], φ ∈ [φ0 − π/4, φ0 + π/4] with φ0 the start-goal azimuth. SPSO's code
//!   centres the window on atan2(dy, dx) but decodes φ from +y (x ← sin φ): we decode from
//!   +x, which points the window at the goal for any start and goal (for SPSO's own
//!   start/goal both readings are within 9° of each other; decision 0011).
//!
//! The increment encodings clamp each point to the area and the altitude bounds after every
//! step, as SPSO's `SphericalToCart.m` does; the last leg goes to the goal. The increments
//! start from the cruise's start ([`TrackScenario::cruise_start`]): above a start on the
//! ground, the band's floor.

use std::f64::consts::{FRAC_PI_4, PI};

use swarm::Bounds;

use super::cost::length_3d;
use super::scenario::TrackScenario;

/// How an optimizer's vector encodes the free waypoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// (x, y, z) per waypoint, each in the scenario's box.
    Cartesian,
    /// (ρ, θ, z') per waypoint, an increment from the previous point (seed 000 eqs. 27-30).
    Cylindrical,
    /// (r, ψ, φ) per waypoint, an increment from the previous point (SPSO).
    Spherical,
}

impl Encoding {
    /// The encoding's name on the command line and in outputs.
    pub fn key(self) -> &'static str {
        match self {
            Encoding::Cartesian => "cartesian",
            Encoding::Cylindrical => "cylindrical",
            Encoding::Spherical => "spherical",
        }
    }

    /// The encoding named `text` (case-insensitive, trimmed), if any.
    pub fn parse(text: &str) -> Option<Self> {
        [
            Encoding::Cartesian,
            Encoding::Cylindrical,
            Encoding::Spherical,
        ]
        .into_iter()
        .find(|encoding| encoding.key() == text.trim().to_ascii_lowercase())
    }

    /// The search box for `waypoints` free waypoints.
    pub fn bounds(self, scenario: &TrackScenario, waypoints: usize) -> Bounds {
        let (min_x, min_y, max_x, max_y) = scenario.area;
        let (low_z, high_z) = scenario.altitude_bounds;
        let (lower, upper): ([f64; 3], [f64; 3]) = match self {
            Encoding::Cartesian => ([min_x, min_y, low_z], [max_x, max_y, high_z]),
            Encoding::Cylindrical => {
                let reach = 2.0 * scenario.start_goal_distance() / (waypoints + 1) as f64;
                let climb = match scenario.height_band {
                    Some((low, high)) => 0.25 * (high - low),
                    None => 0.25 * (high_z - low_z),
                };
                ([0.0, -PI, -climb], [reach, PI, climb])
            }
            Encoding::Spherical => {
                let reach =
                    2.0 * length_3d(scenario.cruise_start, scenario.cruise_goal) / waypoints as f64;
                let azimuth = start_goal_azimuth(scenario);
                (
                    [0.0, -FRAC_PI_4, azimuth - FRAC_PI_4],
                    [reach, FRAC_PI_4, azimuth + FRAC_PI_4],
                )
            }
        };
        let lower = (0..waypoints).flat_map(|_| lower).collect();
        let upper = (0..waypoints).flat_map(|_| upper).collect();
        Bounds::new(lower, upper).expect("track encodings have non-empty boxes")
    }

    /// Decodes `x` into the cruise: its start, the waypoints, its goal (z in the scenario's
    /// altitude reference).
    pub fn decode_into(self, scenario: &TrackScenario, x: &[f64], points: &mut Vec<[f64; 3]>) {
        let (min_x, min_y, max_x, max_y) = scenario.area;
        let (low_z, high_z) = scenario.altitude_bounds;
        let clamp = |p: [f64; 3]| {
            [
                p[0].clamp(min_x, max_x),
                p[1].clamp(min_y, max_y),
                p[2].clamp(low_z, high_z),
            ]
        };
        points.clear();
        points.push(scenario.cruise_start);
        for gene in x.chunks_exact(3) {
            let previous = *points.last().expect("the start is there");
            let next = match self {
                Encoding::Cartesian => [gene[0], gene[1], gene[2]],
                Encoding::Cylindrical => {
                    let (rho, theta, climb) = (gene[0], gene[1], gene[2]);
                    clamp([
                        previous[0] + rho * theta.cos(),
                        previous[1] + rho * theta.sin(),
                        previous[2] + climb,
                    ])
                }
                Encoding::Spherical => {
                    let (r, elevation, azimuth) = (gene[0], gene[1], gene[2]);
                    clamp([
                        previous[0] + r * elevation.cos() * azimuth.cos(),
                        previous[1] + r * elevation.cos() * azimuth.sin(),
                        previous[2] + r * elevation.sin(),
                    ])
                }
            };
            points.push(next);
        }
        points.push(scenario.cruise_goal);
    }

    /// The vector that decodes to these free waypoints (inverse of `decode_into` where no
    /// clamping happened), clamped into the box.
    pub fn encode(self, scenario: &TrackScenario, waypoints: &[[f64; 3]]) -> Vec<f64> {
        let mut previous = scenario.cruise_start;
        let mut x = Vec::with_capacity(3 * waypoints.len());
        for &point in waypoints {
            let (dx, dy, dz) = (
                point[0] - previous[0],
                point[1] - previous[1],
                point[2] - previous[2],
            );
            match self {
                Encoding::Cartesian => x.extend_from_slice(&point),
                Encoding::Cylindrical => x.extend_from_slice(&[dx.hypot(dy), dy.atan2(dx), dz]),
                Encoding::Spherical => {
                    let r = (dx * dx + dy * dy + dz * dz).sqrt();
                    x.extend_from_slice(&[r, dz.atan2(dx.hypot(dy)), dy.atan2(dx)]);
                }
            }
            previous = point;
        }
        self.bounds(scenario, waypoints.len()).clamp(&mut x);
        x
    }
}

fn start_goal_azimuth(scenario: &TrackScenario) -> f64 {
    (scenario.goal[1] - scenario.start[1]).atan2(scenario.goal[0] - scenario.start[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_encoding_round_trips_an_unclamped_track() {
        let scenario = TrackScenario::seed000("II").unwrap();
        let waypoints: Vec<[f64; 3]> = (1..=12)
            .map(|i| {
                let t = i as f64 / 13.0;
                [
                    100.0 + 800.0 * t,
                    900.0 - 800.0 * t + 20.0 * (t * 9.0).sin(),
                    scenario.cruise_start[2] + 40.0 * (t * 7.0).sin(),
                ]
            })
            .collect();
        for encoding in [
            Encoding::Cartesian,
            Encoding::Cylindrical,
            Encoding::Spherical,
        ] {
            let x = encoding.encode(&scenario, &waypoints);
            assert!(encoding.bounds(&scenario, 12).contains(&x), "{encoding:?}");
            let mut points = Vec::new();
            encoding.decode_into(&scenario, &x, &mut points);
            assert_eq!(points.len(), 14);
            for (decoded, expected) in points[1..13].iter().zip(&waypoints) {
                for axis in 0..3 {
                    assert!(
                        (decoded[axis] - expected[axis]).abs() < 1e-9,
                        "{encoding:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn increments_are_clamped_to_the_area_after_every_step() {
        let scenario = TrackScenario::seed000("I").unwrap();
        let bounds = Encoding::Cylindrical.bounds(&scenario, 12);
        let x: Vec<f64> = bounds.upper().to_vec(); // longest steps at θ = π: due west
        let mut points = Vec::new();
        Encoding::Cylindrical.decode_into(&scenario, &x, &mut points);
        let (min_x, min_y, max_x, max_y) = scenario.area;
        let (low, high) = scenario.altitude_bounds;
        assert!(!points.is_empty());
        for point in &points {
            assert!((min_x..=max_x).contains(&point[0]), "{point:?}");
            assert!((min_y..=max_y).contains(&point[1]), "{point:?}");
            assert!((low..=high).contains(&point[2]), "{point:?}");
        }
        // The steps west are long enough to reach the western edge: the clamp did its work
        // (without it the test would pass on any track inside the area).
        assert!(points.iter().any(|point| point[0] == min_x), "{points:?}");
    }
}
