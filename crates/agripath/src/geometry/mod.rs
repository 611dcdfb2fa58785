//! Planar geometry in a local metric frame: projection to and from UTM, polygon validity.

pub mod detour;
pub mod projection;
pub mod ring_index;
pub mod validate;

/// The compass bearing of a swath line, 0..180° (0° = north, clockwise), from the seed's
/// heading (degrees from east, counter-clockwise). A line has two directions; the bearing
/// given is the one below 180°: an east-west line is 90°.
pub fn swath_bearing_deg(heading_deg: f64) -> f64 {
    (90.0 - heading_deg).rem_euclid(180.0)
}

/// The true bearing, 0..180°, of a swath line at the seed's `heading_deg` in a frame whose
/// north lies `grid_north_bearing_deg` clockwise of true north (a line's two directions are
/// one bearing, and a hair under 180° reads 0°).
pub fn true_swath_bearing_deg(heading_deg: f64, grid_north_bearing_deg: f64) -> f64 {
    let bearing = (swath_bearing_deg(heading_deg) + grid_north_bearing_deg).rem_euclid(180.0);
    if bearing > 180.0 - 1e-9 {
        0.0
    } else {
        bearing
    }
}

/// The seed's heading (degrees from east, counter-clockwise, 0..180°) of a line at compass
/// bearing `bearing_deg`: the inverse of [`swath_bearing_deg`].
pub fn heading_of_bearing_deg(bearing_deg: f64) -> f64 {
    (90.0 - bearing_deg).rem_euclid(180.0)
}

pub use projection::{from_utm, mean_longitude, to_utm, wrap_longitude, UtmZone};

use geo::{Coord, Polygon};

/// Changes of direction at the vertices of `polyline` sharper than `tolerance_rad` (contract
/// decision 5, docs/contract.md: every angle counts, so a tolerance only absorbs float noise or draping
/// wiggles). The one turn counter of the coverage routes and the grid routes.
pub fn turn_count(polyline: &[Coord<f64>], tolerance_rad: f64) -> usize {
    polyline
        .windows(3)
        .filter(|triple| {
            let (a, b, c) = (triple[0], triple[1], triple[2]);
            let incoming = (b.x - a.x, b.y - a.y);
            let outgoing = (c.x - b.x, c.y - b.y);
            let cross = incoming.0 * outgoing.1 - incoming.1 * outgoing.0;
            let dot = incoming.0 * outgoing.0 + incoming.1 * outgoing.1;
            cross.atan2(dot).abs() > tolerance_rad
        })
        .count()
}

/// The rings of a polygon, shell first, as closed point lists.
pub fn rings(polygon: &Polygon<f64>) -> impl Iterator<Item = &[Coord<f64>]> {
    std::iter::once(polygon.exterior())
        .chain(polygon.interiors())
        .map(|ring| ring.0.as_slice())
}

/// The lowest and highest corner of `points`' bounding box (infinite for no points).
pub fn bounds(points: &[Coord<f64>]) -> (Coord<f64>, Coord<f64>) {
    let mut low = Coord {
        x: f64::INFINITY,
        y: f64::INFINITY,
    };
    let mut high = Coord {
        x: f64::NEG_INFINITY,
        y: f64::NEG_INFINITY,
    };
    for point in points {
        low.x = low.x.min(point.x);
        low.y = low.y.min(point.y);
        high.x = high.x.max(point.x);
        high.y = high.y.max(point.y);
    }
    (low, high)
}

/// Where a leg `length` long is sampled when it is checked against the terrain: both ends
/// and at most every `spacing`, as fractions of the leg from 0 to 1 (the mission preflight
/// and the track verdict both sample every 1 m).
pub fn leg_samples(length: f64, spacing: f64) -> impl Iterator<Item = f64> {
    let steps = ((length / spacing).ceil() as usize).max(1);
    (0..=steps).map(move |k| k as f64 / steps as f64)
}

/// Distance from `point` to the segment `start`–`end`, metres.
pub fn distance_to_segment(point: Coord<f64>, start: Coord<f64>, end: Coord<f64>) -> f64 {
    let t = nearest_fraction_on_segment(point, start, end);
    let (dx, dy) = (end.x - start.x, end.y - start.y);
    (point.x - start.x - t * dx).hypot(point.y - start.y - t * dy)
}

/// Where on the segment `start`–`end` lies the point nearest `point`, as a fraction of it
/// from 0 to 1 (0 for a segment of no length).
pub fn nearest_fraction_on_segment(point: Coord<f64>, start: Coord<f64>, end: Coord<f64>) -> f64 {
    let (dx, dy) = (end.x - start.x, end.y - start.y);
    let length_squared = dx * dx + dy * dy;
    if length_squared > 0.0 {
        (((point.x - start.x) * dx + (point.y - start.y) * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod bearing_tests {
    use super::*;

    #[test]
    fn bearings_are_compass_angles_of_the_swath_line() {
        // East-west swaths (the seed's 0° or 180°) run at bearing 90°; north-south at 0°.
        assert_eq!(swath_bearing_deg(0.0), 90.0);
        assert_eq!(swath_bearing_deg(90.0), 0.0);
        assert!((swath_bearing_deg(175.8) - 94.2).abs() < 1e-9);
        // A line from south-west to north-east: 45° from east is bearing 45°.
        assert_eq!(swath_bearing_deg(45.0), 45.0);
        assert_eq!(swath_bearing_deg(135.0), 135.0);
        for heading in [0.0, 12.5, 89.9, 90.0, 133.0, 179.9] {
            let back = heading_of_bearing_deg(swath_bearing_deg(heading));
            assert!((back - heading).abs() < 1e-9, "{heading} -> {back}");
        }
    }
}
