//! Queries along a leg of a track: whether a segment clears the ground, how far a leg goes
//! under it or out of the height band, its lowest clearance. The block bounds of the raster
//! (`BLOCK` cells a side) clear most stretches without walking them cell by cell.

use super::{planar_length, HeightMap, Sampling, BLOCK};

/// Where a stretch of leg is proven clear of the ground, its band excursion is sampled every
/// this many cells.
const BAND_STRIDE: usize = 4;

/// What a leg does between its ends ([`HeightMap::leg_excess`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LegExcess {
    /// ∫ depth under the ground (raised by the clearance) along the leg (units × metres).
    pub under_ground: f64,
    /// ∫ distance outside the height band along the leg (scenario units × metres).
    pub outside_band: f64,
    /// Whether any sample is under the ground (raised by the clearance).
    pub dips: bool,
}
impl HeightMap {
    /// The lowest and highest heights in the blocks that the box [x0, x1] × [y0, y1] touches:
    /// bounds of the terrain under anything inside the box.
    #[inline]
    fn range_under(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> (f64, f64) {
        let to_block = |value: f64, origin: f64, count: usize| -> usize {
            let cell = ((value - origin) * self.per_cell).clamp(0.0, (count - 1) as f64);
            cell as usize / BLOCK
        };
        let (c0, c1) = (
            to_block(x0, self.origin_x, self.columns),
            to_block(x1, self.origin_x, self.columns),
        );
        let (r0, r1) = (
            to_block(y0, self.origin_y, self.rows),
            to_block(y1, self.origin_y, self.rows),
        );
        let (mut lowest, mut highest) = (f32::INFINITY, f32::NEG_INFINITY);
        for row in r0..=r1 {
            for column in c0..=c1 {
                let slot = row * self.block_columns + column;
                highest = highest.max(self.block_max[slot]);
                lowest = lowest.min(self.block_min[slot]);
            }
        }
        (f64::from(lowest), f64::from(highest))
    }

    /// Whether the straight segment a → b (z above sea level) stays more than `clearance`
    /// above the bilinear terrain at the samples of [`HeightMap::lowest_clearance`] (every
    /// half cell). The samples are taken in runs about a block long; a run whose stretch of
    /// segment is higher than its blocks' highest point is cleared without sampling, so only
    /// stretches near the ground are walked, and the answer is the same as walking them all.
    pub fn segment_clears(&self, a: [f64; 3], b: [f64; 3], clearance: f64) -> bool {
        if a[2].min(b[2]) > self.highest + clearance {
            return true;
        }
        let steps = self.samples(a, b);
        let per_run = 2 * BLOCK;
        let at = |step: usize| -> [f64; 3] {
            let t = step as f64 / steps as f64;
            [
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            ]
        };
        (0..=steps).step_by(per_run).all(|first| {
            let last = (first + per_run).min(steps);
            let (from, to) = (at(first), at(last));
            let (_, highest) = self.range_under(
                from[0].min(to[0]),
                from[1].min(to[1]),
                from[0].max(to[0]),
                from[1].max(to[1]),
            );
            from[2].min(to[2]) > highest + clearance
                || (first..=last).all(|step| {
                    let p = at(step);
                    p[2] - self.bilinear(p[0], p[1]) > clearance
                })
        })
    }

    /// How far the straight leg a → b (z above sea level) goes under the terrain raised by
    /// `clearance` and out of the height band `band` (heights above the ground), integrated
    /// along the leg (scenario units × metres), on this map's own sampling:
    /// - the depth: a sample at the middle of every one-cell stretch counts its depth times
    ///   the stretch's horizontal length, exactly as walking every cell (stretches whose
    ///   16 × 16-cell blocks prove them clear are skipped, and count nothing);
    /// - the band: the same samples where a stretch may be near the ground; where its blocks
    ///   (or the whole map's highest point) prove it clear of the ground, on the coarse raster
    ///   of every 8th centre, one sample per coarse cell: the band is a preference, smooth
    ///   along a leg, and this keeps one IBA-FCS run under a second (decision 0013).
    pub fn leg_excess(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        clearance: f64,
        band: Option<(f64, f64)>,
    ) -> LegExcess {
        let mut excess = LegExcess::default();
        let (floor, ceiling) = band.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        let horizontal = planar_length(b[0] - a[0], b[1] - a[1]);
        let steps = ((horizontal / self.cell).ceil() as usize).max(1);
        let stretch = horizontal / steps as f64;
        let at = |t: f64| -> [f64; 3] { [0, 1, 2].map(|axis| a[axis] + t * (b[axis] - a[axis])) };
        // (clear of the ground, inside the band) for the stretch from → to, by its blocks.
        let proven = |from: [f64; 3], to: [f64; 3]| {
            let (lowest, highest) = self.range_under(
                from[0].min(to[0]),
                from[1].min(to[1]),
                from[0].max(to[0]),
                from[1].max(to[1]),
            );
            let (low_z, high_z) = (from[2].min(to[2]), from[2].max(to[2]));
            (
                low_z - highest > clearance,
                low_z - highest > floor && high_z - lowest < ceiling,
            )
        };
        // A leg above the highest ground by more than the floor and under the lowest ground's
        // ceiling needs no walk; above the highest ground by the clearance, only the band's
        // excursion is measured, walked without testing runs.
        let (low_z, high_z) = (a[2].min(b[2]), a[2].max(b[2]));
        let clear_leg = low_z - self.highest > clearance;
        if clear_leg && low_z - self.highest > floor && high_z - self.lowest < ceiling {
            return excess;
        }
        if clear_leg {
            // The coarse raster's own blocks (16 coarse cells a side) may prove the leg inside
            // the band where the whole map's extremes cannot.
            if let Some(coarse) = &self.coarse {
                let (lowest, highest) = coarse.range_under(
                    a[0].min(b[0]),
                    a[1].min(b[1]),
                    a[0].max(b[0]),
                    a[1].max(b[1]),
                );
                if low_z - highest > floor && high_z - lowest < ceiling {
                    return excess;
                }
            }
            excess.outside_band = self.band_excess(a, b, horizontal, floor, ceiling);
            return excess;
        }
        let per_run = BLOCK;
        for first in (0..steps).step_by(per_run) {
            let last = (first + per_run).min(steps);
            let (clear, inside) = proven(
                at(first as f64 / steps as f64),
                at(last as f64 / steps as f64),
            );
            if clear && inside {
                continue;
            }
            // Clear of the ground, only the band's excursion is measured, on the coarse raster
            // (it is a preference, smooth along the leg; decision 0013).
            if clear {
                let (t0, t1) = (first as f64 / steps as f64, last as f64 / steps as f64);
                let (from, to) = (at(t0), at(t1));
                excess.outside_band +=
                    self.band_excess(from, to, (t1 - t0) * horizontal, floor, ceiling);
                continue;
            }
            let (under, outside) =
                self.walk(a, b, steps, first..last, 1, clearance, floor, ceiling);
            if under > 0.0 {
                excess.dips = true;
            }
            excess.under_ground += under * stretch;
            excess.outside_band += outside * stretch;
        }
        excess
    }

    /// ∫ distance out of [floor, ceiling] along a → b (`horizontal` long), known to be clear of
    /// the ground: on the coarse raster every coarse cell, else on this one every
    /// [`BAND_STRIDE`] cells.
    fn band_excess(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        horizontal: f64,
        floor: f64,
        ceiling: f64,
    ) -> f64 {
        let (map, stride) = match &self.coarse {
            Some(coarse) => (coarse.as_ref(), 1),
            None => (self, BAND_STRIDE),
        };
        let steps = ((horizontal / map.cell).ceil() as usize).max(1);
        let (_, outside) = map.walk(
            a,
            b,
            steps,
            0..steps,
            stride,
            f64::NEG_INFINITY,
            floor,
            ceiling,
        );
        outside * horizontal / steps as f64
    }

    /// Sums of depth under `clearance` and of distance out of [floor, ceiling] at the middles
    /// of samples `range` of `steps` along a → b (every `stride`-th, each counting for the
    /// samples it stands for), heights in this map's own sampling.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn walk(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        steps: usize,
        range: std::ops::Range<usize>,
        stride: usize,
        clearance: f64,
        floor: f64,
        ceiling: f64,
    ) -> (f64, f64) {
        let height = |x: f64, y: f64| match self.sampling {
            Sampling::Bilinear => self.bilinear(x, y),
            Sampling::Nearest => self.nearest(x, y),
        };
        let per_step = 1.0 / steps as f64;
        let (dx, dy, dz) = (
            (b[0] - a[0]) * per_step,
            (b[1] - a[1]) * per_step,
            (b[2] - a[2]) * per_step,
        );
        let (mut under, mut outside) = (0.0, 0.0);
        let end = range.end;
        for step in range.step_by(stride) {
            let count = stride.min(end - step) as f64;
            let k = step as f64 + 0.5 * count;
            let above = a[2] + k * dz - height(a[0] + k * dx, a[1] + k * dy);
            under += count * (clearance - above).max(0.0);
            outside += count * ((floor - above).max(0.0) + (above - ceiling).max(0.0));
        }
        (under, outside)
    }

    /// Samples along a → b: one every half cell, at least one interval.
    fn samples(&self, a: [f64; 3], b: [f64; 3]) -> usize {
        let horizontal = planar_length(b[0] - a[0], b[1] - a[1]);
        ((horizontal / (0.5 * self.cell)).ceil() as usize).max(1)
    }

    /// The smallest height above the bilinear terrain along a → b, sampled at every half
    /// cell (and at both ends).
    pub fn lowest_clearance(&self, a: [f64; 3], b: [f64; 3]) -> f64 {
        let steps = self.samples(a, b);
        (0..=steps)
            .map(|step| {
                let t = step as f64 / steps as f64;
                let x = a[0] + t * (b[0] - a[0]);
                let y = a[1] + t * (b[1] - a[1]);
                let z = a[2] + t * (b[2] - a[2]);
                z - self.bilinear(x, y)
            })
            .fold(f64::INFINITY, f64::min)
    }
}
