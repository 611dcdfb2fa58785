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
//! The same holds at every x along the swath, not only at its ends: let c(x) be the share
//! of the lines across the swath on which x is core. Spraying [x, x + dx] sprays twice
//! (1 − c)·w·dx, leaving it misses c·w·dx. So the cut is pointwise: spray where
//!
//! - `overlap`: everywhere (today's swath, ends on the pass line): M = 0, D largest;
//! - `gap`: c = 1 (the whole width is core): D = 0 from the swaths;
//! - `balanced` (the default): the least double dose for a floor on coverage. The pointwise
//!   rule "spray where c > j/rows" minimises D + λ·M at every point for λ = (rows − j)/j, so
//!   the levels j = rows − 1, …, 0 run from `gap` to nearly `overlap`; in each field the cut
//!   takes the highest level whose missed core M is at most [`MISSED_BUDGET_SHARE`] of the
//!   field's sprayable area (0.3 %: with what the edge passes miss in corners, it keeps the
//!   coverage as flown at 99.63 % or more on the benchmark fields, above the 99.5 %
//!   and the preflight's 99 %), and the swaths as they were if no level fits. Where a square
//!   end meets the band at a slant this trades the triangle between them; along a swath
//!   that runs beside the band (the first swath along a slanted side, a swath grazing a
//!   hole's band) it turns the sprayer off where most of its width is band. A field whose
//!   swaths meet the band square (a rectangle along its sides) gets `gap`'s cut: no double
//!   dose and nothing missed.
//!
//! Gaps shorter than `SHORTEST_GAP_M` are sprayed through, pieces shorter than
//! `SHORTEST_CUT_SWATH_M` are not flown; a swath may come out as several pieces (as a
//! hole splits one). The core is the innermost pass region eroded by w/2 with round joins,
//! which is where the pass's flown strip (rectangles with round turns) ends: with it `gap`
//! leaves no swath/edge double dose at all (0.00 % of the area on the benchmark farms,
//! against 1.40 % with the mitred core).
//!
//! No piece reaches past today's ends, so no cut sprays more or leaves the sprayable region.

use std::str::FromStr;

use geo::MultiPolygon;
use serde::Serialize;

use geo::algorithm::buffer::{Buffer, BufferStyle, LineJoin};

use super::region::rings;
use super::scan_lines::{scan_segments, Frame, RotatedRings, Segment};

/// The most core ground `balanced` may leave unsprayed in a field, as a share of the field's
/// sprayable area.
pub const MISSED_BUDGET_SHARE: f64 = 0.003;
/// Chord over radius of the core's round joins (0.1: 3 mm inside the arc at w = 5 m).
const CORE_ARC_SEGMENT_PER_RADIUS: f64 = 0.1;
/// Lines across a swath on which the core's end is sampled.
const ROWS: usize = 32;
/// Shortest piece of swath a cut leaves, metres; a shorter one is not flown.
const SHORTEST_CUT_SWATH_M: f64 = 1.0;
/// Shortest gap a cut opens in a swath, metres: the sprayer stays on over a shorter one.
const SHORTEST_GAP_M: f64 = 1.0;

/// Where a swath's spray on/off points sit where it runs into the edge-pass band.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeCut {
    /// On the innermost pass line: no gap, the most double dose (the layout before issue 22).
    Overlap,
    /// Least double-sprayed area with at most [`MISSED_BUDGET_SHARE`] of the field missed;
    /// the default, as on the command line (decision 0019).
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

/// The core of a field: the sprayable region inside the band of its innermost edge pass,
/// computed once and cut against at any heading.
pub struct Core {
    rings: Vec<Vec<geo::Coord<f64>>>,
}

impl Core {
    /// The core inside `innermost`, the innermost pass's region (its ring the pass line), for
    /// passes `width_m` wide.
    pub fn new(innermost: &MultiPolygon<f64>, width_m: f64) -> Self {
        // Round joins: where the pass line turns away from the core (a concave corner of the
        // field) the pass sprays the disc of its turn, which a mitred core would call core
        // and leave the swaths to spray again.
        let core = innermost.buffer_with_style(
            BufferStyle::new(-width_m / 2.0)
                .line_join(LineJoin::Round(CORE_ARC_SEGMENT_PER_RADIUS)),
        );
        Self {
            rings: rings(&core),
        }
    }
}

/// The pieces of swath a cut leaves, and what they spray twice.
#[derive(Debug, Clone, PartialEq)]
pub struct CutSwaths {
    /// The pieces to spray, in the order of the swaths they come from.
    pub segments: Vec<Segment>,
    /// Band the pieces spray again, m²: their strips less the core under them, as sampled by
    /// the cut's lines.
    pub double_m2: f64,
}

/// Cuts `segments` (rotated frame `frame`, swaths `width_m` apart) by `cut` against `core`:
/// the pieces of each swath to spray.
pub fn cut_swath_ends(
    segments: &[Segment],
    core: &Core,
    frame: Frame,
    width_m: f64,
    cut: EdgeCut,
    missed_budget_m2: f64,
) -> CutSwaths {
    if segments.is_empty() {
        return CutSwaths {
            segments: Vec::new(),
            double_m2: 0.0,
        };
    }
    let core_rings = &core.rings;
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
    // Each swath's depth profile: how many of its ROWS lines are core, piece by piece.
    let mut events: Vec<(f64, i32)> = Vec::new();
    let profiles: Vec<Vec<(f64, f64, usize)>> = segments
        .iter()
        .map(|segment| {
            let lowest = row_of(segment.y - width_m / 2.0 + spacing / 2.0);
            events.clear();
            for row in lowest..lowest + ROWS as i64 {
                for &(low, high) in by_row.get(&row).into_iter().flatten() {
                    let (low, high) = (low.max(segment.start_x), high.min(segment.end_x));
                    if high > low {
                        events.push((low, 1));
                        events.push((high, -1));
                    }
                }
            }
            // Ends before starts at one x: two core intervals that only touch leave no gap.
            events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            let mut profile = Vec::with_capacity(events.len());
            let mut depth = 0i32;
            for pair in events.windows(2) {
                depth += pair[0].1;
                if pair[1].0 > pair[0].0 && depth > 0 {
                    profile.push((pair[0].0, pair[1].0, depth as usize));
                }
            }
            profile
        })
        .collect();
    let cut_at = |level: usize| {
        let mut pieces: Vec<Segment> = Vec::with_capacity(segments.len());
        let mut missed_m2 = 0.0;
        let mut double_m2 = 0.0;
        for (segment, profile) in segments.iter().zip(&profiles) {
            let first_piece = pieces.len();
            for &(from, to, depth) in profile {
                if depth <= level {
                    continue;
                }
                // Spray stays on over a gap shorter than SHORTEST_GAP_M.
                match pieces[first_piece..].last_mut() {
                    Some(last) if from - last.end_x < SHORTEST_GAP_M => last.end_x = to,
                    _ => pieces.push(Segment {
                        start_x: from,
                        end_x: to,
                        ..*segment
                    }),
                }
            }
            let mut kept = first_piece;
            for index in first_piece..pieces.len() {
                if pieces[index].end_x - pieces[index].start_x >= SHORTEST_CUT_SWATH_M {
                    pieces[kept] = pieces[index];
                    kept += 1;
                }
            }
            pieces.truncate(kept);
            // M of this swath: core under no piece is missed.
            let own = &pieces[first_piece..];
            let sprayed_of = |from: f64, to: f64| -> f64 {
                own.iter()
                    .map(|piece| (to.min(piece.end_x) - from.max(piece.start_x)).max(0.0))
                    .sum()
            };
            let mut core_sprayed_m2 = 0.0;
            for &(from, to, depth) in profile {
                let sprayed = sprayed_of(from, to);
                missed_m2 += depth as f64 * spacing * (to - from - sprayed);
                core_sprayed_m2 += depth as f64 * spacing * sprayed;
            }
            let sprayed_length: f64 = own.iter().map(Segment::length).sum();
            double_m2 += width_m * sprayed_length - core_sprayed_m2;
        }
        (pieces, missed_m2, double_m2)
    };
    // The swaths whole: all of their strips but the core under them is sprayed twice.
    let whole = || {
        let core_m2: f64 = profiles
            .iter()
            .flatten()
            .map(|&(from, to, depth)| depth as f64 * spacing * (to - from))
            .sum();
        let length: f64 = segments.iter().map(Segment::length).sum();
        (segments.to_vec(), 0.0, width_m * length - core_m2)
    };
    let (segments, _, double_m2) = match cut {
        EdgeCut::Overlap => whole(),
        EdgeCut::Gap => cut_at(ROWS - 1),
        // The pointwise rule at every level (spray where more than `level` lines are core),
        // from the least sprayed down (each level sprays a superset of the one above, so the
        // least double dose): the first whose missed core fits the budget. If none does, the
        // swaths as they were (no cut misses nothing).
        EdgeCut::Balanced => (0..ROWS)
            .rev()
            .map(cut_at)
            .find(|(_, missed_m2, _)| *missed_m2 <= missed_budget_m2)
            .unwrap_or_else(whole),
    };
    CutSwaths {
        segments,
        double_m2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::region::offset;
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
        let core = Core::new(&innermost, 5.0);
        let kept = cut_swath_ends(&segments, &core, frame, 5.0, EdgeCut::Overlap, 0.0);
        assert_eq!(kept.segments, segments);
        // Each swath reaches 2.5 m into the band at both ends: 10 × 2 × 2.5 × 5 m².
        assert!((kept.double_m2 - 250.0).abs() < 1e-6, "{}", kept.double_m2);
        // With no missed ground allowed at all, `balanced` still cuts square ends to the core.
        for cut in [EdgeCut::Balanced, EdgeCut::Gap] {
            let cut_swaths = cut_swath_ends(&segments, &core, frame, 5.0, cut, 0.0);
            assert!(
                cut_swaths.double_m2.abs() < 1e-6,
                "{cut:?} {}",
                cut_swaths.double_m2
            );
            for segment in cut_swaths.segments {
                assert!((segment.start_x - 5.0).abs() < 1e-6, "{cut:?} {segment:?}");
                assert!((segment.end_x - 95.0).abs() < 1e-6, "{cut:?} {segment:?}");
            }
        }
    }

    /// An oblique end: the core's right edge runs at 45° across the swaths. `gap` leaves no
    /// double dose; `balanced` misses no more than its budget (measured by overlay, not by
    /// the cut's own sums) and doubles less the more it may miss.
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
        let core_of_cut = Core::new(&innermost, 5.0);
        let figures = |cut: EdgeCut, budget_m2: f64| {
            let cut_swaths = cut_swath_ends(
                &segments,
                &core_of_cut,
                Frame::new(0.0),
                5.0,
                cut,
                budget_m2,
            );
            let cut_segments = cut_swaths.segments;
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
            // The cut's own double dose, from its 32 lines, against the overlay's.
            assert!(
                (cut_swaths.double_m2 - doubled).abs() <= 0.02 * doubled + 0.5,
                "{cut:?} {budget_m2}: {} against {doubled}",
                cut_swaths.double_m2
            );
            (doubled, missed)
        };
        let (overlap_d, overlap_m) = figures(EdgeCut::Overlap, 0.0);
        let (gap_d, gap_m) = figures(EdgeCut::Gap, 0.0);
        assert!(overlap_m < 1e-6, "{overlap_m}");
        assert!(gap_d < 0.05 * overlap_d, "{gap_d} {overlap_d}");
        let mut last_doubled = f64::INFINITY;
        for share in [0.0, 0.05, 0.2, 0.5] {
            let budget_m2 = share * gap_m;
            let (doubled, missed) = figures(EdgeCut::Balanced, budget_m2);
            // The overlay's strips end exactly where the cut's 32 lines say; a little slack
            // for the lines' sampling of the slanted edge.
            assert!(
                missed <= budget_m2 + 0.02 * gap_m,
                "{share}: {missed} > {budget_m2}"
            );
            assert!(
                doubled <= last_doubled + 1e-6,
                "{share}: {doubled} > {last_doubled}"
            );
            last_doubled = doubled;
        }
        assert!(last_doubled < 0.3 * overlap_d, "{last_doubled} {overlap_d}");
    }

    /// A swath that runs beside the band: the core (y ≥ 5) covers the upper 70 % of its
    /// width on x < 50 and 10 % on x > 50 (about 25 m² of core). `gap` sprays none of it,
    /// `overlap` all of it; `balanced` only x < 50 when it may miss the 25 m², all of it when
    /// it may not.
    #[test]
    fn a_swath_beside_the_band_is_sprayed_only_where_most_of_it_is_core() {
        let innermost = MultiPolygon::new(vec![polygon![
            (x: -2.5, y: 1.5), (x: 50.0, y: 1.5), (x: 50.0, y: 4.5),
            (x: 102.5, y: 4.5), (x: 102.5, y: 40.0), (x: -2.5, y: 40.0)
        ]]);
        let segment = Segment {
            line: 0,
            y: 5.0,
            start_x: 0.0,
            end_x: 100.0,
        };
        let frame = Frame::new(0.0);
        let core = Core::new(&innermost, 5.0);
        let cut = |mode, budget_m2| {
            cut_swath_ends(&[segment], &core, frame, 5.0, mode, budget_m2).segments
        };
        assert_eq!(cut(EdgeCut::Overlap, 0.0), vec![segment]);
        assert!(
            cut(EdgeCut::Gap, 0.0).is_empty(),
            "{:?}",
            cut(EdgeCut::Gap, 0.0)
        );
        let whole = cut(EdgeCut::Balanced, 10.0);
        assert_eq!(whole.len(), 1, "{whole:?}");
        assert!(whole[0].end_x > 99.0, "{whole:?}");
        let balanced = cut(EdgeCut::Balanced, 40.0);
        assert_eq!(balanced.len(), 1, "{balanced:?}");
        assert!(balanced[0].start_x.abs() < 1e-9, "{balanced:?}");
        // Where the core's share steps down from 70 % to 10 %: the band's step at x = 50,
        // eroded by half a swath.
        assert!((balanced[0].end_x - 47.5).abs() < 1.0, "{balanced:?}");
    }

    #[test]
    fn the_library_default_is_the_command_line_default() {
        let command_line = crate::request::plan::PlanOptions::default().edge_cut;
        assert_eq!(command_line.parse::<EdgeCut>(), Ok(EdgeCut::default()));
        assert_eq!(EdgeCut::default(), EdgeCut::Balanced);
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
