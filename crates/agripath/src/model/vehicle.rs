//! The drone's figures: swath, heights, speeds, tank and battery. Read from TOML
//! (`data/vehicles/*.toml` are commented examples); every number carries its unit in its name.
//!
//! A vehicle with a `[camera]` section is a survey vehicle (decision 0022): it has no tank,
//! its sorties end for the battery only, and the mission files trigger the camera by
//! distance along each swath. With a footprint width w and side overlap s %, the swath (the
//! spacing of swaths) is w · (1 − s/100); with a footprint length l along the track and front
//! overlap f %, the trigger distance is l · (1 − f/100), unless stated directly.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Fault, InputError};
use crate::files::read_text;

/// Height above the ground below which ArduCopter lands at `LAND_SPEED` (its `LAND_ALT_LOW`,
/// 10 m by default), metres.
pub const LAND_SLOW_BELOW_M: f64 = 10.0;

/// A spraying or survey drone. `Default` is the seed 001 sprayer (5 m swath, h = 18 m) with
/// seed 003's speeds, tank and battery.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct Vehicle {
    /// The vehicle's name, as reports show it.
    pub name: String,
    /// Width sprayed (or imaged) by one pass, metres; also the spacing of swaths.
    pub swath_width_m: f64,
    /// Height above the terrain while spraying, metres.
    pub spray_height_m: f64,
    /// Seed 001's h: the climb above spray height for a transfer that leaves the work area, metres.
    pub safe_height_m: f64,
    /// Ground speed along a swath, m/s.
    pub spray_speed_mps: f64,
    /// Speed through headland turns, m/s.
    pub turn_speed_mps: f64,
    /// Speed of transfers and return flights, m/s.
    pub transit_speed_mps: f64,
    /// Vertical speed for climbs (and descents, unless `descent_speed_mps` is given), m/s.
    pub climb_speed_mps: f64,
    /// Vertical speed for descents, m/s; `None`: `climb_speed_mps` (the seeds' reading).
    /// ArduCopter descends at `WPNAV_SPEED_DN`, 1.5 m/s by default.
    pub descent_speed_mps: Option<f64>,
    /// Descent speed of the landing's last [`LAND_SLOW_BELOW_M`], m/s (ArduCopter's
    /// `LAND_SPEED`, 0.5 m/s by default); `None`: the whole landing at the descent speed.
    pub land_speed_mps: Option<f64>,
    /// Tank volume, litres (with `application_rate_l_per_ha` it limits the area per sortie).
    pub tank_l: Option<f64>,
    /// Litres applied per hectare.
    pub application_rate_l_per_ha: Option<f64>,
    /// Seed 003's form of the tank limit: seconds of spraying one tank lasts.
    pub tank_spray_time_s: Option<f64>,
    /// Flight time one battery gives, seconds.
    pub battery_endurance_s: f64,
    /// Share of the battery to land with, percent: every sortie, as written and flown, keeps
    /// it unused (0: `battery_endurance_s` is the flight time to plan with, the seeds' reading).
    pub battery_reserve_percent: f64,
    /// Time to swap a battery at the supply point, seconds.
    pub battery_swap_s: f64,
    /// Seed 003 eq. (5): refill time t_b for an empty request…
    pub refill_base_s: f64,
    /// …rising linearly to T_pmax for a full tank.
    pub refill_max_s: f64,
    /// A survey camera instead of a sprayer (`[camera]`); `None` for a sprayer.
    pub camera: Option<Camera>,
    /// The most mission items the autopilot holds, its home item included: every sortie's
    /// mission is held to it by the preflight. `None`: not checked, and the summary warns
    /// above [`COMMON_MISSION_ITEMS`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mission_items_max: Option<u32>,
}

/// Mission items above which the summary warns when the vehicle states no limit: ArduPilot
/// keeps a mission in the board's FRAM, 14-15 bytes an item, which holds about 700 on a
/// Pixhawk (ArduPilot issues #2391 and #7254; more with `BRD_SD_MISSION` on a microSD card);
/// older firmware dropped the items beyond it silently.
pub const COMMON_MISSION_ITEMS: usize = 700;

/// Fewest mission items a limit may give: home and one waypoint.
const FEWEST_MISSION_ITEMS: u32 = 2;

/// A survey camera, triggered by distance along each swath (`MAV_CMD_DO_SET_CAM_TRIGG_DIST`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// Ground distance between photos along a swath, metres; else derived from the
    /// footprint length and the front overlap.
    pub trigger_distance_m: Option<f64>,
    /// Ground footprint of one photo across the track, metres.
    pub footprint_width_m: Option<f64>,
    /// Ground footprint of one photo along the track, metres.
    pub footprint_length_m: Option<f64>,
    /// Overlap of neighbouring swaths' photos, percent of the footprint width.
    pub side_overlap_percent: Option<f64>,
    /// Overlap of consecutive photos along a swath, percent of the footprint length.
    pub front_overlap_percent: Option<f64>,
}

impl Camera {
    /// Swath spacing from the footprint and the side overlap, when both are given: w · (1 − s/100).
    pub fn swath_width_m(&self) -> Option<f64> {
        // w · (100 − s) / 100 keeps round figures round (90 m at 70 % is 27 m, not 27.000000000000004).
        Some(self.footprint_width_m? * (100.0 - self.side_overlap_percent?) / 100.0)
    }

    /// The trigger distance: stated, or l · (1 − f/100) from the footprint length and front overlap.
    pub fn trigger_distance_m(&self) -> Option<f64> {
        self.trigger_distance_m.or_else(|| {
            Some(self.footprint_length_m? * (100.0 - self.front_overlap_percent?) / 100.0)
        })
    }

    /// Checks the figures given and that a trigger distance follows from them.
    fn validate(&self) -> Result<(), Fault> {
        let lengths = [
            ("camera.trigger_distance_m", self.trigger_distance_m),
            ("camera.footprint_width_m", self.footprint_width_m),
            ("camera.footprint_length_m", self.footprint_length_m),
        ];
        for (what, value) in lengths {
            if let Some(value) = value {
                if !(value.is_finite() && value > 0.0 && value <= 10_000.0) {
                    return Err(invalid(
                        what,
                        value,
                        "must be a finite number above 0, at most 10000 m",
                    ));
                }
            }
        }
        let overlaps = [
            ("camera.side_overlap_percent", self.side_overlap_percent),
            ("camera.front_overlap_percent", self.front_overlap_percent),
        ];
        for (what, value) in overlaps {
            if let Some(value) = value {
                if !(value.is_finite() && (0.0..100.0).contains(&value)) {
                    return Err(invalid(
                        what,
                        value,
                        "must be a percentage in 0..100 (100 % would never move on)",
                    ));
                }
            }
        }
        if self.side_overlap_percent.is_some() && self.footprint_width_m.is_none() {
            return Err(Fault::Structure(
                "camera.side_overlap_percent needs camera.footprint_width_m".into(),
            ));
        }
        if self.front_overlap_percent.is_some() != self.footprint_length_m.is_some() {
            return Err(Fault::Structure(
                "camera.footprint_length_m and camera.front_overlap_percent go together".into(),
            ));
        }
        match (self.trigger_distance_m, self.footprint_length_m, self.front_overlap_percent) {
            (None, None, _) => Err(Fault::Structure(
                "a [camera] needs trigger_distance_m, or footprint_length_m with front_overlap_percent".into(),
            )),
            (Some(stated), Some(length), Some(front))
                if (stated - length * (100.0 - front) / 100.0).abs() > 1e-3 =>
            {
                Err(invalid(
                    "camera.trigger_distance_m",
                    stated,
                    &format!(
                        "disagrees with footprint_length_m × (1 − front_overlap_percent/100) = {}: give one of them",
                        crate::error::figure(length * (100.0 - front) / 100.0)
                    ),
                ))
            }
            _ => Ok(()),
        }
    }
}

impl Default for Vehicle {
    fn default() -> Self {
        Self {
            name: "seed 001/003 sprayer".to_string(),
            swath_width_m: 5.0,
            spray_height_m: 2.0,
            safe_height_m: 18.0,
            spray_speed_mps: 3.0,
            turn_speed_mps: 3.0,
            transit_speed_mps: 6.0,
            climb_speed_mps: 2.0,
            descent_speed_mps: None,
            land_speed_mps: None,
            tank_l: None,
            application_rate_l_per_ha: None,
            tank_spray_time_s: Some(15.0 * 60.0),
            battery_endurance_s: 25.0 * 60.0,
            battery_reserve_percent: 0.0,
            battery_swap_s: 60.0,
            refill_base_s: 20.0,
            refill_max_s: 120.0,
            camera: None,
            mission_items_max: None,
        }
    }
}

/// Battery endurance under which a vehicle file gets a note (seconds): two minutes.
pub const SHORT_BATTERY_S: f64 = 120.0;

impl Vehicle {
    /// How far above the spray height a transit flies: h, at least 5 m (decision 0012: a
    /// transit over the highest ground under it, never at crop height even when h is 0).
    pub fn transit_rise_m(&self) -> f64 {
        self.safe_height_m.max(5.0)
    }

    /// The height of a transit above the highest ground under it: spray height + max(h, 5 m).
    pub fn cruise_height_m(&self) -> f64 {
        self.spray_height_m + self.transit_rise_m()
    }

    /// Descent speed, m/s: `descent_speed_mps`, else the climb speed.
    pub fn descent_mps(&self) -> f64 {
        self.descent_speed_mps.unwrap_or(self.climb_speed_mps)
    }

    /// Seconds a change of altitude of `rise_m` metres takes at the vehicle's vertical speeds
    /// (up at the climb speed, down at the descent speed).
    pub fn vertical_s(&self, rise_m: f64) -> f64 {
        if rise_m >= 0.0 {
            rise_m / self.climb_speed_mps
        } else {
            -rise_m / self.descent_mps()
        }
    }

    /// Seconds a landing from `height_m` above the ground takes, as ArduCopter flies
    /// `NAV_LAND`: at the descent speed down to [`LAND_SLOW_BELOW_M`] (`LAND_ALT_LOW`), then at
    /// `land_speed_mps` (`LAND_SPEED`) when given.
    pub fn landing_s(&self, height_m: f64) -> f64 {
        let height_m = height_m.max(0.0);
        match self.land_speed_mps {
            Some(land_mps) => {
                let slow_m = height_m.min(LAND_SLOW_BELOW_M);
                (height_m - slow_m) / self.descent_mps() + slow_m / land_mps
            }
            None => height_m / self.descent_mps(),
        }
    }

    /// The flight time a sortie may use: the endurance less the share to land with.
    pub fn usable_battery_s(&self) -> f64 {
        self.battery_endurance_s * (1.0 - self.battery_reserve_percent / 100.0)
    }

    /// Reads and validates a vehicle file.
    pub fn from_file(path: &Path) -> Result<Self, InputError> {
        let text = read_text(path)?;
        let stated: toml::Table =
            toml::from_str(&text).map_err(|error| InputError::toml(path, &error, &text))?;
        let mut vehicle: Self =
            toml::from_str(&text).map_err(|error| InputError::toml(path, &error, &text))?;
        vehicle
            .apply_stated(&stated)
            .and_then(|()| vehicle.validate())
            .map_err(|fault| InputError::new(path, fault))?;
        Ok(vehicle)
    }

    /// Parses and validates a vehicle file's text; errs on bad TOML or an invalid value.
    pub fn from_toml(text: &str) -> Result<Self, Fault> {
        let fault = |error: toml::de::Error| Fault::Toml {
            message: one_line(&error, text),
            line_column: None,
        };
        let stated: toml::Table = toml::from_str(text).map_err(fault)?;
        let mut vehicle: Self = toml::from_str(text).map_err(fault)?;
        vehicle.apply_stated(&stated)?;
        vehicle.validate()?;
        Ok(vehicle)
    }

    /// Whether the vehicle surveys (has a camera) rather than sprays.
    pub fn is_survey(&self) -> bool {
        self.camera.is_some()
    }

    /// The words the summaries, the report and the map use for a vehicle's work on its
    /// swaths: the noun, the participle and the past ("spray", "spraying", "sprayed"), or a
    /// survey's.
    pub fn work_words(surveys: bool) -> [&'static str; 3] {
        if surveys {
            ["survey", "surveying", "surveyed"]
        } else {
            ["spray", "spraying", "sprayed"]
        }
    }

    /// The survey camera's trigger distance, metres (`None` for a sprayer).
    pub fn trigger_distance_m(&self) -> Option<f64> {
        self.camera.as_ref().and_then(Camera::trigger_distance_m)
    }

    /// Completes a vehicle from what its file (`stated`, the keys as written) says.
    ///
    /// The tank: a file gives it as `tank_l` with `application_rate_l_per_ha` or as
    /// `tank_spray_time_s`, and the seed 003 tank of 900 s that a file without tank keys gets
    /// by default is not the stated one's (a 100 L tank was held to 900 s of spraying,
    /// silently, whichever was smaller); both forms at once are refused.
    ///
    /// A survey vehicle: the swath from the camera's footprint and side overlap, and no tank.
    /// A tank key beside a camera, or a stated swath the footprint contradicts, is refused
    /// rather than ignored.
    pub fn apply_stated(&mut self, stated: &toml::Table) -> Result<(), Fault> {
        let by_volume = ["tank_l", "application_rate_l_per_ha"]
            .into_iter()
            .find(|key| stated.contains_key(*key));
        if let Some(key) = by_volume {
            if self.camera.is_none() && stated.contains_key("tank_spray_time_s") {
                return Err(Fault::Structure(format!(
                    "{key} and tank_spray_time_s both give the tank: give one (tank_l with application_rate_l_per_ha, or tank_spray_time_s)"
                )));
            }
            self.tank_spray_time_s = None;
        }
        let Some(camera) = &self.camera else {
            return Ok(());
        };
        for key in ["tank_l", "application_rate_l_per_ha", "tank_spray_time_s"] {
            if stated.contains_key(key) {
                return Err(Fault::Structure(format!(
                    "{key} and [camera] do not go together: a survey vehicle has no tank (remove {key}, or the camera for a sprayer)"
                )));
            }
        }
        camera.validate()?;
        if let Some(width) = camera.swath_width_m() {
            if stated.contains_key("swath_width_m") && (self.swath_width_m - width).abs() > 1e-3 {
                return Err(invalid(
                    "swath_width_m",
                    self.swath_width_m,
                    &format!(
                        "disagrees with the camera's footprint_width_m × (1 − side_overlap_percent/100) = {}: give one of them",
                        crate::error::figure(width)
                    ),
                ));
            }
            self.swath_width_m = width;
        }
        // The seed 003 tank a file without tank keys gets by default is not this vehicle's.
        self.tank_spray_time_s = None;
        Ok(())
    }

    /// A note when the battery lasts under [`SHORT_BATTERY_S`]: valid (a test rig may fly
    /// that little), but most likely minutes typed where seconds belong (a tenth trial's
    /// `battery_endurance_s = 12.0`, which `validate` passed and `plan` blamed on the supply
    /// point).
    pub fn short_battery_note(&self) -> Option<String> {
        (self.battery_endurance_s < SHORT_BATTERY_S).then(|| {
            let seconds = crate::error::figure(self.battery_endurance_s);
            format!(
                "battery_endurance_s = {seconds} gives {seconds} seconds of flight: the figure is in seconds (a multirotor flies 8-30 minutes, 480-1800 s); minutes typed?"
            )
        })
    }

    /// Checks every figure once; afterwards the vehicle is usable everywhere.
    pub fn validate(&self) -> Result<(), Fault> {
        if let Some(camera) = &self.camera {
            camera.validate()?;
            if self.tank_l.is_some() || self.application_rate_l_per_ha.is_some() {
                return Err(Fault::Structure(
                    "tank_l and [camera] do not go together: a survey vehicle has no tank".into(),
                ));
            }
        }
        let positive = [
            ("swath_width_m", self.swath_width_m),
            ("spray_speed_mps", self.spray_speed_mps),
            ("turn_speed_mps", self.turn_speed_mps),
            ("transit_speed_mps", self.transit_speed_mps),
            ("climb_speed_mps", self.climb_speed_mps),
            ("battery_endurance_s", self.battery_endurance_s),
        ];
        for (what, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(what, value, "must be a finite number above 0"));
            }
        }
        let non_negative = [
            ("spray_height_m", self.spray_height_m),
            ("safe_height_m", self.safe_height_m),
            ("battery_swap_s", self.battery_swap_s),
            ("battery_reserve_percent", self.battery_reserve_percent),
            ("refill_base_s", self.refill_base_s),
            ("refill_max_s", self.refill_max_s),
        ];
        for (what, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(what, value, "must be a finite number, 0 or more"));
            }
        }
        let optional_positive = [
            ("descent_speed_mps", self.descent_speed_mps),
            ("land_speed_mps", self.land_speed_mps),
            ("tank_l", self.tank_l),
            ("application_rate_l_per_ha", self.application_rate_l_per_ha),
            ("tank_spray_time_s", self.tank_spray_time_s),
        ];
        for (what, value) in optional_positive {
            if let Some(value) = value {
                if !(value.is_finite() && value > 0.0) {
                    return Err(invalid(what, value, "must be a finite number above 0"));
                }
            }
        }
        for (what, low, high) in crate::limits::VEHICLE_RANGES {
            let value = match what {
                "swath_width_m" => Some(self.swath_width_m),
                "spray_height_m" => Some(self.spray_height_m),
                "safe_height_m" => Some(self.safe_height_m),
                "spray_speed_mps" => Some(self.spray_speed_mps),
                "turn_speed_mps" => Some(self.turn_speed_mps),
                "transit_speed_mps" => Some(self.transit_speed_mps),
                "climb_speed_mps" => Some(self.climb_speed_mps),
                "descent_speed_mps" => self.descent_speed_mps,
                "land_speed_mps" => self.land_speed_mps,
                "battery_endurance_s" => Some(self.battery_endurance_s),
                "battery_reserve_percent" => Some(self.battery_reserve_percent),
                "battery_swap_s" => Some(self.battery_swap_s),
                "refill_base_s" => Some(self.refill_base_s),
                "refill_max_s" => Some(self.refill_max_s),
                "tank_spray_time_s" => self.tank_spray_time_s,
                "tank_l" => self.tank_l,
                other => unreachable!("a vehicle range names an unknown figure: {other}"),
            };
            if let Some(value) = value {
                if !(low..=high).contains(&value) {
                    return Err(invalid(
                        what,
                        value,
                        &format!("a vehicle's {what} lies in {low}..={high} (docs/limits.md)"),
                    ));
                }
            }
        }
        if let Some(rate) = self.application_rate_l_per_ha {
            if rate > crate::limits::MAX_APPLICATION_RATE_L_PER_HA {
                return Err(invalid(
                    "application_rate_l_per_ha",
                    rate,
                    "at most 10000 litres per hectare (docs/limits.md)",
                ));
            }
        }
        if let Some(items) = self.mission_items_max {
            if items < FEWEST_MISSION_ITEMS {
                return Err(invalid(
                    "mission_items_max",
                    f64::from(items),
                    "must be at least 2: the home item and one waypoint",
                ));
            }
        }
        if self.refill_max_s < self.refill_base_s {
            return Err(invalid(
                "refill_max_s",
                self.refill_max_s,
                "must not be below refill_base_s",
            ));
        }
        if self.tank_l.is_some() != self.application_rate_l_per_ha.is_some() {
            return Err(Fault::Structure(
                "tank_l and application_rate_l_per_ha go together: give both or neither".into(),
            ));
        }
        Ok(())
    }

    /// Litres one metre of swath sprays: the application rate over a swath-wide strip
    /// (`None` when the vehicle gives no rate).
    pub fn litres_per_spray_m(&self) -> Option<f64> {
        self.application_rate_l_per_ha
            .map(|rate| rate / 10_000.0 * self.swath_width_m)
    }

    /// Metres of swath one tank sprays, if the tank limits a sortie (never for a survey).
    pub fn spray_length_per_tank_m(&self) -> Option<f64> {
        if self.is_survey() {
            return None;
        }
        let by_volume = match (self.tank_l, self.application_rate_l_per_ha) {
            // litres / (litres per m²) / swath width
            (Some(tank), Some(rate)) => Some(tank / (rate / 10_000.0) / self.swath_width_m),
            _ => None,
        };
        let by_time = self
            .tank_spray_time_s
            .map(|time| time * self.spray_speed_mps);
        match (by_volume, by_time) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

fn invalid(what: &str, value: f64, why: &str) -> Fault {
    Fault::InvalidValue {
        what: what.to_string(),
        value: crate::error::figure(value),
        why: why.to_string(),
    }
}

/// TOML errors span several lines with a caret drawing; the CLI promises one line.
/// A TOML error in one line, placed at its line and column in `text` (the text it was read
/// from; empty when the value did not come from text). For a file, [`InputError::toml`]
/// places it as `file:line:column` instead.
pub(crate) fn one_line(error: &toml::de::Error, text: &str) -> String {
    let message = crate::error::toml_message(error);
    match error.span() {
        Some(span) if span.start <= text.len() => {
            let (line, column) = crate::error::line_column(text, span.start);
            format!("line {line}, column {column}: {message}")
        }
        _ => message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_is_valid_and_seed_003_tank_is_2700_m() {
        let vehicle = Vehicle::default();
        vehicle.validate().unwrap();
        assert_eq!(vehicle.spray_length_per_tank_m(), Some(2700.0));
    }

    #[test]
    fn example_files_parse() {
        let folder = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/vehicles");
        let mut count = 0;
        for entry in std::fs::read_dir(folder).unwrap() {
            let path = entry.unwrap().path();
            Vehicle::from_file(&path).unwrap_or_else(|error| panic!("{error}"));
            count += 1;
        }
        assert!(count >= 4, "expected an example per seed drone and the T16");
    }

    #[test]
    fn a_tank_is_given_one_way() {
        // A 100 L tank at 20 L/ha and 5 m: 10,000 m of swath, not the 900 s × 5 m/s of the
        // seed 003 default.
        let volume = "tank_l = 100.0\napplication_rate_l_per_ha = 20.0\nswath_width_m = 5.0\nspray_speed_mps = 5.0\n";
        let vehicle = Vehicle::from_toml(volume).unwrap();
        assert_eq!(vehicle.tank_spray_time_s, None);
        assert!((vehicle.spray_length_per_tank_m().unwrap() - 10_000.0).abs() < 1e-9);
        // Without tank keys the seed 003 tank stays.
        let none = Vehicle::from_toml("spray_speed_mps = 5.0\n").unwrap();
        assert_eq!(none.spray_length_per_tank_m(), Some(4_500.0));
        // Both forms: refused, naming both keys.
        let both = format!("{volume}tank_spray_time_s = 600.0\n");
        let error = Vehicle::from_toml(&both).unwrap_err().to_string();
        assert!(
            error.contains("tank_l and tank_spray_time_s both give the tank"),
            "{error}"
        );
    }

    #[test]
    fn a_camera_makes_a_survey_vehicle_without_a_tank() {
        let camera = "[camera]\nfootprint_width_m = 90.0\nfootprint_length_m = 60.0\nside_overlap_percent = 70.0\nfront_overlap_percent = 80.0\n";
        let vehicle = Vehicle::from_toml(camera).unwrap();
        assert!(vehicle.is_survey());
        assert_eq!(vehicle.swath_width_m, 27.0);
        assert_eq!(vehicle.trigger_distance_m(), Some(12.0));
        // No seed 003 tank by default: sorties end for the battery only.
        assert_eq!(vehicle.spray_length_per_tank_m(), None);
        let direct =
            Vehicle::from_toml("swath_width_m = 20.0\n[camera]\ntrigger_distance_m = 8.0\n")
                .unwrap();
        assert_eq!(
            (direct.swath_width_m, direct.trigger_distance_m()),
            (20.0, Some(8.0))
        );
        let agreeing = format!("swath_width_m = 27.0\n{camera}");
        assert_eq!(Vehicle::from_toml(&agreeing).unwrap().swath_width_m, 27.0);
    }

    #[test]
    fn a_survey_vehicle_with_a_tank_or_contradicting_figures_is_refused() {
        let cases = [
            ("tank_l = 10.0\napplication_rate_l_per_ha = 10.0\n[camera]\ntrigger_distance_m = 8.0\n", "tank_l and [camera]"),
            ("tank_spray_time_s = 600.0\n[camera]\ntrigger_distance_m = 8.0\n", "tank_spray_time_s and [camera]"),
            ("swath_width_m = 30.0\n[camera]\nfootprint_width_m = 90.0\nside_overlap_percent = 70.0\ntrigger_distance_m = 8.0\n", "swath_width_m = 30 is invalid: disagrees"),
            ("[camera]\nfootprint_width_m = 90.0\n", "needs trigger_distance_m"),
            ("[camera]\ntrigger_distance_m = 0.0\n", "camera.trigger_distance_m = 0 is invalid"),
            ("[camera]\ntrigger_distance_m = 8.0\nside_overlap_percent = 60.0\n", "needs camera.footprint_width_m"),
            ("[camera]\nfootprint_length_m = 60.0\nfront_overlap_percent = 100.0\n", "front_overlap_percent = 100 is invalid"),
            ("[camera]\ntrigger_distance_m = 8.0\nfootprint_length_m = 60.0\nfront_overlap_percent = 80.0\n", "disagrees with footprint_length_m"),
        ];
        for (text, expected) in cases {
            let error = Vehicle::from_toml(text).unwrap_err().to_string();
            assert!(error.contains(expected), "{text}: {error}");
        }
        let error = toml::from_str::<Vehicle>("[camera]\nshutter = 1\n").unwrap_err();
        assert!(
            error.message().contains("unknown field `shutter`"),
            "{error}"
        );
    }

    #[test]
    fn bad_values_are_named() {
        let error = Vehicle::from_toml("swath_width_m = -1").unwrap_err();
        assert!(error.to_string().contains("swath_width_m = -1"), "{error}");
        let error = Vehicle::from_toml("swath_widht_m = 5").unwrap_err();
        assert!(error.to_string().contains("swath_widht_m"), "{error}");
        let error = Vehicle::from_toml("swath_width_m = nan").unwrap_err();
        assert!(error.to_string().contains("NaN"), "{error}");
    }
}
