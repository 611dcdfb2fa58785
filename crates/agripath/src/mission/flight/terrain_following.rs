//! Terrain following: along a swath the terrain is sampled every `sample_spacing_m` and the
//! waypoints kept are those a vertical Douglas-Peucker keeps at `terrain_tolerance_m`: between
//! two waypoints the straight climb or descent stays within the tolerance of terrain + spray
//! height (what QGroundControl's terrain following precomputes), and flat stretches need
//! only their ends.

use super::MissionSettings;
use crate::error::Fault;
use crate::sortie::route::RoutePoint;
use crate::terrain::Terrain;

/// Keeps the samples a vertical Douglas-Peucker keeps: (distance along, height) pairs.
pub(super) fn simplify(
    profile: &[(f64, f64)],
    tolerance: f64,
    keep: &mut [bool],
    first: usize,
    last: usize,
) {
    if last <= first + 1 {
        return;
    }
    let (x0, z0) = profile[first];
    let (x1, z1) = profile[last];
    let mut worst = (0.0, first);
    for (index, &(x, z)) in profile.iter().enumerate().take(last).skip(first + 1) {
        let along = if x1 > x0 { (x - x0) / (x1 - x0) } else { 0.0 };
        let gap = (z - (z0 + along * (z1 - z0))).abs();
        if gap > worst.0 {
            worst = (gap, index);
        }
    }
    if worst.0 > tolerance {
        keep[worst.1] = true;
        simplify(profile, tolerance, keep, first, worst.1);
        simplify(profile, tolerance, keep, worst.1, last);
    }
}

/// The terrain-following waypoints of a spray run through `points` (plan metres and ground
/// heights): the run's ends, every corner (an edge pass turns at the boundary's vertices),
/// and every sample the terrain needs between them.
pub(super) fn follow_terrain(
    points: &[RoutePoint],
    terrain: &dyn Terrain,
    settings: &MissionSettings,
) -> Result<Vec<RoutePoint>, Fault> {
    let mut samples = vec![points[0]];
    let mut anchors = vec![0];
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        let steps = (length / settings.sample_spacing_m).ceil().max(1.0) as usize;
        for step in 1..steps {
            let t = step as f64 / steps as f64;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            samples.push(RoutePoint {
                x,
                y,
                ground_m: terrain.height_m(x, y)?,
            });
        }
        samples.push(b);
        let corner = points.get(index + 2).is_some_and(|c| {
            let (incoming, outgoing) = ((b.x - a.x, b.y - a.y), (c.x - b.x, c.y - b.y));
            let cross = incoming.0 * outgoing.1 - incoming.1 * outgoing.0;
            let dot = incoming.0 * outgoing.0 + incoming.1 * outgoing.1;
            cross.atan2(dot).abs() > 0.5_f64.to_radians()
        });
        if corner || index + 2 == points.len() {
            anchors.push(samples.len() - 1);
        }
    }
    let mut along = 0.0;
    let profile: Vec<(f64, f64)> = samples
        .iter()
        .enumerate()
        .map(|(index, point)| {
            if index > 0 {
                let previous = samples[index - 1];
                along += (point.x - previous.x).hypot(point.y - previous.y);
            }
            (along, point.ground_m)
        })
        .collect();
    let mut keep = vec![false; samples.len()];
    // The terrain between two samples may stray a little beyond what the samples show: keep
    // a tenth of the tolerance (at least 5 cm) for it, so the flight as sampled finer stays within.
    let tolerance = (settings.terrain_tolerance_m * 0.9).min(settings.terrain_tolerance_m - 0.05);
    for pair in anchors.windows(2) {
        keep[pair[0]] = true;
        keep[pair[1]] = true;
        simplify(&profile, tolerance.max(0.01), &mut keep, pair[0], pair[1]);
    }
    Ok(samples
        .into_iter()
        .zip(keep)
        .filter_map(|(point, kept)| kept.then_some(point))
        .collect())
}
