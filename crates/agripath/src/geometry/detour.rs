//! The shortest way between two points that keeps out of a set of polygons (obstacles: the
//! geofence's exclusion zones, which bind at every altitude, so a transit may not fly over
//! them either).
//!
//! Visibility graph over the corners of each polygon's convex hull grown by a clearance;
//! Dijkstra from start to goal. A straight segment that meets no polygon is returned as is
//! (no corners). The hull makes the graph small and its corners always reachable; the price
//! is a slightly longer way round a concave obstacle, never a way through it.

use geo::{ConvexHull, Coord, Intersects, Line, MultiPoint, Point, Polygon};

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

/// The corners a transit from `start` to `goal` turns at to keep `clearance_m` from every
/// polygon (empty when the straight segment is clear). `None` when the start or the goal is
/// inside a polygon or no way exists.
pub fn detour(
    start: Coord<f64>,
    goal: Coord<f64>,
    polygons: &[Polygon<f64>],
    clearance_m: f64,
) -> Option<Vec<Coord<f64>>> {
    if !blocked(start, goal, polygons) {
        return Some(Vec::new());
    }
    if polygons.iter().any(|polygon| {
        polygon.intersects(&Point::from(start)) || polygon.intersects(&Point::from(goal))
    }) {
        return None;
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

/// The convex hull of `points` grown by `margin_m` (corners rounded by 8-segment arcs), as a
/// closed ring: the geofence's inclusion polygon around a flight.
pub fn grown_convex_hull(points: &[Coord<f64>], margin_m: f64) -> Vec<Coord<f64>> {
    let hull =
        MultiPoint::from(points.iter().map(|&c| Point::from(c)).collect::<Vec<_>>()).convex_hull();
    let ring = &hull.exterior().0;
    let n = ring.len().saturating_sub(1);
    let mut out = Vec::new();
    if n == 0 {
        return out;
    }
    let orientation: f64 = (0..n)
        .map(|i| ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y)
        .sum();
    let sign = if orientation >= 0.0 { 1.0 } else { -1.0 };
    for i in 0..n {
        let here = ring[i];
        let (start, mut end) = if n == 1 {
            (0.0, std::f64::consts::TAU)
        } else {
            let previous = ring[(i + n - 1) % n];
            let next = ring[(i + 1) % n];
            // Outward normals of the incoming and outgoing edges, as angles.
            let incoming = {
                let (dx, dy) = (here.x - previous.x, here.y - previous.y);
                (-sign * dx).atan2(sign * dy)
            };
            let outgoing = {
                let (dx, dy) = (next.x - here.x, next.y - here.y);
                (-sign * dx).atan2(sign * dy)
            };
            (incoming, outgoing)
        };
        // Sweep in the hull's direction of travel.
        if sign > 0.0 {
            while end < start {
                end += std::f64::consts::TAU;
            }
        } else {
            while end > start {
                end -= std::f64::consts::TAU;
            }
        }
        let steps = 8;
        // The arc's points sit on a circle of radius margin / cos(half step) so that its
        // chords stay at least `margin_m` from the corner.
        let step = (end - start) / steps as f64;
        let radius = margin_m / (step / 2.0).cos().max(0.5);
        for k in 0..=steps {
            let angle = start + step * k as f64;
            out.push(Coord {
                x: here.x + radius * angle.cos(),
                y: here.y + radius * angle.sin(),
            });
        }
    }
    out.push(out[0]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Contains, LineString};

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
    fn the_grown_hull_contains_every_point_with_its_margin() {
        let points = [
            Coord { x: 0.0, y: 0.0 },
            Coord { x: 30.0, y: 5.0 },
            Coord { x: 10.0, y: 20.0 },
            Coord { x: 12.0, y: 8.0 },
        ];
        let ring = grown_convex_hull(&points, 10.0);
        let polygon = Polygon::new(LineString::new(ring), vec![]);
        for point in points {
            for (dx, dy) in [(9.9, 0.0), (-9.9, 0.0), (0.0, 9.9), (0.0, -9.9), (7.0, 7.0)] {
                assert!(polygon.contains(&Point::new(point.x + dx, point.y + dy)));
            }
        }
    }
}
