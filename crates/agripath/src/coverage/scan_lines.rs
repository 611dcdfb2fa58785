//! Scan-line swaths of a region at heading θ (seed 001 §2.1, steps ①-⑥).
//!
//! ① take the region's rings (outer boundaries, holes, obstacles); ② rotate them by −θ;
//! ③ lay scan lines parallel to the rotated x axis at spacing w, the first at
//! `y_min + first_offset` (`w/2` in the seed's layout); ④ intersect each line with every edge;
//! ⑤ sort the intersections by x; ⑥ pair them up: each pair is a swath segment inside the region.
//!
//! Vertices on a scan line follow the seed's rule that "the intersection always lies on one
//! side of the line": an edge meets line y = c when exactly one of its ends is strictly above
//! c (`(p.y > c) != (q.y > c)`). A vertex touching the line from above then counts twice (its
//! two edges both cross) and one from below not at all, so pairs cancel as in the seed's
//! Fig. 2, and edges lying on the line meet it nowhere ("coincident lines have no
//! intersection"). Deviations from the paper: none.

use geo::Coord;

/// A heading as the unit vectors of the rotated frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Cosine of the heading.
    pub cos: f64,
    /// Sine of the heading.
    pub sin: f64,
}

impl Frame {
    /// Heading in degrees from +x (east), counter-clockwise.
    pub fn new(heading_deg: f64) -> Self {
        let radians = heading_deg.to_radians();
        Self {
            cos: radians.cos(),
            sin: radians.sin(),
        }
    }

    /// Planning frame → rotated frame (rotation by −θ): swaths run along the rotated x axis.
    pub fn to_rotated(&self, point: Coord<f64>) -> Coord<f64> {
        Coord {
            x: point.x * self.cos + point.y * self.sin,
            y: -point.x * self.sin + point.y * self.cos,
        }
    }

    /// Rotated frame → planning frame.
    pub fn to_plan(&self, point: Coord<f64>) -> Coord<f64> {
        Coord {
            x: point.x * self.cos - point.y * self.sin,
            y: point.x * self.sin + point.y * self.cos,
        }
    }
}

/// One swath segment in the rotated frame: scan line `line` at height `y`, from `start_x` to
/// `end_x` (`start_x < end_x`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Scan line index, 0 for the line nearest the region's smallest rotated y.
    pub line: usize,
    /// Rotated y of the scan line, metres.
    pub y: f64,
    /// Rotated x where the segment starts, metres.
    pub start_x: f64,
    /// Rotated x where the segment ends, metres.
    pub end_x: f64,
}

impl Segment {
    /// Length of the segment (flat, in the plane), metres.
    pub fn length(&self) -> f64 {
        self.end_x - self.start_x
    }
}

/// Rings already rotated into the frame, with their extent.
pub struct RotatedRings {
    /// The rotated rings, each closed (first point repeated last), metres.
    pub rings: Vec<Vec<Coord<f64>>>,
    /// Smallest rotated y over all rings, metres.
    pub min_y: f64,
    /// Largest rotated y over all rings, metres.
    pub max_y: f64,
    /// Smallest rotated x over all rings, metres.
    pub min_x: f64,
}

impl RotatedRings {
    /// Rotates closed rings (first point repeated last) into `frame`.
    pub fn new<'a>(rings: impl IntoIterator<Item = &'a [Coord<f64>]>, frame: Frame) -> Self {
        let mut rotated = Vec::new();
        let (mut min_y, mut max_y, mut min_x) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
        for ring in rings {
            let points: Vec<Coord<f64>> =
                ring.iter().map(|&point| frame.to_rotated(point)).collect();
            for point in &points {
                min_y = min_y.min(point.y);
                max_y = max_y.max(point.y);
                min_x = min_x.min(point.x);
            }
            rotated.push(points);
        }
        Self {
            rings: rotated,
            min_y,
            max_y,
            min_x,
        }
    }
}

/// Swath segments of the region bounded by `rings` (even-odd: holes are rings too) on scan
/// lines `y_k = min_y + first_offset + k·spacing` for every `y_k < max_y`.
pub fn scan_segments(rings: &RotatedRings, spacing: f64, first_offset: f64) -> Vec<Segment> {
    let first = rings.min_y + first_offset;
    // Also true for NaN extents (a region with no rings).
    if first.partial_cmp(&rings.max_y) != Some(std::cmp::Ordering::Less) {
        return Vec::new();
    }
    let line_count = ((rings.max_y - first) / spacing).floor() as usize + 1;
    let mut crossings: Vec<Vec<f64>> = vec![Vec::new(); line_count];
    for ring in &rings.rings {
        for pair in ring.windows(2) {
            let (p, q) = (pair[0], pair[1]);
            if p.y == q.y {
                continue;
            }
            let (low, high) = if p.y < q.y { (p.y, q.y) } else { (q.y, p.y) };
            // Lines with low ≤ y_k < high cross the edge under the half-open rule
            // (one end strictly above y_k, the other at or below it).
            let first_line = ((low - first) / spacing).ceil().max(0.0) as usize;
            let mut line = first_line;
            while line < line_count {
                let y = first + line as f64 * spacing;
                if y >= high {
                    break;
                }
                if y >= low && ((p.y > y) != (q.y > y)) {
                    crossings[line].push(p.x + (y - p.y) * (q.x - p.x) / (q.y - p.y));
                }
                line += 1;
            }
        }
    }
    let mut segments = Vec::new();
    for (line, xs) in crossings.iter_mut().enumerate() {
        xs.sort_by(f64::total_cmp);
        let y = first + line as f64 * spacing;
        for pair in xs.chunks_exact(2) {
            if pair[1] > pair[0] {
                segments.push(Segment {
                    line,
                    y,
                    start_x: pair[0],
                    end_x: pair[1],
                });
            }
        }
    }
    segments
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rings(points: &[&[(f64, f64)]], heading: f64) -> RotatedRings {
        let closed: Vec<Vec<Coord<f64>>> = points
            .iter()
            .map(|ring| {
                let mut coords: Vec<Coord<f64>> =
                    ring.iter().map(|&(x, y)| Coord { x, y }).collect();
                coords.push(coords[0]);
                coords
            })
            .collect();
        RotatedRings::new(closed.iter().map(Vec::as_slice), Frame::new(heading))
    }

    #[test]
    fn square_gives_one_swath_per_line() {
        let square = rings(
            &[&[(0.0, 0.0), (100.0, 0.0), (100.0, 50.0), (0.0, 50.0)]],
            0.0,
        );
        let segments = scan_segments(&square, 5.0, 2.5);
        assert_eq!(segments.len(), 10);
        assert!(segments
            .iter()
            .all(|segment| (segment.length() - 100.0).abs() < 1e-9));
    }

    #[test]
    fn holes_split_swaths_and_vertices_on_lines_follow_the_one_side_rule() {
        // A hole whose corners sit exactly on scan lines y = 12.5 and y = 22.5.
        let field = rings(
            &[
                &[(0.0, 0.0), (100.0, 0.0), (100.0, 50.0), (0.0, 50.0)],
                &[(40.0, 12.5), (60.0, 12.5), (60.0, 22.5), (40.0, 22.5)],
            ],
            0.0,
        );
        let segments = scan_segments(&field, 5.0, 2.5);
        let on_line = |y: f64| segments.iter().filter(|s| (s.y - y).abs() < 1e-9).count();
        // The hole's bottom edge lies on y = 12.5: coincident, so no split there;
        // y = 17.5 passes through the hole: two swaths; its top edge on 22.5: one swath.
        assert_eq!(
            on_line(12.5),
            2,
            "the hole spans [12.5, 22.5): split at its bottom"
        );
        assert_eq!(on_line(17.5), 2);
        assert_eq!(on_line(22.5), 1);
        // A diamond vertex touching a line from below adds nothing, from above cancels.
        let diamond = rings(
            &[&[(50.0, 2.5), (60.0, 12.5), (50.0, 22.5), (40.0, 12.5)]],
            0.0,
        );
        let segments = scan_segments(&diamond, 5.0, 0.0);
        for segment in &segments {
            assert!(segment.length() > 0.0);
        }
        assert_eq!(segments.len(), 3, "{segments:?}");
    }

    #[test]
    fn frame_round_trips() {
        let frame = Frame::new(37.0);
        let point = Coord { x: 12.0, y: -7.0 };
        let back = frame.to_plan(frame.to_rotated(point));
        assert!((back.x - point.x).abs() < 1e-12 && (back.y - point.y).abs() < 1e-12);
    }
}
