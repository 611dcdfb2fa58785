//! The farm's fields, holes and obstacles as the preflight asks about them: a sample every
//! metre of every leg, on farms of up to 10,000 fields and fields of up to 50,000 vertices.
//! Each ring is indexed by bands ([`IndexedRing`]) and the rings by a grid of cells over the
//! farm, so a query looks at the few rings near the point.

use geo::Coord;

use super::SLACK_M;
use crate::geometry::ring_index::IndexedRing;
use crate::model::Farm;

/// A field: its boundary and its holes.
struct FieldRings {
    boundary: IndexedRing,
    holes: Vec<IndexedRing>,
}

/// Which items' boxes (grown by a reach) meet each cell of a grid.
struct Cells {
    origin: Coord<f64>,
    cell_m: f64,
    columns: usize,
    rows: usize,
    items: Vec<Vec<u32>>,
}

impl Cells {
    fn new(boxes: &[(Coord<f64>, Coord<f64>)], reach_m: f64) -> Self {
        let mut low = Coord {
            x: f64::INFINITY,
            y: f64::INFINITY,
        };
        let mut high = Coord {
            x: f64::NEG_INFINITY,
            y: f64::NEG_INFINITY,
        };
        for (a, b) in boxes {
            low.x = low.x.min(a.x - reach_m);
            low.y = low.y.min(a.y - reach_m);
            high.x = high.x.max(b.x + reach_m);
            high.y = high.y.max(b.y + reach_m);
        }
        if boxes.is_empty() {
            return Self {
                origin: Coord { x: 0.0, y: 0.0 },
                cell_m: 1.0,
                columns: 0,
                rows: 0,
                items: Vec::new(),
            };
        }
        // About one item a cell, at most 512 × 512 cells.
        let side = (boxes.len() as f64).sqrt().ceil().clamp(1.0, 512.0);
        let cell_m = ((high.x - low.x).max(high.y - low.y) / side).max(1e-6);
        let columns = ((high.x - low.x) / cell_m).ceil().max(1.0) as usize;
        let rows = ((high.y - low.y) / cell_m).ceil().max(1.0) as usize;
        let mut items = vec![Vec::new(); columns * rows];
        for (index, (a, b)) in boxes.iter().enumerate() {
            let column =
                |x: f64| (((x - low.x) / cell_m).floor().max(0.0) as usize).min(columns - 1);
            let row = |y: f64| (((y - low.y) / cell_m).floor().max(0.0) as usize).min(rows - 1);
            for r in row(a.y - reach_m)..=row(b.y + reach_m) {
                for c in column(a.x - reach_m)..=column(b.x + reach_m) {
                    items[r * columns + c].push(index as u32);
                }
            }
        }
        Self {
            origin: low,
            cell_m,
            columns,
            rows,
            items,
        }
    }

    /// The items whose grown box may hold `p`.
    fn near(&self, p: Coord<f64>) -> &[u32] {
        let column = ((p.x - self.origin.x) / self.cell_m).floor();
        let row = ((p.y - self.origin.y) / self.cell_m).floor();
        if column < 0.0 || row < 0.0 || column >= self.columns as f64 || row >= self.rows as f64 {
            return &[];
        }
        &self.items[row as usize * self.columns + column as usize]
    }
}

/// Whether `p` enters `ring` grown by `margin_m`: inside it (by more than the slack of the
/// files' rounding when there is no margin), or outside within the margin.
fn enters(ring: &IndexedRing, p: Coord<f64>, margin_m: f64) -> bool {
    if ring.contains(p) {
        margin_m > 0.0 || !ring.near(p, SLACK_M)
    } else {
        margin_m > SLACK_M && ring.near(p, margin_m - SLACK_M)
    }
}

/// Where, as a fraction of `a`–`b`, that segment crosses `p`–`q` (`None` when they do not
/// cross, or run parallel).
fn crossing(a: Coord<f64>, b: Coord<f64>, p: Coord<f64>, q: Coord<f64>) -> Option<f64> {
    let (r, s) = (
        Coord {
            x: b.x - a.x,
            y: b.y - a.y,
        },
        Coord {
            x: q.x - p.x,
            y: q.y - p.y,
        },
    );
    let denominator = r.x * s.y - r.y * s.x;
    if denominator == 0.0 {
        return None;
    }
    let (dx, dy) = (p.x - a.x, p.y - a.y);
    let t = (dx * s.y - dy * s.x) / denominator;
    let u = (dx * r.y - dy * r.x) / denominator;
    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some(t)
}

/// The fields, holes and obstacles of a farm, indexed.
pub struct Zones {
    fields: Vec<FieldRings>,
    obstacles: Vec<IndexedRing>,
    field_cells: Cells,
    obstacle_cells: Cells,
    obstacle_margin_m: f64,
}

impl Zones {
    pub fn new(farm: &Farm, obstacle_margin_m: f64) -> Self {
        let reach = obstacle_margin_m.max(0.0) + SLACK_M;
        let field_boxes: Vec<_> = farm
            .fields
            .iter()
            .map(|field| crate::geometry::bounds(&field.polygon.exterior().0))
            .collect();
        let obstacle_boxes: Vec<_> = farm
            .obstacles
            .iter()
            .map(|obstacle| crate::geometry::bounds(&obstacle.polygon.exterior().0))
            .collect();
        Self {
            fields: farm
                .fields
                .iter()
                .map(|field| FieldRings {
                    boundary: IndexedRing::new(&field.polygon.exterior().0),
                    holes: field
                        .polygon
                        .interiors()
                        .iter()
                        .map(|hole| IndexedRing::new(&hole.0))
                        .collect(),
                })
                .collect(),
            obstacles: farm
                .obstacles
                .iter()
                .map(|obstacle| IndexedRing::new(&obstacle.polygon.exterior().0))
                .collect(),
            field_cells: Cells::new(&field_boxes, reach),
            obstacle_cells: Cells::new(&obstacle_boxes, reach),
            obstacle_margin_m,
        }
    }

    fn enters_obstacle(&self, p: Coord<f64>, margin_m: f64) -> bool {
        self.obstacle_cells
            .near(p)
            .iter()
            .any(|&k| enters(&self.obstacles[k as usize], p, margin_m))
    }

    /// Whether `p` is inside an obstacle of the inputs (beyond the files' rounding): no flight
    /// goes there at any height, since the plan's geofence excludes obstacles at every
    /// altitude. Asked of the inputs, so a file whose fence was edited away is still held to it.
    pub fn in_obstacle(&self, p: Coord<f64>) -> bool {
        self.enters_obstacle(p, 0.0)
    }

    /// Whether spraying at `p` is in a hole or an obstacle (grown by the obstacle margin).
    /// A hole of one field that is crop of another (a field drawn inside the hole, or one
    /// overlapping it under `--allow-overlap`) is not a hole there.
    pub fn no_go(&self, p: Coord<f64>) -> bool {
        let near = self.field_cells.near(p);
        let in_hole_of = |k: &u32| {
            let field = &self.fields[*k as usize];
            field.boundary.contains(p) && field.holes.iter().any(|hole| enters(hole, p, 0.0))
        };
        // On a field's edge within the files' rounding counts as on it: a field drawn in
        // another's hole is sprayed to its edge, which the written file may put a few
        // millimetres outside it.
        let on_crop_of = |k: &u32| {
            let field = &self.fields[*k as usize];
            (field.boundary.contains(p) || field.boundary.near(p, SLACK_M))
                && !field.holes.iter().any(|hole| enters(hole, p, 0.0))
        };
        (near.iter().any(in_hole_of) && !near.iter().any(on_crop_of))
            || self.enters_obstacle(p, self.obstacle_margin_m)
    }

    /// A place where the straight leg between `ends` enters an obstacle (grown by the obstacle
    /// margin when `spraying`), beyond the files' rounding, tested against the obstacle's
    /// edges rather than at samples: the leg's nearest approach to a grown obstacle is at one
    /// of its ends, a crossing of an edge, or the foot of a corner on it, and a stretch inside
    /// one lies between two crossings, so those places and the middles between them are all
    /// that need asking.
    ///
    /// Also says what the leg does there, for the failure line.
    pub fn leg_through_obstacle(
        &self,
        ends: [Coord<f64>; 2],
        spraying: bool,
    ) -> Option<(Coord<f64>, &'static str)> {
        let what = if spraying {
            "spraying inside an obstacle"
        } else {
            "flying through an obstacle"
        };
        let margin_m = if spraying {
            self.obstacle_margin_m
        } else {
            0.0
        };
        let [a, b] = ends;
        let reach = margin_m.max(0.0) + SLACK_M;
        let (low, high) = (
            Coord {
                x: a.x.min(b.x) - reach,
                y: a.y.min(b.y) - reach,
            },
            Coord {
                x: a.x.max(b.x) + reach,
                y: a.y.max(b.y) + reach,
            },
        );
        let at = |t: f64| Coord {
            x: a.x + t * (b.x - a.x),
            y: a.y + t * (b.y - a.y),
        };
        for ring in &self.obstacles {
            let (ring_low, ring_high) = ring.bounds();
            if ring_high.x < low.x
                || ring_low.x > high.x
                || ring_high.y < low.y
                || ring_low.y > high.y
            {
                continue;
            }
            let mut places = vec![0.0, 1.0];
            for edge in ring.points().windows(2) {
                places.push(crate::geometry::nearest_fraction_on_segment(edge[0], a, b));
                if let Some(t) = crossing(a, b, edge[0], edge[1]) {
                    places.push(t);
                }
            }
            places.sort_by(f64::total_cmp);
            let middles: Vec<f64> = places
                .windows(2)
                .map(|pair| (pair[0] + pair[1]) / 2.0)
                .collect();
            if let Some(p) = places
                .into_iter()
                .chain(middles)
                .map(at)
                .find(|&p| enters(ring, p, margin_m))
            {
                return Some((p, what));
            }
        }
        None
    }

    /// Whether `p` is over a field (its boundary included), not over a hole or an obstacle.
    pub fn over_field(&self, p: Coord<f64>) -> bool {
        self.field_cells.near(p).iter().any(|&k| {
            let field = &self.fields[k as usize];
            (field.boundary.contains(p) || field.boundary.near(p, SLACK_M))
                && !field.holes.iter().any(|hole| enters(hole, p, 0.0))
        }) && !self.enters_obstacle(p, 0.0)
    }
}

/// A geofence polygon as the file gives it, indexed.
pub struct Fence {
    pub inclusion: bool,
    ring: IndexedRing,
}

impl Fence {
    pub fn new(inclusion: bool, ring: &[Coord<f64>]) -> Self {
        Self {
            inclusion,
            ring: IndexedRing::new(ring),
        }
    }

    /// Whether `p` breaks this polygon: outside an inclusion, inside an exclusion (beyond the
    /// files' rounding).
    pub fn breached_at(&self, p: Coord<f64>) -> bool {
        self.ring.contains(p) != self.inclusion && !self.ring.near(p, SLACK_M)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::field::Field;
    use geo::{LineString, Polygon};

    fn ring(corners: &[(f64, f64)]) -> LineString<f64> {
        LineString::from(corners.to_vec())
    }

    /// The review of decision 0037: a pole thinner than the 1 m sampling step, crossed by a
    /// transit at any offset, is met; a leg that passes it is not.
    #[test]
    fn a_leg_is_tested_against_a_thin_poles_edges() {
        let field = Polygon::new(
            ring(&[(0.0, 0.0), (100.0, 0.0), (100.0, 100.0), (0.0, 100.0)]),
            vec![],
        );
        let mut farm = Farm::local("pole.geojson", vec![Field::new("A", field)]);
        let step = std::f64::consts::TAU / 16.0;
        let corner = 0.25 / (step / 2.0).cos();
        let pole: Vec<(f64, f64)> = (0..16)
            .map(|k| {
                let angle = step * k as f64;
                (50.0 + corner * angle.cos(), 50.0 + corner * angle.sin())
            })
            .collect();
        farm.obstacles.push(crate::model::Obstacle {
            name: "pole".into(),
            polygon: Polygon::new(ring(&pole), vec![]),
        });
        let zones = Zones::new(&farm, 1.0);
        let leg = |offset: f64| {
            [
                Coord {
                    x: 40.3,
                    y: 50.0 + offset,
                },
                Coord {
                    x: 59.7,
                    y: 50.0 + offset,
                },
            ]
        };
        for offset in [0.0, 0.1, 0.2, 0.23] {
            let (_, what) = zones.leg_through_obstacle(leg(offset), false).expect("met");
            assert_eq!(what, "flying through an obstacle");
        }
        assert!(zones.leg_through_obstacle(leg(0.3), false).is_none());
        // Spraying, the pole is grown by the 1 m margin.
        assert!(zones.leg_through_obstacle(leg(1.2), true).is_some());
        assert!(zones.leg_through_obstacle(leg(1.3), true).is_none());
        // A leg that ends before the pole.
        let short = [Coord { x: 40.0, y: 50.0 }, Coord { x: 49.7, y: 50.0 }];
        assert!(zones.leg_through_obstacle(short, false).is_none());
    }

    /// Trial 9: a field drawn inside another's hole is sprayed to its edge, and the written
    /// file may put that edge a few millimetres outside it, in the hole.
    #[test]
    fn a_field_in_anothers_hole_is_crop_to_its_edge() {
        let outer = Polygon::new(
            ring(&[(0.0, 0.0), (200.0, 0.0), (200.0, 200.0), (0.0, 200.0)]),
            vec![ring(&[
                (50.0, 50.0),
                (150.0, 50.0),
                (150.0, 150.0),
                (50.0, 150.0),
            ])],
        );
        let island = Polygon::new(
            ring(&[(70.0, 70.0), (130.0, 70.0), (130.0, 130.0), (70.0, 130.0)]),
            vec![],
        );
        let farm = Farm::local(
            "island.geojson",
            vec![Field::new("Outer", outer), Field::new("Island", island)],
        );
        let zones = Zones::new(&farm, 0.0);
        // On the island's edge, a few millimetres out into the hole, and inside it.
        for p in [
            (70.0, 100.0),
            (69.995, 100.0),
            (100.0, 130.004),
            (100.0, 100.0),
        ] {
            assert!(!zones.no_go(Coord { x: p.0, y: p.1 }), "{p:?}");
        }
        // The hole's ground round the island is still a hole.
        for p in [(60.0, 100.0), (69.9, 100.0), (100.0, 140.0)] {
            assert!(zones.no_go(Coord { x: p.0, y: p.1 }), "{p:?}");
        }
    }
}
