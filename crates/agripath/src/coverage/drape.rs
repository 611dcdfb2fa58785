//! Draping swaths on the terrain (seed 001 §2.2): ① lines perpendicular to the swaths at
//! spacing `a`; ② their crossings split each swath; ③ heights at the crossings and the ends
//! come from the terrain; ④ the points joined in order are the 3D swath.
//!
//! The perpendicular lines are `x' = x_origin + m·a` in the rotated frame, with `x_origin` the
//! field's smallest rotated x, so neighbouring swaths are sampled at the same stations.

use geo::Coord;

use super::scan_lines::{Frame, Segment};
use crate::error::TerrainError;
use crate::terrain::Terrain;

/// A point of a draped path: planning-frame position and the terrain height under it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GroundPoint {
    /// Easting in the planning frame, metres.
    pub x: f64,
    /// Northing in the planning frame, metres.
    pub y: f64,
    /// Terrain height above sea level, metres.
    pub ground_m: f64,
}

/// Stations of a segment: its ends and every `x_origin + m·a` strictly between them.
fn stations(segment: &Segment, x_origin: f64, spacing: f64) -> impl Iterator<Item = f64> + '_ {
    let first = ((segment.start_x - x_origin) / spacing).floor() as i64 + 1;
    let inner = (first..)
        .map(move |m| x_origin + m as f64 * spacing)
        .take_while(move |&x| x < segment.end_x)
        .filter(move |&x| x > segment.start_x);
    std::iter::once(segment.start_x)
        .chain(inner)
        .chain(std::iter::once(segment.end_x))
}

/// The draped points of a segment, from `start_x` to `end_x`.
pub fn drape(
    segment: &Segment,
    frame: Frame,
    terrain: &dyn Terrain,
    x_origin: f64,
    spacing: f64,
) -> Result<Vec<GroundPoint>, TerrainError> {
    stations(segment, x_origin, spacing)
        .map(|x| {
            let point = frame.to_plan(Coord { x, y: segment.y });
            Ok(GroundPoint {
                x: point.x,
                y: point.y,
                ground_m: terrain.height_m(point.x, point.y)?,
            })
        })
        .collect()
}

/// 3D length of a segment draped on the terrain, metres, without keeping its points (the
/// heading search calls this 180 times per swath).
pub fn draped_length(
    segment: &Segment,
    frame: Frame,
    terrain: &dyn Terrain,
    x_origin: f64,
    spacing: f64,
) -> Result<f64, TerrainError> {
    let mut length = 0.0;
    let mut previous: Option<(f64, f64)> = None;
    for x in stations(segment, x_origin, spacing) {
        let point = frame.to_plan(Coord { x, y: segment.y });
        let height = terrain.height_m(point.x, point.y)?;
        if let Some((previous_x, previous_height)) = previous {
            length += (x - previous_x).hypot(height - previous_height);
        }
        previous = Some((x, height));
    }
    Ok(length)
}

/// 3D length of a polyline of ground points lifted by a constant height.
pub fn path_length_3d(points: &[GroundPoint]) -> f64 {
    points
        .windows(2)
        .map(|pair| {
            let (a, b) = (pair[0], pair[1]);
            ((b.x - a.x).powi(2) + (b.y - a.y).powi(2) + (b.ground_m - a.ground_m).powi(2)).sqrt()
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::{Flat, Plateau, Plateaus};

    #[test]
    fn stations_at_spacing_and_ends() {
        let segment = Segment {
            line: 0,
            y: 0.0,
            start_x: 3.0,
            end_x: 47.0,
        };
        let xs: Vec<f64> = stations(&segment, 0.0, 20.0).collect();
        assert_eq!(xs, [3.0, 20.0, 40.0, 47.0]);
    }

    #[test]
    fn flat_length_is_planar_and_a_plateau_adds_its_rims() {
        let segment = Segment {
            line: 0,
            y: 0.0,
            start_x: 0.0,
            end_x: 100.0,
        };
        let frame = Frame::new(0.0);
        let flat = draped_length(&segment, frame, &Flat::new(7.0), 0.0, 1.0).unwrap();
        assert!((flat - 100.0).abs() < 1e-9);
        let hill = Plateaus::new(
            0.0,
            vec![Plateau {
                center: [50.0, 0.0],
                radius_m: 10.0,
                height_m: 3.0,
                edge_ramp_m: 4.0,
            }],
        )
        .unwrap();
        let draped = draped_length(&segment, frame, &hill, 0.0, 1.0).unwrap();
        // Two rims of 4 m run and 3 m rise: each 5 m long instead of 4.
        assert!((draped - 102.0).abs() < 1e-9, "{draped}");
        let points = drape(&segment, frame, &hill, 0.0, 1.0).unwrap();
        assert!((path_length_3d(&points) - draped).abs() < 1e-9);
    }
}
