//! Every mission item of every sortie as CSV, for spreadsheets and other tools:
//! `sortie,index,action,value,lon,lat,ground_m,above_ground_m,sea_level_m`. Sorties are
//! numbered from 1, as the `sortie_NN` files, the KML and the sheet number them; `index` is
//! the mission item's number, from 1 after home (the `.waypoints` row, QGroundControl's item
//! number, and the `item K` of the preflight's lines, so a failure is found by it). Without
//! heights above sea level (no DEM, no stated ground height) `sea_level_m` is left empty:
//! `ground_m` is then the terrain model's (flat 0 m, the field file's or a formula's), and
//! a sea-level column over it would read as true altitudes (decision 0012: never sea level
//! over an assumed ground).

use std::fmt::Write;

use super::flight::{Action, SortieMission};

/// The CSV text, a header line then one line per mission item of each sortie in order;
/// `sea_level_known`: whether the terrain's heights are above sea level.
pub fn waypoints_csv(missions: &[SortieMission], sea_level_known: bool) -> String {
    let mut text =
        String::from("sortie,index,action,value,lon,lat,ground_m,above_ground_m,sea_level_m\n");
    for mission in missions {
        for (index, item) in mission.items.iter().enumerate() {
            let (action, value) = match item.action {
                Action::Takeoff => ("takeoff", String::new()),
                Action::Waypoint => ("waypoint", String::new()),
                Action::Land => ("land", String::new()),
                Action::Speed { mps } => ("speed", format!("{mps}")),
                Action::Spray { on } => ("spray", if on { "on".into() } else { "off".into() }),
                Action::CameraTrigger { distance_m } => ("camera", format!("{distance_m}")),
            };
            let sea_level = if sea_level_known {
                format!("{:.3}", item.sea_level_m())
            } else {
                String::new()
            };
            let _ = writeln!(
                text,
                "{},{},{},{},{:.9},{:.9},{:.3},{:.3},{sea_level}",
                mission.sortie + 1,
                index + 1,
                action,
                value,
                item.lon,
                item.lat,
                item.ground_m,
                item.above_ground_m,
            );
        }
    }
    text
}
