//! `baseline`: boustrophedon cell decomposition with a fixed order, the plan a user of
//! today's ground stations would recognise. The field's path points are split into cells
//! (column runs of neighbouring columns that meet one to one, [`super::fewest_turns::cells`]);
//! cells are flown in a fixed order, by their leftmost column and then their lowest row; each
//! cell is swept column by column along y, entering every column at the end nearer the
//! previous one; between cells the drone takes the shortest clear way.
//!
//! [`single_direction`] is the same plan along x or along y, whichever flies fewer turns: one
//! of the starting routes HPSO's ablation tries (decision 0010).

use super::fewest_turns::{cells, fly_in_order, runs, Sweep};
use super::{GridRoute, PointGrid};

/// The baseline route over `grid`'s path points: cells in fixed order, each swept along y.
pub fn plan(grid: &PointGrid) -> GridRoute {
    plan_along(grid, Sweep::AlongY)
}

/// The boustrophedon along x or along y, whichever has fewer turns (along y on a tie).
pub fn single_direction(grid: &PointGrid) -> GridRoute {
    let along_y = plan_along(grid, Sweep::AlongY);
    let along_x = plan_along(grid, Sweep::AlongX);
    if along_x.measure(grid).turns < along_y.measure(grid).turns {
        along_x
    } else {
        along_y
    }
}

/// Cells of the decomposition along `sweep`, in fixed order (first line, then lowest place
/// along it), each swept along `sweep`.
fn plan_along(grid: &PointGrid, sweep: Sweep) -> GridRoute {
    let mut decomposition = cells(grid, sweep);
    decomposition.sort_by_key(|cell| {
        cell.iter()
            .map(|&p| {
                let (column, row) = grid.cell(p);
                match sweep {
                    Sweep::AlongY => (column, row),
                    Sweep::AlongX => (row, column),
                }
            })
            .min()
            .unwrap_or((i64::MAX, i64::MAX))
    });
    let mut ordered_runs = Vec::new();
    for cell in decomposition {
        ordered_runs.extend(runs(grid, &cell, sweep));
    }
    fly_in_order(grid, ordered_runs)
}
