//! Mission Planner's `QGC WPL 110` text, one file per sortie: a header line, then one item
//! per line in 12 tab-separated columns (index, current, frame, command, p1-p4, lat, lon, alt,
//! autocontinue). Row 0 is home (the supply point, AMSL), as ArduPilot expects; position
//! items are in the frame of the altitude reference (3 relative, 0 sea level, 10 terrain).

use std::fmt::Write;

use super::flight::{MissionSettings, SortieMission};
use super::mavlink::{Command, CMD_NAV_WAYPOINT, FRAME_GLOBAL};

fn number(value: Option<f64>, decimals: usize) -> String {
    match value {
        Some(value) => format!("{value:.decimals$}"),
        None => "nan".into(),
    }
}

/// The `.waypoints` text of one sortie.
pub fn waypoints_file(mission: &SortieMission, settings: &MissionSettings) -> String {
    let mut text = String::from("QGC WPL 110\n");
    let home = &mission.home;
    let _ = writeln!(
        text,
        "0\t1\t{FRAME_GLOBAL}\t{CMD_NAV_WAYPOINT}\t0\t0\t0\t0\t{:.9}\t{:.9}\t{:.3}\t1",
        home.lat,
        home.lon,
        home.sea_level_m()
    );
    for (index, item) in mission.items.iter().enumerate() {
        let command = Command::of(item, settings.altitude, home.ground_m, settings.sprayer);
        let p = command.params;
        let _ = writeln!(
            text,
            "{}\t0\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t1",
            index + 1,
            command.frame,
            command.command,
            number(p[0], 3),
            number(p[1], 3),
            number(p[2], 3),
            number(p[3], 3),
            number(p[4], 9),
            number(p[5], 9),
            number(p[6], 3),
        );
    }
    text
}
