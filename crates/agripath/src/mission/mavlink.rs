//! The MAVLink numbers the mission files use (checked against pymavlink's `ardupilotmega`
//! dialect; `../shared/reference/ecosystem.md` §8.3), and how each [`Action`] becomes a
//! command with its seven parameters.

use super::flight::{Action, AltitudeReference, Item, SprayerCommand};

/// `MAV_FRAME_GLOBAL`: altitude above mean sea level.
pub const FRAME_GLOBAL: u8 = 0;
/// `MAV_FRAME_GLOBAL_RELATIVE_ALT`: altitude above the home position.
pub const FRAME_GLOBAL_RELATIVE_ALT: u8 = 3;
/// `MAV_FRAME_GLOBAL_TERRAIN_ALT`: altitude above the terrain under the vehicle.
pub const FRAME_GLOBAL_TERRAIN_ALT: u8 = 10;
/// `MAV_CMD_NAV_WAYPOINT`: fly to a position.
pub const CMD_NAV_WAYPOINT: u16 = 16;
/// `MAV_CMD_NAV_LAND`: land at a position.
pub const CMD_NAV_LAND: u16 = 21;
/// `MAV_CMD_NAV_TAKEOFF`: take off to an altitude.
pub const CMD_NAV_TAKEOFF: u16 = 22;
/// `MAV_CMD_DO_CHANGE_SPEED`: set the speed.
pub const CMD_DO_CHANGE_SPEED: u16 = 178;
/// `MAV_CMD_DO_SET_SERVO`: set a servo output's PWM.
pub const CMD_DO_SET_SERVO: u16 = 183;
/// `MAV_CMD_DO_SPRAYER`: turn the sprayer on or off.
pub const CMD_DO_SPRAYER: u16 = 216;
/// `MAV_CMD_DO_SET_CAM_TRIGG_DIST`: trigger the camera every p1 metres (0: stop); p3 = 1
/// takes one photo at once.
pub const CMD_DO_SET_CAM_TRIGG_DIST: u16 = 206;

/// A command as mission files store it: number, frame, p1…p7 (`None` = NaN/null).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Command {
    /// The MAVLink command number (`CMD_*`).
    pub command: u16,
    /// The MAVLink frame (`FRAME_*`).
    pub frame: u8,
    /// p1…p7; `None` is written as NaN or null.
    pub params: [Option<f64>; 7],
}

impl Command {
    /// The MAVLink frame of position items in `reference`.
    pub fn frame_of(reference: AltitudeReference) -> u8 {
        match reference {
            AltitudeReference::Relative => FRAME_GLOBAL_RELATIVE_ALT,
            AltitudeReference::SeaLevel => FRAME_GLOBAL,
            AltitudeReference::Terrain => FRAME_GLOBAL_TERRAIN_ALT,
        }
    }

    /// The command of `item`, its altitude in `reference` with the launch ground at
    /// `home_ground_m`.
    pub fn of(
        item: &Item,
        reference: AltitudeReference,
        home_ground_m: f64,
        sprayer: SprayerCommand,
    ) -> Self {
        let frame = Self::frame_of(reference);
        let place = |command: u16, first: [Option<f64>; 4]| Command {
            command,
            frame,
            params: [
                first[0],
                first[1],
                first[2],
                first[3],
                Some(item.lat),
                Some(item.lon),
                Some(item.altitude_m(reference, home_ground_m)),
            ],
        };
        let act = |command: u16, first: [f64; 3]| Command {
            command,
            frame: FRAME_GLOBAL,
            params: [
                Some(first[0]),
                Some(first[1]),
                Some(first[2]),
                Some(0.0),
                Some(0.0),
                Some(0.0),
                Some(0.0),
            ],
        };
        match item.action {
            // Hold 0 s, acceptance radius 1 m, pass through, default yaw.
            Action::Waypoint => place(CMD_NAV_WAYPOINT, [Some(0.0), Some(1.0), Some(0.0), None]),
            Action::Takeoff => place(CMD_NAV_TAKEOFF, [Some(0.0), Some(0.0), Some(0.0), None]),
            Action::Land => place(CMD_NAV_LAND, [Some(0.0), Some(0.0), Some(0.0), None]),
            // Ground speed (1), m/s, throttle unchanged (−1).
            Action::Speed { mps } => act(CMD_DO_CHANGE_SPEED, [1.0, mps, -1.0]),
            // Distance, shutter time unchanged (0), one photo at once when starting.
            Action::CameraTrigger { distance_m } => act(
                CMD_DO_SET_CAM_TRIGG_DIST,
                [distance_m, 0.0, if distance_m > 0.0 { 1.0 } else { 0.0 }],
            ),
            Action::Spray { on } => match sprayer {
                SprayerCommand::DoSprayer => {
                    act(CMD_DO_SPRAYER, [if on { 1.0 } else { 0.0 }, 0.0, 0.0])
                }
                SprayerCommand::Servo {
                    channel,
                    on_pwm,
                    off_pwm,
                } => act(
                    CMD_DO_SET_SERVO,
                    [
                        f64::from(channel),
                        f64::from(if on { on_pwm } else { off_pwm }),
                        0.0,
                    ],
                ),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_camera_trigger_is_do_set_cam_trigg_dist_with_its_distance_then_zero() {
        let item = |action| Item {
            action,
            lon: 105.6,
            lat: -10.5,
            ground_m: 150.0,
            above_ground_m: 60.0,
        };
        let on = Command::of(
            &item(Action::work(true, Some(12.0))),
            AltitudeReference::SeaLevel,
            150.0,
            SprayerCommand::DoSprayer,
        );
        assert_eq!(on.command, CMD_DO_SET_CAM_TRIGG_DIST);
        assert_eq!(on.params[..3], [Some(12.0), Some(0.0), Some(1.0)]);
        let off = Command::of(
            &item(Action::work(false, Some(12.0))),
            AltitudeReference::SeaLevel,
            150.0,
            SprayerCommand::DoSprayer,
        );
        assert_eq!(
            (off.command, off.params[0], off.params[2]),
            (206, Some(0.0), Some(0.0))
        );
        // A sprayer keeps its sprayer command.
        let spray = Command::of(
            &item(Action::work(true, None)),
            AltitudeReference::SeaLevel,
            150.0,
            SprayerCommand::DoSprayer,
        );
        assert_eq!(
            (spray.command, spray.params[0]),
            (CMD_DO_SPRAYER, Some(1.0))
        );
    }
}
