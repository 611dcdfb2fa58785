//! Where a swath's sprayer goes on and off where it runs into the edge-pass band (issue 22,
//! decision 0019).
//!
//! With edge passes, swaths are laid out to end on the innermost pass line (decision 0005),
//! so their square ends reach half a swath into the band the passes already spray, and more
//! where the boundary is oblique: that is 97 % of the double dose of the default layout. The
//! ground the edge passes leave to the swaths is the *core*, the sprayable region shrunk by
//! the headland's width. Across a swath's width the core ends at different places along the
//! swath (all at once where the boundary is square to the swath, spread over w·|cot φ| where
//! it meets the swath at φ). Take `rows` lines across the strip, at lateral offsets v_i, and
//! let e_i be where the core ends on line i. A square end at s then sprays twice
//!
//!   D(s) = Σ_i max(0, s − e_i)·Δv          (the band beyond the core, already sprayed)
//!
//! and leaves unsprayed
//!
//!   M(s) = Σ_i max(0, e_i − s)·Δv          (core short of the end).
//!
//! - `overlap` keeps today's end (the pass line): M = 0, D largest;
//! - `gap` ends where the core first ends, s = min e_i: D = 0;
//! - `balanced` minimises D(s) + k·M(s) with k = [`MISSED_WEIGHT`] (a missed strip is a pest
//!   or weed left, a double dose costs product and may scorch the crop, and the preflight
//!   holds coverage, not dose): D + k·M is convex and piecewise linear in s, its minimum is
//!   the k/(k + 1) quantile of the e_i (its slope is #{e_i < s} − k·#{e_i > s}).
//!
//! No end moves past today's, so no cut sprays more or leaves the sprayable region.

use std::str::FromStr;

use geo::MultiPolygon;
use serde::Serialize;

use super::region::{offset, rings};
use super::scan_lines::{scan_segments, Frame, RotatedRings, Segment};

/// How much more a missed square metre weighs than a double-sprayed one in `balanced`.
pub const MISSED_WEIGHT: f64 = 4.0;
/// Lines across a swath on which the core's end is sampled.
const ROWS: usize = 32;
/// Shortest swath a cut may leave, metres; a shorter one keeps its ends (it lies in a sliver
/// between bands, where a cut would leave the sliver unsprayed).
const SHORTEST_CUT_SWATH_M: f64 = 1.0;

/// Where a swath's spray on/off points sit where it runs into the edge-pass band.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeCut {
    /// On the innermost pass line: no gap, the most double dose (the layout before issue 22).
    Overlap,
    /// Least double-sprayed plus [`MISSED_WEIGHT`] × missed area.
    #[default]
    Balanced,
    /// Where the core first ends: no double dose, the most missed.
    Gap,
}

impl EdgeCut {
    /// The name on the command line.
    pub fn key(self) -> &'static str {
        match self {
            EdgeCut::Overlap => "overlap",
            EdgeCut::Balanced => "balanced",
            EdgeCut::Gap => "gap",
        }
    }
}

impl FromStr for EdgeCut {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        match text.trim().to_ascii_lowercase().as_str() {
            "overlap" => Ok(EdgeCut::Overlap),
            "balanced" => Ok(EdgeCut::Balanced),
            "gap" => Ok(EdgeCut::Gap),
            _ => Err(format!(
                "'{text}' is not an edge cut: overlap, balanced or gap"
            )),
        }
    }
}

/// Moves the ends of `segments` (rotated frame `frame`, swaths `width_m` apart) by `cut`
/// against the core: the sprayable region inside the band of the innermost edge pass
/// (`innermost` is that pass's region, its ring the pass line).
pub fn cut_swath_ends(
    segments: &[Segment],
    innermost: &MultiPolygon<f64>,
    frame: Frame,
    width_m: f64,
    cut: EdgeCut,
) -> Vec<Segment> {
    if cut == EdgeCut::Overlap || segments.is_empty() {
        return segments.to_vec();
    }
    let core = offset(innermost, -width_m / 2.0);
    let core_rings = rings(&core);
    let rotated = RotatedRings::new(core_rings.iter().map(Vec::as_slice), frame);
    // Sample rows at y_swath + v_i, v_i = −w/2 + (i + ½)·Δv, all swaths on one grid.
    let spacing = width_m / ROWS as f64;
    let origin = segments[0].y - width_m / 2.0 + spacing / 2.0;
    let lanes_below = if rotated.min_y.is_finite() {
        ((rotated.min_y - origin) / spacing).floor()
    } else {
        0.0
    };
    let first_y = origin + lanes_below * spacing;
    let first_offset = first_y - rotated.min_y;
    // scan_segments needs its first line at or above min_y.
    let (first_y, first_offset) = if first_offset < 0.0 {
        (first_y + spacing, first_offset + spacing)
    } else {
        (first_y, first_offset)
    };
    let core_rows = if rotated.rings.is_empty() {
        Vec::new()
    } else {
        scan_segments(&rotated, spacing, first_offset)
    };
    // Core intervals by global row index (rounded from their y).
    let row_of = |y: f64| ((y - first_y) / spacing).round() as i64;
    let mut by_row: std::collections::BTreeMap<i64, Vec<(f64, f64)>> = Default::default();
    for row in &core_rows {
        by_row
            .entry(row_of(row.y))
            .or_default()
            .push((row.start_x, row.end_x));
    }
    let quantile = match cut {
        EdgeCut::Balanced => MISSED_WEIGHT / (MISSED_WEIGHT + 1.0),
        _ => 0.0,
    };
    segments
        .iter()
        .map(|segment| {
            let lowest = row_of(segment.y - width_m / 2.0 + spacing / 2.0);
            let mut starts = Vec::with_capacity(ROWS);
            let mut ends = Vec::with_capacity(ROWS);
            for row in lowest..lowest + ROWS as i64 {
                let overlapping: Vec<&(f64, f64)> = by_row
                    .get(&row)
                    .into_iter()
                    .flatten()
                    .filter(|(low, high)| *low < segment.end_x && *high > segment.start_x)
                    .collect();
                // No core on this line along the swath: all of it is band, already sprayed.
                let start = overlapping
                    .iter()
                    .map(|(low, _)| *low)
                    .fold(segment.end_x, f64::min)
                    .max(segment.start_x);
                let end = overlapping
                    .iter()
                    .map(|(_, high)| *high)
                    .fold(segment.start_x, f64::max)
                    .min(segment.end_x);
                starts.push(start);
                ends.push(end);
            }
            starts.sort_by(f64::total_cmp);
            ends.sort_by(f64::total_cmp);
            // The end: the `quantile` of the e_i (the k/(k+1) one: most of the core reached);
            // the start likewise from the other side.
            let at = |sorted: &[f64], share: f64| {
                let index = ((share * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len());
                sorted[index - 1]
            };
            let (new_start, new_end) = match cut {
                EdgeCut::Gap => (starts[ROWS - 1], ends[0]),
                _ => (at(&starts, 1.0 - quantile), at(&ends, quantile)),
            };
            let (new_start, new_end) = (new_start.max(segment.start_x), new_end.min(segment.end_x));
            if new_end - new_start < SHORTEST_CUT_SWATH_M {
                *segment
            } else {
                Segment {
                    start_x: new_start,
                    end_x: new_end,
                    ..*segment
                }
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{polygon, Area, BooleanOps, Polygon};

    /// A 100 × 60 m field at heading 0 (swaths along x), one edge pass of w = 5 m: the core is
    /// x ∈ [5, 95]; swaths run on the pass line x ∈ [2.5, 97.5].
    fn square_case() -> (MultiPolygon<f64>, Vec<Segment>) {
        let innermost = MultiPolygon::new(vec![polygon![
            (x: 2.5, y: 2.5), (x: 97.5, y: 2.5), (x: 97.5, y: 57.5), (x: 2.5, y: 57.5)
        ]]);
        let segments = (0..10)
            .map(|line| Segment {
                line,
                y: 7.5 + 5.0 * line as f64,
                start_x: 2.5,
                end_x: 97.5,
            })
            .collect();
        (innermost, segments)
    }

    #[test]
    fn square_ends_stop_at_the_band_in_every_mode_but_overlap() {
        let (innermost, segments) = square_case();
        let frame = Frame::new(0.0);
        let kept = cut_swath_ends(&segments, &innermost, frame, 5.0, EdgeCut::Overlap);
        assert_eq!(kept, segments);
        for cut in [EdgeCut::Balanced, EdgeCut::Gap] {
            for segment in cut_swath_ends(&segments, &innermost, frame, 5.0, cut) {
                assert!((segment.start_x - 5.0).abs() < 1e-6, "{cut:?} {segment:?}");
                assert!((segment.end_x - 95.0).abs() < 1e-6, "{cut:?} {segment:?}");
            }
        }
    }

    /// An oblique end: the core's right edge runs at 45° across the swaths. `gap` leaves no
    /// double dose, `balanced` less than `overlap` and little missed (measured by overlay).
    #[test]
    fn oblique_ends_trade_double_dose_for_little_missed() {
        let core: Polygon<f64> =
            polygon![(x: 0.0, y: 0.0), (x: 100.0, y: 0.0), (x: 160.0, y: 60.0), (x: 0.0, y: 60.0)];
        let innermost = offset(&MultiPolygon::new(vec![core.clone()]), 2.5);
        let segments: Vec<Segment> = (0..10)
            .map(|line| {
                let y = 5.0 + 5.0 * line as f64;
                Segment {
                    line,
                    y,
                    start_x: 10.0,
                    // On the pass line: 2.5 m off the core edge, √2·2.5 along the swath.
                    end_x: 100.0 + y + 2.5 * 2f64.sqrt(),
                }
            })
            .collect();
        let figures = |cut: EdgeCut| {
            let cut_segments = cut_swath_ends(&segments, &innermost, Frame::new(0.0), 5.0, cut);
            let mut doubled = 0.0;
            let mut missed = 0.0;
            for segment in &cut_segments {
                let lane = MultiPolygon::new(vec![polygon![
                    (x: 10.0, y: segment.y - 2.5), (x: 400.0, y: segment.y - 2.5),
                    (x: 400.0, y: segment.y + 2.5), (x: 10.0, y: segment.y + 2.5)
                ]]);
                let strip =
                    MultiPolygon::new(vec![super::super::measure::swath_strip(segment, 5.0)]);
                let core = MultiPolygon::new(vec![core.clone()]);
                doubled += strip.difference(&core).unsigned_area();
                missed += lane.intersection(&core).difference(&strip).unsigned_area();
            }
            (doubled, missed)
        };
        let (overlap_d, overlap_m) = figures(EdgeCut::Overlap);
        let (balanced_d, balanced_m) = figures(EdgeCut::Balanced);
        let (gap_d, gap_m) = figures(EdgeCut::Gap);
        assert!(overlap_m < 1e-6, "{overlap_m}");
        assert!(gap_d < 0.05 * overlap_d, "{gap_d} {overlap_d}");
        assert!(balanced_d < 0.6 * overlap_d, "{balanced_d} {overlap_d}");
        assert!(balanced_m < 0.2 * gap_m, "{balanced_m} {gap_m}");
        // The k/(k+1) rule: per swath, D ≈ ((s+c)²) and M ≈ (c−s)² with s = c·(k−1)/(k+1).
        let k = MISSED_WEIGHT;
        let ratio = ((2.0 * k / (k + 1.0)) / (2.0 / (k + 1.0))).powi(2);
        assert!(
            (balanced_d / balanced_m / ratio - 1.0).abs() < 0.25,
            "{balanced_d} {balanced_m} {ratio}"
        );
    }

    #[test]
    fn edge_cuts_parse_from_their_names() {
        assert_eq!("gap".parse::<EdgeCut>(), Ok(EdgeCut::Gap));
        assert_eq!(" Balanced".parse::<EdgeCut>(), Ok(EdgeCut::Balanced));
        assert!("overlapping"
            .parse::<EdgeCut>()
            .unwrap_err()
            .contains("overlap, balanced or gap"));
    }
}
