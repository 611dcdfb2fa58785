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
