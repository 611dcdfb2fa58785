//! Straight runs and boustrophedon cells of a grid's path points: the pieces every grid
//! method's decomposition is made of.
//!
//! - A run is a maximal sequence of 4-adjacent points along y (in a column) or along x (in a
//!   row) with a clear move between each point and the next.
//! - A boustrophedon cell groups the runs of neighbouring lines that meet one to one (a run
//!   with exactly one overlapping run in the line before, which overlaps no other), as a sweep
//!   line stays in one cell until it meets an obstacle's or the field's critical point.

use super::PointGrid;

/// Which way runs go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sweep {
    /// Runs go along y, within a column.
    AlongY,
    /// Runs go along x, within a row.
    AlongX,
}

/// The maximal straight runs of `points` (a subset of the grid's valid points) along `sweep`,
/// each ordered by increasing coordinate; no run crosses an obstacle between two of its
/// neighbouring points.
pub fn runs(grid: &PointGrid, points: &[usize], sweep: Sweep) -> Vec<Vec<usize>> {
    let mut inside = vec![false; grid.valid.len()];
    for &p in points {
        inside[p] = true;
    }
    let (outer, inner) = match sweep {
        Sweep::AlongY => (grid.columns, grid.rows),
        Sweep::AlongX => (grid.rows, grid.columns),
    };
    let index = |o: usize, i: usize| match sweep {
        Sweep::AlongY => i * grid.columns + o,
        Sweep::AlongX => o * grid.columns + i,
    };
    let mut result = Vec::new();
    for o in 0..outer {
        let mut current: Vec<usize> = Vec::new();
        for i in 0..inner {
            let p = index(o, i);
            // A run also ends where an obstacle cuts between two neighbouring points.
            let blocked = current
                .last()
                .is_some_and(|&q| !grid.clear(grid.centre(q), grid.centre(p)));
            if (!inside[p] || blocked) && !current.is_empty() {
                result.push(std::mem::take(&mut current));
            }
            if inside[p] {
                current.push(p);
            }
        }
        if !current.is_empty() {
            result.push(current);
        }
    }
    result
}

/// Boustrophedon cells: groups of runs along `sweep` in neighbouring lines that overlap one
/// to one. Returns the points of each cell.
pub fn cells(grid: &PointGrid, sweep: Sweep) -> Vec<Vec<usize>> {
    let lines = runs(grid, &grid.points, sweep);
    let line_of = |run: &Vec<usize>| match sweep {
        Sweep::AlongY => grid.cell(run[0]).0,
        Sweep::AlongX => grid.cell(run[0]).1,
    };
    let span = |run: &Vec<usize>| {
        let along = |p: usize| match sweep {
            Sweep::AlongY => grid.cell(p).1,
            Sweep::AlongX => grid.cell(p).0,
        };
        (
            along(run[0]),
            along(*run.last().expect("runs are not empty")),
        )
    };
    let overlaps = |a: &Vec<usize>, b: &Vec<usize>| {
        let ((a0, a1), (b0, b1)) = (span(a), span(b));
        line_of(b) == line_of(a) + 1 && a0 <= b1 && b0 <= a1
    };
    let mut cell_of = vec![usize::MAX; lines.len()];
    let mut cells: Vec<Vec<usize>> = Vec::new();
    for (k, run) in lines.iter().enumerate() {
        let before: Vec<usize> = (0..k).filter(|&j| overlaps(&lines[j], run)).collect();
        let continues = match before.as_slice() {
            [single] => {
                let successors = (0..lines.len())
                    .filter(|&j| overlaps(&lines[*single], &lines[j]))
                    .count();
                (successors == 1).then_some(cell_of[*single])
            }
            _ => None,
        };
        let cell = continues.unwrap_or_else(|| {
            cells.push(Vec::new());
            cells.len() - 1
        });
        cell_of[k] = cell;
        cells[cell].extend(run.iter().copied());
    }
    cells
}
