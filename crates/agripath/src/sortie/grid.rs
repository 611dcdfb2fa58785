//! Seed 003 §1.1: the grid model of a field and the motion rule that flies it.
//!
//! The field is cut into square cells of swath width over its bounding box; a cell is
//! workable (ω = 1) when it lies wholly inside the field and touches no obstacle, else ω = 0
//! ("boundary and obstacle cells cannot be entered"). Each cell keeps its centre (x, y) and
//! the terrain height z there. The drone starts on the workable cell nearest the supply point,
//! flying along the rows (+y), and at every step:
//!
//! 1. the cell ahead, if its weight is not 0, gains U1;
//! 2. the cell behind on the left, if not 0, gains U2 > U1;
//! 3. the cell behind on the right likewise;
//! 4. the cell behind is set to 0 (every cell flown over is);
//!
//! then it moves to the heaviest of the cells ahead, left and right (ties in that order). The
//! rule flies a boustrophedon along the rows, turning at the headland; it stops when no
//! neighbour can be entered. U1 and U2 are not given (contract decision 4, docs/contract.md): U1 = 1, U2 = 2.
//!
//! Rows run along y (seed 003's crop rows). Moves along a row spray; moves across rows are
//! headland turns (spray off). As the seed's rule does, a column entered sideways below its
//! top (a staircase edge such as the strip's diagonal) leaves that top cell unflown: the
//! count is returned with the route, not hidden.

use geo::{Contains, Coord, Intersects, Polygon, Rect};

use super::route::{RoutePoint, Segment, Speeds, WorkRoute};
use crate::error::Fault;
use crate::model::Farm;
use crate::terrain::Terrain;

/// U1: the reward for the cell ahead.
pub const FORWARD_REWARD: f64 = 1.0;
/// U2: the reward for the cells behind on either side (U2 > U1).
pub const SIDE_REWARD: f64 = 2.0;

/// The cells of one field.
#[derive(Debug, Clone)]
pub struct Grid {
    /// Side of a square cell, metres.
    pub cell_m: f64,
    /// Number of cells along x.
    pub columns: usize,
    /// Number of cells along y.
    pub rows: usize,
    /// The south-west corner of the grid (the field's bounding box), plan metres.
    pub origin: Coord<f64>,
    /// Row-major (row = y index): whether the cell can be worked.
    pub workable: Vec<bool>,
    /// Terrain height at each cell centre (NaN where not workable).
    pub heights: Vec<f64>,
}

/// The route flown by the motion rule over a grid.
#[derive(Debug, Clone)]
pub struct MotionRoute {
    /// The grid the route was flown over.
    pub grid: Grid,
    /// Cell indices in flight order.
    pub cells: Vec<usize>,
    /// The route through the visited cell centres.
    pub route: WorkRoute,
    /// Workable cells the rule never reached.
    pub unvisited: usize,
}

impl Grid {
    /// The grid of field `field` of `farm` with cells of `cell_m`.
    pub fn new(
        farm: &Farm,
        field: usize,
        cell_m: f64,
        terrain: &dyn Terrain,
    ) -> Result<Self, Fault> {
        let polygon: &Polygon<f64> = &farm.fields[field].polygon;
        let bounds = geo::BoundingRect::bounding_rect(polygon).ok_or(Fault::NoFields)?;
        let columns = ((bounds.width() / cell_m) - 1e-9).ceil().max(1.0) as usize;
        let rows = ((bounds.height() / cell_m) - 1e-9).ceil().max(1.0) as usize;
        if columns.saturating_mul(rows) > crate::limits::MAX_SORTIE_GRID_CELLS {
            return Err(Fault::TooLarge(format!(
                "a grid of {columns} × {rows} cells of {cell_m} m"
            )));
        }
        let origin = bounds.min();
        let mut workable = vec![false; columns * rows];
        let mut heights = vec![f64::NAN; columns * rows];
        for row in 0..rows {
            for column in 0..columns {
                let min = Coord {
                    x: origin.x + column as f64 * cell_m,
                    y: origin.y + row as f64 * cell_m,
                };
                let cell = Rect::new(
                    min,
                    Coord {
                        x: min.x + cell_m,
                        y: min.y + cell_m,
                    },
                )
                .to_polygon();
                let inside = polygon.contains(&cell)
                    && !farm
                        .obstacles
                        .iter()
                        .any(|obstacle| obstacle.polygon.intersects(&cell));
                if inside {
                    let index = row * columns + column;
                    workable[index] = true;
                    heights[index] =
                        terrain.height_m(min.x + cell_m / 2.0, min.y + cell_m / 2.0)?;
                }
            }
        }
        Ok(Self {
            cell_m,
            columns,
            rows,
            origin,
            workable,
            heights,
        })
    }

    /// The centre of cell `index`.
    pub fn centre(&self, index: usize) -> Coord<f64> {
        let (row, column) = (index / self.columns, index % self.columns);
        Coord {
            x: self.origin.x + (column as f64 + 0.5) * self.cell_m,
            y: self.origin.y + (row as f64 + 0.5) * self.cell_m,
        }
    }

    /// The neighbour of `index` one step in `direction` (0 = +y, 1 = +x, 2 = −y, 3 = −x).
    fn step(&self, index: usize, direction: usize) -> Option<usize> {
        let (row, column) = ((index / self.columns) as i64, (index % self.columns) as i64);
        let (row, column) = match direction % 4 {
            0 => (row + 1, column),
            1 => (row, column + 1),
            2 => (row - 1, column),
            _ => (row, column - 1),
        };
        (row >= 0 && column >= 0 && row < self.rows as i64 && column < self.columns as i64)
            .then(|| row as usize * self.columns + column as usize)
    }

    /// Flies the motion rule from the workable cell nearest `supply`.
    pub fn fly(self, supply: Coord<f64>, speeds: Speeds) -> Result<MotionRoute, Fault> {
        let start = (0..self.workable.len())
            .filter(|&i| self.workable[i])
            .min_by(|&a, &b| {
                let distance = |i: usize| {
                    let c = self.centre(i);
                    (c.x - supply.x).hypot(c.y - supply.y)
                };
                distance(a).total_cmp(&distance(b)).then(a.cmp(&b))
            })
            .ok_or_else(|| {
                Fault::Structure("no cell of swath width fits inside the field".into())
            })?;
        let mut weight: Vec<f64> = self
            .workable
            .iter()
            .map(|&w| if w { 1.0 } else { 0.0 })
            .collect();
        let reward = |weight: &mut Vec<f64>, cell: Option<usize>, amount: f64| {
            if let Some(cell) = cell {
                if weight[cell] != 0.0 {
                    weight[cell] += amount;
                }
            }
        };
        let (mut current, mut heading) = (start, 0usize);
        weight[current] = 0.0;
        let mut cells = vec![current];
        loop {
            let left = (heading + 3) % 4;
            let right = (heading + 1) % 4;
            let behind = self.step(current, heading + 2);
            reward(&mut weight, self.step(current, heading), FORWARD_REWARD); // rule 1
            reward(
                &mut weight,
                behind.and_then(|b| self.step(b, left)),
                SIDE_REWARD,
            ); // rule 2
            reward(
                &mut weight,
                behind.and_then(|b| self.step(b, right)),
                SIDE_REWARD,
            ); // rule 3
            if let Some(behind) = behind {
                weight[behind] = 0.0; // rule 4
            }
            let mut next: Option<(usize, usize)> = None;
            for direction in [heading, left, right] {
                if let Some(cell) = self.step(current, direction) {
                    if weight[cell] > 0.0
                        && next.is_none_or(|(best, _)| weight[cell] > weight[best])
                    {
                        next = Some((cell, direction));
                    }
                }
            }
            let Some((cell, direction)) = next else { break };
            current = cell;
            heading = direction;
            weight[current] = 0.0;
            cells.push(current);
        }
        let visited = cells.len();
        let unvisited = self.workable.iter().filter(|&&w| w).count() - visited;
        let points: Vec<RoutePoint> = cells
            .iter()
            .map(|&cell| {
                let centre = self.centre(cell);
                RoutePoint {
                    x: centre.x,
                    y: centre.y,
                    ground_m: self.heights[cell],
                }
            })
            .collect();
        let segments: Vec<Segment> = cells
            .windows(2)
            .map(|pair| {
                let same_column = pair[0] % self.columns == pair[1] % self.columns;
                if same_column {
                    Segment::Spray
                } else {
                    Segment::Turn
                }
            })
            .collect();
        let route = WorkRoute::new(points, segments, None, speeds);
        Ok(MotionRoute {
            grid: self,
            cells,
            route,
            unvisited,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::{geojson, CoordinateChoice};
    use crate::terrain::Flat;

    fn farm(text: &str) -> Farm {
        geojson::parse(
            std::path::Path::new("test.geojson"),
            text,
            CoordinateChoice::Local,
        )
        .unwrap()
    }

    const SPEEDS: Speeds = Speeds {
        spray_mps: 3.0,
        turn_mps: 3.0,
        transit_mps: 6.0,
        climb_mps: 3.0,
        descent_mps: 3.0,
        transfer_climb_s: 0.0,
    };

    #[test]
    fn the_motion_rule_flies_a_rectangle_as_a_boustrophedon_visiting_every_cell_once() {
        let farm =
            farm(r#"{"type":"Polygon","coordinates":[[[0,0],[50,0],[50,100],[0,100],[0,0]]]}"#);
        let grid = Grid::new(&farm, 0, 5.0, &Flat::new(0.0)).unwrap();
        assert_eq!(grid.workable.iter().filter(|&&w| w).count(), 200);
        let flown = grid.fly(Coord { x: 0.0, y: 0.0 }, SPEEDS).unwrap();
        assert_eq!(flown.unvisited, 0);
        let mut cells = flown.cells.clone();
        cells.sort_unstable();
        cells.dedup();
        assert_eq!(cells.len(), 200);
        // Ten columns of 95 m sprayed, nine 5 m turns.
        assert!((flown.route.total_spray_m() - 950.0).abs() < 1e-9);
        assert_eq!(
            flown
                .route
                .segments()
                .iter()
                .filter(|s| **s == Segment::Turn)
                .count(),
            9
        );
        let first = flown.route.points()[0];
        assert_eq!((first.x, first.y), (2.5, 2.5));
    }

    #[test]
    fn obstacle_cells_are_never_entered() {
        let farm = farm(
            r#"{"type":"FeatureCollection","features":[
            {"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[0,0],[50,0],[50,100],[0,100],[0,0]]]}},
            {"type":"Feature","properties":{"kind":"obstacle"},"geometry":{"type":"Polygon","coordinates":[[[20,40],[30,40],[30,50],[20,50],[20,40]]]}}]}"#,
        );
        let grid = Grid::new(&farm, 0, 5.0, &Flat::new(0.0)).unwrap();
        let flown = grid.fly(Coord { x: 0.0, y: 0.0 }, SPEEDS).unwrap();
        for &cell in &flown.cells {
            let centre = flown.grid.centre(cell);
            assert!(!(centre.x > 20.0 && centre.x < 30.0 && centre.y > 40.0 && centre.y < 50.0));
        }
    }
}
