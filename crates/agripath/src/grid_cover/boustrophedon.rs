//! `baseline`: boustrophedon cell decomposition with a fixed order, the plan a user of
//! today's ground stations would recognise. The field's path points are split into cells
//! (column runs of neighbouring columns that meet one to one, [`super::fewest_turns::cells`]);
//! cells are flown in a fixed order, by their leftmost column and then their lowest row; each
//! cell is swept column by column along y, entering every column at the end nearer the
//! previous one; between cells the drone takes the shortest clear way.

use super::fewest_turns::{cells, fly_in_order, runs, Sweep};
use super::{GridRoute, PointGrid};

/// The baseline route over `grid`'s path points: cells in fixed order, each swept along y.
pub fn plan(grid: &PointGrid) -> GridRoute {
    let mut decomposition = cells(grid, Sweep::AlongY);
    decomposition.sort_by_key(|cell| {
        cell.iter()
            .map(|&p| (grid.cell(p).0, grid.cell(p).1))
            .min()
            .unwrap_or((i64::MAX, i64::MAX))
    });
    let mut ordered_runs = Vec::new();
    for cell in decomposition {
        ordered_runs.extend(runs(grid, &cell, Sweep::AlongY));
    }
    fly_in_order(grid, ordered_runs)
}
