//! Where reachable ground was missed, as polygons for the map and `plan.geojson` (issue 22):
//! the row measure's missed intervals ([`super::sprayed::measure`]), stacked row on row
//! into monotone polygons. An interval extends the piece whose last interval it overlaps
//! when each is the other's only overlap; where pieces split or merge, new ones begin. A
//! piece's outline runs up the intervals' starts and down their ends at mid-row, closed half
//! a row beyond its first and last rows, then simplified (Ramer–Douglas–Peucker,
//! [`SIMPLIFY_M`]). The area stays the measure's own to within the rows' discretisation.

use geo::{Area, Coord, LineString, MultiPolygon, Polygon, Simplify};

/// Tolerance of the outline's simplification, metres.
const SIMPLIFY_M: f64 = 0.02;
/// Smallest piece kept, m²: below it a piece is the rounding of the rows.
const LEAST_PIECE_M2: f64 = 0.05;

/// One stack of intervals: (row y, low x, high x), bottom up.
#[derive(Debug, Default)]
struct Piece {
    rows: Vec<(f64, f64, f64)>,
}

impl Piece {
    fn polygon(&self, row_m: f64) -> Polygon<f64> {
        let half = row_m / 2.0;
        let (first, last) = (self.rows[0], self.rows[self.rows.len() - 1]);
        let mut outline = vec![Coord {
            x: first.1,
            y: first.0 - half,
        }];
        outline.extend(self.rows.iter().map(|&(y, low, _)| Coord { x: low, y }));
        outline.push(Coord {
            x: last.1,
            y: last.0 + half,
        });
        outline.push(Coord {
            x: last.2,
            y: last.0 + half,
        });
        outline.extend(
            self.rows
                .iter()
                .rev()
                .map(|&(y, _, high)| Coord { x: high, y }),
        );
        outline.push(Coord {
            x: first.2,
            y: first.0 - half,
        });
        outline.push(outline[0]);
        Polygon::new(LineString::new(outline), vec![]).simplify(SIMPLIFY_M)
    }
}

/// Builds the missed pieces of one region row by row (rows in increasing y).
#[derive(Debug, Default)]
pub struct MissedPieces {
    open: Vec<Piece>,
    closed: Vec<Piece>,
}

impl MissedPieces {
    /// Adds row `y`'s missed intervals (sorted, disjoint).
    pub fn add_row(&mut self, y: f64, intervals: &[(f64, f64)]) {
        // A piece taken by an earlier interval of this row is empty: it overlaps nothing.
        let overlaps = |piece: &Piece, &(low, high): &(f64, f64)| {
            piece
                .rows
                .last()
                .is_some_and(|&(_, piece_low, piece_high)| low < piece_high && high > piece_low)
        };
        let mut next_open = Vec::with_capacity(intervals.len());
        let mut taken = vec![false; self.open.len()];
        for interval in intervals {
            let touching: Vec<usize> = (0..self.open.len())
                .filter(|&k| overlaps(&self.open[k], interval))
                .collect();
            let only = match touching.as_slice() {
                [k] if !taken[*k]
                    && intervals
                        .iter()
                        .filter(|other| overlaps(&self.open[*k], other))
                        .count()
                        == 1 =>
                {
                    Some(*k)
                }
                _ => None,
            };
            let mut piece = match only {
                Some(k) => {
                    taken[k] = true;
                    std::mem::take(&mut self.open[k])
                }
                None => Piece::default(),
            };
            piece.rows.push((y, interval.0, interval.1));
            next_open.push(piece);
        }
        for (k, piece) in self.open.drain(..).enumerate() {
            if !taken[k] && !piece.rows.is_empty() {
                self.closed.push(piece);
            }
        }
        self.open = next_open;
    }

    /// The pieces as polygons, rows `row_m` apart.
    pub fn finish(mut self, row_m: f64) -> MultiPolygon<f64> {
        self.closed.append(&mut self.open);
        MultiPolygon::new(
            self.closed
                .iter()
                .filter(|piece| !piece.rows.is_empty())
                .map(|piece| piece.polygon(row_m))
                .filter(|polygon| polygon.unsigned_area() >= LEAST_PIECE_M2)
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stacked_intervals_become_one_piece_and_a_split_begins_two() {
        let mut pieces = MissedPieces::default();
        // A 2 m × 1 m block on rows 0.05..0.95, then a fork into two 0.5 m wide legs.
        for row in 0..10 {
            pieces.add_row(0.05 + 0.1 * row as f64, &[(0.0, 2.0)]);
        }
        for row in 10..20 {
            pieces.add_row(0.05 + 0.1 * row as f64, &[(0.0, 0.5), (1.5, 2.0)]);
        }
        // Two rows that each continue their own piece, beside an interval touching nothing.
        for row in 20..22 {
            pieces.add_row(
                0.05 + 0.1 * row as f64,
                &[(0.0, 0.5), (0.9, 1.3), (1.5, 2.0)],
            );
        }
        let polygons = pieces.finish(0.1);
        assert_eq!(polygons.0.len(), 4, "{polygons:?}");
        let area = polygons.unsigned_area();
        assert!((area - (2.0 + 0.6 + 0.6 + 0.08)).abs() < 1e-9, "{area}");
    }
}
