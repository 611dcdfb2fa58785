//! Where a vehicle can stand: the places a supply point may be chosen among
//! (docs/decisions/0016-supply-point.md).
//!
//! Without access features in the field file, a point P may stand when
//!
//! - P is outside every field's outer boundary (so in no field and in no hole: a hole is a
//!   pond, a building, a stand of trees, not a yard) and outside every obstacle, and at
//!   least m = [`MARGIN_M`] = 5 m from each of their boundaries: the truck and the drone's
//!   take-off stay off the crop and clear of what the obstacle is, with room for a few metres
//!   of GNSS error;
//! - the nearest field boundary is at most r = [`REACH_M`] = 200 m away: the crew walks to the
//!   fields and keeps them in sight, and the point stays on the farm's own ground rather than
//!   a neighbour's. The cost alone rarely wants more: a sum of distances to the route is
//!   smallest among the fields, so r only binds where fields lie far apart.
//!
//! With access features (roads, tracks, yards the operator drew), P may stand only on them:
//! within [`ON_LINE_M`] of a line or a yard's boundary, or inside a yard, and not inside a field's outer boundary or
//! an obstacle. No margin and no reach apply there: a road along a field edge is where the
//! truck parks, and the operator has said where vehicles go.
//!
//! [`StandingRule::settle`] moves a point to a nearby place that may stand (the projection the
//! pattern search moves through): out of a field or obstacle to its nearest boundary point
//! and on by m along the way out, back within r of the nearest field, or onto the nearest
//! point of an access feature.

use geo::{Coord, LineString};

use crate::geometry::ring_index::IndexedRing;
use crate::model::{AccessShape, Farm};

/// Distance a supply point keeps from field and obstacle boundaries, metres.
pub const MARGIN_M: f64 = 5.0;
/// Farthest a supply point may be from the nearest field boundary, metres.
pub const REACH_M: f64 = 200.0;
/// Distance from an access line within which a point is on it, metres.
pub const ON_LINE_M: f64 = 0.5;

/// Distance from a field's or obstacle's outline within which a point is on it, not inside,
/// metres.
const OUTLINE_M: f64 = 0.01;

/// Settling moves a point at most this many times before giving up on it (a point pushed out
/// of one field into another, and back).
const SETTLE_STEPS: usize = 6;

/// A ring with its index for point-in-ring tests and its corners for nearest points.
struct Ring {
    index: IndexedRing,
    points: Vec<Coord<f64>>,
}

impl Ring {
    fn new(ring: &LineString<f64>) -> Self {
        Self {
            index: IndexedRing::new(&ring.0),
            points: ring.0.clone(),
        }
    }
}

/// The nearest point of a polyline to `p`, its distance, and the direction of its segment.
fn nearest_on_polyline(p: Coord<f64>, points: &[Coord<f64>]) -> (Coord<f64>, f64, Coord<f64>) {
    let mut best = (points[0], f64::INFINITY, Coord { x: 1.0, y: 0.0 });
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let length_squared = dx * dx + dy * dy;
        let t = if length_squared > 0.0 {
            (((p.x - a.x) * dx + (p.y - a.y) * dy) / length_squared).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = Coord {
            x: a.x + t * dx,
            y: a.y + t * dy,
        };
        let distance = (p.x - q.x).hypot(p.y - q.y);
        if distance < best.1 {
            best = (q, distance, Coord { x: dx, y: dy });
        }
    }
    best
}

fn unit(v: Coord<f64>) -> Option<Coord<f64>> {
    let length = v.x.hypot(v.y);
    (length > 1e-9).then(|| Coord {
        x: v.x / length,
        y: v.y / length,
    })
}

/// The places a vehicle can stand on one farm.
pub struct StandingRule {
    /// Field outer boundaries and obstacle outlines: not to be stood in, nor within the margin.
    blocked: Vec<Ring>,
    /// How many of `blocked` are fields (they come first).
    fields: usize,
    /// Access lines (polylines) and yards (rings: the outer boundary first, then holes).
    lines: Vec<Vec<Coord<f64>>>,
    yards: Vec<Vec<Ring>>,
    /// m: distance kept from field and obstacle boundaries, metres (0 on access features).
    pub margin_m: f64,
    /// r: farthest from the nearest field boundary, metres (infinite on access features).
    pub reach_m: f64,
}

impl StandingRule {
    /// The rule of `farm`: on its access features when it has any, else [`MARGIN_M`] and
    /// [`REACH_M`] around its fields.
    pub fn new(farm: &Farm) -> Self {
        let mut blocked: Vec<Ring> = farm
            .fields
            .iter()
            .map(|field| Ring::new(field.polygon.exterior()))
            .collect();
        let fields = blocked.len();
        blocked.extend(
            farm.obstacles
                .iter()
                .map(|obstacle| Ring::new(obstacle.polygon.exterior())),
        );
        let mut lines = Vec::new();
        let mut yards = Vec::new();
        for access in &farm.access {
            match &access.shape {
                AccessShape::Line(line) => lines.push(line.0.clone()),
                AccessShape::Area(polygon) => yards.push(
                    crate::geometry::rings(polygon)
                        .map(|ring| Ring::new(&LineString::new(ring.to_vec())))
                        .collect(),
                ),
            }
        }
        let on_access = !farm.access.is_empty();
        Self {
            blocked,
            fields,
            lines,
            yards,
            margin_m: if on_access { 0.0 } else { MARGIN_M },
            reach_m: if on_access { f64::INFINITY } else { REACH_M },
        }
    }

    /// Whether points must stand on access features.
    pub fn on_access(&self) -> bool {
        !self.lines.is_empty() || !self.yards.is_empty()
    }

    /// The access lines, as polylines (for sampling candidates).
    pub fn access_lines(&self) -> &[Vec<Coord<f64>>] {
        &self.lines
    }

    /// The yards' outer boundaries (for sampling candidates).
    pub fn yard_boundaries(&self) -> impl Iterator<Item = &[Coord<f64>]> {
        self.yards.iter().map(|rings| rings[0].points.as_slice())
    }

    /// Distance from `p` to the nearest field boundary, metres.
    pub fn distance_to_fields_m(&self, p: Coord<f64>) -> f64 {
        self.blocked[..self.fields]
            .iter()
            .map(|ring| nearest_on_polyline(p, &ring.points).1)
            .fold(f64::INFINITY, f64::min)
    }

    /// The index of the field whose boundary is nearest `p` (the first of equals).
    pub fn nearest_field(&self, p: Coord<f64>) -> usize {
        self.blocked[..self.fields]
            .iter()
            .map(|ring| nearest_on_polyline(p, &ring.points).1)
            .enumerate()
            .fold((0, f64::INFINITY), |best, (index, distance)| {
                if distance < best.1 {
                    (index, distance)
                } else {
                    best
                }
            })
            .0
    }

    /// Number of fields.
    pub fn field_count(&self) -> usize {
        self.fields
    }

    /// Whether `p` lies in a field's outer boundary or an obstacle.
    /// Whether `p` lies inside a field or an obstacle. On an outline (within [`OUTLINE_M`],
    /// the digitising noise of a road snapped onto a field's edge) is not inside: there the
    /// truck parks beside the crop (decision 0016), and `why_not` reads it the same way.
    fn inside_blocked(&self, p: Coord<f64>) -> bool {
        self.blocked.iter().any(|ring| {
            ring.index.contains(p) && nearest_on_polyline(p, &ring.points).1 > OUTLINE_M
        })
    }

    fn in_yard(&self, p: Coord<f64>) -> bool {
        self.yards.iter().any(|rings| {
            rings[0].index.contains(p) && !rings[1..].iter().any(|hole| hole.index.contains(p))
        })
    }

    /// The nearest point of an access feature to `p` (`p` itself inside a yard).
    fn nearest_access(&self, p: Coord<f64>) -> Option<Coord<f64>> {
        if self.in_yard(p) {
            return Some(p);
        }
        self.lines
            .iter()
            .map(Vec::as_slice)
            .chain(
                self.yards
                    .iter()
                    .flat_map(|rings| rings.iter().map(|ring| ring.points.as_slice())),
            )
            .map(|points| nearest_on_polyline(p, points))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(q, _, _)| q)
    }

    /// Whether a vehicle can stand at `p` (the rules of the module's documentation).
    pub fn allows(&self, p: Coord<f64>) -> bool {
        if !(p.x.is_finite() && p.y.is_finite()) || self.inside_blocked(p) {
            return false;
        }
        if self.on_access() {
            return self.in_yard(p)
                || self
                    .lines
                    .iter()
                    .map(Vec::as_slice)
                    .chain(
                        self.yards
                            .iter()
                            .flat_map(|rings| rings.iter().map(|ring| ring.points.as_slice())),
                    )
                    .any(|points| nearest_on_polyline(p, points).1 <= ON_LINE_M);
        }
        self.blocked
            .iter()
            .all(|ring| nearest_on_polyline(p, &ring.points).1 >= self.margin_m)
            && self.distance_to_fields_m(p) <= self.reach_m
    }

    /// Why a vehicle cannot stand at `p`, in words for the operator: the field, hole or
    /// obstacle it lies in, off the file's access features, or how far from the fields it
    /// is; `None` when none of these holds. For a supply point the operator marked or gave:
    /// `auto` never chooses such a place, and the plan says so instead of refusing the
    /// operator's choice. The margin `auto` keeps from edges is not a reason here: a point
    /// on a field's edge or corner (seed 001's C1) is where a truck parks.
    pub fn why_not(&self, farm: &Farm, p: Coord<f64>) -> Option<String> {
        use geo::Contains;
        if !(p.x.is_finite() && p.y.is_finite()) {
            return Some("it is not a finite point".into());
        }
        let point = geo::Point::from(p);
        for (index, ring) in self.blocked.iter().enumerate() {
            // On the outline is not inside (the ring index counts its boundary in).
            if !ring.index.contains(p) || nearest_on_polyline(p, &ring.points).1 < 1e-6 {
                continue;
            }
            return Some(if index < self.fields {
                let field = &farm.fields[index];
                if field.polygon.contains(&point) {
                    format!("it lies inside field '{}', on the crop", field.name)
                } else {
                    format!("it lies in a hole of field '{}'", field.name)
                }
            } else {
                format!(
                    "it lies inside obstacle '{}'",
                    farm.obstacles[index - self.fields].name
                )
            });
        }
        if self.on_access() {
            return (!self.allows(p)).then(|| {
                "it is not on the field file's access features (roads, tracks, yards)".into()
            });
        }
        let distance = self.distance_to_fields_m(p);
        (distance > self.reach_m).then(|| {
            format!(
                "it is {distance:.0} m from the nearest field (a supply point stands within {:.0} m)",
                self.reach_m
            )
        })
    }

    /// A place near `p` where a vehicle can stand (the module's documentation says how it is
    /// found), or `None` when none is found there.
    pub fn settle(&self, p: Coord<f64>) -> Option<Coord<f64>> {
        if !(p.x.is_finite() && p.y.is_finite()) {
            return None;
        }
        if self.on_access() {
            return self.nearest_access(p).filter(|&q| self.allows(q));
        }
        let mut p = p;
        for _ in 0..SETTLE_STEPS {
            if self.allows(p) {
                return Some(p);
            }
            // The ring broken most: the one p is deepest inside, or nearest within the margin.
            let worst = self
                .blocked
                .iter()
                .map(|ring| {
                    let (q, distance, along) = nearest_on_polyline(p, &ring.points);
                    let inside = ring.index.contains(p);
                    let breach = if inside {
                        self.margin_m + distance
                    } else {
                        self.margin_m - distance
                    };
                    (breach, q, inside, along, ring)
                })
                .filter(|candidate| candidate.0 > 0.0)
                .max_by(|a, b| a.0.total_cmp(&b.0));
            p = match worst {
                Some((_, q, inside, along, ring)) => {
                    let away = if inside { q - p } else { p - q };
                    // On the boundary itself: leave along the segment's normal, on the side
                    // outside the ring.
                    let out = unit(away).or_else(|| {
                        let normal = unit(Coord {
                            x: along.y,
                            y: -along.x,
                        })?;
                        let probe = q + normal * 1e-3;
                        Some(if ring.index.contains(probe) {
                            -normal
                        } else {
                            normal
                        })
                    })?;
                    // A hair beyond the margin, so that the settled point passes `allows`.
                    q + out * (self.margin_m + 1e-3)
                }
                None => {
                    // Too far: back along the way to the nearest field boundary.
                    let (q, distance, _) = self.blocked[..self.fields]
                        .iter()
                        .map(|ring| nearest_on_polyline(p, &ring.points))
                        .min_by(|a, b| a.1.total_cmp(&b.1))?;
                    q + (p - q) * ((self.reach_m - 1e-3) / distance)
                }
            };
        }
        self.allows(p).then_some(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Access, CoordinateSystem, Field, Obstacle};
    use geo::Polygon;

    fn square(x0: f64, y0: f64, side: f64) -> LineString<f64> {
        LineString::from(vec![
            (x0, y0),
            (x0 + side, y0),
            (x0 + side, y0 + side),
            (x0, y0 + side),
            (x0, y0),
        ])
    }

    fn farm() -> Farm {
        Farm {
            source: "test".into(),
            coordinate_system: CoordinateSystem::Local,
            fields: vec![Field::new(
                "F",
                Polygon::new(square(0.0, 0.0, 100.0), vec![square(40.0, 40.0, 20.0)]),
            )],
            obstacles: vec![Obstacle {
                name: "shed".into(),
                polygon: Polygon::new(square(120.0, 0.0, 10.0), vec![]),
            }],
            markers: vec![],
            access: vec![],
            embedded_terrain: None,
            stated_swath_width_m: None,
            notes: Vec::new(),
        }
    }

    #[test]
    fn fields_holes_obstacles_margins_and_reach_are_kept() {
        let rule = StandingRule::new(&farm());
        let at = |x, y| rule.allows(Coord { x, y });
        assert!(!at(50.0, 50.0), "in the hole");
        assert!(!at(10.0, 10.0), "in the field");
        assert!(!at(-3.0, 50.0), "within the margin");
        assert!(at(-6.0, 50.0));
        assert!(!at(125.0, 5.0), "in the obstacle");
        assert!(!at(118.0, 5.0), "within the obstacle's margin");
        assert!(at(-199.0, 50.0));
        assert!(!at(-201.0, 50.0), "beyond the reach");
    }

    #[test]
    fn why_a_vehicle_cannot_stand_names_the_field_hole_obstacle_or_the_distance() {
        let farm = farm();
        let rule = StandingRule::new(&farm);
        let why = |x, y| rule.why_not(&farm, Coord { x, y });
        assert_eq!(why(-6.0, 50.0), None);
        assert_eq!(
            why(10.0, 10.0).unwrap(),
            "it lies inside field 'F', on the crop"
        );
        assert_eq!(why(50.0, 50.0).unwrap(), "it lies in a hole of field 'F'");
        assert_eq!(why(125.0, 5.0).unwrap(), "it lies inside obstacle 'shed'");
        // Within the margin auto keeps, and on the corner, is not a reason.
        assert_eq!(why(-3.0, 50.0), None);
        assert_eq!(why(0.0, 0.0), None);
        assert_eq!(why(118.0, 5.0), None);
        assert_eq!(
            why(-3000.0, 50.0).unwrap(),
            "it is 3000 m from the nearest field (a supply point stands within 200 m)"
        );
    }

    #[test]
    fn settling_leaves_fields_by_the_nearest_side_and_comes_back_within_reach() {
        let rule = StandingRule::new(&farm());
        let settled = rule.settle(Coord { x: 97.0, y: 30.0 }).unwrap();
        assert!(rule.allows(settled));
        assert!((settled.x - 105.0).abs() < 0.01 && (settled.y - 30.0).abs() < 1e-6);
        let hole = rule.settle(Coord { x: 50.0, y: 45.0 }).unwrap();
        assert!(rule.allows(hole), "{hole:?}");
        let on_edge = rule.settle(Coord { x: 0.0, y: 70.0 }).unwrap();
        assert!((on_edge.x + 5.0).abs() < 0.01, "{on_edge:?}");
        let far = rule.settle(Coord { x: -500.0, y: 50.0 }).unwrap();
        assert!((far.x + 200.0).abs() < 0.01, "{far:?}");
    }

    #[test]
    fn with_access_only_the_roads_and_yards_are_allowed() {
        let mut farm = farm();
        farm.access = vec![
            Access {
                name: "road".into(),
                shape: AccessShape::Line(LineString::from(vec![(-2.0, -50.0), (-2.0, 150.0)])),
            },
            Access {
                name: "yard".into(),
                shape: AccessShape::Area(Polygon::new(square(200.0, 200.0, 30.0), vec![])),
            },
        ];
        let rule = StandingRule::new(&farm);
        assert!(rule.allows(Coord { x: -2.0, y: 80.0 }), "on the road");
        assert!(!rule.allows(Coord { x: -10.0, y: 80.0 }), "beside it");
        assert!(rule.allows(Coord { x: 210.0, y: 220.0 }), "in the yard");
        let settled = rule.settle(Coord { x: 30.0, y: 80.0 }).unwrap();
        assert!((settled.x + 2.0).abs() < 1e-9 && (settled.y - 80.0).abs() < 1e-9);
        let yard = rule.settle(Coord { x: 260.0, y: 215.0 }).unwrap();
        assert!((yard.x - 230.0).abs() < 1e-9, "{yard:?}");
    }

    /// A road snapped onto a field's edge (as GIS tools draw one along a field) is where the
    /// truck parks: on it is allowed, inside the field beside it is not (fifth trial).
    #[test]
    fn a_road_along_a_field_edge_holds_the_supply_point() {
        let mut farm = farm();
        farm.access = vec![Access {
            name: "edge road".into(),
            shape: AccessShape::Line(LineString::from(vec![(0.0, -20.0), (0.0, 100.0)])),
        }];
        let rule = StandingRule::new(&farm);
        assert!(rule.allows(Coord { x: 0.0, y: 50.0 }), "on the edge");
        assert!(rule.allows(Coord { x: 0.0, y: 100.0 }), "on the corner");
        assert!(
            !rule.allows(Coord { x: 0.3, y: 50.0 }),
            "on the crop beside it"
        );
        let settled = rule.settle(Coord { x: 30.0, y: 60.0 }).unwrap();
        assert!(rule.allows(settled), "{settled:?}");
        assert!(settled.x.abs() < ON_LINE_M, "{settled:?}");
    }
}
