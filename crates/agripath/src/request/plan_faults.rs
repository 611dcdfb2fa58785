//! The faults of `plan` as the user reads them: points typed on the command line checked
//! and refused naming the flag, planning faults named after their cause.

use super::bad_value;
use crate::error::{Fault, InputError, TerrainError};
use crate::scenario::Scenario;
use crate::settings::PlanSettings;
use crate::terrain::TerrainSpec;

/// A point typed after `flag` (`text`, read as `typed` in the field file's coordinates:
/// longitude first for a lon/lat file), in planning metres. Refused, naming the flag and the
/// value as typed, when it is off the globe or farther from the fields than a farm is wide
/// ([`crate::limits::MAX_FARM_EXTENT_M`]): a typo, not a place to fly from (the battery check
/// would otherwise blame the vehicle). When the two numbers swapped would lie near the fields,
/// the message says so.
pub(super) fn typed_point(
    flag: &str,
    text: &str,
    typed: [f64; 2],
    farm: &crate::model::Farm,
) -> Result<[f64; 2], InputError> {
    let frame = farm.coordinate_system;
    let geographic = matches!(frame, crate::model::CoordinateSystem::Utm(_));
    let on_globe = |[lon, lat]: [f64; 2]| {
        !geographic || ((-180.0..=180.0).contains(&lon) && (-90.0..=90.0).contains(&lat))
    };
    let limit_m = crate::limits::MAX_FARM_EXTENT_M;
    let away_m = |point: [f64; 2]| {
        let (x, y) = frame.to_plan(point[0], point[1]);
        farm.distance_outside_bounds_m(x, y)
    };
    let [a, b] = typed;
    let swapped = [b, a];
    let hint = if on_globe(swapped) && away_m(swapped) <= limit_m {
        format!(
            "; swapped, {b},{a} lies {:.1} km from the fields: did you give {} second?",
            away_m(swapped) / 1000.0,
            if geographic { "the longitude" } else { "x" }
        )
    } else {
        String::new()
    };
    if !on_globe(typed) {
        return Err(bad_value(
            flag,
            text,
            format!("longitude {a}, latitude {b} is off the globe (longitude first: -180..180, then latitude: -90..90){hint}"),
        ));
    }
    let away = away_m(typed);
    if away.is_nan() || away > limit_m {
        return Err(bad_value(
            flag,
            text,
            format!(
                "it lies {:.0} km from the fields (at most {:.0} km){hint}",
                away / 1000.0,
                limit_m / 1000.0
            ),
        ));
    }
    let (x, y) = frame.to_plan(a, b);
    Ok([x, y])
}

/// A planning fault as the user reads it: a fault of the vehicle names the vehicle file
/// (else the field file), and places are in the input's coordinates (lon/lat for a lon/lat
/// farm, not the UTM metres it was planned in). A route that cannot be flown on one battery
/// from a supply point typed on the command line (`settings.start`) farther from the fields
/// than `auto` would stand ([`crate::supply::standing::REACH_M`]) blames that point.
pub fn planning_error(scenario: &Scenario, settings: &PlanSettings, fault: Fault) -> InputError {
    let in_input = |x: f64, y: f64| input_place(scenario, (x, y));
    match fault {
        Fault::UnreachableOnOneBattery { x, y, .. }
            if settings.start.is_some_and(|[sx, sy]| {
                crate::supply::standing::StandingRule::new(&scenario.farm)
                    .distance_to_fields_m(geo::Coord { x: sx, y: sy })
                    > crate::supply::standing::REACH_M
            }) =>
        {
            let [sx, sy] = settings.start.unwrap_or_default();
            let away = crate::supply::standing::StandingRule::new(&scenario.farm)
                .distance_to_fields_m(geo::Coord { x: sx, y: sy });
            bad_value(
                "--supply/--start",
                in_input(sx, sy),
                format!(
                    "it lies {:.1} km from the nearest field, too far for one battery and one tank to reach the route near {} and fly back (--supply auto chooses within {:.0} m)",
                    away / 1000.0,
                    in_input(x, y),
                    crate::supply::standing::REACH_M
                ),
            )
        }
        Fault::UnreachableOnOneBattery {
            x,
            y,
            endurance_s,
            tank,
        } => {
            let near = in_input(x, y);
            let file = scenario
                .vehicle_file
                .as_deref()
                .unwrap_or(scenario.farm.source.as_path());
            // A tank that cannot spray one step of the route is what is short, whatever the
            // battery (the red team's 0.1 L tank was blamed on the battery share).
            if let Some((per_tank_m, step_m)) = tank {
                let (what, value) =
                    match (scenario.vehicle.tank_l, scenario.vehicle.tank_spray_time_s) {
                        (Some(litres), _) => ("tank_l", litres),
                        (None, Some(seconds)) => ("tank_spray_time_s", seconds),
                        (None, None) => ("tank_l", 0.0),
                    };
                return InputError::new(
                    file,
                    Fault::InvalidValue {
                        what: what.into(),
                        value: crate::error::figure(value),
                        why: format!(
                            "one tank sprays {per_tank_m:.1} m of swath, less than the {step_m:.1} m the route near {near} sprays between two of its points"
                        ),
                    },
                );
            }
            let share = scenario.vehicle.battery_reserve_percent;
            // Neither figure is wrong on its own (a 20 % reserve is what operators keep): say
            // what the two leave, and that this farm needs more.
            let battery = if share > 0.0 {
                format!(
                    "battery_endurance_s = {} less battery_reserve_percent = {} leaves {:.0} s",
                    crate::error::figure(endurance_s),
                    crate::error::figure(share),
                    scenario.vehicle.usable_battery_s()
                )
            } else {
                format!(
                    "battery_endurance_s = {}",
                    crate::error::figure(endurance_s)
                )
            };
            // Under two minutes no supply point helps: the figure is the fault (a tenth
            // trial's battery typed in minutes was told to give a nearer --supply).
            let advice = if endurance_s < crate::model::vehicle::SHORT_BATTERY_S {
                "battery_endurance_s is in seconds (a multirotor flies 8-30 minutes, 480-1800 s): minutes typed?"
            } else {
                "the farm is too spread out for one supply point for this vehicle (plan the far fields as a farm of their own, or give a nearer --supply)"
            };
            InputError::new(
                file,
                Fault::Structure(format!(
                    "{battery}, too little for this farm: the route near {near} cannot be reached and flown back on one battery and one tank; {advice}"
                )),
            )
        }
        Fault::Terrain(
            TerrainError::Outside { x, y } | TerrainError::NoData { x, y },
        ) if settings
            .start
            .is_some_and(|[sx, sy]| (sx - x).hypot(sy - y) < 1e-6) =>
        {
            bad_value(
                "--supply/--start",
                in_input(x, y),
                format!(
                    "the terrain has no height there ({}): the supply point must stand on the terrain model",
                    terrain_extent(scenario)
                ),
            )
        }
        other => rendering_error(scenario, &scenario.farm.source, settings.start, other),
    }
}

/// The terrain model's extent in the input's coordinates, for a message.
fn terrain_extent(scenario: &Scenario) -> String {
    match scenario.terrain.extent() {
        Some(extent) => format!(
            "the terrain model covers {} to {}",
            input_place(scenario, (extent.min_x, extent.min_y)),
            input_place(scenario, (extent.max_x, extent.max_y))
        ),
        None => "the terrain model has no extent".into(),
    }
}

/// A fault of writing the mission files as planned, blamed on `source` (or on `--supply`
/// where the supply point `given` on the command line is at fault), with places in the
/// input's coordinates.
pub fn rendering_error(
    scenario: &Scenario,
    source: &std::path::Path,
    given: Option<[f64; 2]>,
    fault: Fault,
) -> InputError {
    let in_input = |place: (f64, f64)| input_place(scenario, place);
    let is_given = |(x, y): (f64, f64)| given.is_some_and(|[gx, gy]| (gx - x).hypot(gy - y) < 1e-6);
    match fault {
        // No transit leaves the supply point given on the command line: blame the flag, not
        // the field file.
        Fault::NoTransit { from, to } if is_given(from) || is_given(to) => {
            let (at, other) = if is_given(from) { (from, to) } else { (to, from) };
            InputError::new(
                "--supply/--start",
                Fault::Structure(format!(
                    "no transit between {} and {} keeps out of the obstacles: the supply point lies inside an obstacle, or is walled in by them",
                    in_input(at),
                    in_input(other)
                )),
            )
        }
        Fault::NoTransit { from, to } => InputError::new(
            source,
            Fault::Structure(format!(
                "no transit from {} to {} keeps out of the obstacles (is the supply point or a launch marker inside one?)",
                in_input(from),
                in_input(to)
            )),
        ),
        // A place the flight crosses off the fields: the DEM is what falls short, so it is
        // the file named (a gap between two fields named the field file, with no reason).
        Fault::Terrain(error @ (TerrainError::Outside { x, y } | TerrainError::NoData { x, y })) => {
            let (file, spec_is_file) = match &scenario.terrain_spec {
                TerrainSpec::File { path, .. } => (path.as_path(), true),
                _ => (source, false),
            };
            let what = match error {
                TerrainError::NoData { .. } => "the terrain model has no data",
                TerrainError::Outside { .. } => "the terrain model does not reach",
            };
            let hint = if spec_is_file {
                "; the DEM must cover the fields and the ground flown over between them and the supply point"
            } else {
                ""
            };
            InputError::new(
                file,
                Fault::Structure(format!(
                    "{what} at {}, which the flight crosses (a transfer, a return to the supply point or a transit between fields); {}{hint}",
                    in_input((x, y)),
                    terrain_extent(scenario)
                )),
            )
        }
        other => InputError::new(source, other),
    }
}

/// A place of the planning frame as the input gave places: lon/lat, or local metres.
fn input_place(scenario: &Scenario, (x, y): (f64, f64)) -> String {
    let frame = scenario.farm.coordinate_system;
    let (a, b) = frame.to_input(x, y);
    match frame {
        crate::model::CoordinateSystem::Local => format!("({a:.1}, {b:.1})"),
        crate::model::CoordinateSystem::Utm(_) => format!("lon {a:.6}, lat {b:.6}"),
    }
}
