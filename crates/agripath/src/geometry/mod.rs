//! Planar geometry in a local metric frame: projection to and from UTM, polygon validity.

pub mod detour;
pub mod projection;
pub mod ring_index;
pub mod validate;

pub use projection::{from_utm, to_utm, UtmZone};

use geo::{Coord, Polygon};

/// The rings of a polygon, shell first, as closed point lists.
pub fn rings(polygon: &Polygon<f64>) -> impl Iterator<Item = &[Coord<f64>]> {
    std::iter::once(polygon.exterior())
        .chain(polygon.interiors())
        .map(|ring| ring.0.as_slice())
}

/// Distance from `point` to the segment `start`–`end`, metres.
pub fn distance_to_segment(point: Coord<f64>, start: Coord<f64>, end: Coord<f64>) -> f64 {
    let (dx, dy) = (end.x - start.x, end.y - start.y);
    let length_squared = dx * dx + dy * dy;
    let t = if length_squared > 0.0 {
        (((point.x - start.x) * dx + (point.y - start.y) * dy) / length_squared).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (point.x - start.x - t * dx).hypot(point.y - start.y - t * dy)
}
