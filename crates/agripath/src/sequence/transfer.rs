//! The transfer model of seed 001 eq. (8) (contract decision 3, docs/contract.md), shared by every sequencer,
//! the route and the report.
//!
//! d = dist(P, Q) + H,  H = 0 if the segment PQ lies in the work area S, else 2h.
//!
//! "Lies in S" follows the seed's two-step test: ① if PQ crosses a boundary edge of S at an
//! interior point of both, it leaves S; ② otherwise PQ is cut at every point where it meets
//! the boundary, and the midpoint of each piece must lie in S (ray casting). S is one field's
//! closed polygon (its boundary counts as inside, its holes do not); a segment that enters an
//! obstacle leaves the work area too. dist is the 3D distance between the pass ends.

use geo::{Coord, Polygon};

use crate::coverage::drape::GroundPoint;
use crate::geometry::validate::point_in_ring;
use crate::geometry::{distance_to_segment, rings};
use crate::model::Farm;

/// A transfer leg between two pass ends.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Transfer {
    /// The pass end the leg leaves.
    pub from: GroundPoint,
    /// The pass end the leg reaches.
    pub to: GroundPoint,
    /// True when the leg leaves the field and climbs h.
    pub climbs: bool,
    /// 3D length plus 2h when it climbs, metres (eq. 8).
    pub cost_m: f64,
}

/// Distances below this are "on" a boundary, metres.
const ON_BOUNDARY_M: f64 = 1e-6;

/// Eq. (8)'s transfer cost over a farm's fields and obstacles, with climb height h.
pub struct TransferModel<'a> {
    farm: &'a Farm,
    safe_height_m: f64,
    /// Each field's bounding box: a segment with an end outside it is not in that field.
    field_boxes: Vec<Bounds>,
    /// Fields that are convex, without holes and clear of obstacles: any segment between two
    /// of their points lies in them, so no geometric test is needed.
    simple_fields: Vec<bool>,
}

struct Bounds {
    min: Coord<f64>,
    max: Coord<f64>,
}

impl Bounds {
    fn holds(&self, point: Coord<f64>) -> bool {
        point.x >= self.min.x - ON_BOUNDARY_M
            && point.x <= self.max.x + ON_BOUNDARY_M
            && point.y >= self.min.y - ON_BOUNDARY_M
            && point.y <= self.max.y + ON_BOUNDARY_M
    }
}

impl<'a> TransferModel<'a> {
    /// The model over `farm`'s fields and obstacles; legs that leave the work area climb
    /// `safe_height_m` (h, metres).
    pub fn new(farm: &'a Farm, safe_height_m: f64) -> Self {
        let field_boxes = farm
            .fields
            .iter()
            .map(|field| {
                let rect =
                    geo::BoundingRect::bounding_rect(&field.polygon).expect("a field has a box");
                Bounds {
                    min: rect.min(),
                    max: rect.max(),
                }
            })
            .collect::<Vec<Bounds>>();
        let simple_fields = farm
            .fields
            .iter()
            .zip(&field_boxes)
            .map(|(field, bounds)| {
                field.polygon.interiors().is_empty()
                    && is_convex(&field.polygon.exterior().0)
                    && !farm.obstacles.iter().any(|obstacle| {
                        obstacle
                            .polygon
                            .exterior()
                            .0
                            .iter()
                            .any(|point| bounds.holds(*point))
                            || geo::Intersects::intersects(&obstacle.polygon, &field.polygon)
                    })
            })
            .collect();
        Self {
            farm,
            safe_height_m,
            field_boxes,
            simple_fields,
        }
    }

    /// The leg from `from` to `to`. Both ends are flown at spray height over the ground, so the
    /// 3D length uses the ground heights.
    pub fn transfer(&self, from: GroundPoint, to: GroundPoint) -> Transfer {
        let length = ((to.x - from.x).powi(2)
            + (to.y - from.y).powi(2)
            + (to.ground_m - from.ground_m).powi(2))
        .sqrt();
        let climbs = !self.inside_work_area(
            Coord {
                x: from.x,
                y: from.y,
            },
            Coord { x: to.x, y: to.y },
        );
        Transfer {
            from,
            to,
            climbs,
            cost_m: length
                + if climbs {
                    2.0 * self.safe_height_m
                } else {
                    0.0
                },
        }
    }

    /// Eq. (8)'s cost alone.
    pub fn cost(&self, from: GroundPoint, to: GroundPoint) -> f64 {
        self.transfer(from, to).cost_m
    }

    /// Eq. (8)'s cost between two pass ends known to lie in fields `from_field` and
    /// `to_field`: a segment lies in one field's polygon only if both ends do, so ends in
    /// different fields always climb and only the common field needs the geometric test.
    pub fn cost_between_fields(
        &self,
        from: GroundPoint,
        to: GroundPoint,
        from_field: usize,
        to_field: usize,
    ) -> f64 {
        let length = ((to.x - from.x).powi(2)
            + (to.y - from.y).powi(2)
            + (to.ground_m - from.ground_m).powi(2))
        .sqrt();
        let (a, b) = (
            Coord {
                x: from.x,
                y: from.y,
            },
            Coord { x: to.x, y: to.y },
        );
        let inside = from_field == to_field
            && (self.simple_fields.get(from_field) == Some(&true)
                || self
                    .farm
                    .fields
                    .get(from_field)
                    .is_some_and(|field| segment_in_closed_polygon(a, b, &field.polygon)))
            && !self
                .farm
                .obstacles
                .iter()
                .any(|obstacle| segment_enters_polygon(a, b, &obstacle.polygon));
        length
            + if inside {
                0.0
            } else {
                2.0 * self.safe_height_m
            }
    }

    fn inside_work_area(&self, from: Coord<f64>, to: Coord<f64>) -> bool {
        let inside_a_field =
            self.farm
                .fields
                .iter()
                .zip(&self.field_boxes)
                .any(|(field, bounds)| {
                    bounds.holds(from)
                        && bounds.holds(to)
                        && segment_in_closed_polygon(from, to, &field.polygon)
                });
        inside_a_field
            && !self
                .farm
                .obstacles
                .iter()
                .any(|obstacle| segment_enters_polygon(from, to, &obstacle.polygon))
    }
}

/// A closed ring whose turns all go the same way (collinear vertices allowed).
fn is_convex(ring: &[Coord<f64>]) -> bool {
    let count = ring.len() - 1;
    let mut sign = 0.0f64;
    for index in 0..count {
        let turn = cross(
            ring[index],
            ring[(index + 1) % count],
            ring[(index + 2) % count],
        );
        if turn.abs() > 1e-12 {
            if sign != 0.0 && turn.signum() != sign {
                return false;
            }
            sign = turn.signum();
        }
    }
    true
}

fn cross(origin: Coord<f64>, a: Coord<f64>, b: Coord<f64>) -> f64 {
    (a.x - origin.x) * (b.y - origin.y) - (a.y - origin.y) * (b.x - origin.x)
}

fn on_boundary(point: Coord<f64>, polygon: &Polygon<f64>) -> bool {
    rings(polygon).any(|ring| {
        ring.windows(2)
            .any(|edge| within_boundary_distance(point, edge[0], edge[1]))
    })
}

/// Margin of the box tests below: a point within [`ON_BOUNDARY_M`] of a segment lies in the
/// segment's box grown by it; twice that leaves room for rounding.
const BOX_MARGIN_M: f64 = 2.0 * ON_BOUNDARY_M;

/// Whether the boxes of segments `a`-`b` and `p`-`q`, grown by [`BOX_MARGIN_M`], meet: when
/// they do not, the segments neither cross nor come within [`ON_BOUNDARY_M`] of each other.
/// Most edges of a field are far from a given transfer; this spares them the distances
/// (eq. 8's test is most of the time to build an ordering problem's cost matrix).
fn boxes_meet(a: Coord<f64>, b: Coord<f64>, p: Coord<f64>, q: Coord<f64>) -> bool {
    a.x.max(b.x) + BOX_MARGIN_M >= p.x.min(q.x)
        && p.x.max(q.x) + BOX_MARGIN_M >= a.x.min(b.x)
        && a.y.max(b.y) + BOX_MARGIN_M >= p.y.min(q.y)
        && p.y.max(q.y) + BOX_MARGIN_M >= a.y.min(b.y)
}

/// `distance_to_segment(point, p, q) <= ON_BOUNDARY_M`, with the box test first (the same
/// answer: a point outside the grown box is farther than that from the segment).
fn within_boundary_distance(point: Coord<f64>, p: Coord<f64>, q: Coord<f64>) -> bool {
    boxes_meet(point, point, p, q) && distance_to_segment(point, p, q) <= ON_BOUNDARY_M
}

/// Strictly inside the polygon (outside its holes), boundary excluded.
fn strictly_inside(point: Coord<f64>, polygon: &Polygon<f64>) -> bool {
    !on_boundary(point, polygon)
        && point_in_ring(point, &polygon.exterior().0)
        && polygon
            .interiors()
            .iter()
            .all(|hole| !point_in_ring(point, &hole.0))
}

/// Where the segment meets the polygon's boundary, as parameters along it; `None` when it
/// crosses an edge at a point interior to both (step ①).
fn boundary_cuts(from: Coord<f64>, to: Coord<f64>, polygon: &Polygon<f64>) -> Option<Vec<f64>> {
    let direction = Coord {
        x: to.x - from.x,
        y: to.y - from.y,
    };
    let length_squared = direction.x * direction.x + direction.y * direction.y;
    let parameter = |point: Coord<f64>| {
        if length_squared == 0.0 {
            0.0
        } else {
            (((point.x - from.x) * direction.x + (point.y - from.y) * direction.y) / length_squared)
                .clamp(0.0, 1.0)
        }
    };
    let mut cuts = vec![0.0, 1.0];
    for ring in rings(polygon) {
        for edge in ring.windows(2) {
            let (p, q) = (edge[0], edge[1]);
            if !boxes_meet(from, to, p, q) {
                // Neither a crossing nor a touch: nothing to cut.
                continue;
            }
            let d1 = cross(p, q, from);
            let d2 = cross(p, q, to);
            let d3 = cross(from, to, p);
            let d4 = cross(from, to, q);
            let scale = (q.x - p.x)
                .hypot(q.y - p.y)
                .max(length_squared.sqrt())
                .max(1.0);
            let tolerance = 1e-9 * scale * scale;
            let straddles = |a: f64, b: f64| {
                (a > tolerance && b < -tolerance) || (a < -tolerance && b > tolerance)
            };
            if straddles(d1, d2) && straddles(d3, d4) {
                return None;
            }
            // Touches: an end of one on the other (including collinear overlaps).
            for point in [p, q] {
                if within_boundary_distance(point, from, to) {
                    cuts.push(parameter(point));
                }
            }
            for (point, t) in [(from, 0.0), (to, 1.0)] {
                if within_boundary_distance(point, p, q) {
                    cuts.push(t);
                }
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    Some(cuts)
}

fn at(from: Coord<f64>, to: Coord<f64>, t: f64) -> Coord<f64> {
    Coord {
        x: from.x + t * (to.x - from.x),
        y: from.y + t * (to.y - from.y),
    }
}

/// The segment lies in the closed polygon (boundary counts as inside, holes do not): step ②.
pub fn segment_in_closed_polygon(from: Coord<f64>, to: Coord<f64>, polygon: &Polygon<f64>) -> bool {
    let Some(cuts) = boundary_cuts(from, to, polygon) else {
        return false;
    };
    cuts.windows(2).all(|pair| {
        let middle = at(from, to, (pair[0] + pair[1]) / 2.0);
        on_boundary(middle, polygon) || strictly_inside(middle, polygon)
    }) && [from, to]
        .iter()
        .all(|&end| on_boundary(end, polygon) || strictly_inside(end, polygon))
}

/// The segment passes through the polygon's interior (flying along its edge does not count).
pub fn segment_enters_polygon(from: Coord<f64>, to: Coord<f64>, polygon: &Polygon<f64>) -> bool {
    let Some(cuts) = boundary_cuts(from, to, polygon) else {
        return true;
    };
    cuts.windows(2)
        .any(|pair| strictly_inside(at(from, to, (pair[0] + pair[1]) / 2.0), polygon))
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::LineString;

    fn notched() -> Polygon<f64> {
        // A U shape: the notch x 40..60, y 50..100 is outside.
        Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (100.0, 0.0),
                (100.0, 100.0),
                (60.0, 100.0),
                (60.0, 50.0),
                (40.0, 50.0),
                (40.0, 100.0),
                (0.0, 100.0),
                (0.0, 0.0),
            ]),
            vec![LineString::from(vec![
                (70.0, 10.0),
                (90.0, 10.0),
                (90.0, 30.0),
                (70.0, 30.0),
                (70.0, 10.0),
            ])],
        )
    }

    fn c(x: f64, y: f64) -> Coord<f64> {
        Coord { x, y }
    }

    #[test]
    fn inside_outside_boundary_and_holes() {
        let polygon = notched();
        assert!(segment_in_closed_polygon(
            c(10.0, 10.0),
            c(30.0, 40.0),
            &polygon
        ));
        // Across the notch: leaves.
        assert!(!segment_in_closed_polygon(
            c(20.0, 80.0),
            c(80.0, 80.0),
            &polygon
        ));
        // Along the bottom of the notch (a boundary edge) and along the outer edge: inside.
        assert!(segment_in_closed_polygon(
            c(40.0, 50.0),
            c(60.0, 50.0),
            &polygon
        ));
        assert!(segment_in_closed_polygon(
            c(0.0, 0.0),
            c(0.0, 100.0),
            &polygon
        ));
        // From a corner of the notch to another corner across it: outside (its midpoint is).
        assert!(!segment_in_closed_polygon(
            c(40.0, 100.0),
            c(60.0, 100.0),
            &polygon
        ));
        // Through the hole: leaves; along the hole's edge: inside.
        assert!(!segment_in_closed_polygon(
            c(60.0, 20.0),
            c(95.0, 20.0),
            &polygon
        ));
        assert!(segment_in_closed_polygon(
            c(70.0, 10.0),
            c(90.0, 10.0),
            &polygon
        ));
        // Ends outside.
        assert!(!segment_in_closed_polygon(
            c(-5.0, 10.0),
            c(10.0, 10.0),
            &polygon
        ));
        // Through a vertex of the notch without leaving: (40, 50) touched from inside.
        assert!(segment_in_closed_polygon(
            c(30.0, 60.0),
            c(50.0, 40.0),
            &polygon
        ));
        assert!(!segment_in_closed_polygon(
            c(30.0, 40.0),
            c(50.0, 60.0),
            &polygon
        ));
    }

    proptest::proptest! {
        /// Eq. (8)'s two tests (with their box shortcuts) agree with `geo`'s DE-9IM relate
        /// (robust predicates), an outside oracle: a segment lies in the closed polygon when
        /// the polygon covers it, and enters it when their interiors meet. Ends on a 5 m grid
        /// over the notched field with a hole, so that most segments touch vertices, run
        /// along edges or end on the boundary, where the shortcuts could go wrong.
        #[test]
        fn segment_tests_agree_with_geo_relate(
            ends in proptest::collection::vec(-2i32..=22, 4),
            jitter in proptest::collection::vec(-1.0f64..1.0, 4),
            snapped in proptest::bool::ANY,
        ) {
            use geo::algorithm::relate::Relate;
            use geo::coordinate_position::CoordPos;
            use geo::dimensions::Dimensions;
            let shift = |k: usize| if snapped { 0.0 } else { jitter[k] };
            let (a, b) = (
                c(5.0 * f64::from(ends[0]) + shift(0), 5.0 * f64::from(ends[1]) + shift(1)),
                c(5.0 * f64::from(ends[2]) + shift(2), 5.0 * f64::from(ends[3]) + shift(3)),
            );
            proptest::prop_assume!(a != b);
            let polygon = notched();
            let matrix = polygon.relate(&geo::Line::new(a, b));
            proptest::prop_assert_eq!(
                segment_in_closed_polygon(a, b, &polygon),
                matrix.is_covers(),
                "in {:?} {:?}", a, b
            );
            proptest::prop_assert_eq!(
                segment_enters_polygon(a, b, &polygon),
                matrix.get(CoordPos::Inside, CoordPos::Inside) != Dimensions::Empty,
                "enters {:?} {:?}", a, b
            );
        }
    }

    #[test]
    fn obstacles_are_entered_or_skirted() {
        let square = Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (10.0, 0.0),
                (10.0, 10.0),
                (0.0, 10.0),
                (0.0, 0.0),
            ]),
            vec![],
        );
        assert!(segment_enters_polygon(c(-5.0, 5.0), c(15.0, 5.0), &square));
        assert!(!segment_enters_polygon(c(-5.0, 0.0), c(15.0, 0.0), &square));
        assert!(!segment_enters_polygon(
            c(-5.0, -5.0),
            c(15.0, -5.0),
            &square
        ));
        assert!(segment_enters_polygon(c(0.0, 0.0), c(10.0, 10.0), &square));
    }
}
