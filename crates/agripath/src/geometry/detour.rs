//! The shortest way between two points that keeps out of a set of polygons (obstacles: the
//! geofence's exclusion zones, which bind at every altitude, so a transit may not fly over
//! them either).
//!
//! Visibility graph over the corners of each polygon's convex hull grown by a clearance;
//! Dijkstra from start to goal. A straight segment that meets no polygon is returned as is
//! (no corners). The hull makes the graph small and its corners always reachable; the price
//! is a slightly longer way round a concave obstacle, never a way through it.

use geo::{Contains, ConvexHull, Coord, Intersects, Line, MultiPoint, Point, Polygon};

/// Corners of the hull grown by `reach`: each hull vertex pushed out along its two edge
/// normals and their bisector, so that every edge of the grown polygon stays at least
/// `reach` × cos 45° from the hull.
fn grown_hull(polygon: &Polygon<f64>, reach: f64) -> Vec<Coord<f64>> {
    let hull = polygon.convex_hull();
    let ring: Vec<Coord<f64>> = hull.exterior().0.clone();
    let n = ring.len().saturating_sub(1);
    if n < 3 {
        return ring;
    }
    let mut corners = Vec::with_capacity(3 * n);
    // Counter-clockwise hull: outward normal of edge (a → b) is (dy, −dx).
    let orientation: f64 = (0..n)
        .map(|i| ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y)
        .sum();
    let sign = if orientation >= 0.0 { 1.0 } else { -1.0 };
    let normal = |a: Coord<f64>, b: Coord<f64>| {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let length = dx.hypot(dy).max(1e-12);
        Coord {
            x: sign * dy / length,
            y: -sign * dx / length,
        }
    };
    for i in 0..n {
        let previous = ring[(i + n - 1) % n];
        let here = ring[i];
        let next = ring[i + 1];
        let (incoming, outgoing) = (normal(previous, here), normal(here, next));
        let bisector = Coord {
            x: incoming.x + outgoing.x,
            y: incoming.y + outgoing.y,
        };
        let bisector_length = bisector.x.hypot(bisector.y).max(1e-12);
        for direction in [
            incoming,
            Coord {
                x: bisector.x / bisector_length,
                y: bisector.y / bisector_length,
            },
            outgoing,
        ] {
            corners.push(Coord {
                x: here.x + reach * direction.x,
                y: here.y + reach * direction.y,
            });
        }
    }
    corners
}

/// Whether the segment a–b meets any of `polygons`.
fn blocked(a: Coord<f64>, b: Coord<f64>, polygons: &[Polygon<f64>]) -> bool {
    let line = Line::new(a, b);
    polygons.iter().any(|polygon| polygon.intersects(&line))
}

/// How far a transit that begins or ends on an obstacle's edge steps off it first, metres.
const STEP_OFF_M: f64 = 0.5;
/// How near an edge a point counts as on it, metres.
const ON_EDGE_M: f64 = 0.01;
/// Directions tried for that step.
const STEP_OFF_DIRECTIONS: usize = 16;

/// The corners a transit from `start` to `goal` turns at to keep `clearance_m` from every
/// polygon (empty when the straight segment is clear). `None` when the start or the goal is
/// inside a polygon or no way exists. A start or goal on a polygon's edge (a swath cut by an
/// obstacle with no margin ends there) first steps 0.5 m off it, the step a corner
/// of its own.
pub fn detour(
    start: Coord<f64>,
    goal: Coord<f64>,
    polygons: &[Polygon<f64>],
    clearance_m: f64,
) -> Option<Vec<Coord<f64>>> {
    if !blocked(start, goal, polygons) {
        return Some(Vec::new());
    }
    let (start_off, goal_off) = (
        off_the_edge(start, polygons)?,
        off_the_edge(goal, polygons)?,
    );
    let mut corners = Vec::new();
    if start_off != start {
        corners.push(start_off);
    }
    corners.extend(shortest_way(start_off, goal_off, polygons, clearance_m)?);
    if goal_off != goal {
        corners.push(goal_off);
    }
    Some(corners)
}

/// `point` when it touches no polygon; when it lies on an edge, the point [`STEP_OFF_M`]
/// away in the first of [`STEP_OFF_DIRECTIONS`] directions whose step meets no polygon after
/// leaving it; `None` when it is inside one (or hemmed in).
fn off_the_edge(point: Coord<f64>, polygons: &[Polygon<f64>]) -> Option<Coord<f64>> {
    let here = Point::from(point);
    if !polygons.iter().any(|polygon| polygon.intersects(&here)) {
        return Some(point);
    }
    // On the edge to within rounding (a swath end computed where its line meets the edge
    // may fall a hair inside), or truly inside.
    let deep_inside = |polygon: &Polygon<f64>| {
        polygon.contains(&here)
            && std::iter::once(polygon.exterior())
                .chain(polygon.interiors())
                .all(|ring| geo::Distance::distance(&geo::Euclidean, ring, &here) > ON_EDGE_M)
    };
    if polygons.iter().any(deep_inside) {
        return None;
    }
    (0..STEP_OFF_DIRECTIONS)
        .map(|k| {
            let angle = std::f64::consts::TAU * k as f64 / STEP_OFF_DIRECTIONS as f64;
            (angle.cos(), angle.sin())
        })
        .find_map(|(dx, dy)| {
            let leaving = Coord {
                x: point.x + 0.02 * dx,
                y: point.y + 0.02 * dy,
            };
            let stepped = Coord {
                x: point.x + STEP_OFF_M * dx,
                y: point.y + STEP_OFF_M * dy,
            };
            (!blocked(leaving, stepped, polygons)).then_some(stepped)
        })
}

/// The corners of the shortest way from `start` to `goal`, both outside every polygon.
fn shortest_way(
    start: Coord<f64>,
    goal: Coord<f64>,
    polygons: &[Polygon<f64>],
    clearance_m: f64,
) -> Option<Vec<Coord<f64>>> {
    if !blocked(start, goal, polygons) {
        return Some(Vec::new());
    }
    // Segments keep out of each hull grown by the clearance (by ≥ 0.7 × clearance at its
    // corners); the graph's corners sit on hulls grown by 1.5 × the clearance, outside them.
    // A grown hull that holds the start or the goal (a swath end close to an obstacle) is
    // replaced by the obstacle itself.
    let blocking: Vec<Polygon<f64>> = polygons
        .iter()
        .map(|polygon| {
            let grown = MultiPoint::from(
                grown_hull(polygon, clearance_m)
                    .into_iter()
                    .map(Point::from)
                    .collect::<Vec<_>>(),
            )
            .convex_hull();
            if grown.intersects(&Point::from(start)) || grown.intersects(&Point::from(goal)) {
                polygon.clone()
            } else {
                grown
            }
        })
        .collect();
    let polygons = blocking.as_slice();
    let mut nodes = vec![start, goal];
    for polygon in &blocking {
        nodes.extend(grown_hull(polygon, 0.5 * clearance_m));
    }
    // Corners that fall inside another obstacle are of no use.
    nodes.retain(|node| {
        !polygons
            .iter()
            .any(|polygon| polygon.intersects(&Point::from(*node)))
    });
    // `retain` keeps order: start and goal stay at 0 and 1.
    let count = nodes.len();
    let mut distance = vec![f64::INFINITY; count];
    let mut previous = vec![usize::MAX; count];
    let mut done = vec![false; count];
    distance[0] = 0.0;
    for _ in 0..count {
        let Some(at) = (0..count)
            .filter(|&k| !done[k] && distance[k].is_finite())
            .min_by(|&a, &b| distance[a].total_cmp(&distance[b]))
        else {
            break;
        };
        if at == 1 {
            break;
        }
        done[at] = true;
        for next in 0..count {
            if done[next] || next == at {
                continue;
            }
            let (a, b) = (nodes[at], nodes[next]);
            let length = (b.x - a.x).hypot(b.y - a.y);
            if distance[at] + length < distance[next] && !blocked(a, b, polygons) {
                distance[next] = distance[at] + length;
                previous[next] = at;
            }
        }
    }
    if !distance[1].is_finite() {
        return None;
    }
    let mut corners = Vec::new();
    let mut at = previous[1];
    while at != 0 {
        corners.push(nodes[at]);
        at = previous[at];
    }
    corners.reverse();
    Some(corners)
}

/// Evenly spaced directions of the geofence polygon [`grown_convex_hull`] draws.
const FENCE_DIRECTIONS: usize = 64;
/// Hull edges at least this long keep their own direction in the fence, metres.
const FENCE_EDGE_M: f64 = 20.0;
/// At most this many such edges (the longest).
const FENCE_EDGES: usize = 256;

/// The convex hull of `points` grown by `margin_m`, as a closed ring of a bounded number of
/// corners whatever the number of points: the intersection of the support half-planes of the
/// hull, moved out by the margin, in 64 evenly spaced directions and in the directions of its
/// edges of 20 m or more (the 256 longest). It holds the hull grown by the margin (every
/// half-plane does), runs along the long edges at exactly the margin, and elsewhere reaches
/// past it by at most margin·(1/cos(π/64) − 1) + 20 m·tan(π/64) < 1 m: the geofence's
/// inclusion polygon round a flight, small enough for an autopilot's fence storage even round
/// a 50,000-vertex field.
pub fn grown_convex_hull(points: &[Coord<f64>], margin_m: f64) -> Vec<Coord<f64>> {
    if points.is_empty() {
        return Vec::new();
    }
    let hull =
        MultiPoint::from(points.iter().map(|&c| Point::from(c)).collect::<Vec<_>>()).convex_hull();
    let corners: Vec<Coord<f64>> = hull.exterior().0.clone();
    let mut long_edges: Vec<(f64, f64)> = corners
        .windows(2)
        .filter_map(|pair| {
            let (dx, dy) = (pair[1].x - pair[0].x, pair[1].y - pair[0].y);
            let length = dx.hypot(dy);
            // The normal on either side: the support takes the outer one.
            (length >= FENCE_EDGE_M).then(|| (length, dy.atan2(-dx)))
        })
        .collect();
    long_edges.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut angles: Vec<f64> = (0..FENCE_DIRECTIONS)
        .map(|k| std::f64::consts::TAU * k as f64 / FENCE_DIRECTIONS as f64)
        .collect();
    for &(_, angle) in long_edges.iter().take(FENCE_EDGES) {
        angles.push(angle.rem_euclid(std::f64::consts::TAU));
        angles.push((angle + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU));
    }
    angles.sort_by(f64::total_cmp);
    angles.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let support: Vec<(f64, f64, f64)> = angles
        .iter()
        .map(|&angle| {
            let (ux, uy) = (angle.cos(), angle.sin());
            let reach = corners
                .iter()
                .map(|p| p.x * ux + p.y * uy)
                .fold(f64::NEG_INFINITY, f64::max);
            (ux, uy, reach + margin_m)
        })
        .collect();
    let count = support.len();
    let mut ring: Vec<Coord<f64>> = (0..count)
        .map(|k| {
            let (ax, ay, ca) = support[k];
            let (bx, by, cb) = support[(k + 1) % count];
            let determinant = ax * by - ay * bx;
            Coord {
                x: (ca * by - cb * ay) / determinant,
                y: (ax * cb - bx * ca) / determinant,
            }
        })
        .collect();
    ring.push(ring[0]);
    ring
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Contains, Distance, LineString};

    fn square(x0: f64, y0: f64, size: f64) -> Polygon<f64> {
        Polygon::new(
            LineString::from(vec![
                (x0, y0),
                (x0 + size, y0),
                (x0 + size, y0 + size),
                (x0, y0 + size),
                (x0, y0),
            ]),
            vec![],
        )
    }

    #[test]
    fn a_clear_segment_needs_no_corner() {
        let corners = detour(
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 10.0, y: 0.0 },
            &[square(0.0, 5.0, 3.0)],
            2.0,
        );
        assert_eq!(corners, Some(vec![]));
    }

    #[test]
    fn a_blocked_segment_goes_round_with_clearance() {
        let obstacle = square(4.0, -2.0, 4.0);
        let (start, goal) = (Coord { x: 0.0, y: 0.0 }, Coord { x: 12.0, y: 0.0 });
        let corners = detour(start, goal, std::slice::from_ref(&obstacle), 1.0).unwrap();
        assert!(!corners.is_empty());
        let mut path = vec![start];
        path.extend(&corners);
        path.push(goal);
        let grown = geo::Buffer::buffer(&obstacle, 0.69);
        for pair in path.windows(2) {
            assert!(!grown.intersects(&Line::new(pair[0], pair[1])), "{path:?}");
        }
        let length: f64 = path
            .windows(2)
            .map(|p| (p[1].x - p[0].x).hypot(p[1].y - p[0].y))
            .sum();
        assert!(length < 12.0 + 8.0, "{length} m");
    }

    #[test]
    fn the_grown_hull_contains_every_point_with_its_margin_and_little_more() {
        let points = [
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 30.0, y: 5.0 },
            Coord { x: 10.0, y: 20.0 },
            Coord { x: 12.0, y: 8.0 },
        ];
        let ring = grown_convex_hull(&points, 10.0);
        assert!(ring.len() <= FENCE_DIRECTIONS + 2 * FENCE_EDGES + 1);
        let polygon = Polygon::new(LineString::new(ring.clone()), vec![]);
        // No corner further than the documented bound from the hull of the points.
        let hull = MultiPoint::from(points.iter().map(|&c| Point::from(c)).collect::<Vec<_>>())
            .convex_hull();
        for corner in &ring {
            let distance = geo::Euclidean.distance(&Point::from(*corner), &hull);
            let bound = 10.0 / (std::f64::consts::PI / 64.0).cos()
                + FENCE_EDGE_M * (std::f64::consts::PI / 64.0).tan();
            assert!(distance <= bound, "{distance} > {bound}");
        }
        for point in points {
            for (dx, dy) in [(9.9, 0.0), (-9.9, 0.0), (0.0, 9.9), (0.0, -9.9), (7.0, 7.0)] {
                assert!(polygon.contains(&Point::new(point.x + dx, point.y + dy)));
            }
        }
    }
}

#[cfg(test)]
mod edge_tests {
    use super::*;

    #[test]
    fn ends_on_an_obstacles_edge_step_off_it_and_go_round() {
        let square = Polygon::new(
            geo::LineString::from(vec![
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 10.0),
                (0.0, 10.0),
                (0.0, 0.0),
            ]),
            vec![],
        );
        let corners = detour(
            Coord { x: 10.0, y: 5.0 },
            Coord { x: 0.0, y: 5.0 },
            std::slice::from_ref(&square),
            2.0,
        )
        .expect("a way round");
        let mut path = vec![Coord { x: 10.0, y: 5.0 }];
        path.extend(corners);
        path.push(Coord { x: 0.0, y: 5.0 });
        for pair in path.windows(2) {
            let middle = Point::new((pair[0].x + pair[1].x) / 2.0, (pair[0].y + pair[1].y) / 2.0);
            assert!(!square.contains(&middle), "{path:?}");
        }
        // Inside is still refused.
        assert!(detour(
            Coord { x: 5.0, y: 5.0 },
            Coord { x: 20.0, y: 5.0 },
            &[square],
            2.0
        )
        .is_none());
    }
}
