//! A route as the sortie planners see it: points in flight order with what each segment is
//! (spraying, turning, transferring), and running sums of spray metres and flight seconds so
//! that any stretch is measured in O(1).
//!
//! A return can happen at any point: the drone leaves there for the supply point, and the
//! next sortie resumes there. Built from the seed 003 grid route ([`super::grid`]) or from a
//! sequenced coverage plan ([`WorkRoute::from_route`]).

use crate::sequence::Route;

/// What the drone does along a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Segment {
    /// Spraying along a swath, at spray speed.
    Spray,
    /// A headland turn between swaths, at turn speed.
    Turn,
    /// A transfer (climbing out of the field and back), at transit speed.
    Transfer,
}

/// A point of the route: plan coordinates and terrain height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoutePoint {
    /// Easting in the planning frame, metres.
    pub x: f64,
    /// Northing in the planning frame, metres.
    pub y: f64,
    /// Terrain height above sea level, metres.
    pub ground_m: f64,
}

impl From<crate::coverage::drape::GroundPoint> for RoutePoint {
    fn from(point: crate::coverage::drape::GroundPoint) -> Self {
        Self {
            x: point.x,
            y: point.y,
            ground_m: point.ground_m,
        }
    }
}

/// The route with prefix sums.
#[derive(Debug, Clone, PartialEq)]
pub struct WorkRoute {
    points: Vec<RoutePoint>,
    /// `segments[i]` leads from `points[i]` to `points[i + 1]`.
    segments: Vec<Segment>,
    /// Spray metres from the start to each point.
    spray_m: Vec<f64>,
    /// Flight seconds from the start to each point.
    flight_s: Vec<f64>,
    /// Non-spray (turn and transfer) metres from the start to each point.
    other_m: Vec<f64>,
    /// Seconds spent spraying over the whole route.
    spray_s: f64,
}

/// Speeds for timing a route, m/s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Speeds {
    /// Speed while spraying.
    pub spray_mps: f64,
    /// Speed in headland turns.
    pub turn_mps: f64,
    /// Speed of transfers.
    pub transit_mps: f64,
    /// Vertical speeds: where the ground under a pass is steep, the drone following it at
    /// spray height climbs at most `climb_mps` and sinks at most `descent_mps`
    /// ([`Speeds::spray_s`]).
    pub climb_mps: f64,
    /// See `climb_mps`.
    pub descent_mps: f64,
    /// Seconds a transfer that climbs out of the field flies beyond its eq. 8 metres at
    /// transit speed: the mission climbs to the cruise height and descends again at climb
    /// speed (decision 0012), where eq. 8 charges the 2h at transit speed.
    pub transfer_climb_s: f64,
}

impl Speeds {
    /// The speeds a route of `vehicle` is timed with.
    pub fn of(vehicle: &crate::model::Vehicle) -> Self {
        Self {
            spray_mps: vehicle.spray_speed_mps,
            turn_mps: vehicle.turn_speed_mps,
            transit_mps: vehicle.transit_speed_mps,
            climb_mps: vehicle.climb_speed_mps,
            descent_mps: vehicle.descent_mps(),
            transfer_climb_s: transfer_climb_s(vehicle),
        }
    }

    /// Seconds to spray a segment of `length_m` (3D) whose ends' ground differs by `rise_m`:
    /// at spray speed, unless following the ground at climb speed takes longer (a slope
    /// steeper than about 35° at the default speeds). The mission files fly each leg in the
    /// longer of its horizontal and vertical times (the preflight times them so); at spray
    /// speed alone, a survey over the steep ground of Christmas Island flew 8 s longer per
    /// sortie than the split planned, and one sortie came to 101.4 % of its battery.
    pub fn spray_s(&self, length_m: f64, rise_m: f64) -> f64 {
        let vertical_s = if rise_m >= 0.0 {
            rise_m / self.climb_mps
        } else {
            -rise_m / self.descent_mps
        };
        (length_m / self.spray_mps).max(vertical_s)
    }
}

/// What the climb and descent of a transfer between fields add to its eq. 8 time: the
/// mission files rise from the spray height to the cruise height, max(h, 5 m) higher, at
/// climb speed, and come down again at descent speed (the mission writer's transfers), eq. 8
/// adds 2h at transit speed. Without it the split planned sorties the files fly longer than the battery lasts
/// (the demo's sorties flew 12 s longer for every such transfer; the preflight refused a
/// survey's sortie at 101.9 % of its battery).
fn transfer_climb_s(vehicle: &crate::model::Vehicle) -> f64 {
    let rise_m = vehicle.transit_rise_m();
    (vehicle.vertical_s(rise_m) + vehicle.vertical_s(-rise_m)
        - 2.0 * vehicle.safe_height_m / vehicle.transit_speed_mps)
        .max(0.0)
}

fn distance_3d(a: &RoutePoint, b: &RoutePoint) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2) + (a.ground_m - b.ground_m).powi(2)).sqrt()
}

impl WorkRoute {
    /// A route from its points and segment kinds (`segments.len() + 1 == points.len()`), timed
    /// with `speeds`. `extra_m[i]`, when given, adds metres to segment i (a transfer's climb).
    pub fn new(
        points: Vec<RoutePoint>,
        segments: Vec<Segment>,
        extra_m: Option<Vec<f64>>,
        speeds: Speeds,
    ) -> Self {
        assert_eq!(
            segments.len() + 1,
            points.len().max(1),
            "one segment between each two points"
        );
        let mut spray_m = Vec::with_capacity(points.len());
        let mut flight_s = Vec::with_capacity(points.len());
        let mut other_m = Vec::with_capacity(points.len());
        let (mut spray, mut flight, mut other, mut spray_s) = (0.0, 0.0, 0.0, 0.0);
        for (index, point) in points.iter().enumerate() {
            if index > 0 {
                let length = distance_3d(&points[index - 1], point)
                    + extra_m.as_ref().map_or(0.0, |extra| extra[index - 1]);
                match segments[index - 1] {
                    Segment::Spray => {
                        let seconds =
                            speeds.spray_s(length, point.ground_m - points[index - 1].ground_m);
                        spray += length;
                        flight += seconds;
                        spray_s += seconds;
                    }
                    Segment::Turn => {
                        other += length;
                        flight += length / speeds.turn_mps;
                    }
                    Segment::Transfer => {
                        other += length;
                        flight += length / speeds.transit_mps + speeds.transfer_climb_s;
                    }
                }
            }
            spray_m.push(spray);
            flight_s.push(flight);
            other_m.push(other);
        }
        Self {
            points,
            segments,
            spray_m,
            flight_s,
            other_m,
            spray_s,
        }
    }

    /// The flight of a sequenced coverage plan: every pass's draped points (spray), the
    /// transfers between passes (turns when they stay in the field, transfers with their
    /// eq. 8 climb when they leave it). The launch and home legs are not part of it: the
    /// sortie planner flies from and to the supply point itself.
    pub fn from_route(route: &Route, speeds: Speeds) -> Self {
        let mut points = Vec::new();
        let mut segments = Vec::new();
        let mut extra = Vec::new();
        for (index, visit) in route.visits.iter().enumerate() {
            for (k, point) in visit.points.iter().enumerate() {
                let point = RoutePoint::from(*point);
                if !points.is_empty() {
                    if k == 0 {
                        let transfer = &route.transfers[index - 1];
                        let straight = distance_3d(points.last().expect("not empty"), &point);
                        if transfer.climbs {
                            segments.push(Segment::Transfer);
                            extra.push((transfer.cost_m - straight).max(0.0));
                        } else {
                            segments.push(Segment::Turn);
                            extra.push(0.0);
                        }
                    } else {
                        segments.push(Segment::Spray);
                        extra.push(0.0);
                    }
                }
                points.push(point);
            }
        }
        Self::new(points, segments, Some(extra), speeds)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the route has no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The points in flight order.
    pub fn points(&self) -> &[RoutePoint] {
        &self.points
    }

    /// The segments: `segments[i]` leads from `points[i]` to `points[i + 1]`.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Spray metres from the start to each point.
    pub fn spray_prefix(&self) -> &[f64] {
        &self.spray_m
    }

    /// Flight seconds from the start to each point.
    pub fn flight_prefix(&self) -> &[f64] {
        &self.flight_s
    }

    /// Spray metres between points `from` and `to` (indices, from ≤ to).
    pub fn spray_between(&self, from: usize, to: usize) -> f64 {
        self.spray_m[to] - self.spray_m[from]
    }

    /// Flight seconds along the route between points `from` and `to`.
    pub fn flight_between(&self, from: usize, to: usize) -> f64 {
        self.flight_s[to] - self.flight_s[from]
    }

    /// Turn and transfer metres between points `from` and `to`.
    pub fn other_between(&self, from: usize, to: usize) -> f64 {
        self.other_m[to] - self.other_m[from]
    }

    /// Seconds of turns and transfers over the whole route (E's D_u / v_u).
    pub fn non_spray_flight_s(&self) -> f64 {
        self.flight_s.last().copied().unwrap_or(0.0) - self.spray_s
    }

    /// All spray metres.
    pub fn total_spray_m(&self) -> f64 {
        self.spray_m.last().copied().unwrap_or(0.0)
    }

    /// Indices of the points where a spray run ends (a swath end, before a turn or transfer,
    /// or the route's last point).
    pub fn spray_run_ends(&self) -> Vec<usize> {
        (1..self.points.len())
            .filter(|&i| {
                self.segments[i - 1] == Segment::Spray
                    && self
                        .segments
                        .get(i)
                        .is_none_or(|next| *next != Segment::Spray)
            })
            .collect()
    }

    /// Indices of the points where a spray run starts.
    pub fn spray_run_starts(&self) -> Vec<usize> {
        (0..self.points.len().saturating_sub(1))
            .filter(|&i| {
                self.segments[i] == Segment::Spray
                    && (i == 0 || self.segments[i - 1] != Segment::Spray)
            })
            .collect()
    }
}
