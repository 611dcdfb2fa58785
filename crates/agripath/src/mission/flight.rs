//! The flight as autopilot commands, one mission per sortie: what every mission exporter
//! writes (QGroundControl `.plan`, `QGC WPL 110`, KML, CSV).
//!
//! A sortie takes off at the supply point to the cruise height (spray height + h), flies to
//! above its first route point, descends to spray height, then follows the route: the
//! sprayer goes on at each swath start and off at its end (`DO_SPRAYER`, or `DO_SET_SERVO`),
//! the speed changes between spraying and transit (`DO_CHANGE_SPEED`), transfers that leave a
//! field climb to the cruise height and back. At its last point the sprayer goes off and the
//! drone climbs, flies back and lands at the supply point.
//!
//! Terrain following: along a swath the terrain is sampled every `sample_spacing_m` and the
//! waypoints kept are those a vertical Douglas-Peucker keeps at `terrain_tolerance_m`: between
//! two waypoints the straight climb or descent stays within the tolerance of terrain + spray
//! height (what QGroundControl's terrain following precomputes), and flat stretches need
//! only their ends.

use serde::{Deserialize, Serialize};

use crate::error::Fault;
use crate::geometry::{from_utm, to_utm, UtmZone};
use crate::model::CoordinateSystem;
use crate::scenario::Scenario;
use crate::sequence::Route;
use crate::sortie::route::{RoutePoint, Segment};
use crate::sortie::PlannedSorties;
use crate::terrain::Terrain;

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

impl AltitudeReference {
    pub const KEYS: [&'static str; 3] = ["relative", "sea-level", "terrain"];

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
        let sea_level_known =
            dem || (stated && matches!(terrain, crate::terrain::TerrainSpec::Flat { .. }));
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
        channel: u16,
        on_pwm: u16,
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
    pub altitude: AltitudeReference,
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

impl Default for MissionSettings {
    fn default() -> Self {
        Self {
            altitude: AltitudeReference::Relative,
            sprayer: SprayerCommand::DoSprayer,
            terrain_tolerance_m: 1.0,
            sample_spacing_m: 1.0,
            // Harbin, Heilongjiang: the Northeast Agricultural University fields of seed 003.
            local_origin: (126.63, 45.75),
            fence_margin_m: 10.0,
        }
    }
}

/// One autopilot command.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "action", rename_all = "snake_case")]
pub enum Action {
    Takeoff,
    Waypoint,
    Land,
    /// Ground speed, m/s.
    Speed {
        mps: f64,
    },
    Spray {
        on: bool,
    },
}

/// A command with its place: longitude, latitude, terrain height and height above it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Item {
    #[serde(flatten)]
    pub action: Action,
    pub lon: f64,
    pub lat: f64,
    pub ground_m: f64,
    pub above_ground_m: f64,
}

impl Item {
    pub fn sea_level_m(&self) -> f64 {
        self.ground_m + self.above_ground_m
    }

    /// The altitude written for this item in `reference`, with the launch point's ground at
    /// `home_ground_m`.
    pub fn altitude_m(&self, reference: AltitudeReference, home_ground_m: f64) -> f64 {
        match reference {
            AltitudeReference::Relative => self.sea_level_m() - home_ground_m,
            AltitudeReference::SeaLevel => self.sea_level_m(),
            AltitudeReference::Terrain => self.above_ground_m,
        }
    }

    /// Whether the command flies somewhere (the others act where the drone is).
    pub fn moves(&self) -> bool {
        matches!(
            self.action,
            Action::Takeoff | Action::Waypoint | Action::Land
        )
    }
}

/// The mission of one sortie.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SortieMission {
    pub sortie: usize,
    /// The supply point: home, takeoff and landing.
    pub home: Item,
    pub items: Vec<Item>,
}

/// Plan metres → longitude, latitude.
#[derive(Debug, Clone, Copy)]
pub struct GeoFrame {
    system: CoordinateSystem,
    /// For local plans: the zone and UTM position of the origin.
    local: Option<(UtmZone, f64, f64)>,
}

impl GeoFrame {
    pub fn new(system: CoordinateSystem, local_origin: (f64, f64)) -> Self {
        let local = (system == CoordinateSystem::Local).then(|| {
            let zone = UtmZone::containing(local_origin.0, local_origin.1);
            let (easting, northing) = to_utm(local_origin.0, local_origin.1, zone);
            (zone, easting, northing)
        });
        Self { system, local }
    }

    pub fn lon_lat(&self, x: f64, y: f64) -> (f64, f64) {
        match self.local {
            Some((zone, easting, northing)) => from_utm(easting + x, northing + y, zone),
            None => self.system.to_input(x, y),
        }
    }

    /// Longitude, latitude → plan metres: the inverse of [`GeoFrame::lon_lat`], for reading
    /// mission files back.
    pub fn plan_xy(&self, lon: f64, lat: f64) -> (f64, f64) {
        match self.local {
            Some((zone, easting, northing)) => {
                let (x, y) = to_utm(lon, lat, zone);
                (x - easting, y - northing)
            }
            None => self.system.to_plan(lon, lat),
        }
    }

    /// A place as the user's input gives it: lon/lat for lon/lat input, metres for local.
    pub fn describe(&self, x: f64, y: f64) -> String {
        match self.system {
            CoordinateSystem::Local => format!("({x:.1}, {y:.1})"),
            CoordinateSystem::Utm(_) => {
                let (lon, lat) = self.lon_lat(x, y);
                format!("({lon:.6}, {lat:.6})")
            }
        }
    }
}

/// Keeps the samples a vertical Douglas-Peucker keeps: (distance along, height) pairs.
fn simplify(profile: &[(f64, f64)], tolerance: f64, keep: &mut [bool], first: usize, last: usize) {
    if last <= first + 1 {
        return;
    }
    let (x0, z0) = profile[first];
    let (x1, z1) = profile[last];
    let mut worst = (0.0, first);
    for (index, &(x, z)) in profile.iter().enumerate().take(last).skip(first + 1) {
        let along = if x1 > x0 { (x - x0) / (x1 - x0) } else { 0.0 };
        let gap = (z - (z0 + along * (z1 - z0))).abs();
        if gap > worst.0 {
            worst = (gap, index);
        }
    }
    if worst.0 > tolerance {
        keep[worst.1] = true;
        simplify(profile, tolerance, keep, first, worst.1);
        simplify(profile, tolerance, keep, worst.1, last);
    }
}

/// The terrain-following waypoints of a spray run through `points` (plan metres and ground
/// heights): the run's ends, every corner (an edge pass turns at the boundary's vertices),
/// and every sample the terrain needs between them.
fn follow_terrain(
    points: &[RoutePoint],
    terrain: &dyn Terrain,
    settings: &MissionSettings,
) -> Result<Vec<RoutePoint>, Fault> {
    let mut samples = vec![points[0]];
    let mut anchors = vec![0];
    for (index, pair) in points.windows(2).enumerate() {
        let (a, b) = (pair[0], pair[1]);
        let length = (b.x - a.x).hypot(b.y - a.y);
        let steps = (length / settings.sample_spacing_m).ceil().max(1.0) as usize;
        for step in 1..steps {
            let t = step as f64 / steps as f64;
            let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
            samples.push(RoutePoint {
                x,
                y,
                ground_m: terrain.height_m(x, y)?,
            });
        }
        samples.push(b);
        let corner = points.get(index + 2).is_some_and(|c| {
            let (incoming, outgoing) = ((b.x - a.x, b.y - a.y), (c.x - b.x, c.y - b.y));
            let cross = incoming.0 * outgoing.1 - incoming.1 * outgoing.0;
            let dot = incoming.0 * outgoing.0 + incoming.1 * outgoing.1;
            cross.atan2(dot).abs() > 0.5_f64.to_radians()
        });
        if corner || index + 2 == points.len() {
            anchors.push(samples.len() - 1);
        }
    }
    let mut along = 0.0;
    let profile: Vec<(f64, f64)> = samples
        .iter()
        .enumerate()
        .map(|(index, point)| {
            if index > 0 {
                let previous = samples[index - 1];
                along += (point.x - previous.x).hypot(point.y - previous.y);
            }
            (along, point.ground_m)
        })
        .collect();
    let mut keep = vec![false; samples.len()];
    // The terrain between two samples may stray a little beyond what the samples show: keep
    // a tenth of the tolerance (at least 5 cm) for it, so the flight as sampled finer stays within.
    let tolerance = (settings.terrain_tolerance_m * 0.9).min(settings.terrain_tolerance_m - 0.05);
    for pair in anchors.windows(2) {
        keep[pair[0]] = true;
        keep[pair[1]] = true;
        simplify(&profile, tolerance.max(0.01), &mut keep, pair[0], pair[1]);
    }
    Ok(samples
        .into_iter()
        .zip(keep)
        .filter_map(|(point, kept)| kept.then_some(point))
        .collect())
}

/// Terrain samples along a transit, metres: at most this far apart (the preflight samples
/// legs at the same spacing).
pub const TRANSIT_SAMPLE_M: f64 = 1.0;

/// The highest ground under the straight leg a → b, sampled every [`TRANSIT_SAMPLE_M`].
pub fn highest_ground(terrain: &dyn Terrain, a: (f64, f64), b: (f64, f64)) -> Result<f64, Fault> {
    let length = (b.0 - a.0).hypot(b.1 - a.1);
    let steps = (length / TRANSIT_SAMPLE_M).ceil().max(1.0) as usize;
    let mut highest = f64::NEG_INFINITY;
    for step in 0..=steps {
        let t = step as f64 / steps as f64;
        highest = highest.max(terrain.height_m(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))?);
    }
    Ok(highest)
}

/// A transit between two places at a level altitude: the corners it turns at to keep out of
/// the obstacles (the geofence's exclusion zones) and the altitude above sea level that
/// clears the highest ground under every leg by `clearance_m`.
struct Transit {
    corners: Vec<RoutePoint>,
    altitude_m: f64,
}

/// How far transits keep from obstacles, metres.
pub const OBSTACLE_CLEARANCE_M: f64 = 2.0;

fn transit(
    from: &RoutePoint,
    to: &RoutePoint,
    scenario: &Scenario,
    obstacles: &[geo::Polygon<f64>],
    clearance_m: f64,
) -> Result<Transit, Fault> {
    let corners = crate::geometry::detour::detour(
        geo::Coord {
            x: from.x,
            y: from.y,
        },
        geo::Coord { x: to.x, y: to.y },
        obstacles,
        OBSTACLE_CLEARANCE_M,
    )
    .ok_or_else(|| {
        Fault::Structure(format!(
            "no transit from ({:.1}, {:.1}) to ({:.1}, {:.1}) keeps out of the obstacles",
            from.x, from.y, to.x, to.y
        ))
    })?;
    let corners: Vec<RoutePoint> = corners
        .into_iter()
        .map(|corner| {
            Ok(RoutePoint {
                x: corner.x,
                y: corner.y,
                ground_m: scenario.terrain.height_m(corner.x, corner.y)?,
            })
        })
        .collect::<Result<_, Fault>>()?;
    let mut path = vec![(from.x, from.y)];
    path.extend(corners.iter().map(|corner| (corner.x, corner.y)));
    path.push((to.x, to.y));
    let mut highest = f64::NEG_INFINITY;
    for pair in path.windows(2) {
        highest = highest.max(highest_ground(scenario.terrain.as_ref(), pair[0], pair[1])?);
    }
    Ok(Transit {
        corners,
        altitude_m: highest + clearance_m,
    })
}

/// The missions of a plan, one per sortie (one in all when the route is not split).
///
/// Every transit (out from the supply point, transfers that leave a field, back home) flies
/// level at the cruise height (spray height + h, h ≥ 5 m) above the highest ground under it,
/// and round the obstacles, which the geofence excludes at every altitude.
pub fn build_missions(
    scenario: &Scenario,
    route: &Route,
    sorties: Option<&PlannedSorties>,
    settings: &MissionSettings,
) -> Result<Vec<SortieMission>, Fault> {
    let vehicle = &scenario.vehicle;
    let frame = GeoFrame::new(scenario.farm.coordinate_system, settings.local_origin);
    let speeds = crate::sortie::route::Speeds {
        spray_mps: vehicle.spray_speed_mps,
        turn_mps: vehicle.turn_speed_mps,
        transit_mps: vehicle.transit_speed_mps,
    };
    let (work_route, supply, bounds) = match sorties {
        Some(split) => {
            let mut bounds: Vec<usize> = vec![0];
            bounds.extend(split.plan.breaks.iter().copied());
            bounds.push(split.work_route.len().saturating_sub(1));
            (split.work_route.clone(), split.supply, bounds)
        }
        None => {
            let launch = route.launch;
            let route = crate::sortie::route::WorkRoute::from_route(route, speeds);
            let supply = launch
                .map(|leg| RoutePoint {
                    x: leg.from.x,
                    y: leg.from.y,
                    ground_m: leg.from.ground_m,
                })
                .or_else(|| route.points().first().copied());
            let Some(supply) = supply else {
                return Ok(vec![]);
            };
            let last = route.len().saturating_sub(1);
            (route, supply, vec![0, last])
        }
    };
    if work_route.len() < 2 {
        return Ok(vec![]);
    }
    let spray_height = vehicle.spray_height_m;
    let cruise = spray_height + vehicle.safe_height_m.max(5.0);
    // An item at `point`, `above` metres over its ground.
    let item = |action: Action, point: &RoutePoint, above: f64| {
        let (lon, lat) = frame.lon_lat(point.x, point.y);
        Item {
            action,
            lon,
            lat,
            ground_m: point.ground_m,
            above_ground_m: above,
        }
    };
    // An item at `point` at `altitude_m` above sea level.
    let level = |action: Action, point: &RoutePoint, altitude_m: f64| {
        item(action, point, altitude_m - point.ground_m)
    };
    let home = item(Action::Waypoint, &supply, 0.0);
    // The geofence's exclusions, which every transit keeps out of.
    let obstacles: Vec<geo::Polygon<f64>> = scenario
        .farm
        .obstacles
        .iter()
        .map(|obstacle| obstacle.polygon.clone())
        .collect();
    let points = work_route.points();
    let segments = work_route.segments();
    let mut missions = Vec::new();
    for (sortie, pair) in bounds.windows(2).enumerate() {
        let (first, last) = (pair[0], pair[1]);
        let out = transit(&supply, &points[first], scenario, &obstacles, cruise)?;
        let mut items = vec![
            level(Action::Takeoff, &supply, out.altitude_m),
            level(
                Action::Speed {
                    mps: vehicle.transit_speed_mps,
                },
                &supply,
                out.altitude_m,
            ),
        ];
        for corner in &out.corners {
            items.push(level(Action::Waypoint, corner, out.altitude_m));
        }
        items.extend([
            level(Action::Waypoint, &points[first], out.altitude_m),
            item(Action::Waypoint, &points[first], spray_height),
            item(
                Action::Speed {
                    mps: vehicle.spray_speed_mps,
                },
                &points[first],
                spray_height,
            ),
        ]);
        let mut index = first;
        while index < last {
            match segments[index] {
                Segment::Spray => {
                    let mut end = index;
                    while end < last && segments[end] == Segment::Spray {
                        end += 1;
                    }
                    items.push(item(
                        Action::Spray { on: true },
                        &points[index],
                        spray_height,
                    ));
                    let run =
                        follow_terrain(&points[index..=end], scenario.terrain.as_ref(), settings)?;
                    for point in &run[1..] {
                        items.push(item(Action::Waypoint, point, spray_height));
                    }
                    // Off at the swath's end: nothing sprays on turns, transfers or returns.
                    items.push(item(
                        Action::Spray { on: false },
                        &points[end],
                        spray_height,
                    ));
                    index = end;
                }
                Segment::Turn => {
                    // Turns stay low inside the field, so they follow the terrain as swaths do.
                    let run = follow_terrain(
                        &points[index..=index + 1],
                        scenario.terrain.as_ref(),
                        settings,
                    )?;
                    for point in &run[1..] {
                        items.push(item(Action::Waypoint, point, spray_height));
                    }
                    index += 1;
                }
                Segment::Transfer => {
                    let (from, to) = (&points[index], &points[index + 1]);
                    let hop = transit(from, to, scenario, &obstacles, cruise)?;
                    items.push(item(
                        Action::Speed {
                            mps: vehicle.transit_speed_mps,
                        },
                        from,
                        spray_height,
                    ));
                    items.push(level(Action::Waypoint, from, hop.altitude_m));
                    for corner in &hop.corners {
                        items.push(level(Action::Waypoint, corner, hop.altitude_m));
                    }
                    items.push(level(Action::Waypoint, to, hop.altitude_m));
                    items.push(item(Action::Waypoint, to, spray_height));
                    items.push(item(
                        Action::Speed {
                            mps: vehicle.spray_speed_mps,
                        },
                        to,
                        spray_height,
                    ));
                    index += 1;
                }
            }
        }
        let back = transit(&points[last], &supply, scenario, &obstacles, cruise)?;
        items.push(item(
            Action::Speed {
                mps: vehicle.transit_speed_mps,
            },
            &points[last],
            spray_height,
        ));
        items.push(level(Action::Waypoint, &points[last], back.altitude_m));
        for corner in &back.corners {
            items.push(level(Action::Waypoint, corner, back.altitude_m));
        }
        items.push(level(Action::Waypoint, &supply, back.altitude_m));
        items.push(item(Action::Land, &supply, 0.0));
        missions.push(SortieMission {
            sortie,
            home,
            items,
        });
    }
    Ok(missions)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn douglas_peucker_keeps_the_bend_and_drops_the_flat() {
        let profile: Vec<(f64, f64)> = (0..=20)
            .map(|i| {
                let x = i as f64;
                (x, if i <= 10 { 0.0 } else { (x - 10.0) * 0.5 })
            })
            .collect();
        let mut keep = vec![false; profile.len()];
        keep[0] = true;
        keep[20] = true;
        simplify(&profile, 0.1, &mut keep, 0, 20);
        let kept: Vec<usize> = (0..=20).filter(|&i| keep[i]).collect();
        assert_eq!(kept, vec![0, 10, 20]);
    }

    struct Waves;

    impl Terrain for Waves {
        fn height_m(&self, x: f64, y: f64) -> Result<f64, crate::TerrainError> {
            Ok(4.0 * (x / 23.0).sin() + 2.0 * (y / 17.0).cos())
        }
        fn extent(&self) -> Option<crate::terrain::Extent> {
            None
        }
        fn describe(&self) -> String {
            "waves".into()
        }
    }

    #[test]
    fn terrain_following_keeps_corners_and_stays_within_the_tolerance() {
        let at = |x: f64, y: f64| RoutePoint {
            x,
            y,
            ground_m: Waves.height_m(x, y).unwrap(),
        };
        // An L-shaped run: along x, then along y.
        let points = [at(0.0, 0.0), at(100.0, 0.0), at(100.0, 80.0)];
        let settings = MissionSettings {
            terrain_tolerance_m: 0.5,
            sample_spacing_m: 1.0,
            ..MissionSettings::default()
        };
        let kept = follow_terrain(&points, &Waves, &settings).unwrap();
        assert!(
            kept.iter().any(|p| p.x == 100.0 && p.y == 0.0),
            "the corner is a waypoint"
        );
        assert!(
            kept.len() > 3 && kept.len() < 60,
            "{} waypoints",
            kept.len()
        );
        for pair in kept.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let length = (b.x - a.x).hypot(b.y - a.y);
            for k in 0..=100 {
                let t = k as f64 / 100.0;
                let (x, y) = (a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
                let flown = a.ground_m + t * (b.ground_m - a.ground_m);
                // Sampled every metre: between samples the gap can grow by the slope × 1 m.
                assert!(
                    (flown - Waves.height_m(x, y).unwrap()).abs() <= 0.5 + 0.2,
                    "{length} m leg at t = {t}"
                );
            }
        }
    }

    #[test]
    fn a_local_frame_is_placed_at_its_origin() {
        let frame = GeoFrame::new(CoordinateSystem::Local, (126.63, 45.75));
        let (lon, lat) = frame.lon_lat(0.0, 0.0);
        assert!((lon - 126.63).abs() < 1e-9 && (lat - 45.75).abs() < 1e-9);
        let (_, north) = frame.lon_lat(0.0, 1000.0);
        assert!((north - 45.75 - 1000.0 / 111_150.0).abs() < 2e-4);
    }
}
