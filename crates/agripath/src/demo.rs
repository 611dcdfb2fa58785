//! The embedded default: seed 001's five-field farm (Table 6) with the 3 m plateau in S4 and
//! the seed 001 sprayer, so that `agripath demo` needs no input files.

use std::path::Path;

use crate::error::InputError;
use crate::input::{geojson, CoordinateChoice};
use crate::model::Vehicle;
use crate::scenario::Scenario;
use crate::scenario::ScenarioParts;

/// `data/seed001_farm.geojson`, compiled in.
pub const FARM_GEOJSON: &str = include_str!("../../../data/seed001_farm.geojson");

/// How the embedded farm is named in messages and reports.
pub const FARM_LABEL: &str = "<embedded>/seed001_farm.geojson";

/// The demo scenario: the farm, its plateau terrain, the default (seed 001) sprayer.
pub fn scenario() -> Result<Scenario, InputError> {
    let farm = geojson::parse(
        Path::new(FARM_LABEL),
        FARM_GEOJSON,
        CoordinateChoice::FromFile,
    )?;
    let vehicle = Vehicle::default();
    let mut vehicle_table = toml::Table::new();
    vehicle_table.insert("name".into(), toml::Value::String(vehicle.name));
    Scenario::with_farm(
        farm,
        ScenarioParts {
            name: Some("seed 001 farm (embedded demo)".into()),
            vehicle_table: Some(vehicle_table),
            ..ScenarioParts::default()
        },
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn embedded_farm_has_five_fields_and_the_plateau() {
        let scenario = super::scenario().unwrap();
        assert_eq!(scenario.farm.fields.len(), 5);
        assert_eq!(scenario.terrain.height_m(426.0, -128.0), Ok(3.0));
        assert_eq!(scenario.terrain.height_m(0.0, 0.0), Ok(0.0));
    }
}
