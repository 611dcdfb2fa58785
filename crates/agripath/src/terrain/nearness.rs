//! How near a straight leg comes to the ground in any direction, not only straight down
//! (decision 0030).
//!
//! The vertical checks hold each sample's height above the ground beneath it. Beside a cliff
//! or a steep bank that height can be large while the ground is a metre away sideways: a
//! third trial flew a track asked for 30 m of clearance 2.24 m past a DEM's cliff face, 32.6 m
//! above the ground beneath. [`GroundNearness`] bounds the distance from a leg to the ground
//! from below, within a reach (the clearance asked for): nothing nearer than the bound is
//! ground.
//!
//! **The bound.** The ground within reach of a stretch of the leg is covered by squares of
//! a lattice aligned with the terrain's own cells (a raster's lines through its cell
//! centres, [`Terrain::lattice`]). Over a square inside one cell a bilinear surface is no
//! higher than the highest of the square's corners `G`, so every point of the ground in the
//! square is at least `min over t of √(d(t)² + max(0, z(t) − G)²)` from the leg, where `d(t)`
//! is the horizontal distance from the leg's point at `t` to the square and `z(t)` its
//! altitude (a convex function of `t`, minimised by golden-section search). Squares of several
//! cells are bounded by every node they hold. Where that coarse bound falls within reach, the
//! square is cut into its cells, and those into quarters while their bound is within reach,
//! nearest first, down to squares of reach / 32: the bound then errs, on the safe side, by at
//! most the slope across one small square. On models with no lattice (the analytic hills of
//! seed 000, plateaus, a DEM reprojected from another frame) the corners are samples of the
//! surface 1 m apart at most, and the bound is as good as that sampling.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

use geo::Coord;

use super::Terrain;
use crate::geometry::nearest_fraction_on_segment;
use crate::geometry::validate::segment_contact;

/// The smallest squares are the reach over this: their bound errs by the slope across one.
const SMALLEST_SHARE: f64 = 32.0;

/// The lattice of a model without one (metres): corners this far apart sample its surface.
const ANALYTIC_STEP_M: f64 = 1.0;

/// Keys of coarse squares hashed by a rotate, an exclusive or and a multiply (FxHash's
/// step): the standard SipHash, a guard against keys chosen by an attacker, cost a tenth of
/// a plan's check time here, and these keys are lattice indices, not anyone's input.
#[derive(Default, Clone, Copy)]
struct SquareHasher(u64);

impl SquareHasher {
    fn add(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(5) ^ word).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
}

impl Hasher for SquareHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.add(u64::from(byte));
        }
    }

    fn write_i64(&mut self, word: i64) {
        self.add(word as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// The highest node of each coarse square looked at, by its indices.
type SquareTops = HashMap<(i64, i64), Option<f64>, BuildHasherDefault<SquareHasher>>;

/// Where the ground is nearest a leg, when within reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nearest {
    /// A lower bound on the distance from the leg to the ground, metres.
    pub distance_m: f64,
    /// The place of the leg nearest that ground (the caller's coordinates).
    pub at: [f64; 2],
}

/// Bounds the distance from legs to the ground of one model, within `reach_m`. Heights of
/// lattice nodes are kept between legs.
pub struct GroundNearness<H: Fn(f64, f64) -> Option<f64>> {
    height: H,
    /// Metres per unit of the caller's horizontal coordinates (altitudes are in metres).
    unit_m: f64,
    reach_m: f64,
    origin: (f64, f64),
    /// A coarse square's side (units) and the lattice cells it holds per axis.
    coarse: (f64, f64),
    cells_per_coarse: (usize, usize),
    /// The side of the smallest squares, metres: reach / [`SMALLEST_SHARE`].
    smallest_m: f64,
    coarse_tops: SquareTops,
}

impl<H: Fn(f64, f64) -> Option<f64>> GroundNearness<H> {
    /// Nearness to the ground of `terrain`, whose heights (metres) `height` gives at the
    /// caller's coordinates (`unit_m` metres each), looked for within `reach_m`.
    pub fn new(terrain: &dyn Terrain, height: H, unit_m: f64, reach_m: f64) -> Self {
        debug_assert!(
            reach_m > 0.0 && unit_m > 0.0,
            "a reach and a unit of length"
        );
        let reach_units = reach_m / unit_m;
        let (origin, cell) = terrain.lattice().unwrap_or((
            (0.0, 0.0),
            (
                (ANALYTIC_STEP_M / unit_m).min(reach_units / 2.0),
                (ANALYTIC_STEP_M / unit_m).min(reach_units / 2.0),
            ),
        ));
        let cell = (cell.0.abs(), cell.1.abs());
        // Coarse squares of whole cells, about reach / 32 on a side where cells are smaller
        // (larger cells are quartered where within reach).
        let target = reach_units / SMALLEST_SHARE;
        let per_axis = |cell: f64| ((target / cell).floor() as usize).clamp(1, 64);
        let cells_per_coarse = (per_axis(cell.0), per_axis(cell.1));
        let coarse = (
            cells_per_coarse.0 as f64 * cell.0,
            cells_per_coarse.1 as f64 * cell.1,
        );
        Self {
            height,
            unit_m,
            reach_m,
            origin,
            coarse,
            cells_per_coarse,
            smallest_m: reach_m / SMALLEST_SHARE,
            coarse_tops: SquareTops::default(),
        }
    }

    /// The highest node of coarse square (i, j): every lattice node in it and on its border.
    /// `None` where a node is off the model (the vertical checks report that).
    fn coarse_top(&mut self, i: i64, j: i64) -> Option<f64> {
        if let Some(&top) = self.coarse_tops.get(&(i, j)) {
            return top;
        }
        let (nx, ny) = self.cells_per_coarse;
        let (cell_x, cell_y) = (self.coarse.0 / nx as f64, self.coarse.1 / ny as f64);
        let (x0, y0) = (
            self.origin.0 + i as f64 * self.coarse.0,
            self.origin.1 + j as f64 * self.coarse.1,
        );
        let mut top = Some(f64::NEG_INFINITY);
        'nodes: for a in 0..=nx {
            for b in 0..=ny {
                match (self.height)(x0 + a as f64 * cell_x, y0 + b as f64 * cell_y) {
                    Some(height) => top = top.map(|t| t.max(height)),
                    None => {
                        top = None;
                        break 'nodes;
                    }
                }
            }
        }
        self.coarse_tops.insert((i, j), top);
        top
    }

    /// A lower bound on the distance from the straight leg `from`–`to` (x, y in the
    /// caller's units, altitude in metres) to the ground, and where, when it is within reach.
    pub fn leg(&mut self, from: [f64; 3], to: [f64; 3]) -> Option<Nearest> {
        let horizontal_m = (to[0] - from[0]).hypot(to[1] - from[1]) * self.unit_m;
        // Stretches a few coarse squares long: each looks at the squares around its own box.
        let longest_m = (4.0 * self.coarse.0.max(self.coarse.1) * self.unit_m).max(self.reach_m);
        let stretches = (horizontal_m / longest_m).ceil().max(1.0) as usize;
        let mut nearest: Option<Nearest> = None;
        for stretch in 0..stretches {
            let at = |t: f64| [0, 1, 2].map(|axis| from[axis] + t * (to[axis] - from[axis]));
            let (a, b) = (
                at(stretch as f64 / stretches as f64),
                at((stretch + 1) as f64 / stretches as f64),
            );
            if let Some(found) = self.stretch(a, b) {
                if nearest.is_none_or(|n| found.distance_m < n.distance_m) {
                    nearest = Some(found);
                }
            }
        }
        nearest
    }

    fn stretch(&mut self, a: [f64; 3], b: [f64; 3]) -> Option<Nearest> {
        let reach = self.reach_m / self.unit_m;
        let index = |value: f64, origin: f64, side: f64| ((value - origin) / side).floor() as i64;
        let (i_low, i_high) = (
            index(a[0].min(b[0]) - reach, self.origin.0, self.coarse.0),
            index(a[0].max(b[0]) + reach, self.origin.0, self.coarse.0),
        );
        let (j_low, j_high) = (
            index(a[1].min(b[1]) - reach, self.origin.1, self.coarse.1),
            index(a[1].max(b[1]) + reach, self.origin.1, self.coarse.1),
        );
        // The coarse squares within reach, nearest first: once one is refined, farther ones
        // whose coarse bound is no nearer are skipped (a 1,000 m reach over a 0.25 m DEM).
        let mut within: Vec<(f64, (f64, f64))> = Vec::new();
        for i in i_low..=i_high {
            for j in j_low..=j_high {
                let corner = (
                    self.origin.0 + i as f64 * self.coarse.0,
                    self.origin.1 + j as f64 * self.coarse.1,
                );
                // A square with a node off the model (no data, or past the DEM's edge) is
                // bounded cell by cell: its cells with every corner on the model still count.
                let top = self.coarse_top(i, j).unwrap_or(f64::INFINITY);
                let (bound, _) = self.square_bound(a, b, corner, self.coarse, top);
                if bound < self.reach_m {
                    within.push((bound, corner));
                }
            }
        }
        within.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut nearest: Option<Nearest> = None;
        for (bound, corner) in within {
            if nearest.is_some_and(|n| bound >= n.distance_m) {
                break;
            }
            // Within reach: bound its cells and their quarters instead, down to squares of
            // the target size where the bound is still within reach.
            self.refine(a, b, corner, self.coarse, &mut nearest);
        }
        nearest
    }

    /// Bounds the quarters of the square at `corner` of `side` (inside one cell), and theirs
    /// where still within reach, down to `smallest_m`; the least bound goes to `nearest`.
    fn refine(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        corner: (f64, f64),
        side: (f64, f64),
        nearest: &mut Option<Nearest>,
    ) {
        let (nx, ny) = self.cells_per_coarse;
        let cell = (self.coarse.0 / nx as f64, self.coarse.1 / ny as f64);
        // A coarse square of several cells is cut into its cells first (each bilinear).
        let (parts_x, parts_y) = if side.0 > cell.0 * 1.5 || side.1 > cell.1 * 1.5 {
            (nx, ny)
        } else {
            (2, 2)
        };
        let part = (side.0 / parts_x as f64, side.1 / parts_y as f64);
        for p in 0..parts_x {
            for q in 0..parts_y {
                let corner = (corner.0 + p as f64 * part.0, corner.1 + q as f64 * part.1);
                let Some(top) = self.small_top(corner, part) else {
                    continue;
                };
                let (bound, at) = self.square_bound(a, b, corner, part, top);
                if bound >= self.reach_m || nearest.is_some_and(|n| bound >= n.distance_m) {
                    continue;
                }
                if part.0.max(part.1) * self.unit_m <= self.smallest_m {
                    *nearest = Some(Nearest {
                        distance_m: bound,
                        at,
                    });
                } else {
                    self.refine(a, b, corner, part, nearest);
                }
            }
        }
    }

    /// The highest of a small square's corners (inside one cell: the bilinear surface's
    /// highest point over it).
    fn small_top(&self, corner: (f64, f64), side: (f64, f64)) -> Option<f64> {
        let mut top = f64::NEG_INFINITY;
        for (dx, dy) in [(0.0, 0.0), (side.0, 0.0), (0.0, side.1), (side.0, side.1)] {
            top = top.max((self.height)(corner.0 + dx, corner.1 + dy)?);
        }
        Some(top)
    }

    /// The bound from the stretch `a`–`b` to ground no higher than `top` over the square at
    /// `corner` of `side`, and the stretch's place nearest it: the least over the stretch of
    /// `√(d(t)² + max(0, z(t) − top)²)`, where `d(t)` is the horizontal distance from its
    /// point at `t` to the square (convex in `t`) and `z(t)` its altitude (linear), so their
    /// squares' sum is convex and a golden-section search finds its least value. (Measured
    /// from the stretch's lowest altitude instead, the bound fell up to a quarter of the reach
    /// short on a leg climbing with the ground; a review of decision 0030.)
    fn square_bound(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        corner: (f64, f64),
        side: (f64, f64),
        top: f64,
    ) -> (f64, [f64; 2]) {
        let (quick, at) = rectangle_segment_distance(corner, side, (a[0], a[1]), (b[0], b[1]));
        let quick_m = quick * self.unit_m;
        let below_lowest = (a[2].min(b[2]) - top).max(0.0);
        // Already out of reach from the lowest altitude, or level: nothing to search.
        let from_lowest = (quick_m * quick_m + below_lowest * below_lowest).sqrt();
        if from_lowest >= self.reach_m || (a[2] - b[2]).abs() < 1e-9 {
            return (from_lowest, at);
        }
        let squared = |t: f64| {
            let (x, y) = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
            // Outside the square along each axis, 0 within its span.
            let dx = (corner.0 - x).max(x - corner.0 - side.0).max(0.0);
            let dy = (corner.1 - y).max(y - corner.1 - side.1).max(0.0);
            let below = (a[2] + t * (b[2] - a[2]) - top).max(0.0);
            (dx * dx + dy * dy) * self.unit_m * self.unit_m + below * below
        };
        let ratio = (5f64.sqrt() - 1.0) / 2.0;
        let (mut low, mut high) = (0.0, 1.0);
        let (mut left, mut right) = (high - ratio * (high - low), low + ratio * (high - low));
        let (mut at_left, mut at_right) = (squared(left), squared(right));
        for _ in 0..48 {
            if at_left <= at_right {
                high = right;
                right = left;
                at_right = at_left;
                left = high - ratio * (high - low);
                at_left = squared(left);
            } else {
                low = left;
                left = right;
                at_left = at_right;
                right = low + ratio * (high - low);
                at_right = squared(right);
            }
        }
        let t = (low + high) / 2.0;
        // The ends too (the least may sit at one), and a hair off for the search's tolerance.
        let (best, t) = [(squared(t), t), (squared(0.0), 0.0), (squared(1.0), 1.0)]
            .into_iter()
            .fold((f64::INFINITY, t), |best, candidate| {
                if candidate.0 < best.0 {
                    candidate
                } else {
                    best
                }
            });
        let place = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
        ((best.sqrt() - 1e-6).max(0.0), place)
    }
}

/// The horizontal distance from the segment `a`–`b` to the rectangle at `corner` of `side`
/// (0 when they meet), and the segment's point nearest it.
///
/// The preflight asks this of every small square near every leg (most of a plan's check
/// time): squared distances compared, one square root at the end (`hypot` per candidate was
/// a quarter of `agripath demo`'s run), and the edges' contact points sought only when
/// clipping says the segment reaches the rectangle.
fn rectangle_segment_distance(
    corner: (f64, f64),
    side: (f64, f64),
    a: (f64, f64),
    b: (f64, f64),
) -> (f64, [f64; 2]) {
    let (min_x, min_y, max_x, max_y) = (corner.0, corner.1, corner.0 + side.0, corner.1 + side.1);
    let inside = |p: (f64, f64)| (min_x..=max_x).contains(&p.0) && (min_y..=max_y).contains(&p.1);
    if inside(a) {
        return (0.0, [a.0, a.1]);
    }
    if inside(b) {
        return (0.0, [b.0, b.1]);
    }
    let point = |p: (f64, f64)| Coord { x: p.0, y: p.1 };
    let (start, end) = (point(a), point(b));
    let corners = [
        (min_x, min_y),
        (max_x, min_y),
        (max_x, max_y),
        (min_x, max_y),
    ]
    .map(point);
    if clipped_meets((min_x, min_y, max_x, max_y), a, b) {
        for k in 0..4 {
            // The segment meets an edge: distance 0 there.
            if let Some(contact) = segment_contact(start, end, corners[k], corners[(k + 1) % 4]) {
                return (0.0, [contact.x, contact.y]);
            }
        }
    }
    // Apart, the nearest pair has a corner of the rectangle or an end of the segment in it:
    // edge by edge, its first corner to the segment, then each end of the segment to the
    // edge (the first of equal distances kept, so the place is the one found before).
    let squared_to_edge = |p: Coord<f64>, from: Coord<f64>, to: Coord<f64>| {
        let t = nearest_fraction_on_segment(p, from, to);
        (p.x - from.x - t * (to.x - from.x)).powi(2) + (p.y - from.y - t * (to.y - from.y)).powi(2)
    };
    let mut best = (f64::INFINITY, [a.0, a.1]);
    for k in 0..4 {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        let t = nearest_fraction_on_segment(p, start, end);
        let on_leg = [a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)];
        for (squared, place) in [
            (
                (p.x - on_leg[0]).powi(2) + (p.y - on_leg[1]).powi(2),
                on_leg,
            ),
            (squared_to_edge(start, p, q), [a.0, a.1]),
            (squared_to_edge(end, p, q), [b.0, b.1]),
        ] {
            if squared < best.0 {
                best = (squared, place);
            }
        }
    }
    (best.0.sqrt(), best.1)
}

/// Whether the segment `a`–`b` reaches the closed box `(min_x, min_y, max_x, max_y)`
/// (Liang and Barsky's clipping: the segment's span of t within each slab).
fn clipped_meets(
    (min_x, min_y, max_x, max_y): (f64, f64, f64, f64),
    a: (f64, f64),
    b: (f64, f64),
) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut low, mut high) = (0.0f64, 1.0f64);
    for (direction, room) in [
        (-dx, a.0 - min_x),
        (dx, max_x - a.0),
        (-dy, a.1 - min_y),
        (dy, max_y - a.1),
    ] {
        if direction == 0.0 {
            if room < 0.0 {
                return false;
            }
        } else {
            let t = room / direction;
            if direction < 0.0 {
                low = low.max(t);
            } else {
                high = high.min(t);
            }
            if low > high {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terrain::Grid;
    use proptest::prelude::*;

    /// A grid of 5 m cells, flat at 200 m west of x = 50 and 300 m east of it.
    fn cliff() -> Grid {
        let columns = 21;
        let rows = 21;
        let values: Vec<f32> = (0..rows * columns)
            .map(|k| {
                if (k % columns) as f64 * 5.0 >= 50.0 {
                    300.0
                } else {
                    200.0
                }
            })
            .collect();
        Grid {
            columns,
            rows,
            first_center_x: 0.0,
            first_center_y: 100.0,
            cell_x: 5.0,
            cell_y: 5.0,
            heights: values,
            epsg: None,
            source: "cliff".into(),
        }
    }

    #[test]
    fn a_leg_beside_a_cliff_is_near_the_ground_though_far_above_the_ground_beneath() {
        let grid = cliff();
        let mut nearness = GroundNearness::new(&grid, |x, y| grid.height_m(x, y).ok(), 1.0, 30.0);
        // Level at 290 m along y, 2.5 m west of the last low cell centre (x = 45): the ground
        // rises from 200 m at x = 45 to 300 m at x = 50, reaching 290 m at x = 49.5.
        let near = nearness
            .leg([47.0, 20.0, 290.0], [47.0, 80.0, 290.0])
            .unwrap();
        assert!(near.distance_m <= 2.5 + 1e-9, "{near:?}");
        assert!(near.distance_m > 0.0, "{near:?}");
        // 40 m above flat ground and more than 30 m west of the cliff's foot (x = 45):
        // nothing within 30 m.
        assert_eq!(nearness.leg([5.0, 20.0, 240.0], [10.0, 80.0, 240.0]), None);
    }

    /// A plane rising 12° eastwards on 5 m cells, and a level leg 35 m above it along a
    /// contour, then one climbing with it up the fall line: both are 35 · cos 12° = 34.24 m from it.
    /// Measured from a stretch's lowest altitude the climbing leg read up to a quarter of the
    /// reach less.
    #[test]
    fn the_bound_is_tight_over_a_plain_slope_level_or_climbing() {
        let (columns, rows) = (200, 40);
        let rise = 12f64.to_radians().tan();
        let grid = Grid {
            columns,
            rows,
            first_center_x: 0.0,
            first_center_y: 195.0,
            cell_x: 5.0,
            cell_y: 5.0,
            heights: (0..rows * columns)
                .map(|k| (100.0 + 5.0 * (k % columns) as f64 * rise) as f32)
                .collect(),
            epsg: None,
            source: "slope".into(),
        };
        let ground = |x: f64| 100.0 + x * rise;
        let mut nearness = GroundNearness::new(&grid, |x, y| grid.height_m(x, y).ok(), 1.0, 40.0);
        let expected = 35.0 * 12f64.to_radians().cos();
        for (from, to) in [
            (
                [300.0, 100.0, ground(300.0) + 35.0],
                [300.0, 150.0, ground(300.0) + 35.0],
            ),
            (
                [300.0, 100.0, ground(300.0) + 35.0],
                [600.0, 100.0, ground(600.0) + 35.0],
            ),
        ] {
            let near = nearness.leg(from, to).unwrap();
            assert!(
                near.distance_m <= expected + 0.05 && near.distance_m > expected - 0.5,
                "{near:?} against {expected}"
            );
        }
    }

    proptest! {
        /// The distance from a segment to a rectangle is the least over the segment, sampled
        /// every 1/4,000 of it, of the distance to the rectangle (within half a step), and
        /// the place given is on the segment at that distance.
        #[test]
        fn the_segment_to_rectangle_distance_is_the_sampled_least(
            corner_x in -20.0f64..20.0, corner_y in -20.0f64..20.0,
            width in 0.01f64..15.0, height in 0.01f64..15.0,
            ax in -40.0f64..40.0, ay in -40.0f64..40.0, bx in -40.0f64..40.0, by in -40.0f64..40.0,
        ) {
            let (corner, side) = ((corner_x, corner_y), (width, height));
            let to_rectangle = |x: f64, y: f64| {
                let dx = (corner_x - x).max(x - corner_x - width).max(0.0);
                let dy = (corner_y - y).max(y - corner_y - height).max(0.0);
                dx.hypot(dy)
            };
            let (distance, place) = rectangle_segment_distance(corner, side, (ax, ay), (bx, by));
            let steps = 4000;
            let sampled = (0..=steps)
                .map(|k| {
                    let t = k as f64 / steps as f64;
                    to_rectangle(ax + t * (bx - ax), ay + t * (by - ay))
                })
                .fold(f64::INFINITY, f64::min);
            let half_step = (bx - ax).hypot(by - ay) / steps as f64 / 2.0;
            prop_assert!(distance <= sampled + 1e-9, "{distance} against sampled {sampled}");
            prop_assert!(distance >= sampled - half_step - 1e-9, "{distance} against sampled {sampled}");
            prop_assert!((to_rectangle(place[0], place[1]) - distance).abs() < 1e-6);
            let off_segment = crate::geometry::distance_to_segment(
                Coord { x: place[0], y: place[1] },
                Coord { x: ax, y: ay },
                Coord { x: bx, y: by },
            );
            prop_assert!(off_segment < 1e-9, "the place is {off_segment} off the segment");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The bound never exceeds the distance to the ground sampled densely (every 0.2 m of
        /// the leg, every 0.25 m of the ground around it).
        #[test]
        fn the_bound_is_never_above_the_sampled_distance(
            x in 20.0f64..80.0, y in 20.0f64..80.0, heading in 0.0f64..6.3,
            altitude in 200.5f64..320.0, climb in -10.0f64..10.0, reach in 1.0f64..6.0,
        ) {
            let grid = cliff();
            let mut nearness = GroundNearness::new(&grid, |x, y| grid.height_m(x, y).ok(), 1.0, reach);
            let to = [x + 8.0 * heading.cos(), y + 8.0 * heading.sin(), altitude + climb];
            let bound = nearness.leg([x, y, altitude], to).map_or(reach, |n| n.distance_m);
            let mut sampled = f64::INFINITY;
            for k in 0..=40 {
                let t = k as f64 / 40.0;
                let (px, py) = (x + t * (to[0] - x), y + t * (to[1] - y));
                let pz = altitude + t * climb;
                let steps = (reach / 0.25).ceil() as i64;
                for a in -steps..=steps {
                    for b in -steps..=steps {
                        let (gx, gy) = (px + a as f64 * 0.25, py + b as f64 * 0.25);
                        if let Ok(ground) = grid.height_m(gx, gy) {
                            let d = ((gx - px).hypot(gy - py)).hypot((pz - ground).max(0.0));
                            sampled = sampled.min(d);
                        }
                    }
                }
            }
            prop_assert!(bound <= sampled + 1e-9, "bound {bound} sampled {sampled}");
            // And not far below it: within the small squares' size and slope.
            prop_assert!(bound >= sampled.min(reach) - reach / 8.0 * 22.0 - 0.2, "bound {bound} sampled {sampled}");
        }
    }
}
