//! What the mission files are asked for: how altitudes are written, how the sprayer is
//! switched, how closely the flight follows the terrain, and where a local plan lies.

use serde::{Deserialize, Serialize};

use crate::error::Fault;

/// How altitudes are written (decision 0012).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AltitudeReference {
    /// Above the launch point's ground (MAV_FRAME_GLOBAL_RELATIVE_ALT, QGC "relative"): the
    /// ground station's default, and the only honest one without a terrain model.
    Relative,
    /// Above sea level from our terrain model (MAV_FRAME_GLOBAL, QGC "absolute"): needs a DEM
    /// or a stated ground height (`--terrain flat:H`).
    SeaLevel,
    /// Above the terrain, as the autopilot measures it (MAV_FRAME_GLOBAL_TERRAIN_ALT, ArduPilot).
    Terrain,
}

/// Whether the terrain gives heights above sea level: a DEM, or a flat ground whose height
/// was stated (`--terrain flat:H`, a scenario's `[terrain]`), not assumed at 0 m.
pub fn sea_level_known(terrain: &crate::terrain::TerrainSpec, stated: bool) -> bool {
    matches!(terrain, crate::terrain::TerrainSpec::File { .. })
        || (stated && matches!(terrain, crate::terrain::TerrainSpec::Flat { .. }))
}

impl AltitudeReference {
    /// Every reference's key, in the order of the variants: the names `--altitude` accepts.
    pub const KEYS: [&'static str; 3] = ["relative", "sea-level", "terrain"];

    /// The reference's key (`relative`, `sea-level` or `terrain`), as `--altitude` takes it.
    pub fn key(self) -> &'static str {
        match self {
            Self::Relative => "relative",
            Self::SeaLevel => "sea-level",
            Self::Terrain => "terrain",
        }
    }

    /// The reference a plan uses: the one asked for, else `sea-level` over a DEM and
    /// `relative` without one. `sea-level` needs heights above sea level: a DEM or a stated
    /// flat ground.
    pub fn resolve(
        requested: Option<Self>,
        terrain: &crate::terrain::TerrainSpec,
        stated: bool,
    ) -> Result<Self, Fault> {
        let dem = matches!(terrain, crate::terrain::TerrainSpec::File { .. });
        let sea_level_known = sea_level_known(terrain, stated);
        match requested {
            None if dem => Ok(Self::SeaLevel),
            None => Ok(Self::Relative),
            Some(Self::SeaLevel) if !sea_level_known => Err(Fault::InvalidValue {
                what: "--altitude".into(),
                value: "sea-level".into(),
                why: "sea-level altitudes need a terrain model (--terrain DEM) or a stated ground height (--terrain flat:H); without them use relative".into(),
            }),
            Some(reference) => Ok(reference),
        }
    }

    /// What the altitudes of this reference assume, for the report and the summary.
    pub fn assumption(self, terrain: &crate::terrain::TerrainSpec) -> String {
        let ground = match terrain {
            crate::terrain::TerrainSpec::File { path, .. } => format!("the DEM {}", path.display()),
            crate::terrain::TerrainSpec::Flat { height_m } => {
                format!("flat ground at {height_m} m")
            }
            _ => "the analytic terrain model (heights relative to its own datum)".into(),
        };
        match self {
            Self::Relative => format!("altitudes relative to the launch point's ground; terrain under the flight from {ground}"),
            Self::SeaLevel => format!("altitudes above sea level from {ground}"),
            Self::Terrain => format!("altitudes above the terrain as the autopilot measures it; planned over {ground}"),
        }
    }
}

impl std::str::FromStr for AltitudeReference {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        match text {
            "relative" => Ok(Self::Relative),
            "sea-level" => Ok(Self::SeaLevel),
            "terrain" => Ok(Self::Terrain),
            other => Err(format!(
                "unknown altitude reference '{other}' (known: relative, sea-level, terrain)"
            )),
        }
    }
}

/// How the sprayer is switched.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SprayerCommand {
    /// MAV_CMD_DO_SPRAYER (216), ArduPilot's sprayer.
    DoSprayer,
    /// MAV_CMD_DO_SET_SERVO (183) on `channel` with these pulse widths, for any pump on a servo output.
    Servo {
        /// The servo output, one of [`SERVO_CHANNELS`].
        channel: u16,
        /// Pulse width that turns the pump on, microseconds, within [`SERVO_PWM_US`].
        on_pwm: u16,
        /// Pulse width that turns the pump off, microseconds, within [`SERVO_PWM_US`].
        off_pwm: u16,
    },
}

/// Servo outputs a `DO_SET_SERVO` may name (ArduPilot has 1-32; PX4 and most boards fewer).
pub const SERVO_CHANNELS: std::ops::RangeInclusive<u16> = 1..=32;
/// Pulse widths a servo output accepts, microseconds.
pub const SERVO_PWM_US: std::ops::RangeInclusive<u16> = 800..=2200;

impl std::str::FromStr for SprayerCommand {
    type Err = String;

    /// `do-sprayer`, or `servo:CHANNEL:ON_PWM:OFF_PWM` with a real channel and pulse widths
    /// (on and off must differ, or the pump would never switch).
    fn from_str(spec: &str) -> Result<Self, String> {
        if spec == "do-sprayer" {
            return Ok(Self::DoSprayer);
        }
        let expected = "expected do-sprayer or servo:CHANNEL:ON_PWM:OFF_PWM".to_string();
        let parts: Vec<&str> = spec.split(':').collect();
        let ["servo", channel, on, off] = parts.as_slice() else {
            return Err(expected);
        };
        let (Ok(channel), Ok(on_pwm), Ok(off_pwm)) = (
            channel.parse::<u16>(),
            on.parse::<u16>(),
            off.parse::<u16>(),
        ) else {
            return Err(expected);
        };
        if !SERVO_CHANNELS.contains(&channel) {
            return Err(format!(
                "servo channel {channel} is not one of {}..={}",
                SERVO_CHANNELS.start(),
                SERVO_CHANNELS.end()
            ));
        }
        for pwm in [on_pwm, off_pwm] {
            if !SERVO_PWM_US.contains(&pwm) {
                return Err(format!(
                    "pulse width {pwm} µs is outside {}..={} µs",
                    SERVO_PWM_US.start(),
                    SERVO_PWM_US.end()
                ));
            }
        }
        if on_pwm == off_pwm {
            return Err(
                "the on and off pulse widths are the same: the pump would never switch".into(),
            );
        }
        Ok(Self::Servo {
            channel,
            on_pwm,
            off_pwm,
        })
    }
}

/// What the mission files are asked for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MissionSettings {
    /// How altitudes are written.
    pub altitude: AltitudeReference,
    /// How the sprayer is switched.
    pub sprayer: SprayerCommand,
    /// Largest gap between the flown altitude and terrain + spray height along a swath, metres.
    pub terrain_tolerance_m: f64,
    /// Terrain samples along swaths, metres.
    pub sample_spacing_m: f64,
    /// Where a plan in local metres lies on Earth (lon, lat of its origin), for mission files.
    pub local_origin: (f64, f64),
    /// How far the geofence's inclusion polygon reaches beyond the flight, metres.
    pub fence_margin_m: f64,
}

/// Where local metres are placed on Earth unless told otherwise (lon, lat): Harbin,
/// Heilongjiang, the Northeast Agricultural University fields of seed 003.
pub const DEFAULT_LOCAL_ORIGIN: (f64, f64) = (126.63, 45.75);

impl Default for MissionSettings {
    fn default() -> Self {
        Self {
            altitude: AltitudeReference::Relative,
            sprayer: SprayerCommand::DoSprayer,
            terrain_tolerance_m: 1.0,
            sample_spacing_m: 1.0,
            local_origin: DEFAULT_LOCAL_ORIGIN,
            fence_margin_m: 10.0,
        }
    }
}
