//! The summary's notes and warnings: a plan that is right but likely not what the operator
//! meant, or checked against less than the ground it will fly over, with what to change.

use super::SortieReport;
use crate::model::vehicle::COMMON_MISSION_ITEMS;
use crate::model::Vehicle;
use crate::preflight::verdict::SortieFlown;
use crate::scenario::Scenario;

/// A note where many sorties end for the battery with their tank under half used: their
/// battery goes on the legs to fields far from the supply point (a fifth trial's farm, one
/// field 1.2 km from the rest: 38 of 103 sorties sprayed under half a tank each, and planned
/// as two farms it took 4.6 h less). `None` for a survey (no tank), or where few sorties do so:
/// at least three, and a fifth of them.
pub(super) fn far_fields_note(sorties: &[SortieReport], usable_percent: f64) -> Option<String> {
    // The last sortie sprays what is left: it says nothing about the legs.
    let ended_by_battery = sorties
        .iter()
        .take(sorties.len().saturating_sub(1))
        .filter(|sortie| {
            sortie.tank_percent.is_some_and(|tank| tank < 50.0)
                && sortie.battery_percent >= usable_percent - 10.0
        })
        .count();
    let count = sorties.len();
    (ended_by_battery >= 3 && 5 * ended_by_battery >= count).then(|| {
        format!(
            "note: {ended_by_battery} of {count} sorties end for the battery with their tank less than half used: most of their flight goes on the legs to fields far from the supply point; a supply point nearer those fields, or planning them as a farm of their own, flies fewer sorties\n"
        )
    })
}

/// A warning where a sortie's mission (home included) holds more items than
/// [`COMMON_MISSION_ITEMS`] and the vehicle states no limit of its own (`limit`): many
/// autopilots cannot store it (a tenth trial's survey drone wrote 705-922 items a sortie and
/// nothing said so). With a limit the preflight holds every sortie to it instead.
pub(super) fn mission_size_warning(sorties: &[SortieFlown], limit: Option<u32>) -> Option<String> {
    if limit.is_some() {
        return None;
    }
    let largest = sorties.iter().max_by_key(|sortie| sortie.items)?;
    let items = largest.items + 1;
    (items > COMMON_MISSION_ITEMS).then(|| {
        let over = sorties
            .iter()
            .filter(|sortie| sortie.items + 1 > COMMON_MISSION_ITEMS)
            .count();
        format!(
            "warning: {over} of {} sorties have more than {COMMON_MISSION_ITEMS} mission items, home included (sortie {}: {items}): ArduPilot on a board that keeps the mission in FRAM holds about {COMMON_MISSION_ITEMS}; give the vehicle's mission_items_max to have every sortie checked against your autopilot, or a larger --terrain-tolerance for fewer waypoints\n",
            sorties.len(),
            largest.sortie
        )
    })
}

/// Least ground one tank of a sprayer covers before the summary asks whether the tank's
/// figures are right, m² (0.1 ha: a 10 L tank at 100 L/ha; the smallest spraying drones
/// carry 8-10 L and spray 10-20 L/ha).
const SMALL_TANK_M2: f64 = 1_000.0;

/// A note where one tank sprays less than [`SMALL_TANK_M2`] and the plan flies several
/// sorties for it: most likely a figure typed wrong (a fifth trial's 0.5 L tank sprayed 51 m
/// of swath per sortie). The plan stands; the note names the keys to check.
pub(super) fn small_tank_note(vehicle: &Vehicle, sorties: usize) -> Option<String> {
    let metres = vehicle.spray_length_per_tank_m()?;
    let area_m2 = metres * vehicle.swath_width_m;
    if sorties < 2 || area_m2 >= SMALL_TANK_M2 {
        return None;
    }
    // The figure that limits the tank is the one to check.
    let by_time_m = vehicle
        .tank_spray_time_s
        .map(|time| time * vehicle.spray_speed_mps);
    let keys = if by_time_m.is_some_and(|by_time| by_time <= metres) {
        "tank_spray_time_s"
    } else {
        "tank_l and application_rate_l_per_ha"
    };
    Some(format!(
        "note: one tank sprays {metres:.0} m of swath ({:.2} ha, {:.0} s of spraying), so the plan flies {sorties} sorties: are the vehicle's {keys} right?\n",
        area_m2 / 10_000.0,
        metres / vehicle.spray_speed_mps
    ))
}

/// The warning for a farm on the globe planned over flat ground: the preflight flew the
/// missions over that flat ground, not over the hills the fields may lie on.
pub(super) fn terrain_warning(scenario: &Scenario) -> Option<String> {
    let on_the_globe = scenario.farm.coordinate_system != crate::model::CoordinateSystem::Local;
    match scenario.terrain_spec {
        crate::terrain::TerrainSpec::Flat { height_m } if on_the_globe => {
            // A flat ground the operator typed is a choice, not an omission: say which.
            let ground = if scenario.terrain_stated {
                format!("flat ground at {height_m} m, as given")
            } else {
                format!("no terrain model: flat ground at {height_m} m assumed")
            };
            Some(format!(
                "{ground}: the missions were planned and checked over it; over real slopes they may fly into the ground or too high to spray (give --terrain DEM)"
            ))
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sortie(tank_percent: Option<f64>, battery_percent: f64) -> SortieReport {
        SortieReport {
            sortie: 1,
            file: "sortie_01.plan".into(),
            spray_m: 0.0,
            litres: None,
            tank_percent,
            photos_estimate: None,
            flight_time_s: 0.0,
            battery_percent,
            return_point: None,
        }
    }

    #[test]
    fn missions_above_what_common_autopilots_hold_are_warned_of_without_a_limit() {
        let sortie = |sortie: usize, items: usize| SortieFlown {
            sortie,
            file: format!("sortie_{sortie:02}.plan"),
            items,
            spray_m: 0.0,
            tank_fraction: None,
            flight_time_s: 0.0,
            battery_fraction: 0.0,
            worst_spray_height_error_m: 0.0,
            least_transit_margin_m: None,
            pump_stopped_m: 0.0,
        };
        let sorties = [sortie(1, 400), sortie(2, 921), sortie(3, 705)];
        let warning = mission_size_warning(&sorties, None).expect("two above 700");
        assert!(
            warning.starts_with("warning: 2 of 3 sorties have more than 700 mission items, home included (sortie 2: 922)"),
            "{warning}"
        );
        // A limit of the vehicle's own: the preflight checks it instead.
        assert!(mission_size_warning(&sorties, Some(1000)).is_none());
        assert!(mission_size_warning(&sorties[..1], None).is_none());
    }

    #[test]
    fn small_tank_note_asks_about_a_tank_under_a_tenth_of_a_hectare() {
        let mut vehicle = Vehicle {
            tank_l: Some(0.5),
            application_rate_l_per_ha: Some(15.0),
            swath_width_m: 6.5,
            ..Vehicle::default()
        };
        let note = small_tank_note(&vehicle, 40).expect("333 m² is a small tank");
        assert!(note.contains("51 m of swath"), "{note}");
        assert!(
            note.contains("tank_l and application_rate_l_per_ha"),
            "{note}"
        );
        assert!(
            small_tank_note(&vehicle, 1).is_none(),
            "one sortie: nothing to ask"
        );
        vehicle.tank_l = Some(16.0);
        assert!(small_tank_note(&vehicle, 40).is_none(), "1.07 ha is a tank");
        vehicle.tank_spray_time_s = Some(10.0);
        let note = small_tank_note(&vehicle, 40).expect("10 s of spraying is a small tank");
        assert!(note.contains("tank_spray_time_s right?"), "{note}");
    }

    #[test]
    fn far_fields_note_needs_several_sorties_ended_by_the_battery_with_tank_to_spare() {
        let far = || sortie(Some(30.0), 76.0);
        let full = || sortie(Some(100.0), 60.0);
        // Three of ten end for the battery with 30 % of a tank: the note, counting them.
        let mut sorties: Vec<_> = (0..3).map(|_| far()).collect();
        sorties.extend((0..7).map(|_| full()));
        let note = far_fields_note(&sorties, 80.0).expect("three of ten is a note");
        assert!(note.starts_with("note: 3 of 10 sorties"), "{note}");
        // Two are not enough, nor three of twenty.
        assert!(far_fields_note(&sorties[1..], 80.0).is_none());
        let many: Vec<_> = (0..3)
            .map(|_| far())
            .chain((0..17).map(|_| full()))
            .collect();
        assert!(far_fields_note(&many, 80.0).is_none());
        // The battery well under its limit: those sorties did not end for it.
        let short: Vec<_> = (0..5).map(|_| sortie(Some(30.0), 50.0)).collect();
        assert!(far_fields_note(&short, 80.0).is_none());
        // The last sortie sprays what is left and is not counted; a survey has no tank.
        let mut ending = vec![far(), far(), full(), full(), far()];
        assert!(far_fields_note(&ending, 80.0).is_none());
        ending.push(full());
        assert!(far_fields_note(&ending, 80.0).is_some());
        let survey: Vec<_> = (0..5).map(|_| sortie(None, 79.0)).collect();
        assert!(far_fields_note(&survey, 80.0).is_none());
    }
}
