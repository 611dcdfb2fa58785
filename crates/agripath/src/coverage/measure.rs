//! How well a layout covers its field: the sprayed strips (every pass ± w/2) against the
//! sprayable region, with exact polygon overlay.

use geo::algorithm::bool_ops::unary_union;
use geo::{Area, BooleanOps, Coord, LineString, MultiPolygon, Polygon};
use serde::Serialize;

use super::region::offset;
use super::scan_lines::{Frame, Segment};

#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CoverageMeasure {
    /// Sprayable area, m².
    pub sprayable_area_m2: f64,
    /// Share of the sprayable area under at least one strip, 0..1.
    pub covered_fraction: f64,
    /// Area sprayed more than once, m² (counted once per extra pass).
    pub overlap_m2: f64,
    /// Strip area outside the sprayable region (over holes, obstacles or off the field), m².
    pub outside_m2: f64,
}

/// The strip one swath sprays: its segment widened by w/2 on each side, square ends.
pub fn swath_strip(segment: &Segment, frame: Frame, width_m: f64) -> Polygon<f64> {
    let half = width_m / 2.0;
    let corners = [
        (segment.start_x, segment.y - half),
        (segment.end_x, segment.y - half),
        (segment.end_x, segment.y + half),
        (segment.start_x, segment.y + half),
        (segment.start_x, segment.y - half),
    ];
    Polygon::new(
        LineString::new(
            corners
                .iter()
                .map(|&(x, y)| frame.to_plan(Coord { x, y }))
                .collect(),
        ),
        vec![],
    )
}

/// The band an edge pass sprays: its line widened by w/2 on each side.
pub fn edge_strip(pass_region: &MultiPolygon<f64>, width_m: f64) -> MultiPolygon<f64> {
    offset(pass_region, width_m / 2.0).difference(&offset(pass_region, -width_m / 2.0))
}

/// Measures `strips` against `sprayable`.
pub fn measure(sprayable: &MultiPolygon<f64>, strips: &[MultiPolygon<f64>]) -> CoverageMeasure {
    let sprayable_area = sprayable.unsigned_area();
    if strips.is_empty() || sprayable_area == 0.0 {
        return CoverageMeasure {
            sprayable_area_m2: sprayable_area,
            covered_fraction: 0.0,
            overlap_m2: 0.0,
            outside_m2: 0.0,
        };
    }
    let union = unary_union(strips.iter());
    let covered = union.intersection(sprayable).unsigned_area();
    let inside_sum: f64 = strips
        .iter()
        .map(|strip| strip.intersection(sprayable).unsigned_area())
        .sum();
    CoverageMeasure {
        sprayable_area_m2: sprayable_area,
        covered_fraction: covered / sprayable_area,
        overlap_m2: (inside_sum - covered).max(0.0),
        outside_m2: union.difference(sprayable).unsigned_area(),
    }
}
