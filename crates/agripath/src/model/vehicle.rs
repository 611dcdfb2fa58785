//! The drone's figures: swath, heights, speeds, tank and battery. Read from TOML
//! (`data/vehicles/*.toml` are commented examples); every number carries its unit in its name.

use std::path::Path;

use serde::Deserialize;

use crate::error::{Fault, InputError};
use crate::files::read_text;

/// A spraying or survey drone. `Default` is the seed 001 sprayer (5 m swath, h = 18 m) with
/// seed 003's speeds, tank and battery.
#[derive(Debug, Clone, PartialEq, Deserialize)]
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
    /// Vertical speed for climbs and descents, m/s.
    pub climb_speed_mps: f64,
    /// Tank volume, litres (with `application_rate_l_per_ha` it limits the area per sortie).
    pub tank_l: Option<f64>,
    /// Litres applied per hectare.
    pub application_rate_l_per_ha: Option<f64>,
    /// Seed 003's form of the tank limit: seconds of spraying one tank lasts.
    pub tank_spray_time_s: Option<f64>,
    /// Flight time one battery gives, seconds.
    pub battery_endurance_s: f64,
    /// Time to swap a battery at the supply point, seconds.
    pub battery_swap_s: f64,
    /// Seed 003 eq. (5): refill time t_b for an empty request…
    pub refill_base_s: f64,
    /// …rising linearly to T_pmax for a full tank.
    pub refill_max_s: f64,
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
            tank_l: None,
            application_rate_l_per_ha: None,
            tank_spray_time_s: Some(15.0 * 60.0),
            battery_endurance_s: 25.0 * 60.0,
            battery_swap_s: 60.0,
            refill_base_s: 20.0,
            refill_max_s: 120.0,
        }
    }
}

impl Vehicle {
    /// Reads and validates a vehicle file.
    pub fn from_file(path: &Path) -> Result<Self, InputError> {
        let text = read_text(path)?;
        Self::from_toml(&text).map_err(|fault| InputError::new(path, fault))
    }

    /// Parses and validates a vehicle file's text; errs on bad TOML or an invalid value.
    pub fn from_toml(text: &str) -> Result<Self, Fault> {
        let vehicle: Self =
            toml::from_str(text).map_err(|error| Fault::Toml(one_line(&error, text)))?;
        vehicle.validate()?;
        Ok(vehicle)
    }

    /// Checks every figure once; afterwards the vehicle is usable everywhere.
    pub fn validate(&self) -> Result<(), Fault> {
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
            ("refill_base_s", self.refill_base_s),
            ("refill_max_s", self.refill_max_s),
        ];
        for (what, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(what, value, "must be a finite number, 0 or more"));
            }
        }
        let optional_positive = [
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
                "battery_endurance_s" => Some(self.battery_endurance_s),
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

    /// Metres of swath one tank sprays, if the tank limits a sortie.
    pub fn spray_length_per_tank_m(&self) -> Option<f64> {
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
/// A TOML error in one line, placed at its line and column in `text` (the file it was read
/// from; empty when the value did not come from text).
pub(crate) fn one_line(error: &toml::de::Error, text: &str) -> String {
    let message = error.message().trim().replace('\n', " ");
    match error.span() {
        Some(span) if span.start <= text.len() => {
            let mut end = span.start;
            while !text.is_char_boundary(end) {
                end -= 1;
            }
            let before = &text[..end];
            let line = before.matches('\n').count() + 1;
            let column = before
                .rsplit('\n')
                .next()
                .map_or(0, |tail| tail.chars().count())
                + 1;
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
    fn bad_values_are_named() {
        let error = Vehicle::from_toml("swath_width_m = -1").unwrap_err();
        assert!(error.to_string().contains("swath_width_m = -1"), "{error}");
        let error = Vehicle::from_toml("swath_widht_m = 5").unwrap_err();
        assert!(error.to_string().contains("swath_widht_m"), "{error}");
        let error = Vehicle::from_toml("swath_width_m = nan").unwrap_err();
        assert!(error.to_string().contains("NaN"), "{error}");
    }
}
