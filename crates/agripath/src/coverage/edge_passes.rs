//! The edge passes: one pass along every ring of each pass region (the field's boundary and
//! its holes' walls, grown inwards pass by pass), draped on the terrain.

use geo::{Area, Coord, MultiPolygon};

use super::drape::{path_length_3d, GroundPoint};
use super::region::rings;
use super::{edge_corners, sliver, EdgePass};
use crate::error::Fault;
use crate::terrain::Terrain;

/// The ground an edge pass covers and where it may spray.
pub(super) struct EdgeLayout<'a> {
    /// The field's number.
    pub field: usize,
    /// Its sprayable region ([`super::region::sprayable_region`]).
    pub sprayable: &'a MultiPolygon<f64>,
    /// The pass regions, whose rings the passes fly.
    pub pass_regions: &'a [MultiPolygon<f64>],
    /// The swath width, metres.
    pub width_m: f64,
}

/// Edge passes along every ring of each pass region, sampled every `spacing_m`: closed, or,
/// with `corner_width_m`, opened where a corner is cut ([`edge_corners`]); a ring round a
/// sliver once along its middle ([`sliver`]); and the corners cut.
pub(super) fn edge_passes(
    layout: &EdgeLayout,
    terrain: &dyn Terrain,
    spacing_m: f64,
    corner_width_m: Option<f64>,
) -> Result<(Vec<EdgePass>, edge_corners::CornerCuts), Fault> {
    let EdgeLayout {
        field,
        sprayable,
        pass_regions,
        width_m,
    } = *layout;
    let mut passes = Vec::new();
    let mut all_cuts = edge_corners::CornerCuts::default();
    for (pass, region) in pass_regions.iter().enumerate() {
        for ring in rings(region) {
            if geo::Polygon::new(geo::LineString::new(ring.clone()), vec![]).unsigned_area() == 0.0
            {
                continue;
            }
            let midline = sliver::sliver_midline(&ring, width_m, sprayable);
            let paths = match (midline, corner_width_m) {
                (Some(midline), _) => vec![midline],
                (None, Some(width_m)) => {
                    let cuts = edge_corners::cut_corners(&ring, region, width_m);
                    all_cuts.corners += cuts.corners;
                    all_cuts.double_saved_m2 += cuts.double_saved_m2;
                    cuts.paths
                }
                (None, None) => vec![ring],
            };
            let thin = |path| thinned(path, THIN_SHARE * width_m);
            for path in paths.into_iter().map(start_mid_side).map(thin) {
                let mut points = Vec::new();
                for pair in path.windows(2) {
                    let (start, end) = (pair[0], pair[1]);
                    let length = (end.x - start.x).hypot(end.y - start.y);
                    let steps = (length / spacing_m).ceil().max(1.0) as usize;
                    for step in 0..steps {
                        let t = step as f64 / steps as f64;
                        points.push(ground_point(
                            Coord {
                                x: start.x + t * (end.x - start.x),
                                y: start.y + t * (end.y - start.y),
                            },
                            terrain,
                        )?);
                    }
                }
                if let Some(&last) = path.last() {
                    points.push(ground_point(last, terrain)?);
                }
                passes.push(EdgePass {
                    field,
                    pass,
                    length_m: path_length_3d(&points),
                    points,
                });
            }
        }
    }
    Ok((passes, all_cuts))
}

/// A closed ring turned to start and end in the middle of its longest side. A pass's
/// spray strip ends square where it starts and where it stops: at a corner that leaves the
/// corner's square unsprayed (a third trial: 8.1 m² of a 20 m square field, 97.9 % covered as
/// flown; decision 0030); on a straight side the two ends meet. Open paths are kept.
fn start_mid_side(path: Vec<Coord<f64>>) -> Vec<Coord<f64>> {
    let closed = path.len() >= 4 && path.first() == path.last();
    if !closed {
        return path;
    }
    let corners = &path[..path.len() - 1];
    let count = corners.len();
    let side = |k: usize| {
        let (a, b) = (corners[k], corners[(k + 1) % count]);
        (b.x - a.x).hypot(b.y - a.y)
    };
    let longest = (0..count)
        .max_by(|&a, &b| side(a).total_cmp(&side(b)).then(b.cmp(&a)))
        .unwrap_or(0);
    let (a, b) = (corners[longest], corners[(longest + 1) % count]);
    let middle = Coord {
        x: (a.x + b.x) / 2.0,
        y: (a.y + b.y) / 2.0,
    };
    let mut turned = Vec::with_capacity(count + 2);
    turned.push(middle);
    turned.extend((1..=count).map(|k| corners[(longest + k) % count]));
    turned.push(middle);
    turned
}

/// The vertices of an edge pass's line that bend it by more than `tolerance_m`:
/// Douglas-Peucker, the line's ends kept. A boundary walked with a phone's GPS, grown
/// inwards, bends every 0.15 m, and each bend was a waypoint (the eleventh trial: 807 mission
/// items for a 0.29 ha field, 1,374 for a rectangle drawn with 2,000 points; 427 and 48 now;
/// decision 0039).
fn thinned(path: Vec<Coord<f64>>, tolerance_m: f64) -> Vec<Coord<f64>> {
    use geo::Simplify;
    if path.len() <= 3 {
        return path;
    }
    geo::LineString::new(path).simplify(tolerance_m).0
}

/// How far an edge pass's line may move when its vertices are thinned, as a share of the
/// swath: its spray strip's edge moves as far (5 cm of a 5 m swath; on the trial's walked
/// field 0.004 % of the spray fell outside, against 0.000 % before).
const THIN_SHARE: f64 = 0.01;

fn ground_point(point: Coord<f64>, terrain: &dyn Terrain) -> Result<GroundPoint, Fault> {
    Ok(GroundPoint {
        x: point.x,
        y: point.y,
        ground_m: terrain.height_m(point.x, point.y)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_closed_ring_starts_in_the_middle_of_its_longest_side_and_keeps_every_corner() {
        let corner = |x: f64, y: f64| Coord { x, y };
        let ring = vec![
            corner(0.0, 0.0),
            corner(10.0, 0.0),
            corner(10.0, 30.0),
            corner(0.0, 30.0),
            corner(0.0, 0.0),
        ];
        let turned = start_mid_side(ring.clone());
        assert_eq!(turned.first(), Some(&corner(10.0, 15.0)));
        assert_eq!(turned.last(), Some(&corner(10.0, 15.0)));
        assert_eq!(
            &turned[1..5],
            &[
                corner(10.0, 30.0),
                corner(0.0, 30.0),
                corner(0.0, 0.0),
                corner(10.0, 0.0)
            ]
        );
        // An open path (a corner cut) is kept as it is.
        let open = ring[..4].to_vec();
        assert_eq!(start_mid_side(open.clone()), open);
    }

    /// A side walked with a phone (2 cm of jitter every 0.15 m, and a point repeated) is one
    /// leg; the corners stay, and no vertex moves the line by more than the tolerance.
    #[test]
    fn thinning_drops_the_jitter_of_a_walked_side_and_keeps_the_corners() {
        let mut path = Vec::new();
        for step in 0..=200 {
            let x = 0.15 * step as f64;
            let jitter = if step % 2 == 0 { 0.02 } else { -0.02 };
            path.push(Coord { x, y: jitter * 0.5 });
            if step == 100 {
                path.push(Coord { x, y: jitter * 0.5 });
            }
        }
        path.push(Coord { x: 30.0, y: 20.0 });
        path.push(Coord { x: 0.0, y: 20.0 });
        let thin = thinned(path.clone(), 0.05);
        assert_eq!(thin.len(), 4, "{thin:?}");
        assert_eq!(thin.first(), path.first());
        assert_eq!(thin.last(), path.last());
        assert!((thin[1].x - 30.0).abs() < 1e-9 && (thin[2].y - 20.0).abs() < 1e-9);
    }
}
