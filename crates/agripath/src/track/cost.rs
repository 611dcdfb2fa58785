//! The cost models of a track, as values: seed 000's F = Σ b_k F_k, SPSO's cost as its
//! MATLAB code computes it, and seed 002's W = V_c + T_c + E_c.
//!
//! Every model scores the same thing, a polyline start → free waypoints → goal with
//! altitudes above sea level, and returns its terms, so reports can show what a cost is made
//! of. The papers' infinite branches (a collision, a crash) are a finite penalty per
//! violation, [`PENALTY`], as the MetaBox port of SPSO's model does: averages over runs stay
//! finite, and any track carrying one is reported infeasible by [`super::safety`].
//!
//! **Along the legs (ours, a deviation from every paper; decision 0013).** The papers score
//! the terrain and the band at the waypoints only, and a leg between two good waypoints may
//! sag out of the band or cut through a hill. Every model here also samples each leg at every
//! raster cell near the ground, and the band on a coarser raster where the leg is proven
//! clear of it ([`HeightMap::leg_excess`](super::height_map::HeightMap::leg_excess)):
//! - under the ground: [`PENALTY`] per leg that dips (the papers' infinite branch) plus
//!   [`DEPTH_PENALTY`] per unit × metre of depth integrated along the leg, so that a track
//!   grazing the ground costs less than one cutting through a hill and every optimizer is
//!   pulled out of the terrain;
//! - the ground the costs see is raised by the verdict's minimum clearance (plus the
//!   raster's error, [`TrackScenario::cost_clearance`]), and more where a slope or a bank
//!   beside is nearer than that ([`TrackScenario::cost_ground`], decision 0032), and every
//!   cylinder grown by the vehicle's radius, so that the costs pull towards what the safety
//!   verdict accepts;
//! - out of the height band: the integrated excursion (units × metres) divided by the
//!   straight track's leg ([`TrackScenario::reference_leg`]), at the model's own factor for
//!   a waypoint out of the band, so that an excursion held over one leg costs what the paper
//!   charges for one waypoint that far out.

use super::height_map::planar_length;
use super::scenario::TrackScenario;

/// What one infinite branch of a paper's cost costs here.
pub const PENALTY: f64 = 1.0e4;

/// Cost per scenario unit × metre of depth under the ground, integrated along a leg.
pub const DEPTH_PENALTY: f64 = 100.0;

/// The legs' excursions between their waypoints, summed over a cruise.
#[derive(Debug, Clone, Copy, Default)]
struct AlongLegs {
    legs_under_ground: usize,
    under_ground: f64,
    outside_band: f64,
}

impl AlongLegs {
    fn of(scenario: &TrackScenario, points: &[[f64; 3]]) -> Self {
        let mut sums = Self::default();
        for pair in points.windows(2) {
            let excess = scenario.cost_ground().leg_excess(
                pair[0],
                pair[1],
                scenario.cost_clearance(),
                scenario.height_band,
            );
            sums.legs_under_ground += usize::from(excess.dips);
            sums.under_ground += excess.under_ground;
            sums.outside_band += excess.outside_band;
        }
        sums
    }

    /// The cost of going under the ground.
    fn terrain_cost(&self) -> f64 {
        self.legs_under_ground as f64 * PENALTY + DEPTH_PENALTY * self.under_ground
    }

    /// The band excursion in waypoint-equivalents (metres out of the band).
    fn band_metres(&self, scenario: &TrackScenario) -> f64 {
        self.outside_band / scenario.reference_leg()
    }
}

/// Legs of a whole track's cruise that the cost models' conservative ground (the terrain
/// raised by the clearance sideways, decision 0032) finds too low: each costs [`PENALTY`],
/// whatever the exact safety check says of the track.
pub fn legs_too_low(scenario: &TrackScenario, points: &[[f64; 3]]) -> usize {
    let (cruise, _) = scenario.cruise_of(points);
    AlongLegs::of(scenario, cruise).legs_under_ground
}

/// A cost and its terms (named by the model).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostBreakdown {
    /// The cost: the terms, weighted, summed.
    pub total: f64,
    /// The model's terms before weighting, in its order (see [`CostModel::term_names`]).
    pub terms: [f64; 4],
}

/// Seed 000 eqs. (17)-(26). The paper gives none of the weights: these are ours, fixed for
/// every algorithm (contract decision 7, `docs/contract.md`; `docs/decisions/0011-tracks.md`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seed000Cost {
    /// b_1..b_4 of eq. (26).
    pub weights: [f64; 4],
    /// D of eq. (19): the danger band around each cylinder, metres.
    pub danger_m: f64,
    /// γ_c of eq. (19), per metre inside the danger band.
    pub threat_factor: f64,
    /// γ_h of eq. (20), per metre outside the height band.
    pub height_factor: f64,
    /// a_1 of eq. (25), per radian of turn.
    pub turn_factor: f64,
    /// a_2 of eq. (25), per radian of pitch change.
    pub pitch_factor: f64,
}

impl Default for Seed000Cost {
    fn default() -> Self {
        Self {
            weights: [1.0, 1.0, 1.0, 1.0],
            danger_m: 20.0,
            threat_factor: 1.0,
            height_factor: 1.0,
            turn_factor: 10.0,
            pitch_factor: 10.0,
        }
    }
}

/// SPSO's `MyCost.m` (Phung & Ha 2021, docs/references.md): weights 5, 1, 10, 1; drone size S = 1, danger
/// distance D = 10·S; angle penalties only above 45°.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpsoCost {
    /// Weights of the length, threat, altitude and smoothness terms.
    pub weights: [f64; 4],
    /// S: the drone's size, added to each cylinder's radius, in the scenario's units.
    pub drone_size: f64,
    /// D: the danger band beyond the drone size, in the scenario's units.
    pub danger: f64,
}

impl Default for SpsoCost {
    fn default() -> Self {
        Self {
            weights: [5.0, 1.0, 10.0, 1.0],
            drone_size: 1.0,
            danger: 10.0,
        }
    }
}

/// Seed 002 eqs. (13)-(16): length, M per waypoint under the terrain, M per waypoint out
/// of the space. M is not given: [`PENALTY`]. Eq. (15) tests the waypoints only, which lets
/// a straight leg cut through a hill between two clear waypoints (a 2-waypoint track through
/// the survey space's highest hills scores as the best): here T_c counts M for each leg that
/// dips under the terrain anywhere (a waypoint under the terrain included), the check
/// contract decision 7 (docs/contract.md) asks of every model.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Seed002Cost;

/// Which cost a track planner minimises.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CostModel {
    /// Seed 000's F.
    Seed000(Seed000Cost),
    /// SPSO's `MyCost.m`.
    Spso(SpsoCost),
    /// Seed 002's W.
    Seed002(Seed002Cost),
}

/// 2D distance from (px, py) to the segment a → b.
pub fn point_segment_distance(px: f64, py: f64, a: [f64; 3], b: [f64; 3]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length_squared = dx * dx + dy * dy;
    let t = if length_squared > 0.0 {
        (((px - a[0]) * dx + (py - a[1]) * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    planar_length(px - (a[0] + t * dx), py - (a[1] + t * dy))
}

pub(crate) fn length_3d(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt()
}

impl CostModel {
    /// Names of the four terms, for reports.
    pub fn term_names(&self) -> [&'static str; 4] {
        match self {
            CostModel::Seed000(_) => ["length", "threat", "height", "turn_pitch"],
            CostModel::Spso(_) => ["length", "threat", "altitude", "smoothness"],
            CostModel::Seed002(_) => ["length", "terrain", "boundary", "unused"],
        }
    }

    /// Width of the danger band around each cylinder (beyond its radius, and SPSO's drone
    /// size) and its cost per unit of intrusion relative to a unit of length: what the lattice
    /// surrogate and the top view need of the model.
    pub fn danger_band(&self) -> (f64, f64) {
        match self {
            CostModel::Seed000(model) => (
                model.danger_m,
                model.threat_factor * model.weights[1] / model.weights[0],
            ),
            CostModel::Spso(model) => (
                model.drone_size + model.danger,
                model.weights[1] / model.weights[0],
            ),
            CostModel::Seed002(_) => (0.0, 0.0),
        }
    }

    /// The weight of the length term, which a track's vertical legs add to.
    pub fn length_weight(&self) -> f64 {
        match self {
            CostModel::Seed000(model) => model.weights[0],
            CostModel::Spso(model) => model.weights[0],
            CostModel::Seed002(_) => 1.0,
        }
    }

    /// The model's name, for reports.
    pub fn label(&self) -> &'static str {
        match self {
            CostModel::Seed000(_) => "seed 000 F (eqs. 17-26)",
            CostModel::Spso(_) => "SPSO MyCost.m",
            CostModel::Seed002(_) => "seed 002 W (eqs. 13-16)",
        }
    }

    /// The cost of a track whose `points` (start, free waypoints, goal) have altitudes above
    /// sea level.
    pub fn evaluate(&self, scenario: &TrackScenario, points: &[[f64; 3]]) -> CostBreakdown {
        match self {
            CostModel::Seed000(model) => seed000(model, scenario, points),
            CostModel::Spso(model) => spso(model, scenario, points),
            CostModel::Seed002(_) => seed002(scenario, points),
        }
    }
}

/// Seed 000, eqs. (17)-(26), with the decisions of `docs/decisions/0011-tracks.md`:
/// d_k is the 2D distance from the axis to the segment; α is the turn angle between the
/// horizontal projections (atan2 of |cross| and dot: eq. (23) prints the arctan of a sine);
/// eq. (21) sums H over every point of the track; the legs add their depth under the ground
/// and their band excursion (module doc).
fn seed000(model: &Seed000Cost, scenario: &TrackScenario, points: &[[f64; 3]]) -> CostBreakdown {
    let mut length = 0.0;
    let mut threat = 0.0;
    let mut height = 0.0;
    let mut angles = 0.0;
    let (h_min, h_max) = scenario.height_band.unwrap_or((0.0, f64::INFINITY));
    let vehicle = scenario.limits.vehicle_radius_m / scenario.unit_m;
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        length += length_3d(a, b);
        for cylinder in &scenario.threats {
            let d = point_segment_distance(cylinder.x, cylinder.y, a, b);
            threat += if d >= model.danger_m + cylinder.radius {
                0.0
            } else if d > cylinder.radius + vehicle {
                model.threat_factor * (model.danger_m + cylinder.radius - d)
            } else {
                PENALTY
            };
        }
    }
    let along = AlongLegs::of(scenario, points);
    height += along.terrain_cost() + model.height_factor * along.band_metres(scenario);
    for point in points {
        let h = point[2] - scenario.terrain.height(point[0], point[1]);
        height += if h <= 0.0 {
            PENALTY
        } else if h <= h_min {
            model.height_factor * (h_min - h)
        } else if h >= h_max {
            model.height_factor * (h - h_max)
        } else {
            0.0
        };
    }
    // Eq. (24): the pitch of each segment; eq. (25): turns between consecutive horizontal
    // projections and changes of pitch.
    let mut previous: Option<(f64, f64, f64)> = None; // (dx, dy, pitch)
    for pair in points.windows(2) {
        let (dx, dy, dz) = (
            pair[1][0] - pair[0][0],
            pair[1][1] - pair[0][1],
            pair[1][2] - pair[0][2],
        );
        let pitch = dz.atan2(planar_length(dx, dy));
        if let Some((px, py, previous_pitch)) = previous {
            let turn = (px * dy - py * dx).abs().atan2(px * dx + py * dy);
            angles +=
                model.turn_factor * turn + model.pitch_factor * (pitch - previous_pitch).abs();
        }
        previous = Some((dx, dy, pitch));
    }
    let terms = [length, threat, height, angles];
    let total = terms
        .iter()
        .zip(model.weights)
        .map(|(term, weight)| term * weight)
        .sum();
    CostBreakdown { total, terms }
}

/// SPSO's `MyCost.m` line by line (one unit = one pixel; altitudes of the free nodes are
/// read back above ground with the same nearest-pixel terrain).
fn spso(model: &SpsoCost, scenario: &TrackScenario, points: &[[f64; 3]]) -> CostBreakdown {
    let count = points.len();
    // J1: 3D length over absolute heights.
    let length: f64 = points
        .windows(2)
        .map(|pair| length_3d(pair[0], pair[1]))
        .sum();
    // J2: the three-branch threat cost per segment and cylinder.
    let mut threat = 0.0;
    let vehicle = scenario.limits.vehicle_radius_m / scenario.unit_m;
    for cylinder in &scenario.threats {
        let outer = cylinder.radius + model.drone_size + model.danger;
        let inner = cylinder.radius + model.drone_size.max(vehicle);
        for pair in points.windows(2) {
            let d = point_segment_distance(cylinder.x, cylinder.y, pair[0], pair[1]);
            threat += if d > outer {
                0.0
            } else if d < inner {
                PENALTY
            } else {
                outer - d
            };
        }
    }
    // J3: |z − z_mid| over the free nodes (above ground); z < 0 is a crash.
    let (z_min, z_max) = scenario.height_band.unwrap_or((0.0, 0.0));
    let middle = 0.5 * (z_min + z_max);
    let along = AlongLegs::of(scenario, points);
    let altitude: f64 = along.terrain_cost()
        + along.band_metres(scenario)
        + points[1..count - 1]
            .iter()
            .map(|point| {
                let above = point[2] - scenario.terrain.height(point[0], point[1]);
                if above < 0.0 {
                    PENALTY
                } else {
                    (above - middle).abs()
                }
            })
            .sum::<f64>();
    // J4: turning angles and climb-angle changes above 45°, in degrees; a zero-length
    // horizontal projection is replaced by the nearest non-zero one (backward for the
    // first segment, forward for the second), as the reference does.
    let mut smoothness = 0.0;
    for i in 0..count.saturating_sub(2) {
        let projection = |from: usize, to: usize| {
            [
                points[to][0] - points[from][0],
                points[to][1] - points[from][1],
            ]
        };
        let mut first = projection(i, i + 1);
        let mut back = i as isize - 1;
        while back >= 0 && first[0] == 0.0 && first[1] == 0.0 {
            first = projection(back as usize, i + 1);
            back -= 1;
        }
        let mut second = projection(i + 1, i + 2);
        let mut ahead = i + 3;
        while ahead < count && second[0] == 0.0 && second[1] == 0.0 {
            second = projection(i + 1, ahead);
            ahead += 1;
        }
        let climb_first = (points[i + 1][2] - points[i][2])
            .atan2(planar_length(first[0], first[1]))
            .to_degrees();
        let climb_second = (points[i + 2][2] - points[i + 1][2])
            .atan2(planar_length(second[0], second[1]))
            .to_degrees();
        let cross = (first[0] * second[1] - first[1] * second[0]).abs();
        let dot = first[0] * second[0] + first[1] * second[1];
        let turn = cross.atan2(dot).to_degrees();
        if turn.abs() > 45.0 {
            smoothness += turn.abs();
        }
        if (climb_second - climb_first).abs() > 45.0 {
            smoothness += (climb_second - climb_first).abs();
        }
    }
    let terms = [length, threat, altitude, smoothness];
    let total = terms
        .iter()
        .zip(model.weights)
        .map(|(term, weight)| term * weight)
        .sum();
    CostBreakdown { total, terms }
}

/// Seed 002 eqs. (13)-(16) over points 1..n (T_c0 = E_c0 = 0 for the start), T_c per leg
/// with its depth (module doc).
fn seed002(scenario: &TrackScenario, points: &[[f64; 3]]) -> CostBreakdown {
    let length: f64 = points
        .windows(2)
        .map(|pair| length_3d(pair[0], pair[1]))
        .sum();
    let (min_x, min_y, max_x, max_y) = scenario.area;
    let (_, z_max) = scenario.altitude_bounds;
    let mut terrain = 0.0;
    let mut boundary = 0.0;
    let (clearance, ground) = (scenario.cost_clearance(), scenario.cost_ground());
    for (leg, point) in points.windows(2).zip(&points[1..]) {
        let excess = ground.leg_excess(leg[0], leg[1], clearance, None);
        if excess.dips || point[2] < ground.height(point[0], point[1]) + clearance {
            terrain += PENALTY;
        }
        terrain += DEPTH_PENALTY * excess.under_ground;
        let outside = !(min_x..=max_x).contains(&point[0])
            || !(min_y..=max_y).contains(&point[1])
            || !(0.0..=z_max).contains(&point[2]);
        if outside {
            boundary += PENALTY;
        }
    }
    CostBreakdown {
        total: length + terrain + boundary,
        terms: [length, terrain, boundary, 0.0],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn point_segment_distance_handles_ends_and_degenerate_segments() {
        let (a, b) = ([0.0, 0.0, 0.0], [10.0, 0.0, 0.0]);
        assert!((point_segment_distance(5.0, 3.0, a, b) - 3.0).abs() < 1e-12);
        assert!((point_segment_distance(-3.0, 4.0, a, b) - 5.0).abs() < 1e-12);
        assert!((point_segment_distance(13.0, 4.0, a, b) - 5.0).abs() < 1e-12);
        assert!((point_segment_distance(3.0, 4.0, a, a) - 5.0).abs() < 1e-12);
    }

    #[test]
    fn spso_straight_line_through_a_cylinder_is_penalised() {
        // The straight start-goal line at 150 m above ground crosses a cylinder (the
        // reference note: J1 = 933.96 but J2 infinite).
        let scenario = TrackScenario::spso().unwrap();
        let n = scenario.free_waypoints;
        let points: Vec<[f64; 3]> = (0..n + 2)
            .map(|i| {
                let t = i as f64 / (n + 1) as f64;
                let x = scenario.start[0] + t * (scenario.goal[0] - scenario.start[0]);
                let y = scenario.start[1] + t * (scenario.goal[1] - scenario.start[1]);
                scenario.sea_level([x, y, 150.0])
            })
            .collect();
        let cost = scenario.cost.evaluate(&scenario, &points);
        assert!(
            (cost.terms[0] - 933.96).abs() < 0.5,
            "J1 = {}",
            cost.terms[0]
        );
        assert!(cost.terms[1] >= PENALTY);
        assert_eq!(cost.terms[2], 0.0);
    }

    #[test]
    fn seed000_terms_follow_the_equations_on_a_hand_computed_track() {
        let mut scenario = TrackScenario::seed000("I").unwrap();
        scenario.threats = vec![super::super::scenario::Threat {
            x: 500.0,
            y: 510.0,
            radius: 5.0,
        }];
        let ground = |x: f64, y: f64| scenario.terrain.height(x, y);
        // Two segments at 150 m above ground at the points: east then north.
        let points = [
            [400.0, 500.0, ground(400.0, 500.0) + 150.0],
            [500.0, 500.0, ground(500.0, 500.0) + 150.0],
            [500.0, 600.0, ground(500.0, 600.0) + 150.0],
        ];
        let cost = scenario.cost.evaluate(&scenario, &points);
        let expected_length = length_3d(points[0], points[1]) + length_3d(points[1], points[2]);
        assert!((cost.terms[0] - expected_length).abs() < 1e-9);
        // The cylinder at distance 10 from the first segment and 0 from the second.
        assert!((cost.terms[1] - (20.0 + 5.0 - 10.0) - PENALTY).abs() < 1e-9);
        assert_eq!(cost.terms[2], 0.0);
        let pitch =
            |a: [f64; 3], b: [f64; 3]| (b[2] - a[2]).atan2((b[0] - a[0]).hypot(b[1] - a[1]));
        let expected_angles = 10.0 * std::f64::consts::FRAC_PI_2
            + 10.0 * (pitch(points[1], points[2]) - pitch(points[0], points[1])).abs();
        assert!((cost.terms[3] - expected_angles).abs() < 1e-9);
    }
}
