//! A terrain raster made for the inner loop of track planning: millions of height queries
//! per second, with no `Result` and no trait object on the way.
//!
//! A track planner evaluates its cost some 150,000 times per run, each time sampling the
//! terrain at every waypoint and along every segment. The analytic terrain of seed 000 costs
//! seven exponentials and five trigonometric calls per query; this raster holds it sampled
//! at 1 m and answers by bilinear interpolation (off by less than 0.15 m from the formula,
//! test `the_orchard_raster_follows_its_formula`). A DEM is held as read.
//!
//! Queries outside the raster take the nearest edge value: the planners clamp their
//! waypoints to the map, and the edge is where a segment sampled at its ends can touch.
//!
//! The queries along legs (is a segment clear of the ground, how far a leg strays under it
//! or out of the height band) are in `legs`, with the block bounds that let them skip most
//! of the walking.

mod legs;
mod raised;

use crate::terrain::{Extent, Grid, Terrain};
use crate::TerrainError;

pub use legs::LegExcess;

/// How heights between cell centres are read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sampling {
    /// Bilinear between the four surrounding centres.
    Bilinear,
    /// The nearest centre, rounding halves away from zero: SPSO's `H(round(y), round(x))`.
    Nearest,
}

/// Heights at the centres of a regular lattice: `heights[row · columns + column]` is the
/// height at (origin_x + column · cell, origin_y + row · cell). Rows go with +y.
#[derive(Debug, Clone)]
pub struct HeightMap {
    origin_x: f64,
    origin_y: f64,
    cell: f64,
    /// 1 / cell: a multiplication in the inner loop instead of a division.
    per_cell: f64,
    /// The last column and row, as floats: the clamps of the inner loop.
    last_u: f64,
    last_v: f64,
    columns: usize,
    rows: usize,
    heights: Vec<f32>,
    sampling: Sampling,
    /// Highest height over blocks of `BLOCK × BLOCK` cells (and one cell of overlap), so
    /// that a segment well above its blocks is cleared without walking it.
    block_max: Vec<f32>,
    /// Lowest height over the same blocks, so that a stretch well inside the height band
    /// is cleared without walking it too.
    block_min: Vec<f32>,
    block_columns: usize,
    /// The same terrain on every [`COARSE`]-th centre (rasters of more than 2·COARSE cells a
    /// side): where a leg is clear of the ground, its band excursion is read there.
    coarse: Option<Box<HeightMap>>,
    /// The lowest and highest heights held.
    lowest: f64,
    highest: f64,
}

/// √(dx² + dy²) without `hypot`'s overflow care, which costs a fifth of a track evaluation.
pub fn planar_length(dx: f64, dy: f64) -> f64 {
    (dx * dx + dy * dy).sqrt()
}

const BLOCK: usize = 16;

/// The coarse raster's cell, in cells of the full one.
const COARSE: usize = 8;

/// Most samples a sampled height map holds (16 MB of heights).
pub const MAX_SAMPLES: f64 = 4.0e6;

impl HeightMap {
    /// A raster from row-major heights (row 0 at `origin_y`, rows going with +y).
    pub fn new(
        origin: (f64, f64),
        cell: f64,
        columns: usize,
        rows: usize,
        heights: Vec<f32>,
        sampling: Sampling,
    ) -> Self {
        assert_eq!(
            heights.len(),
            columns * rows,
            "heights must fill the raster"
        );
        assert!(columns >= 2 && rows >= 2 && cell > 0.0);
        let block_columns = columns.div_ceil(BLOCK);
        let block_rows = rows.div_ceil(BLOCK);
        let mut block_max = vec![f32::NEG_INFINITY; block_columns * block_rows];
        let mut block_min = vec![f32::INFINITY; block_columns * block_rows];
        for row in 0..rows {
            for column in 0..columns {
                let height = heights[row * columns + column];
                // A cell on a block's edge also counts for the neighbouring block: bilinear
                // heights inside a block blend the cells just beyond it.
                let block_row_range =
                    (row.saturating_sub(1) / BLOCK)..=((row + 1).min(rows - 1) / BLOCK);
                for block_row in block_row_range {
                    let block_column_range = (column.saturating_sub(1) / BLOCK)
                        ..=((column + 1).min(columns - 1) / BLOCK);
                    for block_column in block_column_range {
                        let slot = block_row * block_columns + block_column;
                        block_max[slot] = block_max[slot].max(height);
                        block_min[slot] = block_min[slot].min(height);
                    }
                }
            }
        }
        let (lowest, highest) = heights
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), &h| {
                (low.min(f64::from(h)), high.max(f64::from(h)))
            });
        // Every fourth centre, for the band's excursion where a leg is clear of the ground:
        // small enough to stay in the processor's cache, where the full raster is not.
        let coarse = (columns > 2 * COARSE && rows > 2 * COARSE && sampling == Sampling::Bilinear)
            .then(|| {
                let (coarse_columns, coarse_rows) =
                    ((columns - 1) / COARSE + 1, (rows - 1) / COARSE + 1);
                let picked = (0..coarse_rows)
                    .flat_map(|row| {
                        let heights = &heights;
                        (0..coarse_columns)
                            .map(move |column| heights[row * COARSE * columns + column * COARSE])
                    })
                    .collect();
                let mut map = HeightMap::new(
                    origin,
                    cell * COARSE as f64,
                    coarse_columns,
                    coarse_rows,
                    picked,
                    Sampling::Nearest,
                );
                map.sampling = Sampling::Bilinear;
                Box::new(map)
            });
        Self {
            coarse,
            lowest,
            highest,
            origin_x: origin.0,
            origin_y: origin.1,
            cell,
            per_cell: 1.0 / cell,
            last_u: (columns - 1) as f64,
            last_v: (rows - 1) as f64,
            columns,
            rows,
            heights,
            sampling,
            block_max,
            block_min,
            block_columns,
        }
    }

    /// Samples `terrain` at every `cell` metres over [min_x, max_x] × [min_y, max_y] (a
    /// coarser cell for areas above [`MAX_SAMPLES`] samples; at least 2 × 2 samples).
    /// Points the terrain cannot answer are an error naming the point.
    pub fn sample(
        terrain: &dyn Terrain,
        (min_x, min_y, max_x, max_y): (f64, f64, f64, f64),
        cell: f64,
    ) -> Result<Self, crate::TerrainError> {
        let (width, height) = ((max_x - min_x).max(0.0), (max_y - min_y).max(0.0));
        let cell = cell
            .max((width * height / MAX_SAMPLES).sqrt())
            .max(width.max(height) / MAX_SAMPLES.sqrt())
            .max(f64::MIN_POSITIVE);
        let columns = ((width / cell).round() as usize + 1).max(2);
        let rows = ((height / cell).round() as usize + 1).max(2);
        let mut heights = Vec::with_capacity(columns * rows);
        for row in 0..rows {
            let y = (min_y + row as f64 * cell).min(max_y);
            for column in 0..columns {
                let x = (min_x + column as f64 * cell).min(max_x);
                heights.push(terrain.height_m(x, y)? as f32);
            }
        }
        Ok(Self::new(
            (min_x, min_y),
            cell,
            columns,
            rows,
            heights,
            Sampling::Bilinear,
        ))
    }

    /// A DEM in SPSO's model units: x = column + 1, y = row + 1 (row 0 is the raster's top,
    /// as MATLAB's `imread` returns it), one unit per pixel, negative heights set to 0 as
    /// SPSO's `CreateModel.m` does, read at the nearest pixel.
    pub fn from_grid_in_pixel_units(grid: &Grid) -> Self {
        let heights = grid
            .heights
            .iter()
            .map(|&height| {
                if height.is_nan() {
                    0.0
                } else {
                    height.max(0.0)
                }
            })
            .collect();
        Self::new(
            (1.0, 1.0),
            1.0,
            grid.columns,
            grid.rows,
            heights,
            Sampling::Nearest,
        )
    }

    /// The spacing between neighbouring centres, in the map's horizontal unit (metres, or pixels
    /// for a map in pixel units).
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// How heights between centres are read.
    pub fn sampling(&self) -> Sampling {
        self.sampling
    }

    /// (min_x, min_y, max_x, max_y) of the cell centres.
    pub fn bounds(&self) -> (f64, f64, f64, f64) {
        (
            self.origin_x,
            self.origin_y,
            self.origin_x + (self.columns - 1) as f64 * self.cell,
            self.origin_y + (self.rows - 1) as f64 * self.cell,
        )
    }

    /// Lowest and highest height held.
    pub fn range(&self) -> (f64, f64) {
        (self.lowest, self.highest)
    }

    #[inline(always)]
    fn at(&self, row: usize, column: usize) -> f64 {
        f64::from(self.heights[row * self.columns + column])
    }

    /// The height at (x, y) in this map's own sampling.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        match self.sampling {
            Sampling::Bilinear => self.bilinear(x, y),
            Sampling::Nearest => self.nearest(x, y),
        }
    }

    /// The nearest centre's height.
    #[inline(always)]
    pub fn nearest(&self, x: f64, y: f64) -> f64 {
        let column = ((x - self.origin_x) / self.cell).round();
        let row = ((y - self.origin_y) / self.cell).round();
        let column = column.clamp(0.0, (self.columns - 1) as f64) as usize;
        let row = row.clamp(0.0, (self.rows - 1) as f64) as usize;
        self.at(row, column)
    }

    /// The bilinear height: what a physical surface through the centres looks like.
    #[inline(always)]
    pub fn bilinear(&self, x: f64, y: f64) -> f64 {
        // The inner loop of every track cost: two row slices, so that the four reads are
        // checked twice, not four times; the last cell's far side is its edge.
        let u = ((x - self.origin_x) * self.per_cell).clamp(0.0, self.last_u);
        let v = ((y - self.origin_y) * self.per_cell).clamp(0.0, self.last_v);
        let column = (u as usize).min(self.columns - 2);
        let row = (v as usize).min(self.rows - 2);
        let (fu, fv) = (u - column as f64, v - row as f64);
        let start = row * self.columns + column;
        let low = &self.heights[start..start + 2];
        let high = &self.heights[start + self.columns..start + self.columns + 2];
        let low = f64::from(low[0]) + (f64::from(low[1]) - f64::from(low[0])) * fu;
        let high = f64::from(high[0]) + (f64::from(high[1]) - f64::from(high[0])) * fu;
        low + (high - low) * fv
    }
}

/// A height map is a terrain too (bilinear between its centres), for the pictures.
impl Terrain for HeightMap {
    fn height_m(&self, x: f64, y: f64) -> Result<f64, TerrainError> {
        Ok(self.bilinear(x, y))
    }

    fn extent(&self) -> Option<Extent> {
        let (min_x, min_y, max_x, max_y) = self.bounds();
        Some(Extent {
            min_x,
            min_y,
            max_x,
            max_y,
        })
    }

    /// The lattice's lines: bilinear interpolation bends there.
    fn bends_along(&self, from: (f64, f64), to: (f64, f64)) -> Vec<f64> {
        crate::terrain::lattice_bends(
            from,
            to,
            (self.origin_x, self.origin_y),
            (self.cell, self.cell),
        )
    }

    fn lattice(&self) -> Option<((f64, f64), (f64, f64))> {
        Some(((self.origin_x, self.origin_y), (self.cell, self.cell)))
    }

    fn describe(&self) -> String {
        format!("height map of {} m cells", self.cell())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::Composite;

    fn ramp() -> HeightMap {
        // height = x + 10·y on a 3 × 3 lattice of 2 m cells.
        let heights = (0..3)
            .flat_map(|row| (0..3).map(move |column| (2 * column + 20 * row) as f32))
            .collect();
        HeightMap::new((0.0, 0.0), 2.0, 3, 3, heights, Sampling::Bilinear)
    }

    /// A 1 m lattice with one node 20 m higher (1 m samples along this leg read it as 15.45 m,
    /// decision 0028): the places a track leg is checked at find it, as 0.5 mm samples do.
    #[test]
    fn a_peak_one_cell_wide_is_found_along_a_leg() {
        let (columns, rows) = (12, 12);
        let mut heights = vec![0.0f32; columns * rows];
        heights[5 * columns + 6] = 20.0;
        let map = HeightMap::new((0.0, 0.0), 1.0, columns, rows, heights, Sampling::Bilinear);
        let (from, to): ((f64, f64), (f64, f64)) = ((0.5, 5.0), (11.0, 5.0));
        let length = (to.0 - from.0).hypot(to.1 - from.1);
        let ground =
            |t: f64| map.bilinear(from.0 + t * (to.0 - from.0), from.1 + t * (to.1 - from.1));
        let places =
            crate::terrain::profile_places(&map, from, to, length, 1.0, |t| Some(vec![ground(t)]));
        let highest =
            |places: &mut dyn Iterator<Item = f64>| places.map(ground).fold(0.0, f64::max);
        let found = highest(&mut places.into_iter());
        let fine = highest(&mut (0..=30_000).map(|k| f64::from(k) / 30_000.0));
        let metre = highest(&mut crate::geometry::leg_samples(length, 1.0));
        assert!(found >= fine - 1e-9, "{found} against {fine}");
        assert!(
            fine - metre > 1.0,
            "the case: {metre} at 1 m against {fine}"
        );
    }

    #[test]
    fn bilinear_reproduces_a_plane() {
        let map = ramp();
        for &(x, y) in &[(0.0, 0.0), (1.0, 1.0), (3.5, 0.5), (4.0, 4.0), (2.2, 3.9)] {
            assert!((map.bilinear(x, y) - (x + 10.0 * y)).abs() < 1e-9);
        }
        // Outside: the nearest edge value.
        assert!((map.bilinear(-5.0, 0.0) - 0.0).abs() < 1e-9);
        assert!((map.bilinear(9.0, 4.0) - 44.0).abs() < 1e-9);
    }

    #[test]
    fn nearest_rounds_halves_away_from_zero_like_matlab() {
        let heights = vec![1.0, 2.0, 3.0, 4.0];
        let map = HeightMap::new((1.0, 1.0), 1.0, 2, 2, heights, Sampling::Nearest);
        assert_eq!(map.height(1.49, 1.0), 1.0);
        assert_eq!(map.height(1.5, 1.0), 2.0);
        assert_eq!(map.height(1.0, 1.5), 3.0);
    }

    #[test]
    fn segment_clearance_sees_a_ridge_between_clear_ends() {
        // A 50 m ridge at x = 50 on flat ground.
        let heights = (0..11)
            .flat_map(|_| (0..11).map(|column| if column == 5 { 50.0 } else { 0.0 }))
            .collect();
        let map = HeightMap::new((0.0, 0.0), 10.0, 11, 11, heights, Sampling::Bilinear);
        let (a, b) = ([0.0, 50.0, 30.0], [100.0, 50.0, 30.0]);
        assert!((map.lowest_clearance(a, b) - -20.0).abs() < 1e-9);
        assert!(!map.segment_clears(a, b, 0.0));
        assert!(map.segment_clears([0.0, 50.0, 60.0], [100.0, 50.0, 60.0], 0.0));
    }

    #[test]
    fn leg_excess_agrees_with_walking_every_cell() {
        let terrain = Composite::seed000();
        let map = HeightMap::sample(&terrain, (0.0, 0.0, 1000.0, 1000.0), 2.0).unwrap();
        let mut draw = 12345u64;
        let mut uniform = |low: f64, high: f64| {
            draw = draw
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            low + (high - low) * (draw >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..300 {
            let a = [
                uniform(0.0, 1000.0),
                uniform(0.0, 1000.0),
                uniform(0.0, 200.0),
            ];
            let b = [
                uniform(0.0, 1000.0),
                uniform(0.0, 1000.0),
                uniform(0.0, 200.0),
            ];
            let (clearance, band) = (2.0, Some((30.0, 150.0)));
            let excess = map.leg_excess(a, b, clearance, band);
            let horizontal = planar_length(b[0] - a[0], b[1] - a[1]);
            let steps = ((horizontal / map.cell()).ceil() as usize).max(1);
            let (mut under, mut outside, mut dips) = (0.0, 0.0, false);
            for step in 0..steps {
                let t = (step as f64 + 0.5) / steps as f64;
                let p = [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]));
                let above = p[2] - map.bilinear(p[0], p[1]);
                under += (clearance - above).max(0.0) * horizontal / steps as f64;
                dips |= above < clearance;
                outside += ((30.0 - above).max(0.0) + (above - 150.0).max(0.0)) * horizontal
                    / steps as f64;
            }
            assert_eq!(excess.dips, dips);
            assert!(
                (excess.under_ground - under).abs() <= 1e-6 * under.max(1.0),
                "{} vs {under}",
                excess.under_ground
            );
            // Clear of the ground, the band is read on the coarse raster (16 m here): within a
            // quarter of the excursion and a quarter of a metre of it over the leg's length.
            assert!(
                (excess.outside_band - outside).abs() <= 0.25 * outside + 0.25 * horizontal,
                "{} vs {outside}",
                excess.outside_band
            );
        }
    }

    #[test]
    fn the_orchard_raster_follows_its_formula() {
        let terrain = Composite::seed000();
        let map = HeightMap::sample(
            &terrain,
            (0.0, 0.0, 1000.0, 1000.0),
            crate::track::scenario::ORCHARD_CELL_M,
        )
        .unwrap();
        let mut worst: f64 = 0.0;
        for index in 0..20000 {
            let x = (index as f64 * 7.31) % 1000.0;
            let y = (index as f64 * 3.17 + 0.4) % 1000.0;
            worst = worst.max((map.height(x, y) - terrain.height_m(x, y).unwrap()).abs());
        }
        assert!(worst < 0.6, "worst difference {worst} m");
    }
}
