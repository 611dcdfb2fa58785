//! A regular raster of heights: what every DEM reader produces.
//!
//! Cell (row, column) holds the height at its centre; row 0 is the northern edge.
//! Heights between centres are bilinear. The raster answers anywhere inside its outer edge
//! (half a cell beyond the outermost centres, where the edge cells' values are held);
//! outside it, or where a contributing cell has no data, the query fails.

use super::{Extent, Terrain};
use crate::error::{Fault, TerrainError};
use crate::limits::TERRAIN_HEIGHT_RANGE_M;

/// A raster of heights, cell centres on a regular lattice.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Number of columns (west to east).
    pub columns: usize,
    /// Number of rows (north to south).
    pub rows: usize,
    /// x of the centre of column 0, metres (or degrees for a geographic DEM).
    pub first_center_x: f64,
    /// y of the centre of row 0 (the northern row).
    pub first_center_y: f64,
    /// Cell width (positive, eastward).
    pub cell_x: f64,
    /// Cell height (positive; rows go south).
    pub cell_y: f64,
    /// Row-major heights, metres; NaN where there is no data.
    pub heights: Vec<f32>,
    /// EPSG code of the raster's coordinates, when the file says.
    pub epsg: Option<u32>,
    /// What the reader found, for `terrain info`.
    pub source: String,
}

impl Grid {
    /// Height stored at a cell centre (NaN for no data).
    pub fn cell(&self, row: usize, column: usize) -> f32 {
        self.heights[row * self.columns + column]
    }

    /// Planar position of a cell centre.
    pub fn cell_center(&self, row: usize, column: usize) -> (f64, f64) {
        (
            self.first_center_x + column as f64 * self.cell_x,
            self.first_center_y - row as f64 * self.cell_y,
        )
    }

    /// Cells holding data.
    pub fn valid_cells(&self) -> usize {
        self.heights
            .iter()
            .filter(|height| !height.is_nan())
            .count()
    }

    /// Lowest and highest stored height.
    pub fn stored_range(&self) -> Option<(f64, f64)> {
        self.heights
            .iter()
            .filter(|height| !height.is_nan())
            .fold(None, |range, &height| {
                let height = f64::from(height);
                Some(match range {
                    Some((low, high)) => (f64::min(low, height), f64::max(high, height)),
                    None => (height, height),
                })
            })
    }

    /// Refuses a raster no planner can trust: a placement that is not finite (a NaN tiepoint),
    /// no cell with data, or a height outside [`TERRAIN_HEIGHT_RANGE_M`] (an undeclared
    /// no-data value such as 3.4e38 or −32767, which would otherwise be flown as terrain).
    pub fn check_plausible(&self) -> Result<(), Fault> {
        let placement = [
            self.first_center_x,
            self.first_center_y,
            self.cell_x,
            self.cell_y,
        ];
        if placement.iter().any(|value| !value.is_finite())
            || self.cell_x <= 0.0
            || self.cell_y <= 0.0
            || !self.outer_extent().width().is_finite()
            || !self.outer_extent().height().is_finite()
        {
            return Err(Fault::Structure(format!(
                "the raster's placement is not finite: first cell centre ({}, {}), cell {} × {}",
                self.first_center_x, self.first_center_y, self.cell_x, self.cell_y
            )));
        }
        let (lowest, highest) = TERRAIN_HEIGHT_RANGE_M;
        let mut any_data = false;
        for (index, &height) in self.heights.iter().enumerate() {
            if height.is_nan() {
                continue;
            }
            any_data = true;
            if !(f64::from(height) >= lowest && f64::from(height) <= highest) {
                return Err(Fault::InvalidValue {
                    what: format!(
                        "the height at row {}, column {}",
                        index / self.columns,
                        index % self.columns
                    ),
                    value: format!("{} m", crate::error::figure(f64::from(height))),
                    why: format!(
                        "terrain lies within {lowest}..={highest} m (an undeclared no-data value?)"
                    ),
                });
            }
        }
        if !any_data {
            return Err(Fault::Structure(
                "every cell of the raster is no-data".into(),
            ));
        }
        Ok(())
    }

    /// Outer edge of the raster (cell edges, not centres).
    pub fn outer_extent(&self) -> Extent {
        Extent {
            min_x: self.first_center_x - self.cell_x / 2.0,
            max_x: self.first_center_x + (self.columns as f64 - 0.5) * self.cell_x,
            max_y: self.first_center_y + self.cell_y / 2.0,
            min_y: self.first_center_y - (self.rows as f64 - 0.5) * self.cell_y,
        }
    }
}

impl Terrain for Grid {
    fn epsg(&self) -> Option<u32> {
        self.epsg
    }

    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        let column_position = (x - self.first_center_x) / self.cell_x;
        let row_position = (self.first_center_y - y) / self.cell_y;
        let last_column = (self.columns - 1) as f64;
        let last_row = (self.rows - 1) as f64;
        // NaN positions fail these comparisons too, so a NaN query is "outside".
        if !(column_position >= -0.5
            && column_position <= last_column + 0.5
            && row_position >= -0.5
            && row_position <= last_row + 0.5)
        {
            return Err(TerrainError::Outside { x, y });
        }
        let column_position = column_position.clamp(0.0, last_column);
        let row_position = row_position.clamp(0.0, last_row);
        let column = (column_position.floor() as usize).min(self.columns.saturating_sub(2));
        let row = (row_position.floor() as usize).min(self.rows.saturating_sub(2));
        let next_column = (column + 1).min(self.columns - 1);
        let next_row = (row + 1).min(self.rows - 1);
        // A query within a billionth of a cell of a centre is at the centre: the stored value
        // comes back exactly, not blended with rounding noise.
        let snap = |t: f64| {
            if t < 1e-9 {
                0.0
            } else if t > 1.0 - 1e-9 {
                1.0
            } else {
                t
            }
        };
        let tx = snap(column_position - column as f64);
        let ty = snap(row_position - row as f64);
        let mut height = 0.0;
        for (r, c, weight) in [
            (row, column, (1.0 - tx) * (1.0 - ty)),
            (row, next_column, tx * (1.0 - ty)),
            (next_row, column, (1.0 - tx) * ty),
            (next_row, next_column, tx * ty),
        ] {
            if weight == 0.0 {
                continue;
            }
            let value = self.cell(r, c);
            if value.is_nan() {
                return Err(TerrainError::NoData { x, y });
            }
            height += weight * f64::from(value);
        }
        Ok(height)
    }

    fn extent(&self) -> Option<Extent> {
        Some(self.outer_extent())
    }

    /// The lines through the cell centres: bilinear interpolation bends there.
    fn bends_along(&self, from: (f64, f64), to: (f64, f64)) -> Vec<f64> {
        super::lattice_bends(
            from,
            to,
            (self.first_center_x, self.first_center_y),
            (self.cell_x, self.cell_y),
        )
    }

    fn lattice(&self) -> Option<((f64, f64), (f64, f64))> {
        Some((
            (self.first_center_x, self.first_center_y),
            (self.cell_x, self.cell_y),
        ))
    }

    fn describe(&self) -> String {
        self.source.clone()
    }

    fn height_range_m(&self, within: Extent) -> Option<(f64, f64)> {
        let whole = self.outer_extent();
        if within.min_x <= whole.min_x
            && within.min_y <= whole.min_y
            && within.max_x >= whole.max_x
            && within.max_y >= whole.max_y
        {
            return self.stored_range();
        }
        let mut range: Option<(f64, f64)> = None;
        for row in 0..self.rows {
            for column in 0..self.columns {
                let (x, y) = self.cell_center(row, column);
                let value = self.cell(row, column);
                if within.contains(x, y) && !value.is_nan() {
                    let value = f64::from(value);
                    range = Some(match range {
                        Some((low, high)) => (low.min(value), high.max(value)),
                        None => (value, value),
                    });
                }
            }
        }
        range
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn three_by_two() -> Grid {
        Grid {
            columns: 3,
            rows: 2,
            first_center_x: 0.5,
            first_center_y: 1.5,
            cell_x: 1.0,
            cell_y: 1.0,
            heights: vec![0.0, 1.0, 2.0, 10.0, 11.0, f32::NAN],
            epsg: None,
            source: "test".into(),
        }
    }

    #[test]
    fn centres_edges_and_outside() {
        let grid = three_by_two();
        assert_eq!(grid.height_m(0.5, 1.5), Ok(0.0));
        assert_eq!(grid.height_m(1.5, 0.5), Ok(11.0));
        assert_eq!(grid.height_m(1.0, 1.0), Ok(5.5));
        // Half a cell beyond the outermost centre holds the edge value.
        assert_eq!(grid.height_m(0.0, 2.0), Ok(0.0));
        assert!(matches!(
            grid.height_m(-0.1, 1.0),
            Err(TerrainError::Outside { .. })
        ));
        assert!(matches!(
            grid.height_m(2.2, 0.8),
            Err(TerrainError::NoData { .. })
        ));
        assert_eq!(grid.height_m(2.5, 1.5), Ok(2.0));
        assert_eq!(grid.stored_range(), Some((0.0, 11.0)));
    }

    proptest! {
        /// Bilinear heights never leave the range of the four surrounding centres.
        #[test]
        fn interpolation_is_bounded(x in 0.5f64..1.5, y in 0.5f64..1.5) {
            let height = three_by_two().height_m(x, y).unwrap();
            prop_assert!((0.0..=11.0).contains(&height));
        }
    }
}
