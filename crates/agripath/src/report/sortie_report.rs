//! One sortie's row of `report.json` (`sortie_details`).

use serde::Serialize;

use crate::model::Vehicle;
use crate::numbers::round;

/// One sortie in `report.json`.
#[derive(Debug, Clone, Serialize)]
pub struct SortieReport {
    /// Number of the sortie, from 1, as in `preflight.sorties` and the file names
    /// (`plan.geojson`'s features count sorties from 0).
    pub sortie: usize,
    /// The sortie's mission file (`sortie_NN.plan`, with `.waypoints` beside it).
    pub file: String,
    /// Spray metres flown.
    pub spray_m: f64,
    /// Litres sprayed (`null` when the application rate is not known).
    pub litres: Option<f64>,
    /// Share of a tank used, percent (`null` when the tank does not limit a sortie).
    pub tank_percent: Option<f64>,
    /// A survey's photos to expect in this sortie: its survey metres / trigger distance
    /// (absent for a sprayer).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photos_estimate: Option<u64>,
    /// Out from the supply point, along the route and back, seconds.
    pub flight_time_s: f64,
    /// Share of the battery endurance used, percent.
    pub battery_percent: f64,
    /// Where it ends with a return (`null` for the last), in the input's coordinates.
    pub return_point: Option<[f64; 3]>,
}

impl SortieReport {
    /// Sortie `index` (from 0) of `vehicle`: its spray metres, the share of a tank they take
    /// (none where the tank does not limit), its flight seconds and share of the battery, and
    /// its return point; figures rounded as `report.json` writes them.
    pub fn new(
        index: usize,
        spray_m: f64,
        tank_fraction: Option<f64>,
        (flight_s, battery_fraction): (f64, f64),
        return_point: Option<[f64; 3]>,
        vehicle: &Vehicle,
    ) -> Self {
        Self {
            sortie: index + 1,
            file: format!("{}.plan", crate::mission::sortie_file_stem(index)),
            spray_m: round(spray_m, 1e-4),
            litres: vehicle
                .litres_per_spray_m()
                .map(|per_m| round(per_m * spray_m, 1e-3)),
            tank_percent: tank_fraction.map(|f| round(100.0 * f, 1e-3)),
            photos_estimate: vehicle
                .trigger_distance_m()
                .map(|distance| (spray_m / distance).round() as u64),
            flight_time_s: round(flight_s, 1e-3),
            battery_percent: round(100.0 * battery_fraction, 1e-3),
            return_point,
        }
    }

    /// The one flight of a plan not split into sorties (`--sorties none`), from its mission
    /// file as the preflight flew it: every written mission file has its row (trial 7 found
    /// `sortie_details` empty beside a written `sortie_01.plan`).
    pub fn as_flown(flown: &crate::preflight::SortieFlown, vehicle: &Vehicle) -> Self {
        Self::new(
            flown.sortie - 1,
            flown.spray_m,
            flown.tank_fraction,
            (flown.flight_time_s, flown.battery_fraction),
            None,
            vehicle,
        )
    }
}
