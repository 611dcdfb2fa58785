//! An edge pass's ring that encloses (next to) nothing, flown once along its middle.
//!
//! Edge pass k runs along the ring of the sprayable region shrunk by (k + ½)·w
//! ([`super::region::edge_pass_regions`]). On a strip one swath wide, or a hair wider, that
//! region is a sliver: its ring runs up one side and back down the other a few millimetres
//! away. Flown as a loop, the strip is sprayed twice over (a trial's 5.01 m strip: 97 %
//! double-sprayed); and on a strip of exactly one swath the rounding of the offsets leaves
//! stray pieces of ring that cover part of it (62.7 % of a 5 m terrace; decision 0039).
//! A ring whose mean width, 2·area / perimeter, is under [`SLIVER_SHARE`] of the swath is
//! flown once instead, when it folds onto itself about two tips (one strip, not a fork):
//! along its midline, from tip to tip, each end carried on towards the field's end as far
//! as the ground the footprint sweeps stays inside the sprayable region (up to w/2, where
//! the loop's turn would have sprayed, plus a sample's spacing, since the tip is a sample).
//! The ground it leaves is the sliver's own width, at most [`SLIVER_SHARE`] of the strip.
//!
//! The tips are found as the point about which the ring is most nearly mirror-symmetric
//! along its length: resampled evenly, the tip `a` minimises the largest distance between
//! the points k samples before and after it; the midline is the midpoints of those pairs.

use geo::{Area, Contains, Coord, LineString, MultiPolygon, Polygon, Simplify};

/// Largest mean width of a ring flown once along its middle, as a share of the swath.
pub const SLIVER_SHARE: f64 = 0.005;

/// Samples of a ring per metre of its perimeter (at least [`LEAST_SAMPLES`], at most
/// [`MOST_SAMPLES`]).
const SAMPLES_PER_M: f64 = 4.0;
const LEAST_SAMPLES: usize = 64;
const MOST_SAMPLES: usize = 4000;

/// How far the midline may stray from the midpoints when its vertices are thinned, metres.
const SIMPLIFY_M: f64 = 0.01;

/// Whether a ring of `area` and `perimeter` is a sliver for a swath `width_m` wide: its mean
/// width, 2·area / perimeter, at most [`SLIVER_SHARE`] of the swath (false for NaN).
pub fn is_sliver(area: f64, perimeter: f64, width_m: f64) -> bool {
    perimeter > 0.0 && 2.0 * area / perimeter <= SLIVER_SHARE * width_m
}

/// The midline of `ring` (closed, first point repeated last) when it is a sliver for a swath
/// `width_m` wide, its ends carried on inside `sprayable`; `None` for any other ring.
pub fn sliver_midline(
    ring: &[Coord<f64>],
    width_m: f64,
    sprayable: &MultiPolygon<f64>,
) -> Option<Vec<Coord<f64>>> {
    let perimeter: f64 = ring.windows(2).map(|pair| distance(pair[0], pair[1])).sum();
    if ring.len() < 4 || perimeter <= 0.0 {
        return None;
    }
    let area = Polygon::new(LineString::new(ring.to_vec()), vec![]).unsigned_area();
    let mean_width_m = 2.0 * area / perimeter;
    if !is_sliver(area, perimeter, width_m) {
        return None;
    }
    let count = ((perimeter * SAMPLES_PER_M) as usize).clamp(LEAST_SAMPLES, MOST_SAMPLES) & !1;
    let samples = resample(ring, perimeter, count);
    let half = count / 2;
    let at = |index: isize| samples[index.rem_euclid(count as isize) as usize];
    let mismatch_at = |tip: usize, bound: f64| {
        let mut worst = 0.0_f64;
        for k in 1..half as isize {
            worst = worst.max(distance(at(tip as isize + k), at(tip as isize - k)));
            if worst >= bound {
                break;
            }
        }
        worst
    };
    let (mut tip, mut least) = (0, f64::INFINITY);
    for candidate in 0..count {
        let mismatch = mismatch_at(candidate, least);
        if mismatch < least {
            (tip, least) = (candidate, mismatch);
        }
    }
    // One strip folds onto itself about its tips, each sample within the sliver's width and
    // a sample's spacing of its mirror; a fork (a Y of terraces) or a bulge does not: flown as
    // the loop it is, not down a "middle" that would leave the field between the arms.
    let step = perimeter / count as f64;
    let folds = least <= 2.0 * mean_width_m + 2.0 * step;
    if !folds {
        return None;
    }
    let midpoints: Vec<Coord<f64>> = (0..=half as isize)
        .map(|k| {
            let (a, b) = (at(tip as isize + k), at(tip as isize - k));
            Coord {
                x: (a.x + b.x) / 2.0,
                y: (a.y + b.y) / 2.0,
            }
        })
        .collect();
    let mut midline = LineString::new(midpoints).simplify(SIMPLIFY_M).0;
    if midline.len() < 2 {
        return None;
    }
    let last = midline.len() - 1;
    let footprint = Footprint {
        width_m,
        slack_m: mean_width_m + SLACK_M,
        // The tip is a sample: up to a spacing short of the sliver's end.
        reach_m: width_m / 2.0 + step,
    };
    midline[0] = footprint.carried_on(midline[0], midline[1], sprayable);
    midline[last] = footprint.carried_on(midline[last], midline[last - 1], sprayable);
    Some(midline)
}

/// Slack on the footprint's end beyond the sliver's own width, metres.
const SLACK_M: f64 = 0.001;

/// The footprint's end as the midline is carried on.
struct Footprint {
    width_m: f64,
    /// How far the footprint's end may reach past the strip's sides: the midline's tip is a
    /// point of the ring, up to the sliver's width off the strip's middle.
    slack_m: f64,
    /// The farthest the tip is carried on.
    reach_m: f64,
}

impl Footprint {
    /// `tip` moved away from `inner` along their line by the most, up to `reach_m`, that
    /// keeps the ground the footprint sweeps on the way (a rectangle w wide, less the slack
    /// at each side, from the tip to where it stops) inside `sprayable`: not only its end,
    /// which would let a neck or a pole between be sprayed over (the review of 2026-12-08).
    fn carried_on(
        &self,
        tip: Coord<f64>,
        inner: Coord<f64>,
        sprayable: &MultiPolygon<f64>,
    ) -> Coord<f64> {
        let length = distance(tip, inner);
        let half = self.width_m / 2.0 - self.slack_m;
        if length <= 0.0 || half <= 0.0 {
            return tip;
        }
        let along = Coord {
            x: (tip.x - inner.x) / length,
            y: (tip.y - inner.y) / length,
        };
        let across = Coord {
            x: -along.y * half,
            y: along.x * half,
        };
        // The swept rectangles nest as t grows: the test is monotone, so bisection holds.
        let inside = |t: f64| {
            let centre = tip + along * t;
            let swept = Polygon::new(
                LineString::new(vec![
                    tip - across,
                    centre - across,
                    centre + across,
                    tip + across,
                    tip - across,
                ]),
                vec![],
            );
            sprayable.contains(&swept)
        };
        let (mut low, mut high) = (0.0, self.reach_m);
        if inside(high) {
            return tip + along * high;
        }
        for _ in 0..20 {
            let middle = (low + high) / 2.0;
            if inside(middle) {
                low = middle;
            } else {
                high = middle;
            }
        }
        tip + along * low
    }
}

/// `count` points evenly spaced along the closed `ring` of length `perimeter`.
fn resample(ring: &[Coord<f64>], perimeter: f64, count: usize) -> Vec<Coord<f64>> {
    let step = perimeter / count as f64;
    let mut samples = Vec::with_capacity(count);
    let (mut segment, mut walked) = (0, 0.0);
    for index in 0..count {
        let wanted = index as f64 * step;
        while segment + 2 < ring.len()
            && walked + distance(ring[segment], ring[segment + 1]) < wanted
        {
            walked += distance(ring[segment], ring[segment + 1]);
            segment += 1;
        }
        let (a, b) = (ring[segment], ring[segment + 1]);
        let length = distance(a, b);
        let t = if length > 0.0 {
            ((wanted - walked) / length).clamp(0.0, 1.0)
        } else {
            0.0
        };
        samples.push(a + (b - a) * t);
    }
    samples
}

fn distance(a: Coord<f64>, b: Coord<f64>) -> f64 {
    (b.x - a.x).hypot(b.y - a.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coverage::region::{edge_pass_regions, rings};

    fn rectangle(width: f64, length: f64) -> MultiPolygon<f64> {
        MultiPolygon::new(vec![Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (width, 0.0),
                (width, length),
                (0.0, length),
                (0.0, 0.0),
            ]),
            vec![],
        )])
    }

    /// The first pass ring of `strip`'s region, as the coverage lays it out.
    fn first_ring(strip: &MultiPolygon<f64>, width: f64) -> Vec<Coord<f64>> {
        let regions = edge_pass_regions(strip, 1, width);
        rings(&regions[0]).remove(0)
    }

    #[test]
    fn a_strip_a_hair_wider_than_the_swath_is_flown_once_down_its_middle_end_to_end() {
        let strip = rectangle(5.01, 120.0);
        let midline = sliver_midline(&first_ring(&strip, 5.0), 5.0, &strip).unwrap();
        let (first, last) = (midline[0], midline[midline.len() - 1]);
        let (low, high) = if first.y < last.y {
            (first, last)
        } else {
            (last, first)
        };
        assert!(
            low.y.abs() < 0.05 && (high.y - 120.0).abs() < 0.05,
            "{low:?} {high:?}"
        );
        for point in &midline {
            assert!((point.x - 2.505).abs() < 0.01, "{point:?}");
        }
    }

    #[test]
    fn a_bent_strip_is_flown_along_its_bend() {
        // An L: 5.01 m wide, arms 60 m and 40 m along its outer edges.
        let strip = MultiPolygon::new(vec![Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (60.0, 0.0),
                (60.0, 5.01),
                (5.01, 5.01),
                (5.01, 40.0),
                (0.0, 40.0),
                (0.0, 0.0),
            ]),
            vec![],
        )]);
        let midline = sliver_midline(&first_ring(&strip, 5.0), 5.0, &strip).unwrap();
        let ends = [midline[0], midline[midline.len() - 1]];
        let near = |x: f64, y: f64| {
            ends.iter()
                .any(|end| (end.x - x).abs() < 0.05 && (end.y - y).abs() < 0.05)
        };
        assert!(near(60.0, 2.505) && near(2.505, 40.0), "{ends:?}");
        let length: f64 = midline.windows(2).map(|p| distance(p[0], p[1])).sum();
        assert!((length - (57.495 + 37.495)).abs() < 0.1, "{length}");
    }

    #[test]
    fn a_ring_round_real_ground_is_not_a_sliver() {
        let field = rectangle(7.0, 120.0);
        assert!(sliver_midline(&first_ring(&field, 5.0), 5.0, &field).is_none());
    }

    #[test]
    fn a_slanted_end_stops_the_midline_where_the_footprint_would_leave_the_strip() {
        // The strip's north end slants by 45°: carried on, the footprint's end would cross it.
        let strip = MultiPolygon::new(vec![Polygon::new(
            LineString::from(vec![
                (0.0, 0.0),
                (5.01, 0.0),
                (5.01, 105.01),
                (0.0, 100.0),
                (0.0, 0.0),
            ]),
            vec![],
        )]);
        let midline = sliver_midline(&first_ring(&strip, 5.0), 5.0, &strip).unwrap();
        let north = midline.iter().map(|point| point.y).fold(f64::MIN, f64::max);
        // The footprint's end, 5 m across less the slack, stays under the slant: its corner
        // near x = 0 under y = 100 (up to the slack's centimetre).
        assert!(north <= 100.02 && north > 97.0, "{north}");
    }

    #[test]
    fn a_strip_exactly_one_swath_wide_is_flown_end_to_end_whatever_the_rings_first_point() {
        // Drawn from the middle of a long side: the ring's first point is no corner.
        let strip = MultiPolygon::new(vec![Polygon::new(
            LineString::from(vec![
                (5.0, 60.0),
                (5.0, 120.0),
                (0.0, 120.0),
                (0.0, 0.0),
                (5.0, 0.0),
                (5.0, 60.0),
            ]),
            vec![],
        )]);
        let midline = sliver_midline(&first_ring(&strip, 5.0), 5.0, &strip).unwrap();
        let ys: Vec<f64> = [midline[0], midline[midline.len() - 1]]
            .iter()
            .map(|point| point.y)
            .collect();
        let (low, high) = (ys[0].min(ys[1]), ys[0].max(ys[1]));
        assert!(low < 0.05 && high > 119.95, "{midline:?}");
    }

    #[test]
    fn a_forked_sliver_is_no_strip_and_keeps_its_loop() {
        // A T of terraces one swath wide (three ends): no middle line flies every arm.
        let arm = |points: Vec<(f64, f64)>| Polygon::new(LineString::from(points), vec![]);
        let fork = geo::BooleanOps::union(
            &MultiPolygon::new(vec![arm(vec![
                (0.0, 0.0),
                (5.01, 0.0),
                (5.01, 60.0),
                (0.0, 60.0),
                (0.0, 0.0),
            ])]),
            &MultiPolygon::new(vec![arm(vec![
                (4.0, 27.5),
                (45.0, 27.5),
                (45.0, 32.51),
                (4.0, 32.51),
                (4.0, 27.5),
            ])]),
        );
        let regions = edge_pass_regions(&fork, 1, 5.0);
        for ring in rings(&regions[0]) {
            assert!(sliver_midline(&ring, 5.0, &fork).is_none());
        }
    }

    #[test]
    fn the_end_stops_short_of_a_pole_beside_the_strips_end() {
        // A pole (a hole of 0.3 m) 0.5 m from the side, 2 m from the end: the footprint's end
        // alone would clear it at the end line, but it sweeps over it on the way.
        let mut strip = rectangle(5.01, 120.0);
        let pole: Vec<(f64, f64)> = (0..=16)
            .map(|k| {
                let angle = std::f64::consts::TAU * f64::from(k % 16) / 16.0;
                (0.5 + 0.3 * angle.cos(), 2.0 + 0.3 * angle.sin())
            })
            .collect();
        strip.0[0].interiors_push(LineString::from(pole));
        let midline = sliver_midline(&first_ring(&strip, 5.0), 5.0, &strip).unwrap();
        let south = midline.iter().map(|point| point.y).fold(f64::MAX, f64::min);
        assert!((2.3 - 1e-6..2.5).contains(&south), "{south}");
    }
}
