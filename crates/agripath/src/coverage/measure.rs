//! How well a layout covers its field: the sprayed strips (every pass ± w/2) against the
//! sprayable region, with exact polygon overlay.

use geo::algorithm::bool_ops::unary_union;
use geo::{Area, BooleanOps, Coord, LineString, MultiPolygon, Polygon};
use serde::Serialize;

use super::region::offset;
use super::scan_lines::Segment;

/// How well a layout covers its field, by polygon overlay of the sprayed strips.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CoverageMeasure {
    /// Sprayable area, m².
    pub sprayable_area_m2: f64,
    /// Share of the sprayable area under at least one strip, 0..1.
    pub covered_fraction: f64,
    /// Area sprayed more than once, m² (counted once per extra pass).
    pub overlap_m2: f64,
    /// Strip area outside the sprayable region (over holes, obstacles or off the field), m².
    pub outside_m2: f64,
}

/// The strip one swath sprays, in the rotated frame of its heading (where the swath runs
/// along x): its segment widened by w/2 on each side, square ends.
pub fn swath_strip(segment: &Segment, width_m: f64) -> Polygon<f64> {
    let half = width_m / 2.0;
    let corners = [
        (segment.start_x, segment.y - half),
        (segment.end_x, segment.y - half),
        (segment.end_x, segment.y + half),
        (segment.start_x, segment.y + half),
        (segment.start_x, segment.y - half),
    ];
    Polygon::new(
        LineString::new(corners.iter().map(|&(x, y)| Coord { x, y }).collect()),
        vec![],
    )
}

/// The band an edge pass sprays: its line widened by w/2 on each side.
pub fn edge_strip(pass_region: &MultiPolygon<f64>, width_m: f64) -> MultiPolygon<f64> {
    offset(pass_region, width_m / 2.0).difference(&offset(pass_region, -width_m / 2.0))
}

/// Measures `strips` against `sprayable`.
pub fn measure(sprayable: &MultiPolygon<f64>, strips: &[MultiPolygon<f64>]) -> CoverageMeasure {
    let sprayable_area = sprayable.unsigned_area();
    if strips.is_empty() || sprayable_area == 0.0 {
        return CoverageMeasure {
            sprayable_area_m2: sprayable_area,
            covered_fraction: 0.0,
            overlap_m2: 0.0,
            outside_m2: 0.0,
        };
    }
    let union = unary_union(strips.iter());
    let covered = union.intersection(sprayable).unsigned_area();
    let rings = Ring::all(sprayable);
    let inside_sum: f64 = strips
        .iter()
        .map(|strip| match convex_quadrilateral(strip) {
            Some(corners) => rings.iter().map(|ring| ring.clipped_area(&corners)).sum(),
            None => strip.intersection(sprayable).unsigned_area(),
        })
        .sum();
    CoverageMeasure {
        sprayable_area_m2: sprayable_area,
        covered_fraction: covered / sprayable_area,
        overlap_m2: (inside_sum - covered).max(0.0),
        outside_m2: union.difference(sprayable).unsigned_area(),
    }
}

/// A ring of the sprayable region with its box and its sign (+1 shell, −1 hole).
struct Ring {
    points: Vec<Coord<f64>>,
    lower: Coord<f64>,
    upper: Coord<f64>,
    sign: f64,
}

impl Ring {
    fn all(region: &MultiPolygon<f64>) -> Vec<Ring> {
        let mut rings = Vec::new();
        for polygon in region {
            let mut add = |ring: &LineString<f64>, sign: f64| {
                let points: Vec<Coord<f64>> = ring.0.clone();
                let lower = points.iter().fold(
                    Coord {
                        x: f64::INFINITY,
                        y: f64::INFINITY,
                    },
                    |m, p| Coord {
                        x: m.x.min(p.x),
                        y: m.y.min(p.y),
                    },
                );
                let upper = points.iter().fold(
                    Coord {
                        x: f64::NEG_INFINITY,
                        y: f64::NEG_INFINITY,
                    },
                    |m, p| Coord {
                        x: m.x.max(p.x),
                        y: m.y.max(p.y),
                    },
                );
                rings.push(Ring {
                    points,
                    lower,
                    upper,
                    sign,
                });
            };
            add(polygon.exterior(), 1.0);
            for hole in polygon.interiors() {
                add(hole, -1.0);
            }
        }
        rings
    }

    /// The signed share of this ring's area inside the convex `corners` (counter-clockwise),
    /// by Sutherland-Hodgman clipping. For a non-convex ring the clipped ring can run along
    /// the clip edges twice, but those stretches enclose no area: its |signed area| is the
    /// area of ring ∩ quadrilateral, exactly (holes lie inside their shell and apart).
    fn clipped_area(&self, corners: &[Coord<f64>; 4]) -> f64 {
        let (low, high) = crate::geometry::bounds(corners);
        if self.upper.x < low.x
            || self.lower.x > high.x
            || self.upper.y < low.y
            || self.lower.y > high.y
        {
            return 0.0;
        }
        let mut subject: Vec<Coord<f64>> = self.points.clone();
        subject.pop(); // the closing point
        let mut output = Vec::with_capacity(subject.len());
        for edge in 0..4 {
            let (a, b) = (corners[edge], corners[(edge + 1) % 4]);
            let side = |p: Coord<f64>| (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
            output.clear();
            for index in 0..subject.len() {
                let current = subject[index];
                let previous = subject[(index + subject.len() - 1) % subject.len()];
                let (s_current, s_previous) = (side(current), side(previous));
                if s_current >= 0.0 {
                    if s_previous < 0.0 {
                        output.push(crossing(previous, current, s_previous, s_current));
                    }
                    output.push(current);
                } else if s_previous >= 0.0 {
                    output.push(crossing(previous, current, s_previous, s_current));
                }
            }
            std::mem::swap(&mut subject, &mut output);
            if subject.is_empty() {
                return 0.0;
            }
        }
        let twice: f64 = (0..subject.len())
            .map(|i| {
                let (p, q) = (subject[i], subject[(i + 1) % subject.len()]);
                p.x * q.y - q.x * p.y
            })
            .sum();
        self.sign * 0.5 * twice.abs()
    }
}

/// Where the segment p → q crosses the line on which the side values are `sp` and `sq`.
fn crossing(p: Coord<f64>, q: Coord<f64>, sp: f64, sq: f64) -> Coord<f64> {
    let t = sp / (sp - sq);
    Coord {
        x: p.x + t * (q.x - p.x),
        y: p.y + t * (q.y - p.y),
    }
}

/// The four corners (counter-clockwise) of a strip that is one convex quadrilateral.
fn convex_quadrilateral(strip: &MultiPolygon<f64>) -> Option<[Coord<f64>; 4]> {
    let [polygon] = strip.0.as_slice() else {
        return None;
    };
    let ring = &polygon.exterior().0;
    if !polygon.interiors().is_empty() || ring.len() != 5 || ring[0] != ring[4] {
        return None;
    }
    let mut corners = [ring[0], ring[1], ring[2], ring[3]];
    let turn = |a: Coord<f64>, b: Coord<f64>, c: Coord<f64>| {
        (b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x)
    };
    let turns: Vec<f64> = (0..4)
        .map(|i| turn(corners[i], corners[(i + 1) % 4], corners[(i + 2) % 4]))
        .collect();
    if turns.iter().all(|&t| t < 0.0) {
        corners.reverse();
    } else if !turns.iter().all(|&t| t > 0.0) {
        return None;
    }
    Some(corners)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Rotate};

    #[test]
    fn clipping_a_tilted_strip_equals_the_exact_overlay() {
        // An L-shaped field with a hole, and tilted strips across it.
        let field = polygon!(
            exterior: [(x: 0.0, y: 0.0), (x: 100.0, y: 0.0), (x: 100.0, y: 40.0), (x: 40.0, y: 40.0), (x: 40.0, y: 100.0), (x: 0.0, y: 100.0)],
            interiors: [[(x: 10.0, y: 10.0), (x: 20.0, y: 10.0), (x: 20.0, y: 20.0), (x: 10.0, y: 20.0)]],
        );
        let region = MultiPolygon::new(vec![field]);
        let rings = Ring::all(&region);
        for (index, angle) in [0.0, 17.0, 45.0, 63.0, 90.0, 151.0].into_iter().enumerate() {
            let strip = polygon!(
                exterior: [(x: -20.0, y: 12.0 + 9.0 * index as f64), (x: 130.0, y: 12.0 + 9.0 * index as f64),
                           (x: 130.0, y: 18.0 + 9.0 * index as f64), (x: -20.0, y: 18.0 + 9.0 * index as f64)],
                interiors: [],
            )
            .rotate_around_point(angle, geo::Point::new(50.0, 50.0));
            let strip = MultiPolygon::new(vec![strip]);
            let corners = convex_quadrilateral(&strip).expect("a rectangle is convex");
            let ours: f64 = rings.iter().map(|ring| ring.clipped_area(&corners)).sum();
            let exact = strip.intersection(&region).unsigned_area();
            assert!(
                (ours - exact).abs() < 1e-6 * exact.max(1.0),
                "{angle}°: {ours} vs {exact}"
            );
        }
    }
}
