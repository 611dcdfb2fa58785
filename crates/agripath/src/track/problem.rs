//! A track scenario, an encoding and a cost model as one [`swarm::BoxProblem`]: every planner on
//! the swarm engine sees a box and a cost, nothing of terrain or threats.

use swarm::{Bounds, BoxProblem};

use super::cost::CostBreakdown;
use super::encoding::Encoding;
use super::scenario::TrackScenario;

/// A track scenario under an encoding as a box problem: a point of the box is the free
/// waypoints, its cost the total of the scenario's cost model.
pub struct TrackProblem<'a> {
    /// The scenario the tracks are flown in.
    pub scenario: &'a TrackScenario,
    /// How a point of the box is read as waypoints.
    pub encoding: Encoding,
    waypoints: usize,
    bounds: Bounds,
}

impl<'a> TrackProblem<'a> {
    /// The scenario's own number of free waypoints.
    pub fn new(scenario: &'a TrackScenario, encoding: Encoding) -> Self {
        Self::with_waypoints(scenario, encoding, scenario.free_waypoints)
    }

    /// Room for `waypoints` free waypoints (seed 002's variable-length chromosomes use more
    /// room than their initial length; see [`super::improved_genetic`]).
    pub fn with_waypoints(
        scenario: &'a TrackScenario,
        encoding: Encoding,
        waypoints: usize,
    ) -> Self {
        Self {
            scenario,
            encoding,
            waypoints,
            bounds: encoding.bounds(scenario, waypoints),
        }
    }

    /// Number of free waypoints a point of the box holds.
    pub fn waypoints(&self) -> usize {
        self.waypoints
    }

    /// The whole track with altitudes above sea level: the takeoff leg (when the start is
    /// below the band), the cruise through the waypoints, the landing leg.
    pub fn track(&self, x: &[f64]) -> Vec<[f64; 3]> {
        self.scenario.whole_track(&self.cruise(x))
    }

    /// The cruise's start, the waypoints and the cruise's goal, above sea level.
    pub fn cruise(&self, x: &[f64]) -> Vec<[f64; 3]> {
        let mut points = Vec::with_capacity(self.waypoints + 2);
        self.encoding.decode_into(self.scenario, x, &mut points);
        for point in &mut points {
            *point = self.scenario.sea_level(*point);
        }
        points
    }

    /// The cost of the track at `x`, term by term (its `total` is the problem's cost).
    pub fn breakdown(&self, x: &[f64]) -> CostBreakdown {
        self.scenario.evaluate(&self.track(x))
    }
}

impl BoxProblem for TrackProblem<'_> {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        self.breakdown(x).total
    }
}
