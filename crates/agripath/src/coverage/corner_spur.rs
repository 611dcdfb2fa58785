//! Sharp corners of edge passes (issue 15, decision 0019): a spur along the corner's bisector
//! so that the spray reaches into the tip.
//!
//! An edge pass runs w/2 inside the boundary; at a convex corner of interior angle θ its
//! line turns at P, (w/2)/sin(θ/2) from the tip T. A multirotor's footprint there is the two
//! legs' rectangles and the disc of radius w/2 about P, which leaves unsprayed the kite
//! between T, P and the feet of P on the two edges, less the disc's sector:
//!
//!   missed = (w²/4)·(cot(θ/2) − (π − θ)/2)      (0.60 w² at 30°, 0.17 w² at 60°)
//!
//! (the mitred band the planner measured before reached T, so it said 100 %). A square-ended
//! strip one swath wide cannot reach a tip without spraying outside: along the bisector, at
//! distance a from T, the field is 2a·tan(θ/2) wide, narrower than w for a < a_f =
//! (w/2)·cot(θ/2). A spur from P to Q at a_Q from T, sprayed once (its end square, the spray
//! off at Q), leaves missed the triangle beyond Q and sprays outside the field where it is
//! narrower than w; with x = a_f − a_Q and t = tan(θ/2):
//!
//!   missed = t·(a_f − x)²,  outside = t·x²
//!
//! whose sum is least at x = a_f/2 (each (w²/16)·cot(θ/2)). [`SPUR_SHARE`] of a_f is the
//! spur's reach past a_f; it is used where it misses less than the round join alone, which
//! is below [`SPUR_BELOW_RAD`].
//!
//! The pass's ring is opened at each such corner: piece k runs Q_k → P_k → … → P_(k+1) and
//! ends there (spray off, square end); the next piece starts at its spur's end Q_(k+1). The
//! route flies between them as a turn, spray off, so the spur is sprayed once.

use geo::{Contains, Coord, MultiPolygon, Point};

/// The spur's reach past a_f, as a share of a_f. ½ makes missed and outside equal and least
/// under the square-end model above, but as read back (the footprint's round end) it sprayed
/// 2.57 % of seed 004's double_2 field outside it (preflight limit 0.5 %); at 0 the spur ends
/// where the field is one swath wide and sprays nothing outside.
pub const SPUR_SHARE: f64 = 0.0;
/// Corners sharper than this get a spur, radians: there the spur leaves less missed than the
/// round join ((w²/16)·cot(θ/2) < (w²/4)·(cot(θ/2) − (π − θ)/2) below about 83°).
pub const SPUR_BELOW_RAD: f64 = 80.0 * std::f64::consts::PI / 180.0;

/// A ring of an edge pass (closed, first point repeated last) as the paths flown: the ring
/// itself when it has no sharp corner, else one open path per sharp corner, each starting at
/// its spur's end.
pub fn pass_paths(
    ring: &[Coord<f64>],
    region: &MultiPolygon<f64>,
    width_m: f64,
) -> Vec<Vec<Coord<f64>>> {
    let corners = &ring[..ring.len().saturating_sub(1)];
    let count = corners.len();
    if count < 3 {
        return vec![ring.to_vec()];
    }
    let spurs: Vec<(usize, Coord<f64>)> = (0..count)
        .filter_map(|k| spur_end(corners, k, region, width_m).map(|end| (k, end)))
        .collect();
    if spurs.is_empty() {
        return vec![ring.to_vec()];
    }
    let mut paths = Vec::with_capacity(spurs.len());
    for (index, &(corner, end)) in spurs.iter().enumerate() {
        let next = spurs[(index + 1) % spurs.len()].0;
        let mut path = vec![end, corners[corner]];
        let mut k = corner;
        loop {
            k = (k + 1) % count;
            path.push(corners[k]);
            if k == next {
                break;
            }
        }
        paths.push(path);
    }
    paths
}

/// The spur's end Q at corner `k` of the pass line, when the corner is convex and sharper
/// than [`SPUR_BELOW_RAD`].
fn spur_end(
    corners: &[Coord<f64>],
    k: usize,
    region: &MultiPolygon<f64>,
    width_m: f64,
) -> Option<Coord<f64>> {
    let count = corners.len();
    let (previous, here, next) = (
        corners[(k + count - 1) % count],
        corners[k],
        corners[(k + 1) % count],
    );
    let unit = |from: Coord<f64>, to: Coord<f64>| {
        let (dx, dy) = (to.x - from.x, to.y - from.y);
        let length = dx.hypot(dy);
        (length > 1e-9).then(|| Coord {
            x: dx / length,
            y: dy / length,
        })
    };
    let (back, ahead) = (unit(here, previous)?, unit(here, next)?);
    let interior = (back.x * ahead.x + back.y * ahead.y)
        .clamp(-1.0, 1.0)
        .acos();
    if !(interior > 1e-3 && interior < SPUR_BELOW_RAD) {
        return None;
    }
    // The bisector between the two edges points into the corner's wedge; the tip lies the
    // other way.
    let inward = unit(Coord { x: 0.0, y: 0.0 }, back + ahead)?;
    let probe = here + inward * (0.01 * width_m);
    if !region.contains(&Point::from(probe)) {
        return None; // a reflex corner of the region (its wedge is outside)
    }
    let half_angle = interior / 2.0;
    let to_tip = (width_m / 2.0) / half_angle.sin();
    let foot = (width_m / 2.0) / half_angle.tan();
    let spur = to_tip - (1.0 - SPUR_SHARE) * foot;
    Some(here - inward * spur)
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::polygon;

    #[test]
    fn a_sharp_corner_opens_the_ring_with_a_spur_into_the_tip() {
        // A triangle with a 20° tip at the origin, pointing −x; the pass line 2.5 m inside.
        let half = 10f64.to_radians();
        let region = MultiPolygon::new(vec![polygon![
            (x: 0.0, y: 0.0), (x: 100.0, y: -100.0 * half.tan()), (x: 100.0, y: 100.0 * half.tan())
        ]]);
        let pass = super::super::region::offset(&region, -2.5);
        let ring = &pass.0[0].exterior().0;
        let paths = pass_paths(ring, &pass, 5.0);
        // The tip is sharp (20°), the two base corners (80°) are not.
        assert_eq!(paths.len(), 1, "{paths:?}");
        let path = &paths[0];
        let (spur_end, corner) = (path[0], path[1]);
        // P is 2.5/sin 10° = 14.4 m from the tip; Q is (1 − SPUR_SHARE)·a_f from it, with
        // a_f = 2.5·cot 10° = 14.18 m where the field is one swath wide.
        assert!((corner.x - 2.5 / half.sin()).abs() < 1e-6, "{corner:?}");
        let reach = (1.0 - SPUR_SHARE) * 2.5 / half.tan();
        assert!((spur_end.x - reach).abs() < 1e-6, "{spur_end:?}");
        assert!(spur_end.x < corner.x, "the spur points into the tip");
        assert!(spur_end.y.abs() < 1e-9);
        // The open path ends back at the corner after the ring.
        assert_eq!(*path.last().unwrap(), corner);
        assert_eq!(path.len(), ring.len() + 1);
    }

    #[test]
    fn a_square_keeps_its_closed_ring() {
        let region = MultiPolygon::new(vec![polygon![
            (x: 0.0, y: 0.0), (x: 50.0, y: 0.0), (x: 50.0, y: 50.0), (x: 0.0, y: 50.0)
        ]]);
        let pass = super::super::region::offset(&region, -2.5);
        let ring = &pass.0[0].exterior().0;
        assert_eq!(pass_paths(ring, &pass, 5.0), vec![ring.clone()]);
    }
}
