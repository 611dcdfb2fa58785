//! The ground as the track planners' costs see it where the safety verdict measures clearance
//! sideways (decision 0030): raised wherever a slope or a bank within reach is nearer than
//! the clearance, so that an altitude the costs accept keeps the clearance in any direction.
//!
//! A point keeps a distance c from the ground surface g in every direction exactly when it
//! lies above the ground dilated by a ball of radius c (a morphological dilation):
//!
//! D(x) = max over p with |p − x| ≤ c of g(p) + √(c² − |p − x|²).
//!
//! Over level ground D = g + c, the costs' old floor; over a plain slope of gradient s,
//! D = g + c·√(1 + s²). The map holds, at every centre, an upper bound of D over the bilinear
//! surface between the centres (so the costs are never less careful than the verdict, up to
//! the bilinear reading of the bound between centres), from blocks of k × k cells:
//!
//! - a block the centre lies in or on: its highest corner + c, or (tighter on a slope) the
//!   centre's height + c·√(1 + s_B²), s_B bounding the gradient over the block (a bilinear
//!   cell's gradient is bounded by its steepest edges along x and along y; the ground is
//!   then s_B-Lipschitz along the straight path to any point of the block);
//! - a block at horizontal distance d ≤ c: its highest corner + √(c² − d²) (every point of
//!   it is at least d away and no higher).
//!
//! The bound is exact on a plain slope at the centre's own cells and conservative by at most
//! the ground's rise over a block beyond them (their highest corner taken at their nearest
//! point): tracks over steep ground fly that much higher than they need. k = 1 reads every
//! cell in reach; larger k where a clearance spans many cells, so that the
//! work stays under [`WORK`] block visits. The map the costs use is max(g, D − c − a), with a
//! the costs' allowance ([`super::super::scenario::TrackScenario::cost_clearance`]): the costs
//! then treat max(g + c + a, D) as the lowest safe altitude. Over ground no steeper than
//! √((1 + a/c)² − 1) anywhere, D ≤ g + c + a everywhere and the map is not made at all, so
//! the papers' gentle terrains are costed as before.

use super::HeightMap;

/// Most block visits the raised map may take, at least 16 per centre.
const WORK: f64 = 4.0e7;

impl HeightMap {
    /// The ground raised for a clearance of `clearance_m` in any direction, with the costs'
    /// `allowance_m` over it (module documentation); `unit_m` metres per horizontal unit.
    /// `None` where no slope is steep enough to matter.
    pub fn raised_for_clearance(
        &self,
        unit_m: f64,
        clearance_m: f64,
        allowance_m: f64,
    ) -> Option<HeightMap> {
        let (columns, rows) = (self.columns, self.rows);
        let cell_m = self.cell * unit_m;
        let c = clearance_m;
        if !(c > 0.0 && cell_m > 0.0) {
            return None;
        }
        // Each cell's steepest gradient bound.
        let cells = (columns - 1, rows - 1);
        let mut cell_slope = vec![0.0f64; cells.0 * cells.1];
        for row in 0..cells.1 {
            for column in 0..cells.0 {
                let (z00, z10) = (self.at(row, column), self.at(row, column + 1));
                let (z01, z11) = (self.at(row + 1, column), self.at(row + 1, column + 1));
                let along_x = (z10 - z00).abs().max((z11 - z01).abs()) / cell_m;
                let along_y = (z01 - z00).abs().max((z11 - z10).abs()) / cell_m;
                cell_slope[row * cells.0 + column] = along_x.hypot(along_y);
            }
        }
        // Nothing to raise where even the steepest cell stays within the allowance.
        let steepest = cell_slope.iter().copied().fold(0.0, f64::max);
        if c * (steepest.hypot(1.0) - 1.0) <= allowance_m {
            return None;
        }
        let reach_cells = c / cell_m;
        let centres = (columns * rows) as f64;
        let budget = WORK.max(16.0 * centres);
        let mut k = 1usize;
        while centres * (2.0 * reach_cells / k as f64 + 3.0).powi(2) > budget {
            k += 1;
        }
        // Blocks of k × k cells: highest corner and steepest gradient.
        let blocks = (cells.0.div_ceil(k), cells.1.div_ceil(k));
        let mut block_high = vec![f64::NEG_INFINITY; blocks.0 * blocks.1];
        let mut block_slope = vec![0.0f64; blocks.0 * blocks.1];
        for row in 0..cells.1 {
            for column in 0..cells.0 {
                let slot = (row / k) * blocks.0 + column / k;
                let corners = [
                    self.at(row, column),
                    self.at(row, column + 1),
                    self.at(row + 1, column),
                    self.at(row + 1, column + 1),
                ];
                block_high[slot] = corners.into_iter().fold(block_high[slot], f64::max);
                block_slope[slot] = block_slope[slot].max(cell_slope[row * cells.0 + column]);
            }
        }
        let span = |block: usize, count: usize| (block * k, ((block + 1) * k).min(count));
        let gap = |at: usize, (low, high): (usize, usize)| {
            if at < low {
                (low - at) as f64
            } else if at > high {
                (at - high) as f64
            } else {
                0.0
            }
        };
        let reach_blocks = (reach_cells / k as f64).floor() as usize + 1;
        let mut raised = Vec::with_capacity(columns * rows);
        let mut any = false;
        for row in 0..rows {
            let block_rows = (row / k).saturating_sub(reach_blocks)
                ..=((row / k) + reach_blocks).min(blocks.1 - 1);
            for column in 0..columns {
                let ground = self.at(row, column);
                let mut dilated = ground + c;
                let block_columns = (column / k).saturating_sub(reach_blocks)
                    ..=((column / k) + reach_blocks).min(blocks.0 - 1);
                for block_row in block_rows.clone() {
                    let dy = gap(row, span(block_row, cells.1));
                    for block_column in block_columns.clone() {
                        let dx = gap(column, span(block_column, cells.0));
                        let distance = dx.hypot(dy) * cell_m;
                        if distance > c {
                            continue;
                        }
                        let slot = block_row * blocks.0 + block_column;
                        let bound = if distance == 0.0 {
                            (block_high[slot] + c).min(ground + c * block_slope[slot].hypot(1.0))
                        } else {
                            block_high[slot] + (c * c - distance * distance).sqrt()
                        };
                        dilated = dilated.max(bound);
                    }
                }
                let floor = ground.max(dilated - c - allowance_m);
                any |= floor > ground + 1e-3;
                raised.push(floor as f32);
            }
        }
        any.then(|| {
            HeightMap::new(
                (self.origin_x, self.origin_y),
                self.cell,
                columns,
                rows,
                raised,
                self.sampling,
            )
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::Sampling;
    use super::*;

    /// A map of `heights(x, y)` on a `cell`-metre lattice of `side` × `side` centres.
    fn map(side: usize, cell: f64, heights: impl Fn(f64, f64) -> f64) -> HeightMap {
        let values = (0..side)
            .flat_map(|row| (0..side).map(move |column| (row, column)))
            .map(|(row, column)| heights(column as f64 * cell, row as f64 * cell) as f32)
            .collect();
        HeightMap::new((0.0, 0.0), cell, side, side, values, Sampling::Bilinear)
    }

    /// The distance from `point` to the bilinear surface of `map`, by brute force on a fine
    /// grid of surface points within `reach` (an upper bound of the true distance, tight to
    /// the grid's spacing).
    fn distance_to_ground(map: &HeightMap, point: [f64; 3], reach: f64) -> f64 {
        let step = 0.1;
        let steps = (reach / step).ceil() as i64;
        let mut nearest = point[2] - map.bilinear(point[0], point[1]);
        for i in -steps..=steps {
            for j in -steps..=steps {
                let (x, y) = (point[0] + i as f64 * step, point[1] + j as f64 * step);
                let (min_x, min_y, max_x, max_y) = map.bounds();
                if x < min_x || y < min_y || x > max_x || y > max_y {
                    continue;
                }
                let dz = point[2] - map.bilinear(x, y);
                nearest = nearest.min((i as f64 * step).hypot(j as f64 * step).hypot(dz));
            }
        }
        nearest
    }

    #[test]
    fn gentle_ground_is_not_raised_and_a_plain_slope_is_raised_by_its_secant() {
        // 10 %: 30 m of clearance needs 0.15 m more than straight down, within 0.6 m.
        let gentle = map(40, 2.0, |x, _| 0.1 * x);
        assert!(gentle.raised_for_clearance(1.0, 30.0, 0.6).is_none());
        // 100 % (45°): the lowest safe altitude is c·√2 above the ground.
        let steep = map(40, 2.0, |x, _| x);
        let raised = steep.raised_for_clearance(1.0, 10.0, 0.6).expect("raised");
        let (x, y) = (40.0, 40.0);
        let lowest_safe = raised.bilinear(x, y) + 10.6;
        let want = steep.bilinear(x, y) + 10.0 * 2f64.sqrt();
        assert!(lowest_safe >= want - 1e-3, "{lowest_safe} < {want}");
        // Conservative by at most the ground's rise over a cell (the cells beyond the
        // centre's own are bounded by their highest corner at their nearest point).
        assert!(
            lowest_safe <= want + 2.0 + 0.6,
            "{lowest_safe} far above {want}"
        );
    }

    #[test]
    fn an_altitude_the_raised_ground_accepts_keeps_the_clearance_beside_a_cliff() {
        // A step 30 m high, one cell wide, and a knife-edge peak: at every centre of the
        // map, the lowest altitude the costs accept keeps at least the clearance from the
        // bilinear surface in any direction (brute force), and is not wildly above it.
        let ground = |x: f64, y: f64| {
            let step = if x > 20.0 { 30.0 } else { 0.0 };
            let peak = (25.0 - (x - 10.0).hypot(y - 30.0) * 5.0).max(0.0);
            step + peak
        };
        let cliff = map(25, 2.0, ground);
        let clearance = 8.0;
        let raised = cliff
            .raised_for_clearance(1.0, clearance, 0.6)
            .expect("raised");
        let mut worst_excess: f64 = 0.0;
        for row in 0..25 {
            for column in 0..25 {
                let (x, y) = (column as f64 * 2.0, row as f64 * 2.0);
                let altitude = raised.bilinear(x, y) + clearance + 0.6;
                let distance = distance_to_ground(&cliff, [x, y, altitude], clearance + 1.0);
                assert!(
                    distance >= clearance - 0.05,
                    "({x}, {y}) at {altitude:.2}: {distance:.2} m from the ground"
                );
                worst_excess = worst_excess.max(distance - clearance);
            }
        }
        // Conservative, not absurd: within a few metres of the clearance somewhere near the
        // step (the block bounds and the slope bound overestimate, but not by the step).
        assert!(worst_excess < 30.0, "{worst_excess}");
    }

    #[test]
    fn a_wide_reach_over_a_fine_raster_uses_blocks_and_stays_safe() {
        // 1,000 m of clearance over a 1 m raster: blocks of many cells, still an upper bound.
        let hill = map(200, 1.0, |x, y| {
            (60.0 - 0.8 * (x - 100.0).hypot(y - 100.0)).max(0.0)
        });
        let raised = hill.raised_for_clearance(1.0, 1000.0, 0.6).expect("raised");
        // At the hill's top the ball's cap sits on the peak: c above it.
        let top = raised.bilinear(100.0, 100.0) + 1000.6;
        assert!(top >= 60.0 + 1000.0 - 1e-3, "{top}");
        // At the map's corner, 141 m from the top, the cap over the peak still binds.
        let corner = raised.bilinear(0.0, 0.0) + 1000.6;
        let want = 60.0 + (1000.0f64.powi(2) - 141.42f64.powi(2)).sqrt();
        assert!(corner >= want - 0.1, "{corner} < {want}");
    }
}
