//! A mission file's items flown as an autopilot flies them: legs in plan metres with their
//! altitudes above sea level, spray state and speed.
//!
//! ArduPilot's reading of the items: NAV_TAKEOFF climbs where the vehicle stands (from the
//! ground at home) to its altitude; NAV_WAYPOINT flies straight to its place; NAV_LAND flies
//! to its place at the current altitude and descends to the ground; DO_CHANGE_SPEED of speed
//! type (p1) 0 or 1 sets the horizontal speed (p2), and of type 2 or 3 the climb or descent
//! speed (ArduCopter's `ModeAuto::do_change_speed`), which the check flies at the vehicle's
//! figures, so another value is refused, as is a type above 3 (ArduCopter ignores it or, in
//! older firmware, reads it as horizontal: refused as the safe choice); DO_SPRAYER (p1 = 1
//! on) or DO_SET_SERVO on the sprayer's channel switch the spray; DO_SET_CAM_TRIGG_DIST
//! (p1 > 0 on, 0 off) switches a survey camera, read as the same on/off state. Altitudes:
//! frame 0 above sea level, frame 3 above home's ground, frame 10 above the terrain under the
//! vehicle (interpolated along the leg, as terrain following does).

use super::read_back::FileItem;
use crate::mission::flight::SprayerCommand;
use crate::mission::mavlink::{
    CMD_DO_CHANGE_SPEED, CMD_DO_SET_CAM_TRIGG_DIST, CMD_DO_SET_SERVO, CMD_DO_SPRAYER, CMD_NAV_LAND,
    CMD_NAV_TAKEOFF, CMD_NAV_WAYPOINT, FRAME_GLOBAL, FRAME_GLOBAL_RELATIVE_ALT,
    FRAME_GLOBAL_TERRAIN_ALT,
};
use crate::terrain::Terrain;

/// An altitude as an item gives it: above sea level, or above the terrain (frame 10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Height {
    /// Metres above sea level (frame 0, or frame 3 plus home's ground).
    SeaLevel(f64),
    /// Metres above the terrain under the vehicle (frame 10).
    AboveTerrain(f64),
}

/// A place of the flight: plan metres and a height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Place {
    /// Plan x (east), metres.
    pub x: f64,
    /// Plan y (north), metres.
    pub y: f64,
    /// The altitude.
    pub height: Height,
}

/// What kind of motion a leg is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Motion {
    /// Straight climb from the ground at takeoff.
    Takeoff,
    /// Straight descent to the ground at the end.
    Landing,
    /// Any other leg.
    Flight,
}

/// One leg of the flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Leg {
    /// The item (1-based, as ground stations number them) that ends the leg.
    pub item: usize,
    /// Where the leg starts.
    pub from: Place,
    /// Where the leg ends.
    pub to: Place,
    /// Whether the sprayer is on along the leg.
    pub spraying: bool,
    /// Ground speed along the leg, m/s.
    pub speed_mps: f64,
    /// What kind of motion the leg is.
    pub motion: Motion,
}

impl Leg {
    /// A transit's clearance from its samples `(x, y, altitude, ground)`: where it flies
    /// lowest and its height above the highest ground under it (the transit rule); when it
    /// follows the terrain (frame 10), which holds the height above the ground under the
    /// vehicle, its least height above the local ground instead.
    pub fn transit_margin(&self, points: &[(f64, f64, f64, f64)]) -> (f64, f64, f64) {
        let highest = points
            .iter()
            .map(|&(_, _, _, ground)| ground)
            .fold(f64::NEG_INFINITY, f64::max);
        let (x, y, lowest_altitude) = points
            .iter()
            .map(|&(x, y, altitude, _)| (x, y, altitude))
            .fold(
                (0.0, 0.0, f64::INFINITY),
                |low, p| {
                    if p.2 < low.2 {
                        p
                    } else {
                        low
                    }
                },
            );
        let margin = if self.follows_terrain() {
            points
                .iter()
                .map(|&(_, _, altitude, ground)| altitude - ground)
                .fold(f64::INFINITY, f64::min)
        } else {
            lowest_altitude - highest
        };
        (x, y, margin)
    }

    /// Whether the leg follows the terrain (frame 10 at both ends): the autopilot holds a
    /// height above the ground under the vehicle.
    pub fn follows_terrain(&self) -> bool {
        matches!(
            (self.from.height, self.to.height),
            (Height::AboveTerrain(_), Height::AboveTerrain(_))
        )
    }

    /// Horizontal length of the leg, metres.
    pub fn horizontal_m(&self) -> f64 {
        (self.to.x - self.from.x).hypot(self.to.y - self.from.y)
    }

    /// Position and altitude above sea level at fraction `t` of the leg.
    pub fn at(
        &self,
        t: f64,
        terrain: &dyn Terrain,
    ) -> Result<(f64, f64, f64), crate::TerrainError> {
        let x = self.from.x + t * (self.to.x - self.from.x);
        let y = self.from.y + t * (self.to.y - self.from.y);
        let altitude = match (self.from.height, self.to.height) {
            (Height::AboveTerrain(a), Height::AboveTerrain(b)) => {
                terrain.height_m(x, y)? + a + t * (b - a)
            }
            (a, b) => {
                let a = self.sea_level(a, self.from.x, self.from.y, terrain)?;
                let b = self.sea_level(b, self.to.x, self.to.y, terrain)?;
                a + t * (b - a)
            }
        };
        Ok((x, y, altitude))
    }

    fn sea_level(
        &self,
        height: Height,
        x: f64,
        y: f64,
        terrain: &dyn Terrain,
    ) -> Result<f64, crate::TerrainError> {
        Ok(match height {
            Height::SeaLevel(h) => h,
            Height::AboveTerrain(h) => terrain.height_m(x, y)? + h,
        })
    }

    /// The places the preflight samples the leg at, as fractions of it: both ends, every
    /// [`super::SAMPLE_M`], every bend of the terrain under it (a raster's lines through its
    /// cell centres, a plateau's edges), and between two bends where the ground and the height
    /// above it are highest and lowest ([`crate::terrain::profile_places`]). At 1 m alone, a
    /// step in the ground one cell wide was stepped over: a flight 1.08 m off spray height
    /// read 0.89 m (decision 0028).
    pub fn sample_places(&self, terrain: &dyn Terrain) -> Vec<f64> {
        crate::terrain::profile_places(
            terrain,
            (self.from.x, self.from.y),
            (self.to.x, self.to.y),
            self.horizontal_m(),
            super::SAMPLE_M,
            |t| {
                let (x, y, altitude) = self.at(t, terrain).ok()?;
                let ground = terrain.height_m(x, y).ok()?;
                Some(vec![ground, altitude - ground])
            },
        )
    }

    /// Altitude change, metres: up positive, down negative (for timing climbs and descents).
    pub fn rise_m(&self, terrain: &dyn Terrain) -> Result<f64, crate::TerrainError> {
        let (_, _, a) = self.at(0.0, terrain)?;
        let (_, _, b) = self.at(1.0, terrain)?;
        Ok(b - a)
    }

    /// Seconds `vehicle` takes over the leg: the horizontal at the commanded speed, or the
    /// change of altitude at its climb or descent speed where that is longer (the autopilot
    /// holds its vertical speed limit); a landing as ArduCopter flies `NAV_LAND`
    /// ([`crate::model::Vehicle::landing_s`]). `rise_m` is [`Leg::rise_m`].
    pub fn flight_s(&self, vehicle: &crate::model::Vehicle, rise_m: f64) -> f64 {
        let vertical_s = match self.motion {
            Motion::Landing => vehicle.landing_s(-rise_m),
            _ => vehicle.vertical_s(rise_m),
        };
        (self.horizontal_m() / self.speed_mps).max(vertical_s)
    }
}

/// Where flying the items went wrong before any check: an item the autopilot would not fly.
#[derive(Debug, Clone, PartialEq)]
pub struct Unflyable {
    /// The item (1-based, as ground stations number them).
    pub item: usize,
    /// Why the autopilot would not fly it.
    pub why: String,
}

/// The speeds a mission starts with: the horizontal speed before its first DO_CHANGE_SPEED,
/// and the vertical speeds every climb and descent is flown at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartSpeeds {
    /// Horizontal speed, m/s.
    pub horizontal_mps: f64,
    /// Climb speed, m/s (the vehicle's `climb_speed_mps`).
    pub climb_mps: f64,
    /// Descent speed, m/s (the vehicle's `descent_speed_mps`).
    pub descent_mps: f64,
}

impl StartSpeeds {
    /// `vehicle`'s: its transit speed and its vertical speeds.
    pub fn of(vehicle: &crate::model::Vehicle) -> Self {
        Self {
            horizontal_mps: vehicle.transit_speed_mps,
            climb_mps: vehicle.climb_speed_mps,
            descent_mps: vehicle.descent_mps(),
        }
    }
}

/// The legs of `items`, starting on the ground at home (`home_xy`, ground `home_ground_m`);
/// `to_plan` turns (lon, lat) into plan metres.
pub fn fly(
    items: &[FileItem],
    home_xy: (f64, f64),
    home_ground_m: f64,
    sprayer: SprayerCommand,
    speeds: StartSpeeds,
    to_plan: &dyn Fn(f64, f64) -> (f64, f64),
) -> Result<Vec<Leg>, Unflyable> {
    let mut legs = Vec::new();
    let mut here = Place {
        x: home_xy.0,
        y: home_xy.1,
        height: Height::SeaLevel(home_ground_m),
    };
    let mut spraying = false;
    let mut speed = speeds.horizontal_mps;
    let mut landed = false;
    for (index, item) in items.iter().enumerate() {
        let number = index + 1;
        let fail = |why: String| Unflyable { item: number, why };
        let place = |item: &FileItem| -> Result<Place, Unflyable> {
            let values = [item.lat(), item.lon(), item.altitude()];
            if values.iter().any(|v| !v.is_finite()) {
                return Err(fail(
                    "a position item without a finite place and altitude".into(),
                ));
            }
            if !(-90.0..=90.0).contains(&item.lat()) || !(-180.0..=180.0).contains(&item.lon()) {
                return Err(fail("latitude or longitude out of range".into()));
            }
            let (x, y) = to_plan(item.lon(), item.lat());
            let height = match item.frame {
                FRAME_GLOBAL => Height::SeaLevel(item.altitude()),
                FRAME_GLOBAL_RELATIVE_ALT => Height::SeaLevel(home_ground_m + item.altitude()),
                FRAME_GLOBAL_TERRAIN_ALT => Height::AboveTerrain(item.altitude()),
                other => return Err(fail(format!("frame {other} is not a global frame"))),
            };
            Ok(Place { x, y, height })
        };
        if landed {
            return Err(fail("an item after the landing".into()));
        }
        match item.command {
            CMD_NAV_TAKEOFF | CMD_NAV_WAYPOINT => {
                let target = place(item)?;
                // Takeoff climbs where the vehicle stands; a waypoint is flown to.
                let (to, motion) = if item.command == CMD_NAV_TAKEOFF {
                    let above = Place {
                        x: here.x,
                        y: here.y,
                        height: target.height,
                    };
                    (above, Motion::Takeoff)
                } else {
                    (target, Motion::Flight)
                };
                legs.push(Leg {
                    item: number,
                    from: here,
                    to,
                    spraying,
                    speed_mps: speed,
                    motion,
                });
                here = to;
            }
            CMD_NAV_LAND => {
                let target = place(item)?;
                let above = Place {
                    x: target.x,
                    y: target.y,
                    height: here.height,
                };
                legs.push(Leg {
                    item: number,
                    from: here,
                    to: above,
                    spraying,
                    speed_mps: speed,
                    motion: Motion::Flight,
                });
                let ground = Place {
                    height: Height::AboveTerrain(0.0),
                    ..above
                };
                legs.push(Leg {
                    item: number,
                    from: above,
                    to: ground,
                    spraying,
                    speed_mps: speed,
                    motion: Motion::Landing,
                });
                here = ground;
                landed = true;
            }
            CMD_DO_CHANGE_SPEED => {
                let (kind, value) = (item.params[0], item.params[1]);
                if !(value.is_finite() && value > 0.0) {
                    return Err(fail(format!("speed {value} m/s")));
                }
                // ArduCopter sets the horizontal speed for airspeed and ground speed alike,
                // and the vertical speeds for types 2 and 3.
                let vertical = |name: &str, assumed: f64| {
                    if (value - assumed).abs() > 1e-6 {
                        Err(fail(format!(
                            "DO_CHANGE_SPEED sets the {name} speed to {value} m/s; the check \
                             flies every {name} at the vehicle's {assumed} m/s"
                        )))
                    } else {
                        Ok(())
                    }
                };
                if kind == 0.0 || kind == 1.0 {
                    speed = value;
                } else if kind == 2.0 {
                    vertical("climb", speeds.climb_mps)?;
                } else if kind == 3.0 {
                    vertical("descent", speeds.descent_mps)?;
                } else {
                    return Err(fail(format!(
                        "DO_CHANGE_SPEED of speed type {kind} (0 airspeed, 1 ground speed, \
                         2 climb, 3 descent)"
                    )));
                }
            }
            CMD_DO_SPRAYER => {
                spraying = item.params[0] == 1.0;
            }
            // A survey's camera: triggering by distance is its work "on" (what coverage and
            // the outside checks measure), 0 is off.
            CMD_DO_SET_CAM_TRIGG_DIST => {
                let distance = item.params[0];
                if !(distance.is_finite() && distance >= 0.0) {
                    return Err(fail(format!("camera trigger distance {distance} m")));
                }
                spraying = distance > 0.0;
            }
            CMD_DO_SET_SERVO => match sprayer {
                SprayerCommand::Servo {
                    channel,
                    on_pwm,
                    off_pwm,
                } if item.params[0] == f64::from(channel) => {
                    let pwm = item.params[1];
                    if pwm == f64::from(on_pwm) {
                        spraying = true;
                    } else if pwm == f64::from(off_pwm) {
                        spraying = false;
                    } else {
                        return Err(fail(format!(
                            "servo {channel} set to {pwm}, neither the sprayer's on ({on_pwm}) nor off ({off_pwm})"
                        )));
                    }
                }
                _ => {}
            },
            other => {
                return Err(fail(format!(
                    "command {other} is not one the preflight knows how to fly"
                )))
            }
        }
    }
    if !landed {
        // Without it the autopilot ends the mission hovering at the last waypoint, with
        // the battery the sortie was planned to land with, and the battery check would
        // leave out the descent.
        return Err(Unflyable {
            item: items.len(),
            why: "the mission ends without a landing (NAV_LAND): the vehicle would hover at its last waypoint".into(),
        });
    }
    Ok(legs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn item(command: u16, params: [f64; 7]) -> FileItem {
        FileItem {
            command,
            frame: if matches!(command, CMD_NAV_TAKEOFF | CMD_NAV_WAYPOINT | CMD_NAV_LAND) {
                FRAME_GLOBAL_RELATIVE_ALT
            } else {
                FRAME_GLOBAL
            },
            params,
        }
    }

    fn at(lon: f64) -> [f64; 7] {
        [0.0, 1.0, 0.0, 0.0, 0.0, lon, 30.0]
    }

    const START: StartSpeeds = StartSpeeds {
        horizontal_mps: 5.0,
        climb_mps: 2.5,
        descent_mps: 1.5,
    };

    /// `items` flown from home at (0, 0) on the ground at 0 m, a degree being 100 m.
    fn fly_items(items: &[FileItem]) -> Result<Vec<Leg>, Unflyable> {
        let to_plan = |lon: f64, lat: f64| (lon * 100.0, lat * 100.0);
        fly(
            items,
            (0.0, 0.0),
            0.0,
            SprayerCommand::DoSprayer,
            START,
            &to_plan,
        )
    }

    /// ArduCopter's DO_CHANGE_SPEED: types 0 and 1 set the horizontal speed; types 2 and 3 set
    /// the climb and descent speeds, which leave the legs' speed alone (a sprayer's legs
    /// would fly at the transit speed, half the dose, if type 2 were read as the spray
    /// speed) and are refused unless they are the vehicle's own figures.
    #[test]
    fn the_speed_type_says_which_speed_changes() {
        let fly_with = |kind: f64, value: f64| {
            let items = [
                item(CMD_NAV_TAKEOFF, at(0.0)),
                item(CMD_DO_CHANGE_SPEED, [kind, value, -1.0, 0.0, 0.0, 0.0, 0.0]),
                item(CMD_NAV_WAYPOINT, at(1.0)),
                item(CMD_NAV_LAND, at(1.0)),
            ];
            fly_items(&items)
        };
        for kind in [0.0, 1.0] {
            assert_eq!(fly_with(kind, 3.0).unwrap()[1].speed_mps, 3.0);
        }
        // The vehicle's own vertical speeds: flown, the horizontal speed unchanged.
        assert_eq!(fly_with(2.0, 2.5).unwrap()[1].speed_mps, 5.0);
        assert_eq!(fly_with(3.0, 1.5).unwrap()[1].speed_mps, 5.0);
        for (kind, value, says) in [
            (2.0, 3.0, "climb speed to 3 m/s"),
            (3.0, 3.0, "descent speed to 3 m/s"),
            (4.0, 3.0, "speed type 4"),
        ] {
            let error = fly_with(kind, value).unwrap_err();
            assert_eq!(error.item, 2);
            assert!(error.why.contains(says), "{}", error.why);
        }
    }

    #[test]
    fn the_camera_trigger_is_the_survey_on_and_off_state() {
        let trigger = |distance: f64| {
            item(
                CMD_DO_SET_CAM_TRIGG_DIST,
                [distance, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
            )
        };
        let items = [
            item(CMD_NAV_TAKEOFF, at(0.0)),
            item(CMD_NAV_WAYPOINT, at(1.0)),
            trigger(12.0),
            item(CMD_NAV_WAYPOINT, at(2.0)),
            trigger(0.0),
            item(CMD_NAV_WAYPOINT, at(3.0)),
            item(CMD_NAV_LAND, at(3.0)),
        ];
        let legs = fly_items(&items).unwrap();
        let on: Vec<(f64, bool)> = legs.iter().map(|leg| (leg.to.x, leg.spraying)).collect();
        assert_eq!(on[..3], [(0.0, false), (100.0, false), (200.0, true)]);
        assert_eq!(on[3], (300.0, false));
        let negative = [item(CMD_NAV_TAKEOFF, at(0.0)), trigger(-1.0)];
        let error = fly_items(&negative).unwrap_err();
        assert_eq!(error.item, 2);
        // No landing: refused at the last item.
        let error = fly_items(&items[..items.len() - 1]).unwrap_err();
        assert_eq!(error.item, items.len() - 1);
        assert!(error.why.contains("without a landing"), "{}", error.why);
    }

    /// Decision 0028's leg: 4 m of spray over a 12 m step one cell (4 m) wide, its ends at
    /// spray height over the ground. The places the preflight samples find its worst height
    /// above the ground as 1 cm samples do; 1 m samples miss it by more than 10 cm.
    #[test]
    fn sample_places_find_the_worst_height_over_a_step_one_cell_wide() {
        let (columns, rows) = (10, 10);
        let grid = crate::terrain::Grid {
            columns,
            rows,
            first_center_x: 2.0,
            first_center_y: 38.0,
            cell_x: 4.0,
            cell_y: 4.0,
            heights: (0..rows * columns)
                .map(|index| if index / columns < 5 { 12.0 } else { 0.0 })
                .collect(),
            epsg: None,
            source: "step".into(),
        };
        let place = |x: f64, y: f64| Place {
            x,
            y,
            height: Height::SeaLevel(grid.height_m(x, y).unwrap() + 2.5),
        };
        let leg = Leg {
            item: 2,
            from: place(21.83, 23.9),
            to: place(21.69, 19.9),
            spraying: true,
            speed_mps: 5.0,
            motion: Motion::Flight,
        };
        let worst = |places: &mut dyn Iterator<Item = f64>| {
            places
                .map(|t| {
                    let (x, y, altitude) = leg.at(t, &grid).unwrap();
                    (altitude - grid.height_m(x, y).unwrap() - 2.5).abs()
                })
                .fold(0.0, f64::max)
        };
        let sampled = worst(&mut leg.sample_places(&grid).into_iter());
        let fine = worst(&mut (0..=400).map(|k| f64::from(k) / 400.0));
        let metre = worst(&mut crate::geometry::leg_samples(leg.horizontal_m(), 1.0));
        assert!(sampled >= fine - 1e-9, "{sampled} against {fine}");
        assert!(
            fine - metre > 0.1,
            "the case: {metre} at 1 m against {fine}"
        );
    }
}
