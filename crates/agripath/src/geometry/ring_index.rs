//! A closed ring indexed by horizontal bands, for the many point queries of the preflight
//! (a sample every metre of a flight against fields of up to 50,000 vertices): a point-in-ring
//! test and a "within d of the boundary" test that look only at the edges of the bands the
//! query reaches, instead of every edge.

use geo::Coord;

use super::distance_to_segment;

/// A closed ring (first point = last) with its edges bucketed by y.
#[derive(Debug, Clone)]
pub struct IndexedRing {
    points: Vec<Coord<f64>>,
    low: Coord<f64>,
    high: Coord<f64>,
    band_m: f64,
    /// Per band, the edges (index of their first point) whose y-span meets it.
    bands: Vec<Vec<u32>>,
}

impl IndexedRing {
    /// Indexes `ring`; an open ring is closed.
    pub fn new(ring: &[Coord<f64>]) -> Self {
        let mut points = ring.to_vec();
        if let (Some(&first), Some(&last)) = (points.first(), points.last()) {
            if first != last {
                points.push(first);
            }
        }
        let (low, high) = super::bounds(&points);
        let edges = points.len().saturating_sub(1);
        // About eight edges a band on a round ring; one band for small rings.
        let count = (edges / 8).clamp(1, 4096);
        let band_m = ((high.y - low.y) / count as f64).max(1e-9);
        let mut bands = vec![Vec::new(); count];
        for k in 0..edges {
            let (a, b) = (points[k], points[k + 1]);
            let first = ((a.y.min(b.y) - low.y) / band_m).floor().max(0.0) as usize;
            let last = (((a.y.max(b.y) - low.y) / band_m).floor().max(0.0) as usize).min(count - 1);
            for band in bands.iter_mut().take(last + 1).skip(first.min(count - 1)) {
                band.push(k as u32);
            }
        }
        Self {
            points,
            low,
            high,
            band_m,
            bands,
        }
    }

    /// The ring's points, closed (first = last).
    pub fn points(&self) -> &[Coord<f64>] {
        &self.points
    }

    /// The ring's bounding box: its lowest and highest corners.
    pub fn bounds(&self) -> (Coord<f64>, Coord<f64>) {
        (self.low, self.high)
    }

    fn band(&self, y: f64) -> usize {
        (((y - self.low.y) / self.band_m).floor().max(0.0) as usize).min(self.bands.len() - 1)
    }

    /// Even-odd point in ring (the rule of [`super::validate::point_in_ring`]).
    pub fn contains(&self, p: Coord<f64>) -> bool {
        if self.bands.is_empty()
            || p.x < self.low.x
            || p.x > self.high.x
            || p.y < self.low.y
            || p.y > self.high.y
        {
            return false;
        }
        let mut inside = false;
        for &k in &self.bands[self.band(p.y)] {
            let (a, b) = (self.points[k as usize], self.points[k as usize + 1]);
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                inside = !inside;
            }
        }
        inside
    }

    /// Whether the ring's boundary passes within `distance_m` of `p`.
    pub fn near(&self, p: Coord<f64>, distance_m: f64) -> bool {
        if self.bands.is_empty()
            || p.x < self.low.x - distance_m
            || p.x > self.high.x + distance_m
            || p.y < self.low.y - distance_m
            || p.y > self.high.y + distance_m
        {
            return false;
        }
        let (first, last) = (self.band(p.y - distance_m), self.band(p.y + distance_m));
        (first..=last).any(|band| {
            self.bands[band].iter().any(|&k| {
                let (a, b) = (self.points[k as usize], self.points[k as usize + 1]);
                distance_to_segment(p, a, b) <= distance_m
            })
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::validate::point_in_ring;
    use proptest::prelude::*;

    proptest! {
        /// Against the plain tests on a wavy ring of many vertices.
        #[test]
        fn the_index_answers_as_the_plain_tests(
            count in 3usize..400,
            wave in 0.0f64..0.6,
            x in -1.5f64..1.5,
            y in -1.5f64..1.5,
            distance in 0.0f64..0.3,
        ) {
            let ring: Vec<Coord<f64>> = (0..=count)
                .map(|k| {
                    let angle = std::f64::consts::TAU * (k % count) as f64 / count as f64;
                    let radius = 1.0 + wave * (5.0 * angle).sin();
                    Coord { x: radius * angle.cos(), y: radius * angle.sin() }
                })
                .collect();
            let index = IndexedRing::new(&ring);
            let p = Coord { x, y };
            prop_assert_eq!(index.contains(p), point_in_ring(p, &ring));
            let plain = ring
                .windows(2)
                .any(|pair| distance_to_segment(p, pair[0], pair[1]) <= distance);
            prop_assert_eq!(index.near(p, distance), plain);
        }
    }
}
