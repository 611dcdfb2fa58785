//! The sprayable region of a field and its headland: what is sprayed, the edge passes around
//! every boundary and hole, and the interior the swaths fill.
//!
//! sprayable = field − holes − obstacles (grown by the obstacle margin), shrunk by the
//! boundary margin. Edge pass k (k = 0..n) runs along the boundary of `sprayable` shrunk by
//! (k + ½)·w, so its strip covers the band [k·w, (k+1)·w] from every edge; the interior
//! swaths then fill the region inside the innermost pass line and reach it, so that no sliver
//! is left where a swath end meets a slanted edge (the seed's layout leaves 2-4 % there).

use geo::algorithm::buffer::{Buffer, BufferStyle, LineJoin};
use geo::{BooleanOps, BoundingRect, Coord, Intersects, MultiPolygon, Polygon};

use crate::model::{Field, Obstacle};

/// Sharpest corner kept sharp by offsets, radians: real field corners are kept, only spikes
/// are bevelled.
const MITER_LIMIT_ANGLE_RAD: f64 = 0.2;

/// Grows (distance > 0) or shrinks (< 0) a region with mitred corners.
pub fn offset(region: &MultiPolygon<f64>, distance: f64) -> MultiPolygon<f64> {
    if distance == 0.0 {
        return region.clone();
    }
    region.buffer_with_style(
        BufferStyle::new(distance).line_join(LineJoin::Miter(MITER_LIMIT_ANGLE_RAD)),
    )
}

/// The field less its obstacles, shrunk by the boundary margin.
pub fn sprayable_region(
    field: &Field,
    obstacles: &[Obstacle],
    boundary_margin_m: f64,
    obstacle_margin_m: f64,
) -> MultiPolygon<f64> {
    let mut region = MultiPolygon::new(vec![field.polygon.clone()]);
    let field_box = field.polygon.bounding_rect();
    let touching: Vec<&Polygon<f64>> = obstacles
        .iter()
        .map(|obstacle| &obstacle.polygon)
        .filter(|polygon| match (polygon.bounding_rect(), field_box) {
            (Some(obstacle_box), Some(field_box)) => {
                let grown = obstacle_margin_m.max(0.0);
                obstacle_box.min().x - grown <= field_box.max().x
                    && obstacle_box.max().x + grown >= field_box.min().x
                    && obstacle_box.min().y - grown <= field_box.max().y
                    && obstacle_box.max().y + grown >= field_box.min().y
            }
            _ => false,
        })
        .filter(|polygon| obstacle_margin_m > 0.0 || polygon.intersects(&field.polygon))
        .collect();
    // Boolean operations snap coordinates to a fine integer grid; a field without obstacles
    // or margins keeps its exact vertices (Table 7 is computed on them).
    for polygon in touching {
        let grown = offset(&MultiPolygon::new(vec![polygon.clone()]), obstacle_margin_m);
        region = region.difference(&grown);
    }
    if !field.sprayed_with_others.is_empty() {
        // Not grown by the obstacle margin: they are crop, sprayed with the other field.
        region = region.difference(&field.sprayed_by_others());
    }
    offset(&region, -boundary_margin_m)
}

/// The closed rings of a region (outer boundaries and holes), first point repeated last.
pub fn rings(region: &MultiPolygon<f64>) -> Vec<Vec<Coord<f64>>> {
    region
        .0
        .iter()
        .flat_map(|polygon| std::iter::once(polygon.exterior()).chain(polygon.interiors()))
        .filter(|ring| ring.0.len() >= 4)
        .map(|ring| ring.0.clone())
        .collect()
}

/// Edge pass regions (the lines are their rings) for `passes` passes of width `width_m`.
pub fn edge_pass_regions(
    sprayable: &MultiPolygon<f64>,
    passes: usize,
    width_m: f64,
) -> Vec<MultiPolygon<f64>> {
    (0..passes)
        .map(|pass| offset(sprayable, -(pass as f64 + 0.5) * width_m))
        .filter(|region| !region.0.is_empty())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::{Area, LineString};

    fn square(min: f64, max: f64) -> Polygon<f64> {
        Polygon::new(
            LineString::from(vec![
                (min, min),
                (max, min),
                (max, max),
                (min, max),
                (min, min),
            ]),
            vec![],
        )
    }

    #[test]
    fn obstacles_and_margins_shrink_the_sprayable_area() {
        let field = Field::new("f", square(0.0, 100.0));
        let obstacle = Obstacle {
            name: "o".into(),
            polygon: square(40.0, 60.0),
        };
        let plain = sprayable_region(&field, std::slice::from_ref(&obstacle), 0.0, 0.0);
        assert!((plain.unsigned_area() - (10_000.0 - 400.0)).abs() < 1e-6);
        // A 5 m safety margin grows the obstacle to 30 × 30 m (mitred corners stay square).
        let kept_away = sprayable_region(&field, std::slice::from_ref(&obstacle), 0.0, 5.0);
        assert!(
            (kept_away.unsigned_area() - (10_000.0 - 900.0)).abs() < 1.0,
            "{}",
            kept_away.unsigned_area()
        );
        // A 2 m boundary margin shrinks the field to 96 × 96 m.
        let inset = sprayable_region(&field, &[obstacle], 2.0, 0.0);
        assert!(
            (inset.unsigned_area() - (96.0 * 96.0 - 24.0 * 24.0)).abs() < 1.0,
            "{}",
            inset.unsigned_area()
        );
        // An obstacle off the field changes nothing.
        let far = Obstacle {
            name: "far".into(),
            polygon: square(200.0, 210.0),
        };
        assert_eq!(
            sprayable_region(&field, &[far], 0.0, 0.0).unsigned_area(),
            10_000.0
        );
    }
}
