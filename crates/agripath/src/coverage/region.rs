//! The sprayable region of a field and its headland: what is sprayed, the edge passes around
//! every boundary and hole, and the interior the swaths fill.
//!
//! sprayable = field − holes − obstacles (grown by the obstacle margin), shrunk by the
//! boundary margin. Edge pass k (k = 0..n) runs along the boundary of `sprayable` shrunk by
//! (k + ½)·w, so its strip covers the band [k·w, (k+1)·w] from every edge; the interior
//! swaths then fill the region inside the innermost pass line and reach it, so that no sliver
//! is left where a swath end meets a slanted edge (the seed's layout leaves 2-4 % there).

use geo::algorithm::buffer::{Buffer, BufferStyle, LineJoin};
use geo::{Area, BooleanOps, BoundingRect, Coord, Intersects, MultiPolygon, Polygon};

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

/// Chord length over radius of the arcs [`reachable_region`] draws (0.1: chords 25 cm long on
/// a 2.5 m radius, 3 mm inside the arc).
const ARC_SEGMENT_PER_RADIUS: f64 = 0.1;

/// The part of `sprayable` a spray footprint `width_m` across can reach without spraying
/// outside it: the morphological opening of the region by a disc of diameter `width_m`
/// (erode by w/2, then grow by w/2, round joins), the ground a circular footprint can cover
/// in the configuration-space view of coverage (Choset 2001, docs/references.md). What it leaves out is where
/// the region is narrower than one swath: the tip of a corner sharper than 90° (area
/// (w/2)²·(cot(θ/2) − (π − θ)/2) for a corner of angle θ), a neck between two holes or
/// between a hole and the boundary, a sliver. Ground there can only be sprayed by spraying
/// outside too, or by passes shorter than their own width; the preflight reports it as
/// unreachable instead of missed (decision 0023).
pub fn reachable_region(sprayable: &MultiPolygon<f64>, width_m: f64) -> MultiPolygon<f64> {
    if width_m <= 0.0 || sprayable.0.is_empty() {
        return sprayable.clone();
    }
    let round = |region: &MultiPolygon<f64>, distance: f64| {
        region.buffer_with_style(
            BufferStyle::new(distance).line_join(LineJoin::Round(ARC_SEGMENT_PER_RADIUS)),
        )
    };
    // A strip one swath wide is reachable (its pass line, [`pass_region`], is snapped too).
    let radius = width_m / 2.0 - STRIP_SNAP_M;
    let eroded = round(sprayable, -radius);
    if eroded.0.is_empty() {
        return eroded;
    }
    // The grown region's arcs lie on the chords inside the true arcs, and its straight
    // edges on the original ones up to rounding: clip to the region so that nothing
    // outside it is ever called reachable.
    round(&eroded, radius).intersection(sprayable)
}

/// Smallest piece of [`unreachable_part`] kept, m²: below it a piece is the rounding of the
/// offsets along a straight edge, not ground.
const LEAST_UNREACHABLE_M2: f64 = 0.01;

/// The ground of `sprayable` outside its `reachable` part ([`reachable_region`]), without
/// the slivers the offsets' rounding leaves along straight edges.
pub fn unreachable_part(
    sprayable: &MultiPolygon<f64>,
    reachable: &MultiPolygon<f64>,
) -> MultiPolygon<f64> {
    MultiPolygon::new(
        sprayable
            .difference(reachable)
            .0
            .into_iter()
            .filter(|piece| piece.unsigned_area() >= LEAST_UNREACHABLE_M2)
            .collect(),
    )
}

/// Per field, the patches of ground the map and `plan.geojson` draw apart from what was
/// sprayed, as the preflight found them flying the mission files (decision 0023).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GroundPatches {
    /// Ground no swath reaches without spraying outside (sharp tips, corners, necks).
    pub unreachable: Vec<MultiPolygon<f64>>,
    /// Reachable ground the flight left unsprayed.
    pub missed: Vec<MultiPolygon<f64>>,
    /// Where the preflight's checks failed (plan metres; at most 200 per check): the map of
    /// an unsafe plan marks them (decision 0028).
    pub failures: Vec<[f64; 2]>,
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
        .map(|pass| pass_region(sprayable, (pass as f64 + 0.5) * width_m, width_m))
        .filter(|region| !region.0.is_empty())
        .collect()
}

/// How much nearer the edge than w/2 a pass line may lie where the field is a strip
/// (the pass regions, [`reachable_region`]), metres: a strip drawn one swath wide measures
/// a hair either side of it once projected.
pub const STRIP_SNAP_M: f64 = 0.001;

/// `sprayable` shrunk by `inset_m`; but where the region shrunk by [`STRIP_SNAP_M`] less is
/// a sliver (a strip about one swath wide, [`crate::coverage::sliver`]), that sliver whole:
/// shrunk by exactly w/2, a strip one swath wide leaves stray pieces of ring that the
/// offsets' rounding decides (a trial's 5 m terrace: 62.7 % of it covered; decision 0039).
fn pass_region(sprayable: &MultiPolygon<f64>, inset_m: f64, width_m: f64) -> MultiPolygon<f64> {
    let strict = offset(sprayable, -inset_m);
    // The edge passes' own test (`sliver_midline`), on a piece without holes: a ring at a
    // time.
    let is_sliver = |polygon: &Polygon<f64>| {
        use geo::{Euclidean, Length};
        polygon.interiors().is_empty()
            && crate::coverage::sliver::is_sliver(
                polygon.unsigned_area(),
                Euclidean.length(polygon.exterior()),
                width_m,
            )
    };
    // A strip about one swath wide leaves nothing or a sliver shrunk strictly: only then is
    // the region shrunk again, snapped (no second offset per pass on other fields).
    if !strict.0.is_empty() && !strict.0.iter().any(is_sliver) {
        return strict;
    }
    let snapped = offset(sprayable, -(inset_m - STRIP_SNAP_M));
    if !snapped.0.iter().any(is_sliver) {
        return strict;
    }
    let mut pieces = Vec::new();
    for polygon in snapped.0 {
        if is_sliver(&polygon) {
            pieces.push(polygon);
        } else {
            pieces.extend(
                strict
                    .0
                    .iter()
                    .filter(|piece| piece.intersects(&polygon))
                    .cloned(),
            );
        }
    }
    MultiPolygon::new(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::LineString;

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
    fn the_reachable_region_leaves_out_sharp_tips_and_narrow_necks_only() {
        // A square is reachable but for its four corners' (1 − π/4)·(w/2)² each.
        let plain = MultiPolygon::new(vec![square(0.0, 100.0)]);
        let reachable = reachable_region(&plain, 5.0);
        let corners = 4.0 * (1.0 - std::f64::consts::FRAC_PI_4) * 2.5 * 2.5;
        let left = plain.unsigned_area() - reachable.unsigned_area();
        assert!((left - corners).abs() < 0.05, "{left} against {corners}");
        // A 30° tip: (w/2)²·(cot 15° − 75°) is left.
        let tip = MultiPolygon::new(vec![Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (100.0, -100.0 * 15f64.to_radians().tan()),
                (100.0, 100.0 * 15f64.to_radians().tan()),
                (0.0, 0.0),
            ]),
            vec![],
        )]);
        let theta = 30f64.to_radians();
        let expected =
            2.5 * 2.5 * (1.0 / (theta / 2.0).tan() - (std::f64::consts::PI - theta) / 2.0);
        let tip_left = tip.unsigned_area() - reachable_region(&tip, 5.0).unsigned_area();
        // The other two corners are 75° each: (w/2)²·(cot 37.5° − 52.5°) apiece.
        let other = 2.0 * 2.5 * 2.5 * (1.0 / 37.5f64.to_radians().tan() - 52.5f64.to_radians());
        assert!(
            (tip_left - expected - other).abs() < 0.1,
            "{tip_left} against {}",
            expected + other
        );
        // A neck 3 m wide between two holes is unreachable for a 5 m swath, not for a 2 m one.
        let with_holes = MultiPolygon::new(vec![Polygon::new(
            square(0.0, 100.0).exterior().clone(),
            vec![
                LineString::from(vec![
                    (20.0, 40.0),
                    (48.5, 40.0),
                    (48.5, 60.0),
                    (20.0, 60.0),
                    (20.0, 40.0),
                ]),
                LineString::from(vec![
                    (51.5, 40.0),
                    (80.0, 40.0),
                    (80.0, 60.0),
                    (51.5, 60.0),
                    (51.5, 40.0),
                ]),
            ],
        )]);
        let neck = 3.0 * 20.0;
        let wide = with_holes.unsigned_area() - reachable_region(&with_holes, 5.0).unsigned_area();
        let narrow =
            with_holes.unsigned_area() - reachable_region(&with_holes, 2.0).unsigned_area();
        assert!(wide > neck, "{wide}");
        assert!(narrow < 5.0, "{narrow}");
        // Nothing outside the region is ever reachable.
        assert!(
            reachable_region(&with_holes, 5.0)
                .difference(&with_holes)
                .unsigned_area()
                < 1e-6
        );
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
