//! The two bounds on the height of every airborne sample that no setting of the plan moves
//! (the red team's finding of 2026-12-06: a spray height of 0, a terrain tolerance of 5 m, or
//! a `report.json` edited to say 30 m let files that fly into the ground read SAFE; a climb to
//! 250 m inserted in a ground station read SAFE too).
//!
//! - The floor: no sample, spraying or not, nearer the ground than
//!   [`MIN_GROUND_CLEARANCE_M`], straight down or sideways (a slope beside the leg:
//!   `terrain::nearness`, decision 0030).
//! - The ceiling: no sample higher above the highest ground under its leg than a transit
//!   flies (the cruise height: spray height + max(h, 5 m)) and [`CEILING_SLACK_M`]. Every leg
//!   agripath writes keeps to it over any terrain, because a transit's altitude is set from
//!   the highest ground under it; a climb beyond it is an edit, not a plan.

use super::verdict::Tally;
use crate::limits::MIN_GROUND_CLEARANCE_M;
use crate::model::Vehicle;
use crate::terrain::nearness::GroundNearness;

/// How far above the cruise height (over the highest ground under a leg) a file may fly.
pub const CEILING_SLACK_M: f64 = 10.0;

/// Float slack of the ceiling, metres (as the other checks' that hold the plan's own settings:
/// the files' altitudes are written to the centimetre).
const SLACK_M: f64 = 0.02;

/// Rounding allowed below the floor, metres: none to speak of. The floor is the one bound no
/// setting moves, and the report prints it against 0.5 m (a 2 cm slack let 0.482 m read
/// "passed", trial 8, decision 0036).
const FLOOR_ROUNDING_M: f64 = 1e-9;

/// Height above its own ground from which a takeoff or a landing is held to the floor in
/// any direction: twice the floor. Below it the vehicle stands on, or leaves, the ground
/// under it; from it on, a slope as steep as 60° beneath it is still the floor away
/// (1 m · cos 60°), so only a face beside the column (a pylon, a cliff's foot, a ditch's
/// wall) fails it. (That is the geometry; the nearness search is a lower bound, which near a
/// steep face errs low, so a slope a little under 60° can fail too: on the safe side.)
pub(super) const COLUMN_AIRBORNE_M: f64 = 2.0 * MIN_GROUND_CLEARANCE_M;

/// A sample waiting for the ground it is held to: `(sortie, item, x, y, altitude)`.
type Sample = (usize, usize, f64, f64, f64);

/// How a leg flies, for the ceiling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum LegShape {
    /// Across the ground, its altitude above sea level interpolated between its ends.
    Along,
    /// Across the ground following the terrain (frame 10): the autopilot holds a height above
    /// the ground beneath, interpolated between the heights its ends command, so the leg flies
    /// no higher above the local ground than its ends. Its samples between the ends may stand
    /// far above the *highest* ground under the leg where the ground rises early and the
    /// height comes down late (the island's transits out of a valley climb at the supply
    /// point to clear the ridge, then follow the terrain down to the cruise height); the
    /// ceiling holds the heights the file commands, at the two ends.
    FollowingTerrain,
    /// A climb or descent where the vehicle stands.
    InPlace,
}

/// The floor and the ceiling as the samples of a flight are recorded, and the lowest
/// clearance seen.
///
/// The ceiling's ground: a transit is flown level over the highest ground under the whole
/// transit, which may bend round an obstacle in several legs, so consecutive legs across the
/// ground at one altitude are a *level stretch*, held to the highest ground under all of them;
/// a leg whose altitude changes (a draped spray leg, a terrain-following leg) is a stretch of
/// its own. A climb or descent in place is held to the stretches on either side of it: it
/// climbs for the one after it or comes down from the one before it.
pub(super) struct HeightBounds {
    floor: Tally,
    ceiling: Tally,
    /// The least height above the ground of any sample recorded, metres.
    pub lowest_clearance_m: f64,
    /// The highest ground under the last stretch held.
    previous_highest: f64,
    /// The stretch being flown: its samples, the highest ground under it, its altitude when
    /// level.
    stretch: Vec<Sample>,
    stretch_highest: f64,
    stretch_altitude: Option<f64>,
    /// Whether the stretch is a transit that follows the terrain.
    stretch_is_terrain_transit: bool,
    /// Samples of climbs and descents in place since the stretch being flown.
    in_place: Vec<Sample>,
    /// Those between the stretch before and the stretch being flown, held when it closes.
    before_stretch: Vec<Sample>,
}

impl HeightBounds {
    /// The bounds for `vehicle`.
    pub fn new(vehicle: &Vehicle) -> Self {
        Self {
            floor: Tally::new(
                "clearance floor",
                "≥",
                MIN_GROUND_CLEARANCE_M,
                "m from the ground, any airborne sample, in any direction",
            ),
            ceiling: Tally::new(
                "height ceiling",
                "≤",
                vehicle.cruise_height_m() + CEILING_SLACK_M,
                "m above the highest ground under a leg",
            ),
            lowest_clearance_m: f64::INFINITY,
            previous_highest: f64::NEG_INFINITY,
            stretch: Vec::new(),
            stretch_highest: f64::NEG_INFINITY,
            stretch_altitude: None,
            stretch_is_terrain_transit: false,
            in_place: Vec::new(),
            before_stretch: Vec::new(),
        }
    }

    /// Records the samples `(x, y, altitude, ground)` of one airborne leg of shape `shape`:
    /// item `item` of sortie `sortie`; places printed by `place`. Call [`Self::end_sortie`]
    /// after each sortie's legs.
    ///
    /// `transit_beside_m`: for a transit leg, the highest ground beside it that it clears as
    /// well ([`crate::mission::flight::TRANSIT_CORRIDOR_M`]), which the ceiling is held over;
    /// `None` for any other leg. `off_spray`: the leg does not spray. Consecutive legs off
    /// spray that follow the terrain are one stretch, as level ones are: the writer gives a
    /// whole transit, corners and all, one altitude over the highest ground of all its legs,
    /// and terrain following holds each corner's height above the ground there (a review
    /// run: Christmas Island's home leg over a corner read 32.1 m above its own ground).
    pub fn record(
        &mut self,
        (sortie, item): (usize, usize),
        points: &[(f64, f64, f64, f64)],
        shape: LegShape,
        transit_beside_m: Option<f64>,
        off_spray: bool,
        place: &dyn Fn(f64, f64) -> String,
    ) {
        for &(x, y, altitude, ground) in points {
            let clearance = altitude - ground;
            self.lowest_clearance_m = self.lowest_clearance_m.min(clearance);
            self.floor.record_at((x, y), clearance, clearance < MIN_GROUND_CLEARANCE_M - FLOOR_ROUNDING_M, || {
                format!(
                    "sortie {sortie}, item {item} at {}: {clearance:.2} m above the ground (never below {MIN_GROUND_CLEARANCE_M} m)",
                    place(x, y)
                )
            });
        }
        let held = match (shape, points) {
            (LegShape::FollowingTerrain, [first, .., last]) => vec![*first, *last],
            _ => points.to_vec(),
        };
        let samples = held
            .iter()
            .map(|&(x, y, altitude, _)| (sortie, item, x, y, altitude));
        if shape == LegShape::InPlace {
            self.in_place.extend(samples);
            return;
        }
        let highest = points
            .iter()
            .map(|&(_, _, _, ground)| ground)
            .fold(transit_beside_m.unwrap_or(f64::NEG_INFINITY), f64::max);
        let (low, high) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), p| {
                (low.min(p.2), high.max(p.2))
            });
        let level = (high - low <= 1e-6).then_some(low);
        let terrain_transit = shape == LegShape::FollowingTerrain && off_spray;
        let continues = (matches!((level, self.stretch_altitude), (Some(a), Some(b)) if (a - b).abs() <= 1e-6)
            || (terrain_transit && self.stretch_is_terrain_transit))
            && self.in_place.is_empty();
        if !continues {
            self.close_stretch(place);
            self.before_stretch = std::mem::take(&mut self.in_place);
        }
        self.stretch.extend(samples);
        self.stretch_highest = self.stretch_highest.max(highest);
        self.stretch_altitude = level;
        self.stretch_is_terrain_transit = terrain_transit;
    }

    /// Holds the stretch being flown to the highest ground under it, and the climbs and
    /// descents just before it to that or the stretch before them, whichever is higher.
    fn close_stretch(&mut self, place: &dyn Fn(f64, f64) -> String) {
        if self.stretch.is_empty() {
            return;
        }
        let stretch = std::mem::take(&mut self.stretch);
        self.hold(&stretch, self.stretch_highest, place);
        let waiting = std::mem::take(&mut self.before_stretch);
        self.hold(
            &waiting,
            self.previous_highest.max(self.stretch_highest),
            place,
        );
        self.previous_highest = self.stretch_highest;
        self.stretch_highest = f64::NEG_INFINITY;
        self.stretch_altitude = None;
        self.stretch_is_terrain_transit = false;
    }

    /// Ends a sortie: its last stretch held, and its last climbs and descents to it.
    pub fn end_sortie(&mut self, place: &dyn Fn(f64, f64) -> String) {
        self.close_stretch(place);
        let waiting = std::mem::take(&mut self.in_place);
        self.hold(&waiting, self.previous_highest, place);
        self.previous_highest = f64::NEG_INFINITY;
    }

    /// Holds `samples` to the ceiling over ground `highest`.
    fn hold(&mut self, samples: &[Sample], highest: f64, place: &dyn Fn(f64, f64) -> String) {
        let ceiling = self.ceiling.limit;
        for &(sortie, item, x, y, altitude) in samples {
            let height = altitude - highest;
            self.ceiling.record_at((x, y), height, height > ceiling + SLACK_M, || {
                format!(
                    "sortie {sortie}, item {item} at {}: {height:.1} m above the highest ground under the leg (ceiling {ceiling:.1} m: the cruise height and {CEILING_SLACK_M} m)",
                    place(x, y)
                )
            });
        }
    }

    /// Records how near the airborne leg `item` of sortie `sortie` (its samples `points`,
    /// `(x, y, altitude, ground)`) comes to the ground sideways, between consecutive samples
    /// (a terrain-following leg bends with the ground only at them), where nearer than the
    /// ground beneath, which the floor holds already.
    pub fn record_sideways<H: Fn(f64, f64) -> Option<f64>>(
        &mut self,
        (sortie, item): (usize, usize),
        points: &[(f64, f64, f64, f64)],
        nearness: &mut GroundNearness<H>,
        place: &dyn Fn(f64, f64) -> String,
    ) {
        let beneath = points
            .iter()
            .map(|&(_, _, altitude, ground)| altitude - ground)
            .fold(f64::INFINITY, f64::min);
        let Some(near) = points
            .windows(2)
            .filter_map(|pair| {
                nearness.leg(
                    [pair[0].0, pair[0].1, pair[0].2],
                    [pair[1].0, pair[1].1, pair[1].2],
                )
            })
            .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m))
        else {
            return;
        };
        let distance = near.distance_m;
        if distance >= beneath || beneath < MIN_GROUND_CLEARANCE_M - FLOOR_ROUNDING_M {
            return;
        }
        self.lowest_clearance_m = self.lowest_clearance_m.min(distance);
        let [x, y] = near.at;
        self.floor.record_at((x, y), distance, distance < MIN_GROUND_CLEARANCE_M - FLOOR_ROUNDING_M, || {
            format!(
                "sortie {sortie}, item {item} at {}: {distance:.2} m from the ground beside it, a slope or a bank ({beneath:.2} m above the ground beneath; never nearer than {MIN_GROUND_CLEARANCE_M} m in any direction)",
                place(x, y)
            )
        });
    }

    /// Holds a takeoff's or a landing's column (item `item` of sortie `sortie`, its samples
    /// `points`, `(x, y, altitude, ground)`, all over one place) to the floor in any direction
    /// from [`COLUMN_AIRBORNE_M`] above its ground to its top. Only a failure is recorded:
    /// where the column passes, its figure would be the distance at the height where the
    /// check begins, a number of this rule's making, not of the flight's.
    pub fn record_column<H: Fn(f64, f64) -> Option<f64>>(
        &mut self,
        (sortie, item): (usize, usize),
        points: &[(f64, f64, f64, f64)],
        nearness: &mut GroundNearness<H>,
        place: &dyn Fn(f64, f64) -> String,
    ) {
        let Some(&(x, y, _, ground)) = points.first() else {
            return;
        };
        let top = points
            .iter()
            .map(|&(_, _, altitude, _)| altitude)
            .fold(f64::NEG_INFINITY, f64::max);
        let bottom = ground + COLUMN_AIRBORNE_M;
        if top <= bottom {
            return;
        }
        let Some(near) = nearness.leg([x, y, bottom], [x, y, top]) else {
            return;
        };
        let distance = near.distance_m;
        if distance >= MIN_GROUND_CLEARANCE_M - FLOOR_ROUNDING_M {
            return;
        }
        self.lowest_clearance_m = self.lowest_clearance_m.min(distance);
        let [near_x, near_y] = near.at;
        self.floor.record_at((near_x, near_y), distance, true, || {
            format!(
                "sortie {sortie}, item {item} at {}: the climb or descent where the vehicle stands passes {distance:.2} m from the ground beside it (a face, a mast or a bank; never nearer than {MIN_GROUND_CLEARANCE_M} m in any direction once {COLUMN_AIRBORNE_M} m up)",
                place(x, y)
            )
        });
    }

    /// The two checks, floor first.
    pub fn tallies(self) -> [Tally; 2] {
        [self.floor, self.ceiling]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A leg's samples from `ground(t)` and the height above it `height(t)`, 21 of them.
    fn leg(ground: impl Fn(f64) -> f64, height: impl Fn(f64) -> f64) -> Vec<(f64, f64, f64, f64)> {
        (0..=20)
            .map(|k| {
                let t = f64::from(k) / 20.0;
                (100.0 * t, 0.0, ground(t) + height(t), ground(t))
            })
            .collect()
    }

    fn failures(shape: LegShape, points: &[(f64, f64, f64, f64)]) -> usize {
        let vehicle = Vehicle::default();
        let mut bounds = HeightBounds::new(&vehicle);
        let place = |x: f64, y: f64| format!("({x}, {y})");
        bounds.record((1, 3), points, shape, None, false, &place);
        bounds.end_sortie(&place);
        let (mut checks, mut lines) = (Vec::new(), Vec::new());
        for tally in bounds.tallies() {
            tally.finish(&mut checks, &mut lines, &mut Vec::new());
        }
        assert!(checks[0].passed, "the floor: {lines:?}");
        lines.len()
    }

    /// Trial 8: a takeoff 1.25 m from the centre of a mast one 1 m cell wide (its bilinear
    /// face 0.25 m beside the column) fails the floor once 1 m up; the same column 4 m away,
    /// and one on a plane sloping 50 %, pass without touching the floor's figure.
    #[test]
    fn a_takeoff_column_is_held_to_the_floor_beside_it() {
        use crate::terrain::Terrain;
        let (columns, rows) = (12, 12);
        let grid = |height: &dyn Fn(usize, usize) -> f32| crate::terrain::Grid {
            columns,
            rows,
            first_center_x: 0.5,
            first_center_y: 11.5,
            cell_x: 1.0,
            cell_y: 1.0,
            heights: (0..rows * columns)
                .map(|index| height(index % columns, index / columns))
                .collect(),
            epsg: None,
            source: "mast".into(),
        };
        let mast = grid(&|column, row| {
            if (column, row) == (6, 6) {
                140.0
            } else {
                100.0
            }
        });
        let slope = grid(&|column, _| 100.0 + 0.5 * column as f32);
        let column_at = |terrain: &crate::terrain::Grid, x: f64, y: f64| {
            let vehicle = Vehicle::default();
            let mut bounds = HeightBounds::new(&vehicle);
            let mut nearness = GroundNearness::new(
                terrain,
                |x, y| terrain.height_m(x, y).ok(),
                1.0,
                MIN_GROUND_CLEARANCE_M,
            );
            let ground = terrain.height_m(x, y).unwrap();
            let points = [(x, y, ground, ground), (x, y, ground + 17.5, ground)];
            let place = |x: f64, y: f64| format!("({x}, {y})");
            bounds.record_column((1, 1), &points, &mut nearness, &place);
            let (mut checks, mut lines) = (Vec::new(), Vec::new());
            for tally in bounds.tallies() {
                tally.finish(&mut checks, &mut lines, &mut Vec::new());
            }
            (checks[0].passed, checks[0].figure, lines)
        };
        // The mast's cell centre is (6.5, 5.5); its bilinear surface reaches 1 m either way.
        let (passed, figure, lines) = column_at(&mast, 6.5 + 1.25, 5.5);
        assert!(!passed);
        assert!(figure < 0.3, "{figure}");
        assert!(lines[0].contains("climb or descent"), "{lines:?}");
        for (terrain, x, y) in [(&mast, 6.5 + 4.0, 5.5), (&slope, 6.0, 6.0)] {
            let (passed, figure, lines) = column_at(terrain, x, y);
            assert!(passed, "{lines:?}");
            // No figure recorded: the check reports its limit.
            assert_eq!(figure, MIN_GROUND_CLEARANCE_M);
        }
    }

    /// A transit over a corner that follows the terrain: its first leg crosses a 30 m ridge,
    /// its second runs over level ground, both at the one altitude the writer gave the whole
    /// transit. Off spray, the two legs are one stretch held over the ridge; as legs of
    /// their own, the second reads 30 m above its ground and breaks the ceiling.
    #[test]
    fn a_terrain_following_transit_is_held_over_the_ground_of_all_its_legs() {
        let vehicle = Vehicle::default();
        let altitude = 30.0 + vehicle.cruise_height_m();
        // Terrain following holds the ends' height above the ground (both ends of the ridge
        // leg are on level ground at the transit's altitude) over the ridge between them.
        let ridge = leg(|t| 30.0 * (1.0 - (2.0 * t - 1.0).abs()), |_| altitude);
        let level = leg(|_| 0.0, |_| 0.0)
            .into_iter()
            .map(|(x, y, _, ground)| (x + 100.0, y, altitude, ground))
            .collect::<Vec<_>>();
        let ceiling_failures = |off_spray: bool| {
            let mut bounds = HeightBounds::new(&vehicle);
            let place = |x: f64, y: f64| format!("({x}, {y})");
            for (item, points) in [(2, &ridge), (3, &level)] {
                let shape = LegShape::FollowingTerrain;
                bounds.record((1, item), points, shape, Some(0.0), off_spray, &place);
            }
            bounds.end_sortie(&place);
            let (mut checks, mut lines) = (Vec::new(), Vec::new());
            for tally in bounds.tallies() {
                tally.finish(&mut checks, &mut lines, &mut Vec::new());
            }
            !checks[1].passed
        };
        assert!(!ceiling_failures(true));
        assert!(ceiling_failures(false));
    }

    #[test]
    fn a_terrain_following_leg_is_held_at_the_heights_its_ends_command() {
        let vehicle = Vehicle::default();
        let ceiling = vehicle.cruise_height_m() + CEILING_SLACK_M;
        // Out of a valley: the ground rises 30 m in the first tenth of the leg, and the
        // height comes down from the climb at the start (30 m + the cruise height, to clear
        // the ridge) to the cruise height over it. Between the ends the vehicle stands far
        // above the highest ground; the ends keep to the ceiling.
        let cruise = vehicle.cruise_height_m();
        let out_of_the_valley = leg(
            |t| (300.0 * t).min(30.0),
            |t| (30.0 + cruise) * (1.0 - t) + cruise * t,
        );
        let worst = out_of_the_valley
            .iter()
            .map(|p| p.2 - 30.0)
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            worst > ceiling,
            "{worst} m, the samples are over the ceiling"
        );
        assert_eq!(failures(LegShape::FollowingTerrain, &out_of_the_valley), 0);
        // A leg level above sea level is held at every sample.
        assert!(failures(LegShape::Along, &out_of_the_valley) > 0);
        // An edited end 250 m above the terrain fails, following the terrain or not.
        let edited = leg(|_| 0.0, |t| cruise + 250.0 * t);
        assert_eq!(failures(LegShape::FollowingTerrain, &edited), 1);
    }
}
