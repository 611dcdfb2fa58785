//! Contour-parallel runs: every point is swept parallel to the boundary it is nearer to, so the
//! runs form rings round the field's edge and round each obstacle, and a route can fly them as
//! a spiral in which every junction is an L (one turn) instead of a U (two).
//!
//! For a valid point p let ℓ, r, d, u be the numbers of valid points reachable from p by clear
//! 4-neighbour moves straight left, right, down and up. Then p is swept
//!
//! - along x (it lies on a top or bottom side of its ring) when min(d, u) < min(ℓ, r),
//! - along y (a left or right side) when min(ℓ, r) < min(d, u),
//! - and, on a tie (a ring's corner), along the sweep `corner` chooses.
//!
//! On a W × H rectangle this gives ⌈min(W, H)/2⌉ nested rings of four runs each, which a spiral
//! flies with one turn per junction: about 2·min(W, H) − 2 turns, the count a boustrophedon needs
//! (2·(runs − 1)) only without obstacles. Round an obstacle the rings close round it, where a
//! boustrophedon must split every line that meets it. This is the direction-per-region idea of
//! turn-minimising coverage (Bochkarev & Smith 2016, docs/references.md) taken to single points;
//! the runs are ordered by the same exact-turn search as every other decomposition
//! ([`super::fewest_turns`]).

use super::runs::{runs, Sweep};
use super::PointGrid;

/// The valid points reachable from `index` in steps of (dc, dr) by clear moves between
/// neighbours, not counting `index` itself.
fn reach(grid: &PointGrid, index: usize, dc: i64, dr: i64) -> usize {
    let mut count = 0;
    let mut at = index;
    loop {
        let (column, row) = grid.cell(at);
        let (c, r) = (column + dc, row + dr);
        if c < 0 || r < 0 || c >= grid.columns as i64 || r >= grid.rows as i64 {
            return count;
        }
        let next = r as usize * grid.columns + c as usize;
        if !grid.valid[next] || !grid.clear(grid.centre(at), grid.centre(next)) {
            return count;
        }
        count += 1;
        at = next;
    }
}

/// The sweep of each valid point (in `grid.points` order) under the contour rule, corners
/// (ties) going to `corner`.
pub fn directions(grid: &PointGrid, corner: Sweep) -> Vec<Sweep> {
    grid.points
        .iter()
        .map(|&p| {
            let across_x = reach(grid, p, -1, 0).min(reach(grid, p, 1, 0));
            let across_y = reach(grid, p, 0, -1).min(reach(grid, p, 0, 1));
            match across_y.cmp(&across_x) {
                std::cmp::Ordering::Less => Sweep::AlongX,
                std::cmp::Ordering::Greater => Sweep::AlongY,
                std::cmp::Ordering::Equal => corner,
            }
        })
        .collect()
}

/// The straight runs of a direction per point: the maximal runs along x of the points swept
/// along x, and along y of the others.
pub fn runs_of(grid: &PointGrid, directions: &[Sweep]) -> Vec<Vec<usize>> {
    let of = |sweep: Sweep| -> Vec<usize> {
        grid.points
            .iter()
            .zip(directions)
            .filter(|(_, &d)| d == sweep)
            .map(|(&p, _)| p)
            .collect()
    };
    let mut all = runs(grid, &of(Sweep::AlongX), Sweep::AlongX);
    all.extend(runs(grid, &of(Sweep::AlongY), Sweep::AlongY));
    all
}

/// The contour-parallel runs of `grid`, corners swept along `corner`.
pub fn ring_runs(grid: &PointGrid, corner: Sweep) -> Vec<Vec<usize>> {
    runs_of(grid, &directions(grid, corner))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::{geojson, CoordinateChoice};

    fn rectangle(width_m: f64, height_m: f64) -> PointGrid {
        let text = format!(
            r#"{{"type":"Polygon","coordinates":[[[0,0],[{width_m},0],[{width_m},{height_m}],[0,{height_m}],[0,0]]]}}"#
        );
        let farm = geojson::parse(
            std::path::Path::new("t.geojson"),
            &text,
            CoordinateChoice::Local,
        )
        .unwrap();
        PointGrid::new(&farm, 0, 5.0).unwrap()
    }

    /// 4 × 3 points (indices row · 4 + column): the bottom and top rows along x (corners
    /// included), the middle row's two inner points along x, its two ends along y.
    #[test]
    fn a_rectangle_gets_rings() {
        let grid = rectangle(20.0, 15.0);
        let mut runs = ring_runs(&grid, Sweep::AlongX);
        runs.sort();
        assert_eq!(
            runs,
            vec![
                vec![0, 1, 2, 3],
                vec![4],
                vec![5, 6],
                vec![7],
                vec![8, 9, 10, 11]
            ]
        );
        // Corners (ties) along y instead: the side columns take the outer corners, and the
        // middle row's inner points, tied too, become columns of one point.
        let mut runs = ring_runs(&grid, Sweep::AlongY);
        runs.sort();
        let expected: Vec<Vec<usize>> = vec![
            vec![0, 4, 8],
            vec![1, 2],
            vec![3, 7, 11],
            vec![5],
            vec![6],
            vec![9, 10],
        ];
        assert_eq!(runs, expected);
    }

    /// Every valid point is in exactly one run, on any field.
    #[test]
    fn the_runs_cover_every_point_once() {
        for (name, text) in crate::repro::seed004::FIELDS {
            let farm = geojson::parse(
                std::path::Path::new("t.geojson"),
                text,
                CoordinateChoice::FromFile,
            )
            .unwrap();
            let grid = PointGrid::new(&farm, 0, 5.0).unwrap();
            for corner in [Sweep::AlongX, Sweep::AlongY] {
                let mut points: Vec<usize> = ring_runs(&grid, corner).concat();
                points.sort_unstable();
                assert_eq!(points, grid.points, "{name}");
            }
        }
    }
}
