//! The coarse set of supply point candidates: a few hundred places a vehicle can stand,
//! spread so that the best is never far from one of them (docs/decisions/0016-supply-point.md).
//!
//! Without access features:
//!
//! - every field's outer boundary, sampled every s_b = max(P / [`BOUNDARY_SAMPLES`], 5 m)
//!   (P: all the fields' perimeters), each sample moved out along the edge's outward normal by
//!   m + 1 m: the best point of a farm of large fields usually stands right at a field's edge;
//! - a lattice over the fields' box grown by r, every s_g = max(√(box area /
//!   [`LATTICE_SAMPLES`]), 10 m), for the gaps between fields;
//! - the spray-weighted centroid of the route (each spray segment's midpoint, weighted by its
//!   length: the cheap bound), and the route's first and last points, so that the
//!   search can do at least as well as a place beside the old rule's point.
//!
//! With access features: their lines sampled every max(L / [`ACCESS_SAMPLES`], 5 m) (L: all
//! the lines' length), the yards' corners and a lattice inside them, and the three route
//! points above. Every point goes through [`StandingRule::settle`]; a point settled in the
//! same 1 m square as an earlier one is dropped. The order is deterministic.

use geo::Coord;

use super::standing::{StandingRule, MARGIN_M};
use crate::model::Farm;
use crate::sortie::route::{Segment, WorkRoute};

/// About how many boundary samples all fields get together.
pub const BOUNDARY_SAMPLES: f64 = 240.0;
/// About how many lattice points the grown box gets.
pub const LATTICE_SAMPLES: f64 = 240.0;
/// About how many samples all access lines get together.
pub const ACCESS_SAMPLES: f64 = 300.0;

/// The candidates, and the lattice spacing s_g (metres): the scale the refinement starts at.
pub struct Candidates {
    /// Places a vehicle can stand, in a fixed order.
    pub points: Vec<Coord<f64>>,
    /// The spacing of the coarse samples, metres.
    pub spacing_m: f64,
}

/// The spray-weighted centroid of `route`: Σ midpoint · length / Σ length over its spray
/// segments (the first point when it sprays nothing).
pub fn spray_centroid(route: &WorkRoute) -> Option<Coord<f64>> {
    let points = route.points();
    let (mut sum_x, mut sum_y, mut sum) = (0.0, 0.0, 0.0);
    for (index, segment) in route.segments().iter().enumerate() {
        if *segment != Segment::Spray {
            continue;
        }
        let (a, b) = (points[index], points[index + 1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        sum_x += 0.5 * (a.x + b.x) * length;
        sum_y += 0.5 * (a.y + b.y) * length;
        sum += length;
    }
    if sum > 0.0 {
        Some(Coord {
            x: sum_x / sum,
            y: sum_y / sum,
        })
    } else {
        points.first().map(|point| Coord {
            x: point.x,
            y: point.y,
        })
    }
}

/// Points every `spacing` along a polyline, its corners included.
fn along(points: &[Coord<f64>], spacing: f64, out: &mut Vec<(Coord<f64>, Coord<f64>)>) {
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        let steps = (length / spacing).ceil().max(1.0) as usize;
        for k in 0..steps {
            let t = k as f64 / steps as f64;
            out.push((a + (b - a) * t, b - a));
        }
    }
    if let Some(&last) = points.last() {
        out.push((last, Coord { x: 1.0, y: 0.0 }));
    }
}

/// A lattice every `spacing` over the box `low`–`high`.
fn lattice(low: Coord<f64>, high: Coord<f64>, spacing: f64) -> Vec<Coord<f64>> {
    let columns = ((high.x - low.x) / spacing).floor() as usize;
    let rows = ((high.y - low.y) / spacing).floor() as usize;
    let mut points = Vec::with_capacity((columns + 1) * (rows + 1));
    for row in 0..=rows {
        for column in 0..=columns {
            points.push(Coord {
                x: low.x + spacing * (column as f64 + 0.5),
                y: low.y + spacing * (row as f64 + 0.5),
            });
        }
    }
    points
}

/// The coarse candidate set of `farm` for `route` (the module's documentation lists it).
pub fn coarse(farm: &Farm, route: &WorkRoute, standing: &StandingRule) -> Candidates {
    let mut raw: Vec<Coord<f64>> = Vec::new();
    let spacing_m;
    if standing.on_access() {
        let lines = standing.access_lines();
        let length: f64 = lines
            .iter()
            .flat_map(|line| line.windows(2))
            .map(|pair| (pair[1].x - pair[0].x).hypot(pair[1].y - pair[0].y))
            .sum();
        spacing_m = (length / ACCESS_SAMPLES).max(5.0);
        let mut samples = Vec::new();
        for line in lines {
            along(line, spacing_m, &mut samples);
        }
        raw.extend(samples.into_iter().map(|(point, _)| point));
        for boundary in standing.yard_boundaries() {
            raw.extend(boundary.iter().copied());
            let (low, high) = crate::geometry::bounds(boundary);
            let inside = ((high.x - low.x) * (high.y - low.y) / 16.0).sqrt().max(5.0);
            raw.extend(lattice(low, high, inside));
        }
    } else {
        let perimeter: f64 = farm
            .fields
            .iter()
            .flat_map(|field| field.polygon.exterior().0.windows(2))
            .map(|pair| (pair[1].x - pair[0].x).hypot(pair[1].y - pair[0].y))
            .sum();
        let boundary_spacing = (perimeter / BOUNDARY_SAMPLES).max(5.0);
        for field in &farm.fields {
            let ring = &field.polygon.exterior().0;
            let index = crate::geometry::ring_index::IndexedRing::new(ring);
            let mut samples = Vec::new();
            along(ring, boundary_spacing, &mut samples);
            for (point, direction) in samples {
                let length = direction.x.hypot(direction.y).max(1e-12);
                let normal = Coord {
                    x: direction.y / length,
                    y: -direction.x / length,
                };
                let offset = normal * (MARGIN_M + 1.0);
                // Outward is the side of the edge outside this field.
                let outward = if index.contains(point + normal * 1e-3) {
                    point - offset
                } else {
                    point + offset
                };
                raw.push(outward);
            }
        }
        let bounds = farm.bounds();
        let grow = standing.reach_m;
        let low = Coord {
            x: bounds.min().x - grow,
            y: bounds.min().y - grow,
        };
        let high = Coord {
            x: bounds.max().x + grow,
            y: bounds.max().y + grow,
        };
        spacing_m = ((high.x - low.x) * (high.y - low.y) / LATTICE_SAMPLES)
            .sqrt()
            .max(10.0);
        raw.extend(
            lattice(low, high, spacing_m)
                .into_iter()
                .filter(|&point| standing.allows(point)),
        );
    }
    let ends = [route.points().first(), route.points().last()]
        .into_iter()
        .flatten()
        .map(|point| Coord {
            x: point.x,
            y: point.y,
        });
    raw.extend(spray_centroid(route).into_iter().chain(ends));
    let mut points: Vec<Coord<f64>> = Vec::with_capacity(raw.len());
    let mut seen = std::collections::HashSet::new();
    for point in raw {
        let Some(settled) = standing.settle(point) else {
            continue;
        };
        // In the same square metre as an earlier candidate: the same place.
        let cell = ((settled.x).floor() as i64, (settled.y).floor() as i64);
        if seen.insert(cell) {
            points.push(settled);
        }
    }
    Candidates { points, spacing_m }
}
