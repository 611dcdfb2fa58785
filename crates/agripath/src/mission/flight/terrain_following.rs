//! Terrain following: along a swath the terrain is sampled every `sample_spacing_m` and the
//! waypoints kept are those a vertical Douglas-Peucker keeps at `terrain_tolerance_m`: between
//! two waypoints the straight climb or descent stays within the tolerance of terrain + spray
//! height (what QGroundControl's terrain following precomputes), and flat stretches need
//! only their ends. Where a straight climb between two waypoints would pass a bank nearer than
//! the floor sideways, every sample between them is kept.

use super::MissionSettings;
use crate::error::Fault;
use crate::limits::MIN_GROUND_CLEARANCE_M;
use crate::sortie::route::RoutePoint;
use crate::terrain::nearness::GroundNearness;
use crate::terrain::Terrain;

/// What the planner keeps beyond the preflight's floor sideways, metres: the margin its
/// bound may err by on a steep bank.
const SIDEWAYS_MARGIN_M: f64 = 0.25;

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
    spray_height_m: f64,
) -> Result<Vec<RoutePoint>, Fault> {
    let mut samples = vec![points[0]];
    let mut anchors = vec![0];
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        // Every sample spacing, and where the terrain bends and peaks between (a step in
        // a raster one cell wide lies between two samples a metre apart; decision 0028).
        let place = |t: f64| (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
        let places = crate::terrain::profile_places(
            terrain,
            (a.x, a.y),
            (b.x, b.y),
            length,
            settings.sample_spacing_m,
            |t| {
                let (x, y) = place(t);
                terrain.height_m(x, y).ok().map(|ground| vec![ground])
            },
        );
        for &t in &places[1..places.len() - 1] {
            let (x, y) = place(t);
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
    // Sideways too: between two waypoints kept, the straight climb may pass a bank nearer
    // than the preflight's floor though well above the ground beneath (the island's terrace
    // edges; decision 0030). There every sample is kept: the flight then holds the spray
    // height over each.
    let mut nearness = GroundNearness::new(
        terrain,
        |x, y| terrain.height_m(x, y).ok(),
        1.0,
        MIN_GROUND_CLEARANCE_M + SIDEWAYS_MARGIN_M,
    );
    let kept: Vec<usize> = (0..samples.len()).filter(|&index| keep[index]).collect();
    for pair in kept.windows(2) {
        let (first, last) = (pair[0], pair[1]);
        if last <= first + 1 {
            continue;
        }
        let at = |point: &RoutePoint| [point.x, point.y, point.ground_m + spray_height_m];
        let (from, to) = (at(&samples[first]), at(&samples[last]));
        // Nearer beside than beneath: ground within reach straight down is the terrain
        // tolerance's business (else a spray height within 0.75 m of the tolerance's low end
        // keeps every sample of every swath).
        let span = profile[last].0 - profile[first].0;
        let beneath = (first..=last)
            .map(|index| {
                let along = if span > 0.0 {
                    (profile[index].0 - profile[first].0) / span
                } else {
                    0.0
                };
                from[2] + along * (to[2] - from[2]) - samples[index].ground_m
            })
            .fold(f64::INFINITY, f64::min);
        if nearness
            .leg(from, to)
            .is_some_and(|near| near.distance_m < beneath - 0.01)
        {
            keep[first..=last].fill(true);
        }
    }
    Ok(samples
        .into_iter()
        .zip(keep)
        .filter_map(|(point, kept)| kept.then_some(point))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::Grid;

    /// A swath over a 12 m cliff one cell (4 m) wide, on a slant across the cells (the case of
    /// decision 0028): the waypoints kept, flown in straight lines, stay within the tolerance
    /// of the ground sampled every centimetre. At 1 m samples alone they strayed 1.14 m.
    #[test]
    fn waypoints_hold_the_tolerance_over_a_cliff_one_cell_wide() {
        let (columns, rows) = (30, 30);
        let heights = (0..rows * columns)
            .map(|index| {
                let (row, column) = (index / columns, index % columns);
                let ramp = 0.3 * column as f32;
                if row < 15 {
                    ramp + 12.0
                } else {
                    ramp
                }
            })
            .collect();
        let grid = Grid {
            columns,
            rows,
            first_center_x: 2.0,
            first_center_y: 118.0,
            cell_x: 4.0,
            cell_y: 4.0,
            heights,
            epsg: None,
            source: "cliff".into(),
        };
        let settings = MissionSettings::default();
        let point = |x: f64, y: f64| RoutePoint {
            x,
            y,
            ground_m: grid.height_m(x, y).unwrap(),
        };
        // Runs of whole metres, so the 1 m samples fall at every offset from the cliff's bends
        // (the lines y = 62 and y = 58 through the cell centres).
        let mut worst: f64 = 0.0;
        for tenth in 0..10 {
            let start = 65.0 + 0.1 * f64::from(tenth);
            let run = [point(51.83, start), point(51.69, start - 44.0)];
            let kept = follow_terrain(&run, &grid, &settings, 2.5).unwrap();
            for pair in kept.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                let length = (b.x - a.x).hypot(b.y - a.y);
                let steps = (length / 0.01).ceil() as usize;
                for step in 0..=steps {
                    let t = step as f64 / steps as f64;
                    let ground = grid
                        .height_m(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y))
                        .unwrap();
                    let flown = a.ground_m + t * (b.ground_m - a.ground_m);
                    worst = worst.max((flown - ground).abs());
                }
            }
        }
        assert!(
            worst <= settings.terrain_tolerance_m,
            "{worst} m off the ground's profile"
        );
    }
}
