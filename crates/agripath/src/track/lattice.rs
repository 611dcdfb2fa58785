//! Our planner's first stage: shortest paths on a terrain lattice, which choose the way
//! around threats and hills that a swarm has to find by chance.
//!
//! The area is a lattice of about 160 × 160 nodes joined to their 16 neighbours (the 8
//! adjacent ones and the 8 knight moves, so that paths can run at 26.6° steps as well as
//! 45°). A node is closed when it lies in a threat cylinder (with a margin of one lattice
//! step) or when the ground under it is higher than the altitude bounds allow. A move costs
//! its 3D length flown at the scenario's preferred height above the ground (the middle of
//! the band, or just above the floor without one), plus, near a threat, the danger-band cost
//! spread over the move: the lattice only has to pick the corridor; the refinement stage
//! ([`super::refine`]) then scores the real cost.
//!
//! Several corridors are returned: after each search, the nodes near the path found cost
//! three times more, so that the next search takes another way when one is nearly as good.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use super::scenario::{AltitudeReference, TrackScenario};

const TARGET_NODES_PER_SIDE: f64 = 160.0;
const MOVES: [(i32, i32); 16] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
    (2, 1),
    (2, -1),
    (-2, 1),
    (-2, -1),
    (1, 2),
    (1, -2),
    (-1, 2),
    (-1, -2),
];

struct Lattice<'a> {
    scenario: &'a TrackScenario,
    origin: (f64, f64),
    step: f64,
    columns: usize,
    rows: usize,
    open: Vec<bool>,
    /// The altitude (above sea level) the lattice flies at each node.
    altitude: Vec<f64>,
    /// Danger-band cost per unit length at each node.
    danger: Vec<f64>,
    /// Extra factor on moves near corridors already returned.
    detour: Vec<f64>,
}

/// The altitude (in the scenario's reference) a track prefers over ground `ground`.
fn preferred_altitude(scenario: &TrackScenario, ground: f64) -> f64 {
    let (low, high) = scenario.altitude_bounds;
    match (scenario.altitude_reference, scenario.height_band) {
        (AltitudeReference::AboveGround, Some((band_low, band_high))) => {
            0.5 * (band_low + band_high)
        }
        (AltitudeReference::AboveGround, None) => low,
        // Just inside the band: lower is shorter when the ground undulates under a climb.
        (AltitudeReference::SeaLevel, Some((band_low, band_high))) => {
            (ground + band_low + 0.1 * (band_high - band_low)).clamp(low, high)
        }
        (AltitudeReference::SeaLevel, None) => (ground + 2.0).clamp(low, high),
    }
}

impl<'a> Lattice<'a> {
    fn new(scenario: &'a TrackScenario) -> Self {
        let (min_x, min_y, max_x, max_y) = scenario.area;
        let step = ((max_x - min_x).max(max_y - min_y) / TARGET_NODES_PER_SIDE).max(1e-6);
        let columns = ((max_x - min_x) / step).floor() as usize + 1;
        let rows = ((max_y - min_y) / step).floor() as usize + 1;
        let leg = scenario.start_goal_distance() / (scenario.free_waypoints + 1) as f64;
        let (_, high) = scenario.altitude_bounds;
        let (danger_width, danger_weight) = scenario.cost.danger_band();
        let mut open = vec![true; columns * rows];
        let mut altitude = vec![0.0; columns * rows];
        let mut danger = vec![0.0; columns * rows];
        for row in 0..rows {
            for column in 0..columns {
                let index = row * columns + column;
                let (x, y) = (min_x + column as f64 * step, min_y + row as f64 * step);
                let ground = scenario.terrain.height(x, y);
                // Above the ground raised beside steep banks (decision 0032).
                let preferred = preferred_altitude(scenario, scenario.cost_ground().height(x, y));
                let sea_level = match scenario.altitude_reference {
                    AltitudeReference::AboveGround => preferred + ground,
                    AltitudeReference::SeaLevel => preferred,
                };
                altitude[index] = sea_level;
                if scenario.altitude_reference == AltitudeReference::SeaLevel
                    && ground + 1.0 >= high
                {
                    open[index] = false;
                }
                for threat in &scenario.threats {
                    let d = (x - threat.x).hypot(y - threat.y);
                    if d <= threat.radius + step {
                        open[index] = false;
                    } else if d < threat.radius + danger_width {
                        danger[index] += danger_weight * (threat.radius + danger_width - d) / leg;
                    }
                }
            }
        }
        Self {
            scenario,
            origin: (min_x, min_y),
            step,
            columns,
            rows,
            open,
            altitude,
            danger,
            detour: vec![1.0; columns * rows],
        }
    }

    fn position(&self, index: usize) -> [f64; 3] {
        let (row, column) = (index / self.columns, index % self.columns);
        [
            self.origin.0 + column as f64 * self.step,
            self.origin.1 + row as f64 * self.step,
            self.altitude[index],
        ]
    }

    fn nearest_open(&self, x: f64, y: f64) -> Option<usize> {
        (0..self.open.len())
            .filter(|&index| self.open[index])
            .min_by(|&a, &b| {
                let distance = |index: usize| {
                    let p = self.position(index);
                    (p[0] - x).hypot(p[1] - y)
                };
                distance(a).total_cmp(&distance(b))
            })
    }

    /// Dijkstra from the node nearest the start to the node nearest the goal.
    fn shortest(&self) -> Option<Vec<usize>> {
        let source =
            self.nearest_open(self.scenario.cruise_start[0], self.scenario.cruise_start[1])?;
        let target =
            self.nearest_open(self.scenario.cruise_goal[0], self.scenario.cruise_goal[1])?;
        let mut distance = vec![f64::INFINITY; self.open.len()];
        let mut previous = vec![usize::MAX; self.open.len()];
        let mut queue = BinaryHeap::new();
        distance[source] = 0.0;
        queue.push(Reverse((Ordered(0.0), source)));
        while let Some(Reverse((Ordered(cost), node))) = queue.pop() {
            if node == target {
                break;
            }
            if cost > distance[node] {
                continue;
            }
            let (row, column) = ((node / self.columns) as i32, (node % self.columns) as i32);
            for (dc, dr) in MOVES {
                let (next_row, next_column) = (row + dr, column + dc);
                if next_row < 0
                    || next_column < 0
                    || next_row >= self.rows as i32
                    || next_column >= self.columns as i32
                {
                    continue;
                }
                let next = next_row as usize * self.columns + next_column as usize;
                // A knight move also needs the two nodes it passes between to be open.
                let middle = (row + dr / 2) as usize * self.columns + (column + dc / 2) as usize;
                let beside = (row + (dr - dr / 2)) as usize * self.columns
                    + (column + (dc - dc / 2)) as usize;
                if !self.open[next] || !self.open[middle] || !self.open[beside] {
                    continue;
                }
                let (a, b) = (self.position(node), self.position(next));
                let length =
                    ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2) + (b[2] - a[2]).powi(2)).sqrt();
                let weight = length
                    * (1.0 + 0.5 * (self.danger[node] + self.danger[next]))
                    * 0.5
                    * (self.detour[node] + self.detour[next]);
                let candidate = cost + weight;
                if candidate < distance[next] {
                    distance[next] = candidate;
                    previous[next] = node;
                    queue.push(Reverse((Ordered(candidate), next)));
                }
            }
        }
        if distance[target].is_infinite() {
            return None;
        }
        let mut path = vec![target];
        while let Some(&last) = path.last() {
            if last == source {
                break;
            }
            path.push(previous[last]);
        }
        path.reverse();
        Some(path)
    }

    /// Makes moves within three steps of `path` three times dearer.
    fn discourage(&mut self, path: &[usize]) {
        for &node in path {
            let (row, column) = ((node / self.columns) as i32, (node % self.columns) as i32);
            for dr in -3..=3 {
                for dc in -3..=3 {
                    let (r, c) = (row + dr, column + dc);
                    if r >= 0 && c >= 0 && (r as usize) < self.rows && (c as usize) < self.columns {
                        self.detour[r as usize * self.columns + c as usize] = 3.0;
                    }
                }
            }
        }
    }
}

/// Total-ordered f64 for the heap (costs are finite and non-negative).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Ordered(f64);

impl Eq for Ordered {}

impl PartialOrd for Ordered {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Ordered {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Up to `count` corridors from start to goal, each as `free_waypoints` waypoints spaced
/// evenly along it (z in the scenario's altitude reference).
pub fn corridors(scenario: &TrackScenario, count: usize) -> Vec<Vec<[f64; 3]>> {
    let mut lattice = Lattice::new(scenario);
    let mut found = Vec::new();
    for _ in 0..count {
        let Some(path) = lattice.shortest() else {
            break;
        };
        let mut polyline: Vec<[f64; 3]> = vec![scenario.cruise_start];
        polyline.extend(path.iter().map(|&node| lattice.position(node)));
        polyline.push(scenario.cruise_goal);
        found.push(resample(scenario, &polyline, scenario.free_waypoints));
        lattice.discourage(&path);
    }
    found
}

/// `count` points at equal horizontal arc length strictly inside `polyline`, at the
/// preferred altitude over their ground.
fn resample(scenario: &TrackScenario, polyline: &[[f64; 3]], count: usize) -> Vec<[f64; 3]> {
    let lengths: Vec<f64> = polyline
        .windows(2)
        .map(|pair| (pair[1][0] - pair[0][0]).hypot(pair[1][1] - pair[0][1]))
        .collect();
    let total: f64 = lengths.iter().sum();
    let mut points = Vec::with_capacity(count);
    let (mut segment, mut walked) = (0, 0.0);
    for index in 1..=count {
        let wanted = total * index as f64 / (count + 1) as f64;
        while segment + 1 < lengths.len() && walked + lengths[segment] < wanted {
            walked += lengths[segment];
            segment += 1;
        }
        let t = if lengths[segment] > 0.0 {
            ((wanted - walked) / lengths[segment]).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (a, b) = (polyline[segment], polyline[segment + 1]);
        let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
        let mut z = preferred_altitude(scenario, scenario.cost_ground().height(x, y));
        if scenario.altitude_reference == AltitudeReference::SeaLevel
            && scenario.height_band.is_none()
        {
            // Without a band, the shortest climb is the straight start-goal slope, raised
            // where the ground is higher.
            let fraction = index as f64 / (count + 1) as f64;
            let slope = scenario.cruise_start[2]
                + fraction * (scenario.cruise_goal[2] - scenario.cruise_start[2]);
            let (low, high) = scenario.altitude_bounds;
            z = slope.max(z).clamp(low, high);
        }
        points.push([x, y, z]);
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corridors_avoid_every_threat_and_differ() {
        for task in ["I", "II", "III"] {
            let scenario = TrackScenario::seed000(task).unwrap();
            let found = corridors(&scenario, 3);
            assert!(found.len() >= 2, "task {task}");
            assert_eq!(found[0].len(), scenario.free_waypoints);
            for waypoints in &found {
                for point in waypoints {
                    for threat in &scenario.threats {
                        assert!((point[0] - threat.x).hypot(point[1] - threat.y) > threat.radius);
                    }
                }
            }
            assert_ne!(found[0], found[1]);
        }
        let spso = TrackScenario::spso().unwrap();
        let found = corridors(&spso, 1);
        assert_eq!(found[0].len(), spso.free_waypoints);
        assert!(
            found[0].iter().all(|p| p[2] == 150.0),
            "SPSO's nodes sit at the band's middle"
        );
    }
}
